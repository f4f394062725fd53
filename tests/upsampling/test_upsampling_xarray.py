"""The xarray accessor's upsample: RGB DataArray -> spectral cube, equal to the NumPy and dask paths."""

import numpy as np
import pytest
import xarray as xr

import spectrocolor as sc
import spectrocolor.images  # noqa: F401  (registers DataArray.spectro)
from spectrocolor.upsampling import PATHS, upsample, upsample_dask, upsample_spectra
from upsampling_tables import rec2020_table, srgb_table

da = pytest.importorskip("dask.array")
PATHS_CODE = {name: code for code, name in PATHS.items()}


def rgb_image(shape=(5, 6), seed=0):
    values = np.random.default_rng(seed).random((*shape, 3)) * 1.2 - 0.1  # some outside the cube
    return xr.DataArray(values, dims=("y", "x", "RGB"), coords={"RGB": ["R", "G", "B"]},
                        attrs={"note": "dropped"})


def test_numpy_backed_equals_upsample_spectra_bit_for_bit():
    table, rgb = srgb_table(), rgb_image()
    cube = rgb.spectro.upsample(table)
    assert cube.dims == ("y", "x", "wavelength")
    # exact: per-pixel blend of 4 nodes in a fixed order (no BLAS, no sum across pixels), whatever the batch or block
    np.testing.assert_array_equal(cube.values, upsample_spectra(table, rgb.values))
    # exact: a copy of the same numbers (written and read back, no arithmetic)
    np.testing.assert_array_equal(cube.coords["wavelength"].values, table.wavelengths_nm)
    assert cube.coords["wavelength"].attrs["units"] == "nm"
    assert cube.attrs == {"quantity": "reflectance", "space": "sRGB", "illuminant": table.illuminant,
                          "observer": table.observer, "out_of_range": "toward-grey"}


def test_dask_backed_is_lazy_and_equals_upsample_dask_and_numpy_bit_for_bit():
    table, rgb = rec2020_table(), rgb_image((7, 5), seed=1)
    lazy = rgb.chunk({"y": 3, "x": 2, "RGB": 2})  # the channels split too: taken as one chunk
    cube = lazy.spectro.upsample(table, out_of_range="nan")
    assert isinstance(cube.data, da.Array) and cube.data.chunks[0] == (3, 3, 1)
    computed = cube.compute().values
    reference = upsample_dask(table, da.from_array(rgb.values, chunks=(3, 2, 3)), "nan").compute()
    whole = upsample(table, rgb.values, "nan")
    # pixels in the thin gap of a cell with moved nodes are solved (path 2), and the solver's
    # rounding depends on the batch (one colour alone vs several: measured 1e-14 apart, two
    # certified solutions of one strictly convex programme); the rest are blends
    solved = whole.path == PATHS_CODE["certified solve"]
    for other in (reference, whole.reflectance):
        # exact: per-pixel blend of 4 nodes in a fixed order (no BLAS, no sum across pixels), any batch or block
        np.testing.assert_array_equal(computed[~solved], other[~solved])
        # 1e-12 on the 0-1 scale: 100 times the measured spread of two certified solutions
        np.testing.assert_allclose(computed[solved], other[solved], rtol=0, atol=1e-12)
    assert np.isnan(computed).any() and not np.isnan(computed).all()


def test_channel_dimension_anywhere_and_the_colour_is_reproduced():
    table = srgb_table()
    rgb = rgb_image((4, 3), seed=2).clip(0, 1).transpose("RGB", "x", "y").rename({"RGB": "channel"})
    cube = rgb.spectro.upsample(table, dim="channel")
    assert cube.dims == ("x", "y", "wavelength")
    XYZ = cube.spectro.to_xyz(illuminant=table.illuminant)
    target = np.moveaxis(rgb.values, 0, -1) @ table.matrix.T
    error = np.abs(XYZ.values - target).max(axis=-1) / np.abs(target).max(axis=-1)
    assert error.max() <= 1e-9  # the table's acceptance criterion, through the accessor


@pytest.mark.parametrize("array, arguments, message", [
    (rgb_image(), {"table": "srgb.scup"}, "UpsamplingTable"),
    (rgb_image(), {"dim": "channel"}, "'channel' of length 3"),
    (rgb_image().isel(RGB=[0, 1]), {}, "length 3"),
    (rgb_image().rename({"x": "wavelength"}), {}, "already has a 'wavelength'"),
    (rgb_image(), {"out_of_range": "sideways"}, "sideways"),
])
def test_bad_arguments_get_one_clear_error(array, arguments, message):
    arguments = {"table": srgb_table(), **arguments}
    with pytest.raises(sc.ColorimetryError, match=message):
        array.spectro.upsample(**arguments)
