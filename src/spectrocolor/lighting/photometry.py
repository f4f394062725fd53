"""Photometry of light spectra: photopic and scotopic luminous quantities, luminous efficacy.

A luminous quantity is ``K_m Σ S(λ) V(λ) Δλ`` over the spectrum's own samples, with
K_m = 683 lm/W and V(λ) = ȳ(λ) of the CIE 1931 observer (photopic), or K'_m = 1700 lm/W and
V'(λ) (scotopic, CIE 1951; the rhodopic action spectrum of CIE S 026 Table 2 is V'(λ)). Its
unit follows from the spectrum's:

===========================  =====================  ==========================
spectral quantity            radiometric sum        luminous quantity
===========================  =====================  ==========================
radiant flux, W/nm           radiant flux, W        luminous flux, lm
irradiance, W·m⁻²·nm⁻¹       irradiance, W/m²       illuminance, lx
radiance, W·sr⁻¹·m⁻²·nm⁻¹    radiance, W·sr⁻¹·m⁻²   luminance, cd/m²
===========================  =====================  ==========================

The luminous efficacy of radiation (LER, lm/W) is the luminous over the radiant sum; it does
not depend on the spectrum's scale. The weighting functions are tabulated at 1 nm (V: 360–830
nm, V': 380–780 nm) and interpolated linearly at the spectrum's samples; outside their tables
they are zero (their values at the table ends are below 10⁻⁶ of the peak). Δλ is the sample
spacing (half-spans at the ends of an irregular grid, as in :mod:`spectrocolor.colorimetry`).

References
----------
CIE 015:2018 §7.1 (K_m = 683 lm/W). ISO 23539:2005 / CIE S 010/E:2004 *Photometry — The CIE
system of physical photometry* (V(λ), V'(λ), K'_m = 1700 lm/W). CIE S 026/E:2018 Table 2.
"""

from __future__ import annotations

from functools import lru_cache

import numpy as np

from ..colorimetry import K_M_LM_PER_W
from ..data_tables import load_table
from ..errors import SpectrumError
from ..observers import observer
from ..registry import Registry
from ..sampling import interval_weights_nm
from ..spectrum import Spectrum

#: Maximum luminous efficacy for scotopic vision, lm/W (ISO 23539:2005 / CIE S 010).
K_M_SCOTOPIC_LM_PER_W = 1700.0


def _photopic() -> tuple[np.ndarray, np.ndarray]:
    cmfs = observer("1931")
    return cmfs.wavelengths_nm, cmfs.values[1]


def _scotopic() -> tuple[np.ndarray, np.ndarray]:
    header, table = load_table("lighting/cie_s026_alpha_opic.csv")
    return table[:, 0], table[:, header.index("s_rh")]


#: Visions: name → (K_m in lm/W, loader of the tabulated (wavelengths_nm, V)).
VISIONS = Registry("vision", "a vision")
VISIONS.add("photopic", (K_M_LM_PER_W, _photopic), "V(λ) = ȳ(λ) of CIE 1931, K_m = 683 lm/W")
VISIONS.add("scotopic", (K_M_SCOTOPIC_LM_PER_W, _scotopic), "V'(λ) (CIE 1951), K'_m = 1700 lm/W")


def weighting_on(wavelengths_nm, table_nm: np.ndarray, table: np.ndarray) -> np.ndarray:
    """A tabulated weighting function at ``wavelengths_nm``: linear inside the table, 0 outside.

    Parameters
    ----------
    wavelengths_nm : array_like, shape (K,)
        The grid, nm.
    table_nm : numpy.ndarray, shape (M,)
        The table's wavelengths, nm, increasing.
    table : numpy.ndarray, shape (M,)
        The tabulated values.

    Returns
    -------
    numpy.ndarray, shape (K,)
        The function at ``wavelengths_nm``.

    Examples
    --------
    >>> weighting_on([399.5, 500.0, 900.0], np.array([399.0, 400.0]), np.array([1.0, 3.0])).tolist()
    [2.0, 0.0, 0.0]
    """
    return np.interp(np.asarray(wavelengths_nm, dtype=float), table_nm, table, left=0.0, right=0.0)


@lru_cache(maxsize=32)
def _weights(grid_key: bytes, vision: str) -> np.ndarray:
    grid = np.frombuffer(grid_key, dtype=float)
    result = weighting_on(grid, *VISIONS.get(vision)[1]()) * interval_weights_nm(grid)
    result.setflags(write=False)
    return result


def spectral_values(spd, argument: str = "spd") -> np.ndarray:
    """``spd.values`` as float64 after checking ``spd`` is a Spectrum of finite values.

    Parameters
    ----------
    spd : Spectrum
        Spectra ``(..., K)``, K >= 2.
    argument : str, default "spd"
        The caller's argument name, for error messages.

    Returns
    -------
    numpy.ndarray, shape (..., K)
        The values as float64.

    Raises
    ------
    SpectrumError
        For a non-Spectrum, fewer than two samples, or non-finite values.

    Examples
    --------
    >>> from spectrocolor import wavelength_grid
    >>> spectral_values(Spectrum.constant(1, wavelength_grid(400, 700, 100))).tolist()
    [1.0, 1.0, 1.0, 1.0]
    """
    if not isinstance(spd, Spectrum):
        raise SpectrumError(
            f"{argument}: expected a spectrocolor.Spectrum, got {type(spd).__name__}; "
            "wrap arrays as Spectrum(wavelengths_nm, values)"
        )
    if spd.wavelengths_nm.size < 2:
        raise SpectrumError(f"{argument}: needs at least two samples to sum over (Δλ), got one")
    values = np.asarray(spd.values, dtype=np.float64)
    if not np.all(np.isfinite(values)):
        raise SpectrumError(f"{argument}: values must be finite (no NaN or infinity)")
    return values


def luminous_quantity(spd, vision: str = "photopic") -> np.ndarray:
    """Luminous flux (lm), illuminance (lx) or luminance (cd/m²) of spectra ``(..., K)``.

    Parameters
    ----------
    spd : Spectrum
        Spectral radiant flux (W/nm), irradiance (W·m⁻²·nm⁻¹) or radiance
        (W·sr⁻¹·m⁻²·nm⁻¹); the result is in lm, lx or cd/m² respectively.
    vision : str
        ``"photopic"`` (V(λ), 683 lm/W) or ``"scotopic"`` (V'(λ), 1700 lm/W).

    Returns
    -------
    ndarray
        Shape ``spd.batch_shape``.

    References
    ----------
    CIE S 010/E:2004, ISO 23539:2005.

    Examples
    --------
    >>> from spectrocolor import wavelength_grid
    >>> flat = Spectrum.constant(0.001, wavelength_grid(360, 830, 1))  # 1 mW/nm
    >>> round(float(luminous_quantity(flat)), 3)  # 683 lm/W × 1 mW/nm × Σ V Δλ (106.857 nm)
    72.983
    """
    values = spectral_values(spd)
    vision = VISIONS.canonical(vision)
    K_m = VISIONS.get(vision)[0]
    return K_m * (values @ _weights(np.ascontiguousarray(spd.wavelengths_nm).tobytes(), vision))


def radiant_quantity(spd) -> np.ndarray:
    """Radiant flux (W), irradiance (W/m²) or radiance of spectra ``(..., K)``: ``Σ S Δλ``.

    Over the spectrum's own range (so an LER depends on the range measured).

    Parameters
    ----------
    spd : Spectrum
        Spectral power distributions ``(..., K)`` (e.g. W·nm⁻¹ or W·m⁻²·nm⁻¹).

    Returns
    -------
    numpy.ndarray, shape (...)
        ``Σ S Δλ`` in the units of the data times nm.

    Raises
    ------
    SpectrumError
        As :func:`spectral_values`.

    Examples
    --------
    >>> from spectrocolor import wavelength_grid
    >>> round(float(radiant_quantity(Spectrum.constant(0.001, wavelength_grid(380, 780, 5)))), 6)
    0.405
    """
    return spectral_values(spd) @ interval_weights_nm(spd.wavelengths_nm)


def luminous_efficacy_of_radiation(spd, vision: str = "photopic") -> np.ndarray:
    """Luminous efficacy of radiation (LER), lm/W, of spectra ``(..., K)`` (any scale).

    ``K = K_m ∫ S V dλ / ∫ S dλ``: the luminous flux per watt of radiant flux.

    Parameters
    ----------
    spd : Spectrum
        Spectral power distributions ``(..., K)``, any radiometric scale (it cancels).
    vision : str, default "photopic"
        ``"photopic"`` (V(λ), K_m = 683 lm/W) or ``"scotopic"`` (V′(λ), K′_m = 1700 lm/W).

    Returns
    -------
    numpy.ndarray, shape (...)
        LER in lm/W; NaN for a spectrum with no radiant power.

    Raises
    ------
    ColorimetryError
        For an unknown ``vision`` or a grid outside the luminous efficiency functions.

    References
    ----------
    CIE 015:2018 §7.1 (K_m = 683 lm/W); ISO 23539:2005 / CIE S 010/E:2004 (V(λ), V′(λ), K′_m).

    Examples
    --------
    >>> from spectrocolor import wavelength_grid
    >>> green = Spectrum.block(555, 555, wavelength_grid(550, 560, 1))
    >>> round(float(luminous_efficacy_of_radiation(green)), 1)  # V(555 nm) = 1
    683.0
    """
    with np.errstate(divide="ignore", invalid="ignore"):
        return luminous_quantity(spd, vision) / radiant_quantity(spd)
