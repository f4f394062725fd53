"""The fuzz suite's resource tier (issue 25): lying sizes never hang, crash or swallow the machine.

Every reader and every size-taking option is fed what a hostile or damaged input claims -- a
header promising 310 GB in a sparse file, a 1 kB archive whose member claims 4.5 GB, a chunked
dataset that is nothing but fill value, a PNG of 40 megapixels made of 234 kB of zeros, options
asking for 16384² pixels -- in a child process under an address-space limit
(``RLIMIT_AS``, :data:`ADDRESS_SPACE`) and a time limit (:data:`TIME_LIMIT_S`), as a modest
machine would run it. Each case must end in one clear error (a ``SpectrumError`` /
``ColorimetryError``, on the command line exit 2 with one ``error:`` line) or in a result computed
in bounded memory (streamed); never a traceback, a kill by the memory limit or a hang (the time
limit). The peak memory (``VmHWM``, the child's own) of the largest accepted job of each kind is recorded
(``record_property``; ``pytest -rA`` shows it) and stated in ``docs/robustness.md``.

Why this file is long: it is the tier's one file on purpose -- every hostile size, one child
runner and one way of recording peaks -- so that the held-out harness's kinds of input can be
checked against it in one place.

The long run (larger photos and textures, a few minutes):
``SPECTROCOLOR_LONG_FUZZ=1 .venv/bin/python -m pytest -m slow tests/fuzz/test_fuzz_resources.py``.
"""

from __future__ import annotations

import io
import json
import os
import struct
import subprocess
import sys
import textwrap
import zipfile
import zlib
from pathlib import Path

import numpy as np
import pytest

resource = pytest.importorskip("resource")  # POSIX: the address-space limit

#: Address space of each child: what a modest machine gives one process.
ADDRESS_SPACE = 2 * 2**30
#: Wall-clock limit of each child, s (a hang is a failure, not a wait).
TIME_LIMIT_S = 120
LONG = os.environ.get("SPECTROCOLOR_LONG_FUZZ") == "1"
long_run = pytest.mark.skipif(not LONG, reason="long fuzz run: set SPECTROCOLOR_LONG_FUZZ=1")
WAVELENGTHS = [float(w) for w in range(400, 701, 10)]

#: The child's own peak resident memory, MiB: ``VmHWM`` of Linux's /proc/self/status, which
#: starts again at exec. ``ru_maxrss`` survives fork and exec, so a child of this test run (by then
#: hundreds of MiB) would report the run's peak instead of its own; it is the fallback without /proc.
_OWN_PEAK = """
def _own_peak_mib():
    if os.path.exists("/proc/self/status"):
        with open("/proc/self/status") as status:
            for line in status:
                if line.startswith("VmHWM:"):
                    return int(line.split()[1]) / 1024
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
"""

_PRELUDE = """
import json, os, resource, sys
from spectrocolor.errors import ColorimetryError, SpectrumError
""" + _OWN_PEAK + """

def report(call):
    try:
        value = call()
        outcome = {"outcome": "result", "summary": repr(value)[:200]}
    except (SpectrumError, ColorimetryError) as exc:
        outcome = {"outcome": "error", "type": type(exc).__name__, "message": str(exc)}
    outcome["maxrss_mib"] = _own_peak_mib()
    print("OUTCOME " + json.dumps(outcome))
"""

_CLI = """
import os, resource, sys
""" + _OWN_PEAK + """
from spectrocolor.cli import main
try:
    status = main(sys.argv[1:])
finally:
    with open(os.environ["SPECTROCOLOR_TEST_RSS"], "w") as handle:
        handle.write(str(_own_peak_mib()))
sys.exit(status)
"""


def _limit() -> None:
    resource.setrlimit(resource.RLIMIT_AS, (ADDRESS_SPACE, ADDRESS_SPACE))


def _environment(extra: dict | None = None) -> dict:
    env = dict(os.environ)
    env.pop("SPECTROCOLOR_MEMORY_BUDGET", None)  # the default budget unless a case sets one
    # one BLAS thread: its per-thread buffers would count against the address space
    env.update({"OPENBLAS_NUM_THREADS": "1", "OMP_NUM_THREADS": "1", "MKL_NUM_THREADS": "1",
                "NUMBA_NUM_THREADS": "1", "MPLBACKEND": "Agg"})
    env.update(extra or {})
    return env


def _run(argv: list[str], env: dict, timeout: float) -> subprocess.CompletedProcess:
    try:
        return subprocess.run(argv, capture_output=True, text=True, timeout=timeout,
                              preexec_fn=_limit, env=env)
    except subprocess.TimeoutExpired:
        pytest.fail(f"hang: no answer within {timeout} s (the time limit) for {argv[-1][:200]}")


def api(code: str, *, env: dict | None = None, timeout: float = TIME_LIMIT_S) -> dict:
    """Run ``report(lambda: ...)`` calls in a limited child; the one outcome, checked to be clean."""
    done = _run([sys.executable, "-c", _PRELUDE + textwrap.dedent(code)], _environment(env), timeout)
    assert done.returncode == 0, (
        f"the child died (status {done.returncode}: a traceback, or killed by the "
        f"{ADDRESS_SPACE >> 30} GiB limit):\n{done.stderr[-3000:]}")
    lines = [line for line in done.stdout.splitlines() if line.startswith("OUTCOME ")]
    assert len(lines) == 1, done.stdout[-2000:]
    return json.loads(lines[0].removeprefix("OUTCOME "))


def cli(argv: list, tmp_path: Path, *, env: dict | None = None, timeout: float = TIME_LIMIT_S) -> tuple:
    """``spectrocolor ARGV`` in a limited child: (status, the error line or '', peak MiB)."""
    rss = tmp_path / f"rss-{os.getpid()}-{len(list(tmp_path.iterdir()))}.txt"
    done = _run([sys.executable, "-c", _CLI, *map(str, argv)],
                _environment({**(env or {}), "SPECTROCOLOR_TEST_RSS": str(rss)}), timeout)
    assert "Traceback" not in done.stderr, done.stderr[-3000:]
    assert done.returncode in (0, 2), (
        f"status {done.returncode} (killed by the {ADDRESS_SPACE >> 30} GiB limit?):\n{done.stderr[-2000:]}")
    error = ""
    if done.returncode == 2:
        lines = done.stderr.strip().splitlines()
        assert len(lines) == 1 and ": error: " in lines[0], done.stderr[-2000:]
        error = lines[0]
    return done.returncode, error, float(rss.read_text()) if rss.exists() else float("nan")


def record_peak(record_property, job: str, peak_mib: float) -> None:
    """Keep the peak memory of an accepted job: in the JUnit report and in the captured output."""
    record_property(f"{job}_maxrss_mib", round(peak_mib, 1))
    print(f"peak memory (VmHWM) of {job}: {peak_mib:.0f} MiB")


def assert_clear_error(outcome: dict, *phrases: str) -> None:
    assert outcome["outcome"] == "error", outcome
    message = outcome["message"]
    assert "\n" not in message, message
    for phrase in phrases:
        assert phrase in message, (phrase, message)


# --- hostile files -------------------------------------------------------------------------------


def _sparse(path: Path, length: int) -> bool:
    """Make ``path`` ``length`` bytes long without writing them; False where holes are not kept."""
    with open(path, "r+b" if path.exists() else "wb") as handle:
        handle.truncate(length)
    return getattr(os.stat(path), "st_blocks", 0) * 512 < length // 1000


def _npy_header(shape, descr="<f4") -> bytes:
    text = f"{{'descr': '{descr}', 'fortran_order': False, 'shape': {tuple(shape)!r}, }}"
    text += " " * (117 - len(text)) + "\n"
    return b"\x93NUMPY\x01\x00" + struct.pack("<H", len(text)) + text.encode()


@pytest.fixture(scope="module")
def files(tmp_path_factory) -> dict:
    folder = tmp_path_factory.mktemp("hostile")
    made: dict[str, Path] = {}
    # ENVI: a 251-byte header and a raw file of 310 GB of holes
    hdr = folder / "scene.hdr"
    hdr.write_text("ENVI\nsamples = 50000\nlines = 50000\nbands = 31\nheader offset = 0\ndata type = 4\n"
                   "interleave = bsq\nbyte order = 0\nwavelength units = nm\nwavelength = {"
                   + ",".join(f"{w:g}" for w in WAVELENGTHS) + "}\n")
    made["envi_sparse"] = hdr if _sparse(folder / "scene.raw", 50000 * 50000 * 31 * 4) else None
    # TIFF: the same cube as uncompressed pages, nothing written
    import tifffile

    tif = folder / "sparse.tif"
    tifffile.imwrite(tif, shape=(31, 50000, 50000), dtype="f4", metadata={"wavelengths_nm": WAVELENGTHS})
    made["tiff_sparse"] = tif if getattr(os.stat(tif), "st_blocks", 0) * 512 < 2**30 else None
    # .npy: a negative shape; a header claiming 310 GB and no data
    (folder / "negative.npy").write_bytes(_npy_header((10, -3, 31)) + bytes(64))
    made["npy_negative"] = folder / "negative.npy"
    (folder / "claims.npy").write_bytes(_npy_header((50000, 50000, 31)))
    made["npy_claims"] = folder / "claims.npy"
    # .npz: a member whose header claims 4.5 GB and holds 100 bytes
    with zipfile.ZipFile(folder / "lying.npz", "w", zipfile.ZIP_DEFLATED) as archive:
        archive.writestr("values.npy", _npy_header((30000, 600, 31), "<f8") + bytes(100))
        buffer = io.BytesIO()
        np.save(buffer, np.array(WAVELENGTHS))
        archive.writestr("wavelengths_nm.npy", buffer.getvalue())
    made["npz_lying"] = folder / "lying.npz"
    made["npz_bomb"] = _zip_bomb(folder / "bomb.npz")
    made["mat_fill"] = _mat73_fill(folder / "fill.mat")
    made["nc_fill"] = _netcdf_fill(folder / "fill.nc")
    made["scup_sparse"] = _scup_sparse(folder / "sparse.scup")
    made["sctx_sparse"] = _sctx_sparse(folder / "sparse.sctx")
    return made


def _zip_bomb(path: Path) -> Path:
    """An .npz whose zip directory and member header both claim 3.7 GB from ~150 bytes."""
    claimed = (15000, 1000, 31)
    with zipfile.ZipFile(path, "w", zipfile.ZIP_DEFLATED) as archive:
        archive.writestr("values.npy", _npy_header(claimed, "<f8") + bytes(100))
    data = bytearray(path.read_bytes())
    size = 128 + 15000 * 1000 * 31 * 8  # < 2**32: fits the classic zip fields
    data[22:26] = struct.pack("<I", size)  # local header: uncompressed size
    central = data.index(b"PK\x01\x02")
    data[central + 24:central + 28] = struct.pack("<I", size)  # central directory: the same
    path.write_bytes(bytes(data))
    return path


def _mat73_fill(path: Path) -> Path:
    """MATLAB v7.3: a chunked (31, 100000, 100000) float64 dataset never written (all fill value)."""
    import h5py

    with h5py.File(path, "w", userblock_size=512) as handle:
        handle.create_dataset("rad", shape=(31, 100000, 100000), chunks=(1, 1024, 1024), dtype="f8")
        handle.create_dataset("wavelengths_nm", data=np.array(WAVELENGTHS))
    with open(path, "r+b") as handle:
        handle.write(b"MATLAB 7.3 MAT-file, Platform: GLNXA64, Created on: Wed May  1 10:00:00 2024 HDF5 schema 1.00 .")
    return path


def _netcdf_fill(path: Path) -> Path:
    """netCDF-4: a chunked (100000, 100000, 31) float32 variable never written (all fill value)."""
    import h5netcdf

    with h5netcdf.File(path, "w") as handle:
        handle.dimensions = {"y": 100000, "x": 100000, "wavelength": 31}
        handle.create_variable("reflectance", ("y", "x", "wavelength"), "f4", chunks=(1024, 1024, 1))
        wavelength = handle.create_variable("wavelength", ("wavelength",), "f8", data=np.array(WAVELENGTHS))
        wavelength.attrs["units"] = "nm"
    return path


def _scup_sparse(path: Path) -> Path | None:
    """A .scup header (n = 129, K = 262) and 4.5 GB of holes: the length the header promises."""
    n, K, J = 129, 262, 8
    header = struct.pack("<8sIIII2d9d", b"SCUPTBL\0", 1, n, K, J, 380.0, 1.0, *np.eye(3).ravel())
    nodes, cells = n**3, (n - 1) ** 3
    length = 112 + J + 8 * nodes * K + 8 * nodes * 3 + 8 * nodes + 8 * nodes * 3 + 16 * cells + 8 * K * 3 + nodes + 4
    path.write_bytes(header + b"{}      ")
    return path if _sparse(path, length) else None


def _sctx_sparse(path: Path) -> Path | None:
    """A .sctx header claiming 65535 x 65535 texels (142 GB) over holes."""
    path.write_bytes(struct.pack("<8sIIIIII", b"SCTEXEL\0", 1, 65535, 65535, 17, 81, 0))
    return path if _sparse(path, 32 + 33 * 65535 * 65535 + 4) else None


def _need(files: dict, name: str) -> Path:
    if files[name] is None:
        pytest.skip("this file system does not keep holes in sparse files")
    return files[name]


def _chunk(kind: bytes, body: bytes) -> bytes:
    return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body))


def zero_png(path: Path, width: int, height: int, bit_depth: int = 8, channels: int = 3) -> Path:
    """A PNG of zeros, compressed row by row (a 40-megapixel 16-bit one takes 234 kB)."""
    colour_type = {1: 0, 2: 4, 3: 2, 4: 6}[channels]
    row = bytes(1 + width * channels * bit_depth // 8)
    compressor = zlib.compressobj(9)
    with open(path, "wb") as out:
        out.write(b"\x89PNG\r\n\x1a\n" + _chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, bit_depth,
                                                                    colour_type, 0, 0, 0)))
        for _ in range(height):
            data = compressor.compress(row)
            if data:
                out.write(_chunk(b"IDAT", data))
        out.write(_chunk(b"IDAT", compressor.flush()) + _chunk(b"IEND", b""))
    return path


# --- cube readers ---------------------------------------------------------------------------------


@pytest.mark.parametrize(("name", "phrases"), [
    ("envi_sparse", ["scene.raw", "289 GiB", "sparse file"]),
    ("tiff_sparse", ["sparse.tif", "289 GiB", "sparse file"]),
    ("npy_negative", ["negative.npy", "(10, -3, 31)", "whole number >= 0"]),
    ("npy_claims", ["claims.npy", "(50000, 50000, 31)", "289 GiB", "the file holds"]),
    ("npz_lying", ["lying.npz", "member 'values'", "4.16 GiB", "the member holds 100 B"]),
    ("npz_bomb", ["bomb.npz", "member 'values'", "expansion over 1032:1"]),
    ("mat_fill", ["fill.mat", "variable 'rad'", "fill value", "2.26 TiB"]),
    ("nc_fill", ["fill.nc", "variable 'reflectance'", "fill value", "1.13 TiB"]),
])
@pytest.mark.slow
def test_cube_files_that_lie_about_their_size_are_refused_before_reading(files, tmp_path, name, phrases):
    path = _need(files, name)
    wavelengths = ", wavelengths_nm=" + repr(WAVELENGTHS) if path.suffix == ".npy" else ""
    outcome = api(f"""
        from spectrocolor.images import read_cube, write_converted, plan_conversion
        def convert():
            cube = read_cube({str(path)!r}{wavelengths})
            plan = plan_conversion("rgb", cube.wavelengths_nm, illuminant="D65")
            return write_converted({str(tmp_path / 'out.png')!r}, cube.values, plan)
        report(convert)
    """)
    assert_clear_error(outcome, *phrases)
    argv = ["image", path, "--out", tmp_path / "cli.png"] + (["--wavelengths", "400:700:10"] if wavelengths else [])
    status, error, _ = cli(argv, tmp_path)
    assert status == 2 and phrases[-1] in error, error


@pytest.mark.slow
def test_a_cube_that_is_really_there_is_streamed_within_a_small_budget(tmp_path, record_property):
    cube = tmp_path / "cube.npy"
    values = np.lib.format.open_memmap(cube, "w+", np.float32, (1500, 1000, 31))  # 186 MB
    values[:] = np.linspace(0.0, 1.0, 31, dtype=np.float32)
    values.flush()
    del values
    status, error, peak = cli(["--memory-budget", "16MiB", "image", cube, "--wavelengths", "400:700:10",
                               "--out", tmp_path / "cube.png"], tmp_path)
    assert status == 0, error
    record_peak(record_property, "image of a 186 MB .npy cube, budget 16 MiB", peak)
    from PIL import Image

    with Image.open(tmp_path / "cube.png") as picture:
        assert picture.size == (1000, 1500)


@pytest.mark.slow
@pytest.mark.parametrize("save", ["savez", "savez_compressed"])
def test_an_npz_cube_beyond_the_budget_is_streamed(tmp_path, record_property, save):
    """An .npz member beyond the budget was refused (read whole); now it is read in blocks: a
    stored member from the archive's bytes, a deflated one inflated row by row."""
    cube = tmp_path / "cube.npz"
    values = np.empty((1000, 1000, 31), np.float32)  # 124 MB, beyond the 64 MiB budget below
    values[:] = np.linspace(0.0, 1.0, 31, dtype=np.float32)
    values[::7] *= 0.5  # some structure, so deflate does not reach its 1032:1 limit
    getattr(np, save)(cube, values=values, wavelengths_nm=np.arange(400.0, 701.0, 10.0))
    del values
    status, error, peak = cli(["--memory-budget", "64MiB", "image", cube, "--out", tmp_path / "cube.png"],
                              tmp_path)
    assert status == 0, error
    record_peak(record_property, f"image of a 124 MB .npz cube ({save}), budget 64 MiB", peak)
    assert peak < 512  # the cube itself would be 124 MB, its float64 copy 248 MB


def _photo(path: Path, width: int, height: int) -> Path:
    """A photo of one colour (a few kB to a few hundred kB on disk), of the kind the suffix says:
    .tif (deflate strips of 64 rows), .jpg, or _pal.png (a palette PNG)."""
    from PIL import Image

    codes = np.empty((height, width, 3), np.uint8)
    codes[...] = (200, 120, 40)
    if path.suffix == ".tif":
        import tifffile

        tifffile.imwrite(path, codes, photometric="rgb", compression="zlib", rowsperstrip=64)
    elif path.suffix == ".jpg":
        Image.fromarray(codes).save(path, quality=90)
    else:
        Image.fromarray(codes).quantize(4).save(path)
    return path


#: Code of a function giving the child's own peak resident memory, MiB: ``VmHWM`` of Linux's
#: /proc/self/status, which starts again at exec -- ``ru_maxrss`` keeps the high-water mark of
#: the forked parent (this test run, by then hundreds of MiB), so it overstates a small child's
#: peak -- and ``ru_maxrss`` where there is no /proc.
_HWM = ("(lambda: next((int(line.split()[1]) / 1024 for line in open('/proc/self/status') "
        "if line.startswith('VmHWM:')), None) if os.path.exists('/proc/self/status') "
        "else resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024)")

#: name -> (file, memory budget, bound on the peak of reading its 40 MP in blocks, MiB)
STREAMED_PHOTOS = {
    "TIFF": ("big.tif", "64MiB", 128),  # before: refused (decoded whole, 120 MB > 64 MiB); now 46 MiB
    "JPEG": ("big.jpg", None, 250),  # before: 416 MiB (decoded whole, copied to NumPy); now 192
    "palette PNG": ("big_pal.png", "64MiB", 160),  # before: refused (RGB expansion, whole); now 76
}


@pytest.mark.slow
@pytest.mark.parametrize("kind", sorted(STREAMED_PHOTOS))
def test_40_megapixel_photos_are_read_in_blocks_of_the_budget(tmp_path, record_property, kind):
    name, budget, bound = STREAMED_PHOTOS[kind]
    photo = _photo(tmp_path / name, 6324, 6324)  # 40 MP
    outcome = api(f"""
        from pathlib import Path
        from spectrocolor.cli.photos import open_photo

        def read():
            photo = open_photo(Path({str(photo)!r}))
            rows = photo.rows_per_block()
            seen = sum(len(block) for block in photo.blocks(rows))
            return (photo.width, seen, {_HWM}())
        report(read)
    """, env={"SPECTROCOLOR_MEMORY_BUDGET": budget} if budget else None)
    assert outcome["outcome"] == "result", outcome
    width, seen, peak = eval(outcome["summary"])  # a tuple of numbers written by repr
    assert (width, seen) == (6324, 6324), outcome
    record_peak(record_property, f"reading a 40 MP {kind} in blocks (budget {budget or '1 GiB'})", peak)
    assert peak < bound


@pytest.mark.slow
@long_run
@pytest.mark.parametrize("kind", sorted(STREAMED_PHOTOS))
def test_cli_relights_40_megapixel_tiff_jpeg_and_palette_photos(tmp_path, record_property, kind):
    name, budget, _ = STREAMED_PHOTOS[kind]
    photo = _photo(tmp_path / name, 6324, 6324)
    status, error, peak = cli([*(["--memory-budget", budget] if budget else []), "relight", photo, "--to", "A",
                               "--resolution", "3", "--out", tmp_path / "o.png"], tmp_path, timeout=1800)
    assert status == 0, error
    record_peak(record_property, f"relight of a 40 MP {kind} (budget {budget or '1 GiB'})", peak)


# --- upsampling tables and texel files ------------------------------------------------------------


def test_sparse_tables_and_texel_files_are_refused(files, tmp_path):
    table = _need(files, "scup_sparse")
    outcome = api(f"""
        from spectrocolor.upsampling import load_table
        report(lambda: load_table({str(table)!r}))
    """)
    assert_clear_error(outcome, "sparse.scup", "n = 129", "4.34 GiB", "sparse file")
    texels = _need(files, "sctx_sparse")
    outcome = api(f"""
        from spectrocolor.upsampling.texels import load_texel_coefficients
        report(lambda: load_texel_coefficients({str(texels)!r}))
    """)
    assert_clear_error(outcome, "sparse.sctx", "65535 x 65535 texels", "132 GiB", "sparse file")
    photo = zero_png(tmp_path / "photo.png", 8, 8)
    status, error, _ = cli(["relight", photo, "--to", "A", "--table", table, "--out", tmp_path / "o.png"],
                           tmp_path)
    assert status == 2 and "sparse file" in error, error


@pytest.mark.slow
def test_a_real_texel_file_beyond_the_budget_is_one_error(tmp_path):
    outcome = api(f"""
        import numpy as np
        from spectrocolor.upsampling import upsampling_table
        from spectrocolor.upsampling.texels import load_texel_coefficients, save_texel_coefficients
        table = upsampling_table("sRGB", "D65", resolution=2, measure_excess=False)
        path = save_texel_coefficients(table, np.zeros((256, 256, 3)), {str(tmp_path / 't.sctx')!r})
        report(lambda: load_texel_coefficients(path, table, memory_budget="1MiB"))
    """)
    assert_clear_error(outcome, "256 x 256 texels", "2.06 MiB", "memory budget of 1 MiB")


# --- photos ------------------------------------------------------------------------------------------


@pytest.mark.slow
def test_a_40_megapixel_png_of_zeros_relights_in_bounded_memory_on_the_server_side(tmp_path, record_property):
    photo = zero_png(tmp_path / "zeros16.png", 6324, 6324, bit_depth=16)  # 40 MP, 234 kB
    assert photo.stat().st_size < 400_000
    outcome = api(f"""
        import base64
        from spectrocolor.app.relight_photo import relight_photo
        data = base64.b64encode(open({str(photo)!r}, "rb").read()).decode()
        report(lambda: {{k: v for k, v in relight_photo(data, [30.0] * 31, 10.0, "1931").items()
                         if not k.endswith("png")}})
    """)
    assert outcome["outcome"] == "result", outcome
    assert "'photo_width': 6324" in outcome["summary"]
    record_peak(record_property, "relight_photo of a 40 MP 16-bit PNG", outcome["maxrss_mib"])
    assert outcome["maxrss_mib"] < 1024  # it was 2.4 GiB: the 16-bit codes, then floats, whole


@pytest.mark.slow
@pytest.mark.parametrize("channels", [3, 4])
def test_the_server_holds_one_8_bit_copy_of_a_40_megapixel_png(tmp_path, record_property, channels):
    """The worker decodes an 8-bit PNG block by block into one RGB image before downscaling (it
    held Pillow's decoded image and its RGB conversion: two full-size copies, 2 x 153 MiB)."""
    photo = zero_png(tmp_path / "zeros8.png", 6324, 6324, channels=channels)
    outcome = api(f"""
        import resource
        from spectrocolor.app.relight_photo import decode_photo
        data = open({str(photo)!r}, "rb").read()
        before = {_HWM}()
        def decode():
            codes, size = decode_photo(data)
            return (size, codes.shape, {_HWM}() - before)
        report(decode)
    """)
    assert outcome["outcome"] == "result", outcome
    size, shape, grown = eval(outcome["summary"])  # a tuple of numbers written by repr
    assert size == (6324, 6324) and shape == (1024, 1024, 3)
    record_peak(record_property, f"decode_photo of a 40 MP 8-bit PNG ({channels} channels), growth", grown)
    # one copy, 40 MP x 4 B = 153 MiB (Pillow keeps RGB in 4 bytes), an 8 MiB block of rows and the
    # downscale's 1024-row pass (25 MiB); it was 330 MiB (two copies and the resize)
    assert grown < 260


@pytest.mark.slow
def test_png_headers_that_lie_are_one_error(tmp_path):
    lying = zero_png(tmp_path / "lying.png", 4, 4)
    data = bytearray(lying.read_bytes())
    data[16:24] = struct.pack(">II", 16384, 16384)  # IHDR claims 2^28 pixels; the data are 4 x 4
    data[29:33] = struct.pack(">I", zlib.crc32(bytes(data[12:29])))
    lying.write_bytes(bytes(data))
    outcome = api(f"""
        from spectrocolor.upsampling import read_png
        report(lambda: read_png({str(lying)!r}))
    """)
    assert_clear_error(outcome, "lying.png", "16384 x 16384")
    status, error, _ = cli(["relight", lying, "--to", "A", "--resolution", "3", "--out", tmp_path / "o.png"],
                           tmp_path)
    assert status == 2 and "16384 x 16384 pixels need" in error, error


@pytest.mark.slow
def test_cli_upsample_streams_a_16_megapixel_texture(tmp_path, record_property):
    texture = zero_png(tmp_path / "texture.png", 4000, 4000)
    status, error, peak = cli(["upsample", texture, "--coefficients", tmp_path / "t.sctx",
                               "--resolution", "3"], tmp_path)
    assert status == 0, error
    assert (tmp_path / "t.sctx").stat().st_size == 32 + 33 * 16_000_000 + 4
    record_peak(record_property, "upsample of a 16 MP texture", peak)


@pytest.mark.slow
@long_run
@pytest.mark.parametrize(("width", "height", "bit_depth"), [(12000, 12000, 8), (16384, 16384, 8)])
def test_cli_relight_streams_photos_of_144_and_268_megapixels(tmp_path, record_property, width, height, bit_depth):
    photo = zero_png(tmp_path / "big.png", width, height, bit_depth)
    status, error, peak = cli(["relight", photo, "--to", "A", "--resolution", "3", "--out", tmp_path / "o.png"],
                              tmp_path, timeout=1800)
    assert status == 0, error
    record_peak(record_property, f"relight of a {width} x {height} photo", peak)


@pytest.mark.slow
@long_run
def test_cli_upsample_streams_an_81_megapixel_texture(tmp_path, record_property):
    texture = zero_png(tmp_path / "texture.png", 9000, 9000)
    status, error, peak = cli(["upsample", texture, "--coefficients", tmp_path / "t.sctx",
                               "--resolution", "3"], tmp_path, timeout=1800)
    assert status == 0, error
    record_peak(record_property, "upsample of an 81 MP texture", peak)


# --- options and arguments that ask for too much -----------------------------------------------------


@pytest.mark.parametrize(("argv", "phrases"), [
    (["thinfilm", "map", "--width", "16384", "--height", "16384"], ["--width 16384 --height 16384", "10 GiB"]),
    (["thinfilm", "map", "--step", "1e-6"], ["--step 1e-06 nm", "224 GiB"]),
    (["thinfilm", "map", "--max-thickness", "1e9"], ["(--max-thickness)", "298 GiB"]),
    (["relight", "PHOTO", "--to", "A", "--resolution", "65"], ["--resolution 65", "1.99 GiB",
                                                                "choose --resolution 51 or less"]),
])
def test_options_beyond_the_budget_are_one_error_naming_the_option(tmp_path, argv, phrases):
    argv = [str(zero_png(tmp_path / "p.png", 4, 4)) if a == "PHOTO" else a for a in argv]
    status, error, _ = cli([*argv, "--out", tmp_path / "o.png"], tmp_path)
    assert status == 2, error
    for phrase in phrases:
        assert phrase in error, (phrase, error)


@pytest.mark.parametrize(("call", "phrases"), [
    ("sc.macadam_limits(50.0, samples=10**7)", ["samples", "36000"]),
    ("sc.zawischa_strip(columns=10**7)", ["columns: 10000000 columns", "28.3 GiB"]),
    ("sc.colour_table(sc.soap_film, 1500.0, thickness_step_nm=1e-6)", ["thickness_step_nm", "224 GiB"]),
    ("sc.colour_table(sc.soap_film, 1e300, thickness_step_nm=1e-300)", ["thickness_step_nm"]),
    ("sc.upsampling_table(resolution=129)", ["resolution 129", "GiB"]),
])
def test_arguments_beyond_the_budget_are_one_error(call, phrases):
    outcome = api(f"""
        import spectrocolor as sc
        report(lambda: {call})
    """, timeout=60)
    assert_clear_error(outcome, *phrases)
