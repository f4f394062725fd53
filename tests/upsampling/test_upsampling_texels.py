"""Texel coefficient files (.sctx): round trip, their table, damaged files, readers and the CLI."""

import shutil
import struct
import subprocess
import zlib
from pathlib import Path

import numpy as np
import pytest
from PIL import Image

import spectrocolor as sc
from spectrocolor.cli import main
from spectrocolor.upsampling import load_table, save_table, texel_coefficients, upsample
from spectrocolor.upsampling.texels import (
    load_texel_coefficients,
    save_texel_coefficients,
    table_fingerprint,
    texel_bytes,
)
from upsampling_tables import rec2020_table, srgb_table

READERS = Path(__file__).resolve().parents[2] / "docs" / "upsampling"
# float32 weights: each within 2⁻²⁴ relative of the float64 weight, the reflectances at most 1,
# so a texel's spectrum is within 4 · 2⁻²⁴ ≈ 2.4e-7 of the float64 blend (plus float64 rounding)
FLOAT32_BLEND = 4 * 2.0**-24 + 1e-15
# the reference readers repeat TexelCoefficients.reflectance operation for operation
READER_TOLERANCE = 8 * np.finfo(float).eps


def texture(seed=0, shape=(6, 9)):
    t = np.random.default_rng(seed).random((*shape, 3)) * 1.2 - 0.1  # some texels outside
    t[0, 0] = (0.25, 0.5, 0.75)
    return t


def test_round_trip_keeps_the_coefficients_bit_for_bit(tmp_path):
    table, t = srgb_table(), texture()
    path = save_texel_coefficients(table, t, tmp_path / "t.sctx")
    back = load_texel_coefficients(path, table)
    nodes, weights, exact = texel_coefficients(table, t)
    # exact: a copy of the same numbers (written and read back, no arithmetic)
    np.testing.assert_array_equal(back.nodes, nodes)
    # exact: a copy of the same numbers (written and read back, no arithmetic)
    np.testing.assert_array_equal(back.weights, weights)
    # exact: a copy of the same numbers (written and read back, no arithmetic)
    np.testing.assert_array_equal(back.exact, exact)
    assert (back.resolution, back.samples, back.fingerprint) == (9, 81, table_fingerprint(table))
    assert 0 < exact.sum() < exact.size
    reference = upsample(table, t).reflectance
    assert np.abs(back.reflectance(table) - reference).max() <= FLOAT32_BLEND


def test_the_file_belongs_to_its_table(tmp_path):
    path = save_texel_coefficients(srgb_table(), texture(), tmp_path / "t.sctx")
    with pytest.raises(sc.ColorimetryError, match="another table"):
        load_texel_coefficients(path, rec2020_table())
    other = sc.upsampling_table("Display P3", "D65", resolution=9, measure_excess=False)
    with pytest.raises(sc.ColorimetryError, match="fingerprint"):
        load_texel_coefficients(path).reflectance(other)
    with pytest.raises(sc.ColorimetryError, match="'nan' has no coefficients"):
        texel_bytes(srgb_table(), texture(), "nan")
    with pytest.raises(sc.ColorimetryError, match=r"\(H, W, 3\)"):
        texel_bytes(srgb_table(), np.zeros((4, 3)))


def with_crc(body: bytes) -> bytes:
    return body + struct.pack("<I", zlib.crc32(body))


GOOD = None


def good_bytes() -> bytes:
    global GOOD
    if GOOD is None:
        GOOD = texel_bytes(srgb_table(), texture(shape=(2, 3)))
    return GOOD


def damaged(kind: str) -> bytes:
    data = bytearray(good_bytes()[:-4])
    texels = 6
    if kind == "magic":
        data[0:8] = b"SCUPTBL\0"
    elif kind == "version":
        data[8:12] = struct.pack("<I", 2)
    elif kind == "size":
        data[12:16] = struct.pack("<I", 4)
    elif kind == "node":
        data[32:36] = struct.pack("<I", 9**3)
    elif kind == "weight":
        data[32 + 16 * texels:36 + 16 * texels] = struct.pack("<f", -0.5)
    elif kind == "flag":
        data[32 + 32 * texels] = 7
    elif kind == "crc":
        return bytes(data) + b"\0\0\0\0"
    elif kind == "short":
        return bytes(data[:20])
    return with_crc(bytes(data))


@pytest.mark.parametrize("kind, message", [
    ("magic", "magic"), ("version", "version 2"), ("size", "promises"), ("node", "node index"),
    ("weight", "weights"), ("flag", "flags"), ("crc", "CRC-32"), ("short", "shorter"),
])
def test_damaged_files_are_refused_with_one_error(tmp_path, kind, message):
    path = tmp_path / "bad.sctx"
    path.write_bytes(damaged(kind))
    with pytest.raises(sc.SpectrumError, match=message) as error:
        load_texel_coefficients(path)
    assert str(path) in str(error.value)


def test_python_reference_reader_agrees(tmp_path):
    import importlib.util

    spec = importlib.util.spec_from_file_location("scup_reader", READERS / "reader.py")
    reader = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(reader)
    table = rec2020_table()
    t = texture(1)
    save_table(table, tmp_path / "t.scup")
    path = save_texel_coefficients(table, t, tmp_path / "t.sctx")
    expected = load_texel_coefficients(path, table).reflectance(table)
    _, rho = reader.read_table(tmp_path / "t.scup")
    nodes, weights = reader.read_texels(path)
    for y, x in ((0, 0), (5, 8), (3, 4)):
        np.testing.assert_allclose(reader.texel_spectrum(rho, nodes[y, x], weights[y, x]), expected[y, x],
                                   rtol=0, atol=READER_TOLERANCE)


def test_c_reference_reader_agrees(tmp_path):
    cc = shutil.which("cc")
    if cc is None:
        pytest.skip("no C compiler (cc) on PATH: the C reference reader is not compiled here")
    exe = tmp_path / "texels"
    subprocess.run([cc, "-std=c99", "-O2", "-ffp-contract=off", "-Wall", "-Werror", "-o", str(exe),
                    str(READERS / "texels.c")], check=True, capture_output=True)
    table = srgb_table()
    save_table(table, tmp_path / "t.scup")
    path = save_texel_coefficients(table, texture(2), tmp_path / "t.sctx")
    expected = load_texel_coefficients(path, table).reflectance(table)
    for y, x in ((0, 0), (5, 8), (2, 7)):
        run = subprocess.run([str(exe), str(tmp_path / "t.scup"), str(path), str(x), str(y)], check=True,
                             capture_output=True, text=True)
        got = np.array([line.split() for line in run.stdout.splitlines()], dtype=float)
        # exact: whole-nanometre wavelengths: small integers, exact in any arithmetic
        np.testing.assert_array_equal(got[:, 0], table.wavelengths_nm)
        np.testing.assert_allclose(got[:, 1], expected[y, x], rtol=0, atol=READER_TOLERANCE)
    bad = subprocess.run([str(exe), str(tmp_path / "t.scup"), str(path), "9", "0"], capture_output=True,
                         text=True)
    assert bad.returncode == 1 and "outside the texture" in bad.stderr


def test_cli_writes_coefficients_and_their_table(tmp_path, capsys):
    codes = np.random.default_rng(4).integers(0, 256, (5, 7, 3), dtype=np.uint8)
    Image.fromarray(codes).save(tmp_path / "tex.png")
    assert main(["upsample", str(tmp_path / "tex.png"), "--coefficients", str(tmp_path / "tex.sctx"),
                 "--save-table", str(tmp_path / "t.scup"), "--resolution", "5"]) == 0
    assert "0 texels not reproduced exactly" in capsys.readouterr().out
    table = load_table(tmp_path / "t.scup")
    back = load_texel_coefficients(tmp_path / "tex.sctx", table)
    nodes, weights, _ = texel_coefficients(table, sc.upsampling.rgb_linear_from_image(codes))
    # exact: a copy of the same numbers (written and read back, no arithmetic)
    np.testing.assert_array_equal(back.nodes, nodes)
    # exact: a copy of the same numbers (written and read back, no arithmetic)
    np.testing.assert_array_equal(back.weights, weights)
    # with the saved table, the same file again (and only with --force over an existing one)
    assert main(["upsample", str(tmp_path / "tex.png"), "--coefficients", str(tmp_path / "tex.sctx"),
                 "--table", str(tmp_path / "t.scup")]) == 2
    assert "--force" in capsys.readouterr().err
    assert main(["upsample", str(tmp_path / "tex.png"), "--coefficients", str(tmp_path / "tex.sctx"),
                 "--table", str(tmp_path / "t.scup"), "--force"]) == 0
    assert load_texel_coefficients(tmp_path / "tex.sctx", table).fingerprint == back.fingerprint


@pytest.mark.parametrize("argv, message", [
    (["--coefficients", "{tmp}/tex.png", "--force"], "must end in .sctx"),
    (["--coefficients", "{tmp}/o.sctx", "--save-table", "{tmp}/tex.png"], "must end in .scup"),
    (["--coefficients", "{tmp}/o.sctx", "--resolution", "1"], "--resolution"),
    (["--coefficients", "{tmp}/o.sctx", "--from", "Q9"], "--from"),
    (["--coefficients", "{tmp}/o.sctx", "--save-table", "{tmp}/new.scup", "--table", "{tmp}/t.scup"],
     "--table"),
])
def test_cli_bad_options_get_one_line(tmp_path, capsys, argv, message):
    Image.fromarray(np.zeros((2, 2, 3), np.uint8)).save(tmp_path / "tex.png")
    (tmp_path / "t.scup").write_bytes(b"x")
    argv = [a.replace("{tmp}", str(tmp_path)) for a in argv]
    assert main(["upsample", str(tmp_path / "tex.png"), *argv]) == 2
    err = capsys.readouterr().err
    assert message in err and "Traceback" not in err and len(err.strip().splitlines()) == 1
    assert not (tmp_path / "o.sctx").exists()


# --- streamed writing (issue 25) ------------------------------------------------------------------


def test_texel_files_written_in_blocks_are_the_same_bytes(tmp_path):
    from spectrocolor.upsampling.texels import write_texel_blocks

    table = srgb_table()
    texture = np.random.default_rng(5).random((7, 5, 3)) * 1.2 - 0.1  # some out of range
    path, inexact = write_texel_blocks(tmp_path / "t.sctx", table, [texture[:3], texture[3:6], texture[6:]], 5, 7)
    assert path.read_bytes() == texel_bytes(table, texture)
    assert inexact == int(np.count_nonzero(~load_texel_coefficients(path, table).exact))
    with pytest.raises(sc.ColorimetryError, match="blocks: 3 rows given for a texture of height 7"):
        write_texel_blocks(tmp_path / "u.sctx", table, [texture[:3]], 5, 7)
    assert not (tmp_path / "u.sctx").exists()
