"""Observers and illuminants sampled on a summation grid: the ingredients of weight matrices.

Shared by :mod:`spectrocolor.colorimetry` (summation and 1 nm weights) and
:mod:`spectrocolor.astm_e308` (ASTM E2022 weights). Never extrapolates.
"""

from __future__ import annotations

import numpy as np

from .errors import ColorimetryError, SpectrumError
from .illuminants import resolve_illuminant
from .interpolation import resample_linear
from .observers import resolve_observer as resolve_observer_value
from .spectrum import Spectrum


def interval_weights_nm(wavelengths_nm: np.ndarray) -> np.ndarray:
    """Δλ for each sample: the constant step on a uniform grid, else half the span to the neighbours.

    Parameters
    ----------
    wavelengths_nm : numpy.ndarray, shape (K,)
        A validated, strictly increasing grid, nm.

    Returns
    -------
    numpy.ndarray, shape (K,)
        Δλ per sample, nm (trapezoidal weights on an irregular grid; 1 for a single sample).

    Examples
    --------
    >>> import numpy as np
    >>> interval_weights_nm(np.array([400.0, 410.0, 430.0])).tolist()
    [5.0, 15.0, 10.0]
    """
    steps = np.diff(wavelengths_nm)
    if steps.size == 0:
        return np.ones(1)
    if np.allclose(steps, steps[0], rtol=1e-9, atol=0):
        return np.full(wavelengths_nm.size, float(steps[0]))
    delta = np.empty(wavelengths_nm.size)
    delta[0], delta[-1] = steps[0] / 2, steps[-1] / 2
    delta[1:-1] = (steps[:-1] + steps[1:]) / 2
    return delta


def resolve_observer(observer) -> tuple[str, Spectrum]:
    """(label, colour-matching functions) for a name/alias, a user's (3, K) Spectrum or an Observer.

    A thin wrapper over :func:`spectrocolor.observers.resolve_observer`, the one observer
    resolver, for callers that want the pair.

    Parameters
    ----------
    observer : str, Spectrum or Observer
        The observer, in any form or resolved; see :term:`observer`.

    Returns
    -------
    tuple of (str, Spectrum)
        The canonical name (``"custom observer"`` for a Spectrum) and the functions.

    Raises
    ------
    ColorimetryError
        For an unknown name or a Spectrum that is not (3, K).

    Examples
    --------
    >>> name, cmfs = resolve_observer("10deg")
    >>> name, cmfs.values.shape
    ('CIE 1964 10°', (3, 471))
    """
    resolved = resolve_observer_value(observer)
    return resolved.name, resolved.cmfs()


def cmfs_on(grid: np.ndarray, observer) -> np.ndarray:
    """The observer's x̄, ȳ, z̄ interpolated linearly at ``grid`` (nm), shape (K, 3); never extrapolated.

    Parameters
    ----------
    grid : numpy.ndarray, shape (K,)
        The summation grid, nm.
    observer : str, Spectrum or Observer
        As :func:`spectrocolor.observers.resolve_observer` (public callers pass the resolved value).

    Returns
    -------
    numpy.ndarray, shape (K, 3)
        x̄, ȳ, z̄ at the grid.

    Raises
    ------
    ColorimetryError
        For a grid reaching outside the observer's table.

    Examples
    --------
    >>> import numpy as np
    >>> cmfs_on(np.array([555.0]), "1931").round(4).tolist()
    [[0.5121, 1.0, 0.0057]]
    """
    resolved = resolve_observer_value(observer)
    observer_name, cmfs = resolved.name, resolved.cmfs()
    try:
        table = resample_linear(cmfs.wavelengths_nm, cmfs.values, grid)  # (3, K), banded
    except SpectrumError:
        lo, hi = cmfs.wavelengths_nm[[0, -1]]
        raise ColorimetryError(
            f"wavelengths_nm: {grid[0]:g}–{grid[-1]:g} nm reaches outside the {observer_name} "
            f"observer's {lo:g}–{hi:g} nm; restrict the spectrum (Spectrum.restrict({lo:g}, {hi:g}))"
        ) from None
    return table.T  # (K, 3)


def illuminant_on(grid: np.ndarray, illuminant) -> np.ndarray:
    """Relative SPD (K,) at ``grid`` (nm) of an illuminant in any form of :func:`~.illuminants.resolve_illuminant`.

    A name (CIE, ``"blackbody:T"``, ``"D:T"``) is evaluated at ``grid``; a Spectrum must contain
    every grid sample (its own samples are used, never interpolated behind the caller's back).

    Parameters
    ----------
    grid : numpy.ndarray, shape (K,)
        The summation grid, nm.
    illuminant : str, float, Spectrum or Illuminant
        The light, not ``None`` (public callers pass the resolved value); see :term:`illuminant`.

    Returns
    -------
    numpy.ndarray, shape (K,)
        Relative SPD at the grid.

    Raises
    ------
    ColorimetryError
        For ``None``, an unknown illuminant, or a Spectrum without every grid sample.

    Examples
    --------
    >>> import numpy as np
    >>> illuminant_on(np.array([560.0, 600.0]), "D65").round(3).tolist()
    [100.0, 90.006]
    """
    light = resolve_illuminant(illuminant)
    if light is None:
        raise ColorimetryError("illuminant: weights for reflectances need an illuminant, got None (lights)")
    resolved = light.spectrum
    if resolved is None:  # a named light: evaluated (or interpolated) at the grid
        return light.spd(grid).values
    source = resolved.wavelengths_nm
    position = np.clip(np.searchsorted(source, grid), 0, source.size - 1)
    if not np.allclose(source[position], grid, rtol=0, atol=1e-9):
        raise ColorimetryError(
            "illuminant: its wavelengths do not include every sample of the summation grid "
            f"({grid[0]:g}–{grid[-1]:g} nm, K={grid.size}); resample it explicitly with "
            ".resample(wavelengths_nm) or pass a CIE illuminant by name"
        )
    return resolved.values[position]


def reflectance_weights(products: np.ndarray) -> np.ndarray:
    """Weights ``k S x̄ Δλ`` (K, 3) from the products ``S x̄ Δλ``, with k = 100 / Σ S ȳ Δλ.

    The CIE 015 normalisation for reflectance and transmittance factors: the perfect white
    (factor 1 everywhere) gets Y = 100.

    Parameters
    ----------
    products : numpy.ndarray, shape (K, 3)
        ``S(λ) x̄(λ) Δλ``, ``S ȳ Δλ``, ``S z̄ Δλ`` per sample.

    Returns
    -------
    numpy.ndarray, shape (K, 3)
        The weights, column 1 summing to 100.

    Raises
    ------
    ColorimetryError
        If ``Σ S ȳ Δλ`` is not positive.

    References
    ----------
    CIE 015:2018 §7.1 (the normalising constant k).

    Examples
    --------
    >>> import numpy as np
    >>> reflectance_weights(np.array([[1.0, 2.0, 3.0], [1.0, 2.0, 1.0]])).tolist()
    [[25.0, 50.0, 75.0], [25.0, 50.0, 25.0]]
    """
    white_Y = products[:, 1].sum()
    if not white_Y > 0:
        raise ColorimetryError(
            "illuminant: Σ S(λ) ȳ(λ) Δλ is not positive over the summation range; no luminance "
            "to normalise by"
        )
    return products * (100.0 / white_Y)
