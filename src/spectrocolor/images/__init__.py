"""Spectral images at scale: read cubes and convert them block by block.

Needs the ``images`` extra (Pillow, tifffile, xarray, dask, h5netcdf, tqdm); the core package
never imports this. ``import spectrocolor.images`` registers the ``.spectro`` accessor on xarray
DataArrays (:class:`~spectrocolor.images.accessor.SpectroAccessor`); ``import spectrocolor``
alone does not.

* :func:`read_cube` — .npy/.npz, multi-page TIFF, ENVI, netCDF/HDF5, folder of band images.
* :func:`cube_to_xyz`, :func:`cube_to_lab`, :func:`cube_to_rgb` — bounded-memory conversion.
* writing the results: :func:`spectrocolor.pictures.write_image` (PNG 8/16-bit codes, float TIFF).
* :func:`write_converted` — convert straight into a PNG or float TIFF, one row block at a time.
* ``DataArray.spectro.to_xyz / to_lab / to_rgb`` — the same, lazy on dask.
"""

from __future__ import annotations

from . import accessor  # noqa: F401  (registers DataArray.spectro)
from .convert import ConversionPlan, cube_to_lab, cube_to_rgb, cube_to_xyz, plan_conversion, write_converted
from .cube import MappedArray, SpectralCube, wavelengths_to_nm
from .readers import read_cube, read_envi_header

__all__ = [
    "ConversionPlan",
    "MappedArray",
    "SpectralCube",
    "cube_to_lab",
    "cube_to_rgb",
    "cube_to_xyz",
    "plan_conversion",
    "read_cube",
    "read_envi_header",
    "wavelengths_to_nm",
    "write_converted",
]
