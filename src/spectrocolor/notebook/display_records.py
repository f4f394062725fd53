"""What a notebook shows for a :class:`~spectrocolor.Rendering`: swatches and what the gamut strategy did.

Examples
--------
>>> from spectrocolor import render
>>> "shown black" in rendering_html(render([[1.0, 60.0, 5.0]], gamut="flag"))
True
"""

from __future__ import annotations

import numpy as np

from ..display.explain import GAMUT_ACTIONS
from ..display.render import Rendering
from . import layout
from .colours import Swatches, swatches_of
from .markup import number, numbers
from .svg import Canvas, swatch_row

__all__ = ["SHOWN_COLOURS", "SHOWN_ROWS", "rendering_html", "rendering_svg", "rendering_text", "rendering_swatches"]

#: Swatches drawn of a large rendering (the rest are counted).
SHOWN_COLOURS = 24
#: Table rows of a large rendering.
SHOWN_ROWS = 8


def _count(rendering) -> int:
    return int(np.prod(np.shape(rendering.in_gamut), dtype=np.int64))


def rendering_swatches(rendering, count: int) -> Swatches:
    """Swatches of the first ``count`` colours of a rendering (8-bit codes, else the encoded values).

    Parameters
    ----------
    rendering : Rendering
        From :func:`spectrocolor.render`.
    count : int
        How many colours (from the first, C order).

    Returns
    -------
    Swatches
        Hex colours, the explorer's badges and the library's explanations.

    Examples
    --------
    >>> from spectrocolor import render
    >>> rendering_swatches(render([[20.0, 21.0, 22.0]]), 1).hexes
    ['#807e7c']
    """
    n = min(count, _count(rendering))

    def first(array, width=None):
        flat = np.asarray(array)
        return flat.reshape(-1, width)[:n] if width else flat.reshape(-1)[:n]

    codes = first(rendering.codes, 3)
    if rendering.bit_depth != 8:  # e.g. SPECTRA's 64 levels: show the encoded values on this screen
        codes = np.round(first(rendering.rgb_encoded, 3) * 255).astype(np.int64)
    part = Rendering(first(rendering.rgb_linear, 3), first(rendering.rgb_encoded, 3), codes,
                     first(rendering.in_gamut), first(rendering.negative, 3), first(rendering.over, 3),
                     first(rendering.rgb_unmapped, 3), rendering.gamut, rendering.normalise,
                     rendering.scale, rendering.space, 8)
    return swatches_of(part, np.ones(n, dtype=bool), n)


def _summary(rendering) -> str:
    count = _count(rendering)
    outside = count - int(np.count_nonzero(rendering.in_gamut))
    colours = "1 colour" if count == 1 else f"{count:,} colours"
    state = "all in gamut" if outside == 0 else f"{outside:,} outside the display"
    return f"{colours}, {rendering.space}, {rendering.bit_depth}-bit, normalise={rendering.normalise!r}, " \
           f"gamut={rendering.gamut!r}, {state}"


def rendering_text(rendering) -> str:
    """One line: count, space, depth, normalisation, strategy, how many left the gamut, first hex.


    Examples
    --------
    >>> from spectrocolor import render
    >>> rendering_text(render([[20.0, 21.0, 22.0], [1.0, 60.0, 5.0]]))
    "Rendering(2 colours, sRGB, 8-bit, normalise='none', gamut='desaturate', 1 outside the display, \
hex=['#807e7c', '#00e89d'])"
    """
    shown = rendering_swatches(rendering, 4).hexes
    more = ", …" if _count(rendering) > len(shown) else ""
    hexes = ", ".join(repr(h) for h in shown)
    return f"Rendering({_summary(rendering)}, hex=[{hexes}{more}])"


def rendering_html(rendering) -> str:
    """HTML: swatches, what the gamut strategy did, and a table of the first colours.


    Examples
    --------
    >>> from spectrocolor import render
    >>> "#807e7c" in rendering_html(render([[20.0, 21.0, 22.0]]))
    True
    """
    count = _count(rendering)
    swatches = rendering_swatches(rendering, SHOWN_COLOURS)
    picture = Canvas(min(len(swatches.hexes), SHOWN_COLOURS) * 23 + 2, 24, f"{count} rendered colours")
    picture.add(*swatch_row(swatches.hexes, 1, 1, 20, swatches.explanations))
    linear = np.asarray(rendering.rgb_unmapped).reshape(-1, 3)
    codes = np.asarray(rendering.codes).reshape(-1, 3)
    rows = []
    for i in range(min(SHOWN_ROWS, count)):
        colour, badge = swatches.hexes[i], swatches.badges[i]
        rows.append([layout.swatch(colour, swatches.explanations[i]), f"#{i}", numbers(linear[i], 3),
                     "  ".join(str(int(c)) for c in codes[i]), colour,
                     layout.badge(badge, swatches.explanations[i]) if badge else "in gamut"])
    parts = [picture.markup(),
             layout.table(["", "", "linear R G B (before gamut)", "codes", "shown", "display"], rows,
                          text_columns=(0, 1, 5))]
    action = GAMUT_ACTIONS.get(rendering.gamut, rendering.gamut)
    parts.append(layout.note(f"gamut strategy {rendering.gamut!r}: a colour the display cannot show is {action}"
                             if rendering.gamut == "flag" else
                             f"gamut strategy {rendering.gamut!r}: outside the display, {action}"))
    scale = np.asarray(rendering.scale, dtype=float)
    if scale.size == 1:
        parts.append(layout.note(f"scale: linear RGB divided by {number(float(scale.reshape(-1)[0]), 4)}"))
    if count > SHOWN_ROWS:
        parts.append(layout.note(f"first {min(SHOWN_COLOURS, count)} swatches and {SHOWN_ROWS} rows of "
                                 f"{count:,} colours shown"))
    return str(layout.card("Rendering", _summary(rendering), parts))


def rendering_svg(rendering) -> str:
    """Standalone SVG: the first swatches in a row.


    Examples
    --------
    >>> from spectrocolor import render
    >>> 'fill="#807e7c"' in rendering_svg(render([[20.0, 21.0, 22.0]]))
    True
    """
    swatches = rendering_swatches(rendering, SHOWN_COLOURS)
    canvas = Canvas(len(swatches.hexes) * 23 + 2, 24, _summary(rendering))
    canvas.add(*swatch_row(swatches.hexes, 1, 1, 20, swatches.explanations))
    return str(canvas.markup(standalone=True))
