"""The .scup file: round trip, damaged files refused, and the Python and C reference readers."""

import importlib.util
import shutil
import struct
import subprocess
from pathlib import Path

import numpy as np
import pytest

import spectrocolor as sc
from spectrocolor.upsampling import load_table, save_table, upsample
from spectrocolor.upsampling.fileformat import HEADER, table_bytes
from upsampling_tables import rec2020_table, srgb_table

READERS = Path(__file__).resolve().parents[2] / "docs" / "upsampling"
# The readers repeat the package's arithmetic in the same order, so they agree to the last bit
# on IEEE hosts; allow 8 ulps of 1 (each of the ~8 operations of the blend rounds once), so an
# exotic compiler's contraction or ordering still passes while a wrong node or weight cannot.
READER_TOLERANCE = 8 * np.finfo(float).eps
QUERIES = [(0.0, 0.0, 0.0), (1.0, 1.0, 1.0), (0.2, 0.7, 0.4), (0.9, 0.1, 0.55), (0.5, 0.5, 0.25)]


@pytest.mark.parametrize("table_of", [srgb_table, rec2020_table])
def test_round_trip_is_bit_exact(tmp_path, table_of):
    table = table_of()
    back = load_table(save_table(table, tmp_path / "t.scup"))
    for name in ("wavelengths_nm", "reflectance", "node_XYZ100", "node_status", "roughness",
                 "multipliers", "cell_excess_bound", "cell_excess_measured", "matrix", "weights"):
        # exact: a copy of the same numbers (written and read back, no arithmetic)
        np.testing.assert_array_equal(getattr(back, name), getattr(table, name), err_msg=name)
    assert (back.space, back.illuminant, back.observer) == (table.space, table.illuminant,
                                                            table.observer)
    t = np.random.default_rng(1).random((100, 3))
    # exact: per-pixel blend of 4 nodes in a fixed order (no BLAS, no sum across pixels), whatever the batch or block
    # (on the same nodes, read back)
    np.testing.assert_array_equal(upsample(back, t).reflectance, upsample(table, t).reflectance)


def test_header_layout_is_as_documented(tmp_path):
    table = srgb_table()
    data = table_bytes(table)
    magic, version, n, K, J = struct.unpack_from("<8sIIII", data)
    assert (magic, version, n, K) == (b"SCUPTBL\0", 1, 9, 81) and J % 8 == 0
    start, step = struct.unpack_from("<2d", data, 24)
    assert (start, step) == (380.0, 5.0)  # exact: a copy of the same numbers (written and read back, no arithmetic)
    # exact: a copy of the same numbers (written and read back, no arithmetic)
    np.testing.assert_array_equal(np.frombuffer(data, "<f8", 9, 40).reshape(3, 3), table.matrix)
    first = np.frombuffer(data, "<f8", 81, HEADER.size + J)
    # exact: a copy of the same numbers (written and read back, no arithmetic)
    np.testing.assert_array_equal(first, table.reflectance[0, 0, 0])


def _damaged(tmp_path, change):
    data = bytearray(table_bytes(srgb_table()))
    change(data)
    path = tmp_path / "bad.scup"
    path.write_bytes(bytes(data))
    return path


@pytest.mark.parametrize("change, message", [
    (lambda d: d.__setitem__(slice(0, 8), b"NOTATABL"), "magic"),
    (lambda d: d.__setitem__(slice(8, 12), struct.pack("<I", 2)), "version"),
    (lambda d: d.__setitem__(slice(12, 16), struct.pack("<I", 1000)), "nodes per axis"),
    (lambda d: d.__delitem__(slice(-100, None)), "header promises"),
    (lambda d: d.__setitem__(500, d[500] ^ 0xFF), "CRC-32"),
    (lambda d: d.__delitem__(slice(50, None)), "shorter than"),
])
def test_damaged_files_are_refused_with_one_clear_error(tmp_path, change, message):
    with pytest.raises(sc.SpectrumError, match=message):
        load_table(_damaged(tmp_path, change))


def test_missing_file_and_folder_are_refused(tmp_path):
    with pytest.raises(sc.SpectrumError, match="cannot read"):
        load_table(tmp_path / "nothing.scup")
    with pytest.raises(sc.SpectrumError):
        load_table(tmp_path)


def test_save_replaces_atomically_and_leaves_no_temporary(tmp_path):
    path = tmp_path / "t.scup"
    path.write_bytes(b"old")
    save_table(srgb_table(), path)
    assert load_table(path).resolution == 9
    assert sorted(p.name for p in tmp_path.iterdir()) == ["t.scup"]
    with pytest.raises(sc.SpectrumError, match="UpsamplingTable"):
        save_table("not a table", tmp_path / "x.scup")


def test_python_reference_reader_agrees(tmp_path):
    spec = importlib.util.spec_from_file_location("scup_reader", READERS / "reader.py")
    reader = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(reader)
    table = rec2020_table()
    path = save_table(table, tmp_path / "t.scup")
    wavelengths, nodes = reader.read_table(path)
    # exact: a copy of the same numbers (written and read back, no arithmetic)
    np.testing.assert_array_equal(wavelengths, table.wavelengths_nm)
    for q in QUERIES:
        np.testing.assert_allclose(reader.spectrum(nodes, q), upsample(table, q).reflectance,
                                   rtol=0, atol=READER_TOLERANCE)


def test_c_reference_reader_agrees(tmp_path):
    cc = shutil.which("cc")
    if cc is None:
        pytest.skip("no C compiler (cc) on PATH: the C reference reader is not compiled here")
    exe = tmp_path / "reader"
    subprocess.run([cc, "-std=c99", "-O2", "-ffp-contract=off", "-Wall", "-Werror", "-o",
                    str(exe), str(READERS / "reader.c")], check=True, capture_output=True)
    table = rec2020_table()
    path = save_table(table, tmp_path / "t.scup")
    for q in QUERIES:
        run = subprocess.run([str(exe), str(path), *map(repr, q)], check=True,
                             capture_output=True, text=True)
        got = np.array([line.split() for line in run.stdout.splitlines()], dtype=float)
        # exact: whole-nanometre wavelengths: small integers, exact in any arithmetic
        np.testing.assert_array_equal(got[:, 0], table.wavelengths_nm)
        np.testing.assert_allclose(got[:, 1], upsample(table, q).reflectance, rtol=0,
                                   atol=READER_TOLERANCE)
    bad = subprocess.run([str(exe), str(path), "2", "0", "0"], capture_output=True, text=True)
    assert bad.returncode == 1 and "[0, 1]" in bad.stderr
