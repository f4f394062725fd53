"""Inline SVG pictures built as plain strings: a canvas, plot axes, curves, swatches, strips, bars.

Every picture is small (a few hundred pixels), bounded in size whatever the data (curves are
thinned to :data:`MAX_POINTS` points, strips and grids to :data:`MAX_CELLS` cells), uses
``currentColor`` for axes and text (readable on light and dark themes) and holds no script and
no link. The same markup serves inline in HTML and, with the SVG namespace declared, as a
standalone ``image/svg+xml`` document.

Examples
--------
>>> canvas = Canvas(40, 20, "two swatches")
>>> canvas.add(*swatch_row(["#ff0000", "#00ff00"], x=0, y=0, size=20, titles=["red", "green"]))
>>> canvas.markup().startswith('<svg width="40" height="20"')
True
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .markup import Markup, element

__all__ = ["SVG_NAMESPACE", "MAX_POINTS", "MAX_CELLS", "Canvas", "Axes", "nice_ticks", "curve_paths",
           "spectrum_axes", "swatch_row", "strip", "thin"]

#: The namespace a standalone SVG document declares (an identifier, not a network address).
SVG_NAMESPACE = "http://www.w3.org/2000/svg"
#: Largest number of points drawn per curve.
MAX_POINTS = 600
#: Largest number of cells drawn in a strip or a grid.
MAX_CELLS = 4096
_MUTED = dict(stroke="currentColor", stroke_opacity="0.45")


class Canvas:
    """An SVG picture of ``width`` × ``height`` pixels, built element by element.

    Parameters
    ----------
    width, height : int
        Size in CSS pixels.
    label : str
        What the picture shows (its ``<title>`` and ``aria-label``).

    Examples
    --------
    >>> Canvas(10, 10, "empty").markup(standalone=True).startswith('<svg xmlns=')
    True
    """

    def __init__(self, width: int, height: int, label: str):
        self.width, self.height, self.label = int(width), int(height), label
        self.parts: list[Markup] = []

    def add(self, *parts: Markup) -> None:
        """Append elements (markup built by this package).

        Parameters
        ----------
        *parts : Markup
            Elements, drawn in order (later on top).

        Examples
        --------
        >>> c = Canvas(10, 10, "dot"); c.add(element("circle", r=2)); len(c.parts)
        1
        """
        self.parts.extend(parts)

    def markup(self, standalone: bool = False) -> Markup:
        """The ``<svg>`` element; ``standalone`` declares the namespace for an SVG document.

        Parameters
        ----------
        standalone : bool, default False
            True for ``image/svg+xml`` output (the namespace is required there), False inline.

        Returns
        -------
        Markup
            The picture.

        Examples
        --------
        >>> "<title>dot</title>" in Canvas(10, 10, "dot").markup()
        True
        """
        return element("svg", element("title", self.label), *self.parts,
                       xmlns=SVG_NAMESPACE if standalone else None, width=self.width, height=self.height,
                       viewBox=f"0 0 {self.width} {self.height}", role="img", aria_label=self.label,
                       font_family="system-ui, sans-serif", font_size=10, style="overflow: visible;")


@dataclass(frozen=True)
class Axes:
    """A linear map from data (x, y) to pixels inside a rectangle of the canvas.

    Attributes
    ----------
    x_range, y_range : tuple of float
        Data limits (low, high).
    left, top, width, height : float
        The plotting rectangle in pixels.

    Examples
    --------
    >>> a = Axes((400.0, 700.0), (0.0, 1.0), 10, 0, 300, 100)
    >>> float(a.x(550.0)), float(a.y(0.25))
    (160.0, 75.0)
    """

    x_range: tuple
    y_range: tuple
    left: float
    top: float
    width: float
    height: float

    def x(self, value):
        """Pixel column of data x (array or float)."""
        lo, hi = self.x_range
        return self.left + (np.asarray(value, dtype=float) - lo) / (hi - lo) * self.width

    def y(self, value):
        """Pixel row of data y (array or float), up is larger y."""
        lo, hi = self.y_range
        return self.top + self.height - (np.asarray(value, dtype=float) - lo) / (hi - lo) * self.height


def nice_ticks(low: float, high: float, count: int = 4) -> list[float]:
    """Round tick values (1, 2, 2.5 or 5 × 10ⁿ apart) covering ``[low, high]``.

    Parameters
    ----------
    low, high : float
        The data range.
    count : int, default 4
        About how many intervals.

    Returns
    -------
    list of float
        Ticks inside the range.

    Examples
    --------
    >>> nice_ticks(380, 780)
    [400.0, 500.0, 600.0, 700.0]
    >>> nice_ticks(0, 1)
    [0.0, 0.25, 0.5, 0.75, 1.0]
    """
    if not (math.isfinite(low) and math.isfinite(high)) or high <= low:
        return [low] if math.isfinite(low) else []
    raw = (high - low) / count
    power = 10.0 ** math.floor(math.log10(raw))
    step = next(m * power for m in (1, 2, 2.5, 5, 10) if m * power >= raw * 0.999)
    first = math.ceil(low / step - 1e-9) * step
    ticks = []
    value = first
    while value <= high + step * 1e-9:
        ticks.append(round(value, 12) + 0.0)
        value += step
    return ticks


def _tick_text(value: float) -> str:
    return f"{value:g}"


def thin(count: int, limit: int = MAX_POINTS) -> np.ndarray:
    """Indices of at most ``limit`` evenly spread samples of ``count`` (first and last kept).

    Parameters
    ----------
    count : int
        Number of samples.
    limit : int, default MAX_POINTS
        Largest number kept.

    Returns
    -------
    numpy.ndarray of int
        Increasing indices.

    Examples
    --------
    >>> thin(5, 3).tolist()
    [0, 2, 4]
    """
    if count <= limit:
        return np.arange(count)
    return np.unique(np.linspace(0, count - 1, limit).round().astype(np.intp))


def curve_paths(axes: Axes, x, y) -> str:
    """SVG path data of a curve, broken where y is not finite.

    Parameters
    ----------
    axes : Axes
        The data → pixel map.
    x, y : array_like, shape (K,)
        The curve.

    Returns
    -------
    str
        ``"M x y L x y …"`` (empty when no point is finite).

    Examples
    --------
    >>> curve_paths(Axes((0, 2), (0, 1), 0, 0, 20, 10), [0, 1, 2], [0, float("nan"), 1])
    'M0.0 10.0M20.0 0.0'
    """
    x = np.asarray(x, dtype=float)
    y = np.asarray(y, dtype=float)
    px, py = axes.x(x), axes.y(np.clip(y, *axes.y_range))
    out = []
    pen_down = False
    for u, v, ok in zip(px.tolist(), py.tolist(), np.isfinite(y).tolist(), strict=True):
        if not ok:
            pen_down = False
            continue
        out.append(f"{'L' if pen_down else 'M'}{u:.1f} {v:.1f}")
        pen_down = True
    return "".join(out)


def spectrum_axes(axes: Axes, y_ticks, y_label: str, tint=None) -> list[Markup]:
    """Frame, wavelength ticks (nm), y ticks and an optional spectral hue band under the axis.

    Parameters
    ----------
    axes : Axes
        The plotting rectangle (x in nm).
    y_ticks : list of float
        Values marked on the y axis.
    y_label : str
        The quantity on the y axis.
    tint : callable, optional
        ``wavelengths_nm -> rgb8`` for the band under the axis (e.g.
        :func:`spectrocolor.pictures.wavelength_tint`); no band when None.

    Returns
    -------
    list of Markup
        Elements to add to a canvas.

    Examples
    --------
    >>> len(spectrum_axes(Axes((400, 700), (0, 1), 30, 5, 200, 100), [0, 1], "ρ")) > 4
    True
    """
    left, top, width, height = axes.left, axes.top, axes.width, axes.height
    bottom = top + height
    parts = [element("rect", x=f"{left:.1f}", y=f"{top:.1f}", width=f"{width:.1f}", height=f"{height:.1f}",
                     fill="none", **_MUTED)]
    if tint is not None:
        lo, hi = max(axes.x_range[0], 360.0), min(axes.x_range[1], 830.0)
        if hi > lo:
            steps = np.linspace(lo, hi, 61)
            colours = tint((steps[:-1] + steps[1:]) / 2)
            for a, b, (r, g, bl) in zip(steps[:-1], steps[1:], colours.tolist(), strict=True):
                x0, x1 = float(axes.x(a)), float(axes.x(b))
                parts.append(element("rect", x=f"{x0:.1f}", y=f"{bottom + 1:.1f}", width=f"{x1 - x0 + 0.3:.1f}",
                                     height="4", fill=f"#{r:02x}{g:02x}{bl:02x}"))
    for tick in nice_ticks(*axes.x_range):
        u = float(axes.x(tick))
        parts.append(element("line", x1=f"{u:.1f}", x2=f"{u:.1f}", y1=f"{bottom:.1f}", y2=f"{bottom + 7:.1f}",
                             **_MUTED))
        parts.append(element("text", _tick_text(tick), x=f"{u:.1f}", y=f"{bottom + 17:.1f}",
                             text_anchor="middle", fill="currentColor"))
    parts.append(element("text", "nm", x=f"{left + width:.1f}", y=f"{bottom + 27:.1f}", text_anchor="end",
                         fill="currentColor", fill_opacity="0.7"))
    for tick in y_ticks:
        v = float(axes.y(tick))
        parts.append(element("line", x1=f"{left - 3:.1f}", x2=f"{left:.1f}", y1=f"{v:.1f}", y2=f"{v:.1f}",
                             **_MUTED))
        parts.append(element("text", _tick_text(tick), x=f"{left - 5:.1f}", y=f"{v + 3:.1f}", text_anchor="end",
                             fill="currentColor"))
    parts.append(element("text", y_label, x=f"{left:.1f}", y=f"{top - 4:.1f}", fill="currentColor",
                         fill_opacity="0.7"))
    return parts


def curve(axes: Axes, x, y, colour: str, title: str | None = None) -> Markup:
    """One curve stroked in ``colour`` over a faint halo (so a white curve stays visible).

    Parameters
    ----------
    axes : Axes
        The data → pixel map.
    x, y : array_like, shape (K,)
        The curve (thinned to :data:`MAX_POINTS`).
    colour : str
        ``"#rrggbb"``.
    title : str, optional
        Tooltip (escaped).

    Returns
    -------
    Markup
        A ``<g>`` of two paths.

    Examples
    --------
    >>> "#ff0000" in curve(Axes((0, 1), (0, 1), 0, 0, 10, 10), [0, 1], [0, 1], "#ff0000")
    True
    """
    keep = thin(len(x))
    d = curve_paths(axes, np.asarray(x)[keep], np.asarray(y)[keep])
    return element("g", element("title", title) if title else None,
                   element("path", d=d, fill="none", stroke="currentColor", stroke_opacity="0.35", stroke_width="3",
                           stroke_linejoin="round"),
                   element("path", d=d, fill="none", stroke=colour, stroke_width="1.6", stroke_linejoin="round"))


def swatch_row(hexes, x: float, y: float, size: float, titles=None, gap: float = 3.0) -> list[Markup]:
    """Squares of the given colours in a row, each with a thin outline and a tooltip.

    Parameters
    ----------
    hexes : list of str
        ``"#rrggbb"`` (``None`` for a colour that cannot be shown: a crossed empty square).
    x, y : float
        Top left of the first square.
    size : float
        Side of each square.
    titles : list of str, optional
        Tooltips (escaped).
    gap : float, default 3
        Space between squares.

    Returns
    -------
    list of Markup
        Elements to add to a canvas.

    Examples
    --------
    >>> len(swatch_row(["#000000", None], 0, 0, 10))
    2
    """
    titles = titles or [None] * len(hexes)
    parts = []
    for i, (colour, title) in enumerate(zip(hexes, titles, strict=True)):
        left = x + i * (size + gap)
        box = dict(x=f"{left:.1f}", y=f"{y:.1f}", width=f"{size:.1f}", height=f"{size:.1f}")
        tip = element("title", title) if title else None
        if colour is None:
            parts.append(element("g", tip, element("rect", fill="none", **_MUTED, **box),
                                 element("line", x1=f"{left:.1f}", y1=f"{y + size:.1f}", x2=f"{left + size:.1f}",
                                         y2=f"{y:.1f}", **_MUTED)))
        else:
            parts.append(element("rect", tip, fill=colour, stroke="currentColor", stroke_opacity="0.3", **box))
    return parts


def strip(rgb8, x: float, y: float, width: float, height: float, label: str | None = None) -> list[Markup]:
    """A strip of colours (one column each, thinned to :data:`MAX_CELLS` columns).

    Parameters
    ----------
    rgb8 : array_like, shape (N, 3)
        8-bit codes in order.
    x, y, width, height : float
        The strip's rectangle.
    label : str, optional
        Tooltip of the whole strip.

    Returns
    -------
    list of Markup
        Column rectangles and an outline.

    Examples
    --------
    >>> len(strip([[255, 0, 0], [0, 0, 255]], 0, 0, 20, 5))
    3
    """
    codes = np.asarray(rgb8).reshape(-1, 3)
    keep = thin(len(codes), MAX_CELLS)
    step = width / len(keep)
    parts = []
    for i, (r, g, b) in enumerate(codes[keep].tolist()):
        parts.append(element("rect", x=f"{x + i * step:.2f}", y=f"{y:.1f}", width=f"{step + 0.25:.2f}",
                             height=f"{height:.1f}", fill=f"#{r:02x}{g:02x}{b:02x}"))
    parts.append(element("rect", element("title", label) if label else None, x=f"{x:.1f}", y=f"{y:.1f}",
                         width=f"{width:.1f}", height=f"{height:.1f}", fill="none", **_MUTED))
    return parts
