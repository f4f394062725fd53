"""Additive and subtractive mixing of spectral distributions, and complementary distributions.

Seed 002 (Sällström, SPECTRA) treats light as a vector in a linear space: superimposing two
fluxes adds their spectral distributions (*additive* mixing, "parallel composition"), passing a
flux through two filters multiplies it wavelength by wavelength by each transmittance
(*subtractive* mixing, "serial composition"), and two distributions are *complementary* when
they add up to the full constant distribution ``f(λ) ≡ f_max`` (setting 3: what is taken from
one is added to the other).

All functions work on arrays ``(..., K)`` sampled on one wavelength grid, or on the package's
:class:`~spectrocolor.Spectrum` (then every Spectrum must have the same grid, plain arrays given
with them must have its K samples, and the result is a Spectrum on that grid), on a scale
given by ``full``: ``full=1`` for reflectance or transmittance factors 0-1, ``full=30`` for
SPECTRA's bin levels 0-30. They broadcast like NumPy and never loop in Python.

References
----------
P. Sällström (1999), USIP Report 99-05, sections "Complementarity and circularity", "Serial
and parallel composition of light fluxes", settings 3 and 5, and "Some further demonstrations".
"""

from __future__ import annotations

import numpy as np

from .errors import SpectrumError
from .spectrum import Spectrum

__all__ = ["additive_mix", "subtractive_mix", "complement", "complementary_edit"]


def _grid_of(values, arguments) -> np.ndarray | None:
    """The one wavelength grid of the Spectra among ``values`` (None if there are none).

    Spectra on different grids are refused (mixing is wavelength by wavelength; nothing is
    resampled silently), and so are plain arrays whose last axis is not the grid's K.
    """
    grid, first = None, None
    for value, argument in zip(values, arguments, strict=True):
        if isinstance(value, Spectrum):
            if grid is None:
                grid, first = value.wavelengths_nm, argument
            elif value.wavelengths_nm.shape != grid.shape or not np.array_equal(value.wavelengths_nm, grid):
                raise SpectrumError(
                    f"{argument}: sampled at {value.wavelengths_nm[0]:g}–{value.wavelengths_nm[-1]:g} nm "
                    f"(K = {value.wavelengths_nm.size}), {first} at {grid[0]:g}–{grid[-1]:g} nm "
                    f"(K = {grid.size}); mixing is wavelength by wavelength: resample one onto the "
                    f"other's grid first, e.g. {argument}.resample({first}.wavelengths_nm)")
    if grid is not None:
        for value, argument in zip(values, arguments, strict=True):
            if not isinstance(value, Spectrum):
                shape = np.shape(value)
                if not shape or shape[-1] != grid.size:
                    raise SpectrumError(f"{argument}: an array mixed with Spectra needs their K = "
                                        f"{grid.size} samples on its last axis, got shape {shape}")
    return grid


def _wrapped(result: np.ndarray | float, grid: np.ndarray | None):
    """``result`` as a Spectrum on ``grid`` when the inputs were Spectra, else the array."""
    return result if grid is None else Spectrum(grid, result)


def _values(value, argument: str) -> np.ndarray:
    if isinstance(value, Spectrum):
        value = value.values
    try:
        a = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise SpectrumError(f"{argument}: expected numbers (..., K), got {value!r:.60}") from None
    if a.ndim == 0:
        raise SpectrumError(f"{argument}: expected an array of K samples (..., K), got a scalar")
    if not np.all(np.isfinite(a)):
        raise SpectrumError(f"{argument}: contains NaN or infinite values")
    return a


def _full(full) -> float:
    if isinstance(full, bool) or not isinstance(full, int | float) or not np.isfinite(full) \
            or full <= 0:
        raise SpectrumError(f"full: expected a positive number (1 for factors, 30 for SPECTRA "
                            f"levels), got {full!r}")
    return float(full)


def _within(a: np.ndarray, full: float, argument: str) -> np.ndarray:
    if a.size and (a.min() < 0 or a.max() > full * (1 + 1e-12)):
        raise SpectrumError(
            f"{argument}: values must lie in 0-{full:g} (the scale given by full), got "
            f"{a.min():.6g} to {a.max():.6g}")
    return a


def additive_mix(*distributions, weights=None) -> np.ndarray:
    """Superimpose lights: ``Σ w_i f_i(λ)`` (parallel composition, seed 002).

    Parameters
    ----------
    *distributions : array_like (..., K) or Spectrum
        Spectral distributions on one grid (any non-negative scale), broadcast together; Spectra
        must share their grid.
    weights : sequence of float, optional
        One non-negative factor per distribution (e.g. spotlight intensities); default 1 each.

    Returns
    -------
    ndarray (..., K) or Spectrum
        The spectral distribution of the superimposed lights, on the inputs' scale (a Spectrum
        on their grid when any input is a Spectrum).

    Raises
    ------
    SpectrumError
        For negative or non-finite values, shapes that do not broadcast, Spectra on different
        grids, or weights that are not one non-negative number per distribution.

    References
    ----------
    P. Sällström (1999), USIP Report 99-05, "Serial and parallel composition of light fluxes".

    Examples
    --------
    >>> additive_mix([0, 10, 20], [30, 20, 10]).tolist()
    [30.0, 30.0, 30.0]
    >>> additive_mix([1, 2], [3, 4], weights=[0.5, 2]).tolist()
    [6.5, 9.0]
    >>> from spectrocolor import illuminant, wavelength_grid
    >>> grid = wavelength_grid(380, 780, 5)
    >>> mixed = additive_mix(illuminant("D65", grid), illuminant("A", grid), weights=[1, 0.5])
    >>> type(mixed).__name__, mixed.values.shape
    ('Spectrum', (81,))
    """
    if not distributions:
        raise SpectrumError("distributions: give at least one spectral distribution")
    names = [f"distributions[{i}]" for i in range(len(distributions))]
    grid = _grid_of(distributions, names)
    arrays = [_values(d, name) for d, name in zip(distributions, names, strict=True)]
    for i, a in enumerate(arrays):
        if a.size and a.min() < 0:
            raise SpectrumError(f"distributions[{i}]: a light cannot be negative "
                                f"(minimum {a.min():.6g})")
    if weights is None:
        w = np.ones(len(arrays))
    else:
        w = _values(weights, "weights")
        if w.shape != (len(arrays),) or w.min() < 0:
            raise SpectrumError(
                f"weights: expected {len(arrays)} non-negative numbers, one per distribution, "
                f"got {np.asarray(weights).tolist()!r:.80}")
    try:
        stacked = np.broadcast_arrays(*arrays)
    except ValueError:
        raise SpectrumError(
            "distributions: shapes " + ", ".join(str(a.shape) for a in arrays)
            + " do not broadcast (they must share the grid of K samples)") from None
    return _wrapped(sum(float(wi) * a for wi, a in zip(w, stacked, strict=True)), grid)


def subtractive_mix(*transmittances, full: float = 1.0) -> np.ndarray:
    """Light through filters in series: the product of the transmittances (seed 002, setting 5).

    Each transmittance is a factor ``t(λ) / full``; the result is on the same scale:
    ``full · Π (t_i / full)``. With the illuminant as the first factor on its own scale and the
    filters after it, this is also "a coloured light on a coloured sample". The order does not
    matter (commuting operators, seed 002 "Equivalent visual situations").

    Parameters
    ----------
    *transmittances : array_like (..., K) or Spectrum
        Transmittances on the scale ``0..full``, on one grid, broadcast together; Spectra must
        share their grid.
    full : float
        The value that means "transmits everything": 1 for factors, 30 for SPECTRA's levels.

    Returns
    -------
    ndarray (..., K) or Spectrum
        ``full · Π (t_i / full)`` on the inputs' scale (a Spectrum on their grid when any input
        is a Spectrum).

    Raises
    ------
    SpectrumError
        For values outside ``0..full``, shapes that do not broadcast, or Spectra on different
        grids.

    References
    ----------
    P. Sällström (1999), USIP Report 99-05, setting 5 and "Equivalent visual situations".

    Examples
    --------
    Two SPECTRA filters at levels 15 and 30 in one bin, 30 and 0 in the next:

    >>> subtractive_mix([15, 30], [30, 0], full=30).tolist()
    [15.0, 0.0]
    >>> subtractive_mix([0.5, 0.8], [0.5, 0.5]).tolist()
    [0.25, 0.4]
    >>> from spectrocolor import Spectrum
    >>> subtractive_mix(Spectrum([400, 500], [0.5, 0.8]), [0.5, 0.5]).values.tolist()
    [0.25, 0.4]
    """
    f = _full(full)
    if not transmittances:
        raise SpectrumError("transmittances: give at least one transmittance")
    names = [f"transmittances[{i}]" for i in range(len(transmittances))]
    grid = _grid_of(transmittances, names)
    arrays = [_within(_values(t, name), f, name) for t, name in zip(transmittances, names, strict=True)]
    try:
        stacked = np.broadcast_arrays(*arrays)
    except ValueError:
        raise SpectrumError(
            "transmittances: shapes " + ", ".join(str(a.shape) for a in arrays)
            + " do not broadcast (they must share the grid of K samples)") from None
    out = stacked[0]
    for a in stacked[1:]:
        out = out * a
    return _wrapped(out / f ** (len(stacked) - 1), grid)


def complement(distribution, full: float = 1.0) -> np.ndarray:
    """The complementary distribution ``full − f(λ)``: the two add up to the full spectrum.

    Seed 002 ("Complementarity and circularity"): given a filter ``r(λ)``, the filter
    ``1 − r(λ)`` gives, superimposed with it, the colourless light of the unfiltered source.

    Parameters
    ----------
    distribution : array_like (..., K) or Spectrum
        Values on the scale ``0..full``.
    full : float
        The level of the full constant distribution (1 for factors, 30 for SPECTRA levels).

    Returns
    -------
    ndarray (..., K) or Spectrum
        ``full − f``, a Spectrum on the same grid when ``distribution`` is one.

    Examples
    --------
    >>> complement([0, 10, 30], full=30).tolist()
    [30.0, 20.0, 0.0]
    """
    f = _full(full)
    grid = _grid_of([distribution], ["distribution"])
    return _wrapped(f - _within(_values(distribution, "distribution"), f, "distribution"), grid)


def complementary_edit(left, right, index: int, level: float,
                       full: float | None = None) -> tuple[np.ndarray, np.ndarray]:
    """Set one bin of ``left`` and give the difference to ``right`` (SPECTRA setting 3).

    "What you take away from one of them is added to the other one": the sum of the pair at
    every bin is conserved. ``level`` is limited to what the pair's sum allows (0 to the
    sum), so both stay non-negative, and, when ``full`` is given, to what keeps both at or
    below ``full``.

    Parameters
    ----------
    left, right : array_like (K,)
        The pair of distributions (same scale, same grid).
    index : int
        The bin to edit (0..K-1; negative counts from the end, as in Python).
    level : float
        The new value of ``left[index]`` (clipped to ``0..left[index] + right[index]``).
    full : float, optional
        The top of the scale (30 for SPECTRA's levels): neither side may exceed it.

    Returns
    -------
    (left, right) : tuple of ndarray (K,)
        New arrays; the inputs are not changed.

    Examples
    --------
    >>> a, b = complementary_edit([30, 28], [0, 2], 1, 20)
    >>> a.tolist(), b.tolist()
    ([30.0, 20.0], [0.0, 10.0])
    >>> complementary_edit([10], [25], 0, 0, full=30)[0].tolist()   # right may not pass 30
    [5.0]
    """
    a = _values(left, "left").copy()
    b = _values(right, "right").copy()
    if a.ndim != 1 or a.shape != b.shape:
        raise SpectrumError(f"left and right: expected two 1-D arrays of the same length, got "
                            f"{a.shape} and {b.shape}")
    if min(a.min(), b.min()) < 0:
        raise SpectrumError("left and right: values must be non-negative")
    if isinstance(index, bool) or not isinstance(index, int | np.integer) \
            or not -a.size <= index < a.size:
        raise SpectrumError(f"index: expected an integer bin 0..{a.size - 1}, got {index!r}")
    if isinstance(level, bool) or not isinstance(level, int | float | np.number) \
            or not np.isfinite(level):
        raise SpectrumError(f"level: expected a finite number, got {level!r}")
    total = a[index] + b[index]
    low, high = 0.0, total
    if full is not None:
        f = _full(full)
        low, high = max(low, total - f), min(high, f)
    a[index] = min(max(float(level), low), high)
    b[index] = total - a[index]
    return a, b
