"""Faithful display: RGB spaces, transfer functions, normalisation, gamut handling, adaptation.

Modules: :mod:`.spaces` (RGB spaces), :mod:`.transfer` (transfer functions, integer codes),
:mod:`.normalise` (scales), :mod:`.gamut` (out-of-gamut strategies), :mod:`.render` (the whole
chain), :mod:`.adaptation` (chromatic adaptation) and :mod:`.chain` (the explorer's linear chain:
SPECTRA's k, the adaptation of E, normalisation A). Needs only NumPy.
"""

from .adaptation import adapt, adaptation_matrix
from .chain import CHAIN_NORMALISATIONS, WHITE_ADAPTATIONS, DisplayChain, display_chain
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
    "CHAIN_NORMALISATIONS",
    "WHITE_ADAPTATIONS",
    "DisplayChain",
    "display_chain",
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
