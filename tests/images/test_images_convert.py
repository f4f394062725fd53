"""Block-wise cube conversion: equal to the in-memory library path, independent of the block
size (no seams), bounded in memory, and cross-checked against colour-science."""

from __future__ import annotations

import json
import struct
import tracemalloc
import zlib

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import spectrocolor as sc
from spectrocolor.errors import ColorimetryError, SpectrumError
from spectrocolor.images import (
    SpectralCube,
    cube_to_lab,
    cube_to_rgb,
    cube_to_xyz,
    read_cube,
)

WAVELENGTHS = np.arange(400.0, 701.0, 10.0)


def _cube(shape=(9, 13), seed=0) -> np.ndarray:
    """Smooth random reflectances (sums of Gaussians), 0..1."""
    rng = np.random.default_rng(seed)
    centres = rng.uniform(400, 700, size=(*shape, 3, 1))
    heights = rng.uniform(0, 0.33, size=(*shape, 3, 1))
    bumps = heights * np.exp(-0.5 * ((WAVELENGTHS - centres) / 40.0) ** 2)
    return 0.01 + bumps.sum(axis=-2)


@pytest.mark.parametrize("illuminant", ["D65", "A", "C"])
@pytest.mark.parametrize("observer", ["1931", "1964"])
@pytest.mark.parametrize("rows", [1, 4, None])
def test_chunked_xyz_equals_tristimulus(illuminant, observer, rows):
    values = _cube()
    expected = sc.tristimulus(sc.Spectrum(WAVELENGTHS, values), observer=observer, illuminant=illuminant)
    result = cube_to_xyz(values, WAVELENGTHS, illuminant=illuminant, observer=observer,
                         rows_per_block=rows)
    assert result.shape == (9, 13, 3) and result.dtype == np.float64
    np.testing.assert_allclose(result, expected, rtol=1e-12, atol=0)


def test_lights_without_illuminant():
    radiance = _cube() * 3.7
    expected = sc.tristimulus(sc.Spectrum(WAVELENGTHS, radiance), observer="1931")
    np.testing.assert_allclose(cube_to_xyz(radiance, WAVELENGTHS, rows_per_block=2), expected,
                               rtol=1e-12)


def test_xyz_cross_checked_with_colour_science():
    colour = pytest.importorskip("colour")
    values = _cube((4, 5))
    shape = colour.SpectralShape(400, 700, 10)
    cmfs = colour.MSDS_CMFS["CIE 1931 2 Degree Standard Observer"].copy().align(shape)
    illuminant = colour.SDS_ILLUMINANTS["D65"].copy().align(shape)
    msds = colour.MultiSpectralDistributions(
        values.reshape(-1, WAVELENGTHS.size).T, WAVELENGTHS)
    expected = colour.msds_to_XYZ(msds, cmfs, illuminant, method="Integration")
    result = cube_to_xyz(values, WAVELENGTHS, illuminant="D65", rows_per_block=3)
    np.testing.assert_allclose(result.reshape(-1, 3), np.reshape(expected, (-1, 3)), rtol=1e-9)


def test_illuminant_c_white_chromaticity():
    """The perfect white under C (5 nm, 380-780 nm): CIE 015:2018 table 9, x = 0.31006,
    y = 0.31616 (seed 001 uses illuminant C throughout)."""
    grid = np.arange(380.0, 781.0, 5.0)
    XYZ = cube_to_xyz(np.ones((2, 2, grid.size)), grid, illuminant="C")
    assert XYZ[1, 1, 1] == pytest.approx(100.0, abs=1e-12)
    np.testing.assert_allclose(sc.xy(XYZ[1, 1]), [0.31006, 0.31616], atol=5e-5)


@given(rows=st.integers(1, 12), seed=st.integers(0, 1000))
@settings(max_examples=20, deadline=None)
def test_block_size_leaves_no_seams(rows, seed):
    values = _cube((11, 6), seed)
    whole = cube_to_rgb(values, WAVELENGTHS, illuminant="D65", output="rgb_linear")
    blocked = cube_to_rgb(values, WAVELENGTHS, illuminant="D65", output="rgb_linear",
                          rows_per_block=rows)
    # exact: each image row is the same (W, K) @ (K, 3) call whatever the block (matmul loops over leading axes); the
    # rest is per pixel
    np.testing.assert_array_equal(blocked, whole)
    # exact: each image row is the same (W, K) @ (K, 3) call whatever the block (matmul loops over leading axes); the
    # rest is per pixel
    np.testing.assert_array_equal(
        cube_to_lab(values, WAVELENGTHS, illuminant="A", rows_per_block=rows),
        cube_to_lab(values, WAVELENGTHS, illuminant="A"))


def test_lab_of_perfect_white_and_against_library():
    values = _cube()
    values[0, 0] = 1.0
    lab = cube_to_lab(values, WAVELENGTHS, illuminant="D65", rows_per_block=5)
    np.testing.assert_allclose(lab[0, 0], [100.0, 0.0, 0.0], atol=1e-12)
    W = sc.weights(WAVELENGTHS, observer="1931", illuminant="D65")
    expected = sc.lab(sc.tristimulus(sc.Spectrum(WAVELENGTHS, values), observer="1931", illuminant="D65"),
                      W.sum(axis=0))
    np.testing.assert_allclose(lab, expected, rtol=1e-12, atol=1e-12)


def test_lab_cross_checked_with_colour_science():
    colour = pytest.importorskip("colour")
    values = _cube((3, 4))
    XYZ = cube_to_xyz(values, WAVELENGTHS, illuminant="D65")
    white = sc.weights(WAVELENGTHS, observer="1931", illuminant="D65").sum(axis=0)
    expected = colour.XYZ_to_Lab(XYZ / 100, colour.XYZ_to_xy(white / 100))
    np.testing.assert_allclose(cube_to_lab(values, WAVELENGTHS, illuminant="D65"), expected,
                               rtol=1e-9, atol=1e-9)


def test_lab_of_lights_needs_a_white():
    with pytest.raises(ColorimetryError, match="white_XYZ is required"):
        cube_to_lab(_cube(), WAVELENGTHS)
    white = cube_to_xyz(np.ones((1, 1, 31)), WAVELENGTHS)[0, 0]
    np.testing.assert_allclose(
        cube_to_lab(np.ones((2, 2, 31)), WAVELENGTHS, white_XYZ=white)[1, 1], [100, 0, 0],
        atol=1e-12)


@pytest.mark.parametrize("illuminant", ["A", "D65", "C"])
def test_adapted_perfect_white_is_display_white(illuminant):
    white = np.ones((2, 3, WAVELENGTHS.size))
    codes = cube_to_rgb(white, WAVELENGTHS, illuminant=illuminant, bit_depth=16)
    assert codes.dtype == np.uint16
    np.testing.assert_array_equal(codes, 65535)  # exact: uint16 codes of 1 ± 1e-15: any rounding gives the top code


def test_rgb_steps_are_the_library_functions():
    values = _cube()
    W = sc.weights(WAVELENGTHS, observer="1931", illuminant="A")
    XYZ = values @ W
    adapted = sc.adapt(XYZ, W.sum(axis=0), sc.rgb_space("Display P3").white_XYZ)
    expected = sc.render(adapted * 0.8, space="Display P3", gamut="preserve-luminance")
    codes = cube_to_rgb(values, WAVELENGTHS, illuminant="A", space="Display P3",
                        gamut="preserve-luminance", exposure=0.8, rows_per_block=2)
    assert codes.dtype == np.uint8
    # exact: uint8 codes of the same library steps on the same per-row arrays
    np.testing.assert_array_equal(codes, expected.codes)
    unadapted = cube_to_rgb(values, WAVELENGTHS, illuminant="A", adaptation=None,
                            output="rgb_encoded")
    np.testing.assert_allclose(unadapted, sc.render(XYZ).rgb_encoded, rtol=1e-12)


def test_scale_for_integer_codes():
    values = _cube()
    codes = np.round(values * 10000).astype(np.uint16)
    np.testing.assert_allclose(
        cube_to_xyz(codes, WAVELENGTHS, illuminant="D65", scale=1e-4),
        cube_to_xyz(codes / 10000.0, WAVELENGTHS, illuminant="D65"), rtol=1e-12)


def _envi(tmp_path, values):
    raw = tmp_path / "cube.img"
    np.ascontiguousarray(values.transpose(2, 0, 1), "<f4").tofile(raw)  # BSQ
    lines, samples, bands = values.shape
    (tmp_path / "cube.hdr").write_text(
        f"ENVI\nsamples = {samples}\nlines = {lines}\nbands = {bands}\nheader offset = 0\n"
        "data type = 4\ninterleave = bsq\nbyte order = 0\nwavelength units = nm\n"
        "wavelength = {" + ", ".join(f"{w:g}" for w in WAVELENGTHS) + "}\n")
    return tmp_path / "cube.hdr"


def test_disk_cube_equals_memory_cube_and_writes_into_memmap(tmp_path):
    values = _cube((40, 17)).astype(np.float32)
    cube = read_cube(_envi(tmp_path, values))
    assert isinstance(cube, SpectralCube)
    out = np.memmap(tmp_path / "xyz.raw", dtype=np.float64, mode="w+", shape=(40, 17, 3))
    result = cube_to_xyz(cube, illuminant="D65", rows_per_block=7, out=out)
    assert result is out
    # exact: each image row is the same (W, K) @ (K, 3) call whatever the block (matmul loops over leading axes); the
    # rest is per pixel
    np.testing.assert_array_equal(np.asarray(out), cube_to_xyz(values, WAVELENGTHS,
                                                               illuminant="D65"))


def test_memory_is_bounded_by_the_block(tmp_path):
    values = _cube((400, 50)).astype(np.float32)  # 2.5 MB on disk, 5 MB as float64
    cube = read_cube(_envi(tmp_path, values))
    del values
    budget_mib = 0.25
    tracemalloc.start()
    try:
        codes = cube_to_rgb(cube, illuminant="D65", max_block_mib=budget_mib)
        _, peak = tracemalloc.get_traced_memory()
    finally:
        tracemalloc.stop()
    assert codes.shape == (400, 50, 3)
    cube_bytes = 400 * 50 * 31 * 8
    assert peak < cube_bytes / 4, f"peak {peak} bytes for a {cube_bytes}-byte cube"


def test_progress_bar(capsys):
    cube_to_xyz(_cube(), WAVELENGTHS, illuminant="D65", rows_per_block=2, progress=True)
    assert "rows" in capsys.readouterr().err


def test_errors():
    values = _cube()
    with pytest.raises(SpectrumError, match="wavelengths_nm is required"):
        cube_to_xyz(values, illuminant="D65")
    with pytest.raises(SpectrumError, match="K = 30 bands"):
        cube_to_xyz(values, WAVELENGTHS[:-1], illuminant="D65")
    with pytest.raises(ColorimetryError, match="scale must be a positive number"):
        cube_to_xyz(values, WAVELENGTHS, illuminant="D65", scale=0)
    with pytest.raises(ColorimetryError, match="bit_depth must be 8 or 16"):
        cube_to_rgb(values, WAVELENGTHS, illuminant="D65", bit_depth=12)
    with pytest.raises(ColorimetryError, match="exposure"):
        cube_to_rgb(values, WAVELENGTHS, illuminant="D65", exposure=-1)
    with pytest.raises(ColorimetryError, match="gamut"):
        cube_to_rgb(values, WAVELENGTHS, illuminant="D65", gamut="squash")
    with pytest.raises(SpectrumError, match="rows_per_block must be at least 1"):
        cube_to_xyz(values, WAVELENGTHS, illuminant="D65", rows_per_block=0)
    cube = SpectralCube(values, WAVELENGTHS)
    with pytest.raises(SpectrumError, match="taken from the SpectralCube"):
        cube_to_xyz(cube, WAVELENGTHS)
    with pytest.raises(SpectrumError, match="30 wavelengths for 31 bands"):
        SpectralCube(values, WAVELENGTHS[1:])


def test_cli_image_png_and_tiff(tmp_path, capsys):
    import tifffile
    from PIL import Image

    from spectrocolor.cli import main

    values = _cube((20, 11)).astype(np.float32)
    hdr = _envi(tmp_path, values)
    png = tmp_path / "out.png"
    assert main(["image", str(hdr), "--illuminant", "D65", "--out", str(png), "--chunks", "3",
                 "--progress"]) == 0
    assert "wrote" in capsys.readouterr().out
    with Image.open(png) as image:
        # exact: each image row is the same (W, K) @ (K, 3) call whatever the block (matmul loops over leading axes);
        # the rest is per pixel
        np.testing.assert_array_equal(np.asarray(image),
                                      cube_to_rgb(values, WAVELENGTHS, illuminant="D65"))
    tif = tmp_path / "lab.tif"
    assert main(["image", str(hdr), "--illuminant", "A", "--quantity", "lab",
                 "--out", str(tif)]) == 0
    np.testing.assert_allclose(tifffile.imread(tif),
                               cube_to_lab(values, WAVELENGTHS, illuminant="A"), rtol=1e-6,
                               atol=1e-4)  # written as float32
    np.save(tmp_path / "cube.npy", values)
    assert main(["image", str(tmp_path / "cube.npy"), "--illuminant", "D65",
                 "--out", str(png), "--bit-depth", "16", "--wavelengths", "400:700:10",
                 "--force"]) == 0
    # exact: each image row is the same (W, K) @ (K, 3) call whatever the block (matmul loops over leading axes); the
    # rest is per pixel
    np.testing.assert_array_equal(
        _png16(png),
        cube_to_rgb(values, WAVELENGTHS, illuminant="D65", bit_depth=16))


def _png16(path):
    return _decode_png(path.read_bytes())


def _decode_png(data: bytes) -> np.ndarray:
    """Independent PNG reader (PNG specification, 3rd ed., W3C 2025): non-interlaced truecolour,
    with or without alpha, 8 or 16 bits, any of the five filter types (§9.2), in plain Python."""
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    position, chunks = 8, {}
    while position < len(data):
        (length,) = struct.unpack(">I", data[position:position + 4])
        kind = data[position + 4:position + 8]
        body = data[position + 8:position + 8 + length]
        (crc,) = struct.unpack(">I", data[position + 8 + length:position + 12 + length])
        assert crc == zlib.crc32(kind + body)
        chunks.setdefault(kind, []).append(body)
        position += 12 + length
    assert list(chunks)[-1] == b"IEND"
    width, height, depth, colour, _, _, interlace = struct.unpack(">IIBBBBB", chunks[b"IHDR"][0])
    assert depth in (8, 16) and colour in (2, 6) and interlace == 0
    channels = 3 if colour == 2 else 4
    bpp = channels * depth // 8
    stride = width * bpp
    raw = zlib.decompress(b"".join(chunks[b"IDAT"]))
    assert len(raw) == height * (stride + 1)
    previous, lines = bytearray(stride), []
    for row in range(height):
        kind, line = raw[row * (stride + 1)], bytearray(raw[row * (stride + 1) + 1:(row + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - bpp] if i >= bpp else 0
            b = previous[i]
            c = previous[i - bpp] if i >= bpp else 0
            if kind == 1:
                line[i] = (line[i] + a) % 256
            elif kind == 2:
                line[i] = (line[i] + b) % 256
            elif kind == 3:
                line[i] = (line[i] + (a + b) // 2) % 256
            elif kind == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) % 256
            else:
                assert kind == 0
        lines.append(bytes(line))
        previous = line
    samples = np.frombuffer(b"".join(lines), ">u2" if depth == 16 else np.uint8)
    return samples.reshape(height, width, channels).astype(np.uint16 if depth == 16 else np.uint8)


def test_cli_image_errors(tmp_path, capsys):
    from spectrocolor.cli import main

    np.save(tmp_path / "cube.npy", _cube((3, 3)))
    cases = [
        (["--illuminant", "D65", "--out", "x.png"], "no wavelengths"),
        (["--illuminant", "D65", "--out", "x.png", "--wavelengths", "400:700"], "--wavelengths"),
        (["--illuminant", "D65", "--out", "x.jpg", "--wavelengths", "400:700:10"], ".png or .tif"),
        (["--illuminant", "D65", "--quantity", "xyz", "--out", "x.png"], "write it to a .tif"),
        (["--illuminant", "D65", "--out", "x.png", "--wavelengths", "400:690:10"],
         "30 wavelengths for 31 bands"),
        (["--illuminant", "D65", "--out", "x.png", "--wavelengths", "400:700:10",
          "--wavelength-units", "furlong"], "unknown wavelength units 'furlong'"),
    ]
    for extra, message in cases:
        assert main(["image", str(tmp_path / "cube.npy"), *extra]) == 2
        assert message in capsys.readouterr().err


# --- streamed writing (write_converted) and masked pixels ----------------------------------------


def _masked_cube(shape=(23, 9)) -> np.ndarray:
    values = _cube(shape).astype(np.float32)
    values[0, 0] = np.nan  # a NaN in every band (an ENVI data ignore value becomes this)
    values[5, 3, 7] = np.nan  # one bad band masks the pixel too
    values[22, 8] = np.inf
    return values


MASK = np.zeros((23, 9), bool)
MASK[0, 0] = MASK[5, 3] = MASK[22, 8] = True


@pytest.mark.parametrize("rows", [1, 4, 23, None])
@pytest.mark.parametrize("bit_depth", [8, 16])
def test_streamed_png_equals_the_in_memory_codes(tmp_path, rows, bit_depth):
    from spectrocolor.images import plan_conversion, write_converted

    values = _cube((23, 9))
    plan = plan_conversion("rgb", WAVELENGTHS, illuminant="D65", bit_depth=bit_depth)
    path = write_converted(tmp_path / "a.png", values, plan, rows_per_block=rows)
    expected = cube_to_rgb(values, WAVELENGTHS, illuminant="D65", bit_depth=bit_depth)
    # exact: each image row is the same (W, K) @ (K, 3) call whatever the block (matmul loops over leading axes); the
    # rest is per pixel
    np.testing.assert_array_equal(_decode_png(path.read_bytes()), expected)
    if bit_depth == 8:  # and Pillow reads the same pixels
        from PIL import Image

        with Image.open(path) as image:
            # exact: each image row is the same (W, K) @ (K, 3) call whatever the block (matmul loops over leading
            # axes); the rest is per pixel
            np.testing.assert_array_equal(np.asarray(image), expected)
    assert [p.name for p in tmp_path.iterdir()] == ["a.png"]


@pytest.mark.parametrize("quantity", ["xyz", "lab"])
def test_streamed_tiff_equals_the_in_memory_floats(tmp_path, quantity):
    import tifffile

    from spectrocolor.images import plan_conversion, write_converted

    values = _masked_cube()
    plan = plan_conversion(quantity, WAVELENGTHS, illuminant="A")
    path = write_converted(tmp_path / "a.tif", values, plan, rows_per_block=4, metadata={"q": quantity})
    expected = (cube_to_xyz if quantity == "xyz" else cube_to_lab)(values, WAVELENGTHS, illuminant="A")
    with tifffile.TiffFile(path) as tif:
        assert tif.pages[0].rowsperstrip == 4 and json.loads(tif.pages[0].description)["q"] == quantity
        written = tif.asarray()
    # exact: XYZ and CIELAB are not masked before the product: each image row is the same (W, K) @ (K, 3) call
    # whatever the block (matmul loops over leading axes); the rest is per pixel
    np.testing.assert_array_equal(written, expected.astype(np.float32))  # NaN or inf where masked
    assert not np.isfinite(written[MASK]).any() and np.isfinite(written[~MASK]).all()


@pytest.mark.slow
def test_streaming_never_holds_the_whole_image(tmp_path):
    from spectrocolor.images import plan_conversion, write_converted

    values = _cube((1600, 50)).astype(np.float32)
    cube = read_cube(_envi(tmp_path, values))
    del values
    plan = plan_conversion("rgb", cube.wavelengths_nm, illuminant="D65", output="rgb_linear")
    image_float64_bytes = 1600 * 50 * 3 * 8
    tracemalloc.start()
    try:
        write_converted(tmp_path / "a.tif", cube.values, plan, rows_per_block=10)
        _, peak = tracemalloc.get_traced_memory()
    finally:
        tracemalloc.stop()
    # the whole float64 image would be 1.92 MB (and 0.96 MB more as float32 for the TIFF); one
    # 10-row block of spectra is 62 kB as float32, 124 kB as float64, and rendering it about as much
    assert peak < image_float64_bytes / 4, f"peak {peak} bytes"


def test_write_converted_refuses_what_the_format_cannot_hold(tmp_path):
    from spectrocolor.images import plan_conversion, write_converted

    values = _cube((3, 2))
    lab = plan_conversion("lab", WAVELENGTHS, illuminant="D65")
    codes = plan_conversion("rgb", WAVELENGTHS, illuminant="D65")
    for path, plan, extra, message in [
        (tmp_path / "a.png", lab, {}, "PNG needs integer codes"),
        (tmp_path / "a.tif", codes, {}, "TIFF output is for floats"),
        (tmp_path / "a.jpg", codes, {}, "unknown image format"),
        (tmp_path / "a.png", codes, {"metadata": {"a": 1}}, "TIFF files only"),
    ]:
        with pytest.raises(SpectrumError, match=message):
            write_converted(path, values, plan, **extra)
    with pytest.raises(SpectrumError, match=r"shape \(H, W, K\)"):
        write_converted(tmp_path / "a.png", values[0], codes)
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize("bit_depth", [8, 16])
def test_masked_transparent_gives_rgba_with_alpha_zero_there(bit_depth):
    values = _masked_cube()
    plain = cube_to_rgb(values, WAVELENGTHS, illuminant="D65", bit_depth=bit_depth)
    rgba = cube_to_rgb(values, WAVELENGTHS, illuminant="D65", bit_depth=bit_depth, masked="transparent")
    full = 255 if bit_depth == 8 else 65535
    assert rgba.shape == (23, 9, 4) and rgba.dtype == plain.dtype
    np.testing.assert_array_equal(rgba[..., 3], np.where(MASK, 0, full))  # exact: alpha codes set from the mask
    # exact: integer codes from the same calls on the same data
    np.testing.assert_array_equal(rgba[..., :3][~MASK], plain[~MASK])
    assert (rgba[MASK] == 0).all()


def test_masked_colour_in_codes_floats_and_hex():
    values = _masked_cube()
    plain = cube_to_rgb(values, WAVELENGTHS, illuminant="D65")
    magenta = cube_to_rgb(values, WAVELENGTHS, illuminant="D65", masked=(255, 0, 255))
    assert (magenta[MASK] == [255, 0, 255]).all()
    # exact: integer codes from the same calls on the same data
    np.testing.assert_array_equal(magenta[~MASK], plain[~MASK])
    hex16 = cube_to_rgb(values, WAVELENGTHS, illuminant="D65", bit_depth=16, masked="#FF8000")
    assert (hex16[MASK] == [65535, 32896, 0]).all()  # 0x80 * 257
    floats = cube_to_rgb(values, WAVELENGTHS, illuminant="D65", output="rgb_linear", masked=(0.5, 0.25, 1.0))
    # exact: the colour given for masked pixels, set
    assert (floats[MASK] == [0.5, 0.25, 1.0]).all() and np.isfinite(floats).all()
    default = cube_to_rgb(values, WAVELENGTHS, illuminant="D65", output="rgb_linear")
    assert np.isnan(default[MASK]).all()  # the default is unchanged: NaN floats, black codes
    assert (plain[MASK] == 0).all()


@pytest.mark.parametrize("masked", ["transparent", (1, 2, 3)])
def test_masked_rgba_png_and_tiff_files(tmp_path, masked):
    import tifffile

    from spectrocolor.images import plan_conversion, write_converted

    values = _masked_cube()
    png_plan = plan_conversion("rgb", WAVELENGTHS, illuminant="D65", masked=masked)
    png = write_converted(tmp_path / "a.png", values, png_plan, rows_per_block=5)
    # exact: codes of floats that agree to ~1e-13: a code moves only at a half-code tie, which these inputs do not
    # reach (masked pixels change the shapes of the 3 x 3 products)
    np.testing.assert_array_equal(_decode_png(png.read_bytes()),
                                  cube_to_rgb(values, WAVELENGTHS, illuminant="D65", masked=masked))
    tif_plan = plan_conversion("rgb", WAVELENGTHS, illuminant="D65", output="rgb_linear", masked=masked)
    tif = write_converted(tmp_path / "a.tif", values, tif_plan, rows_per_block=5)
    with tifffile.TiffFile(tif) as file:
        written = file.asarray()
        assert file.pages[0].extrasamples == ((2,) if masked == "transparent" else ())  # unassociated alpha
    expected = cube_to_rgb(values, WAVELENGTHS, illuminant="D65", output="rgb_linear", masked=masked)
    # Masked pixels are left out before the 3 × 3 products of adaptation and rendering, so blocks
    # of 5 rows and the whole image multiply (n, 3) arrays of other n, which a BLAS kernel may
    # sum in another order (a few ulps of the float64 values); stored as float32 that is at most
    # one float32 rounding apart, eps32 relative (atol: values that round to 0 on one side).
    np.testing.assert_allclose(written, expected.astype(np.float32), rtol=np.finfo(np.float32).eps,
                               atol=64 * np.finfo(float).eps * np.nanmax(np.abs(expected)))
    np.testing.assert_array_equal(np.isnan(written), np.isnan(expected))


@pytest.mark.parametrize("masked, kwargs, message", [
    ("see-through", {}, "masked: expected"),
    ("#12345", {}, "masked: expected"),
    ("#GG0000", {}, "masked: expected"),
    ((256, 0, 0), {}, "whole codes from 0 to 255"),
    ((1.5, 0, 0), {}, "whole codes"),
    ((-1, 0, 0), {"bit_depth": 16}, "0 to 65535"),
    ((np.nan, 0, 0), {"output": "rgb_linear"}, "finite floats"),
    ((1, 2), {}, "masked: expected"),
    ([[1, 2, 3]], {}, "masked: expected"),
    (object(), {}, "masked: expected"),
])
def test_masked_refuses_what_it_cannot_be(masked, kwargs, message):
    with pytest.raises(ColorimetryError, match=message):
        cube_to_rgb(_cube((2, 2)), WAVELENGTHS, illuminant="D65", masked=masked, **kwargs)


def test_masked_is_for_rgb_only():
    from spectrocolor.images import plan_conversion

    with pytest.raises(ColorimetryError, match="masked applies to quantity 'rgb'"):
        plan_conversion("lab", WAVELENGTHS, illuminant="D65", masked="transparent")


@given(masked=st.one_of(st.none(), st.text(max_size=12), st.lists(st.floats(allow_nan=True), max_size=4),
                        st.lists(st.integers(-70000, 70000), min_size=3, max_size=3)),
       bit_depth=st.sampled_from([8, 16]), output=st.sampled_from(["codes", "rgb_linear"]))
@settings(max_examples=80, deadline=None)
def test_generated_masked_options_give_an_image_or_one_clear_error(masked, bit_depth, output):
    values = _cube((3, 2))
    values[0, 0] = np.nan
    try:
        result = cube_to_rgb(values, WAVELENGTHS, illuminant="D65", masked=masked, bit_depth=bit_depth,
                             output=output)
    except ColorimetryError as exc:
        assert str(exc).startswith("masked: expected") and "\n" not in str(exc)
        return
    assert result.shape[-1] == (4 if masked == "transparent" else 3)
    if masked is not None and masked != "transparent":
        assert np.isfinite(result.astype(float)).all()


def test_cli_masked(tmp_path, capsys):
    import tifffile
    from PIL import Image

    from spectrocolor.cli import main

    values = _masked_cube()
    np.save(tmp_path / "cube.npy", values)
    common = ["image", str(tmp_path / "cube.npy"), "--illuminant", "D65", "--wavelengths", "400:700:10"]
    assert main([*common, "--masked", "transparent", "--out", str(tmp_path / "a.png")]) == 0
    with Image.open(tmp_path / "a.png") as image:
        assert image.mode == "RGBA"
        np.testing.assert_array_equal(np.asarray(image)[..., 3], np.where(MASK, 0, 255))
    assert main([*common, "--masked", "#00ff00", "--out", str(tmp_path / "b.png")]) == 0
    with Image.open(tmp_path / "b.png") as image:
        assert (np.asarray(image)[MASK] == [0, 255, 0]).all()
    assert main([*common, "--masked", "0.1,0.2,0.3", "--out", str(tmp_path / "c.tif")]) == 0
    np.testing.assert_allclose(tifffile.imread(tmp_path / "c.tif")[MASK], [[0.1, 0.2, 0.3]] * 3, rtol=1e-7)
    assert main([*common, "--masked", "transparent", "--out", str(tmp_path / "d.tif")]) == 0
    assert tifffile.imread(tmp_path / "d.tif").shape == (23, 9, 4)
    assert main([*common, "--masked", "black", "--out", str(tmp_path / "e.png")]) == 0
    capsys.readouterr()
    for extra, message in [
        (["--masked", "purple", "--out", str(tmp_path / "x.png")], "--masked: expected black, transparent"),
        (["--masked", "300,0,0", "--out", str(tmp_path / "x.png")], "--masked: expected"),
        (["--masked", "transparent", "--quantity", "lab", "--out", str(tmp_path / "x.tif")],
         "--masked applies to --quantity rgb"),
    ]:
        assert main([*common, *extra]) == 2
        err = capsys.readouterr().err
        assert message in err and err.count("\n") == 1
    assert not (tmp_path / "x.png").exists() and not (tmp_path / "x.tif").exists()
