"""Spectral image readers added for instrument and dataset files: ENVI's reading fields (reflectance
scale factor, data ignore value, bbl, fwhm) honoured the same way in the API and the CLI, MATLAB
.mat cubes (v5 through scipy.io, v7.3 as HDF5 through h5py), and headers that claim more data than
the file holds refused before anything is allocated."""

import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import spectrocolor as sc
from spectrocolor import SpectrumError
from spectrocolor.images import cube_to_xyz, read_cube

sys.path.insert(0, str(Path(__file__).parent))
from test_images_io import _envi_list, _write_envi  # noqa: E402  (the ENVI writer of the cube tests)

WAVELENGTHS = np.arange(400.0, 701.0, 10.0)


@pytest.fixture
def codes():
    """Reflectance 0.5 everywhere as int16 codes of 1e-4, one pixel marked -9999 (no data)."""
    values = np.full((3, 4, WAVELENGTHS.size), 5000, dtype=np.int16)
    values[1, 2, :] = -9999
    return values


def _envi_with_fields(folder, values, extra):
    return _write_envi(folder, values, "bil", wavelengths=_envi_list(WAVELENGTHS), extra=extra)


def test_envi_scale_factor_and_ignore_value_are_applied_through_the_api(tmp_path, codes):
    hdr = _envi_with_fields(tmp_path, codes, "reflectance scale factor = 10000\ndata ignore value = -9999")
    cube = read_cube(hdr)
    assert cube.values.dtype == np.float32 and len(cube.metadata["applied"]) == 2
    values = np.asarray(cube.values)
    assert np.isnan(values[1, 2]).all() and np.nanmax(values) == np.float32(0.5)
    XYZ = cube_to_xyz(cube, illuminant="D65")
    assert np.isnan(XYZ[1, 2]).all()
    np.testing.assert_allclose(XYZ[0, 0, 1], 50.0, rtol=1e-6)  # the docs' example: grey, not white
    raw = read_cube(hdr, raw=True)
    # exact: decimal text parsed by float(): correctly rounded, the same double on every CPU
    assert raw.values.dtype == np.int16 and raw.metadata["reflectance scale factor"] == 10000.0


def test_envi_bad_bands_are_dropped_and_fwhm_kept(tmp_path, codes):
    bbl = ["1"] * WAVELENGTHS.size
    bbl[0] = bbl[-1] = "0"
    fwhm = "{" + ", ".join(["10.5"] * WAVELENGTHS.size) + "}"
    hdr = _envi_with_fields(tmp_path, codes, f"bbl = {{{', '.join(bbl)}}}\nfwhm = {fwhm}")
    cube = read_cube(hdr)
    # exact: a copy of the same numbers (written and read back, no arithmetic)
    np.testing.assert_array_equal(cube.wavelengths_nm, WAVELENGTHS[1:-1])
    assert cube.shape == (3, 4, WAVELENGTHS.size - 2) and cube.metadata["fwhm_nm"].shape == (WAVELENGTHS.size - 2,)
    # exact: integer codes 5000 read as floats
    np.testing.assert_array_equal(np.asarray(cube.values)[0, 0], np.full(WAVELENGTHS.size - 2, 5000.0))
    assert np.asarray(cube.values[0:2, 1:3, 0:4]).shape == (2, 2, 4)


@pytest.mark.parametrize(
    ("extra", "message"),
    [
        ("bbl = {1, 0}", "'bbl' lists 2 values"),
        ("reflectance scale factor = 0", "finite \\(positive\\)"),
        ("data ignore value = none", "must be a number"),
        ("bbl = {" + ", ".join(["2"] * 31) + "}", "1 \\(good band\\) or 0"),
        ("bbl = {" + ", ".join(["0"] * 31) + "}", "every band bad"),
    ],
)
def test_envi_reading_fields_bad_values_are_clear_errors(tmp_path, codes, extra, message):
    with pytest.raises(SpectrumError, match=message):
        read_cube(_envi_with_fields(tmp_path, codes, extra))


def test_cli_image_applies_the_same_fields(tmp_path, codes):
    hdr = _envi_with_fields(tmp_path, codes, "reflectance scale factor = 10000\ndata ignore value = -9999")
    out = tmp_path / "xyz.tif"
    result = subprocess.run(
        [
            sys.executable,
            "-m",
            "spectrocolor",
            "image",
            str(hdr),
            "--illuminant",
            "D65",
            "--quantity",
            "xyz",
            "--out",
            str(out),
        ],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert result.returncode == 0, result.stderr
    assert "reflectance scale factor 10000" in result.stderr and "ignore value" in result.stderr
    import tifffile

    XYZ = tifffile.imread(out)
    # exact: each image row is the same (W, K) @ (K, 3) call whatever the block (matmul loops over leading axes); the
    # rest is per pixel
    np.testing.assert_array_equal(XYZ, cube_to_xyz(read_cube(hdr), illuminant="D65").astype(np.float32))


def test_masked_pixels_render_black_in_the_api_and_the_cli(tmp_path, codes):
    from spectrocolor.images import cube_to_rgb

    hdr = _envi_with_fields(tmp_path, codes, "reflectance scale factor = 10000\ndata ignore value = -9999")
    rgb8 = cube_to_rgb(read_cube(hdr), illuminant="D65")
    assert rgb8[1, 2].tolist() == [0, 0, 0] and rgb8[0, 0].tolist() == [188, 188, 188]  # sRGB of Y = 50 grey
    out = tmp_path / "scene.png"
    result = subprocess.run(
        [sys.executable, "-m", "spectrocolor", "image", str(hdr), "--illuminant", "D65", "--out", str(out)],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert result.returncode == 0, result.stderr
    from PIL import Image

    # exact: integer codes through an encoder and a decoder: no floating point
    np.testing.assert_array_equal(np.asarray(Image.open(out)), rgb8)


def test_npy_header_claiming_more_than_the_file_is_refused_without_allocating(tmp_path):
    path = tmp_path / "huge.npy"
    header = np.lib.format.header_data_from_array_1_0(np.zeros((1, 1, 1), np.float32))
    header["shape"] = (100_000, 100_000, 31)
    with open(path, "wb") as handle:
        np.lib.format.write_array_header_1_0(handle, header)
        handle.write(b"\0" * 512)
    assert path.stat().st_size < 1024
    with pytest.raises(SpectrumError, match="claims shape \\(100000, 100000, 31\\)"):
        read_cube(path, wavelengths_nm=np.arange(31) * 10 + 400.0)


def test_envi_header_claiming_100000_squared_pixels_is_refused(tmp_path):
    hdr = _write_envi(tmp_path, np.zeros((2, 2, 2), np.float32), "bsq")
    text = hdr.read_text().replace("samples = 2", "samples = 100000").replace("lines   = 2", "lines   = 100000")
    hdr.write_text(text)
    with pytest.raises(SpectrumError, match="describes 80000000000"):
        read_cube(hdr)


# --- MATLAB --------------------------------------------------------------------------------------


def _cube():
    rng = np.random.default_rng(3)
    return rng.random((5, 6, WAVELENGTHS.size))


def test_mat_v5_reads_the_cube_and_its_wavelengths(tmp_path):
    import scipy.io

    values = _cube()
    path = tmp_path / "scene.mat"
    scipy.io.savemat(path, {"ref": values, "bands": WAVELENGTHS.reshape(1, -1), "note": "x"})
    cube = read_cube(path, wavelength_units="nm")
    # exact: a copy of the same numbers (written and read back, no arithmetic)
    np.testing.assert_array_equal(np.asarray(cube.values), values)
    # exact: a copy of the same numbers (written and read back, no arithmetic)
    np.testing.assert_array_equal(cube.wavelengths_nm, WAVELENGTHS)
    assert cube.metadata == {"variable": "ref", "mat": "v5"}
    with pytest.raises(SpectrumError, match="units are not given"):
        read_cube(path)


def _write_mat73(path: Path, variables: dict) -> None:
    """MATLAB v7.3 layout: a 512-byte text header, then HDF5 with column-major (reversed) axes."""
    import h5py

    with h5py.File(path, "w", userblock_size=512) as handle:
        for name, array in variables.items():
            handle.create_dataset(name, data=np.asarray(array).T)
    with open(path, "r+b") as handle:
        handle.write(b"MATLAB 7.3 MAT-file, Platform: GLNXA64, Created on: Wed May  1 10:00:00 2024 HDF5 schema 1.00 .")


def test_mat_v73_reads_lazily_in_matlab_order(tmp_path):
    values = _cube()
    path = tmp_path / "icvl.mat"
    _write_mat73(path, {"rad": values, "wavelengths_nm": WAVELENGTHS})
    cube = read_cube(path)
    assert cube.shape == values.shape and cube.metadata["mat"] == "v7.3"
    # exact: a copy of the same numbers (written and read back, no arithmetic)
    np.testing.assert_array_equal(cube.values[1:3, 2:5], values[1:3, 2:5])
    # exact: a copy of the same numbers (written and read back, no arithmetic)
    np.testing.assert_array_equal(cube.values[4], values[4])
    XYZ = cube_to_xyz(cube, illuminant="D65", rows_per_block=2)
    np.testing.assert_allclose(XYZ, sc.tristimulus(sc.Spectrum(WAVELENGTHS, values), illuminant="D65"), rtol=1e-12)


@pytest.mark.parametrize(
    ("variables", "kwargs", "message"),
    [
        ({"a": np.zeros((2, 2, 3)), "b": np.zeros((2, 2, 3))}, {}, "found a, b"),
        ({"a": np.zeros((2, 3))}, {}, "found none"),
        ({"a": np.zeros((2, 2, 3))}, {"variable": "z"}, "no variable 'z'"),
        ({"a": np.zeros((2, 2, 3))}, {}, "missing wavelengths"),
    ],
)
def test_mat_choices_and_missing_wavelengths_are_clear_errors(tmp_path, variables, kwargs, message):
    import scipy.io

    scipy.io.savemat(tmp_path / "v5.mat", variables)
    _write_mat73(tmp_path / "v73.mat", variables)
    for name in ("v5.mat", "v73.mat"):
        with pytest.raises(SpectrumError, match=message):
            read_cube(tmp_path / name, **kwargs)


def test_damaged_mat_files_are_clear_errors(tmp_path):
    path = tmp_path / "bad.mat"
    path.write_bytes(b"MATLAB 5.0 MAT-file" + b"\0" * 200)
    with pytest.raises(SpectrumError, match="bad.mat"):
        read_cube(path)
    path.write_bytes(b"MATLAB 7.3 MAT-file" + b"\0" * 600)
    with pytest.raises(SpectrumError, match="not a readable HDF5"):
        read_cube(path)
