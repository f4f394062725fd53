"""Tristimulus values: spectra → CIE XYZ as one matrix product with precomputed weights.

For a reflectance (or transmittance) factor ρ under an illuminant S, CIE 015 gives
``X = k Σ ρ(λ) S(λ) x̄(λ) Δλ`` with ``k = 100 / Σ S(λ) ȳ(λ) Δλ``, so the perfect white has
``Y = 100`` and Y is the luminance factor in percent (seed 001 §1.8, seed 003). Everything
that does not depend on ρ is folded into a weight matrix ``W`` (K × 3): ``XYZ = ρ @ W``.
Seed 001's Tables 40–42 are such weights (illuminant-weighted distribution coefficients).

Summation methods (the ``method`` argument):

``"sum"`` (default)
    Sum at the spectrum's own samples with the observer and illuminant taken at the same
    wavelengths. This is what seeds 001 and 003 do, what CIE 015 §7.1 describes for data at
    the tabulation interval, and it is exact for data measured at 1 nm. It is the default
    because it is the definition: no interpolation enters unless you ask for it.
``"1nm"``
    CIE 015's recommendation for coarser data: interpolate the spectrum linearly to 1 nm and
    sum with the 1 nm observer and illuminant. Interpolation is linear in ρ, so this is still
    a K × 3 matrix (``P.T @ W_1nm``) and costs nothing extra per spectrum.
``"astm-e308"``
    The industry route for 1, 5, 10 and 20 nm reflectance data: ASTM E308 Table 5 weights
    computed by ASTM E2022 (Lagrange interpolation to 1 nm folded into the weights, E308's
    range adjustment); reflectances only (an illuminant is required). See
    :mod:`spectrocolor.astm_e308`.
``"astm-e308-table6"`` (alias ``"astm-e308-uncorrected"``)
    ASTM E308 Table 6 weights for 10 or 20 nm data *not* corrected for the instrument's bandpass
    (triangular, equal to the interval): E308's Stearns & Stearns correction folded into the
    Table 5 weights. See :mod:`spectrocolor.bandpass`.

The cache holds weights per (grid, observer, illuminant name, method); weight arrays are
read-only.

References
----------
CIE 015:2018 *Colorimetry*, 4th ed., §7 (calculation of tristimulus values).
Wyszecki, G. & Stiles, W. S. (1982). *Color Science*, 2nd ed., p. 158–160.
"""

from __future__ import annotations

from functools import lru_cache

import numpy as np

from .astm_e308 import astm_e308_table6_weights, astm_e308_weights
from .errors import ColorimetryError
from .illuminants import Illuminant, resolve_illuminant
from .interpolation import interpolation_matrix
from .observers import DEFAULT_OBSERVER, Observer, resolve_observer
from .registry import Registry
from .sampling import (
    cmfs_on,
    illuminant_on,
    interval_weights_nm,
    reflectance_weights,
)
from .spectrum import Spectrum, validate_wavelengths

#: Maximum luminous efficacy of radiation for photopic vision, lm/W (CIE 015:2018 §7.1).
K_M_LM_PER_W = 683.0


def _sum_weights(grid: np.ndarray, observer, illuminant) -> np.ndarray:
    cmfs = cmfs_on(grid, observer)
    delta = interval_weights_nm(grid)
    if illuminant is None:
        return cmfs * delta[:, None]
    spd = illuminant_on(grid, illuminant)
    return reflectance_weights(cmfs * (spd * delta)[:, None])


def _one_nm_weights(grid: np.ndarray, observer, illuminant) -> np.ndarray:
    fine = np.arange(np.ceil(grid[0] - 1e-9), np.floor(grid[-1] + 1e-9) + 1.0)
    if fine.size < 2:
        raise ColorimetryError(f"method: '1nm' needs a range of at least 1 nm, got {grid[0]:g}–{grid[-1]:g} nm")
    if fine[0] != grid[0] or fine[-1] != grid[-1]:
        raise ColorimetryError(
            f"method: '1nm' needs a grid that starts and ends on whole nanometres, got {grid[0]:g}–{grid[-1]:g}"
        )
    projection = interpolation_matrix(grid, fine, "linear")  # (M, K)
    return projection.T @ _sum_weights(fine, observer, illuminant)


#: The summation methods: name → function (grid, observer, illuminant) → (K, 3) weights; the
#: functions take the resolved :class:`~spectrocolor.observers.Observer` and
#: :class:`~spectrocolor.illuminants.Illuminant` (or ``None`` for lights).
SUMMATION_METHODS = Registry("method", "a summation method")
SUMMATION_METHODS.add("sum", _sum_weights, "sum at the spectrum's own samples (the definition; seeds 001, 003)")
SUMMATION_METHODS.add("1nm", _one_nm_weights, "interpolate linearly to 1 nm, then sum (CIE 015's recommendation)")
SUMMATION_METHODS.add(
    "astm-e308", astm_e308_weights, "ASTM E308 Table 5 weights by ASTM E2022 (reflectances, uniform 1/5/10/20 nm)"
)
SUMMATION_METHODS.add(
    "astm-e308-table6",
    astm_e308_table6_weights,
    "ASTM E308 Table 6 weights: 10/20 nm data not corrected for a bandpass equal to the interval",
    aliases=("astm-e308-uncorrected",),
)
#: The summation method used when none is given.
DEFAULT_METHOD = "sum"


def _compute_weights(grid: np.ndarray, observer: Observer, illuminant: Illuminant | None, method: str) -> np.ndarray:
    result = np.ascontiguousarray(SUMMATION_METHODS.get(method)(grid, observer, illuminant))
    result.setflags(write=False)
    return result


@lru_cache(maxsize=256)
def _cached_weights(grid_key: bytes, observer: Observer, illuminant: Illuminant | None, method: str) -> np.ndarray:
    grid = np.frombuffer(grid_key, dtype=float)
    return _compute_weights(grid, observer, illuminant, method)


def resolved_weights(grid: np.ndarray, observer: Observer, illuminant: Illuminant | None, method: str) -> np.ndarray:
    """:func:`weights` for a validated grid and resolved values (cached for named ones).

    Parameters
    ----------
    grid : numpy.ndarray, shape (K,)
        A validated grid of at least two samples, nm.
    observer : Observer
        From :func:`spectrocolor.observers.resolve_observer`.
    illuminant : Illuminant or None
        From :func:`spectrocolor.illuminants.resolve_illuminant`.
    method : str
        A canonical name of :data:`SUMMATION_METHODS`.

    Returns
    -------
    numpy.ndarray
        Read-only (K, 3) weights.

    Examples
    --------
    >>> from spectrocolor import wavelength_grid
    >>> from spectrocolor.observers import resolve_observer
    >>> W = resolved_weights(wavelength_grid(400, 700, 10), resolve_observer("1931"), None, "sum")
    >>> W.shape
    (31, 3)
    """
    if observer.cacheable and (illuminant is None or illuminant.cacheable):
        return _cached_weights(grid.tobytes(), observer, illuminant, method)
    return _compute_weights(grid, observer, illuminant, method)


def weights(wavelengths_nm, *, observer=DEFAULT_OBSERVER, illuminant=None, method: str = DEFAULT_METHOD) -> np.ndarray:
    """Weight matrix ``W`` (K, 3) such that ``XYZ = values @ W``.

    Parameters
    ----------
    wavelengths_nm : array_like, shape (K,)
        The spectra's sampling grid, nm (must lie within the observer's range).
    observer : str, Spectrum or Observer, keyword-only
        Whose colour-matching functions the weights hold (default CIE 1931 2°); a Spectrum is used
        on its own samples; see :term:`observer`.
    illuminant : None, str, float, Spectrum or Illuminant, keyword-only
        ``None`` (default): the spectra are lights and ``W = x̄ȳz̄ · Δλ`` (relative units of the
        light); otherwise the light the reflectance or transmittance factors (0–1) are seen under,
        and ``W`` is normalised so the perfect white has ``Y = 100``; see :term:`illuminant`.
    method : str, keyword-only
        A name in :data:`SUMMATION_METHODS`: ``"sum"`` (default, summation at the given samples),
        ``"1nm"`` (linear interpolation to 1 nm, then summation) or ``"astm-e308"`` (ASTM
        E2022/E308 weighting factors for uniform 1, 5, 10 or 20 nm data, reflectances only); see
        the module docstring.

    Returns
    -------
    numpy.ndarray
        Read-only (K, 3) float64 array, cached per (grid, observer, named illuminant, method).

    Raises
    ------
    ColorimetryError
        For a grid outside the observer, an unknown observer, illuminant or method.

    Examples
    --------
    >>> from spectrocolor import wavelength_grid
    >>> W = weights(wavelength_grid(380, 780, 10), observer="1931", illuminant="D65")
    >>> round(float(W[:, 1].sum()), 9)
    100.0
    """
    grid = validate_wavelengths(wavelengths_nm)
    if grid.size < 2:
        raise ColorimetryError(
            f"wavelengths_nm: summation needs at least two samples (Δλ is undefined for one), got {grid.tolist()}"
        )
    method = SUMMATION_METHODS.canonical(method)
    return resolved_weights(grid, resolve_observer(observer), resolve_illuminant(illuminant), method)


def apply_weights(values, W: np.ndarray) -> np.ndarray:
    """``values @ W`` for spectra ``(..., K)`` and weights ``(K, 3)``: XYZ on the weights' scale.

    Float32 spectra are summed in float32 (``W`` cast down: half the memory traffic, ~1e-7
    relative rounding, for large cubes); every other dtype is summed in float64.

    Parameters
    ----------
    values : array_like, shape (..., K)
        Spectral values on the weights' grid.
    W : numpy.ndarray, shape (K, 3)
        Weights from :func:`weights`.

    Returns
    -------
    numpy.ndarray, shape (..., 3)
        XYZ on the weights' scale (XYZ100 for reflectances under an illuminant).

    Examples
    --------
    >>> import numpy as np
    >>> from spectrocolor import wavelength_grid
    >>> W = weights(wavelength_grid(400, 700, 10), illuminant="D65")
    >>> XYZ = apply_weights(np.ones((2, 31), np.float32), W)
    >>> XYZ.dtype.name, round(float(XYZ[0, 1]), 3)
    ('float32', 100.0)
    """
    values = np.asarray(values)
    if values.dtype == np.float32:
        return values @ W.astype(np.float32)
    return values.astype(np.float64, copy=False) @ W


def tristimulus(
    spectrum: Spectrum,
    *,
    observer=DEFAULT_OBSERVER,
    illuminant=None,
    method: str = DEFAULT_METHOD,
    k: float | str | None = None,
) -> np.ndarray:
    """CIE XYZ of spectra, shape ``(..., 3)``.

    Parameters
    ----------
    spectrum : Spectrum
        Spectra ``(..., K)``. With an illuminant: reflectance/transmittance factors (0–1) and the
        result is on the XYZ100 scale (perfect white Y = 100; Y is the luminance factor in %).
        Without (``illuminant=None``, the default): lights, summed as ``k Σ S x̄ Δλ``.
    observer : str or Spectrum, keyword-only
        As in :func:`weights` (default CIE 1931 2°).
    illuminant : None, str, float or Spectrum, keyword-only
        As in :func:`weights`; default ``None`` (the spectra are lights).
    method : str, keyword-only
        As in :func:`weights` (default ``"sum"``).
    k : None, float or "absolute", keyword-only
        Lights only: ``None`` or a number (default 1: relative units of the light) or
        ``"absolute"`` for 683 lm/W (spectral radiance in W·sr⁻¹·m⁻²·nm⁻¹ gives Y in cd/m²).

    Returns
    -------
    numpy.ndarray
        XYZ, shape ``spectrum.batch_shape + (3,)``. Float32 spectra are summed in float32 (for
        large cubes); everything else in float64. NaN in a spectrum gives NaN in its XYZ.

    Raises
    ------
    ColorimetryError
        For a non-Spectrum input, ``k`` with an illuminant, and as :func:`weights`.

    References
    ----------
    CIE 015:2018 §7.1 (tristimulus values by summation); seed 001 §1.8, seed 003.

    Examples
    --------
    >>> from spectrocolor import Spectrum, wavelength_grid
    >>> white = Spectrum.constant(1.0, wavelength_grid(380, 780, 5))
    >>> tristimulus(white, illuminant="D65").round(3).tolist()
    [95.043, 100.0, 108.88]
    """
    if not isinstance(spectrum, Spectrum):
        raise ColorimetryError(
            f"spectrum: expected a spectrocolor.Spectrum, got {type(spectrum).__name__}; "
            "wrap arrays as Spectrum(wavelengths_nm, values)"
        )
    if illuminant is not None and k is not None:
        raise ColorimetryError("k: only for lights; with an illuminant the scale is fixed by Y_white = 100")
    W = weights(spectrum.wavelengths_nm, observer=observer, illuminant=illuminant, method=method)
    XYZ = apply_weights(spectrum.values, W)
    if illuminant is None and k is not None:
        if k == "absolute":
            XYZ = XYZ * K_M_LM_PER_W
        elif isinstance(k, int | float) and np.isfinite(k):
            XYZ = XYZ * float(k)
        else:
            raise ColorimetryError(f"k: expected a finite number or 'absolute', got {k!r}")
    return XYZ


def white_point(
    illuminant, *, observer=DEFAULT_OBSERVER, wavelengths_nm=None, method: str = DEFAULT_METHOD
) -> np.ndarray:
    """XYZ100 of the perfect reflecting diffuser under ``illuminant``, shape (3,), Y = 100.

    Parameters
    ----------
    illuminant : str, float or Spectrum
        The light whose white is wanted, not ``None``; see :term:`illuminant`.
    observer : str or Spectrum, keyword-only
        As in :func:`weights` (default CIE 1931 2°).
    wavelengths_nm : array_like, optional, keyword-only
        The summation grid, nm. Default: the illuminant's own grid restricted to the observer's
        range and to 380–780 nm (for the CIE tables: 5 nm, 380–780 nm, the range of CIE 015:2018
        §7.2, which reproduces its published white points). A white for data on another grid should
        be summed on that grid: pass ``wavelengths_nm=data.wavelengths_nm``; see
        :term:`wavelength grid`.
    method : str, keyword-only
        As in :func:`weights`.

    Returns
    -------
    numpy.ndarray
        XYZ100 of the white, shape (3,).

    Raises
    ------
    ColorimetryError
        For ``illuminant=None`` (lights have no perfect white) and as :func:`weights`.

    References
    ----------
    CIE 015:2018 §7.2 (white points of the CIE illuminants).

    Examples
    --------
    >>> from spectrocolor import xy
    >>> xy(white_point("D65")).round(5).tolist()
    [0.31272, 0.32903]
    """
    light = resolve_illuminant(illuminant)
    if light is None:
        raise ColorimetryError(
            "illuminant: a white point needs an illuminant; None means lights, which have no perfect white"
        )
    viewer = resolve_observer(observer)
    if wavelengths_nm is None:
        spd = light.spd()
        lo, hi = viewer.cmfs().wavelengths_nm[[0, -1]]
        wavelengths_nm = spd.restrict(max(lo, 380.0), min(hi, 780.0)).wavelengths_nm
    W = weights(wavelengths_nm, observer=viewer, illuminant=light, method=method)
    return np.array(W.sum(axis=0))
