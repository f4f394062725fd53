"""The spectral locus, dominant / complementary wavelength, excitation and colorimetric purity.

The spectral locus
------------------
The locus is the chromaticity of monochromatic light, computed from the observer's
colour-matching functions at 1 nm. At the ends of the spectrum it stops being a clean
curve, and only its *monotonic part* bounds the gamut:

* CIE 1931 2°: from 699 nm to 830 nm every tabulated point has x = 0.73469, y = 0.26531
  (the table was built that way); the differences between them (< 4e-7) are rounding
  noise, so the tail zig-zags back and forth on the spot.
* CIE 1964 10° and the CIE 2015 observers: beyond about 701-703 nm the locus genuinely
  turns back (x falls from 0.7204 at 701 nm to 0.7115 at 830 nm for the 1964 observer).

:func:`spectral_locus` therefore returns, by default, the locus from its bluest to its
reddest point: the extremes are the points of largest and smallest polar angle around
the equal-energy white E; of the wavelengths whose chromaticity equals an extreme to within
1e-5 (the precision of the CIE's 5-decimal chromaticity tables; the 2015 tables wobble
by ~1e-6 between 697 and 704 nm) the one nearest the middle of the spectrum is kept. The
result (360-699 nm for the 1931 and 1964 observers, 390-697 nm for the 2015 observers)
turns strictly monotonically around E, and the purple line joins its two ends.
``full=True`` gives the whole table.

Dominant wavelength
-------------------
Seed 001 §1.7, CIE 015:2018 §9.1: draw the ray from the white W through the colour S; it
leaves the gamut at a boundary point B. If B is on the spectral locus, its wavelength is
the dominant wavelength. If B is on the purple line, the colour has no dominant
wavelength; the ray from S back through W meets the locus at the *complementary*
wavelength. Excitation purity is ``|S - W| / |B - W|`` with B on the dominant side (on the
purple line for purples), as in seed 001 Fig. 1.4 and CIE 015.

The boundary point is found exactly: for one white, the locus vertices are sorted by polar
angle around W, each colour's angle is located among them by binary search, and the ray is
intersected with that one segment. The wavelength is interpolated linearly along the
segment (sub-nanometre; colour-science snaps to the nearest tabulated wavelength). Time is
O(N log K) and memory O(N) for N colours, with no N × K intermediate.

Conventions, and how they differ from colour-science 0.4.7
-----------------------------------------------------------
* ``wavelength_nm`` is always positive; ``complementary`` says whether it is a
  complementary wavelength. (``colour.dominant_wavelength`` returns complementary
  wavelengths as negative numbers.)
* The white itself, and any colour within ``WHITE_TOLERANCE`` (1e-12 in x, y: floating-point
  rounding, e.g. a flat grey reflectance) of it: wavelength NaN, complementary False, excitation
  purity 0. The hue of such a colour is undefined, so no wavelength is invented for it.
* Colours outside the gamut get their boundary point as usual and an excitation purity
  greater than 1; ``result.outside_locus`` flags them (purity > 1 + 1e-9).
* NaN chromaticities (e.g. black) give NaN wavelength and purity.
* The purple line joins the ends of the monotonic locus. colour-science joins 360 and
  830 nm; for CIE 1931 these coincide to 3e-7, for the 1964 observer colour-science's
  line cuts through the gamut.
* The white must lie inside the gamut and every ray from it must cross the boundary once
  (the locus turns monotonically around it); a ColorimetryError says so otherwise.
"""

from __future__ import annotations

from functools import cache, lru_cache
from typing import NamedTuple

import numpy as np

from .coordinates import colour_array
from .coordinates import xy as xy_from_XYZ
from .errors import ColorimetryError
from .observers import DEFAULT_OBSERVER, canonical_observer_name
from .observers import observer as named_observer

__all__ = [
    "SpectralLocus",
    "spectral_locus",
    "DominantWavelength",
    "dominant_wavelength",
    "colorimetric_purity",
]

#: Locus points this close (in x and y) to an extreme chromaticity count as the same point:
#: the precision of the CIE's published 5-decimal chromaticities.
_SAME_CHROMATICITY = 1e-5
#: Excitation purity above 1 + this flags a colour outside the gamut.
_OUTSIDE_TOLERANCE = 1e-9
_EQUAL_ENERGY_XY = np.array([1.0 / 3.0, 1.0 / 3.0])


class SpectralLocus(NamedTuple):
    """Chromaticities of monochromatic stimuli: ``wavelengths_nm`` (K,) and ``xy`` (K, 2).

    Returned by :func:`spectral_locus`; a named tuple, so ``wavelengths_nm, xy = locus`` works.

    Attributes
    ----------
    wavelengths_nm : numpy.ndarray, shape (K,)
        Wavelengths of the monochromatic stimuli, nm, increasing (read-only).
    xy : numpy.ndarray, shape (K, 2)
        Their CIE chromaticity coordinates x, y (read-only).

    Examples
    --------
    >>> wavelengths_nm, xy = spectral_locus("1931")
    >>> xy[wavelengths_nm == 520].round(4).tolist()
    [[0.0743, 0.8338]]
    """

    wavelengths_nm: np.ndarray
    xy: np.ndarray


class DominantWavelength(NamedTuple):
    """Result of :func:`dominant_wavelength`; each field has the colours' leading shape.

    Attributes
    ----------
    wavelength_nm : ndarray of float
        Dominant wavelength in nm, or the complementary wavelength where ``complementary``
        is True (always positive). NaN for the white itself and for NaN input.
    complementary : ndarray of bool
        True where the colour lies toward the purple line.
    excitation_purity : ndarray of float
        ``|S - W| / |B - W|``: 0 at the white, 1 on the gamut boundary, > 1 outside it.

    Examples
    --------
    >>> result = dominant_wavelength([[0.5437, 0.3211], [0.30, 0.20]], "D65")
    >>> result.wavelength_nm.round(1).tolist(), result.complementary.tolist()
    ([616.4, 556.0], [False, True])
    >>> result.excitation_purity.round(3).tolist(), result.outside_locus.tolist()
    ([0.623, 0.474], [False, False])
    """

    wavelength_nm: np.ndarray
    complementary: np.ndarray
    excitation_purity: np.ndarray

    @property
    def outside_locus(self) -> np.ndarray:
        """True where the colour lies outside the gamut (excitation purity > 1 + 1e-9)."""
        return np.asarray(self.excitation_purity) > 1.0 + _OUTSIDE_TOLERANCE


def _readonly(array: np.ndarray) -> np.ndarray:
    array.setflags(write=False)
    return array


@cache
def _locus(canonical: str, full: bool) -> SpectralLocus:
    cmfs = named_observer(canonical)
    wavelengths = np.array(cmfs.wavelengths_nm, dtype=np.float64)
    xy = xy_from_XYZ(cmfs.values.T)
    if full:
        return SpectralLocus(_readonly(wavelengths), _readonly(np.ascontiguousarray(xy)))
    angle = np.unwrap(np.arctan2(xy[:, 1] - _EQUAL_ENERGY_XY[1], xy[:, 0] - _EQUAL_ENERGY_XY[0]))
    # the angle decreases from blue through green to red; the extremes bound the gamut
    bluest, reddest = int(np.argmax(angle)), int(np.argmin(angle))
    # the ends: the wavelengths nearest the middle that share the extreme chromaticities
    index = np.arange(len(wavelengths))
    near_blue = np.hypot(*(xy - xy[bluest]).T) <= _SAME_CHROMATICITY
    near_red = np.hypot(*(xy - xy[reddest]).T) <= _SAME_CHROMATICITY
    blue = int(index[near_blue & (index >= bluest) & (index <= reddest)].max())
    red = int(index[near_red & (index >= blue) & (index <= reddest)].min())
    keep = slice(blue, red + 1)
    if not np.all(np.diff(angle[keep]) < 0):
        raise ColorimetryError(  # a property of the shipped tables, checked by the tests
            f"observer {canonical!r}: the spectral locus between {wavelengths[blue]:g} and "
            f"{wavelengths[red]:g} nm does not turn monotonically around the equal-energy white"
        )
    return SpectralLocus(_readonly(wavelengths[keep].copy()), _readonly(xy[keep].copy()))


def spectral_locus(observer=DEFAULT_OBSERVER, *, full: bool = False) -> SpectralLocus:
    """Chromaticity (x, y) of monochromatic light, from the observer's CMFs at 1 nm.

    Parameters
    ----------
    observer : str, default DEFAULT_OBSERVER
        The observer whose locus is wanted; see :term:`observer`.
    full : bool, keyword-only
        False (default): only the monotonic part of the locus, from its bluest to its
        reddest chromaticity (see the module documentation); its ends are joined by the
        purple line. True: every tabulated wavelength, including the red tail that
        stagnates (1931) or turns back (1964, 2015).

    Returns
    -------
    SpectralLocus
        ``(wavelengths_nm, xy)``: read-only arrays of shape (K,) and (K, 2).

    Raises
    ------
    ColorimetryError
        For an unknown observer.

    References
    ----------
    CIE 015:2018 §9 (the chromaticity diagram and the spectral locus).

    Examples
    --------
    >>> locus = spectral_locus("1931")
    >>> locus.wavelengths_nm[[0, -1]]
    array([360., 699.])
    """
    return _locus(canonical_observer_name(observer), bool(full))


class _Boundary(NamedTuple):
    wavelength_nm: np.ndarray
    complementary: np.ndarray
    excitation_purity: np.ndarray
    boundary_xy: np.ndarray


def _white_xy(white, observer: str) -> np.ndarray:
    if isinstance(white, str):
        from .colorimetry import white_point  # same layer; imported when a name is given

        return xy_from_XYZ(white_point(white, observer=observer))
    white_xy = colour_array(white, "white", 2, "the white's chromaticity x, y, or an illuminant name")
    if white_xy.shape != (2,) or not np.all(np.isfinite(white_xy)):
        raise ColorimetryError(
            f"white must be one finite chromaticity (x, y) or an illuminant name such as "
            f"'D65'; got {white!r:.80}"
        )
    return white_xy


@lru_cache(maxsize=64)
def _polygon(canonical: str, white_x: float, white_y: float):
    """Locus vertex angles around the white (strictly decreasing) and the locus itself."""
    locus = _locus(canonical, False)
    white = np.array([white_x, white_y])
    offsets = locus.xy - white
    angles = np.unwrap(np.arctan2(offsets[:, 1], offsets[:, 0]))
    # closing the polygon: the purple line must continue the clockwise turn back to the start
    sweep = angles[0] - angles[-1]
    closing = np.arctan2(offsets[-1, 0] * offsets[0, 1] - offsets[-1, 1] * offsets[0, 0],
                         offsets[-1] @ offsets[0])
    winding = sweep - closing
    if not (abs(winding - 2.0 * np.pi) < 1e-6 and closing < 0):
        raise ColorimetryError(
            f"white: chromaticity ({white_x:.5f}, {white_y:.5f}) lies outside the gamut of "
            f"observer {canonical!r} (the spectral locus and purple line); a white must be a "
            "chromaticity inside it, such as an illuminant's white point"
        )
    if not np.all(np.diff(angles) < 0):
        bad = locus.wavelengths_nm[1:][np.diff(angles) >= 0]
        raise ColorimetryError(
            f"white: chromaticity ({white_x:.5f}, {white_y:.5f}) is so close to the spectral "
            f"locus of observer {canonical!r} that rays from it meet the locus more than once "
            f"(near {bad[0]:g} nm); the dominant wavelength is ambiguous for this white"
        )
    return locus, white, angles


def _segment_hits(angles, theta):
    """Index k of the locus segment met by rays at polar angle theta (-1: the purple line)."""
    top = angles[0]
    wrapped = top - np.mod(top - theta, 2.0 * np.pi)  # in (top - 2π, top]
    on_locus = wrapped >= angles[-1]
    k = np.searchsorted(-angles, -wrapped, side="right") - 1
    k = np.clip(k, 0, len(angles) - 2)
    return np.where(on_locus, k, -1)


#: Chromaticity distance from the white (x, y units) below which a colour counts as the white.
WHITE_TOLERANCE = 1e-12


def _boundary(xy, white, observer: str) -> _Boundary:
    canonical = canonical_observer_name(observer)
    points = colour_array(xy, "xy", 2, "chromaticity coordinates x, y")
    white_xy = _white_xy(white, observer)
    locus, white_xy, angles = _polygon(canonical, float(white_xy[0]), float(white_xy[1]))
    lam, vertices = locus.wavelengths_nm, locus.xy

    d = points - white_xy
    valid = np.all(np.isfinite(points), axis=-1)
    at_white = valid & (np.hypot(d[..., 0], d[..., 1]) <= WHITE_TOLERANCE)
    theta = np.arctan2(d[..., 1], d[..., 0])
    theta = np.where(valid, theta, 0.0)

    k = _segment_hits(angles, theta)
    purple = k < 0
    start = np.where(purple[..., None], vertices[-1], vertices[np.maximum(k, 0)])
    end = np.where(purple[..., None], vertices[0], vertices[np.maximum(k, 0) + 1])
    edge = end - start
    to_start = start - white_xy
    with np.errstate(divide="ignore", invalid="ignore"):
        denominator = d[..., 0] * edge[..., 1] - d[..., 1] * edge[..., 0]
        t = (to_start[..., 0] * edge[..., 1] - to_start[..., 1] * edge[..., 0]) / denominator
        purity = 1.0 / t  # |S - W| / |B - W| with B = W + t (S - W)
        boundary_xy = white_xy + t[..., None] * d
        s = np.clip((to_start[..., 0] * d[..., 1] - to_start[..., 1] * d[..., 0]) / denominator,
                    0.0, 1.0)
    kk = np.maximum(k, 0)
    wavelength = lam[kk] + s * (lam[kk + 1] - lam[kk])

    if np.any(purple):  # complementary wavelength: the opposite ray meets the locus
        kc = _segment_hits(angles, theta + np.pi)
        kc = np.maximum(kc, 0)  # the opposite ray of a purple cannot meet the purple line
        a, b = vertices[kc], vertices[kc + 1]
        edge_c = b - a
        to_a = a - white_xy
        # the same formula for s as above: the sign of the direction cancels
        with np.errstate(divide="ignore", invalid="ignore"):
            den_c = d[..., 0] * edge_c[..., 1] - d[..., 1] * edge_c[..., 0]
            s_c = np.clip((to_a[..., 0] * d[..., 1] - to_a[..., 1] * d[..., 0]) / den_c, 0, 1)
        wavelength = np.where(purple, lam[kc] + s_c * (lam[kc + 1] - lam[kc]), wavelength)

    wavelength = np.where(valid & ~at_white, wavelength, np.nan)
    purity = np.where(at_white, 0.0, np.where(valid, purity, np.nan))
    boundary_xy = np.where((valid & ~at_white)[..., None], boundary_xy, np.nan)
    complementary = purple & valid & ~at_white
    return _Boundary(wavelength, complementary, purity, boundary_xy)


def dominant_wavelength(xy, white, observer=DEFAULT_OBSERVER) -> DominantWavelength:
    """Dominant (or complementary) wavelength and excitation purity of chromaticities.

    Parameters
    ----------
    xy : array_like, shape (..., 2)
        Chromaticities of the colours (e.g. ``sc.xy(XYZ)``).
    white : (x, y) or str
        The reference white: a chromaticity, or an illuminant name (then its white point
        for ``observer``, ``sc.white_point(name, observer)``). For surface colours this is
        the illuminant's white (seed 001 §1.8).
    observer : str
        Observer whose spectral locus is used (default CIE 1931 2°).

    Returns
    -------
    DominantWavelength
        ``(wavelength_nm, complementary, excitation_purity)``, each of shape ``(...)``,
        plus the property ``outside_locus``. See the module documentation for the
        conventions (positive complementary wavelengths; white → NaN and purity 0;
        purity > 1 outside the gamut).

    Raises
    ------
    ColorimetryError
        For malformed input, or a white outside the gamut or too close to the locus.

    References
    ----------
    CIE 015:2018 *Colorimetry*, §9.1 (dominant wavelength, excitation purity).
    Seed 001 (Visser 1986) §1.7 and Figure 1.4.

    Examples
    --------
    >>> result = dominant_wavelength([0.54369557, 0.32107944], [0.3127, 0.3290])
    >>> round(float(result.wavelength_nm), 2), bool(result.complementary)
    (616.4, False)
    """
    hit = _boundary(xy, white, observer)
    return DominantWavelength(hit.wavelength_nm, hit.complementary, hit.excitation_purity)


def colorimetric_purity(xy, white, observer=DEFAULT_OBSERVER) -> np.ndarray:
    """Colorimetric purity ``p_c = p_e · y_b / y`` of chromaticities.

    ``p_e`` is the excitation purity and ``y_b`` the y chromaticity of the boundary point
    on the dominant side (the spectral locus, or the purple line for purples, as in
    colour-science). For a mixture of the white with a monochromatic stimulus, ``p_c`` is the
    luminance of the monochromatic part over the luminance of the mixture.

    Parameters
    ----------
    xy : array_like, shape (..., 2)
        Chromaticities of the colours.
    white : (x, y) or str
        The reference white, as for :func:`dominant_wavelength`.
    observer : str, default DEFAULT_OBSERVER
        Observer whose spectral locus is used (CIE 1931 2°).

    Returns
    -------
    numpy.ndarray, shape (...)
        Colorimetric purity, dimensionless: 0 at the white, 1 on the spectral locus, NaN for
        NaN input.

    Raises
    ------
    ColorimetryError
        As :func:`dominant_wavelength`.

    References
    ----------
    CIE 015:2018 *Colorimetry*, §9.2 (colorimetric purity).

    Examples
    --------
    >>> round(float(colorimetric_purity([0.54369557, 0.32107944], [0.3127, 0.3290])), 4)
    0.6136
    """
    hit = _boundary(xy, white, observer)
    points = colour_array(xy, "xy", 2, "chromaticity coordinates x, y")
    with np.errstate(divide="ignore", invalid="ignore"):
        ratio = hit.boundary_xy[..., 1] / points[..., 1]
    return np.where(hit.excitation_purity == 0, 0.0, hit.excitation_purity * ratio)
