"""Block-wise cube conversion: equal to the in-memory library path, independent of the block
size (no seams), bounded in memory, and cross-checked against colour-science."""

from __future__ import annotations

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
    np.testing.assert_array_equal(blocked, whole)  # bit for bit
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
    np.testing.assert_array_equal(codes, 65535)


def test_rgb_steps_are_the_library_functions():
    values = _cube()
    W = sc.weights(WAVELENGTHS, observer="1931", illuminant="A")
    XYZ = values @ W
    adapted = sc.adapt(XYZ, W.sum(axis=0), sc.rgb_space("Display P3").white_XYZ)
    expected = sc.render(adapted * 0.8, space="Display P3", gamut="preserve-luminance")
    codes = cube_to_rgb(values, WAVELENGTHS, illuminant="A", space="Display P3",
                        gamut="preserve-luminance", exposure=0.8, rows_per_block=2)
    assert codes.dtype == np.uint8
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
