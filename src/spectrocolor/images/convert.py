"""Convert spectral cubes to XYZ, CIELAB or display RGB, block by block.

A cube (H, W, K) is processed in blocks of whole rows, so memory holds one block of spectra
(``max_block_mib``) plus the output, whatever the cube's size: a cube that lives on disk
(:class:`~spectrocolor.images.MappedArray` from ENVI/.npy/TIFF, or an ``np.memmap``) larger
than memory converts, and the output may itself be a memmap (``out=``). Every block goes
through the same functions (:mod:`spectrocolor.images.blocks`) that the xarray/dask accessor
maps over chunks, so all paths give the same numbers.

Why this file is long: the conversion plan and the block loop it drives belong together: the plan's
memory sizes are the loop's block sizes, and the output writers follow the plan's choice of format.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from ..display.gamut import DEFAULT_GAMUT
from ..errors import ColorimetryError, SpectrumError
from ..observers import DEFAULT_OBSERVER
from . import blocks
from .cube import SpectralCube

__all__ = ["cube_to_xyz", "cube_to_lab", "cube_to_rgb", "ConversionPlan", "plan_conversion", "write_converted"]

_OUTPUTS = ("codes", "rgb_linear", "rgb_encoded")


@dataclass(frozen=True)
class ConversionPlan:
    """What to apply to each block: ``function(block, **keywords)`` -> (..., 3) of ``dtype``.

    Attributes
    ----------
    quantity : str
        "XYZ100" (or "XYZ" for lights), "CIELAB", or "rgb codes" / "rgb_linear" / "rgb_encoded".
    function : callable
        One of ``spectrocolor.images.blocks``.
    keywords : dict
        Its other arguments (weights, white, options).
    dtype : numpy dtype
        Output dtype.
    white_XYZ : ndarray or None
        The white used (CIELAB reference, source white of the adaptation).
    channels : int
        Values per pixel of the result: 3, or 4 for RGB with an alpha channel
        (``masked="transparent"``).
    """

    quantity: str
    function: Callable[..., Any]
    keywords: dict
    dtype: np.dtype
    white_XYZ: np.ndarray | None
    channels: int = 3


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
    masked=None,
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
    masked : None, "transparent" or 3 numbers, keyword-only, default None
        As for :func:`cube_to_rgb` ("rgb" only: XYZ and CIELAB keep NaN for masked pixels).

    Returns
    -------
    ConversionPlan
        The block function, its keywords, the output dtype and the white used.

    Raises
    ------
    ColorimetryError
        For an unknown quantity or output, a scale or exposure that is not positive, a bit
        depth other than 8 or 16 for codes, CIELAB of lights without ``white_XYZ``, a
        ``masked`` that is not None, "transparent" or a colour of the output's kind, and as
        :func:`spectrocolor.weights`.

    Examples
    --------
    >>> import numpy as np
    >>> plan = plan_conversion("lab", np.arange(400, 701, 10), illuminant="D65")
    >>> plan.quantity, plan.dtype.name, plan.white_XYZ.round(3).tolist()
    ('CIELAB', 'float64', [94.94, 100.0, 108.709])
    """
    from .. import colorimetry

    if quantity not in ("xyz", "lab", "rgb"):
        raise ColorimetryError(f"quantity must be 'xyz', 'lab' or 'rgb'; got {quantity!r}")
    if masked is not None and quantity != "rgb":
        raise ColorimetryError(
            f"masked applies to quantity 'rgb'; {quantity} keeps NaN for masked pixels (got masked={masked!r:.40})"
        )
    scale = float(scale)
    if not np.isfinite(scale) or scale <= 0:
        raise ColorimetryError(f"scale must be a positive number; got {scale!r}")
    weights = np.asarray(
        colorimetry.weights(wavelengths_nm, observer=observer, illuminant=illuminant, method=method),
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
    masked = masked_fill(masked, output, bit_depth)
    adapt_from = perfect_white if adaptation is not None else None
    options = {
        "adapt_from": adapt_from,
        "adapt_method": adaptation,
        "exposure": exposure,
        "space": space,
        "gamut": gamut,
        "bit_depth": bit_depth,
        "output": output,
        "masked": masked,
    }
    if output == "codes":
        dtype = np.dtype(np.uint8 if bit_depth == 8 else np.uint16)
        label = f"rgb codes ({bit_depth}-bit)"
    else:
        dtype, label = np.dtype(np.float64), output
    channels = 4 if isinstance(masked, str) else 3
    if channels == 4:
        label += " with alpha (0 where masked)"
    return ConversionPlan(label, blocks.rgb_block,
                          {"weights": scaled, "options": options}, dtype, adapt_from, channels)


def masked_fill(masked, output: str = "codes", bit_depth: int = 8):
    """Check the ``masked`` option of an RGB conversion: what masked pixels become.

    Parameters
    ----------
    masked : None, "transparent", "#RRGGBB" or 3 numbers
        ``None``: black codes, or NaN floats. ``"transparent"``: an alpha channel is added, 0
        on masked pixels (whose colour is 0) and full (255, 65535 or 1.0) elsewhere. A colour:
        ``"#RRGGBB"`` (scaled to 16-bit codes by 257, to floats by 1/255) or three values in the
        output's own units (codes from 0 to 255 or 65535, or floats).
    output : str, default "codes"
        "codes", "rgb_linear" or "rgb_encoded".
    bit_depth : int, default 8
        8 or 16 (codes).

    Returns
    -------
    None, "transparent" or numpy.ndarray, shape (3,)
        The checked option; a colour in the output's dtype.

    Raises
    ------
    ColorimetryError
        Anything else, e.g. codes outside 0 to 255, a fractional code, NaN.

    Examples
    --------
    >>> masked_fill("#ff8000").tolist(), masked_fill((0, 0, 65535), bit_depth=16).tolist()
    ([255, 128, 0], [0, 0, 65535])
    >>> masked_fill("#ff8000", output="rgb_encoded").round(4).tolist()
    [1.0, 0.502, 0.0]
    """
    if masked is None or (isinstance(masked, str) and masked == "transparent"):
        return masked
    codes = output == "codes"
    top = 65535 if codes and bit_depth == 16 else 255
    kind = f"whole codes from 0 to {top}" if codes else "finite floats"
    accepted = f"None, 'transparent', '#RRGGBB' or three {kind}"
    if isinstance(masked, str):
        text = masked.strip()
        if len(text) != 7 or text[0] != "#" or not all(c in "0123456789abcdefABCDEF" for c in text[1:]):
            raise ColorimetryError(f"masked: expected {accepted}; got {masked!r:.40}")
        rgb8 = np.array([int(text[i:i + 2], 16) for i in (1, 3, 5)])
        if not codes:
            return rgb8 / 255.0
        return (rgb8 * (257 if bit_depth == 16 else 1)).astype(np.uint16 if bit_depth == 16 else np.uint8)
    try:
        colour = np.asarray(masked, dtype=np.float64)
    except (TypeError, ValueError):
        colour = None
    if colour is None or colour.shape != (3,) or not np.isfinite(colour).all():
        raise ColorimetryError(f"masked: expected {accepted}; got {masked!r:.40}")
    if not codes:
        return colour
    if np.any(colour != np.round(colour)) or colour.min() < 0 or colour.max() > top:
        raise ColorimetryError(f"masked: expected {accepted}; got {masked!r:.40}")
    return colour.astype(np.uint16 if bit_depth == 16 else np.uint8)


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


def run_blocks(values, plan: ConversionPlan, *, rows_per_block=None, max_block_mib=None,
               out=None, progress=False) -> np.ndarray:
    """Apply ``plan`` to ``values`` (N, ..., K) in blocks along the first axis.

    Parameters
    ----------
    values : ndarray, MappedArray, np.memmap or array-like with ``shape`` and slicing
        The spectra; only one block is in memory at a time.
    plan : ConversionPlan
    rows_per_block : int, optional
        Rows per block; default: as many as fit in ``max_block_mib`` MiB of float64 spectra.
    max_block_mib : float, optional
        Memory of one block of float64 spectra, MiB; see :term:`block`.
    out : ndarray or np.memmap, shape (N, ..., plan.channels), optional
        Where to write (e.g. a ``tifffile.memmap`` or ``np.memmap`` for outputs larger than
        memory); a new array by default.
    progress : bool
        Show a progress bar over rows (tqdm) on standard error.

    Returns
    -------
    ndarray, shape (N, ..., plan.channels)
        The converted values, of ``plan.dtype`` (``out`` itself when given).

    Raises
    ------
    SpectrumError
        For ``rows_per_block`` below 1 or an ``out`` of the wrong shape.
    spectrocolor.errors.BudgetError
        When the result (without ``out``) or one block exceeds the memory budget.

    Examples
    --------
    >>> import numpy as np
    >>> plan = plan_conversion("lab", np.arange(400, 701, 10), illuminant="D65")
    >>> lab = run_blocks(np.full((4, 2, 31), 0.5), plan, rows_per_block=1)
    >>> lab.shape, lab[0, 0].round(3).tolist()
    ((4, 2, 3), [76.069, 0.0, 0.0])
    """
    out_shape = (*tuple(values.shape)[:-1], plan.channels)
    if out is None:
        from ..budget import check_bytes

        check_bytes(math.prod(out_shape) * plan.dtype.itemsize,
                    f"the result, shape {out_shape} of {plan.dtype.name} (give out= a memory map, or "
                    "write the image with write_converted, which streams it)")
        out = np.empty(out_shape, dtype=plan.dtype)
    elif tuple(out.shape) != out_shape:
        raise SpectrumError(f"out must have shape {out_shape}; got {tuple(out.shape)}")
    for start, block in iter_blocks(values, plan, rows_per_block=rows_per_block,
                                    max_block_mib=max_block_mib, progress=progress):
        out[start:start + len(block)] = block
    return out


def _rows_per_block(shape: tuple[int, ...], rows_per_block, max_block_mib: float | None) -> int:
    from ..budget import block_bytes, check_bytes

    per_row = math.prod(int(n) for n in shape[1:]) * 8
    if rows_per_block is None:
        block = block_bytes() if max_block_mib is None else int(max_block_mib * 2**20)
        rows_per_block = max(1, block // max(per_row, 1))
    rows_per_block = int(rows_per_block)
    if rows_per_block < 1:
        raise SpectrumError(f"rows_per_block must be at least 1; got {rows_per_block}")
    # what one block becomes in float64 (its working copies are a few times more)
    check_bytes(min(rows_per_block, shape[0]) * per_row,
                f"a block of {min(rows_per_block, shape[0])} row(s) of {shape[1:]} spectra as float64")
    return rows_per_block


def iter_blocks(values, plan: ConversionPlan, *, rows_per_block=None, max_block_mib=None,
                progress=False) -> Iterator[tuple[int, np.ndarray]]:
    """Apply ``plan`` to ``values`` (N, ..., K) block by block, yielding each result as made.

    Parameters
    ----------
    values : ndarray, MappedArray, np.memmap or array-like with ``shape`` and slicing
        The spectra; only one block is read at a time.
    plan : ConversionPlan
        From :func:`plan_conversion`.
    rows_per_block : int, optional
        Rows per block; default: as many as fit in ``max_block_mib`` MiB of float64 spectra.
    max_block_mib : float, optional
        Memory of one block of float64 spectra, MiB; see :term:`block`.
    progress : bool
        Show a progress bar over rows (tqdm) on standard error.

    Yields
    ------
    tuple
        ``(start, block)``: the first row of the block and its result, shape
        ``(rows, ..., plan.channels)`` of ``plan.dtype``; every block has ``rows_per_block``
        rows but the last.

    Raises
    ------
    SpectrumError
        For ``rows_per_block`` below 1.

    Examples
    --------
    >>> import numpy as np
    >>> plan = plan_conversion("xyz", np.arange(400, 701, 10), illuminant="D65")
    >>> [(start, block.shape) for start, block in iter_blocks(np.ones((3, 2, 31)), plan, rows_per_block=2)]
    [(0, (2, 2, 3)), (2, (1, 2, 3))]
    """
    n_rows = tuple(values.shape)[0]
    rows_per_block = _rows_per_block(tuple(values.shape), rows_per_block, max_block_mib)
    bar = None
    if progress:
        from tqdm import tqdm

        bar = tqdm(total=n_rows, unit="rows", desc=plan.quantity, leave=False)
    try:
        for start in range(0, n_rows, rows_per_block):
            stop = min(start + rows_per_block, n_rows)
            yield start, np.asarray(plan.function(values[start:stop], **plan.keywords), dtype=plan.dtype)
            if bar is not None:
                bar.update(stop - start)
    finally:
        if bar is not None:
            bar.close()


def write_converted(path, values, plan: ConversionPlan, *, rows_per_block=None,
                    max_block_mib: float | None = None, metadata: dict | None = None,
                    progress: bool = False) -> Path:
    """Convert a cube block by block straight into a PNG or float TIFF file.

    Each block is computed and written before the next is read, so memory holds one block of
    spectra and its result, never the whole image (neither floats nor codes): a PNG is
    compressed row block by row block (:func:`spectrocolor.imagefiles.write_png_blocks`), a
    TIFF gets one strip per block (:func:`spectrocolor.imagefiles.write_tiff_blocks`). The
    file is written beside ``path`` and renamed over it once read back, like every writer.

    Parameters
    ----------
    path : str or os.PathLike
        ``.png`` (a plan with ``output="codes"``: 8- or 16-bit RGB, RGBA with
        ``masked="transparent"``) or ``.tif``/``.tiff`` (floats, written as float32).
    values : ndarray, MappedArray, np.memmap or array-like, shape (H, W, K)
        The spectra, e.g. ``read_cube(...).values``.
    plan : ConversionPlan
        From :func:`plan_conversion`.
    rows_per_block : int, keyword-only, optional
        Rows per block; default as many as fit in ``max_block_mib``.
    max_block_mib : float, keyword-only, optional
        Memory of one block of float64 spectra, MiB; see :term:`block`.
    metadata : dict, keyword-only, optional
        TIFF only: JSON-serialisable facts stored in the image description.
    progress : bool, keyword-only, default False
        Show a tqdm progress bar over rows on standard error.

    Returns
    -------
    pathlib.Path
        ``path``, the whole converted image.

    Raises
    ------
    SpectrumError
        A suffix other than .png/.tif/.tiff, a PNG from a plan without integer codes (or a TIFF
        from one with codes), values
        that are not (H, W, K), metadata for a PNG.
    spectrocolor.safe_write.OutputError
        The converted image could not be written; a previous file at ``path`` is kept
        (:term:`atomic write`).

    Examples
    --------
    >>> import tempfile, pathlib
    >>> import numpy as np
    >>> from PIL import Image
    >>> plan = plan_conversion("rgb", np.arange(400, 701, 10), illuminant="D65")
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     path = write_converted(pathlib.Path(folder) / "grey.png", np.full((4, 5, 31), 0.5), plan,
    ...                            rows_per_block=3)
    ...     np.asarray(Image.open(path))[3, 4].tolist()
    [188, 188, 188]
    """
    from ..imagefiles import write_png_blocks, write_tiff_blocks

    path = Path(path)
    shape = tuple(values.shape)
    if len(shape) != 3 or 0 in shape:
        raise SpectrumError(f"values must have shape (H, W, K) with H, W, K >= 1; got {shape}")
    suffix = path.suffix.lower()
    if suffix not in (".png", ".tif", ".tiff"):
        raise SpectrumError(f"{path}: unknown image format {suffix!r}; accepted: .png (8/16-bit codes), "
                            ".tif/.tiff (float)")
    rows = _rows_per_block(shape, rows_per_block, max_block_mib)
    results = (block for _, block in iter_blocks(values, plan, rows_per_block=rows, progress=progress))
    height, width = shape[:2]
    if suffix == ".png":
        if plan.dtype.kind != "u":
            raise SpectrumError(f"PNG needs integer codes; the plan gives {plan.quantity} floats "
                                "(plan with output='codes', or write a .tif)")
        if metadata:
            raise SpectrumError("metadata is stored in TIFF files only; PNG gets none")
        return write_png_blocks(path, results, height, width, plan.channels, plan.dtype.itemsize * 8)
    if plan.dtype.kind != "f":
        raise SpectrumError(f"TIFF output is for floats; the plan gives {plan.quantity} (write codes to .png)")
    return write_tiff_blocks(path, results, (height, width, plan.channels), rows, metadata)


def cube_to_xyz(cube, wavelengths_nm=None, *, illuminant=None, observer=DEFAULT_OBSERVER,
                method: str = "sum", scale: float = 1.0, rows_per_block=None,
                max_block_mib: float | None = None, out=None, progress: bool = False) -> np.ndarray:
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
        With one, the values are reflectance factors (0–1 after ``scale``) and the result is XYZ100;
        without, they are a light's radiance (or any radiometric quantity) and XYZ = Σ value · cmf ·
        dλ; see :term:`illuminant`.
    observer : str, keyword-only, default DEFAULT_OBSERVER
        The observer of the result; see :term:`observer`.
    method : str, keyword-only, default "sum"
        "sum" or "1nm", as for :func:`spectrocolor.weights`.
    scale : float, keyword-only, default 1.0
        Factor from the stored values to reflectance (e.g. 1/255 for 8-bit codes, 1/10000 for
        an ENVI reflectance scale factor of 10000). Applied exactly, folded into the weights.
    rows_per_block : int, keyword-only, optional
        Rows of the cube per block (default: as many as fit); see :term:`block`.
    max_block_mib : float, keyword-only, optional
        Memory of one block of float64 spectra, MiB; see :term:`block`.
    out : numpy.ndarray or numpy.memmap, shape (H, W, 3), keyword-only, optional
        Where to write the XYZ (a memory map for results larger than memory); default a new array.
    progress : bool, keyword-only, default False
        Show a progress bar over the cube's rows.

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
                max_block_mib: float | None = None, out=None, progress: bool = False) -> np.ndarray:
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
        Rows per block; see :term:`block`.
    max_block_mib : float, keyword-only, optional
        Memory of one block of float64 spectra, MiB; see :term:`block`.
    out : numpy.ndarray or numpy.memmap, shape (H, W, 3), keyword-only, optional
        Where to write L*, a*, b*; default a new array; see :term:`block`.
    progress : bool, keyword-only, default False
        Show a tqdm progress bar on standard error.

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
                output: str = "codes", masked=None, rows_per_block=None, max_block_mib: float | None = None,
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
    masked : None, "transparent", "#RRGGBB" or 3 numbers, keyword-only, default None
        What masked pixels become (NaN or infinite values, e.g. where an ENVI header's data
        ignore value was): ``None`` black codes (0, 0, 0) or NaN floats; ``"transparent"`` adds
        an alpha channel (result (H, W, 4)): 0 on masked pixels, whose colour is 0, and 255,
        65535 or 1.0 elsewhere; or a colour (see :func:`masked_fill`).
    rows_per_block : int, keyword-only, optional
        The height of a block in rows (default: as many as fit); see :term:`block`.
    max_block_mib : float, keyword-only, optional
        Memory of one block of float64 spectra, MiB; see :term:`block`.
    out : numpy.ndarray or numpy.memmap, shape (H, W, 3), keyword-only, optional
        An array or memory map to write the RGB into (default a new one).
    progress : bool, keyword-only, default False
        Whether to show a progress bar over rows.

    Returns
    -------
    ndarray, shape (H, W, 3), or (H, W, 4) with ``masked="transparent"``
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
    >>> grey[0, 0] = np.nan  # a masked pixel
    >>> rgba8 = cube_to_rgb(grey, np.arange(400, 701, 10), illuminant="D65", masked="transparent")
    >>> rgba8[0, 0].tolist(), rgba8[0, 1].tolist()
    ([0, 0, 0, 0], [188, 188, 188, 255])
    """
    values, wavelengths = _values_and_wavelengths(cube, wavelengths_nm)
    plan = plan_conversion("rgb", wavelengths, illuminant=illuminant, observer=observer,
                           method=method, scale=scale, space=space, gamut=gamut,
                           exposure=exposure, adaptation=adaptation, bit_depth=bit_depth,
                           output=output, masked=masked)
    return run_blocks(values, plan, rows_per_block=rows_per_block, max_block_mib=max_block_mib,
                      out=out, progress=progress)
