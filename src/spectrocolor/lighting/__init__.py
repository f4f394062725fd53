"""Light sources: colour rendering, colour fidelity and gamut, photometry, α-opic quantities.

Every metric takes spectral power distributions as a :class:`~spectrocolor.Spectrum` of shape
``(..., K)`` and returns arrays of the batch shape, so 100 000 candidate spectra are one call.

* :func:`colour_rendering_index` — CIE 13.3-1995 Ra, R1–R14 (:mod:`.cri`)
* :func:`colour_fidelity` — CIE 224:2017 Rf and ANSI/IES TM-30-20 Rf, Rg, hue bins
  (:mod:`.fidelity`, CAM02-UCS in :mod:`.cam02ucs`, reference illuminants in :mod:`.reference`)
* :func:`luminous_quantity`, :func:`luminous_efficacy_of_radiation` — photometry (:mod:`.photometry`)
* :func:`alpha_opic` — CIE S 026 α-opic irradiances, efficacies, EDI, DER (:mod:`.alpha_opic`)
* :func:`summary`, :func:`light_report` — every metric per light (:mod:`.summary`)
* :func:`light_refusals` — why a metric gives a light NaN (:mod:`.spectra`): no power, negative
  power, values that are not finite, a spectrum that does not cover the metric's range

Presentation sits in its own modules (the import graph of docs/design.md keeps it out of this
package's namespace): :func:`spectrocolor.lighting.report.write_light_report` (HTML, CSV,
JSON) and :func:`spectrocolor.lighting.vector_graphic.vector_graphic` (the TM-30 colour vector
graphic; needs matplotlib).
"""

from __future__ import annotations

from .alpha_opic import ALPHA_OPIC, AlphaOpic, alpha_opic, alpha_opic_irradiance, d65_efficacies_W_per_lm
from .cri import CRI, colour_rendering_index
from .fidelity import Fidelity, colour_fidelity
from .photometry import luminous_efficacy_of_radiation, luminous_quantity, radiant_quantity
from .spectra import light_refusals
from .summary import LightReport, light_report, summary

__all__ = [
    "ALPHA_OPIC",
    "AlphaOpic",
    "CRI",
    "Fidelity",
    "LightReport",
    "alpha_opic",
    "alpha_opic_irradiance",
    "colour_fidelity",
    "colour_rendering_index",
    "d65_efficacies_W_per_lm",
    "light_refusals",
    "light_report",
    "luminous_efficacy_of_radiation",
    "luminous_quantity",
    "radiant_quantity",
    "summary",
]
