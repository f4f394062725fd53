"""Convert spectral cubes to XYZ, CIELAB or display RGB, block by block.

A cube (H, W, K) is processed in blocks of whole rows, so memory holds one block of spectra
(``max_block_mib``) plus the output, whatever the cube's size: a cube that lives on disk
(:class:`~spectrocolor.images.MappedArray` from ENVI/.npy/TIFF, or an ``np.memmap``) larger
than memory converts, and the output may itself be a memmap (``out=``). Every block goes
through the same functions (:mod:`spectrocolor.images.blocks`) that the xarray/dask accessor
maps over chunks, so all paths give the same numbers.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..display.gamut import DEFAULT_GAMUT
from ..errors import ColorimetryError, SpectrumError
from ..observers import DEFAULT_OBSERVER
from . import blocks
from .cube import SpectralCube

__all__ = ["cube_to_xyz", "cube_to_lab", "cube_to_rgb", "ConversionPlan", "plan_conversion"]

_OUTPUTS = ("codes", "rgb_linear", "rgb_encoded")


@dataclass(frozen=True)
class ConversionPlan:
    """What to apply to each block: ``function(block, **keywords)`` -> (..., 3) of ``dtype``.

    Attributes
    ----------
    quantity : str
        "XYZ100" (or "XYZ" for lights), "CIELAB", or "rgb codes" / "rgb_linear" / "rgb_encoded".
    function : callable
        One of :mod:`spectrocolor.images.blocks`.
    keywords : dict
        Its other arguments (weights, white, options).
    dtype : numpy dtype
        Output dtype.
    white_XYZ : ndarray or None
        The white used (CIELAB reference, source white of the adaptation).
    """

    quantity: str
    function: object
    keywords: dict
    dtype: np.dtype
    white_XYZ: np.ndarray | None


def plan_conversion(
    quantity: str,
    wavelengths_nm,
    *,
    illuminant=None,
    observer=DEFAULT_OBSERVER,
    method: str = "sum",
    scale: float = 1.0,
    white_XYZ=None,
    space="sRGB",
    gamut: str = DEFAULT_GAMUT,
    exposure: float = 1.0,
    adaptation: str | None = "bradford",
    bit_depth: int = 8,
    output: str = "codes",
) -> ConversionPlan:
    """Precompute the per-block work of a conversion (weights, white, render options).

    Parameters are those of :func:`cube_to_xyz`, :func:`cube_to_lab` and :func:`cube_to_rgb`;
    ``quantity`` is "xyz", "lab" or "rgb".

    Parameters
    ----------
    quantity : {"xyz", "lab", "rgb"}
        What to compute.
    wavelengths_nm : array_like, shape (K,)
        Band wavelengths, nm.
    illuminant : str or Spectrum, keyword-only, optional
        As for :func:`cube_to_xyz` (``None``: the values are lights).
    observer : str, keyword-only, default DEFAULT_OBSERVER
        As for :func:`cube_to_xyz`.
    method : str, keyword-only, default "sum"
        As for :func:`cube_to_xyz`.
    scale : float, keyword-only, default 1.0
        As for :func:`cube_to_xyz`.
    white_XYZ : array_like, shape (3,), keyword-only, optional
        As for :func:`cube_to_lab`.
    space : str or RGBSpace, keyword-only, default "sRGB"
        As for :func:`cube_to_rgb`.
    gamut : str, keyword-only, default DEFAULT_GAMUT
        As for :func:`cube_to_rgb`.
    exposure : float, keyword-only, default 1.0
        As for :func:`cube_to_rgb`.
    adaptation : str or None, keyword-only, default "bradford"
        As for :func:`cube_to_rgb`.
    bit_depth : int, keyword-only, default 8
        As for :func:`cube_to_rgb`.
    output : str, keyword-only, default "codes"
        As for :func:`cube_to_rgb`.

    Returns
    -------
    ConversionPlan
        The block function, its keywords, the output dtype and the white used.

    Raises
    ------
    ColorimetryError
        For an unknown quantity or output, a scale or exposure that is not positive, a bit
        depth other than 8 or 16 for codes, CIELAB of lights without ``white_XYZ``, and as
        :func:`spectrocolor.weights`.

    Examples
    --------
    >>> import numpy as np
    >>> plan = plan_conversion("lab", np.arange(400, 701, 10), illuminant="D65")
    >>> plan.quantity, plan.dtype.name, plan.white_XYZ.round(3).tolist()
    ('CIELAB', 'float64', [94.94, 100.0, 108.709])
    """
    import spectrocolor as sc

    if quantity not in ("xyz", "lab", "rgb"):
        raise ColorimetryError(f"quantity must be 'xyz', 'lab' or 'rgb'; got {quantity!r}")
    scale = float(scale)
    if not np.isfinite(scale) or scale <= 0:
        raise ColorimetryError(f"scale must be a positive number; got {scale!r}")
    weights = np.asarray(
        sc.weights(wavelengths_nm, observer=observer, illuminant=illuminant, method=method),
        dtype=np.float64,
    )
    scaled = weights * scale if scale != 1.0 else weights.copy()
    scaled.setflags(write=False)
    perfect_white = weights.sum(axis=0) if illuminant is not None else None
    name = "XYZ100" if illuminant is not None else "XYZ"
    if quantity == "xyz":
        return ConversionPlan(name, blocks.xyz_block, {"weights": scaled}, np.dtype(np.float64),
                              perfect_white)
    if quantity == "lab":
        if white_XYZ is None:
            if perfect_white is None:
                raise ColorimetryError(
                    "white_XYZ is required for CIELAB of lights (illuminant=None); give the "
                    "reference white's XYZ on the same scale"
                )
            white_XYZ = perfect_white
        white = np.asarray(white_XYZ, dtype=np.float64)
        return ConversionPlan("CIELAB", blocks.lab_block,
                              {"weights": scaled, "white_XYZ": white},
                              np.dtype(np.float64), white)
    if output not in _OUTPUTS:
        raise ColorimetryError(f"output must be one of {_OUTPUTS}; got {output!r}")
    if bit_depth not in (8, 16) and output == "codes":
        raise ColorimetryError(f"bit_depth must be 8 or 16 for image codes; got {bit_depth!r}")
    exposure = float(exposure)
    if not np.isfinite(exposure) or exposure <= 0:
        raise ColorimetryError(f"exposure must be a positive number; got {exposure!r}")
    adapt_from = perfect_white if adaptation is not None else None
    options = {
        "adapt_from": adapt_from,
        "adapt_method": adaptation,
        "exposure": exposure,
        "space": space,
        "gamut": gamut,
        "bit_depth": bit_depth,
        "output": output,
    }
    if output == "codes":
        dtype = np.dtype(np.uint8 if bit_depth == 8 else np.uint16)
        label = f"rgb codes ({bit_depth}-bit)"
    else:
        dtype, label = np.dtype(np.float64), output
    return ConversionPlan(label, blocks.rgb_block,
                          {"weights": scaled, "options": options}, dtype, adapt_from)


def _values_and_wavelengths(cube, wavelengths_nm):
    if isinstance(cube, SpectralCube):
        if wavelengths_nm is not None:
            raise SpectrumError("wavelengths_nm is taken from the SpectralCube; do not pass it")
        return cube.values, cube.wavelengths_nm
    if wavelengths_nm is None:
        raise SpectrumError(
            "wavelengths_nm is required when the cube is an array (or pass a SpectralCube)"
        )
    if not hasattr(cube, "shape") or not hasattr(cube, "__getitem__"):
        cube = np.asarray(cube)
    wavelengths = np.asarray(wavelengths_nm, dtype=np.float64)
    if len(cube.shape) < 2 or cube.shape[-1] != wavelengths.size:
        raise SpectrumError(
            f"cube must have shape (..., K) with K = {wavelengths.size} bands (one per "
            f"wavelength); got shape {tuple(cube.shape)}"
        )
    return cube, wavelengths


def run_blocks(values, plan: ConversionPlan, *, rows_per_block=None, max_block_mib=64.0,
               out=None, progress=False) -> np.ndarray:
    """Apply ``plan`` to ``values`` (N, ..., K) in blocks along the first axis.

    Parameters
    ----------
    values : ndarray, MappedArray, np.memmap or array-like with ``shape`` and slicing
        The spectra; only one block is in memory at a time.
    plan : ConversionPlan
    rows_per_block : int, optional
        Rows per block; default: as many as fit in ``max_block_mib`` MiB of float64 spectra.
    max_block_mib : float
        Memory budget of one block (float64 spectra), in MiB.
    out : ndarray or np.memmap, shape (N, ..., 3), optional
        Where to write (e.g. a ``tifffile.memmap`` or ``np.memmap`` for outputs larger than
        memory); a new array by default.
    progress : bool
        Show a progress bar over rows (tqdm) on standard error.

    Returns
    -------
    ndarray, shape (N, ..., 3)
        The converted values, of ``plan.dtype`` (``out`` itself when given).

    Raises
    ------
    SpectrumError
        For ``rows_per_block`` below 1 or an ``out`` of the wrong shape.

    Examples
    --------
    >>> import numpy as np
    >>> plan = plan_conversion("lab", np.arange(400, 701, 10), illuminant="D65")
    >>> lab = run_blocks(np.full((4, 2, 31), 0.5), plan, rows_per_block=1)
    >>> lab.shape, lab[0, 0].round(3).tolist()
    ((4, 2, 3), [76.069, 0.0, 0.0])
    """
    shape = tuple(values.shape)
    n_rows = shape[0]
    per_row = int(np.prod(shape[1:], dtype=np.int64)) * 8
    if rows_per_block is None:
        rows_per_block = max(1, int(max_block_mib * 2**20) // max(per_row, 1))
    rows_per_block = int(rows_per_block)
    if rows_per_block < 1:
        raise SpectrumError(f"rows_per_block must be at least 1; got {rows_per_block}")
    out_shape = (*shape[:-1], 3)
    if out is None:
        out = np.empty(out_shape, dtype=plan.dtype)
    elif tuple(out.shape) != out_shape:
        raise SpectrumError(f"out must have shape {out_shape}; got {tuple(out.shape)}")
    bar = None
    if progress:
        from tqdm import tqdm

        bar = tqdm(total=n_rows, unit="rows", desc=plan.quantity, leave=False)
    try:
        for start in range(0, n_rows, rows_per_block):
            stop = min(start + rows_per_block, n_rows)
            out[start:stop] = plan.function(values[start:stop], **plan.keywords)
            if bar is not None:
                bar.update(stop - start)
    finally:
        if bar is not None:
            bar.close()
    return out


def cube_to_xyz(cube, wavelengths_nm=None, *, illuminant=None, observer=DEFAULT_OBSERVER,
                method: str = "sum", scale: float = 1.0, rows_per_block=None,
                max_block_mib: float = 64.0, out=None, progress: bool = False) -> np.ndarray:
    """CIE XYZ of every pixel of a spectral cube, converted in bounded-memory row blocks.

    Parameters
    ----------
    cube : SpectralCube or array-like, shape (H, W, K) (or any (N, ..., K))
        The spectra. A :class:`SpectralCube` brings its wavelengths; an array needs
        ``wavelengths_nm``. Memory-mapped or :class:`MappedArray` values are read block by
        block.
    wavelengths_nm : array_like, shape (K,), optional
        Band wavelengths in nm (arrays only).
    illuminant : str or Spectrum, optional
        With an illuminant, the values are reflectances (0-1 after ``scale``) and the result is
        XYZ100 (the perfect white has Y = 100). Without, the values are a light's spectral
        radiance (or any radiometric quantity) and XYZ = sum of value x cmf x dλ.
    observer : str, keyword-only, default DEFAULT_OBSERVER
        "1931", "1964", "2015-2", "2015-10" and the aliases of :func:`spectrocolor.observer`.
    method : str, keyword-only, default "sum"
        "sum" or "1nm", as for :func:`spectrocolor.weights`.
    scale : float, keyword-only, default 1.0
        Factor from the stored values to reflectance (e.g. 1/255 for 8-bit codes, 1/10000 for
        an ENVI reflectance scale factor of 10000). Applied exactly, folded into the weights.
    rows_per_block : int, keyword-only, optional
        Rows (first-axis entries) per block; default as many as fit in ``max_block_mib``.
    max_block_mib : float, keyword-only, default 64.0
        Memory budget of one block of float64 spectra, MiB.
    out : numpy.ndarray or numpy.memmap, shape (H, W, 3), keyword-only, optional
        Where to write (e.g. a memory map for outputs larger than memory); default a new array.
    progress : bool, keyword-only, default False
        Show a tqdm progress bar over rows on standard error.

    Returns
    -------
    ndarray, shape (H, W, 3), float64
        XYZ100 with an illuminant; XYZ in the values' radiometric scale without.

    Raises
    ------
    SpectrumError
        For a cube that is not (..., K) numbers, missing or mismatched wavelengths, or an
        ``out`` of the wrong shape.
    ColorimetryError
        As :func:`spectrocolor.weights` (unknown observer, illuminant or method, a grid outside
        the observer).

    References
    ----------
    CIE 015:2018 §7.1 (tristimulus values), as :func:`spectrocolor.tristimulus`.

    Examples
    --------
    >>> import numpy as np
    >>> grey = np.full((2, 3, 31), 0.5)
    >>> float(cube_to_xyz(grey, np.arange(400, 701, 10), illuminant="D65")[0, 0, 1].round(6))
    50.0
    >>> codes = np.full((2, 2, 31), 128, dtype=np.uint8)  # reflectance stored as 8-bit codes
    >>> cube_to_xyz(codes, np.arange(400, 701, 10), illuminant="D65", scale=1 / 255,
    ...             rows_per_block=1)[0, 0].round(3).tolist()
    [47.656, 50.196, 54.568]
    """
    values, wavelengths = _values_and_wavelengths(cube, wavelengths_nm)
    plan = plan_conversion("xyz", wavelengths, illuminant=illuminant, observer=observer,
                           method=method, scale=scale)
    return run_blocks(values, plan, rows_per_block=rows_per_block, max_block_mib=max_block_mib,
                      out=out, progress=progress)


def cube_to_lab(cube, wavelengths_nm=None, *, illuminant=None, observer=DEFAULT_OBSERVER,
                method: str = "sum", scale: float = 1.0, white_XYZ=None, rows_per_block=None,
                max_block_mib: float = 64.0, out=None, progress: bool = False) -> np.ndarray:
    """CIELAB (L*, a*, b*) of every pixel, in bounded-memory row blocks.

    The reference white is, by default, the perfect reflector under ``illuminant`` on the
    cube's own wavelength grid (the column sums of the weights, Y = 100), so a reflectance of 1
    gives L* = 100, a* = b* = 0 exactly. For lights (no illuminant) give ``white_XYZ``.
    Other parameters as for :func:`cube_to_xyz`.

    Parameters
    ----------
    cube : SpectralCube or array_like, shape (H, W, K)
        The spectra, as for :func:`cube_to_xyz`.
    wavelengths_nm : array_like, shape (K,), optional
        Band wavelengths in nm (arrays only).
    illuminant : str or Spectrum, keyword-only, optional
        The light for reflectances (the result is relative to its perfect reflector).
    observer : str, keyword-only, default DEFAULT_OBSERVER
        Observer name or alias.
    method : str, keyword-only, default "sum"
        Summation method, as for :func:`spectrocolor.weights`.
    scale : float, keyword-only, default 1.0
        Factor from the stored values to reflectance (0–1).
    white_XYZ : array_like, shape (3,), keyword-only, optional
        The reference white on the XYZ scale of the result (required for lights).
    rows_per_block : int, keyword-only, optional
        Rows (first-axis entries) per block; default as many as fit in ``max_block_mib``.
    max_block_mib : float, keyword-only, default 64.0
        Memory budget of one block of float64 spectra, MiB.
    out : numpy.ndarray or numpy.memmap, shape (H, W, 3), keyword-only, optional
        Where to write (e.g. a memory map for outputs larger than memory); default a new array.
    progress : bool, keyword-only, default False
        Show a tqdm progress bar over rows on standard error.

    Returns
    -------
    ndarray, shape (H, W, 3), float64
        L*, a*, b* (CIE 015:2018, section 8.2.1, via :func:`spectrocolor.lab`).

    Raises
    ------
    SpectrumError
        As :func:`cube_to_xyz`.
    ColorimetryError
        As :func:`cube_to_xyz`, and for lights without ``white_XYZ``.

    References
    ----------
    CIE 015:2018, section 8.2.1 (CIELAB).

    Examples
    --------
    >>> import numpy as np
    >>> grey = np.full((2, 3, 31), 0.5)
    >>> cube_to_lab(grey, np.arange(400, 701, 10), illuminant="D65")[0, 0].round(3).tolist()
    [76.069, 0.0, 0.0]
    """
    values, wavelengths = _values_and_wavelengths(cube, wavelengths_nm)
    plan = plan_conversion("lab", wavelengths, illuminant=illuminant, observer=observer,
                           method=method, scale=scale, white_XYZ=white_XYZ)
    return run_blocks(values, plan, rows_per_block=rows_per_block, max_block_mib=max_block_mib,
                      out=out, progress=progress)


def cube_to_rgb(cube, wavelengths_nm=None, *, illuminant=None, observer=DEFAULT_OBSERVER,
                method: str = "sum", scale: float = 1.0, space="sRGB", gamut: str = DEFAULT_GAMUT,
                exposure: float = 1.0, adaptation: str | None = "bradford", bit_depth: int = 8,
                output: str = "codes", rows_per_block=None, max_block_mib: float = 64.0,
                out=None, progress: bool = False) -> np.ndarray:
    """Display RGB of every pixel, in bounded-memory row blocks.

    Each block: XYZ (as :func:`cube_to_xyz`), then -- for reflectances under an illuminant and
    ``adaptation`` not None -- chromatic adaptation from the illuminant's white to the display
    white (:func:`spectrocolor.adapt`), then XYZ x ``exposure``, then
    :func:`spectrocolor.render` with ``normalise="none"`` (Y = 100 is the display's white at
    full drive) and the given gamut strategy.

    Parameters
    ----------
    cube : SpectralCube or array_like, shape (H, W, K)
        The spectra, as for :func:`cube_to_xyz`.
    wavelengths_nm : array_like, shape (K,), optional
        Band wavelengths in nm (arrays only).
    illuminant : str or Spectrum, keyword-only, optional
        The light for reflectances; without one the values are lights.
    observer : str, keyword-only, default DEFAULT_OBSERVER
        Observer name or alias.
    method : str, keyword-only, default "sum"
        Summation method, as for :func:`spectrocolor.weights`.
    scale : float, keyword-only, default 1.0
        Factor from the stored values to reflectance (0–1).
    space : str or RGBSpace, keyword-only, default "sRGB"
        Display space, e.g. "sRGB", "Display P3".
    gamut : str, keyword-only, default DEFAULT_GAMUT
        "desaturate" (the default), "clip", "flag" or "preserve-luminance" (see
        :func:`spectrocolor.render`).
        One fixed exposure and per-pixel strategies keep blocks independent, so there are no
        seams; per-image normalisations are not offered here (choose ``exposure``).
    exposure : float, keyword-only, default 1.0
        Multiplier on XYZ before rendering (2.0 = one stop brighter).
    adaptation : str or None, keyword-only, default "bradford"
        "bradford" (default), "von kries", "cat02", "cat16", or None to render the colours as
        seen without adaptation. Lights (no illuminant) are never adapted.
    bit_depth : int, keyword-only, default 8
        8 or 16 for ``output="codes"``.
    output : str, keyword-only, default "codes"
        "codes" (uint8/uint16, ready for PNG), "rgb_linear" or "rgb_encoded" (float64).
    rows_per_block : int, keyword-only, optional
        Rows (first-axis entries) per block; default as many as fit in ``max_block_mib``.
    max_block_mib : float, keyword-only, default 64.0
        Memory budget of one block of float64 spectra, MiB.
    out : numpy.ndarray or numpy.memmap, shape (H, W, 3), keyword-only, optional
        Where to write (e.g. a memory map for outputs larger than memory); default a new array.
    progress : bool, keyword-only, default False
        Show a tqdm progress bar over rows on standard error.

    Returns
    -------
    ndarray, shape (H, W, 3)
        uint8/uint16 codes, or float64 linear or encoded RGB (0–1), as ``output`` says.

    Raises
    ------
    SpectrumError
        As :func:`cube_to_xyz`.
    ColorimetryError
        For an unknown space, gamut strategy, adaptation or output, a bit depth other than 8
        or 16, and as :func:`cube_to_xyz`.

    Examples
    --------
    >>> import numpy as np
    >>> grey = np.full((2, 3, 31), 0.5)
    >>> rgb8 = cube_to_rgb(grey, np.arange(400, 701, 10), illuminant="D65")
    >>> rgb8.dtype.name, rgb8[0, 0].tolist()
    ('uint8', [188, 188, 188])
    """
    values, wavelengths = _values_and_wavelengths(cube, wavelengths_nm)
    plan = plan_conversion("rgb", wavelengths, illuminant=illuminant, observer=observer,
                           method=method, scale=scale, space=space, gamut=gamut,
                           exposure=exposure, adaptation=adaptation, bit_depth=bit_depth,
                           output=output)
    return run_blocks(values, plan, rows_per_block=rows_per_block, max_block_mib=max_block_mib,
                      out=out, progress=progress)
