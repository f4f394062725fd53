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

from collections.abc import Iterator, Mapping

import numpy as np

from ..errors import ColorimetryError
from .gamut import GAMUT_STRATEGIES
from .spaces import rgb_space

__all__ = ["GAMUT_ACTIONS", "out_of_gamut_channels", "explain"]

class _GamutActions(Mapping[str, str]):
    """Strategy name → what it does to a colour the display cannot show: a live view of
    ``extra["action"]`` of :data:`~spectrocolor.display.gamut.GAMUT_STRATEGIES` (the
    description where a strategy gives no action), so a new strategy needs no entry here."""

    def __getitem__(self, name: str) -> str:
        if not isinstance(name, str) or name not in GAMUT_STRATEGIES.names():
            raise KeyError(name)
        return GAMUT_STRATEGIES.extra(name, "action", GAMUT_STRATEGIES.description(name))

    def __iter__(self) -> Iterator[str]:
        return iter(GAMUT_STRATEGIES.names())

    def __len__(self) -> int:
        return len(GAMUT_STRATEGIES)

    def __repr__(self) -> str:
        return repr(dict(self))


#: What each gamut strategy does to a colour the display cannot show (one line each), read
#: from the registry's entries.
GAMUT_ACTIONS: Mapping[str, str] = _GamutActions()

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
    dark = _not_positive_luminance(rendering)
    messages = []
    for ok, neg, over, no_light in zip(inside, *out_of_gamut_channels(rendering), dark, strict=True):
        if ok:
            messages.append("in gamut")
            continue
        what = [f"{', '.join(neg)} negative"] if neg else []
        what += [f"{', '.join(over)} above 1"] if over else []
        done = f"{action}; its luminance on this display is not positive, so that leaves black" if no_light else action
        messages.append(f"cannot be reproduced ({'; '.join(what)}): {done}")
    return messages


def _not_positive_luminance(rendering) -> np.ndarray:
    """Per colour: whether a luminance-keeping strategy met a colour of luminance ≤ 0 (shown black).

    A colour far outside the display's gamut can have a negative luminance in the display's own
    terms (for example after a von Kries adaptation in display RGB); keeping that luminance leaves
    nothing to show. Only the strategies that keep luminance are affected.
    """
    count = np.asarray(rendering.in_gamut).size
    if rendering.gamut not in ("desaturate", "preserve-luminance"):
        return np.zeros(count, bool)
    try:
        luminance_row = np.asarray(rgb_space(rendering.space).matrix_to_XYZ)[1]
    except (ColorimetryError, ValueError, TypeError):
        return np.zeros(count, bool)
    luminance = np.asarray(rendering.rgb_unmapped, dtype=float).reshape(-1, 3) @ luminance_row
    return luminance <= 0
