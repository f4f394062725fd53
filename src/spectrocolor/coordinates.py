"""Colour coordinates derived from tristimulus values: xy, xyY, uv, u'v', CIELAB, CIELCh.

Every function takes arrays with the colour on the last axis, ``(..., 3)`` for XYZ /
xyY / Lab or ``(..., 2)`` for chromaticities, and returns the same leading shape.
Tristimulus values may be on any scale (``XYZ100`` with Y = 100 for the perfect white, or
``XYZ1``); chromaticities are scale-free. CIELAB needs the white on the *same* scale as
the colour.

Black (X + Y + Z = 0) has no chromaticity: its x, y, u, v are NaN (documented NaN, no
warning). NaN inputs give NaN outputs.

References
----------
CIE 015:2018, *Colorimetry*, 4th ed., sections 7.1 (chromaticity), 8.1 (CIE 1976 UCS
u'v'), 8.2.1 (CIELAB, with the exact constants (6/29)^3 and (29/6)^2 / 3) and 8.2.2
(CIELCh). CIE 1960 UCS: MacAdam (1937), J. Opt. Soc. Am. 27, 294-299.

Why this file is long: it is the one table of coordinate systems derived from tristimulus values
(xy, xyY, uv, u'v', CIELAB, CIELCh) with their inverses; each function is short, and splitting the
file would separate each forward transform from its inverse and from the shape checks they share.
"""

from __future__ import annotations

import numpy as np

from .errors import ColorimetryError

__all__ = [
    "xy",
    "xyY",
    "XYZ_from_xyY",
    "uv_1960",
    "xy_from_uv_1960",
    "uv_1976",
    "xy_from_uv_1976",
    "lab",
    "XYZ_from_lab",
    "lch",
]

_DELTA = 6.0 / 29.0  # CIELAB break point of f(t), CIE 015:2018 eq. 8.4


def colour_array(values, name: str, size: int, what: str) -> np.ndarray:
    """``values`` as a float64 array whose last axis has length ``size``, or a ColorimetryError.

    The shared validation of colour arguments: ``name`` is the argument named in the error,
    ``what`` says what the ``size`` components are (e.g. "tristimulus values X, Y, Z").

    Parameters
    ----------
    values : array_like, shape (..., size)
        The colours (real numbers; complex is refused).
    name : str
        The argument named in the error.
    size : int
        Required length of the last axis (3 for XYZ, 2 for xy).
    what : str
        What the components are, for the error message.

    Returns
    -------
    numpy.ndarray
        Float64, shape (..., size).

    Raises
    ------
    ColorimetryError
        For non-real or non-numeric values or a last axis of another length.

    Examples
    --------
    >>> colour_array([1, 2, 3], "XYZ", 3, "tristimulus values X, Y, Z").dtype.name
    'float64'
    >>> colour_array([1, 2], "XYZ", 3, "tristimulus values X, Y, Z")
    Traceback (most recent call last):
    ...
    spectrocolor.errors.ColorimetryError: XYZ must have shape (..., 3) (tristimulus values X, Y, Z); got shape (2,)
    """
    try:
        array = np.asarray(values)
        if array.dtype.kind not in "biuf":  # complex parts are never dropped silently
            raise TypeError(f"dtype {array.dtype}")
        array = array.astype(np.float64, copy=False)
    except (TypeError, ValueError) as exc:
        raise ColorimetryError(
            f"{name} must be real numeric {what} with shape (..., {size}); got {values!r:.80}"
        ) from exc
    if array.ndim == 0 or array.shape[-1] != size:
        raise ColorimetryError(
            f"{name} must have shape (..., {size}) ({what}); got shape {array.shape}"
        )
    return array


def _safe_divide(numerator: np.ndarray, denominator: np.ndarray) -> np.ndarray:
    """numerator / denominator, NaN where the denominator is 0 (no warning)."""
    with np.errstate(divide="ignore", invalid="ignore"):
        safe = np.where(denominator != 0, denominator, 1.0)
        return np.where(denominator != 0, numerator / safe, np.nan)


def xy(XYZ) -> np.ndarray:
    """CIE chromaticity coordinates x = X / (X+Y+Z), y = Y / (X+Y+Z).

    Parameters
    ----------
    XYZ : array_like, shape (..., 3)
        Tristimulus values on any scale.

    Returns
    -------
    ndarray, shape (..., 2)
        (x, y); NaN where X + Y + Z = 0 (black has no chromaticity).

    Raises
    ------
    ColorimetryError
        For input whose last axis is not 3 or that is not numeric.

    References
    ----------
    CIE 015:2018, section 7 (chromaticity coordinates).

    Examples
    --------
    >>> xy([95.047, 100.0, 108.883]).round(4)
    array([0.3127, 0.329 ])
    """
    XYZ = colour_array(XYZ, "XYZ", 3, "tristimulus values X, Y, Z")
    total = XYZ.sum(axis=-1, keepdims=True)
    return _safe_divide(XYZ[..., :2], total)


def xyY(XYZ) -> np.ndarray:
    """Chromaticity and luminance (x, y, Y); Y keeps the scale of the input.

    Parameters
    ----------
    XYZ : array_like, shape (..., 3)
        Tristimulus values on any scale (XYZ100 gives Y in percent).

    Returns
    -------
    ndarray, shape (..., 3)
        (x, y, Y); x and y are NaN for black (Y is then 0).

    Raises
    ------
    ColorimetryError
        For input whose last axis is not 3 or that is not numeric.

    Examples
    --------
    >>> xyY([95.047, 100.0, 108.883]).round(4).tolist()
    [0.3127, 0.329, 100.0]
    """
    XYZ = colour_array(XYZ, "XYZ", 3, "tristimulus values X, Y, Z")
    return np.concatenate([xy(XYZ), XYZ[..., 1:2]], axis=-1)


def XYZ_from_xyY(xyY) -> np.ndarray:
    """Tristimulus values from (x, y, Y): X = xY/y, Z = (1-x-y)Y/y.

    Parameters
    ----------
    xyY : array_like, shape (..., 3)
        Y on the scale wanted for the result.

    Returns
    -------
    ndarray, shape (..., 3)
        XYZ on the scale of Y. Where Y = 0 the result is black (0, 0, 0) whatever x, y
        are (so the NaN chromaticity that :func:`xyY` gives black round-trips).

    Raises
    ------
    ColorimetryError
        Where y = 0 but Y != 0 (an infinite X and Z), or for malformed input.

    Examples
    --------
    >>> XYZ_from_xyY([0.3127, 0.3290, 100.0]).round(3).tolist()
    [95.046, 100.0, 108.906]
    >>> XYZ_from_xyY([float("nan"), float("nan"), 0.0]).tolist()  # black round-trips
    [0.0, 0.0, 0.0]
    """
    xyY = colour_array(xyY, "xyY", 3, "chromaticity x, y and luminance Y")
    x, y, Y = xyY[..., 0], xyY[..., 1], xyY[..., 2]
    impossible = (y == 0) & (Y != 0)
    if np.any(impossible):
        raise ColorimetryError(
            f"xyY has y = 0 with Y != 0 at {int(impossible.sum())} colour(s): X and Z would be "
            "infinite; a colour with luminance needs y > 0"
        )
    black = Y == 0
    with np.errstate(divide="ignore", invalid="ignore"):
        scale = np.where(black, 0.0, Y / np.where(y == 0, 1.0, y))
        X = np.where(black, 0.0, x * scale)
        Z = np.where(black, 0.0, (1.0 - x - y) * scale)
    return np.stack([X, Y.astype(np.float64), Z], axis=-1)


def _uv_from(XYZ, xy_, name: str) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(4X, 6Y, X + 15Y + 3Z) from XYZ, or the same quantities from xy (scaled by 1/(X+Y+Z))."""
    if (XYZ is None) == (xy_ is None):
        raise ColorimetryError(
            f"{name} takes exactly one of XYZ (shape (..., 3)) or xy= (shape (..., 2))"
        )
    if XYZ is not None:
        XYZ = colour_array(XYZ, "XYZ", 3, f"tristimulus values; for chromaticities call {name}(xy=...)")
        X, Y, Z = XYZ[..., 0], XYZ[..., 1], XYZ[..., 2]
        return 4.0 * X, 6.0 * Y, X + 15.0 * Y + 3.0 * Z
    chroma = colour_array(xy_, "xy", 2, "chromaticity coordinates x, y")
    x, y = chroma[..., 0], chroma[..., 1]
    return 4.0 * x, 6.0 * y, -2.0 * x + 12.0 * y + 3.0


def uv_1960(XYZ=None, *, xy=None) -> np.ndarray:
    """CIE 1960 UCS chromaticity u = 4X / (X+15Y+3Z), v = 6Y / (X+15Y+3Z).

    The 1960 diagram is the one in which correlated colour temperature and Duv are
    defined (CIE 015:2018 section 9.5).

    Parameters
    ----------
    XYZ : array_like, shape (..., 3), optional
        Tristimulus values (any scale).
    xy : array_like, shape (..., 2), keyword-only, optional
        Chromaticities instead of XYZ. Give exactly one of the two.

    Returns
    -------
    ndarray, shape (..., 2)
        (u, v); NaN for black.

    Raises
    ------
    ColorimetryError
        Unless exactly one of ``XYZ`` and ``xy`` is given, or for malformed input.

    References
    ----------
    CIE 015:2018, section 9.5 (the CIE 1960 UCS diagram).

    Examples
    --------
    >>> uv_1960([95.047, 100.0, 108.883]).round(5).tolist()
    [0.19784, 0.31222]
    """
    four_x, six_y, denominator = _uv_from(XYZ, xy, "uv_1960")
    return np.stack([_safe_divide(four_x, denominator), _safe_divide(six_y, denominator)], -1)


def xy_from_uv_1960(uv) -> np.ndarray:
    """Chromaticity (x, y) from CIE 1960 UCS (u, v): x = 3u / d, y = 2v / d, d = 2u - 8v + 4.

    Parameters
    ----------
    uv : array_like, shape (..., 2)
        CIE 1960 UCS chromaticity (u, v).

    Returns
    -------
    ndarray, shape (..., 2)
        CIE 1931 chromaticity (x, y); NaN where d = 0.

    Raises
    ------
    ColorimetryError
        For input whose last axis is not 2 or that is not numeric.

    Examples
    --------
    >>> xy_from_uv_1960(uv_1960(xy=[0.3127, 0.3290])).round(6).tolist()
    [0.3127, 0.329]
    """
    uv = colour_array(uv, "uv", 2, "CIE 1960 chromaticity u, v")
    u, v = uv[..., 0], uv[..., 1]
    denominator = 2.0 * u - 8.0 * v + 4.0
    return np.stack([_safe_divide(3.0 * u, denominator), _safe_divide(2.0 * v, denominator)], -1)


def uv_1976(XYZ=None, *, xy=None) -> np.ndarray:
    """CIE 1976 UCS chromaticity u' = 4X / (X+15Y+3Z), v' = 9Y / (X+15Y+3Z).

    Parameters
    ----------
    XYZ : array_like, shape (..., 3), optional
        Tristimulus values (any scale).
    xy : array_like, shape (..., 2), keyword-only, optional
        Chromaticities instead of XYZ. Give exactly one of the two.

    Returns
    -------
    ndarray, shape (..., 2)
        (u', v'); NaN for black.

    Raises
    ------
    ColorimetryError
        Unless exactly one of ``XYZ`` and ``xy`` is given, or for malformed input.

    References
    ----------
    CIE 015:2018, section 8.1 (the CIE 1976 UCS diagram).

    Examples
    --------
    >>> uv_1976(xy=[0.31272, 0.32903]).round(5)
    array([0.19783, 0.46834])
    """
    four_x, six_y, denominator = _uv_from(XYZ, xy, "uv_1976")
    return np.stack([_safe_divide(four_x, denominator), _safe_divide(1.5 * six_y, denominator)],
                    -1)


def xy_from_uv_1976(uv) -> np.ndarray:
    """Chromaticity (x, y) from CIE 1976 (u', v'): x = 9u' / d, y = 4v' / d, d = 6u' - 16v' + 12.

    Parameters
    ----------
    uv : array_like, shape (..., 2)
        CIE 1976 UCS chromaticity (u', v').

    Returns
    -------
    ndarray, shape (..., 2)
        CIE 1931 chromaticity (x, y); NaN where d = 0.

    Raises
    ------
    ColorimetryError
        For input whose last axis is not 2 or that is not numeric.

    Examples
    --------
    >>> xy_from_uv_1976([0.19783, 0.46834]).round(4).tolist()
    [0.3127, 0.329]
    """
    uv = colour_array(uv, "uv", 2, "CIE 1976 chromaticity u', v'")
    u, v = uv[..., 0], uv[..., 1]
    denominator = 6.0 * u - 16.0 * v + 12.0
    return np.stack([_safe_divide(9.0 * u, denominator), _safe_divide(4.0 * v, denominator)], -1)


def _white(white_XYZ, name: str) -> np.ndarray:
    white = colour_array(white_XYZ, name, 3, "the white's tristimulus values Xn, Yn, Zn")
    if not np.all((white > 0) & np.isfinite(white)):
        raise ColorimetryError(
            f"{name} must be positive, finite tristimulus values of the reference white (e.g. "
            f"sc.white_point('D65')); got {white_XYZ!r:.80}"
        )
    return white


def lab(XYZ, white_XYZ) -> np.ndarray:
    """CIE 1976 L*a*b* (CIELAB) relative to a reference white.

    Parameters
    ----------
    XYZ : array_like, shape (..., 3)
        Tristimulus values, on the same scale as ``white_XYZ``.
    white_XYZ : array_like, shape (3,) or broadcastable to (..., 3)
        The reference white (e.g. ``sc.white_point("D65")`` with Y = 100); all positive.

    Returns
    -------
    ndarray, shape (..., 3)
        (L*, a*, b*); L* = 100 for the white itself. Uses the exact CIE constants
        ((6/29)^3 = 216/24389 as the break point), so the two branches join continuously.

    Raises
    ------
    ColorimetryError
        For malformed input or a white that is not positive and finite.

    References
    ----------
    CIE 015:2018, section 8.2.1.

    Examples
    --------
    >>> from spectrocolor import white_point
    >>> lab([41.24, 21.26, 1.93], white_point("D65")).round(2).tolist()
    [53.23, 80.11, 67.22]
    """
    XYZ = colour_array(XYZ, "XYZ", 3, "tristimulus values X, Y, Z")
    ratio = XYZ / _white(white_XYZ, "white_XYZ")
    with np.errstate(invalid="ignore"):
        f = np.where(
            ratio > _DELTA**3, np.cbrt(ratio), ratio / (3.0 * _DELTA**2) + 4.0 / 29.0
        )
    L = 116.0 * f[..., 1] - 16.0
    a = 500.0 * (f[..., 0] - f[..., 1])
    b = 200.0 * (f[..., 1] - f[..., 2])
    return np.stack([L, a, b], axis=-1)


def XYZ_from_lab(lab, white_XYZ) -> np.ndarray:
    """Tristimulus values from CIELAB, the exact inverse of :func:`lab`.

    Parameters
    ----------
    lab : array_like, shape (..., 3)
        (L*, a*, b*).
    white_XYZ : array_like, shape (3,) or broadcastable to (..., 3)
        The reference white; the result is on its scale.

    Returns
    -------
    ndarray, shape (..., 3)
        XYZ on the scale of ``white_XYZ`` (XYZ100 for ``white_point(...)``).

    Raises
    ------
    ColorimetryError
        For malformed input or a white that is not positive and finite.

    References
    ----------
    CIE 015:2018, section 8.2.1.

    Examples
    --------
    >>> from spectrocolor import white_point
    >>> XYZ_from_lab([100.0, 0.0, 0.0], white_point("D65")).round(3).tolist()
    [95.043, 100.0, 108.88]
    """
    lab = colour_array(lab, "lab", 3, "CIELAB L*, a*, b*")
    white = _white(white_XYZ, "white_XYZ")
    fy = (lab[..., 0] + 16.0) / 116.0
    f = np.stack([fy + lab[..., 1] / 500.0, fy, fy - lab[..., 2] / 200.0], axis=-1)
    ratio = np.where(f > _DELTA, f**3, 3.0 * _DELTA**2 * (f - 4.0 / 29.0))
    return ratio * white


def lch(lab) -> np.ndarray:
    """CIELCh: lightness L*, chroma C*ab and hue angle h_ab in degrees.

    Parameters
    ----------
    lab : array_like, shape (..., 3)
        CIELAB (L*, a*, b*).

    Returns
    -------
    ndarray, shape (..., 3)
        (L*, C*ab, h_ab) with h_ab in [0, 360) degrees; h_ab = 0 for neutrals (a* = b* = 0).

    Raises
    ------
    ColorimetryError
        For input whose last axis is not 3 or that is not numeric.

    References
    ----------
    CIE 015:2018, section 8.2.2.

    Examples
    --------
    >>> lch([50.0, 3.0, -4.0]).round(2).tolist()
    [50.0, 5.0, 306.87]
    """
    lab = colour_array(lab, "lab", 3, "CIELAB L*, a*, b*")
    a, b = lab[..., 1], lab[..., 2]
    hue = np.degrees(np.arctan2(b, a)) % 360.0
    hue = np.where(hue >= 360.0, 0.0, hue)  # a tiny negative angle rounds up to 360.0
    return np.stack([lab[..., 0], np.hypot(a, b), hue], axis=-1)


def lab_from_lch(lch) -> np.ndarray:
    """CIELAB from CIELCh: the inverse of :func:`lch`.

    Parameters
    ----------
    lch : array_like, shape (..., 3)
        (L*, C*ab, h_ab) with the hue angle in degrees (any real angle; 360 wraps).

    Returns
    -------
    ndarray, shape (..., 3)
        (L*, a*, b*) with a* = C*ab cos h_ab and b* = C*ab sin h_ab.

    Raises
    ------
    ColorimetryError
        For a negative chroma or malformed input.

    References
    ----------
    CIE 015:2018, section 8.2.2.

    Examples
    --------
    >>> lab_from_lch([50.0, 10.0, 90.0]).round(12).tolist()
    [50.0, 0.0, 10.0]
    """
    lch = colour_array(lch, "lch", 3, "CIELCh L*, C*ab, h_ab (degrees)")
    if np.any(lch[..., 1] < 0):
        raise ColorimetryError("lch: chroma C*ab must be >= 0")
    hue = np.radians(lch[..., 2])
    return np.stack([lch[..., 0], lch[..., 1] * np.cos(hue), lch[..., 1] * np.sin(hue)], axis=-1)
