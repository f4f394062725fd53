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
from .spectra import light_grid

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

    def __len__(self) -> int:
        return len(self.names)

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


def light_report(spd) -> LightReport:
    """Every lighting metric of lights ``(..., K)`` (flattened to N lights).

    ``spd`` as for :func:`~spectrocolor.lighting.colour_fidelity` (1 or 5 nm, 380–780 nm at
    least); CIE 13.3 uses samples from 360 nm where present.

    Parameters
    ----------
    spd : Spectrum
        Spectral power distributions ``(..., K)`` of the lights, uniform 1 or 5 nm, covering
        380–780 nm; any scale.

    Returns
    -------
    LightReport
        CRI, fidelity, LER and α-opic quantities of the N lights.

    Raises
    ------
    ColorimetryError
        For a grid that does not cover 380–780 nm at 1 or 5 nm, and as the metrics.

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
    light_grid(spd, 380.0, 780.0)  # one clear error before any work
    flat = _flat(spd)
    names = spd.names if spd.names and len(spd.names) == len(flat.values) else tuple(
        f"spectrum {i + 1}" for i in range(len(flat.values)))
    return LightReport(
        names=tuple(names),
        cri=colour_rendering_index(flat),
        fidelity=colour_fidelity(flat),
        ler_lm_per_W=luminous_efficacy_of_radiation(flat),
        alpha_opic=alpha_opic(flat),
    )


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
