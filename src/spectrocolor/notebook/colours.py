"""Swatches on the default display, with the explorer's gamut badge.

The default display is the explorer's (sRGB, :data:`spectrocolor.display.gamut.DEFAULT_GAMUT`).
Object colours are Bradford-adapted from the perfect white under their illuminant to the
display's white (as :func:`spectrocolor.measurement_report` does); lights keep their own
brightness relation to nothing, so each is shown as bright as the display allows (normalisation
``"per-colour"``, SPECTRA's alternative B) after adapting the equal-energy white E to the
display's white (the explorer's default). A colour the display cannot show carries the badge the
explorer puts on its card: the channels that left 0–1 and what the gamut strategy did
(:data:`spectrocolor.display.explain.GAMUT_ACTIONS`).

Examples
--------
>>> import numpy as np
>>> shown = object_swatches(np.array([[20.0, 21.0, 22.0]]), np.array([95.047, 100.0, 108.883]))
>>> shown.hexes, shown.badges
(['#807e7c'], [None])
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..display.adaptation import adapt
from ..display.explain import GAMUT_ACTIONS, explain, out_of_gamut_channels
from ..display.gamut import DEFAULT_GAMUT
from ..display.render import Rendering, render
from ..display.spaces import rgb_space

__all__ = ["DISPLAY", "Swatches", "object_swatches", "light_swatches", "swatches_of", "badge_text", "hex_of"]

#: The explorer's default display.
DISPLAY = "sRGB"


@dataclass(frozen=True)
class Swatches:
    """Display colours of a few colours, with what the gamut strategy did to each.

    Attributes
    ----------
    hexes : list of str or None
        ``"#rrggbb"``; None for a colour that has no light or is not finite.
    badges : list of str or None
        The explorer's badge text for a colour outside the display, else None.
    explanations : list of str
        The library's one-line explanation (:func:`spectrocolor.display.explain.explain`), or
        why there is no colour.
    rendering : Rendering or None
        The rendering of the colours that were shown.
    """

    hexes: list
    badges: list
    explanations: list
    rendering: Rendering | None


def hex_of(codes) -> str:
    """``"#rrggbb"`` of three 8-bit codes.

    Parameters
    ----------
    codes : sequence of int, length 3
        8-bit codes.

    Returns
    -------
    str
        The hex colour.

    Examples
    --------
    >>> hex_of([255, 128, 0])
    '#ff8000'
    """
    r, g, b = (int(c) for c in codes)
    return f"#{r:02x}{g:02x}{b:02x}"


def badge_text(negative, over, gamut: str) -> str:
    """The explorer's badge: ``"R negative, G above 1: <what the strategy did>"``.

    Parameters
    ----------
    negative, over : list of str
        Channels below 0 and above 1.
    gamut : str
        The strategy applied.

    Returns
    -------
    str
        The badge text.

    Examples
    --------
    >>> badge_text(["R", "B"], ["G"], "flag")
    'R negative, B negative, G above 1: shown black'
    """
    channels = [f"{c} negative" for c in negative] + [f"{c} above 1" for c in over]
    return f"{', '.join(channels)}: {GAMUT_ACTIONS.get(gamut, gamut)}"


def swatches_of(rendering: Rendering | None, shown, count: int, reason: str = "no light") -> Swatches:
    """Swatches from a rendering of the colours ``shown`` (a boolean mask over ``count`` colours).

    Parameters
    ----------
    rendering : Rendering or None
        The rendering of ``XYZ[shown]`` (8-bit), or None when nothing was shown.
    shown : array_like of bool, shape (count,)
        Which colours were rendered.
    count : int
        Number of colours.
    reason : str, default "no light"
        Explanation for the colours not rendered.

    Returns
    -------
    Swatches
        One entry per colour.

    Examples
    --------
    >>> r = render([[1.0, 60.0, 5.0]], gamut="flag")
    >>> swatches_of(r, [True, False], 2).badges
    ['R negative, B negative, G above 1: shown black', None]
    """
    shown = np.asarray(shown, dtype=bool).reshape(-1)
    hexes: list = [None] * count
    badges: list = [None] * count
    lines = [reason] * count
    if rendering is not None and shown.any():
        codes = np.asarray(rendering.codes).reshape(-1, 3)
        inside = np.asarray(rendering.in_gamut).reshape(-1)
        negative, over = out_of_gamut_channels(rendering)
        messages = explain(rendering)
        for j, i in enumerate(np.flatnonzero(shown).tolist()):
            hexes[i] = hex_of(codes[j])
            lines[i] = messages[j]
            if not inside[j]:
                badges[i] = badge_text(negative[j], over[j], rendering.gamut)
    return Swatches(hexes, badges, lines, rendering)


def object_swatches(XYZ100, white_XYZ) -> Swatches:
    """Object colours (XYZ100 under an illuminant with perfect white ``white_XYZ``) on the display.

    Parameters
    ----------
    XYZ100 : array_like, shape (N, 3)
        Tristimulus values, perfect white Y = 100.
    white_XYZ : array_like, shape (3,)
        The perfect white under the same illuminant and observer.

    Returns
    -------
    Swatches
        sRGB codes after Bradford adaptation to the display's white and the default gamut
        strategy; None for non-finite colours.

    Examples
    --------
    >>> import numpy as np
    >>> object_swatches(np.array([[np.nan, 1.0, 1.0]]), np.array([95.047, 100.0, 108.883])).hexes
    [None]
    """
    XYZ = np.asarray(XYZ100, dtype=float).reshape(-1, 3)
    shown = np.all(np.isfinite(XYZ), axis=-1)
    space = rgb_space(DISPLAY)
    rendering = None
    if shown.any():
        rendering = render(adapt(XYZ[shown], white_XYZ, space.white_XYZ, method="bradford"), space,
                           gamut=DEFAULT_GAMUT, bit_depth=8)
    return swatches_of(rendering, shown, len(XYZ), reason="not finite")


def light_swatches(XYZ, white_XYZ) -> Swatches:
    """Lights on the display, each as bright as it can be shown (normalisation "per-colour").

    Parameters
    ----------
    XYZ : array_like, shape (N, 3)
        Tristimulus values of the lights (any common scale).
    white_XYZ : array_like, shape (3,)
        The equal-energy white E on the same scale (adapted to the display's white).

    Returns
    -------
    Swatches
        sRGB codes; None for lights with Y ≤ 0 ("no light") or not finite.

    Examples
    --------
    >>> import numpy as np
    >>> light_swatches(np.array([[1.0, 1.0, 1.0], [0.0, 0.0, 0.0]]), np.array([1.0, 1.0, 1.0])).hexes
    ['#ffffff', None]
    """
    XYZ = np.asarray(XYZ, dtype=float).reshape(-1, 3)
    shown = np.all(np.isfinite(XYZ), axis=-1) & (XYZ[:, 1] > 0)
    space = rgb_space(DISPLAY)
    rendering = None
    if shown.any():
        target = space.white_XYZ * (np.asarray(white_XYZ)[1] / space.white_XYZ[1])
        rendering = render(adapt(XYZ[shown], white_XYZ, target, method="bradford"), space,
                           normalise="per-colour", gamut=DEFAULT_GAMUT, bit_depth=8)
    return swatches_of(rendering, shown, len(XYZ), reason="no light")
