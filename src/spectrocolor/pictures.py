"""Pictures without plotting: colour swatches, coloured strips and a wavelength tint palette.

Images are built as ``(H, W, 3)`` uint8 arrays (``rgb8``: already encoded display values, 0-255)
by :func:`swatch_image` and :func:`strip_image`, and written by :func:`save_image` as PNG
(Pillow, imported only when a PNG is written) or binary PPM (P6, written directly; seed 000
writes the ASCII variant P3 of the same format).

References
----------
D. Zawischa, How to calculate and render colours -- thin films as an example, Appendix A (the
PPM strip with ticks every 500 nm of path difference).
P. Sällström (1999), USIP Report 99-05, "Can you really display a pure spectrum?" (the palette
anchored at the unique hues).
Netpbm PPM format specification, https://netpbm.sourceforge.net/doc/ppm.html

:func:`write_image` writes every picture, swatch, strip, thickness map and converted cube (it
or :func:`save_image`); the files themselves are written by :mod:`spectrocolor.imagefiles`
(PNG 8-bit and 16-bit grey: Pillow; 16-bit RGB: ``imagecodecs``; float TIFF: tifffile, with a
JSON description holding the metadata you pass), atomically.

OpenEXR is not written: float TIFF carries the same data losslessly and every HDR tool reads it.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from . import imagefiles
from .errors import ColorimetryError, SpectrumError
from .safe_write import verify_size, write_bytes

__all__ = [
    "write_image",
    "TINT_HUE_ANCHORS",
    "wavelength_tint",
    "swatch_image",
    "strip_image",
    "save_image",
    "write_swatches",
    "write_strip",
]

#: (wavelength nm, HSV hue degrees) anchors of the illustrative spectrum palette. Seed 002 places
#: unique blue at 470 nm, the blue-green "as blue as green" at 500 nm, essentially green from 510
#: to 570 nm, unique yellow at 580 nm, orange "as yellow as red" at 600 nm, red from 620 nm.
TINT_HUE_ANCHORS = (
    (360.0, 275.0),
    (430.0, 260.0),
    (470.0, 240.0),
    (500.0, 180.0),
    (510.0, 135.0),
    (540.0, 120.0),
    (570.0, 95.0),
    (580.0, 60.0),
    (600.0, 30.0),
    (620.0, 0.0),
    (830.0, 0.0),
)


def _hsv_to_rgb(hue_deg: np.ndarray, saturation: np.ndarray, value: np.ndarray) -> np.ndarray:
    h = (np.asarray(hue_deg) % 360.0) / 60.0
    c = value * saturation
    x = c * (1 - np.abs(h % 2 - 1))
    zero = np.zeros_like(c)
    sector = np.floor(h).astype(int) % 6
    choices = [
        np.stack([c, x, zero], -1),
        np.stack([x, c, zero], -1),
        np.stack([zero, c, x], -1),
        np.stack([zero, x, c], -1),
        np.stack([x, zero, c], -1),
        np.stack([c, zero, x], -1),
    ]
    rgb = np.choose(sector[..., None], choices)
    return rgb + (value - c)[..., None]


def wavelength_tint(wavelengths_nm) -> np.ndarray:
    """Illustrative sRGB colour for each wavelength, for tinting spectrum bars (``rgb8``).

    A spectral light cannot be shown on a display (seed 002: "Certainly not!"); this palette
    shows its *hue*, with hues interpolated linearly between :data:`TINT_HUE_ANCHORS` (unique
    blue 470 nm, blue-green 500 nm, yellow 580 nm, orange 600 nm), full saturation, and a
    brightness that peaks at 555 nm and falls off roughly symmetrically,
    ``value = 0.3 + 0.7 exp(-((lambda - 555) / 106)**2)``, so that bars at the spectrum's ends stay
    visible. Not a colorimetric rendering: use :func:`spectrocolor.render` for that.

    Parameters
    ----------
    wavelengths_nm : array_like, shape (...)
        Wavelengths in nm, 360 to 830.

    Returns
    -------
    ndarray of uint8, shape (..., 3)
        8-bit sRGB codes (``rgb8``), illustrative only.

    Raises
    ------
    SpectrumError
        For non-numbers, NaN, or wavelengths outside 360–830 nm.

    References
    ----------
    Seed 002 (Sällström 1999): SPECTRA's tinted spectrum bars and "Certainly not!".

    Examples
    --------
    >>> wavelength_tint([470, 555, 620]).tolist()
    [[0, 0, 170], [53, 255, 0], [199, 0, 0]]
    """
    try:
        wl = np.asarray(wavelengths_nm, dtype=float)
    except (TypeError, ValueError):
        raise SpectrumError(f"wavelengths_nm: expected numbers in nm, got {wavelengths_nm!r:.60}") from None
    if not np.all(np.isfinite(wl)) or np.any((wl < 360) | (wl > 830)):
        raise SpectrumError(
            "wavelengths_nm must be finite and within 360-830 nm for wavelength_tint"
        )
    anchors = np.array(TINT_HUE_ANCHORS)
    hue = np.interp(wl, anchors[:, 0], anchors[:, 1])
    value = 0.3 + 0.7 * np.exp(-(((wl - 555.0) / 106.0) ** 2))
    rgb = _hsv_to_rgb(hue, np.ones_like(wl), value)
    return np.rint(rgb * 255).astype(np.uint8)


def _rgb8(rgb8, argument: str = "rgb8") -> np.ndarray:
    a = np.asarray(rgb8)
    if a.ndim != 2 or a.shape[1] != 3 or a.shape[0] == 0:
        raise ColorimetryError(f"{argument} must have shape (N, 3) with N >= 1, got {a.shape}")
    if not np.issubdtype(a.dtype, np.integer) or a.min() < 0 or a.max() > 255:
        raise ColorimetryError(f"{argument} must hold integers 0-255 (8-bit codes)")
    return a.astype(np.uint8)


def swatch_image(
    rgb8,
    size: int = 64,
    columns: int | None = None,
    gap: int = 4,
    background=(255, 255, 255),
    crossed=None,
) -> np.ndarray:
    """Square swatches on a background, row by row.

    Parameters
    ----------
    rgb8 : array_like of int, shape (N, 3)
        8-bit codes 0–255.
    size : int, default 64
        Swatch side in pixels.
    columns : int, optional
        Swatches per row (default: all in one row, at most 8).
    gap : int, default 4
        Pixels between swatches and around them.
    background : tuple of int, default (255, 255, 255)
        8-bit colour of the background.
    crossed : array_like of bool, shape (N,), optional
        Swatches to mark with a diagonal cross in the background colour -- e.g.
        ``~rendering.in_gamut`` to show SPECTRA's "cannot be reproduced".

    Returns
    -------
    ndarray (H, W, 3) uint8
        The picture.

    Raises
    ------
    ColorimetryError
        For codes that are not (N, 3) integers 0–255, or invalid sizes.

    Examples
    --------
    >>> image = swatch_image([[255, 0, 0], [0, 0, 255]], size=8, gap=2, crossed=[False, True])
    >>> image.shape, image[2, 2].tolist(), image[2, 12].tolist()  # the second swatch is crossed
    ((12, 22, 3), [255, 0, 0], [255, 255, 255])
    """
    colours = _rgb8(rgb8)
    if int(size) != size or size < 1 or int(gap) != gap or gap < 0:
        raise ColorimetryError("size must be a positive integer and gap a non-negative one")
    n = colours.shape[0]
    cols = min(n, 8) if columns is None else int(columns)
    if cols < 1:
        raise ColorimetryError(f"columns must be a positive integer, got {columns!r}")
    rows = -(-n // cols)
    bg = _rgb8([background], "background")[0]
    img = np.empty((gap + rows * (size + gap), gap + cols * (size + gap), 3), np.uint8)
    img[...] = bg
    marks = np.zeros(n, bool) if crossed is None else np.asarray(crossed, bool).reshape(n)
    diag = np.arange(size)
    for i in range(n):  # one slice assignment per swatch (N is small: swatches, not pixels)
        r, c = divmod(i, cols)
        y0, x0 = gap + r * (size + gap), gap + c * (size + gap)
        img[y0 : y0 + size, x0 : x0 + size] = colours[i]
        if marks[i]:
            img[y0 + diag, x0 + diag] = bg
            img[y0 + diag, x0 + size - 1 - diag] = bg
    return img


def strip_image(
    rgb8,
    height: int = 80,
    ticks=None,
    tick_height: int = 10,
    tick_rgb8=(255, 255, 255),
) -> np.ndarray:
    """A strip one pixel column per colour, optionally with a band of tick marks below.

    As in Zawischa's Fortran (seed 000): the colours fill the top ``height - tick_height`` rows;
    the bottom ``tick_height`` rows are black, with each tick three pixels wide (its column and
    one either side) in ``tick_rgb8``.

    Parameters
    ----------
    rgb8 : array_like of int, shape (N, 3)
        8-bit codes 0–255, one column each.
    height : int, default 80
        Picture height in pixels, tick band included.
    ticks : sequence of int, optional
        Column indices (0-based) of tick marks; None for no tick band.
    tick_height : int, default 10
        Height of the black tick band in pixels.
    tick_rgb8 : tuple of int, default (255, 255, 255)
        8-bit colour of the ticks.

    Returns
    -------
    ndarray (height, N, 3) uint8
        The picture.

    Raises
    ------
    ColorimetryError
        For malformed codes, a height not above the tick band, or ticks outside the strip.

    References
    ----------
    Seed 000 (Zawischa), Appendix A (the Fortran that draws the strip).

    Examples
    --------
    >>> strip = strip_image([[255, 0, 0]] * 5, height=10, ticks=[2], tick_height=3)
    >>> strip.shape, strip[0, 0].tolist(), strip[9, 2].tolist(), strip[9, 0].tolist()
    ((10, 5, 3), [255, 0, 0], [255, 255, 255], [0, 0, 0])
    """
    colours = _rgb8(rgb8)
    n = colours.shape[0]
    band = 0 if ticks is None else int(tick_height)
    if int(height) != height or height < 1 or not 0 <= band < height:
        raise ColorimetryError("height must be a positive integer larger than tick_height")
    img = np.empty((int(height), n, 3), np.uint8)
    img[: height - band] = colours[None]
    if band:
        idx = np.asarray(ticks, dtype=int).reshape(-1)
        if np.any((idx < 0) | (idx >= n)):
            raise ColorimetryError(f"ticks must be column indices in 0..{n - 1}")
        img[height - band :] = 0
        cols = np.clip(np.concatenate([idx - 1, idx, idx + 1]), 0, n - 1)
        img[height - band :, cols] = _rgb8([tick_rgb8], "tick_rgb8")[0]
    return img


def save_image(image, path) -> Path:
    """Write an ``(H, W, 3)`` uint8 image as PNG (Pillow) or binary PPM P6, by file extension.

    The file is written beside ``path``, read back and renamed over it
    (:func:`spectrocolor.safe_write.atomic_path`): a failed write leaves any previous file
    unchanged and raises :class:`spectrocolor.safe_write.OutputError`.

    Parameters
    ----------
    image : numpy.ndarray of uint8, shape (H, W, 3)
        8-bit codes.
    path : str or os.PathLike
        Output file ending in ``.png`` (needs Pillow) or ``.ppm``.

    Returns
    -------
    pathlib.Path
        ``path``, the encoded picture.

    Raises
    ------
    ColorimetryError
        For an image that is not (H, W, 3) uint8, or another extension.
    spectrocolor.safe_write.OutputError
        The picture could not be written, or its size on disk is not the encoded size; see
        :term:`atomic write`.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> import numpy as np
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     save_image(np.zeros((2, 3, 3), np.uint8), pathlib.Path(folder) / "black.ppm").name
    'black.ppm'
    """
    img = np.asarray(image)
    if img.ndim != 3 or img.shape[2] != 3 or img.dtype != np.uint8 or 0 in img.shape:
        raise ColorimetryError(
            f"image must be an (H, W, 3) uint8 array with H, W >= 1, got {img.shape} {img.dtype}"
        )
    path = Path(path)
    suffix = path.suffix.lower()
    height, width = img.shape[:2]
    if suffix == ".ppm":
        data = f"P6\n{width} {height}\n255\n".encode("ascii") + np.ascontiguousarray(img).tobytes()
        write_bytes(path, data, verify=lambda p: verify_size(p, len(data)))
    elif suffix == ".png":
        write_image(path, img)
    else:
        raise ColorimetryError(f"path must end in .png or .ppm, got {path.name!r}")
    return path


def write_swatches(rgb8, path, **options) -> Path:
    """:func:`swatch_image` written to ``path`` (.png or .ppm); options as for swatch_image.

    Parameters
    ----------
    rgb8 : array_like of int, shape (N, 3)
        8-bit codes 0–255, e.g. ``render(...).codes``.
    path : str or os.PathLike
        Output file; ``.png`` (needs Pillow) or ``.ppm`` (binary P6). Written atomically.
    **options : dict
        ``size``, ``columns``, ``gap``, ``background``, ``crossed``: see :func:`swatch_image`.

    Returns
    -------
    pathlib.Path
        ``path``, the swatches.

    Raises
    ------
    ColorimetryError
        For malformed codes or options, or another file extension.
    spectrocolor.safe_write.OutputError
        The swatch picture could not be written; see :term:`atomic write`.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     path = write_swatches([[255, 0, 0], [0, 128, 255]], pathlib.Path(folder) / "s.ppm", size=16)
    ...     path.read_bytes().split()[:3]  # binary PPM header: width 44, height 24 pixels
    [b'P6', b'44', b'24']
    """
    return save_image(swatch_image(rgb8, **options), path)


def write_strip(rgb8, path, **options) -> Path:
    """:func:`strip_image` written to ``path`` (.png or .ppm); options as for strip_image.

    Parameters
    ----------
    rgb8 : array_like of int, shape (N, 3)
        8-bit codes 0–255, one pixel column each (e.g. ``zawischa_strip().colours.rgb8``).
    path : str or os.PathLike
        Output file; ``.png`` (needs Pillow) or ``.ppm`` (binary P6). Written atomically.
    **options : dict
        ``height``, ``ticks``, ``tick_height``, ``tick_rgb8``: see :func:`strip_image`.

    Returns
    -------
    pathlib.Path
        ``path``, the strip.

    Raises
    ------
    ColorimetryError
        For malformed codes or options, or another file extension.
    spectrocolor.safe_write.OutputError
        The strip could not be written (:term:`atomic write`).

    References
    ----------
    Seed 000 (Zawischa): the strip with tick marks every 500 nm.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     path = write_strip([[255, 0, 0], [0, 128, 255], [0, 0, 0]], pathlib.Path(folder) / "s.ppm",
    ...                        height=20, ticks=[1], tick_height=5)
    ...     path.read_bytes().split()[:3]
    [b'P6', b'3', b'20']
    """
    return save_image(strip_image(rgb8, **options), path)


def write_image(path, image, *, metadata: dict | None = None) -> Path:
    """Write an image array to PNG (integer codes) or TIFF (floating point).

    Parameters
    ----------
    path : str or Path
        Output file; ``.png`` or ``.tif``/``.tiff``.
    image : array_like, shape (H, W, 3) or (H, W)
        For PNG: ``uint8`` codes (8-bit PNG) or ``uint16`` codes (16-bit PNG), e.g. the
        ``codes`` of :func:`spectrocolor.render`. For TIFF: float32 or float64 values, written
        as they are (no scaling, no clipping), e.g. XYZ100 or CIELAB.
    metadata : dict, keyword-only, optional
        TIFF only: JSON-serialisable facts stored in the image description.

    Returns
    -------
    Path
        The path written.

    Raises
    ------
    SpectrumError
        An unsupported suffix, shape or dtype (e.g. floats for PNG: quantise them first).
    spectrocolor.safe_write.OutputError
        The picture could not be written; see :term:`atomic write`.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> import numpy as np
    >>> from PIL import Image
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     path = write_image(pathlib.Path(folder) / "codes.png", np.zeros((2, 3, 3), np.uint8))
    ...     with Image.open(path) as picture:
    ...         print(picture.size)  # width, height
    (3, 2)
    """
    path = Path(path)
    array = np.asarray(image)
    if array.ndim not in (2, 3) or (array.ndim == 3 and array.shape[2] != 3) or 0 in array.shape:
        raise SpectrumError(f"image must have shape (H, W, 3) or (H, W) with H, W >= 1; got "
                            f"{array.shape}")
    suffix = path.suffix.lower()
    if suffix == ".png":
        if metadata:
            raise SpectrumError("metadata is stored in TIFF files only; PNG gets none")
        if array.dtype not in (np.uint8, np.uint16):
            raise SpectrumError(
                f"PNG needs uint8 or uint16 codes; got {array.dtype} (render with bit_depth=8 or"
                " 16, or write floats to .tif)"
            )
    elif suffix in (".tif", ".tiff"):
        if array.dtype not in (np.float32, np.float64):
            raise SpectrumError(
                f"TIFF output is for float32/float64 values; got {array.dtype} (write codes "
                "to .png)"
            )
    else:
        raise SpectrumError(
            f"{path}: unknown image format {suffix!r}; accepted: .png (8/16-bit codes), "
            ".tif/.tiff (float)"
        )
    return imagefiles.write_image(path, array, metadata=metadata)
