"""Correlated colour temperature (CCT) and Duv, and chromaticities on the Planckian locus.

The Planckian locus is computed here, not taken from a published table: Planck's law
(c2 = 1.4388e-2 m·K, CIE 015:2018) summed at 1 nm with the observer's colour-matching
functions over their whole range, in the CIE 1960 (u, v) diagram where CCT is defined.

Method
------
CCT is the temperature of the point of the Planckian locus nearest to the colour in the
CIE 1960 diagram, Duv the signed distance (positive above the locus, toward green), as in
Ohno (2013). Ohno's combined method interpolates on a 1 % temperature table with a
cascade of refinements; here the locus is tabulated once per observer with a 0.01 % step
(46 000 points, 1 000 K to 100 000 K, cached), the nearest table point is found, and
Ohno's parabolic step is applied to the squared distances to it and its two neighbours.
On so fine a table the parabola is exact to rounding: CCT is accurate to **0.001 K** and
Duv to **1e-9** over the whole range (the tests check round trips through
:func:`xy_from_cct`, which evaluates Planck's law directly); Ohno reports about 1 K for his
combined method.

Search: the nearest of every 100th table point (1 % steps) and a parabola through its
neighbours give a first estimate; the nearest of the 31 fine points around it follows.
Colours are processed in chunks of 4096, so memory is bounded.

Validity: CCT is returned for colours whose nearest locus point lies between 1 000 K and
100 000 K; elsewhere CCT and Duv are NaN. CIE 015 considers CCT meaningful only for
|Duv| <= 0.05; larger |Duv| values are returned as computed, and callers should check.

References
----------
Y. Ohno, "Practical use and calculation of CCT and Duv", LEUKOS 10 (1), 47-55 (2014)
(conference version 2013). CIE 015:2018 *Colorimetry*, §9.5 (correlated colour
temperature, CIE 1960 UCS).
"""

from __future__ import annotations

from functools import cache
from typing import NamedTuple

import numpy as np

from .arguments import real_array
from .coordinates import uv_1960, xy_from_uv_1960
from .errors import ColorimetryError
from .observers import DEFAULT_OBSERVER, canonical_observer_name
from .observers import observer as named_observer
from .radiators import C2_CIE_LOCUS_M_K, planck

__all__ = ["CCT", "cct", "xy_from_cct"]

_T_MIN_K, _T_MAX_K = 1_000.0, 100_000.0
_FINE_RATIO = 1.0001
_COARSE_EVERY = 100
_FINE_WINDOW = 15
_CHUNK = 4096


class CCT(NamedTuple):
    """Correlated colour temperature ``cct_K`` (K) and ``duv`` (CIE 1960 uv distance).

    Returned by :func:`cct`; a named tuple, so ``T, duv = cct(xy)`` works.

    Attributes
    ----------
    cct_K : numpy.ndarray, shape (...)
        Correlated colour temperature, K; NaN outside 1 000–100 000 K and for NaN input.
    duv : numpy.ndarray, shape (...)
        Signed distance from the Planckian locus in the CIE 1960 (u, v) diagram, dimensionless;
        positive above the locus (toward green), negative below it (toward magenta).

    Examples
    --------
    >>> T, duv = cct([[0.31272, 0.32903], [0.44757, 0.40745]])  # D65, A
    >>> T.round(0).tolist(), duv.round(4).tolist()
    ([6503.0, 2856.0], [0.0032, 0.0])
    """

    cct_K: np.ndarray
    duv: np.ndarray


def _planck_uv(temperatures_K: np.ndarray, canonical: str) -> np.ndarray:
    """CIE 1960 (u, v) of blackbodies at the given temperatures, shape (N, 2)."""
    cmfs = named_observer(canonical)
    out = np.empty((len(temperatures_K), 2))
    for start in range(0, len(temperatures_K), _CHUNK):
        T = temperatures_K[start:start + _CHUNK, None]
        radiance = planck(cmfs.wavelengths_nm, T, C2_CIE_LOCUS_M_K)
        out[start:start + _CHUNK] = uv_1960(radiance @ cmfs.values.T)
    return out


@cache
def _locus_table(canonical: str) -> tuple[np.ndarray, np.ndarray]:
    """Fine table of temperatures (ratio 1.0001) and their (u, v)."""
    steps = int(np.ceil(np.log(_T_MAX_K / _T_MIN_K) / np.log(_FINE_RATIO)))
    temperatures = _T_MIN_K * _FINE_RATIO ** np.arange(steps + 1)
    uv = _planck_uv(temperatures, canonical)
    temperatures.setflags(write=False)
    uv.setflags(write=False)
    return temperatures, uv


def _vertex_offset(d2_before, d2_at, d2_after):
    """Offset (in table steps) of the vertex of the parabola through three squared distances."""
    with np.errstate(divide="ignore", invalid="ignore"):
        curvature = d2_before - 2.0 * d2_at + d2_after
        offset = (d2_before - d2_after) / (2.0 * curvature)
        minimum = d2_at - (d2_before - d2_after) ** 2 / (8.0 * curvature)
    return offset, minimum


def _nearest_index(points: np.ndarray, table: np.ndarray) -> np.ndarray:
    """Index of the nearest fine-table point: a parabola on every 100th, then a local search."""
    coarse = table[::_COARSE_EVERY]
    norms = (coarse**2).sum(axis=1)
    index = np.empty(len(points), dtype=np.intp)
    window = np.arange(-_FINE_WINDOW, _FINE_WINDOW + 1)
    rows = np.arange(min(_CHUNK, len(points)))
    for start in range(0, len(points), _CHUNK):  # chunks keep the distance matrices small
        p = points[start:start + _CHUNK]
        r = rows[: len(p)]
        d2 = norms - 2.0 * p @ coarse.T + (p**2).sum(axis=1)[:, None]
        c = np.clip(np.argmin(d2, axis=1), 1, len(coarse) - 2)
        offset, _ = _vertex_offset(d2[r, c - 1], d2[r, c], d2[r, c + 1])
        offset = np.nan_to_num(np.clip(offset, -1.0, 1.0))
        guess = np.rint((c + offset) * _COARSE_EVERY).astype(np.intp)
        candidates = np.clip(guess[:, None] + window, 0, len(table) - 1)
        near = np.sum((table[candidates] - p[:, None, :]) ** 2, axis=-1)
        index[start:start + _CHUNK] = candidates[r, np.argmin(near, axis=1)]
    return index


def cct(xy=None, *, XYZ=None, observer=DEFAULT_OBSERVER) -> CCT:
    """Correlated colour temperature and Duv (Ohno 2013 definition, exact projection).

    Parameters
    ----------
    xy : array_like, shape (..., 2), optional
        Chromaticities.
    XYZ : array_like, shape (..., 3), keyword-only, optional
        Tristimulus values instead of ``xy`` (any scale). Give exactly one of the two.
    observer : str, keyword-only
        Observer for the Planckian locus; it must be the observer the colour was computed with
        (default CIE 1931 2°, the one CCT is normally quoted for); see :term:`observer`.

    Returns
    -------
    CCT
        ``(cct_K, duv)`` with the leading shape of the input. Accurate to 0.001 K and 1e-9 in
        Duv (see the module documentation); NaN outside 1 000-100 000 K or for NaN input.

    Raises
    ------
    ColorimetryError
        Unless exactly one of ``xy`` and ``XYZ`` is given, for malformed input or an unknown
        observer.

    References
    ----------
    Y. Ohno, LEUKOS 10 (1), 47-55 (2014). CIE 015:2018, §9.5.

    Examples
    --------
    >>> result = cct([0.31272, 0.32903])  # D65
    >>> round(float(result.cct_K)), round(float(result.duv), 4)
    (6503, 0.0032)
    """
    if (xy is None) == (XYZ is None):
        raise ColorimetryError(
            "cct takes exactly one of xy (shape (..., 2)) or XYZ= (shape (..., 3))"
        )
    uv = uv_1960(XYZ) if XYZ is not None else uv_1960(xy=xy)
    shape = uv.shape[:-1]
    points = uv.reshape(-1, 2)
    valid = np.all(np.isfinite(points), axis=1)
    points = np.where(valid[:, None], points, 0.0)

    temperatures, table = _locus_table(canonical_observer_name(observer))
    last = len(table) - 1
    i = _nearest_index(points, table)

    # parabola through the squared distances to the three nearest table points (uniform in
    # log T); its vertex is the nearest point of the locus (Ohno's parabolic step, on a table
    # fine enough that the parabola is exact to rounding)
    j = np.clip(i, 1, last - 1)
    d2 = [np.sum((points - table[j + shift]) ** 2, axis=1) for shift in (-1, 0, 1)]
    delta, _ = _vertex_offset(*d2)
    T = temperatures[j] * _FINE_RATIO**delta
    # the nearest locus point, by quadratic interpolation of the table at the same offset
    before, at, after = table[j - 1], table[j], table[j + 1]
    step = delta[:, None]
    foot = at + 0.5 * (after - before) * step + 0.5 * (after - 2.0 * at + before) * step**2
    distance = np.hypot(*(points - foot).T)
    tangent = table[j + 1] - table[j - 1]
    offset = points - table[j]
    # with increasing T the locus runs right to left: a point to the left of the direction
    # of travel lies below the locus (negative Duv), one to its right above it (positive)
    left = (tangent[:, 0] * offset[:, 1] - tangent[:, 1] * offset[:, 0]) > 0
    duv = np.where(left, -distance, distance)

    # at the table's ends the nearest point is the end itself: out of range
    inside = valid & (i > 0) & (i < last) & (np.abs(delta) <= 1.0)
    T = np.where(inside, T, np.nan)
    duv = np.where(inside, duv, np.nan)
    return CCT(T.reshape(shape), duv.reshape(shape))


def xy_from_cct(cct_K, duv=0.0, observer=DEFAULT_OBSERVER) -> np.ndarray:
    """Chromaticity of a colour temperature, on the Planckian locus or Duv away from it.

    Parameters
    ----------
    cct_K : array_like, shape (...)
        Temperatures in kelvin, 1 000-100 000 K.
    duv : array_like, default 0.0
        Signed distance from the locus in the CIE 1960 diagram (positive toward green),
        broadcast against ``cct_K``.
    observer : str, default DEFAULT_OBSERVER
        Observer for the Planckian locus (default CIE 1931 2°).

    Returns
    -------
    ndarray, shape (..., 2)
        (x, y) computed directly from Planck's law and the observer (no table).

    Raises
    ------
    ColorimetryError
        For a temperature that is not finite or outside 1 000–100 000 K, or an unknown observer.

    References
    ----------
    CIE 015:2018 §9.5 (Planckian locus in the CIE 1960 UCS diagram, Duv).

    Examples
    --------
    >>> xy_from_cct(6504).round(4)
    array([0.3135, 0.3236])
    """
    T = real_array(cct_K, "cct_K", "temperatures in kelvin")
    if not np.all(np.isfinite(T)) or np.any((T < _T_MIN_K) | (T > _T_MAX_K)):
        raise ColorimetryError(
            f"cct_K must be finite temperatures between {_T_MIN_K:g} and {_T_MAX_K:g} K; "
            f"got {cct_K!r:.80}"
        )
    duv = real_array(duv, "duv", "distances from the Planckian locus", finite=True)
    try:
        T, duv = np.broadcast_arrays(T, duv)
    except ValueError:
        raise ColorimetryError(f"cct_K, duv: shapes {T.shape} and {duv.shape} do not broadcast") from None
    canonical = canonical_observer_name(observer)
    flat = T.reshape(-1)
    step = 1e-4  # relative; central difference for the locus direction
    uv = _planck_uv(flat, canonical)
    tangent = _planck_uv(flat * (1 + step), canonical) - _planck_uv(flat * (1 - step), canonical)
    tangent /= np.hypot(tangent[:, 0], tangent[:, 1])[:, None]
    # normal pointing to larger v (toward green): tangent runs right to left with T
    normal = np.stack([tangent[:, 1], -tangent[:, 0]], axis=-1)
    normal *= np.sign(normal[:, 1:2])
    uv = uv + duv.reshape(-1, 1) * normal
    return xy_from_uv_1960(uv).reshape(*T.shape, 2)
