"""Every lighting metric of a batch of lights at once, and the headline numbers of one light.

:func:`summary` gives the headline numbers of one light as plain floats (for the explorer app
and other callers); :func:`light_report` computes everything for a batch at once, for the
writers of :mod:`spectrocolor.lighting.report`.

Headline: CCT (K), Duv, Ra, R9 (CIE 13.3), Rf, Rg (CIE 224:2017 / TM-30-20), luminous
efficacy of radiation (lm/W), melanopic DER (CIE S 026), and whether CIE 13.3 considers the
CCT meaningful (``|Duv|`` ≤ 5.4 × 10⁻³).

References
----------
CIE 13.3-1995; CIE 224:2017; ANSI/IES TM-30-20; CIE S 026/E:2018.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..errors import ColorimetryError
from ..spectrum import Spectrum
from .alpha_opic import AlphaOpic, alpha_opic
from .cri import CRI, colour_rendering_index
from .fidelity import Fidelity, colour_fidelity
from .photometry import luminous_efficacy_of_radiation
from .spectra import RESAMPLE_HINT, checked_lights

#: The headline columns, in order (name → description with unit).
HEADLINE = {
    "cct_K": "correlated colour temperature, K",
    "duv": "distance from the Planckian locus, CIE 1960 uv",
    "Ra": "CIE 13.3 general colour rendering index",
    "R9": "CIE 13.3 special index of TCS09 (red)",
    "Rf": "CIE 224:2017 / TM-30 fidelity index",
    "Rg": "TM-30 gamut index",
    "LER_lm_per_W": "luminous efficacy of radiation, lm/W",
    "melanopic_DER": "CIE S 026 melanopic daylight (D65) efficacy ratio",
}


@dataclass(frozen=True)
class LightReport:
    """All lighting metrics of N lights (flattened batch), with their names.

    Attributes
    ----------
    names : tuple of str
        One name per light (the Spectrum's names, else ``spectrum 1``, …).
    cri : CRI
        CIE 13.3 colour rendering.
    fidelity : Fidelity
        CIE 224 / TM-30 fidelity and gamut.
    ler_lm_per_W : ndarray (N,)
        Luminous efficacy of radiation, lm/W.
    alpha_opic : AlphaOpic
        CIE S 026 α-opic quantities.
    ler_reason : ndarray of str (N,)
        Why a light's LER is NaN (``""`` where computed).

    Examples
    --------
    >>> from spectrocolor import illuminant
    >>> report = light_report(illuminant("FL2"))
    >>> {k: round(float(v[0]), 1) for k, v in report.headline().items() if k in ("Ra", "Rf", "LER_lm_per_W")}
    {'Ra': 64.2, 'Rf': 70.1, 'LER_lm_per_W': 336.4}
    """

    names: tuple
    cri: CRI
    fidelity: Fidelity
    ler_lm_per_W: np.ndarray
    alpha_opic: AlphaOpic
    ler_reason: np.ndarray

    def __len__(self) -> int:
        return len(self.names)

    def reasons(self) -> np.ndarray:
        """Why each light has NaN metrics, one line per light (``""`` where all are computed).

        Returns
        -------
        numpy.ndarray of str, shape (N,)
            The distinct reasons of CIE 13.3, CIE 224 / TM-30, LER and α-opic, joined by "; ".

        Examples
        --------
        >>> import numpy as np
        >>> from spectrocolor import Spectrum, illuminant
        >>> fl2 = illuminant("FL2")
        >>> report = light_report(Spectrum(fl2.wavelengths_nm, np.stack([fl2.values, -fl2.values])))
        >>> [reason[:14] for reason in report.reasons()]
        ['', 'negative power']
        """
        out = []
        for parts in zip(self.cri.reason, self.fidelity.reason, self.ler_reason, self.alpha_opic.reason,
                         strict=True):
            distinct = list(dict.fromkeys(str(p) for p in parts if p))
            out.append("; ".join(distinct))
        return np.array(out, dtype=str)

    def headline(self) -> dict[str, np.ndarray]:
        """The :data:`HEADLINE` columns as arrays (N,).

        Returns
        -------
        dict of str to numpy.ndarray
            ``cct_K``, ``duv``, ``Ra``, ``R9``, ``Rf``, ``Rg``, ``LER_lm_per_W``,
            ``melanopic_DER``, each of shape (N,).

        Examples
        --------
        >>> from spectrocolor import illuminant
        >>> list(light_report(illuminant("FL2")).headline())
        ['cct_K', 'duv', 'Ra', 'R9', 'Rf', 'Rg', 'LER_lm_per_W', 'melanopic_DER']
        """
        return {
            "cct_K": self.fidelity.cct_K,
            "duv": self.fidelity.duv,
            "Ra": self.cri.Ra,
            "R9": self.cri.R9,
            "Rf": self.fidelity.Rf,
            "Rg": self.fidelity.Rg,
            "LER_lm_per_W": self.ler_lm_per_W,
            "melanopic_DER": self.alpha_opic.melanopic_der,
        }


def _flat(spd: Spectrum) -> Spectrum:
    return spd if spd.values.ndim == 2 else Spectrum(spd.wavelengths_nm, spd.values.reshape(-1, spd.values.shape[-1]))


def light_report(spd, *, rounding: str = "none", resample_hint: str = RESAMPLE_HINT) -> LightReport:
    """Every lighting metric of lights ``(..., K)`` (flattened to N lights).

    ``spd`` as for :func:`~spectrocolor.lighting.colour_fidelity` (1 or 5 nm, 380–780 nm at
    least); CIE 13.3 uses samples from 360 nm where present. A light that a metric refuses (no
    power, negative power, values that are not finite, a spectrum not covering 380–780 nm) gets
    NaN there and its reason (:meth:`LightReport.reasons`); the other lights are computed as
    alone.

    Parameters
    ----------
    spd : Spectrum
        Spectral power distributions ``(..., K)`` of the lights, uniform 1 or 5 nm, covering
        380–780 nm; any scale.
    rounding : {"none", "integer"}, keyword-only, default "none"
        The CIE 13.3 indices as computed, or rounded as CIE reports them
        (:data:`spectrocolor.lighting.cri.ROUNDINGS`).
    resample_hint : str, keyword-only
        How a refused grid interval is to be fixed (the command line names its own option).

    Returns
    -------
    LightReport
        CRI, fidelity, LER and α-opic quantities of the N lights.

    Raises
    ------
    SpectrumError
        For a grid other than 1 or 5 nm, and for a single light (shape ``(K,)``) that is refused.

    References
    ----------
    CIE 13.3-1995; CIE 224:2017 and ANSI/IES TM-30-20; CIE S 026/E:2018.

    Examples
    --------
    >>> from spectrocolor import illuminant
    >>> report = light_report(illuminant("FL2"))
    >>> len(report), round(float(report.fidelity.Rf[0]), 1)
    (1, 70.1)
    """
    checked_lights(spd, "fidelity", resample_hint=resample_hint)  # one clear error before any work
    flat = _flat(spd)
    names = spd.names if spd.names and len(spd.names) == len(flat.values) else tuple(
        f"spectrum {i + 1}" for i in range(len(flat.values)))
    return LightReport(
        names=tuple(names),
        cri=colour_rendering_index(flat, rounding, resample_hint=resample_hint),
        fidelity=colour_fidelity(flat, resample_hint=resample_hint),
        ler_lm_per_W=luminous_efficacy_of_radiation(flat),
        alpha_opic=alpha_opic(flat),
        ler_reason=light_refusals_ler(flat),
    )


def light_refusals_ler(spd) -> np.ndarray:
    """Why the LER of each light of a batch is NaN (``""`` where computed), shape (N,).

    Parameters
    ----------
    spd : Spectrum
        Lights ``(N, K)``.

    Returns
    -------
    numpy.ndarray of str, shape (N,)
        The photometric refusals (:func:`~spectrocolor.lighting.spectra.checked_lights`,
        negative luminous sums).

    Examples
    --------
    >>> import numpy as np
    >>> from spectrocolor import Spectrum, illuminant
    >>> fl2 = illuminant("FL2")
    >>> light_refusals_ler(Spectrum(fl2.wavelengths_nm, np.stack([fl2.values, 0 * fl2.values]))).tolist()
    ['', 'no power: every sample from 380 to 780 nm is 0']
    """
    from .photometry import checked_luminous

    checked, _ = checked_luminous(spd, "photopic")
    return checked.reasons


def summary(spd) -> dict[str, float | bool]:
    """Headline numbers of one light as plain Python floats: CCT, Duv, Ra, R9, Rf, Rg, LER, DER.

    For the explorer app and other callers that want JSON-ready values; NaN where a metric is
    undefined (no CCT). ``cri_meaningful`` is CIE 13.3's ``|Duv|`` ≤ 5.4 × 10⁻³.

    Parameters
    ----------
    spd : Spectrum
        One light's spectral power distribution (1 or 5 nm, covering 380–780 nm; any scale).

    Returns
    -------
    dict of str to float or bool
        The :data:`HEADLINE` values and ``cri_meaningful``.

    Raises
    ------
    ColorimetryError
        As :func:`light_report`.

    Examples
    --------
    >>> from spectrocolor import illuminant
    >>> values = summary(illuminant("FL2"))
    >>> {key: round(values[key], 1) for key in ("cct_K", "Ra", "Rf", "Rg")}
    {'cct_K': 4224.5, 'Ra': 64.2, 'Rf': 70.1, 'Rg': 86.4}
    """
    if not isinstance(spd, Spectrum) or spd.batch_shape not in ((), (1,)):
        shape = spd.batch_shape if isinstance(spd, Spectrum) else type(spd).__name__
        raise ColorimetryError(f"spd: summary takes one light (a Spectrum of shape (K,)), got {shape}")
    report = light_report(spd)
    values: dict[str, float | bool] = {key: float(column[0]) for key, column in report.headline().items()}
    values["cri_meaningful"] = bool(report.cri.meaningful[0])
    return values
