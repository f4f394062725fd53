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
not depend on the spectrum's scale, but the radiant sum depends on the range measured, so the
luminous quantities and the LER need a spectrum that covers 380–780 nm (outside it V(λ) is below
4 × 10⁻⁵ of its peak; a light measured over 400–700 nm only would give FL2 an LER 2.7 % too
high). A light with no power, negative power (``Σ S Δλ ≤ 0``, or a negative luminous sum) or
values that are not finite is refused: NaN with a reason in a batch
(:func:`~spectrocolor.lighting.spectra.light_refusals`), a
:class:`~spectrocolor.errors.SpectrumError` for one light. The weighting functions are tabulated at 1 nm (V: 360–830
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
from .spectra import checked_lights

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


def checked_luminous(spd, vision: str, argument: str = "spd"):
    """Lights checked for photometry and their luminous sums, negative sums refused.

    :func:`~spectrocolor.lighting.spectra.checked_lights` with ``"photometry"``, then a light
    whose luminous sum ``K_m Σ S V Δλ`` is negative (negative samples outweighing the rest where
    V is large) is refused too. Shared by the photometric and α-opic quantities and the report.

    Parameters
    ----------
    spd : Spectrum
        Spectral power distributions ``(..., K)`` covering 380–780 nm.
    vision : str
        ``"photopic"`` or ``"scotopic"`` (:data:`VISIONS`).
    argument : str, default "spd"
        The caller's argument name, for messages.

    Returns
    -------
    checked : CheckedLights
        The lights (N, K) and a reason per light (``""`` where computed).
    luminous : numpy.ndarray, shape (N,)
        ``K_m Σ S V Δλ`` in lm, lx or cd/m² (per the input's unit); NaN for refused lights.

    Raises
    ------
    SpectrumError
        For a non-Spectrum, and for a single light that is refused.

    Examples
    --------
    >>> from spectrocolor import wavelength_grid
    >>> checked, luminous = checked_luminous(Spectrum.block(555, 555, wavelength_grid(380, 780, 1)), "photopic")
    >>> checked.reasons.tolist(), round(float(luminous[0]), 6)
    ([''], 683.0)
    """
    vision = VISIONS.canonical(vision)
    K_m = VISIONS.get(vision)[0]
    checked = checked_lights(spd, "photometry", argument)
    total = K_m * (checked.values @ _weights(np.ascontiguousarray(checked.grid).tobytes(), vision))
    negative = (total < 0) & checked.ok
    if negative.any():
        reasons = checked.reasons.astype(object)
        for i in np.flatnonzero(negative):
            reasons[i] = (f"negative power: the {vision} luminous sum is {total[i]:.4g} "
                          "(negative samples outweigh the rest)")
        checked = type(checked)(checked.grid, np.where(negative[:, None], 0.0, checked.values),
                                reasons.astype(str), checked.batch_shape)
        if checked.batch_shape == ():
            raise SpectrumError(f"{argument}: {checked.reasons[0]}")
    return checked, checked.refuse(total)


def luminous_quantity(spd, vision: str = "photopic") -> np.ndarray:
    """Luminous flux (lm), illuminance (lx) or luminance (cd/m²) of spectra ``(..., K)``.

    Parameters
    ----------
    spd : Spectrum
        Spectral radiant flux (W/nm), irradiance (W·m⁻²·nm⁻¹) or radiance
        (W·sr⁻¹·m⁻²·nm⁻¹), covering 380–780 nm; the result is in lm, lx or cd/m².
    vision : str
        ``"photopic"`` (V(λ), 683 lm/W) or ``"scotopic"`` (V'(λ), 1700 lm/W).

    Returns
    -------
    ndarray
        Shape ``spd.batch_shape``; NaN for a light refused in a batch (no power, negative
        power, not finite, not covering 380–780 nm: :func:`~spectrocolor.lighting.light_refusals`).

    Raises
    ------
    SpectrumError
        For a non-Spectrum, and for a single light that is refused.

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
    checked, total = checked_luminous(spd, vision)
    return total.reshape(checked.batch_shape)


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
        LER in lm/W; NaN for a light refused in a batch: no power, negative power, values that
        are not finite, or a spectrum that does not cover 380–780 nm (the radiant sum depends on
        the range; :func:`~spectrocolor.lighting.light_refusals` says which and why).

    Raises
    ------
    ColorimetryError
        For an unknown ``vision``.
    SpectrumError
        For a non-Spectrum, and for a single light that is refused.

    References
    ----------
    CIE 015:2018 §7.1 (K_m = 683 lm/W); ISO 23539:2005 / CIE S 010/E:2004 (V(λ), V′(λ), K′_m).

    Examples
    --------
    >>> from spectrocolor import wavelength_grid
    >>> green = Spectrum.block(555, 555, wavelength_grid(380, 780, 1))
    >>> round(float(luminous_efficacy_of_radiation(green)), 1)  # V(555 nm) = 1
    683.0
    """
    checked, luminous = checked_luminous(spd, vision)
    radiant = checked.refuse(checked.values @ interval_weights_nm(checked.grid))
    with np.errstate(divide="ignore", invalid="ignore"):
        return (luminous / radiant).reshape(checked.batch_shape)
