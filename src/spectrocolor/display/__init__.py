"""Faithful display: RGB spaces, transfer functions, normalisation, gamut handling, adaptation.

Modules: :mod:`.spaces` (RGB spaces), :mod:`.transfer` (transfer functions, integer codes),
:mod:`.normalise` (scales), :mod:`.gamut` (out-of-gamut strategies), :mod:`.render` (the whole
chain) and :mod:`.adaptation` (chromatic adaptation). Needs only NumPy.
"""

from .adaptation import adapt, adaptation_matrix
from .gamut import GAMUT_STRATEGIES, gamut_flags
from .normalise import NORMALISATIONS, max_object_rgb, white_scale
from .render import Rendering, render
from .spaces import RGBSpace, rgb_space, rgb_space_names
from .transfer import (
    BT2020Curve,
    LevelTable,
    PowerLaw,
    SRGBCurve,
    from_codes,
    spectra_excitation_table,
    to_codes,
    transfer,
    transfer_names,
)

__all__ = [
    "adapt",
    "adaptation_matrix",
    "GAMUT_STRATEGIES",
    "gamut_flags",
    "NORMALISATIONS",
    "max_object_rgb",
    "white_scale",
    "Rendering",
    "render",
    "RGBSpace",
    "rgb_space",
    "rgb_space_names",
    "BT2020Curve",
    "LevelTable",
    "PowerLaw",
    "SRGBCurve",
    "from_codes",
    "spectra_excitation_table",
    "to_codes",
    "transfer",
    "transfer_names",
]
