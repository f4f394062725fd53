"""What a notebook shows for :class:`~spectrocolor.FilmColours` and seed 000's ``ZawischaStrip``: the strip.

A series of films is a strip of its colours in order (a map of films, ``(H, W)``, a small
picture), thinned to at most :data:`~spectrocolor.notebook.svg.MAX_CELLS` cells, with the first
few colours in a table (XYZ100, xy, the display colour and the gamut badge). Zawischa's strip
carries its ticks every 500 nm of optical path difference, as in seed 000.

Examples
--------
>>> from spectrocolor import soap_film, film_colours, wavelength_grid
>>> colours = film_colours(soap_film([100.0, 300.0, 500.0], wavelength_grid(380, 780, 5)))
>>> "#c8ffa8" in film_colours_html(colours)
True
"""

from __future__ import annotations

import numpy as np

from . import layout
from .display_records import rendering_swatches
from .markup import element, number
from .svg import MAX_CELLS, Canvas, strip, thin

__all__ = ["SHOWN_ROWS", "film_colours_html", "film_colours_svg", "film_colours_text", "zawischa_strip_html",
           "zawischa_strip_svg", "zawischa_strip_text"]

#: Films listed in the table.
SHOWN_ROWS = 6
_SIDE = int(MAX_CELLS**0.5)


def _codes(colours) -> np.ndarray:
    """Display colours as 8-bit codes, the batch shape kept."""
    rendering = colours.rendering
    if rendering.bit_depth == 8:
        return np.asarray(rendering.codes)
    return np.round(np.asarray(rendering.rgb_encoded) * 255).astype(np.int64)


def _picture(colours, width: int = 520) -> Canvas:
    codes = _codes(colours)
    shape = codes.shape[:-1]
    if len(shape) <= 1:
        canvas = Canvas(width, 34, f"{int(np.prod(shape))} film colours in order")
        canvas.add(*strip(codes.reshape(-1, 3), 1, 1, width - 2, 32))
        return canvas
    grid = codes.reshape(-1, shape[-1], 3) if len(shape) > 2 else codes
    rows, cols = thin(grid.shape[0], _SIDE), thin(grid.shape[1], _SIDE)
    cell = max(2.0, min(8.0, 360.0 / max(len(rows), len(cols))))
    canvas = Canvas(int(len(cols) * cell) + 2, int(len(rows) * cell) + 2, f"film colours, shape {shape}")
    for i, r in enumerate(rows.tolist()):
        for j, c in enumerate(cols.tolist()):
            red, green, blue = (int(v) for v in grid[r, c])
            canvas.add(element("rect", x=f"{1 + j * cell:.1f}", y=f"{1 + i * cell:.1f}", width=f"{cell + 0.2:.1f}",
                               height=f"{cell + 0.2:.1f}", fill=f"#{red:02x}{green:02x}{blue:02x}"))
    return canvas


def _summary(colours) -> str:
    shape = np.shape(colours.rendering.in_gamut)
    count = int(np.prod(shape, dtype=np.int64))
    outside = count - int(np.count_nonzero(colours.rendering.in_gamut))
    films = "one film" if not shape else f"{count:,} films" + (f" (shape {shape})" if len(shape) > 1 else "")
    return (f"{films} · {colours.illuminant}, {colours.observer} · exposure {colours.exposure!r} · "
            f"{colours.rendering.space}, gamut {colours.rendering.gamut!r}, "
            + ("all in gamut" if outside == 0 else f"{outside:,} outside the display"))


def film_colours_text(colours) -> str:
    """One line: how many films, the light, observer, exposure and display.


    Examples
    --------
    >>> from spectrocolor import soap_film, film_colours, wavelength_grid
    >>> film_colours_text(film_colours(soap_film([100.0, 300.0], wavelength_grid(380, 780, 5))))
    "FilmColours(2 films · blackbody 6504 K, CIE 1931 2° · exposure 'global-max' · sRGB, gamut 'desaturate', \
all in gamut)"
    """
    return f"FilmColours({_summary(colours)})"


def _table(colours):
    count = int(np.prod(np.shape(colours.rendering.in_gamut), dtype=np.int64))
    n = min(count, SHOWN_ROWS)
    swatches = rendering_swatches(colours.rendering, n)
    XYZ = np.asarray(colours.XYZ100, dtype=float).reshape(-1, 3)
    xy = np.asarray(colours.xy, dtype=float).reshape(-1, 2)
    rows = []
    for i in range(n):
        colour, badge = swatches.hexes[i], swatches.badges[i]
        rows.append([layout.swatch(colour, swatches.explanations[i]), f"#{i}", *(number(v, 3) for v in XYZ[i]),
                     *(number(v, 4) for v in xy[i]), colour, layout.badge(badge, swatches.explanations[i]) if badge
                     else ""])
    table = layout.table(["", "", "X", "Y", "Z", "x", "y", colours.rendering.space, ""], rows,
                         text_columns=(0, 1, 8))
    notes = [layout.note(f"first {n} of {count:,} films listed")] if count > n else []
    return [table, *notes]


def film_colours_html(colours) -> str:
    """HTML: the strip (or map) of film colours and the first films in a table.


    Examples
    --------
    >>> from spectrocolor import soap_film, film_colours, wavelength_grid
    >>> "FilmColours" in film_colours_html(film_colours(soap_film([100.0], wavelength_grid(380, 780, 5))))
    True
    """
    return str(layout.card("FilmColours", _summary(colours), [_picture(colours).markup(), *_table(colours)]))


def film_colours_svg(colours) -> str:
    """Standalone SVG: the strip (or map) of film colours.


    Examples
    --------
    >>> from spectrocolor import soap_film, film_colours, wavelength_grid
    >>> film_colours_svg(film_colours(soap_film([100.0], wavelength_grid(380, 780, 5)))).startswith("<svg")
    True
    """
    return str(_picture(colours).markup(standalone=True))


def _zawischa_canvas(strip_record, width: int = 620) -> Canvas:
    codes = _codes(strip_record.colours).reshape(-1, 3)
    opd = np.asarray(strip_record.opd_nm, dtype=float)
    canvas = Canvas(width, 68, f"soap-film colours against optical path difference, {opd[0]:g}–{opd[-1]:g} nm")
    canvas.add(*strip(codes, 1, 1, width - 2, 36))
    step = (width - 2) / len(codes)
    for column in np.asarray(strip_record.tick_columns).tolist():
        x = 1 + (column + 0.5) * step
        canvas.add(element("line", x1=f"{x:.1f}", x2=f"{x:.1f}", y1="37", y2="43", stroke="currentColor"),
                   element("text", f"{opd[column]:g}", x=f"{x:.1f}", y="53", text_anchor="middle",
                           fill="currentColor", font_size=9))
    canvas.add(element("text", "optical path difference, nm", x=1, y=66, fill="currentColor", fill_opacity="0.7",
                       font_size=9))
    return canvas


def zawischa_strip_html(strip_record) -> str:
    """HTML: seed 000's strip with its ticks, and what it was computed with.


    Examples
    --------
    >>> from spectrocolor import zawischa_strip
    >>> "optical path difference" in zawischa_strip_html(zawischa_strip(columns=200))
    True
    """
    colours = strip_record.colours
    parts = [_zawischa_canvas(strip_record).markup(),
             layout.note("seed 000 (Zawischa): two-beam soap film under a 6504 K blackbody, luminance-preserving "
                         "treatment of negative RGB, the largest channel of the series at full drive")]
    return str(layout.card("ZawischaStrip", _summary(colours), parts))


def zawischa_strip_svg(strip_record) -> str:
    """Standalone SVG: seed 000's strip with its ticks.


    Examples
    --------
    >>> from spectrocolor import zawischa_strip
    >>> zawischa_strip_svg(zawischa_strip(columns=200)).count("<line") >= 2
    True
    """
    return str(_zawischa_canvas(strip_record).markup(standalone=True))


def zawischa_strip_text(strip_record) -> str:
    """One line: columns, the range of optical path difference, the ticks and the colours' summary.


    Examples
    --------
    >>> from spectrocolor import zawischa_strip
    >>> zawischa_strip_text(zawischa_strip(columns=200))[:60]
    'ZawischaStrip(200 columns, 5–1000 nm, 2 ticks · 200 films · '
    """
    opd = np.asarray(strip_record.opd_nm, dtype=float)
    return (f"ZawischaStrip({opd.size} columns, {opd[0]:g}–{opd[-1]:g} nm, {len(strip_record.tick_columns)} ticks"
            f" · {_summary(strip_record.colours)})")
