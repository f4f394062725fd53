"""Reference illuminants of the colour rendering and colour fidelity indices, batched by CCT.

CIE 13.3 (colour rendering index): a Planckian radiator below 5000 K, a CIE daylight
illuminant from 5000 K up. CIE 224:2017 and ANSI/IES TM-30 (colour fidelity): a Planckian
radiator below 4000 K, CIE daylight above 5000 K, and in between a mixture of the two,
each first scaled to the same luminance (Y, CIE 1931 2°), with the daylight share
``(T − 4000 K) / 1000 K``.

The Planckian radiator uses c₂ = 1.4388 × 10⁻² m·K (the constant with which CIE 015 defines
the Planckian locus); the daylight illuminant of a CCT is S0 + M1 S1 + M2 S2 with M1, M2
rounded to three decimals and the 5 nm basis interpolated linearly (CIE 015:2018 §4.1.2, as
:func:`spectrocolor.daylight`), defined for 4000–25 000 K. Outside its range the reference is
NaN.

References
----------
CIE 13.3-1995 §5.2. CIE 224:2017 §4.2. ANSI/IES TM-30-20 §4.3. CIE 015:2018 §4.1.2, eqs.
(4.7)–(4.10).
"""

from __future__ import annotations

import numpy as np

from ..data_tables import load_table
from ..interpolation import interpolation_matrix
from ..radiators import C2_CIE_LOCUS_M_K, planck
from ..sampling import cmfs_on

#: Daylight series: CIE 015:2018 eqs. (4.7)–(4.8), defined for 4000 K ≤ T ≤ 25 000 K.
DAYLIGHT_RANGE_K = (4000.0, 25000.0)


def planckian_spd(cct_K, wavelengths_nm) -> np.ndarray:
    """Planckian radiators ``(..., K)`` at temperatures ``cct_K``, equal to 1 at 560 nm.

    Parameters
    ----------
    cct_K : array_like, shape (...)
        Temperatures, K.
    wavelengths_nm : array_like, shape (K,)
        The grid, nm.

    Returns
    -------
    numpy.ndarray, shape (..., K)
        Relative SPDs (c₂ = 1.4388e-2 m·K, as CIE 015 defines the Planckian locus).

    Examples
    --------
    >>> planckian_spd([2856.0], [560.0]).tolist()
    [[1.0]]
    """
    T = np.asarray(cct_K, dtype=float)[..., None]
    grid = np.asarray(wavelengths_nm, dtype=float)
    with np.errstate(invalid="ignore", over="ignore"):
        return planck(grid, T, C2_CIE_LOCUS_M_K) / planck(560.0, T, C2_CIE_LOCUS_M_K)


def daylight_spd(cct_K, wavelengths_nm) -> np.ndarray:
    """CIE daylight illuminants ``(..., K)`` of correlated colour temperatures ``cct_K``.

    The batched form of :func:`spectrocolor.daylight` (same rounding of M1, M2, same linear
    interpolation of the basis); NaN outside 4000–25 000 K.

    Parameters
    ----------
    cct_K : array_like, shape (...)
        Correlated colour temperatures, K.
    wavelengths_nm : array_like, shape (K,)
        The grid, nm.

    Returns
    -------
    numpy.ndarray, shape (..., K)
        Relative SPDs (100 near 560 nm, as the CIE tables).

    References
    ----------
    CIE 015:2018 §4.1.2.

    Examples
    --------
    >>> from spectrocolor import daylight
    >>> bool(np.allclose(daylight_spd([6504.0], [560.0]), daylight(6504.0, [560.0]).values))
    True
    """
    T = np.asarray(cct_K, dtype=float)
    inside = (T >= DAYLIGHT_RANGE_K[0]) & (T <= DAYLIGHT_RANGE_K[1])
    T = np.where(inside, T, np.nan)
    with np.errstate(invalid="ignore"):
        x = np.where(
            T <= 7000.0,
            -4.6070e9 / T**3 + 2.9678e6 / T**2 + 0.09911e3 / T + 0.244063,
            -2.0064e9 / T**3 + 1.9018e6 / T**2 + 0.24748e3 / T + 0.237040,
        )
        y = -3.000 * x**2 + 2.870 * x - 0.275
        m = 0.0241 + 0.2562 * x - 0.7341 * y
        m1 = np.round((-1.3515 - 1.7703 * x + 5.9114 * y) / m, 3)
        m2 = np.round((0.0300 - 31.4424 * x + 30.0717 * y) / m, 3)
    header, table = load_table("illuminants/D_series_basis.csv")
    grid = np.asarray(wavelengths_nm, dtype=float)
    s0, s1, s2 = table[:, 1:].T @ interpolation_matrix(table[:, 0], grid, "linear").T
    return s0 + m1[..., None] * s1 + m2[..., None] * s2


def cri_reference(cct_K, wavelengths_nm) -> np.ndarray:
    """CIE 13.3 reference illuminants ``(..., K)``: Planckian below 5000 K, daylight from 5000 K.

    Parameters
    ----------
    cct_K : array_like, shape (...)
        The test lights' CCTs, K.
    wavelengths_nm : array_like, shape (K,)
        The grid, nm.

    Returns
    -------
    numpy.ndarray, shape (..., K)
        Relative SPDs (each branch on its own scale; CIE 13.3 normalises later).

    References
    ----------
    CIE 13.3-1995 (choice of the reference illuminant).

    Examples
    --------
    >>> cri_reference([4000.0], [560.0]).tolist()
    [[1.0]]
    """
    T = np.asarray(cct_K, dtype=float)
    below = (T < 5000.0)[..., None]
    return np.where(below, planckian_spd(T, wavelengths_nm), daylight_spd(T, wavelengths_nm))


def fidelity_reference(cct_K, wavelengths_nm) -> np.ndarray:
    """CIE 224:2017 / TM-30 reference illuminants ``(..., K)``, scaled to Y = 1 (CIE 1931 2°).

    Planckian up to 4000 K, daylight from 5000 K, and a mixture in proportion to the CCT in
    between.

    Parameters
    ----------
    cct_K : array_like, shape (...)
        The test lights' CCTs, K.
    wavelengths_nm : array_like, shape (K,)
        The grid, nm.

    Returns
    -------
    numpy.ndarray, shape (..., K)
        SPDs with ``Σ S ȳ Δλ = 1``.

    References
    ----------
    CIE 224:2017 (reference illuminant); ANSI/IES TM-30-20.

    Examples
    --------
    >>> from spectrocolor import wavelength_grid
    >>> grid = wavelength_grid(380, 780, 5)
    >>> S = fidelity_reference([4500.0], grid)
    >>> round(float((S @ cmfs_on(grid, "1931")[:, 1] * 5)[0]), 12)
    1.0
    """
    shape = np.shape(cct_K)
    T = np.asarray(cct_K, dtype=float).reshape(-1)
    grid = np.asarray(wavelengths_nm, dtype=float)
    V_delta = cmfs_on(grid, "1931")[:, 1] * np.gradient(grid)
    share = np.clip((T - 4000.0) / 1000.0, 0.0, 1.0)  # daylight share: 0 below 4000 K, 1 above 5000 K
    result = np.full((T.size, grid.size), np.nan)
    with np.errstate(invalid="ignore", divide="ignore"):
        planckian, daylight = share < 1.0, share > 0.0  # NaN temperatures are in neither
        if np.any(planckian):
            spd = planckian_spd(T[planckian], grid)
            result[planckian] = spd / (spd @ V_delta)[..., None]
        if np.any(daylight):
            spd = daylight_spd(T[daylight], grid)
            spd = spd / (spd @ V_delta)[..., None]
            weight = share[daylight][..., None]
            mixed = planckian[daylight]
            result[daylight] = np.where(mixed[..., None], (1.0 - weight) * result[daylight] + weight * spd, spd)
    return result.reshape(*shape, grid.size)
