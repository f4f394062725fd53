"""Spectral upsampling: exact reflectance spectra for RGB images at lookup-table speed.

* :func:`upsampling_table` — certified smoothest reflectances (van Trigt 1990) at the nodes of
  a grid over a display space's linear RGB cube (or normalised XYZ), with per-cell records of
  the roughness excess of interpolation (rigorous bound and measurement).
* :func:`upsample`, :func:`upsample_spectra`, :func:`colours_under`,
  :func:`texel_coefficients`, :func:`upsample_blocks`, :func:`upsample_dask` — tetrahedral
  blending of node spectra: the input colour is reproduced to 1e-9 relative and ``0 ≤ ρ ≤ 1``
  holds exactly wherever the report says ``exact``; in cells with nodes moved toward grey
  (wide-gamut spaces) every colour some reflectance produces is settled exactly
  (:mod:`spectrocolor.upsampling.moved_cells`; :data:`PATHS` names the way each took).
* :func:`relight` — an image's colours under another light.
* :func:`save_table`, :func:`load_table` — the ``.scup`` binary layout (readers in Python and
  C in ``docs/upsampling/``).
* :func:`save_texel_coefficients`, :func:`load_texel_coefficients` — per-texel coefficients
  (``.sctx``) for renderers.
* :func:`read_png` — 8- and 16-bit PNG codes without loss (Pillow cuts 16-bit RGB to 8 bits);
  :mod:`spectrocolor.imagefiles`, needs ``imagecodecs`` (extras ``images``, ``app``).

With numba installed (extra ``fast``) the lookup and blends run in compiled kernels
(:mod:`spectrocolor.upsampling.compiled`), with the same numbers as the NumPy path.

The core needs only NumPy/SciPy; dask is imported only by :func:`upsample_dask`, numba only
when a kernel first runs.
"""

from ..imagefiles import read_png
from .apply import (
    OUT_OF_RANGE_STRATEGIES,
    Lookup,
    Upsampled,
    colours_under,
    lookup,
    texel_coefficients,
    upsample,
    upsample_blocks,
    upsample_dask,
    upsample_spectra,
)
from .fileformat import load_table, save_table
from .moved_cells import PATHS
from .relight import relight, rgb_linear_from_image
from .table import NODE_STATUS, UpsamplingTable, upsampling_table
from .texels import TexelCoefficients, load_texel_coefficients, save_texel_coefficients

__all__ = [
    "NODE_STATUS",
    "OUT_OF_RANGE_STRATEGIES",
    "PATHS",
    "Lookup",
    "TexelCoefficients",
    "Upsampled",
    "UpsamplingTable",
    "colours_under",
    "load_table",
    "load_texel_coefficients",
    "lookup",
    "read_png",
    "relight",
    "rgb_linear_from_image",
    "save_table",
    "save_texel_coefficients",
    "texel_coefficients",
    "upsample",
    "upsample_blocks",
    "upsample_dask",
    "upsample_spectra",
    "upsampling_table",
]
