"""Hostile files and options on the command line: exit 2 with one ``error:`` line, never a traceback.

Every case runs the real ``spectrocolor`` entry point (in this process, for speed). A raw
exception escaping ``main`` fails the test with that exception; a clear refusal is exit status 2
with exactly one line saying ``error:``. Generated files (hypothesis) cover the spectral readers;
hand-made ones cover the cube readers, numbers without bounds and output paths.

The long run: ``SPECTROCOLOR_LONG_FUZZ=1 pytest -m slow tests/fuzz/test_fuzz_cli.py``.
"""

from __future__ import annotations

import json
import os
import zipfile

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import spectrocolor.cli as cli

LONG = os.environ.get("SPECTROCOLOR_LONG_FUZZ") == "1"
long_run = pytest.mark.skipif(not LONG, reason="long fuzz run: set SPECTROCOLOR_LONG_FUZZ=1")

GOOD_CSV = "wavelength_nm,a,b\n" + "".join(f"{w},0.5,0.25\n" for w in range(380, 781, 10))


def run(argv, capsys) -> tuple[int, str, str]:
    """Run the CLI; return (status, stdout, stderr) after checking the error contract."""
    try:
        code = cli.main([str(a) for a in argv])
    except SystemExit as exc:  # argparse's own refusals: usage line(s) + one error line
        code = exc.code
    out, err = capsys.readouterr()
    assert "Traceback" not in err and "Traceback" not in out
    if code == 2:
        errors = [line for line in err.splitlines() if "error:" in line]
        assert len(errors) == 1, err
    else:
        assert code in (0, 1), (code, err)
    return code, out, err


def refused(argv, capsys, *words) -> str:
    code, _, err = run(argv, capsys)
    assert code == 2, (argv, err)
    for word in words:
        assert word in err, (word, err)
    return err


@pytest.fixture
def good(tmp_path):
    path = tmp_path / "good.csv"
    path.write_text(GOOD_CSV)
    return path


# --- spectral files ------------------------------------------------------------------------------

SPECTRAL_COMMANDS = [
    ["xyz"], ["describe"], ["render", "--out", "{out}.png"], ["diagram", "--out", "{out}.svg"],
    ["report", "--illuminant", "D65", "--out", "{out}.csv"],
]


def _argv(command, path, tmp_path):
    return [command[0], path, *(a.format(out=tmp_path / "o") for a in command[1:])]


HOSTILE_FILES = {
    "empty.csv": b"",
    "header.csv": b"wavelength_nm,a\n",
    "bom.csv": b"\xef\xbb\xbfwavelength_nm,a\n400,1\n500,1\n",
    "binary.csv": bytes(range(256)) * 20,
    "nan.csv": b"wavelength_nm,a\n400,nan\n500,inf\n600,-inf\n",
    "huge.csv": b"wavelength_nm,a\n400,1e308\n500,1e308\n600,-1e308\n",
    "ragged.csv": b"wavelength_nm,a,b\n400,1\n500,1,2,3\n",
    "decreasing.csv": b"wavelength_nm,a\n500,1\n400,1\n",
    "duplicate.csv": b"wavelength_nm,a\n400,1\n400,1\n",
    "microns.csv": b"wavelength_nm,a\n0.4,1\n0.5,1\n",
    "long_cell.csv": b"wavelength_nm," + b"a" * 200_000 + b"\n400,1\n500,1\n",
    "many_columns.csv": b"wavelength_nm," + b",".join(b"c%d" % i for i in range(20_000)) + b"\n",
    "nested.json": b"[" * 100_000 + b"]" * 100_000,
    "nested_obj.json": b'{"a":' * 50_000 + b"1" + b"}" * 50_000,
    "wrong.json": b'{"wavelengths_nm": "x", "values": {"a": 1}}',
    "complex.json": json.dumps({"wavelengths_nm": [400, 500],
                                "values": [[1, 2], [3]]}).encode(),
    "latin1.csv": "wavelength_nm,é\n400,1\n500,1\n".encode("latin-1"),
    "semicolon.csv": b"wavelength_nm;a\n400;0,5\n500;0,5\n",
    "only_names.csv": b"a,b,c\nx,y,z\n",
}


@pytest.mark.parametrize("name", sorted(HOSTILE_FILES))
@pytest.mark.parametrize("command", SPECTRAL_COMMANDS, ids=lambda c: c[0])
@pytest.mark.slow
def test_hostile_spectral_files(tmp_path, capsys, name, command):
    path = tmp_path / name
    path.write_bytes(HOSTILE_FILES[name])
    run(_argv(command, path, tmp_path), capsys)


@pytest.mark.parametrize("command", SPECTRAL_COMMANDS, ids=lambda c: c[0])
def test_devices_and_pipes_are_never_read(tmp_path, capsys, command):
    refused(_argv(command, "/dev/zero", tmp_path), capsys, "not a regular file")
    fifo = tmp_path / "fifo"
    os.mkfifo(fifo)
    refused(_argv(command, fifo, tmp_path), capsys, "not a regular file")


CSV_TEXT = st.text(alphabet=st.sampled_from(list("0123456789.,;-+eE\n\t \"#naifINFwavelength_m")),
                   max_size=400)


@settings(max_examples=25, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(text=CSV_TEXT, command=st.sampled_from(SPECTRAL_COMMANDS[:2] + SPECTRAL_COMMANDS[4:]))
def test_generated_spectral_files(tmp_path_factory, capsys, text, command):
    folder = tmp_path_factory.mktemp("gen")
    path = folder / "gen.csv"
    path.write_text("wavelength_nm,a\n" + text)
    run(_argv(command, path, folder), capsys)


@long_run
@pytest.mark.slow
@settings(max_examples=1500, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(data=st.binary(max_size=3000) | CSV_TEXT.map(str.encode),
       suffix=st.sampled_from([".csv", ".json", ".txt", ".cgats", ".ti3", ".sp", ".xml"]),
       command=st.sampled_from(SPECTRAL_COMMANDS))
def test_generated_spectral_files_long(tmp_path_factory, capsys, data, suffix, command):
    folder = tmp_path_factory.mktemp("long")
    path = folder / f"gen{suffix}"
    path.write_bytes(data)
    run(_argv(command, path, folder), capsys)


# --- cube files ----------------------------------------------------------------------------------


def _npy_header_only(path, shape):
    """A .npy whose header claims ``shape`` but holds no data."""
    with open(path, "wb") as fh:
        np.lib.format.write_array_header_1_0(fh, {"descr": "<f4", "fortran_order": False,
                                                   "shape": shape})


def _cubes(tmp_path):
    cubes = {}
    cubes["object.npy"] = tmp_path / "object.npy"
    np.save(cubes["object.npy"], np.array([[{"a": 1}]], dtype=object), allow_pickle=True)
    cubes["truncated.npy"] = tmp_path / "truncated.npy"
    np.save(cubes["truncated.npy"], np.ones((20, 20, 31), np.float32))
    with open(cubes["truncated.npy"], "r+b") as fh:
        fh.truncate(3000)
    cubes["claims_huge.npy"] = tmp_path / "claims_huge.npy"
    _npy_header_only(cubes["claims_huge.npy"], (100_000, 100_000, 31))
    cubes["empty.npy"] = tmp_path / "empty.npy"
    np.save(cubes["empty.npy"], np.ones((0, 5, 31), np.float32))
    cubes["2d.npy"] = tmp_path / "2d.npy"
    np.save(cubes["2d.npy"], np.ones((5, 31), np.float32))
    cubes["bomb.npz"] = tmp_path / "bomb.npz"
    with zipfile.ZipFile(cubes["bomb.npz"], "w", zipfile.ZIP_DEFLATED) as zf:
        with zf.open("cube.npy", "w", force_zip64=True) as fh:
            np.lib.format.write_array_header_1_0(fh, {"descr": "<f8", "fortran_order": False,
                                                       "shape": (20_000, 20_000, 31)})
            fh.write(b"\0" * 1_000_000)
    cubes["junk.tif"] = tmp_path / "junk.tif"
    cubes["junk.tif"].write_bytes(b"II*\0" + np.random.default_rng(5).bytes(500))
    cubes["hdr_bad_scale.hdr"] = tmp_path / "bad.hdr"
    cubes["hdr_bad_scale.hdr"].write_text(
        "ENVI\nsamples = 2\nlines = 2\nbands = 3\ndata type = 4\ninterleave = bsq\n"
        "byte order = 0\nheader offset = -5\nreflectance scale factor = abc\n"
        "wavelength = {400, 500, 600}\n")
    (tmp_path / "bad.img").write_bytes(b"\0" * 48)
    cubes["hdr_huge.hdr"] = tmp_path / "huge.hdr"
    cubes["hdr_huge.hdr"].write_text(
        "ENVI\nsamples = 100000\nlines = 100000\nbands = 31\ndata type = 4\ninterleave = bsq\n"
        "byte order = 0\nwavelength = {" + ", ".join(str(w) for w in range(400, 710, 10)) + "}\n")
    (tmp_path / "huge.img").write_bytes(b"\0" * 1000)
    cubes["not_a_cube.xyz"] = tmp_path / "cube.xyz"
    cubes["not_a_cube.xyz"].write_text("hello")
    return cubes


CUBE_NAMES = ["object.npy", "truncated.npy", "claims_huge.npy", "empty.npy", "2d.npy", "bomb.npz",
              "junk.tif", "hdr_bad_scale.hdr", "hdr_huge.hdr", "not_a_cube.xyz"]


@settings(max_examples=200 if LONG else 20, deadline=None,
          suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(head=st.sampled_from([b"II*\0", b"MM\0*", b"II+\0", b"\x93NUMPY", b"PK\x03\x04",
                             b"\x89HDF\r\n\x1a\n", b"CDF\x01"]),
       body=st.binary(max_size=1500), suffix=st.sampled_from([".tif", ".npy", ".npz", ".nc"]))
def test_generated_cube_files(tmp_path_factory, capsys, head, body, suffix):
    folder = tmp_path_factory.mktemp("cube")
    cube = folder / f"gen{suffix}"
    cube.write_bytes(head + body)
    code, _, _ = run(["image", cube, "--illuminant", "D65", "--wavelengths", "400:700:10",
                      "--out", folder / "out.png"], capsys)
    assert code == 2


@pytest.mark.parametrize("name", CUBE_NAMES)
def test_hostile_cubes(tmp_path, capsys, name):
    cube = _cubes(tmp_path)[name]
    code, _, _ = run(["image", cube, "--illuminant", "D65", "--wavelengths", "400:700:10",
                      "--out", tmp_path / "out.png"], capsys)
    assert code == 2


# --- numbers without bounds, and options ----------------------------------------------------------


@pytest.mark.parametrize("argv,words", [
    (["thinfilm", "strip", "--tick-every", "1e-9"], ["--tick-every"]),
    (["thinfilm", "strip", "--tick-every", "nan"], ["--tick-every"]),
    (["thinfilm", "strip", "--max-thickness", "inf"], ["--max-thickness"]),
    (["thinfilm", "strip", "--max-thickness", "nan"], ["--max-thickness"]),
    (["thinfilm", "strip", "--columns", "1000000000"], ["at most"]),
    (["thinfilm", "map", "--width", "100000000"], ["--width"]),
    (["thinfilm", "strip", "--film", "\x00\x01\xff"], []),
    (["thinfilm", "strip", "--under", "water:nan"], ["--under"]),
    (["thinfilm", "strip", "--under", ":::"], ["--under"]),
    (["image", "{good}", "--illuminant", "D65", "--wavelengths", "400:700:1e-9"],
     ["--wavelengths"]),
    (["image", "{good}", "--illuminant", "D65", "--wavelengths", "400:nan:10"], ["--wavelengths"]),
    (["image", "{good}", "--illuminant", "D65", "--wavelengths", "700:400:10"], ["--wavelengths"]),
    (["image", "{good}", "--illuminant", "D65", "--out", "{tmp}/x.bmp"], ["--out"]),
    (["image", "{cube}", "--illuminant", "D65", "--wavelengths", "400:700:10",
      "--scheduler", "not-an-address"], ["--scheduler"]),
    (["image", "{cube}", "--illuminant", "D65", "--wavelengths", "400:700:10", "--masked", "see-through"],
     ["--masked"]),
    (["image", "{cube}", "--illuminant", "D65", "--wavelengths", "400:700:10", "--masked", "nan,0,0"],
     ["--masked"]),
    (["image", "{cube}", "--illuminant", "D65", "--wavelengths", "400:700:10", "--masked", "#12345g"],
     ["--masked"]),
    (["image", "{cube}", "--illuminant", "D65", "--wavelengths", "400:700:10", "--masked", "1e309,0,0"],
     ["--masked"]),
    (["image", "{cube}", "--illuminant", "D65", "--wavelengths", "400:700:10", "--masked", "",
      "--out", "{tmp}/x.tif", "--quantity", "xyz"], ["--masked"]),
    (["recover", "--xyz", "nan", "1", "1"], []),
    (["recover", "--xyz", "1e308", "1e308", "1e308"], []),
    (["recover", "--hex", "zzzzzz"], ["--hex"]),
    (["recover", "--xyz", "20", "20", "20", "--range", "380", "780", "1e-9"], []),
    (["recover", "--xyz", "20", "20", "20", "--range", "780", "380", "5"], []),
    (["render", "{good}", "--size", "100000"], ["--size"]),
    (["app", "--host", "0.0.0.0"], ["--allow-remote"]),
    (["app", "--host", "192.0.2.1", "--port", "1"], ["--allow-remote"]),
    (["app", "--port", "70000"], ["--port"]),
    (["app", "--classroom", "--host", "127.0.0.2", "--port", "70000"], ["--port"]),
    (["app", "--classroom", "--host", "192.0.2.1", "--port", "1"], ["192.0.2.1"]),
])
def test_options_out_of_bounds(tmp_path, capsys, good, argv, words):
    cube = tmp_path / "cube.npy"
    np.save(cube, np.full((4, 4, 31), 0.5))
    argv = [a.format(good=good, tmp=tmp_path, cube=cube) for a in argv]
    if "--out" not in argv and argv[0] != "app":
        argv += ["--out", tmp_path / ("out.csv" if argv[0] == "recover" else "out.png")]
    refused(argv, capsys, *words)


@pytest.mark.parametrize("out", ["{tmp}/" + "n" * 300 + ".png", "{good}/x.png", "{tmp}",
                                 "{tmp}/missing/x.png"])
def test_impossible_output_paths(tmp_path, capsys, good, out):
    refused(["render", good, "--out", out.format(tmp=tmp_path, good=good)], capsys)


def test_wrong_output_suffixes(tmp_path, capsys, good):
    refused(["diagram", good, "--out", tmp_path / "d.bmp"], capsys, "--out")
    refused(["recover", "--xyz", "20", "20", "20", "--out", tmp_path / "r.csv",
             "--plot", tmp_path / "p.gif"], capsys, "--plot")


@settings(max_examples=200 if LONG else 25, deadline=None,
          suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(masked=st.one_of(st.text(max_size=20), st.sampled_from(["transparent", "black", "#00FF00", "0,0,0",
                                                                 "65535,0,0", "0.5,0.5,0.5", "-1,0,0"])),
       suffix=st.sampled_from([".png", ".tif"]), bit_depth=st.sampled_from(["8", "16"]))
def test_generated_masked_options(tmp_path_factory, capsys, masked, suffix, bit_depth):
    """``image --masked`` with any text: an image, or exit 2 with one line naming --masked."""
    folder = tmp_path_factory.mktemp("masked")
    values = np.full((3, 4, 31), 0.5)
    values[1, 2] = np.nan
    np.save(folder / "cube.npy", values)
    code, _, err = run(["image", folder / "cube.npy", "--illuminant", "D65", "--wavelengths", "400:700:10",
                        f"--masked={masked}", "--bit-depth", bit_depth, "--out", folder / f"out{suffix}"], capsys)
    if code == 2:
        assert "--masked" in err
    else:
        assert code == 0 and (folder / f"out{suffix}").is_file()
