"""What a notebook shows for :class:`~spectrocolor.CRI` and :class:`~spectrocolor.Fidelity`.

``CRI``: Ra, R9, CCT, Duv and whether CIE 13.3 applies, and the special indices R1–R14 as bars
in the colours of the test colour samples (sRGB under D65). ``Fidelity``: Rf, Rg, CCT, Duv,
the TM-30 colour vector graphic (drawn as ANSI/IES TM-30-20 §6.2 lays it out, from
:func:`spectrocolor.lighting.vector_graphic.normalised_graphic`) and the per-bin fidelity,
chroma and hue shifts. A batch of lights lists the first :data:`SHOWN_LIGHTS` and draws the
first one.

Examples
--------
>>> from spectrocolor import colour_rendering_index, illuminant
>>> "R9" in cri_html(colour_rendering_index(illuminant("FL2")))
True
"""

from __future__ import annotations

from functools import cache

import numpy as np

from ..colorimetry import weights
from ..lighting.cri import DELTA_C_LIMIT
from ..lighting.fidelity import HUE_BINS
from ..lighting.spectra import tcs_reflectances
from ..lighting.vector_graphic import bin_colours_rgb8, normalised_graphic
from ..spectrum import wavelength_grid
from . import layout
from .colours import hex_of, object_swatches
from .markup import Markup, element, number
from .svg import Canvas, nice_ticks

__all__ = ["SHOWN_LIGHTS", "tcs_hexes", "cri_html", "cri_svg", "cri_text", "fidelity_html", "fidelity_svg",
           "fidelity_text", "vector_graphic_svg"]

#: Lights of a batch listed in the table.
SHOWN_LIGHTS = 8
_TEST_RED = "#d62728"


@cache
def tcs_hexes() -> tuple[str, ...]:
    """sRGB colours of the CIE 13.3 test colour samples TCS01–TCS14 under D65 (for the bars).

    Returns
    -------
    tuple of str
        Fourteen ``"#rrggbb"``.

    Examples
    --------
    >>> len(tcs_hexes()), tcs_hexes()[8] != tcs_hexes()[9]
    (14, True)
    """
    grid = wavelength_grid(380, 780, 5)
    W = weights(grid, observer="1931", illuminant="D65")
    return tuple(object_swatches(tcs_reflectances(grid) @ W, W.sum(axis=0)).hexes)


def _batch(record, field: str) -> tuple[tuple, int]:
    shape = np.shape(getattr(record, field))
    return shape, int(np.prod(shape, dtype=np.int64))


def _flat(values, count: int, width: int | None = None) -> np.ndarray:
    array = np.asarray(values, dtype=float)
    return array.reshape(count, width) if width else array.reshape(count)


def _lights(count: int) -> str:
    return "1 light" if count == 1 else f"{count:,} lights"


def _index_label(shape: tuple, i: int) -> str:
    if not shape:
        return "light"
    if len(shape) == 1:
        return f"#{i}"
    return str(tuple(int(k) for k in np.unravel_index(i, shape)))


def _count_note(shape: tuple, count: int) -> list[Markup]:
    if count <= SHOWN_LIGHTS:
        return []
    return [layout.note(f"first {SHOWN_LIGHTS} of {count:,} lights listed (batch shape {shape}); the graphic "
                        "shows the first")]


# ----------------------------------------------------------------------------- CRI


def _cri_bars(Ri, label: str) -> Canvas:
    width, height = 330, 150
    left, top, plot_h = 30, 10, 110
    low = min(0.0, float(np.nanmin(Ri)) if np.isfinite(Ri).any() else 0.0)
    high = 100.0

    def y(value):
        return top + plot_h - (value - low) / (high - low) * plot_h

    canvas = Canvas(width, height, f"CIE 13.3 special colour rendering indices R1–R14 of {label}")
    bar = (width - left - 6) / 14
    for tick in nice_ticks(low, high, 4):
        canvas.add(element("line", x1=left, x2=width - 4, y1=f"{y(tick):.1f}", y2=f"{y(tick):.1f}",
                           stroke="currentColor", stroke_opacity="0.15"),
                   element("text", f"{tick:g}", x=left - 4, y=f"{y(tick) + 3:.1f}", text_anchor="end",
                           fill="currentColor"))
    zero = y(0.0)
    for i, (value, colour) in enumerate(zip(Ri.tolist(), tcs_hexes(), strict=True)):
        x = left + i * bar + 2
        tip = element("title", f"R{i + 1} = {number(value, 1)} (TCS{i + 1:02d})")
        if np.isfinite(value):
            top_y, bottom_y = min(y(value), zero), max(y(value), zero)
            canvas.add(element("rect", tip, x=f"{x:.1f}", y=f"{top_y:.1f}", width=f"{bar - 4:.1f}",
                               height=f"{max(bottom_y - top_y, 0.5):.1f}", fill=colour, stroke="currentColor",
                               stroke_opacity="0.35"))
        canvas.add(element("text", f"R{i + 1}", x=f"{x + (bar - 4) / 2:.1f}", y=top + plot_h + 14,
                           text_anchor="middle", fill="currentColor", font_size=9),
                   element("text", number(value, 0), x=f"{x + (bar - 4) / 2:.1f}", y=top + plot_h + 25,
                           text_anchor="middle", fill="currentColor", fill_opacity="0.7", font_size=9))
    return canvas


def _cri_row(cri, i: int, count: int, shape: tuple) -> list:
    Ra, cct, duv = (_flat(v, count)[i] for v in (cri.Ra, cri.cct_K, cri.duv))
    R9 = _flat(cri.Ri, count, 14)[i, 8]
    meaningful = bool(np.asarray(cri.meaningful).reshape(count)[i])
    return [_index_label(shape, i), number(Ra, 1), number(R9, 1), number(cct, 0), number(duv, 4),
            "yes" if meaningful else f"no (|Duv| > {DELTA_C_LIMIT:g} or no CCT)"]


def cri_text(cri) -> str:
    """One line: Ra, R9, CCT and Duv of the light (of the first and the count for a batch).


    Examples
    --------
    >>> from spectrocolor import colour_rendering_index, illuminant
    >>> cri_text(colour_rendering_index(illuminant("FL2")))
    'CRI(Ra=64.2, R9=-83.9, CCT=4224 K, Duv=0.0018, meaningful)'
    """
    shape, count = _batch(cri, "Ra")
    if count == 0:
        return f"CRI(no lights, batch shape {shape})"
    _, Ra, R9, cct, duv, meaningful = _cri_row(cri, 0, count, shape)
    state = "meaningful" if meaningful == "yes" else "not meaningful (CIE 13.3 §5.3)"
    head = f"{_lights(count)}, batch shape {shape}, first: " if shape else ""
    return f"CRI({head}Ra={Ra}, R9={R9}, CCT={cct} K, Duv={duv}, {state})"


def cri_html(cri) -> str:
    """HTML: Ra, R9, CCT, Duv and validity in a table; R1–R14 as bars in the samples' colours.


    Examples
    --------
    >>> from spectrocolor import colour_rendering_index, illuminant
    >>> "64.2" in cri_html(colour_rendering_index(illuminant("FL2")))
    True
    """
    shape, count = _batch(cri, "Ra")
    rows = [_cri_row(cri, i, count, shape) for i in range(min(count, SHOWN_LIGHTS))]
    table = layout.table(["", "Ra", "R9", "CCT K", "Duv", "CIE 13.3 applies"], rows, text_columns=(0, 5))
    parts = [table]
    if count:
        Ri = _flat(cri.Ri, count, 14)[0]
        parts = [layout.row([_cri_bars(Ri, _index_label(shape, 0)).markup(), table])]
    parts += _count_note(shape, count)
    parts.append(layout.note("CIE 13.3-1995: Ra is the mean of R1–R8; bars in the colours of TCS01–TCS14 "
                             "under D65"))
    subtitle = "one light" if not shape else f"{_lights(count)}, batch shape {shape}"
    return str(layout.card("CRI", subtitle, parts))


def cri_svg(cri) -> str:
    """Standalone SVG: the R1–R14 bars of the (first) light.


    Examples
    --------
    >>> from spectrocolor import colour_rendering_index, illuminant
    >>> cri_svg(colour_rendering_index(illuminant("FL2"))).count("<rect") >= 14
    True
    """
    shape, count = _batch(cri, "Ra")
    Ri = _flat(cri.Ri, count, 14)[0] if count else np.full(14, np.nan)
    return str(_cri_bars(Ri, _index_label(shape, 0)).markup(standalone=True))


# ----------------------------------------------------------------------------- Fidelity


def _point(xy, size: float) -> tuple[float, float]:
    scale = size / 3.0
    return size / 2 + xy[0] * scale, size / 2 - xy[1] * scale


def _polygon(points, size: float) -> str:
    return " ".join(f"{u:.1f},{v:.1f}" for u, v in (_point(p, size) for p in points))


def vector_graphic_svg(fidelity, index=(), size: int = 260) -> Canvas:
    """The TM-30 colour vector graphic of one light as an SVG canvas (no matplotlib).

    Parameters
    ----------
    fidelity : Fidelity
        From :func:`spectrocolor.colour_fidelity`.
    index : int or tuple, default ()
        Which light of a batch.
    size : int, default 260
        Side in pixels.

    Returns
    -------
    Canvas
        Reference polygon (the unit circle), the light's polygon (red), one arrow per hue bin in
        the bin's colour, Rf, Rg, CCT and Duv in the corners.

    Examples
    --------
    >>> from spectrocolor import colour_fidelity, illuminant
    >>> vector_graphic_svg(colour_fidelity(illuminant("FL2"))).markup().count("<polygon") >= 2
    True
    """
    reference, test = normalised_graphic(fidelity, index)
    colours = [hex_of(c) for c in bin_colours_rgb8()]
    canvas = Canvas(size, size, "TM-30 colour vector graphic")
    angles = np.radians(np.arange(HUE_BINS + 1) * 360.0 / HUE_BINS)
    for j in range(HUE_BINS):  # faint hue-bin wedges out to radius 1.5
        a, b = angles[j], angles[j + 1]
        corners = [(0.0, 0.0), (1.5 * np.cos(a), 1.5 * np.sin(a)), (1.5 * np.cos(b), 1.5 * np.sin(b))]
        canvas.add(element("polygon", points=_polygon(corners, size), fill=colours[j], fill_opacity="0.18"))
    for radius in (0.8, 1.2):
        u, v = _point((0.0, 0.0), size)
        canvas.add(element("circle", cx=f"{u:.1f}", cy=f"{v:.1f}", r=f"{radius * size / 3:.1f}", fill="none",
                           stroke="currentColor", stroke_opacity="0.35", stroke_dasharray="2 3"))
    canvas.add(element("polygon", points=_polygon(reference, size), fill="none", stroke="currentColor",
                       stroke_width="1.6"),
               element("polygon", points=_polygon(test, size), fill="none", stroke=_TEST_RED, stroke_width="1.8"))
    for j in range(HUE_BINS):
        (x0, y0), (x1, y1) = _point(reference[j], size), _point(test[j], size)
        length = float(np.hypot(x1 - x0, y1 - y0))
        if length > 1.0:
            dx, dy = (x1 - x0) / length, (y1 - y0) / length
            head = [(x1, y1), (x1 - 7 * dx + 3.5 * dy, y1 - 7 * dy - 3.5 * dx), (x1 - 7 * dx - 3.5 * dy,
                                                                                 y1 - 7 * dy + 3.5 * dx)]
            canvas.add(element("line", x1=f"{x0:.1f}", y1=f"{y0:.1f}", x2=f"{x1 - 5 * dx:.1f}",
                               y2=f"{y1 - 5 * dy:.1f}", stroke=colours[j], stroke_width="2.2"),
                       element("polygon", points=" ".join(f"{u:.1f},{v:.1f}" for u, v in head), fill=colours[j]))
        u, v = _point(1.38 * reference[j], size)
        canvas.add(element("text", str(j + 1), x=f"{u:.1f}", y=f"{v + 3:.1f}", text_anchor="middle",
                           fill="currentColor", fill_opacity="0.6", font_size=8))
    Rf, Rg, cct, duv = (float(np.asarray(v)[index]) for v in (fidelity.Rf, fidelity.Rg, fidelity.cct_K, fidelity.duv))
    canvas.add(element("text", f"Rf {number(Rf, 0)}", x=4, y=14, fill="currentColor", font_size=13,
                       font_weight="bold"),
               element("text", f"Rg {number(Rg, 0)}", x=size - 4, y=14, text_anchor="end", fill="currentColor",
                       font_size=13, font_weight="bold"),
               element("text", f"CCT {number(cct, 0)} K", x=4, y=size - 5, fill="currentColor"),
               element("text", f"Duv {number(duv, 4)}", x=size - 4, y=size - 5, text_anchor="end",
                       fill="currentColor"))
    return canvas


def _fidelity_row(fidelity, i: int, count: int, shape: tuple) -> list:
    Rf, Rg, cct, duv = (_flat(v, count)[i] for v in (fidelity.Rf, fidelity.Rg, fidelity.cct_K, fidelity.duv))
    return [_index_label(shape, i), number(Rf, 1), number(Rg, 1), number(cct, 0), number(duv, 4)]


def _bins_table(fidelity, first: int, count: int) -> Markup:
    Rf_h = _flat(fidelity.Rf_h, count, HUE_BINS)[first]
    Rcs = _flat(fidelity.Rcs_h, count, HUE_BINS)[first]
    Rhs = _flat(fidelity.Rhs_h, count, HUE_BINS)[first]
    colours = [hex_of(c) for c in bin_colours_rgb8()]
    return layout.table(
        ["hue bin", *(layout.cells(layout.swatch(c, f"bin {j + 1}", 9), str(j + 1)) for j, c in enumerate(colours))],
        [["Rf,h", *(number(v, 0) for v in Rf_h)],
         ["Rcs,h %", *(number(100 * v, 0) for v in Rcs)],
         ["Rhs,h", *(number(v, 2) for v in Rhs)]])


def fidelity_text(fidelity) -> str:
    """One line: Rf, Rg, CCT and Duv of the light (of the first and the count for a batch).


    Examples
    --------
    >>> from spectrocolor import colour_fidelity, illuminant
    >>> fidelity_text(colour_fidelity(illuminant("FL2")))
    'Fidelity(Rf=70.1, Rg=86.4, CCT=4224 K, Duv=0.0018)'
    """
    shape, count = _batch(fidelity, "Rf")
    if count == 0:
        return f"Fidelity(no lights, batch shape {shape})"
    _, Rf, Rg, cct, duv = _fidelity_row(fidelity, 0, count, shape)
    head = f"{_lights(count)}, batch shape {shape}, first: " if shape else ""
    return f"Fidelity({head}Rf={Rf}, Rg={Rg}, CCT={cct} K, Duv={duv})"


def fidelity_html(fidelity) -> str:
    """HTML: the TM-30 colour vector graphic, Rf, Rg, CCT, Duv, and the per-bin shifts.


    Examples
    --------
    >>> from spectrocolor import colour_fidelity, illuminant
    >>> "Rg" in fidelity_html(colour_fidelity(illuminant("FL2")))
    True
    """
    shape, count = _batch(fidelity, "Rf")
    rows = [_fidelity_row(fidelity, i, count, shape) for i in range(min(count, SHOWN_LIGHTS))]
    table = layout.table(["", "Rf", "Rg", "CCT K", "Duv"], rows)
    parts = [table]
    if count:
        index = np.unravel_index(0, shape) if shape else ()
        parts = [layout.row([vector_graphic_svg(fidelity, index).markup(), table]), _bins_table(fidelity, 0, count)]
    parts += _count_note(shape, count)
    parts.append(layout.note("CIE 224:2017 / ANSI/IES TM-30-20: the reference in the text colour (the unit "
                             "circle), the light in red; arrows from the reference to the light in each hue bin"))
    subtitle = "one light" if not shape else f"{_lights(count)}, batch shape {shape}"
    return str(layout.card("Fidelity", subtitle, parts))


def fidelity_svg(fidelity) -> str:
    """Standalone SVG: the colour vector graphic of the (first) light.


    Examples
    --------
    >>> from spectrocolor import colour_fidelity, illuminant
    >>> fidelity_svg(colour_fidelity(illuminant("FL2"))).startswith("<svg")
    True
    """
    shape, count = _batch(fidelity, "Rf")
    index = np.unravel_index(0, shape) if shape else ()
    return str(vector_graphic_svg(fidelity, index).markup(standalone=True))
