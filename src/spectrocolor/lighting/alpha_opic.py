"""CIE S 026 α-opic quantities: irradiances, efficacies, equivalent daylight illuminances, DER.

For each of the five photoreceptor types α (S-cone-opic, M-cone-opic, L-cone-opic, rhodopic,
melanopic), with the action spectra s_α(λ) of CIE S 026 Table 2 (peak 1):

* α-opic irradiance E_α = Σ E(λ) s_α(λ) Δλ, W/m², from a spectral irradiance in
  W·m⁻²·nm⁻¹ (any other radiometric quantity gives the matching α-opic quantity);
* α-opic efficacy of luminous radiation (ELR) K_α,v = E_α / E_v, W/lm, with E_v the
  illuminance (:func:`~spectrocolor.lighting.photometry.luminous_quantity`);
* α-opic equivalent daylight (D65) illuminance (EDI) E_v,α^D65 = E_α / K_α,v^D65, lx: the
  illuminance of D65 that gives the same α-opic irradiance (melanopic EDI is the quantity
  recommended for reporting light exposure);
* α-opic daylight (D65) efficacy ratio (DER) γ_α,v^D65 = K_α,v / K_α,v^D65 (scale-free).

The D65 efficacies K_α,v^D65 are computed here from the same tables (D65 interpolated linearly
to 1 nm); they reproduce the values CIE S 026 publishes (0.8173, 1.4558, 1.6289, 1.4497,
1.3262 mW/lm) to the digits printed, which the tests check.

The action spectra are tabulated at 1 nm from 380 to 780 nm (blank cells of the table are 0),
interpolated linearly at the spectrum's samples and zero outside (as V'(λ) in
:mod:`~spectrocolor.lighting.photometry`); the spectrum must cover 380–780 nm. A light with no
power, negative power (``Σ S Δλ ≤ 0``, or a negative α-opic or luminous sum) or values that are
not finite is refused: NaN and a ``reason`` in a batch, a
:class:`~spectrocolor.errors.SpectrumError` for one light.

References
----------
CIE S 026/E:2018 *CIE system for metrology of optical radiation for ipRGC-influenced responses
to light*, §3, Table 2 (action spectra), and its D65 efficacies. DOI 10.25039/S026.2018.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cache, lru_cache

import numpy as np

from ..data_tables import load_table
from ..errors import SpectrumError
from ..illuminants import illuminant
from ..sampling import interval_weights_nm
from ..spectrum import wavelength_grid
from .photometry import checked_luminous, luminous_quantity, weighting_on
from .spectra import CheckedLights, checked_lights

#: The five α-opic quantities, in the order of every (..., 5) array here.
ALPHA_OPIC = ("s-cone-opic", "m-cone-opic", "l-cone-opic", "rhodopic", "melanopic")
_COLUMNS = ("s_sc", "s_mc", "s_lc", "s_rh", "s_mel")


@dataclass(frozen=True)
class AlphaOpic:
    """α-opic quantities of spectra; arrays ``(..., 5)`` in the order of :data:`ALPHA_OPIC`.

    Attributes
    ----------
    irradiance_W_m2 : ndarray
        α-opic irradiances E_α (W/m² for a spectral irradiance in W·m⁻²·nm⁻¹).
    efficacy_W_lm : ndarray
        α-opic efficacies of luminous radiation K_α,v = E_α / E_v (W/lm).
    edi_lx : ndarray
        α-opic equivalent daylight (D65) illuminances (lx).
    der : ndarray
        α-opic daylight (D65) efficacy ratios (1 for D65).
    illuminance_lx : ndarray
        Photopic illuminance E_v (lx), shape ``(...)``.
    reason : ndarray of str
        Why a light's quantities are NaN, shape ``(...)``; ``""`` where they are computed.

    References
    ----------
    CIE S 026/E:2018, *CIE system for metrology of optical radiation for ipRGC-influenced
    responses to light*.

    Examples
    --------
    >>> from spectrocolor import alpha_opic, illuminant, wavelength_grid
    >>> d65 = alpha_opic(illuminant("D65", wavelength_grid(380, 780, 5)))
    >>> d65.der.round(3).tolist()  # D65 is the reference: every ratio is 1
    [1.0, 1.0, 1.0, 1.0, 1.0]
    """

    irradiance_W_m2: np.ndarray
    efficacy_W_lm: np.ndarray
    edi_lx: np.ndarray
    der: np.ndarray
    illuminance_lx: np.ndarray
    reason: np.ndarray

    @property
    def melanopic_edi_lx(self) -> np.ndarray:
        """Melanopic equivalent daylight (D65) illuminance, lx."""
        return self.edi_lx[..., 4]

    @property
    def melanopic_der(self) -> np.ndarray:
        """Melanopic daylight (D65) efficacy ratio."""
        return self.der[..., 4]


@cache
def _action_table() -> tuple[np.ndarray, np.ndarray]:
    header, table = load_table("lighting/cie_s026_alpha_opic.csv")
    return table[:, 0], table[:, [header.index(c) for c in _COLUMNS]]


def action_spectra(wavelengths_nm) -> np.ndarray:
    """CIE S 026 action spectra s_α at ``wavelengths_nm``, shape (K, 5); 0 outside 380–780 nm.

    Parameters
    ----------
    wavelengths_nm : array_like, shape (K,)
        The grid, nm.

    Returns
    -------
    numpy.ndarray, shape (K, 5)
        s_sc, s_mc, s_lc, s_rh, s_mel (order of :data:`ALPHA_OPIC`), each peaking at 1.

    References
    ----------
    CIE S 026/E:2018, Table 2.

    Examples
    --------
    >>> float(action_spectra([490.0])[0, 4])  # melanopic peak
    1.0
    """
    grid, table = _action_table()
    return np.stack([weighting_on(wavelengths_nm, grid, column) for column in table.T], axis=-1)


@lru_cache(maxsize=32)
def _weights(grid_key: bytes) -> np.ndarray:
    grid = np.frombuffer(grid_key, dtype=float)
    result = action_spectra(grid) * interval_weights_nm(grid)[:, None]
    result.setflags(write=False)
    return result


def alpha_opic_irradiance(spd) -> np.ndarray:
    """α-opic irradiances ``(..., 5)``, W/m², of spectral irradiances (W·m⁻²·nm⁻¹).

    Parameters
    ----------
    spd : Spectrum
        Spectral irradiances ``(..., K)``, W·m⁻²·nm⁻¹.

    Returns
    -------
    numpy.ndarray, shape (..., 5)
        E_α = Σ E(λ) s_α(λ) Δλ, W/m²; NaN for a light refused in a batch (no power, negative
        power or α-opic sum, not finite, not covering 380–780 nm).

    Raises
    ------
    SpectrumError
        For a non-Spectrum, and for a single light that is refused.

    References
    ----------
    CIE S 026/E:2018 (α-opic irradiance).

    Examples
    --------
    >>> from spectrocolor import Spectrum
    >>> flat = Spectrum.constant(0.01, wavelength_grid(380, 780, 1))
    >>> round(float(alpha_opic_irradiance(flat)[4]), 4)  # 0.01 × Σ s_mel Δλ
    0.8768
    """
    checked, irradiance = _irradiance(checked_lights(spd, "alpha-opic"))
    return irradiance.reshape(*checked.batch_shape, len(ALPHA_OPIC))


def _irradiance(checked: CheckedLights, argument: str = "spd") -> tuple[CheckedLights, np.ndarray]:
    """α-opic irradiances (N, 5) of checked lights; lights with a negative one refused."""
    irradiance = checked.values @ _weights(np.ascontiguousarray(checked.grid).tobytes())
    negative = np.any(irradiance < 0, axis=1) & checked.ok
    if negative.any():
        reasons = checked.reasons.astype(object)
        for i in np.flatnonzero(negative):
            which = ", ".join(ALPHA_OPIC[k] for k in np.flatnonzero(irradiance[i] < 0))
            reasons[i] = f"negative power: negative {which} irradiance (negative samples outweigh the rest)"
        checked = CheckedLights(checked.grid, np.where(negative[:, None], 0.0, checked.values),
                                reasons.astype(str), checked.batch_shape)
        if checked.batch_shape == ():
            raise SpectrumError(f"{argument}: {checked.reasons[0]}")
    return checked, checked.refuse(irradiance)


@cache
def d65_efficacies_W_per_lm() -> np.ndarray:
    """α-opic efficacies of luminous radiation of D65, K_α,v^D65 (W/lm), shape (5,).

    Examples
    --------
    >>> (d65_efficacies_W_per_lm() * 1000).round(4).tolist()  # CIE S 026, mW/lm
    [0.8173, 1.4558, 1.6289, 1.4497, 1.3262]
    """
    d65 = illuminant("D65", wavelength_grid(380, 780, 1))
    result = alpha_opic_irradiance(d65) / luminous_quantity(d65)
    result.setflags(write=False)
    return result


def alpha_opic(spd) -> AlphaOpic:
    """All CIE S 026 α-opic quantities of spectral irradiances ``(..., K)`` in W·m⁻²·nm⁻¹.

    Parameters
    ----------
    spd : Spectrum
        Spectral irradiance, W·m⁻²·nm⁻¹ (relative spectra give relative irradiances and EDIs,
        and correct efficacies and DERs).

    Returns
    -------
    AlphaOpic

    References
    ----------
    CIE S 026/E:2018, §3.

    Examples
    --------
    >>> from spectrocolor import illuminant
    >>> result = alpha_opic(illuminant("A", wavelength_grid(380, 780, 5)))
    >>> round(float(result.melanopic_der), 3)  # illuminant A: half as melanopic per lux as D65
    0.496
    """
    checked, irradiance = _irradiance(checked_lights(spd, "alpha-opic"))
    spd_ok = spd if checked.ok.all() else None
    if spd_ok is None:  # the luminous sums of the lights still computed, the others 0
        from ..spectrum import Spectrum

        spd_ok = Spectrum(checked.grid, checked.values)
    lit, illuminance = checked_luminous(spd_ok, "photopic")
    reasons = np.where(checked.ok, lit.reasons.reshape(-1), checked.reasons)
    ok = reasons == ""
    illuminance = np.where(ok, illuminance.reshape(-1), np.nan)
    irradiance = np.where(ok[:, None], irradiance, np.nan)
    with np.errstate(divide="ignore", invalid="ignore"):
        efficacy = irradiance / illuminance[:, None]
    reference = d65_efficacies_W_per_lm()
    shape = checked.batch_shape
    return AlphaOpic(
        irradiance_W_m2=irradiance.reshape(*shape, 5),
        efficacy_W_lm=efficacy.reshape(*shape, 5),
        edi_lx=(irradiance / reference).reshape(*shape, 5),
        der=(efficacy / reference).reshape(*shape, 5),
        illuminance_lx=illuminance.reshape(shape),
        reason=reasons.astype(str).reshape(shape),
    )
