"""The one text that says whether a colour could be shown, and what was done if not.

SPECTRA prints "Cannot be reproduced!" and advises: "Keep an eye on the r,g,b-values displayed,
so that you know which one needs to be compensated" (seed 002, question 4). This module turns a
:class:`~spectrocolor.display.render.Rendering` into that message, naming the channels that
went negative or above full drive and the gamut strategy that was applied, so that every
interface (the explorer, the command line) says the same thing.

References
----------
P. Sällström (1999), USIP Report 99-05, STEP 3 and "Some questions", 4.
"""

from __future__ import annotations

import numpy as np

from ..errors import ColorimetryError

__all__ = ["GAMUT_ACTIONS", "out_of_gamut_channels", "explain"]

#: What each gamut strategy does to a colour the display cannot show (one line each).
GAMUT_ACTIONS = {
    "flag": "shown black",
    "clip": "each channel clipped to 0-1",
    "preserve-luminance": "negative channels set to 0 at constant luminance",
    "desaturate": "desaturated toward the white at constant luminance (hue kept)",
}

_CHANNELS = ("R", "G", "B")


def out_of_gamut_channels(rendering) -> tuple[list, list]:
    """The channel names (``"R"``, ``"G"``, ``"B"``) below 0 and above 1, per colour.

    Parameters
    ----------
    rendering : Rendering
        From :func:`~spectrocolor.display.render.render`.

    Returns
    -------
    negative, over : nested lists of str
        Same leading shape as the rendering's colours, flattened to a list of colours.

    Examples
    --------
    >>> from spectrocolor.display.render import render
    >>> out_of_gamut_channels(render([[1.0, 60.0, 5.0]], "sRGB"))
    ([['R', 'B']], [['G']])
    """
    neg = np.asarray(rendering.negative, dtype=bool).reshape(-1, 3)
    over = np.asarray(rendering.over, dtype=bool).reshape(-1, 3)
    names = np.array(_CHANNELS)
    return [names[row].tolist() for row in neg], [names[row].tolist() for row in over]


def explain(rendering) -> list[str]:
    """One line per colour: ``"in gamut"`` or ``"cannot be reproduced (…): <what was done>"``.

    Parameters
    ----------
    rendering : Rendering
        From :func:`~spectrocolor.display.render.render`.

    Returns
    -------
    list of str
        One message per colour (the rendering's colours flattened in C order).

    Examples
    --------
    >>> from spectrocolor.display.render import render
    >>> explain(render([[20.0, 21.0, 22.0], [1.0, 60.0, 5.0]], "sRGB", gamut="desaturate"))
    ['in gamut', 'cannot be reproduced (R, B negative; G above 1): desaturated toward the \
white at constant luminance (hue kept)']
    """
    if rendering.gamut not in GAMUT_ACTIONS:
        raise ColorimetryError(
            f"rendering.gamut {rendering.gamut!r} is unknown; accepted: "
            f"{', '.join(GAMUT_ACTIONS)}")
    action = GAMUT_ACTIONS[rendering.gamut]
    inside = np.asarray(rendering.in_gamut, dtype=bool).reshape(-1)
    messages = []
    for ok, neg, over in zip(inside, *out_of_gamut_channels(rendering), strict=True):
        if ok:
            messages.append("in gamut")
            continue
        what = [f"{', '.join(neg)} negative"] if neg else []
        what += [f"{', '.join(over)} above 1"] if over else []
        messages.append(f"cannot be reproduced ({'; '.join(what)}): {action}")
    return messages
