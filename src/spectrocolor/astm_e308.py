"""ASTM E308 tristimulus weights for 1, 5, 10 and 20 nm data, computed by ASTM E2022.

Industry computes XYZ from 10 nm or 20 nm reflectance data with the weighting-factor tables of
ASTM E308. Those tables are not a subsampling of the CIE 1 nm functions: ASTM E2022 builds them
so that summing ``R(λⱼ) Wⱼ`` over the measured wavelengths equals the 1 nm summation
``k Σ S(λ) x̄(λ) R̃(λ)`` of a reflectance ``R̃`` interpolated to 1 nm from the measured values.
Because that interpolation is linear in R, each 1 nm product ``S x̄`` is distributed onto the
measured wavelengths with the interpolation coefficients:

* inside the data, every 1 nm wavelength between two measured ones uses the cubic Lagrange
  polynomial through the four nearest measured wavelengths (two on each side);
* in the first and last measurement interval, the quadratic through the three end wavelengths
  (E2022 §7, "Lagrange interpolating coefficients" for inner and boundary intervals);
* ``k = 100 / Σ Wⱼ,ȳ``: the perfect white has Y = 100 (identical to ``100 / Σ S ȳ`` at 1 nm,
  as the Lagrange coefficients of each 1 nm wavelength sum to one).

**Illuminants at 1 nm.** E2022 needs ``S(λ)`` at every nanometre; the CIE tabulates most
illuminants at 5 nm. E308's printed white points are reproduced (within one unit of the third
decimal, tests/test_astm_e308.py) when A comes from its formula, D65 from CIE S 014-2's 1 nm table
(the linear interpolation of the 5 nm one) and C, D50, D55, D75 from the 5 nm tables by E2022's own
Lagrange scheme (cubic inside, quadratic at the ends) — the same interpolator E2022 applies to the
measured data. Linear interpolation of those 5 nm tables misses the printed white points by up to
0.06 (C, Z). See ``illuminant_at_1nm``.

**Which table.** :func:`astm_e308_weights` reproduces E308 **Table 5**: weights for spectral
data that have been corrected for the instrument's spectral bandpass (or were measured with a
bandpass narrow enough to need none); it is the table colour-science's
``tristimulus_weighting_factors_ASTME2022`` computes. :func:`astm_e308_table6_weights` gives
**Table 6**, for 10 and 20 nm data *not* corrected for bandpass, measured with a triangular
bandpass equal to the interval: E308's Stearns & Stearns correction (:mod:`spectrocolor.bandpass`)
is folded into the Table 5 weights of the same grid, ``W₆ = Bᵀ W₅``, so that uncorrected data
with Table 6 give exactly what Stearns–Stearns-corrected data give with Table 5. ``B`` keeps
column sums, so both tables have the same white point, as in E308. The numbering follows E308's
own introduction (Tables 5 are the 1985 tables; the 1994 revision added the reduction of the
bandpass dependence), Westland et al. (2012) §4.8.3 ("since ASTM Table 5 is used it is assumed
that the reflectance data have been corrected for the spectral bandpass") and the OptProp
toolbox's ``roo2xyz`` ("uncompensated": Table 6).

**Range.** Weights are computed over E308's reference range, 360–780 nm (widened to the data's
range when the data extend beyond it, and narrowed to where the observer and illuminant are
defined), on the data's own interval, then shortened to the measured range as E308 prescribes:
the weights of unmeasured wavelengths are added to the weights of the shortest and longest
measured wavelength (this amounts to assuming the reflectance stays constant beyond the data).
1 nm wavelengths of the reference range that fall beyond the last whole interval (for example
360–364 nm when the data are at 10 nm from 405 nm) go to the end weight in the same way.

**Not provided:** E308's alternatives for 5 nm data (plain summation, spectrocolor's
``method="sum"``) and for 20 nm data (interpolating the data to 10 nm first).

References
----------
ASTM E2022-11, *Standard Practice for Calculation of Weighting Factors for Tristimulus
Integration*, §7 (weights from 1 nm data with Lagrange interpolation of the measured data).
ASTM E308-17, *Standard Practice for Computing the Colors of Objects by Using the CIE System*,
§7 (tristimulus integration with weights; Tables 5 and 6; adjustment of weights to a shorter
range); the introduction of ASTM E308-22 (history of Tables 5 and 6).
Westland, S., Ripamonti, C. & Cheung, V. (2012). *Computational Colour Science Using MATLAB*,
2nd ed., Wiley, §4.5–4.6 and §4.8.3.
"""

from __future__ import annotations

import numpy as np

from .bandpass import stearns_stearns_matrix
from .errors import ColorimetryError
from .illuminants import resolve_illuminant
from .observers import resolve_observer
from .sampling import cmfs_on, illuminant_on, reflectance_weights
from .spectrum import validate_wavelengths

#: Measurement intervals for which ASTM E308 gives (and E2022 computes) weights, nm.
INTERVALS_NM = (1, 5, 10, 20)
#: Measurement intervals for which ASTM E308 tabulates Table 6 (bandpass included) weights, nm.
TABLE6_INTERVALS_NM = (10, 20)
#: Wavelength range of the ASTM E308 weighting tables, nm.
REFERENCE_RANGE_NM = (360.0, 780.0)


def _validated_grid(wavelengths_nm) -> tuple[np.ndarray, int]:
    """The data grid and its interval; uniform, 1/5/10/20 nm, starting and ending on whole nm."""
    grid = validate_wavelengths(wavelengths_nm)
    if grid.size < 2:
        raise ColorimetryError("wavelengths_nm: ASTM E308 weights need at least two measured wavelengths")
    steps = np.diff(grid)
    step = round(float(steps[0]))
    if not np.allclose(steps, step, rtol=0, atol=1e-9) or step not in INTERVALS_NM:
        found = np.unique(np.round(steps, 6))[:4]
        raise ColorimetryError(
            f"wavelengths_nm: ASTM E308 weights need a uniform interval of 1, 5, 10 or 20 nm, got steps "
            f"{', '.join(f'{s:g}' for s in found)} nm; resample the data or use method 'sum' or '1nm'"
        )
    if not np.allclose(grid[[0, -1]], np.round(grid[[0, -1]]), rtol=0, atol=1e-9):
        raise ColorimetryError(
            f"wavelengths_nm: ASTM E308 weights need a grid that starts and ends on whole nanometres, "
            f"got {grid[0]:g}–{grid[-1]:g} nm"
        )
    return np.round(grid), step


def _illuminant_extent(illuminant) -> tuple[float, float]:
    """Wavelength range on which the illuminant is defined, nm (formulas — A, blackbodies — everywhere)."""
    light = resolve_illuminant(illuminant)
    if light is None:
        raise ColorimetryError(
            "illuminant: ASTM E308 weights are for reflectance or transmittance factors and need an "
            "illuminant (a CIE name such as 'D65', 'blackbody:T', or a Spectrum at 1 nm), got None"
        )
    if light.by_formula:
        return -np.inf, np.inf
    native = light.spd().wavelengths_nm
    return float(native[0]), float(native[-1])


def _reference_range(grid: np.ndarray, observer, illuminant) -> tuple[float, float]:
    """E308's 360–780 nm, widened to the data, within the observer's and illuminant's range."""
    viewer = resolve_observer(observer)
    observer_name, cmfs = viewer.name, viewer.cmfs()
    defined_lo = max(np.ceil(cmfs.wavelengths_nm[0]), _illuminant_extent(illuminant)[0])
    defined_hi = min(np.floor(cmfs.wavelengths_nm[-1]), _illuminant_extent(illuminant)[1])
    if grid[0] < defined_lo or grid[-1] > defined_hi:
        raise ColorimetryError(
            f"wavelengths_nm: {grid[0]:g}–{grid[-1]:g} nm reaches outside {defined_lo:g}–{defined_hi:g} nm, "
            f"where the {observer_name} observer and the illuminant are both defined; restrict the "
            f"spectrum (Spectrum.restrict({defined_lo:g}, {defined_hi:g})), or pass the illuminant as a 1 nm "
            "Spectrum that covers the data (e.g. a lamp measured from 360 nm)"
        )
    lo = min(grid[0], max(REFERENCE_RANGE_NM[0], defined_lo))
    hi = max(grid[-1], min(REFERENCE_RANGE_NM[1], defined_hi))
    return float(lo), float(hi)


def _lagrange_basis(t: np.ndarray, count: int) -> np.ndarray:
    """Lagrange basis polynomials on the nodes 0, 1, …, count − 1 evaluated at ``t``: (M, count)."""
    nodes = np.arange(count, dtype=float)
    basis = np.ones((t.size, count))
    for k in range(count):
        for m in range(count):
            if m != k:
                basis[:, k] *= (t - nodes[m]) / (nodes[k] - nodes[m])
    return basis


def lagrange_matrix(reference_nm: np.ndarray, fine_nm: np.ndarray) -> np.ndarray:
    """(M, N) matrix taking values at the uniform ``reference_nm`` to ASTM E2022's 1 nm estimates.

    Cubic Lagrange through the two neighbours on each side inside, quadratic through the three
    end wavelengths in the first and last interval; fine wavelengths beyond the reference grid
    take the end value.

    Parameters
    ----------
    reference_nm : numpy.ndarray, shape (N,)
        Uniform reference wavelengths, nm (N >= 3).
    fine_nm : numpy.ndarray, shape (M,)
        Target wavelengths, nm (normally whole nanometres).

    Returns
    -------
    numpy.ndarray, shape (M, N)
        Interpolation weights; each row sums to 1.

    References
    ----------
    ASTM E2022-11 §7 (Lagrange interpolation).

    Examples
    --------
    >>> import numpy as np
    >>> P = lagrange_matrix(np.arange(400.0, 431.0, 10.0), np.array([405.0, 415.0]))
    >>> (P + 0.0).round(4).tolist()  # quadratic in the first interval, cubic inside
    [[0.375, 0.75, -0.125, 0.0], [-0.0625, 0.5625, 0.5625, -0.0625]]
    """
    N = reference_nm.size
    step = reference_nm[1] - reference_nm[0]
    position = (fine_nm - reference_nm[0]) / step
    matrix = np.zeros((fine_nm.size, N))
    matrix[position < 0, 0] = 1.0
    matrix[position > N - 1, N - 1] = 1.0
    inside = np.flatnonzero((position >= 0) & (position <= N - 1))
    interval = np.clip(np.floor(position[inside]).astype(int), 0, N - 2)
    boundary = (interval == 0) | (interval == N - 2)
    for rows, first, count in (
        (inside[~boundary], interval[~boundary] - 1, 4),
        (inside[boundary], np.where(interval[boundary] == 0, 0, N - 3), 3),
    ):
        basis = _lagrange_basis(position[rows] - first, count)
        matrix[rows[:, None], first[:, None] + np.arange(count)] = basis
    return matrix


def illuminant_at_1nm(fine_nm: np.ndarray, illuminant) -> np.ndarray:
    """Relative SPD at the whole nanometres ``fine_nm``, as ASTM E308 builds its 1 nm illuminants.

    * ``"A"``: CIE 015's defining formula (exact at any wavelength).
    * ``"D65"``: linear interpolation of the 5 nm table: this reproduces CIE S 014-2's official
      1 nm D65 table, which E308 uses.
    * every other named table (C, D50, D55, D75, FL…, LED…; 5 nm): ASTM E2022's Lagrange
      interpolation (:func:`lagrange_matrix`: cubic through the four nearest 5 nm values, quadratic
      in the end intervals). Linear interpolation misses E308's printed white points by up to
      0.06 (C, Z); this scheme meets them within one unit of the printed third decimal for
      C, D50, D55 and D75.
    * a :class:`Spectrum`: its own samples, which must include every wavelength of ``fine_nm``.

    Parameters
    ----------
    fine_nm : numpy.ndarray, shape (M,)
        Whole-nanometre wavelengths.
    illuminant : str or Spectrum
        A CIE name or a Spectrum containing every wavelength of ``fine_nm``.

    Returns
    -------
    numpy.ndarray, shape (M,)
        Relative SPD (100 at 560 nm for the CIE tables).

    Raises
    ------
    ColorimetryError
        For wavelengths outside a table, or a Spectrum that lacks some of them.

    References
    ----------
    ASTM E2022-11 §7 (Lagrange interpolation to 1 nm); CIE S 014-2/E:2006 (1 nm D65).

    Examples
    --------
    >>> import numpy as np
    >>> illuminant_at_1nm(np.array([560.0, 561.0]), "D65").round(4).tolist()
    [100.0, 99.6334]
    """
    light = resolve_illuminant(illuminant)
    if light is not None and light.tabulated and light.name != "D65":
        table = light.spd()
        lo, hi = table.wavelengths_nm[[0, -1]]
        if fine_nm[0] < lo or fine_nm[-1] > hi:
            raise ColorimetryError(f"illuminant: {light.name} is tabulated at {lo:g}–{hi:g} nm only")
        return lagrange_matrix(table.wavelengths_nm, fine_nm) @ table.values
    return illuminant_on(fine_nm, light)


def astm_e308_weights(wavelengths_nm: np.ndarray, observer, illuminant) -> np.ndarray:
    """ASTM E308 Table 5 weights (K, 3) for reflectance data on ``wavelengths_nm``, by ASTM E2022.

    ``XYZ100 = R @ W`` for reflectance or transmittance factors ``R`` (0–1) measured at
    ``wavelengths_nm``; the perfect white (R = 1) has Y = 100. See the module docstring for the
    procedure, the table reproduced (Table 5: no bandpass correction in the weights; correct the
    data for bandpass first if your instrument does not) and the range adjustment.

    Parameters
    ----------
    wavelengths_nm : array_like, shape (K,)
        The measured wavelengths, nm: uniform with an interval of 1, 5, 10 or 20 nm, starting and
        ending on whole nanometres, within the observer's and illuminant's range; see
        :term:`wavelength grid`.
    observer : str or Spectrum
        The observer of the table; a (3, K) :class:`Spectrum` is used at 1 nm, interpolated linearly
        if needed; see :term:`observer`.
    illuminant : str or Spectrum
        The light of the table: a CIE name (evaluated at 1 nm by ``illuminant_at_1nm``: A from its
        formula, D65 linearly as CIE's 1 nm table, the other 5 nm tables by E2022's Lagrange scheme)
        or a :class:`Spectrum` that includes every whole nanometre of the reference range (normally
        360–780 nm; a Spectrum defined on a shorter range shortens the reference range to it, as for
        the CIE FL illuminants, which start at 380 nm); see :term:`illuminant`.

    Returns
    -------
    numpy.ndarray
        (K, 3) float64 weights for X, Y, Z; ``W[:, 1].sum() == 100`` to rounding.

    Raises
    ------
    ColorimetryError
        For an interval other than 1, 5, 10, 20 nm, a non-uniform grid, ends that are not whole
        nm, data outside the observer's or illuminant's range, a missing illuminant, or an
        illuminant Spectrum without 1 nm values over the reference range.

    References
    ----------
    ASTM E2022-11 §7; ASTM E308-17 §7 and Table 5.

    Examples
    --------
    >>> from spectrocolor import wavelength_grid
    >>> W = astm_e308_weights(wavelength_grid(400, 700, 10), "1931", "D65")
    >>> W.shape, round(float(W[:, 1].sum()), 9)
    ((31, 3), 100.0)
    """
    grid, step = _validated_grid(wavelengths_nm)
    observer = resolve_observer(observer)  # once: the helpers below take the resolved values
    illuminant = resolve_illuminant(illuminant)
    lo, hi = _reference_range(grid, observer, illuminant)
    below = int((grid[0] - lo) // step)  # reference wavelengths below the data
    above = int((hi - grid[-1]) // step)
    reference = np.arange(grid[0] - below * step, grid[-1] + above * step + step / 2, step)
    fine = np.arange(lo, hi + 0.5)
    try:
        spd = illuminant_at_1nm(fine, illuminant)
    except ColorimetryError as exc:
        raise ColorimetryError(
            f"{exc}. ASTM E2022 weights need the illuminant at every 1 nm from {lo:g} to {hi:g} nm"
        ) from None
    products = cmfs_on(fine, observer) * spd[:, None]  # S x̄, S ȳ, S z̄ at 1 nm (Δλ = 1 nm)
    reference_weights = reflectance_weights(lagrange_matrix(reference, fine).T @ products)
    # E308 range adjustment: unmeasured wavelengths' weights go to the end measured wavelengths.
    result = reference_weights[below : below + grid.size].copy()
    result[0] += reference_weights[:below].sum(axis=0)
    result[-1] += reference_weights[below + grid.size :].sum(axis=0)
    return result


def astm_e308_table6_weights(wavelengths_nm: np.ndarray, observer, illuminant) -> np.ndarray:
    """ASTM E308 Table 6 weights (K, 3): 10 or 20 nm data NOT corrected for the instrument's bandpass.

    For an instrument whose triangular bandpass equals its measurement interval (e.g. 10 nm data
    from a 10 nm bandpass) whose data have not been bandpass-corrected. E308's Stearns & Stearns
    correction ``B`` (:func:`spectrocolor.bandpass.stearns_stearns_matrix`, end rules at the first
    and last *measured* wavelength) is folded into the Table 5 weights of the same grid:
    ``W₆ = Bᵀ W₅``, hence ``R @ W₆ == (B @ R) @ W₅`` for every reflectance ``R``. Columns of ``B``
    sum to one, so the white point is Table 5's.

    Parameters
    ----------
    wavelengths_nm : array_like, shape (K,)
        The measured wavelengths, nm: uniform 10 or 20 nm (the intervals E308 gives Table 6 for),
        otherwise as for :func:`astm_e308_weights`; see :term:`wavelength grid`.
    observer : str or Spectrum
        As for :func:`astm_e308_weights`.
    illuminant : str or Spectrum
        As for :func:`astm_e308_weights`.

    Returns
    -------
    numpy.ndarray
        (K, 3) float64 weights for X, Y, Z; ``W[:, 1].sum() == 100`` to rounding.

    Raises
    ------
    ColorimetryError
        For an interval other than 10 or 20 nm, and everything :func:`astm_e308_weights` refuses.

    References
    ----------
    ASTM E308-17, Tables 5 and 6 and the bandpass correction (Stearns & Stearns, α = 0.083);
    ASTM E2022-11 (weights for data not corrected for bandpass).

    Examples
    --------
    >>> from spectrocolor import wavelength_grid
    >>> W6 = astm_e308_table6_weights(wavelength_grid(400, 700, 10), "1931", "D65")
    >>> W5 = astm_e308_weights(wavelength_grid(400, 700, 10), "1931", "D65")
    >>> bool(np.allclose(W6.sum(axis=0), W5.sum(axis=0), rtol=1e-13)), round(float(W6[13, 1] - W5[13, 1]), 3)
    (True, 0.072)
    """
    grid, step = _validated_grid(wavelengths_nm)
    if step not in TABLE6_INTERVALS_NM:
        raise ColorimetryError(
            f"wavelengths_nm: ASTM E308 Table 6 (bandpass included) is for 10 or 20 nm data, got {step} nm; "
            "for other intervals correct the data with bandpass_correction(...) if needed and use 'astm-e308'"
        )
    return stearns_stearns_matrix(grid.size).T @ astm_e308_weights(grid, observer, illuminant)
