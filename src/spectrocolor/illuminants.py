"""CIE illuminants, Planckian radiators and the CIE daylight series.

References
----------
CIE 015:2018 *Colorimetry*, 4th ed.: §4.1 and Table 5 (illuminant A formula with
c₂ = 1.435 × 10⁻² m·K), §4.1.2 and Table 6 (daylight basis S0, S1, S2 and the xD, yD, M1, M2
formulae), Tables 8–10 (FL1–FL12, LED-B1–B5). CODATA 2018 (second radiation constant
c₂ = 1.438 776 877 × 10⁻² m·K). Sources of the files: ``data/PROVENANCE.md``.
"""

from __future__ import annotations

import re
from functools import cache

import numpy as np

from .arguments import real_number
from .data_tables import load_table
from .errors import ColorimetryError, SpectrumError
from .registry import Registry
from .spectrum import Spectrum, validate_wavelengths, wavelength_grid

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

#: The CIE illuminants by name: value "formula" (A), "constant" (E) or "table" (a CIE table in
#: data/illuminants/), with one-line descriptions (CIE 015:2018 §4, Tables 5-10).
ILLUMINANTS = Registry("illuminant", "a CIE illuminant name (or use 'blackbody:T' / 'D:T' for other temperatures)")
ILLUMINANTS.add("A", "formula", "incandescent tungsten, a 2856 K Planckian radiator (CIE 015 eq. 4.1)")
ILLUMINANTS.add("B", "table", "direct sunlight, about 4874 K (obsolete; CIE 015 Table 10 note)")
ILLUMINANTS.add("C", "table", "average daylight, about 6774 K (obsolete; seed 001's illuminant)")
for _cct in (50, 55, 65, 75):
    ILLUMINANTS.add(f"D{_cct}", "table", f"CIE daylight, about {_cct}00 K")
ILLUMINANTS.add("E", "constant", "equal energy: 100 at every wavelength")
for _i, _kind in enumerate(("standard",) * 6 + ("broadband",) * 3 + ("three-band",) * 3, start=1):
    ILLUMINANTS.add(f"FL{_i}", "table", f"CIE fluorescent lamp {_i} ({_kind})")
for _i in range(1, 6):
    ILLUMINANTS.add(f"LED-B{_i}", "table", f"CIE phosphor-converted white LED {_i} (CIE 015 Table 10)")
_DEFAULT_GRID = (300.0, 830.0, 5.0)
#: Temperatures accepted for Planckian radiators, K. Below about 100 K the relative SPD
#: over 360–830 nm underflows to zero (exp(c₂/λT) overflows), so nothing meaningful remains.
MIN_TEMPERATURE_K, MAX_TEMPERATURE_K = 100.0, 1.0e6


def illuminant_names() -> tuple[str, ...]:
    """Names of the CIE illuminants accepted by :func:`illuminant`.

    Returns
    -------
    tuple of str
        Canonical names: A, B, C, D50–D75, E, FL1–FL12, LED-B1–B5. Blackbodies (``"blackbody:T"``)
        and daylights of any temperature (``"D:T"``) are accepted too but not listed.

    Examples
    --------
    >>> names = illuminant_names()
    >>> names[:8], len(names)
    (('A', 'B', 'C', 'D50', 'D55', 'D65', 'D75', 'E'), 25)
    """
    return ILLUMINANTS.names()


def canonical_illuminant_name(name: str) -> str:
    """``"d65"``, ``"FL 11"``, ``"led_b1"`` → ``"D65"``, ``"FL11"``, ``"LED-B1"``; or raise.

    Parameters
    ----------
    name : str
        A CIE illuminant name in any case, with or without spaces or underscores (``"F2"`` is
        read as ``"FL2"``).

    Returns
    -------
    str
        One of :func:`illuminant_names`.

    Raises
    ------
    ColorimetryError
        For a non-string or an unknown name (use :func:`canonical_illuminant` for
        ``"blackbody:T"``, ``"D:T"`` and temperatures).

    Examples
    --------
    >>> canonical_illuminant_name("fl 11"), canonical_illuminant_name("led_b1"), canonical_illuminant_name("F2")
    ('FL11', 'LED-B1', 'FL2')
    """
    if not isinstance(name, str):
        raise ColorimetryError(f"illuminant: expected a name such as 'D65', got {name!r}")
    key = re.sub(r"[\s_]+", "", name.strip().upper())
    key = re.sub(r"^LED-?B", "LED-B", key)
    key = re.sub(r"^F(\d)", r"FL\1", key) if not key.startswith("FL") else key
    return ILLUMINANTS.canonical(key if key in ILLUMINANTS else name)


#: The illuminant used wherever a reflectance needs one and the caller gives none: CIE D65
#: (CIE 015:2018 §4.1, the standard daylight illuminant). Stated here once; every function,
#: the CLI and the app take their default from this constant.
DEFAULT_ILLUMINANT = "D65"

#: ``KIND:T``; the temperature text is cut out by :func:`_temperature_key`, not by the pattern (a
#: lazy ``.*?`` between ``\s*`` runs took cubic time on a name padded with spaces).
_TEMPERATURE_KEY = re.compile(r"\s*+(blackbody|planck|bb|d|daylight)\s*+:(.*)", re.IGNORECASE)


def _temperature_key(name: str) -> tuple[str, str] | None:
    """``(kind, temperature text)`` of ``"blackbody:6504 K"``-style names, or None (linear time)."""
    match = _TEMPERATURE_KEY.fullmatch(name)
    if match is None:
        return None
    value = match.group(2).strip()
    if len(value) > 1 and value[-1] in "kK":
        value = value[:-1].rstrip()
    return (match.group(1), value) if value else None
_ACCEPTED_SOURCES = (
    "a CIE name such as 'D65' or 'A', 'blackbody:T' (a Planckian radiator at T kelvin), 'D:T' "
    "(the CIE daylight of correlated colour temperature T, 4000–25000 K), a temperature in kelvin "
    "(a blackbody), or a spectrocolor.Spectrum with one distribution"
)
_ACCEPTED = f"None (no illuminant: the spectra are lights), {_ACCEPTED_SOURCES}"


def canonical_illuminant(illuminant, argument: str = "illuminant"):
    """The one illuminant vocabulary of spectrocolor, resolved to a canonical form.

    Every module, the command line and the app accept the same forms, and ``None`` means the
    same thing everywhere: no illuminant, so the spectra are lights (sources), not reflectances.

    Parameters
    ----------
    illuminant : None, str, int, float or Spectrum
        ``None``; a CIE name in any spelling (``"D65"``, ``"d65"``, ``"FL 11"``, ``"led_b1"``);
        ``"blackbody:T"`` (also ``"planck:T"``) for a Planckian radiator at ``T`` kelvin;
        ``"D:T"`` (also ``"daylight:T"``) for the CIE daylight series at ``T`` kelvin; a number,
        taken as a blackbody temperature in kelvin; or a :class:`Spectrum` with one distribution.
    argument : str
        The name of the caller's argument, used in the error message.

    Returns
    -------
    None, str or Spectrum
        ``None``; a canonical name (``"D65"``, ``"blackbody:6504"``, ``"D:5000"``), hashable and
        usable as a cache key; or the Spectrum itself.

    Raises
    ------
    ColorimetryError
        For anything else, naming ``argument`` and listing the accepted forms.

    Examples
    --------
    >>> canonical_illuminant("fl 11"), canonical_illuminant(6504), canonical_illuminant("daylight:5000K")
    ('FL11', 'blackbody:6504', 'D:5000')
    """
    if illuminant is None:
        return None
    if isinstance(illuminant, Spectrum):
        if illuminant.values.ndim != 1:
            raise ColorimetryError(
                f"{argument}: expected one spectral distribution, got a batch of shape {illuminant.batch_shape}"
            )
        return illuminant
    if isinstance(illuminant, int | float | np.integer | np.floating) and not isinstance(illuminant, bool):
        return f"blackbody:{_temperature(illuminant, argument):g}"
    if isinstance(illuminant, str):
        match = _temperature_key(illuminant)
        if match:
            kind = match[0].lower()
            try:
                value = float(match[1])
            except ValueError:
                raise ColorimetryError(
                    f"{argument}: {illuminant!r} needs a temperature in kelvin after the colon, e.g. 'blackbody:6504'"
                ) from None
            temperature = _temperature(value, argument)
            if kind in ("d", "daylight"):
                try:
                    daylight_xy(temperature)  # validates the 4000–25000 K range
                except ColorimetryError as exc:  # name the caller's argument, not daylight's
                    raise ColorimetryError(f"{argument}: {illuminant!r:.40}: {exc}") from None
                return f"D:{temperature:g}"
            return f"blackbody:{temperature:g}"
        try:
            return canonical_illuminant_name(illuminant)
        except ColorimetryError:
            raise ColorimetryError(
                f"{argument}: {illuminant!r:.80} is not a CIE illuminant name ({', '.join(ILLUMINANTS)}); "
                "other forms: 'blackbody:T', 'D:T', a temperature in kelvin, a Spectrum, or None for lights"
            ) from None
    raise ColorimetryError(f"{argument}: expected {_ACCEPTED}; got {illuminant!r:.80}")


def _temperature(value, argument: str) -> float:
    value = float(value)
    if not (np.isfinite(value) and MIN_TEMPERATURE_K <= value <= MAX_TEMPERATURE_K):
        raise ColorimetryError(
            f"{argument}: a temperature must be {MIN_TEMPERATURE_K:g}–{MAX_TEMPERATURE_K:g} K, got {value!r}"
        )
    return value


def illuminant_label(illuminant) -> str:
    """A short human-readable name of an illuminant given in any accepted form.

    Parameters
    ----------
    illuminant : None, str, int, float or Spectrum
        Any form :func:`canonical_illuminant` accepts.

    Returns
    -------
    str
        The canonical CIE name, ``"blackbody T K"``, ``"CIE daylight T K"``, the Spectrum's name
        (``"user illuminant"`` when it has none), or ``"none (lights)"`` for ``None``.

    Raises
    ------
    ColorimetryError
        As :func:`canonical_illuminant`.

    Examples
    --------
    >>> illuminant_label("d50"), illuminant_label(3000), illuminant_label(None)
    ('D50', 'blackbody 3000 K', 'none (lights)')
    """
    resolved = canonical_illuminant(illuminant)
    if resolved is None:
        return "none (lights)"
    if isinstance(resolved, Spectrum):
        return resolved.names[0] if resolved.names and resolved.names[0] else "user illuminant"
    kind, _, value = resolved.partition(":")
    if not value:
        return resolved
    return f"blackbody {value} K" if kind == "blackbody" else f"CIE daylight {value} K"


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


def _illuminant_A(grid: np.ndarray) -> np.ndarray:
    """CIE 015:2018 eq. (4.1): S_A(λ) = 100 (560/λ)⁵ (e^{c₂/(560·2848)} − 1)/(e^{c₂/(λ·2848)} − 1)."""
    return blackbody(ILLUMINANT_A_TEMPERATURE_K, grid, c2_m_K=C2_ILLUMINANT_A_M_K).values


@cache
def _table(name: str) -> Spectrum:
    header, table = load_table(f"illuminants/{name}.csv")
    return Spectrum(table[:, 0], table[:, 1], (name,))


def illuminant(name, wavelengths_nm=None, method: str = "linear") -> Spectrum:
    """Relative spectral power distribution of an illuminant named in the library's vocabulary.

    Parameters
    ----------
    name : str, int, float or Spectrum
        Any form :func:`canonical_illuminant` accepts except ``None``: ``"A"`` (evaluated from
        its defining formula on any grid), ``"E"`` (equal energy, 100 everywhere), ``"B"``,
        ``"C"``, ``"D50"``, ``"D55"``, ``"D65"``, ``"D75"``, ``"FL1"``–``"FL12"``,
        ``"LED-B1"``–``"LED-B5"`` (the CIE tables, 5 nm); ``"blackbody:T"`` or a number
        (:func:`blackbody`); ``"D:T"`` (:func:`daylight`); a Spectrum (resampled if a grid is
        given).
    wavelengths_nm : array_like, optional
        Grid to return, nm. ``None``: the table's own grid (A: 300–780 nm, E: 300–830 nm, 5 nm;
        blackbody 360–830 nm at 1 nm; daylight 300–830 nm at 5 nm). Tabulated illuminants are
        interpolated with ``method`` (default linear, as CIE 015 recommends for the daylight
        series) and never extrapolated.
    method : str, default "linear"
        Interpolation for tabulated illuminants (see :meth:`Spectrum.resample`).

    Returns
    -------
    Spectrum
        Relative SPD (arbitrary units; the CIE tables are 100 at 560 nm).

    Raises
    ------
    ColorimetryError
        For ``None``, an unknown name, or a grid outside the table's range (never extrapolated).

    References
    ----------
    CIE 015:2018 §4.1 and Tables 5–10 (see the module docstring).

    Examples
    --------
    >>> float(illuminant("D65", [560.0]).values[0])
    100.0
    >>> float(illuminant("blackbody:2856", [560.0]).values[0])
    100.0
    """
    canonical = canonical_illuminant(name, "name")
    if canonical is None:
        raise ColorimetryError(f"name: expected {_ACCEPTED_SOURCES}; got None")
    if isinstance(canonical, Spectrum):
        if wavelengths_nm is None:
            return canonical
        try:
            return canonical.resample(wavelengths_nm, method)
        except SpectrumError as exc:
            raise ColorimetryError(f"illuminant: {exc}") from None
    kind, _, value = canonical.partition(":")
    if kind == "blackbody":
        return blackbody(float(value), wavelengths_nm)
    if kind == "D" and value:
        return daylight(float(value), wavelengths_nm)
    if canonical == "A":
        grid = _table("A").wavelengths_nm if wavelengths_nm is None else validate_wavelengths(wavelengths_nm)
        return Spectrum(grid, _illuminant_A(grid), ("A",))
    if canonical == "E":
        grid = _grid_or_default(wavelengths_nm, _DEFAULT_GRID)
        return Spectrum(grid, np.full(grid.size, 100.0), ("E",))
    table = _table(canonical)
    if wavelengths_nm is None:
        return table
    try:
        return table.resample(wavelengths_nm, method)
    except SpectrumError as exc:
        raise ColorimetryError(f"illuminant {canonical}: {exc}") from None


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
