"""Spectral cube files: each format written by its own library (or by hand for ENVI) reads back
to the same array and wavelengths; bad files get clear errors; images write and read back."""

from __future__ import annotations

import pickle
import struct
import tempfile
import zlib
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

tifffile = pytest.importorskip("tifffile")
xr = pytest.importorskip("xarray")
Image = pytest.importorskip("PIL.Image")

from spectrocolor.errors import SpectrumError  # noqa: E402
from spectrocolor.images import (  # noqa: E402
    MappedArray,
    SpectralCube,
    read_cube,
    read_envi_header,
)
from spectrocolor.pictures import write_image  # noqa: E402

WAVELENGTHS = np.arange(400.0, 701.0, 10.0)  # 31 bands


@pytest.fixture
def cube() -> np.ndarray:
    rng = np.random.default_rng(7)
    return rng.random((5, 7, WAVELENGTHS.size)).astype(np.float32)


def _same(result: SpectralCube, values: np.ndarray, wavelengths=WAVELENGTHS) -> None:
    assert result.shape == values.shape
    array = np.asarray(result.values)
    assert array.dtype == values.dtype
    # exact: a copy of the same numbers (written and read back, no arithmetic)
    np.testing.assert_array_equal(array, values)
    # exact: a copy of the same numbers (written and read back, no arithmetic)
    np.testing.assert_array_equal(result.wavelengths_nm, wavelengths)


# --- NumPy ----------------------------------------------------------------------------------


def test_npy_reads_lazily_with_given_wavelengths(tmp_path, cube):
    path = tmp_path / "cube.npy"
    np.save(path, cube)
    result = read_cube(path, wavelengths_nm=WAVELENGTHS)
    assert isinstance(result.values, MappedArray)
    _same(result, cube)
    # exact: a copy of the same numbers (written and read back, no arithmetic)
    np.testing.assert_array_equal(result.values[2:4], cube[2:4])
    # exact: a copy of the same numbers (written and read back, no arithmetic)
    np.testing.assert_array_equal(result.values[1:3, 2:5, 4:9], cube[1:3, 2:5, 4:9])


def test_npy_fortran_order(tmp_path, cube):
    path = tmp_path / "cube.npy"
    np.save(path, np.asfortranarray(cube))
    _same(read_cube(path, wavelengths_nm=WAVELENGTHS), cube)


def test_npy_without_wavelengths_is_an_error(tmp_path, cube):
    path = tmp_path / "cube.npy"
    np.save(path, cube)
    with pytest.raises(SpectrumError, match="no wavelengths"):
        read_cube(path)


def test_npy_band_count_mismatch(tmp_path, cube):
    path = tmp_path / "cube.npy"
    np.save(path, cube)
    with pytest.raises(SpectrumError, match="30 wavelengths for 31 bands"):
        read_cube(path, wavelengths_nm=WAVELENGTHS[:-1])


def test_npz_round_trip_nm_and_um(tmp_path, cube):
    np.savez(tmp_path / "a.npz", values=cube, wavelengths_nm=WAVELENGTHS)
    _same(read_cube(tmp_path / "a.npz"), cube)
    np.savez_compressed(tmp_path / "b.npz", values=cube, wavelengths_um=WAVELENGTHS / 1000)
    result = read_cube(tmp_path / "b.npz")
    np.testing.assert_allclose(result.wavelengths_nm, WAVELENGTHS, rtol=1e-15)


def test_npz_missing_wavelengths(tmp_path, cube):
    np.savez(tmp_path / "a.npz", values=cube)
    with pytest.raises(SpectrumError, match="missing wavelengths"):
        read_cube(tmp_path / "a.npz")


def test_npz_unitless_wavelengths_need_units(tmp_path, cube):
    np.savez(tmp_path / "a.npz", values=cube, wavelengths=WAVELENGTHS)
    with pytest.raises(SpectrumError, match="units are not given"):
        read_cube(tmp_path / "a.npz")
    _same(read_cube(tmp_path / "a.npz", wavelength_units="nm"), cube)


# --- TIFF -----------------------------------------------------------------------------------


@pytest.mark.parametrize("compression", [None, "zlib"])
def test_multipage_tiff_round_trip(tmp_path, cube, compression):
    path = tmp_path / "cube.tif"
    tifffile.imwrite(path, np.moveaxis(cube, -1, 0), compression=compression,
                     metadata={"wavelengths_nm": WAVELENGTHS.tolist()})
    with tifffile.TiffFile(path) as tif:
        assert len(tif.pages) == WAVELENGTHS.size  # one page per band
    result = read_cube(path)
    assert isinstance(result.values, MappedArray) == (compression is None)
    _same(result, cube)
    # exact: a copy of the same numbers (written and read back, no arithmetic)
    np.testing.assert_array_equal(result.values[3:5, 1:4], cube[3:5, 1:4])


def test_tiff_micrometre_metadata_and_big_endian(tmp_path, cube):
    path = tmp_path / "cube.tiff"
    tifffile.imwrite(path, np.moveaxis(cube.astype(">f4"), -1, 0), byteorder=">",
                     metadata={"wavelengths": (WAVELENGTHS / 1000).tolist(),
                               "wavelength_units": "micrometers"})
    result = read_cube(path)
    # exact: a copy of the same numbers (written and read back, no arithmetic)
    np.testing.assert_array_equal(np.asarray(result.values), cube)
    np.testing.assert_allclose(result.wavelengths_nm, WAVELENGTHS, rtol=1e-15)


def test_tiff_errors(tmp_path, cube):
    path = tmp_path / "cube.tif"
    tifffile.imwrite(path, np.moveaxis(cube, -1, 0), metadata={"note": "no wavelengths"})
    with pytest.raises(SpectrumError, match="missing wavelengths"):
        read_cube(path)
    tifffile.imwrite(path, np.moveaxis(cube, -1, 0),
                     metadata={"wavelengths": WAVELENGTHS.tolist(), "wavelength_units": "cm-1"})
    with pytest.raises(SpectrumError, match="unknown wavelength units 'cm-1'"):
        read_cube(path)
    tifffile.imwrite(path, np.moveaxis(cube, -1, 0),
                     metadata={"wavelengths_nm": WAVELENGTHS[:-2].tolist()})
    with pytest.raises(SpectrumError, match="29 wavelengths for 31 bands"):
        read_cube(path)


# --- ENVI -----------------------------------------------------------------------------------

_ENVI_CODES = {"u1": 1, "i2": 2, "i4": 3, "f4": 4, "f8": 5, "u2": 12}


def _write_envi(folder: Path, values: np.ndarray, interleave: str, *, big_endian=False,
                offset=0, wavelengths="{400, 410}", units="Nanometers", raw_name="scene.img",
                extra="") -> Path:
    """An ENVI file pair written by hand from the format's documented layout."""
    lines, samples, bands = values.shape
    stored = {"bsq": values.transpose(2, 0, 1), "bil": values.transpose(0, 2, 1),
              "bip": values}[interleave]
    dtype = values.dtype.newbyteorder(">" if big_endian else "<")
    (folder / raw_name).write_bytes(b"\0" * offset + np.ascontiguousarray(stored, dtype).tobytes())
    header = [
        "ENVI",
        "description = {synthetic cube,",
        "  written by the tests}",
        f"samples = {samples}",
        f"lines   = {lines}",
        f"bands   = {bands}",
        f"header offset = {offset}",
        "file type = ENVI Standard",
        f"data type = {_ENVI_CODES[values.dtype.str[1:]]}",
        f"interleave = {interleave}",
        f"byte order = {1 if big_endian else 0}",
    ]
    if units is not None:
        header.append(f"wavelength units = {units}")
    if wavelengths is not None:
        header.append(f"wavelength = {wavelengths}")
    header.append(extra)
    hdr = folder / (Path(raw_name).stem + ".hdr")
    hdr.write_text("\n".join(header) + "\n")
    return hdr


def _envi_list(values) -> str:
    """A wavelength list spread over several lines, as ENVI writers do."""
    items = [f"{v:g}" for v in values]
    return "{\n " + ",\n ".join(", ".join(items[i:i + 8]) for i in range(0, len(items), 8)) + "}"


@pytest.mark.parametrize("interleave", ["bsq", "bil", "bip"])
@pytest.mark.parametrize("big_endian", [False, True])
def test_envi_round_trip(tmp_path, cube, interleave, big_endian):
    hdr = _write_envi(tmp_path, cube, interleave, big_endian=big_endian, offset=128,
                      wavelengths=_envi_list(WAVELENGTHS))
    result = read_cube(hdr)
    _same(result, cube)
    # exact: a copy of the same numbers (written and read back, no arithmetic)
    np.testing.assert_array_equal(result.values[1:4], cube[1:4])  # row reads without mmap
    _same(read_cube(tmp_path / "scene.img"), cube)  # the raw file finds its header


def test_envi_micrometres_are_converted(tmp_path, cube):
    hdr = _write_envi(tmp_path, cube, "bip", wavelengths=_envi_list(WAVELENGTHS / 1000),
                      units="Micrometers")
    np.testing.assert_allclose(read_cube(hdr).wavelengths_nm, WAVELENGTHS, rtol=1e-15)


@settings(max_examples=25, deadline=None)
@given(
    shape=st.tuples(st.integers(1, 6), st.integers(1, 6), st.integers(1, 5)),
    dtype=st.sampled_from(["u1", "i2", "u2", "i4", "f4", "f8"]),
    interleave=st.sampled_from(["bsq", "bil", "bip"]),
    big_endian=st.booleans(),
    offset=st.integers(0, 64),
    data=st.data(),
)
def test_envi_any_layout_round_trips(shape, dtype, interleave, big_endian, offset, data):
    rng = np.random.default_rng(data.draw(st.integers(0, 2**32 - 1)))
    values = (rng.random(shape) * 100).astype(dtype)
    wavelengths = 380.0 + 7.5 * np.arange(shape[2])
    with tempfile.TemporaryDirectory() as folder:
        hdr = _write_envi(Path(folder), values, interleave, big_endian=big_endian, offset=offset,
                          wavelengths=_envi_list(wavelengths))
        result = read_cube(hdr)
        # exact: a copy of the same numbers (written and read back, no arithmetic)
        np.testing.assert_array_equal(np.asarray(result.values), values)
        # exact: a copy of the same numbers (written and read back, no arithmetic)
        np.testing.assert_array_equal(result.values[shape[0] - 1:], values[shape[0] - 1:])
        # exact: a copy of the same numbers (written and read back, no arithmetic)
        np.testing.assert_array_equal(result.wavelengths_nm, wavelengths)


def test_envi_header_parser(tmp_path, cube):
    hdr = _write_envi(tmp_path, cube, "bsq", wavelengths=_envi_list(WAVELENGTHS),
                      extra="reflectance scale factor = 10000\n; a comment")
    fields = read_envi_header(hdr)
    assert fields["description"] == "{synthetic cube, written by the tests}"
    assert fields["interleave"] == "bsq"
    # exact: decimal text parsed by float(): correctly rounded, the same double on every CPU
    assert read_cube(hdr, raw=True).metadata["reflectance scale factor"] == 10000.0


@pytest.mark.parametrize(
    ("kwargs", "message"),
    [
        ({"wavelengths": None}, "missing wavelengths"),
        ({"wavelengths": "{400, 410, 420}"}, "lists 3 values but 'bands' = 31"),
        ({"units": "Wavenumber"}, "unknown wavelength units 'Wavenumber'"),
        ({"units": None}, "units are not given"),
        ({"extra": "interleave = bsx"}, "'interleave' must be bsq, bil or bip"),
    ],
)
def test_envi_bad_headers(tmp_path, cube, kwargs, message):
    options = {"wavelengths": _envi_list(WAVELENGTHS)} | kwargs
    hdr = _write_envi(tmp_path, cube, "bsq", **options)
    with pytest.raises(SpectrumError, match=message):
        read_cube(hdr)


def test_envi_truncated_raw_file(tmp_path, cube):
    hdr = _write_envi(tmp_path, cube, "bil", wavelengths=_envi_list(WAVELENGTHS))
    raw = tmp_path / "scene.img"
    raw.write_bytes(raw.read_bytes()[:-4])
    with pytest.raises(SpectrumError, match="the file has 4336 bytes but the header"):
        read_cube(hdr)


def test_envi_not_a_header(tmp_path):
    (tmp_path / "x.hdr").write_text("samples = 3\n")
    with pytest.raises(SpectrumError, match="not an ENVI header"):
        read_cube(tmp_path / "x.hdr")


# --- netCDF / HDF5 ----------------------------------------------------------------------------


@pytest.mark.parametrize(("suffix", "units", "factor"),
                         [(".nc", "nm", 1.0), (".h5", "micrometers", 1e-3), (".nc", "µm", 1e-3)])
def test_netcdf_round_trip(tmp_path, cube, suffix, units, factor):
    path = tmp_path / f"cube{suffix}"
    array = xr.DataArray(cube, dims=("y", "x", "wavelength"),
                         coords={"wavelength": ("wavelength", WAVELENGTHS * factor,
                                                {"units": units})}, name="radiance")
    array.to_netcdf(path, engine="h5netcdf")
    result = read_cube(path)
    # exact: a copy of the same numbers (written and read back, no arithmetic)
    np.testing.assert_array_equal(np.asarray(result.values), cube)
    np.testing.assert_allclose(result.wavelengths_nm, WAVELENGTHS, rtol=1e-15)


def test_netcdf_wavelength_first_is_transposed(tmp_path, cube):
    path = tmp_path / "cube.nc"
    xr.DataArray(np.moveaxis(cube, -1, 0), dims=("wavelength", "y", "x"),
                 coords={"wavelength": ("wavelength", WAVELENGTHS, {"units": "nm"})},
                 name="r").to_netcdf(path, engine="h5netcdf")
    # exact: a copy of the same numbers (written and read back, no arithmetic)
    np.testing.assert_array_equal(np.asarray(read_cube(path).values), cube)


def test_netcdf_errors(tmp_path, cube):
    path = tmp_path / "cube.nc"
    dataset = xr.Dataset(
        {"a": (("y", "x", "wavelength"), cube), "b": (("y", "x", "wavelength"), cube)},
        coords={"wavelength": WAVELENGTHS},
    )
    dataset.to_netcdf(path, engine="h5netcdf")
    with pytest.raises(SpectrumError, match="several variables"):
        read_cube(path)
    with pytest.raises(SpectrumError, match="units are not given"):
        read_cube(path, variable="a")
    # exact: a copy of the same numbers (written and read back, no arithmetic)
    np.testing.assert_array_equal(
        np.asarray(read_cube(path, variable="b", wavelength_units="nm").values), cube)
    xr.Dataset({"a": (("y", "x", "band"), cube)}).to_netcdf(tmp_path / "n.nc", engine="h5netcdf")
    with pytest.raises(SpectrumError, match="no variable has a 'wavelength' dimension"):
        read_cube(tmp_path / "n.nc")
    xr.Dataset({"a": (("y", "x", "wavelength"), cube)}).to_netcdf(tmp_path / "m.nc",
                                                                 engine="h5netcdf")
    with pytest.raises(SpectrumError, match="missing wavelengths"):
        read_cube(tmp_path / "m.nc")


# --- folder of band images ---------------------------------------------------------------------


def test_folder_of_16_bit_pngs(tmp_path):
    rng = np.random.default_rng(3)
    codes = rng.integers(0, 65536, size=(4, 6, 5)).astype(np.uint16)
    names = ["scene_400nm.png", "scene_410nm.png", "scene_420nm.png", "scene_430nm.png",
             "scene_440nm.png"]
    for k in [3, 0, 4, 1, 2]:  # written out of order
        Image.fromarray(codes[..., k]).save(tmp_path / names[k])
    (tmp_path / "notes.txt").write_text("ignored")
    result = read_cube(tmp_path)
    _same(result, codes, np.arange(400.0, 441.0, 10.0))


def test_folder_of_float_tiffs_in_micrometres(tmp_path, cube):
    for k, wavelength in enumerate(WAVELENGTHS):
        tifffile.imwrite(tmp_path / f"band-{wavelength / 1000:.2f}um.tif", cube[..., k])
    result = read_cube(tmp_path)
    # exact: a copy of the same numbers (written and read back, no arithmetic)
    np.testing.assert_array_equal(result.values, cube)
    np.testing.assert_allclose(result.wavelengths_nm, WAVELENGTHS, rtol=1e-12)


def test_folder_errors(tmp_path, cube):
    for k in range(2):
        tifffile.imwrite(tmp_path / f"band_{400 + 10 * k}.tif", cube[..., k])
    with pytest.raises(SpectrumError, match="units are not given"):
        read_cube(tmp_path)
    _same(read_cube(tmp_path, wavelength_units="nm"), cube[..., :2], np.array([400.0, 410.0]))
    tifffile.imwrite(tmp_path / "band_0.41um.tif", cube[..., 1])
    with pytest.raises(SpectrumError, match="several images for the same wavelength"):
        read_cube(tmp_path, wavelength_units="nm")
    (tmp_path / "band_0.41um.tif").unlink()
    tifffile.imwrite(tmp_path / "band_420.tif", cube[:2, :, 2])
    with pytest.raises(SpectrumError, match="differ in size"):
        read_cube(tmp_path, wavelength_units="nm")
    (tmp_path / "band_420.tif").unlink()
    tifffile.imwrite(tmp_path / "background.tif", cube[..., 3])
    with pytest.raises(SpectrumError, match="no wavelength in the file name"):
        read_cube(tmp_path, wavelength_units="nm")


def test_unknown_format_and_missing_file(tmp_path):
    (tmp_path / "cube.xyz").write_text("?")
    with pytest.raises(SpectrumError, match="unknown cube format '.xyz'"):
        read_cube(tmp_path / "cube.xyz")
    with pytest.raises(FileNotFoundError):
        read_cube(tmp_path / "absent.npy")


def test_mapped_array_pickles_as_a_reference(tmp_path):
    values = np.arange(2 * 3 * 1000, dtype=np.float64).reshape(2, 3, 1000)
    np.save(tmp_path / "big.npy", values)
    mapped = read_cube(tmp_path / "big.npy", wavelengths_nm=np.arange(1000.0) + 1).values
    blob = pickle.dumps(mapped)
    assert len(blob) < 1000  # a path and a layout, not 48 kB of data
    # exact: a copy of the same numbers (written and read back, no arithmetic)
    np.testing.assert_array_equal(np.asarray(pickle.loads(blob)), values)


# --- writers ------------------------------------------------------------------------------------


def test_png_8_bit(tmp_path):
    codes = np.random.default_rng(1).integers(0, 256, (3, 4, 3)).astype(np.uint8)
    write_image(tmp_path / "a.png", codes)
    with Image.open(tmp_path / "a.png") as image:
        assert image.mode == "RGB"
        # exact: integer codes through an encoder and a decoder: no floating point
        np.testing.assert_array_equal(np.asarray(image), codes)


def _decode_png_rgb16(data: bytes) -> np.ndarray:
    """Independent reader for unfiltered, non-interlaced 16-bit RGB PNG (PNG spec, 3rd ed.)."""
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
    width, height, depth, colour, _, _, interlace = struct.unpack(">IIBBBBB", chunks[b"IHDR"][0])
    assert (depth, colour, interlace) == (16, 2, 0)
    raw = np.frombuffer(zlib.decompress(b"".join(chunks[b"IDAT"])), np.uint8)
    raw = raw.reshape(height, 1 + width * 6)
    assert np.all(raw[:, 0] == 0)
    return raw[:, 1:].copy().view(">u2").reshape(height, width, 3).astype(np.uint16)


def test_png_16_bit_rgb(tmp_path):
    codes = np.random.default_rng(2).integers(0, 65536, (5, 3, 3)).astype(np.uint16)
    path = write_image(tmp_path / "a.png", codes)
    # exact: integer codes through an encoder and a decoder: no floating point
    np.testing.assert_array_equal(_decode_png_rgb16(path.read_bytes()), codes)
    with Image.open(path) as image:  # Pillow reads it (as 8-bit: the high bytes)
        assert image.size == (3, 5)
        np.testing.assert_array_equal(np.asarray(image.convert("RGB")), codes >> 8)


def test_float_tiff_with_metadata(tmp_path):
    XYZ = np.random.default_rng(4).random((4, 5, 3)) * 100
    write_image(tmp_path / "xyz.tif", XYZ, metadata={"quantity": "XYZ100", "illuminant": "D65"})
    # exact: a copy of the same numbers (written and read back, no arithmetic)
    np.testing.assert_array_equal(tifffile.imread(tmp_path / "xyz.tif"), XYZ)
    with tifffile.TiffFile(tmp_path / "xyz.tif") as tif:
        assert tif.shaped_metadata[0]["quantity"] == "XYZ100"


def test_writer_errors(tmp_path):
    with pytest.raises(SpectrumError, match="PNG needs uint8 or uint16 codes"):
        write_image(tmp_path / "a.png", np.zeros((2, 2, 3)))
    with pytest.raises(SpectrumError, match="TIFF output is for float32/float64"):
        write_image(tmp_path / "a.tif", np.zeros((2, 2, 3), np.uint8))
    with pytest.raises(SpectrumError, match="shape"):
        write_image(tmp_path / "a.png", np.zeros((2, 2, 4), np.uint8))
    with pytest.raises(SpectrumError, match="unknown image format '.jpg'"):
        write_image(tmp_path / "a.jpg", np.zeros((2, 2, 3), np.uint8))


@pytest.mark.parametrize("suffix", [".npy", ".npz", ".tif"])
def test_garbage_files_are_spectrum_errors(tmp_path, suffix):
    path = tmp_path / f"garbage{suffix}"
    path.write_bytes(b"garbage, not an array")
    with pytest.raises(SpectrumError, match="not a"):
        read_cube(path, wavelengths_nm=np.arange(400.0, 701.0, 10.0))


def test_text_arrays_are_not_cubes(tmp_path):
    np.save(tmp_path / "text.npy", np.full((2, 2, 3), "a"))
    with pytest.raises(SpectrumError, match="values must be numbers"):
        read_cube(tmp_path / "text.npy", wavelengths_nm=[400.0, 500.0, 600.0])
    np.savez(tmp_path / "text.npz", values=np.full((2, 2, 3), "a"), wavelengths_nm=[400, 500, 600])
    with pytest.raises(SpectrumError, match="values must be numbers"):
        read_cube(tmp_path / "text.npz")
