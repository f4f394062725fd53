"""Optical media: complex refractive index ``N(λ) = n(λ) + i k(λ)`` on any wavelength grid.

A :class:`Medium` is a named function of vacuum wavelength in nanometres with a stated range of
validity; asking for an index outside that range is an error, never an extrapolation. Wherever the
optics functions accept a medium they also accept a plain number (a constant index).

Sign convention: ``k >= 0`` means absorption (fields ``exp(i(kz - ωt))``).

Why this file is long: it is a catalogue: the :class:`Medium` type and each named material's
dispersion formula with its citation; every entry is short and independent, and :func:`medium` lists
them from one place.
"""

from __future__ import annotations

import csv
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..arguments import real_array
from ..errors import SpectrumError


@dataclass(frozen=True)
class Medium:
    """A medium with a wavelength-dependent complex refractive index.

    Parameters
    ----------
    name : str
        Human-readable name, e.g. ``"water (Daimon & Masumura 2007, 20 °C)"``.
    index_function : callable
        Maps vacuum wavelengths in nm, shape ``(K,)``, to the complex index ``n + ik``,
        shape ``(K,)`` (``k >= 0`` is absorption).
    valid_nm : tuple of float, default (0.0, inf)
        ``(lowest, highest)`` vacuum wavelength in nm where the model is defined.

    Examples
    --------
    >>> import numpy as np
    >>> glass = Medium("n = 1.5", lambda wl: np.full(wl.shape, 1.5 + 0j), (400.0, 700.0))
    >>> glass.refractive_index([400, 700]).real.tolist()
    [1.5, 1.5]
    >>> medium("water")  # the built-in media are Medium objects too
    Medium('water (Daimon & Masumura 2007, 20 °C)')
    """

    name: str
    index_function: Callable[[np.ndarray], np.ndarray]
    valid_nm: tuple[float, float] = (0.0, np.inf)

    def refractive_index(self, wavelengths_nm) -> np.ndarray:
        """Complex refractive index ``n + ik`` at the given vacuum wavelengths (nm), shape ``(K,)``.

        Parameters
        ----------
        wavelengths_nm : array_like, shape (K,)
            Vacuum wavelengths, nm, finite and positive, inside ``valid_nm``.

        Returns
        -------
        numpy.ndarray of complex, shape (K,)
            ``n + ik`` at each wavelength.

        Raises
        ------
        SpectrumError
            If a wavelength lies outside ``valid_nm`` (never extrapolated) or the grid is
            malformed.

        Examples
        --------
        >>> medium("water").refractive_index([589.3]).real.round(4).tolist()
        [1.3333]
        """
        wl = _wavelengths(wavelengths_nm)
        lo, hi = self.valid_nm
        if wl.size and (wl.min() < lo or wl.max() > hi):
            raise SpectrumError(
                f"wavelengths_nm: {self.name} is defined for {lo:g}-{hi:g} nm, got "
                f"{wl.min():g}-{wl.max():g} nm; restrict the wavelength grid (no extrapolation)"
            )
        index = np.asarray(self.index_function(wl), dtype=complex)
        return np.broadcast_to(index, wl.shape).copy()

    def __repr__(self) -> str:
        return f"Medium({self.name!r})"


def _wavelengths(wavelengths_nm) -> np.ndarray:
    wl = real_array(wavelengths_nm, "wavelengths_nm", "wavelengths in nm", SpectrumError)
    if wl.ndim != 1 or not np.all(np.isfinite(wl)) or np.any(wl <= 0):
        raise SpectrumError(
            "wavelengths_nm: expected a 1-D array of finite positive wavelengths in nm, "
            f"got shape {wl.shape}"
        )
    return wl


def refractive_index(medium, wavelengths_nm) -> np.ndarray:
    """Complex index of a :class:`Medium`, a number, or a ``(K,)`` array, on a grid (nm).

    Parameters
    ----------
    medium : Medium, complex or array_like, shape (K,)
        A :class:`Medium`, a real or complex number (constant index), or an array of shape
        ``(K,)`` already sampled on ``wavelengths_nm``.
    wavelengths_nm : array_like, shape (K,)
        Vacuum wavelengths in nm.

    Returns
    -------
    ndarray of complex, shape ``(K,)``
        ``n + ik`` at each wavelength.

    Raises
    ------
    SpectrumError
        For an index with ``n <= 0``, ``k < 0`` or non-finite, an array of the wrong shape, a
        malformed grid, or wavelengths outside a Medium's range.

    Examples
    --------
    >>> refractive_index(1.38, [400.0, 700.0]).tolist()
    [(1.38+0j), (1.38+0j)]
    """
    wl = _wavelengths(wavelengths_nm)
    if isinstance(medium, Medium):
        index = medium.refractive_index(wl)
    else:
        try:
            index = np.asarray(medium, dtype=complex)
        except (TypeError, ValueError) as exc:
            raise SpectrumError(
                f"medium: expected a Medium, a number or a (K,) array of indices, got {medium!r}"
            ) from exc
        if index.ndim == 0:
            index = np.full(wl.shape, index)
        elif index.shape != wl.shape:
            raise SpectrumError(
                f"medium: an index array must have the wavelength grid's shape {wl.shape}, "
                f"got {index.shape}"
            )
    if not np.all(np.isfinite(index)) or np.any(index.real <= 0) or np.any(index.imag < 0):
        raise SpectrumError(
            "medium: refractive indices must be finite with n > 0 and k >= 0 (n + ik convention)"
        )
    return index


def constant(n: float, k: float = 0.0, name: str | None = None) -> Medium:
    """A medium with a wavelength-independent index ``n + ik``.

    Parameters
    ----------
    n : float
        Real part, > 0.
    k : float, default 0.0
        Imaginary part (absorption), >= 0.
    name : str, optional
        Default ``"n = <n>"`` (with ``+ <k>i`` when absorbing).

    Returns
    -------
    Medium
        Valid at every wavelength.

    Raises
    ------
    SpectrumError
        For ``n <= 0``, ``k < 0`` or a non-finite value.

    Examples
    --------
    >>> constant(2.0, 0.1).refractive_index([500.0]).tolist()
    [(2+0.1j)]
    """
    if not (np.isfinite(n) and n > 0 and np.isfinite(k) and k >= 0):
        raise SpectrumError(f"medium: a constant index needs finite n > 0 and k >= 0, got n={n!r}, "
                            f"k={k!r}")
    value = complex(n, k)
    return Medium(name or f"n = {value.real:g}" + (f" + {k:g}i" if k else ""),
                  lambda wl: np.full(wl.shape, value))


def cauchy(a: float, b_um2: float = 0.0, c_um4: float = 0.0, name: str = "Cauchy",
           valid_nm: tuple[float, float] = (300.0, 1000.0)) -> Medium:
    """Cauchy dispersion ``n(λ) = A + B/λ² + C/λ⁴`` with λ in µm (non-absorbing).

    Parameters
    ----------
    a : float
        Constant term A.
    b_um2 : float, default 0.0
        B in µm².
    c_um4 : float, default 0.0
        C in µm⁴.
    name : str, default "Cauchy"
        The medium's name.
    valid_nm : tuple of float, default (300.0, 1000.0)
        Range of validity in nm (a Cauchy fit is only meaningful where it was fitted).

    Returns
    -------
    Medium
        Non-absorbing (k = 0).

    Examples
    --------
    >>> cauchy(1.45575, 0.004920).refractive_index([587.56]).real.round(4).tolist()  # typical oil
    [1.47]
    """
    def index(wl_nm):
        inv2 = 1.0 / (wl_nm * 1e-3) ** 2
        return a + b_um2 * inv2 + c_um4 * inv2**2

    return Medium(name, index, valid_nm)


def sellmeier(b, c_um2, name: str = "Sellmeier",
              valid_nm: tuple[float, float] = (300.0, 1000.0)) -> Medium:
    """Sellmeier dispersion ``n² = 1 + Σ Bᵢ λ² / (λ² − Cᵢ)`` with λ in µm (non-absorbing).

    Parameters
    ----------
    b : array_like, shape (M,)
        Oscillator strengths ``Bᵢ`` (dimensionless).
    c_um2 : array_like, shape (M,)
        Resonance terms ``Cᵢ`` in µm² (same length as ``b``).
    name : str, default "Sellmeier"
        The medium's name.
    valid_nm : tuple of float, default (300.0, 1000.0)
        Range of validity in nm.

    Returns
    -------
    Medium
        Non-absorbing (k = 0).

    Raises
    ------
    SpectrumError
        For ``b`` and ``c_um2`` that are not 1-D of equal length.

    Examples
    --------
    >>> glass = sellmeier([1.03961212, 0.231792344, 1.01046945], [0.00600069867, 0.0200179144, 103.560653])
    >>> glass.refractive_index([587.56]).real.round(4).tolist()  # N-BK7, n_d
    [1.5168]
    """
    b = np.asarray(b, dtype=float)
    c = np.asarray(c_um2, dtype=float)
    if b.ndim != 1 or b.shape != c.shape:
        raise SpectrumError(
            f"sellmeier: b and c_um2 must be 1-D of equal length, got {b.shape} and {c.shape}"
        )

    def index(wl_nm):
        lam2 = (wl_nm * 1e-3)[:, None] ** 2
        return np.sqrt(1.0 + np.sum(b * lam2 / (lam2 - c), axis=-1))

    return Medium(name, index, valid_nm)


def water() -> Medium:
    """Liquid water at 20 °C, four-term Sellmeier fit of Daimon & Masumura (2007).

    Valid 182-1129 nm. ``n(589.3 nm) ≈ 1.3333``.

    References
    ----------
    M. Daimon and A. Masumura, "Measurement of the refractive index of distilled water from the
    near-infrared region to the ultraviolet region," Appl. Opt. 46, 3811-3820 (2007), Table 3
    (20.0 °C).

    Returns
    -------
    Medium
        Valid 182–1129 nm.

    Examples
    --------
    >>> water().refractive_index([589.3]).real.round(4).tolist()
    [1.3333]
    """
    return sellmeier(
        [5.684027565e-1, 1.726177391e-1, 2.086189578e-2, 1.130748688e-1],
        [5.101829712e-3, 1.821153936e-2, 2.620722293e-2, 1.069792721e1],
        name="water (Daimon & Masumura 2007, 20 °C)",
        valid_nm=(182.0, 1129.0),
    )


def water_iapws(temperature_K: float = 293.15, density_kg_m3: float = 998.2) -> Medium:
    """Water from the IAPWS 1997 formulation (Harvey et al. 1998), any temperature and density.

    Valid 200-1100 nm, 261.15-773.15 K, 0-1060 kg/m³. Give the density that belongs to the
    temperature (998.2 kg/m³ at 20 °C and 0.1 MPa).

    References
    ----------
    A. H. Harvey, J. S. Gallagher and J. M. H. Levelt Sengers, "Revised formulation for the
    refractive index of water and steam as a function of wavelength, temperature and density,"
    J. Phys. Chem. Ref. Data 27, 761-774 (1998); IAPWS Release R9-97.

    Parameters
    ----------
    temperature_K : float, default 293.15
        Temperature, K (261.15–773.15).
    density_kg_m3 : float, default 998.2
        Density, kg/m³ (0–1060), belonging to the temperature and pressure.

    Returns
    -------
    Medium
        Valid 200–1100 nm.

    Raises
    ------
    SpectrumError
        For a temperature or density outside the formulation's range.

    Examples
    --------
    >>> water_iapws().refractive_index([589.0]).real.round(4).tolist()
    [1.3334]
    """
    if not (261.15 <= temperature_K <= 773.15) or not (0 < density_kg_m3 <= 1060):
        raise SpectrumError(
            "water_iapws: temperature_K must be 261.15-773.15 and density_kg_m3 in (0, 1060], "
            f"got {temperature_K!r}, {density_kg_m3!r}"
        )
    a = (0.244257733, 9.74634476e-3, -3.73234996e-3, 2.68678472e-4,
         1.58920570e-3, 2.45934259e-3, 0.900704920, -1.66626219e-2)
    lam_uv2, lam_ir2 = 0.2292020**2, 5.432937**2
    t = temperature_K / 273.15
    rho = density_kg_m3 / 1000.0

    def index(wl_nm):
        lam2 = (wl_nm / 589.0) ** 2
        rhs = rho * (a[0] + a[1] * rho + a[2] * t + a[3] * lam2 * t + a[4] / lam2
                     + a[5] / (lam2 - lam_uv2) + a[6] / (lam2 - lam_ir2) + a[7] * rho**2)
        return np.sqrt((2 * rhs + 1) / (1 - rhs))

    return Medium(f"water (IAPWS 1997, {temperature_K:g} K, {density_kg_m3:g} kg/m³)",
                  index, (200.0, 1100.0))


def typical_oil() -> Medium:
    """An illustrative light mineral oil: Cauchy model with n_d = 1.470 and Abbe number V_d = 50.

    Not a measurement of a particular oil: mineral and vegetable oils lie roughly at
    n_d = 1.46-1.48 with V_d ≈ 45-60. ``A = 1.45575``, ``B = 0.004920 µm²`` reproduce
    n(587.56 nm) = 1.470 and (n_d − 1)/(n_F − n_C) = 50.

    Returns
    -------
    Medium
        Valid 350–1000 nm.

    Examples
    --------
    >>> typical_oil().refractive_index([587.56]).real.round(4).tolist()
    [1.47]
    """
    return cauchy(1.45575, 0.004920, name="typical oil (Cauchy, n_d 1.470, V_d 50)",
                  valid_nm=(350.0, 1000.0))


def bk7() -> Medium:
    """Schott N-BK7 crown glass, Sellmeier formula from the Schott data sheet (n_d = 1.5168).

    References
    ----------
    SCHOTT AG, Optical Glass Data Sheets, N-BK7 (517642.251).

    Returns
    -------
    Medium
        Valid 300–2500 nm.

    Examples
    --------
    >>> bk7().refractive_index([587.56]).real.round(4).tolist()
    [1.5168]
    """
    return sellmeier(
        [1.03961212, 0.231792344, 1.01046945],
        [0.00600069867, 0.0200179144, 103.560653],
        name="N-BK7 glass (Schott)", valid_nm=(300.0, 2500.0),
    )


def fused_silica() -> Medium:
    """Fused silica at 20 °C, Sellmeier formula of Malitson (1965), valid 210-3710 nm.

    References
    ----------
    I. H. Malitson, "Interspecimen comparison of the refractive index of fused silica,"
    J. Opt. Soc. Am. 55, 1205-1209 (1965).

    Returns
    -------
    Medium
        Valid 210–3710 nm.

    Examples
    --------
    >>> fused_silica().refractive_index([587.56]).real.round(4).tolist()
    [1.4585]
    """
    return sellmeier(
        [0.6961663, 0.4079426, 0.8974794],
        [0.0684043**2, 0.1162414**2, 9.896161**2],
        name="fused silica (Malitson 1965)", valid_nm=(210.0, 3710.0),
    )


def table(wavelengths_nm, n, k=None, name: str = "table") -> Medium:
    """A medium from tabulated n(λ) and k(λ), interpolated linearly inside the table only.

    Parameters
    ----------
    wavelengths_nm : array_like, shape (M,)
        Strictly increasing vacuum wavelengths in nm, ``M >= 2``.
    n : array_like, shape (M,)
        Real part of the index at those wavelengths (> 0).
    k : array_like, shape (M,), optional
        Imaginary part (>= 0); default 0.
    name : str, default "table"
        The medium's name.

    Returns
    -------
    Medium
        Valid over the table's range only.

    Raises
    ------
    SpectrumError
        For arrays of different lengths, fewer than 2 rows, a grid that is not strictly
        increasing, or ``n <= 0``, ``k < 0``, non-finite values.

    Examples
    --------
    >>> film = table([400, 500, 600], [1.50, 1.48, 1.47], [0.0, 0.01, 0.02], name="film")
    >>> film.refractive_index([450.0]).round(4).tolist(), film.valid_nm
    ([(1.49+0.005j)], (400.0, 600.0))
    """
    wl = np.asarray(wavelengths_nm, dtype=float)
    n = np.asarray(n, dtype=float)
    k = np.zeros_like(n) if k is None else np.asarray(k, dtype=float)
    if wl.ndim != 1 or wl.size < 2 or n.shape != wl.shape or k.shape != wl.shape:
        raise SpectrumError(
            f"table: wavelengths_nm, n and k must be 1-D of equal length >= 2, got "
            f"{wl.shape}, {n.shape}, {k.shape}"
        )
    if np.any(np.diff(wl) <= 0):
        raise SpectrumError("table: wavelengths_nm must be strictly increasing")
    if not (np.all(np.isfinite(n)) and np.all(np.isfinite(k))) or np.any(n <= 0) or np.any(k < 0):
        raise SpectrumError("table: need finite n > 0 and k >= 0 at every wavelength")
    wl, n, k = wl.copy(), n.copy(), k.copy()
    return Medium(name, lambda x: np.interp(x, wl, n) + 1j * np.interp(x, wl, k),
                  (float(wl[0]), float(wl[-1])))


def read_medium_csv(path, name: str | None = None) -> Medium:
    """Read a medium from a CSV file with columns ``wavelength_nm,n`` and optionally ``k``.

    Lines starting with ``#`` are comments. Values are interpolated linearly between rows and
    never extrapolated.

    Parameters
    ----------
    path : str or os.PathLike
        The CSV file: a header naming ``wavelength_nm`` and ``n`` (and optionally ``k``).
    name : str, optional
        The medium's name; default the file's stem.

    Returns
    -------
    Medium
        As :func:`table`.

    Raises
    ------
    SpectrumError
        For an empty file, a missing column, non-numeric values or ragged rows.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     path = pathlib.Path(folder) / "film.csv"
    ...     _ = path.write_text("# my film\\nwavelength_nm,n\\n400,1.50\\n700,1.47\\n")
    ...     read_medium_csv(path).valid_nm
    (400.0, 700.0)
    """
    path = Path(path)
    with path.open(newline="") as fh:
        rows = [r for r in csv.reader(fh) if r and not r[0].lstrip().startswith("#")]
    if not rows:
        raise SpectrumError(f"{path}: empty medium file; expected columns wavelength_nm,n[,k]")
    header = [h.strip().lower() for h in rows[0]]
    if "wavelength_nm" not in header or "n" not in header:
        raise SpectrumError(
            f"{path}: header must name columns wavelength_nm and n (and optionally k), "
            f"got {rows[0]}"
        )
    try:
        data = np.array([[float(v) for v in r] for r in rows[1:]], dtype=float)
    except ValueError as exc:
        raise SpectrumError(f"{path}: non-numeric value in the table: {exc}") from exc
    if data.ndim != 2 or data.shape[1] != len(header):
        raise SpectrumError(f"{path}: every row needs {len(header)} values")
    column = {h: data[:, i] for i, h in enumerate(header)}
    return table(column["wavelength_nm"], column["n"], column.get("k"), name=name or path.stem)


_NAMED = {
    "air": lambda: constant(1.0, name="air (n = 1)"),
    "vacuum": lambda: constant(1.0, name="vacuum"),
    "water": water,
    "soap": water,
    "oil": typical_oil,
    "bk7": bk7,
    "glass": bk7,
    "fused-silica": fused_silica,
}


def medium(spec) -> Medium:
    """A medium from a name, a number, or a CSV path.

    Names: ``air``, ``vacuum``, ``water`` (= ``soap``), ``oil``, ``bk7`` (= ``glass``),
    ``fused-silica``. Numbers like ``"1.38"`` or ``"2.0+0.1j"`` give a constant index; a
    string ending in ``.csv`` is read with :func:`read_medium_csv`.

    Parameters
    ----------
    spec : str, int, float, complex or Medium
        A name above, a number or numeric string (a constant complex index ``n + ik``), a path
        to a CSV file with columns ``wavelength_nm,n[,k]``, or a Medium (returned unchanged).

    Returns
    -------
    Medium
        The medium, with its range of validity in nm.

    Raises
    ------
    SpectrumError
        For an unknown name, an index with ``n <= 0`` or ``k < 0``, or a malformed CSV file.

    References
    ----------
    Daimon & Masumura (2007) (water); SCHOTT N-BK7 data sheet; Malitson (1965) (fused silica);
    see the docstrings of :func:`water`, :func:`bk7` and :func:`fused_silica`.

    Examples
    --------
    >>> medium("glass").refractive_index([587.56]).real.round(4).tolist()
    [1.5168]
    >>> medium("2.0+0.1j").refractive_index([500.0]).tolist()
    [(2+0.1j)]
    """
    if isinstance(spec, Medium):
        return spec
    if isinstance(spec, (int, float, complex)):
        value = complex(spec)
        return constant(value.real, value.imag)
    text = str(spec).strip()
    key = text.lower()
    if key in _NAMED:
        return _NAMED[key]()
    if key.endswith(".csv"):
        return read_medium_csv(text)
    try:
        value = complex(text.replace(" ", ""))
    except ValueError:
        raise SpectrumError(
            f"medium: unknown medium {text!r}; use one of {sorted(_NAMED)}, a number such as "
            "1.38 or 2.0+0.1j, or a CSV file with columns wavelength_nm,n[,k]"
        ) from None
    return constant(value.real, value.imag)
