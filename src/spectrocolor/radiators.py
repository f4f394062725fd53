"""Planckian radiators and the CIE daylight series: the formulas behind the lights that have one.

:func:`planck` is Planck's law on any grid; :func:`blackbody` a Planckian radiator normalised at
560 nm; illuminant A is a blackbody with CIE 015's own c₂ and temperature; :func:`daylight_xy`
and :func:`daylight` are the CIE daylight locus and the D series of any correlated colour
temperature. :mod:`spectrocolor.illuminants` names these lights (``"blackbody:T"``, ``"D:T"``,
``"A"``) and resolves them; this module only evaluates them.

References
----------
CIE 015:2018 *Colorimetry*, 4th ed.: §4.1 and Table 5 (illuminant A formula with
c₂ = 1.435 × 10⁻² m·K), §4.1.2 and Table 6 (daylight basis S0, S1, S2 and the xD, yD, M1, M2
formulae). CODATA 2018 (second radiation constant c₂ = 1.438 776 877 × 10⁻² m·K).
"""

from __future__ import annotations

import numpy as np

from .arguments import real_number
from .data_tables import load_table
from .errors import ColorimetryError, SpectrumError
from .spectrum import Spectrum, validate_wavelengths, wavelength_grid

__all__ = [
    "C2_CODATA_M_K", "C2_CIE_LOCUS_M_K", "C2_ILLUMINANT_A_M_K", "ILLUMINANT_A_TEMPERATURE_K",
    "planck", "blackbody", "daylight_xy", "daylight", "illuminant_A_values",
]

#: Second radiation constant, CODATA 2018, m·K.
C2_CODATA_M_K = 1.438776877e-2
#: Second radiation constant with which CIE 015:2018 defines the Planckian locus (correlated
#: colour temperature), m·K.
C2_CIE_LOCUS_M_K = 1.4388e-2
#: Second radiation constant used in the definition of CIE illuminant A, m·K.
C2_ILLUMINANT_A_M_K = 1.435e-2
#: Temperature in the defining formula of illuminant A (with c₂ = 1.435e-2 m·K; this is the
#: 2856 K Planckian radiator of the ITS-68/CODATA constant c₂ = 1.4388e-2 m·K).
ILLUMINANT_A_TEMPERATURE_K = 2848.0


def _grid_or_default(wavelengths_nm, default: tuple[float, float, float]) -> np.ndarray:
    if wavelengths_nm is None:
        return wavelength_grid(*default)
    return validate_wavelengths(wavelengths_nm)


def planck(wavelengths_nm, temperature_K, c2_m_K: float) -> np.ndarray:
    """Relative Planck spectral radiance ``1 / (λ⁵ (exp(c₂/λT) − 1))`` with λ in m, arbitrary scale.

    ``wavelengths_nm`` and ``temperature_K`` broadcast against each other (e.g. (K,) and (N, 1)).

    Parameters
    ----------
    wavelengths_nm : array_like
        Wavelengths, nm.
    temperature_K : array_like
        Temperatures, K.
    c2_m_K : float
        Second radiation constant c₂, m·K (e.g. :data:`C2_CODATA_M_K`).

    Returns
    -------
    numpy.ndarray
        The broadcast shape; proportional to spectral radiance (the constant ``2hc²`` omitted).

    Examples
    --------
    >>> p = planck([400.0, 560.0, 700.0], 6504.0, C2_CODATA_M_K)
    >>> (100 * p / p[1]).round(3).tolist()  # as blackbody(6504, [400, 560, 700])
    [109.067, 100.0, 73.951]
    """
    wavelength_m = np.asarray(wavelengths_nm, dtype=float) * 1e-9
    return 1.0 / (wavelength_m**5 * np.expm1(c2_m_K / (wavelength_m * temperature_K)))


def blackbody(
    temperature_K: float,
    wavelengths_nm=None,
    normalise_at_nm: float = 560.0,
    c2_m_K: float = C2_CODATA_M_K,
) -> Spectrum:
    """Planckian radiator at ``temperature_K``, relative SPD equal to 100 at ``normalise_at_nm``.

    Defaults: 360–830 nm at 1 nm and the CODATA 2018 second radiation constant. CIE 015 defines
    the Planckian locus for correlated colour temperature with c₂ = 1.4388e-2 m·K (pass
    ``c2_m_K=C2_CIE_LOCUS_M_K`` to match it; the two differ by 1.6e-5 in temperature). Seed 000
    (Zawischa) lights its soap films with ``blackbody(6504)``.

    Parameters
    ----------
    temperature_K : float
        Temperature of the radiator, K (positive).
    wavelengths_nm : array_like, shape (K,), optional
        The grid, nm; default 360–830 nm at 1 nm.
    normalise_at_nm : float, default 560.0
        Wavelength at which the SPD is 100, nm.
    c2_m_K : float, default C2_CODATA_M_K
        Second radiation constant c₂, m·K (1.438776877e-2, CODATA 2018).

    Returns
    -------
    Spectrum
        Relative spectral power ``100 · M(λ, T) / M(normalise_at_nm, T)`` (Planck's law),
        dimensionless, named ``"blackbody"``.

    Raises
    ------
    ColorimetryError
        For a temperature that is not a positive number, or one so low that the ratio
        overflows on the grid.

    References
    ----------
    CIE 015:2018 §4.1 (Planckian radiators; illuminant A); CODATA 2018 for c₂.

    Examples
    --------
    >>> blackbody(6504, [400, 560, 700]).values.round(3).tolist()
    [109.067, 100.0, 73.951]
    """
    if not (isinstance(temperature_K, int | float) and np.isfinite(temperature_K) and temperature_K > 0):
        raise ColorimetryError(f"temperature_K: expected a positive temperature in kelvin, got {temperature_K!r}")
    normalise_at_nm = real_number(normalise_at_nm, "normalise_at_nm", "a wavelength in nm",
                                  positive=True)
    grid = _grid_or_default(wavelengths_nm, (360.0, 830.0, 1.0))
    # the ratio in logarithms: at a few tens of kelvin both radiances underflow to 0 (0/0 = NaN)
    log_ratio = _log_planck(grid, temperature_K, c2_m_K) - _log_planck(
        np.array(normalise_at_nm, dtype=float), temperature_K, c2_m_K)
    with np.errstate(over="ignore"):
        values = 100.0 * np.exp(log_ratio)
    if not np.all(np.isfinite(values)):
        raise ColorimetryError(
            f"temperature_K, normalise_at_nm: a blackbody at {temperature_K:g} K relative to "
            f"{normalise_at_nm:g} nm exceeds the floating-point range on this grid; use a higher "
            "temperature or normalise at a longer wavelength")
    return Spectrum(grid, values, ("blackbody",))


def _log_planck(wavelengths_nm, temperature_K, c2_m_K: float) -> np.ndarray:
    """Natural logarithm of :func:`planck`, finite where the radiance itself under/overflows."""
    wavelength_m = np.asarray(wavelengths_nm, dtype=float) * 1e-9
    x = c2_m_K / (wavelength_m * temperature_K)
    return -5.0 * np.log(wavelength_m) - (x + np.log(-np.expm1(-x)))  # log(e^x - 1), stable


def illuminant_A_values(grid: np.ndarray) -> np.ndarray:
    """CIE 015:2018 eq. (4.1): S_A(λ) = 100 (560/λ)⁵ (e^{c₂/(560·2848)} − 1)/(e^{c₂/(λ·2848)} − 1)."""
    return blackbody(ILLUMINANT_A_TEMPERATURE_K, grid, c2_m_K=C2_ILLUMINANT_A_M_K).values


def daylight_xy(cct_K: float) -> np.ndarray:
    """Chromaticity (xD, yD) of the CIE daylight illuminant of correlated colour temperature ``cct_K``.

    CIE 015:2018 eqs. (4.7)–(4.9); valid for 4000 K ≤ T ≤ 25 000 K.

    Parameters
    ----------
    cct_K : float
        Correlated colour temperature, K, 4000–25000.

    Returns
    -------
    numpy.ndarray
        ``[xD, yD]``, CIE 1931 chromaticity, shape (2,).

    Raises
    ------
    ColorimetryError
        For a non-number or a temperature outside 4000–25000 K.

    References
    ----------
    CIE 015:2018 §4.1.2, eqs. (4.7)–(4.9).

    Examples
    --------
    >>> daylight_xy(6504).round(5).tolist()
    [0.31271, 0.32912]
    """
    if not isinstance(cct_K, int | float | np.number) or isinstance(cct_K, bool):
        raise ColorimetryError(f"cct_K: expected a temperature in kelvin (4000–25000), got {cct_K!r}")
    T = float(cct_K)
    if not 4000.0 <= T <= 25000.0:
        raise ColorimetryError(f"cct_K: the CIE daylight series is defined for 4000–25000 K, got {cct_K!r}")
    if T <= 7000.0:
        x = -4.6070e9 / T**3 + 2.9678e6 / T**2 + 0.09911e3 / T + 0.244063
    else:
        x = -2.0064e9 / T**3 + 1.9018e6 / T**2 + 0.24748e3 / T + 0.237040
    y = -3.000 * x**2 + 2.870 * x - 0.275
    return np.array([x, y])


def daylight(cct_K: float, wavelengths_nm=None, round_coefficients: bool = True) -> Spectrum:
    """CIE daylight illuminant of correlated colour temperature ``cct_K`` from S0, S1, S2.

    ``S(λ) = S0(λ) + M1 S1(λ) + M2 S2(λ)`` with M1, M2 from (xD, yD) (CIE 015:2018 eq. 4.10).
    With ``round_coefficients`` (default) M1 and M2 are rounded to three decimals, as the CIE
    did for the tabulated D50–D75; so ``daylight(6500 * 1.4388 / 1.4380)`` reproduces the D65
    table. The basis is tabulated at 5 nm (300–830 nm) and interpolated linearly.

    Parameters
    ----------
    cct_K : float
        Correlated colour temperature, K, 4000–25000.
    wavelengths_nm : array_like, shape (K,), optional
        The grid, nm, within 300–830 nm; default the basis's own 5 nm grid, 300–830 nm.
    round_coefficients : bool, default True
        Round M1 and M2 to three decimals (CIE practice for the tabulated D illuminants).

    Returns
    -------
    Spectrum
        Relative SPD (100 near 560 nm, like the CIE tables), named ``"D<cct_K>K"``.

    Raises
    ------
    ColorimetryError
        For a temperature outside 4000–25000 K or a grid outside 300–830 nm.

    References
    ----------
    CIE 015:2018 §4.1.2, eqs. (4.7)–(4.10) and Table 6 (S0, S1, S2).

    Examples
    --------
    >>> d65 = daylight(6500 * 1.4388 / 1.4380, [400, 560, 700])
    >>> d65.values.round(3).tolist()
    [82.755, 100.0, 71.609]
    >>> from spectrocolor.illuminants import illuminant
    >>> illuminant("D65", [400, 560, 700]).values.tolist()
    [82.7549, 100.0, 71.6091]
    """
    x, y = daylight_xy(cct_K)
    m = 0.0241 + 0.2562 * x - 0.7341 * y
    m1 = (-1.3515 - 1.7703 * x + 5.9114 * y) / m
    m2 = (0.0300 - 31.4424 * x + 30.0717 * y) / m
    if round_coefficients:
        m1, m2 = round(m1, 3), round(m2, 3)
    header, table = load_table("illuminants/D_series_basis.csv")
    basis = Spectrum(table[:, 0], table[:, 1:].T.copy())
    if wavelengths_nm is not None:
        try:
            basis = basis.resample(wavelengths_nm, "linear")
        except SpectrumError as exc:
            raise ColorimetryError(f"daylight: {exc}") from None
    s0, s1, s2 = basis.values
    return Spectrum(basis.wavelengths_nm, s0 + m1 * s1 + m2 * s2, (f"D{cct_K:g}K",))
