"""Plots (matplotlib, imported only when a plot is made): chromaticity diagrams, spectra.

Figures are made with :class:`matplotlib.figure.Figure` (no pyplot state, safe in servers);
pass ``ax`` to draw into your own axes.

The filled horseshoe
--------------------
Every pixel inside the spectral locus is painted with its own chromaticity at the highest
luminance the display allows (largest channel = 1). Chromaticities inside the display's gamut
triangle are shown exactly. Those outside it cannot be shown by any display with these
primaries; they are painted with the nearest displayable chromaticity *on the line toward the
display's white point* (the ``"desaturate"`` gamut strategy: same hue angle about the white,
less saturation), so the colours outside the triangle are honest about hue and wrong about
saturation -- the triangle drawn on top marks where exactness ends.

Why this file is long: the chromaticity diagram is one feature with three parts that only it uses
(the filled horseshoe, the loci, and the collision-free placement of point labels); a module per
part would export helpers nobody else calls.
"""

from __future__ import annotations

import functools

import numpy as np

from .errors import ColorimetryError
from .observers import DEFAULT_OBSERVER

__all__ = ["chromaticity_diagram", "spectrum_plot", "planckian_locus_xy", "horseshoe_image"]

_LOCUS_LABELS_NM = (380, 460, 470, 480, 490, 500, 510, 520, 540, 560, 580, 600, 620, 700)
_PLANCK_LABELS_K = (1500, 2000, 3000, 4000, 6500, 10000)


def plain_text(draw):
    """Decorator: every text a drawing function makes is plain text, never maths.

    Matplotlib reads a string with two ``$`` as mathtext, so a light named ``$\\frac{1$`` (or
    ``a $\\undefinedmacro$ b``) in a file would stop the figure with a parser error, and a
    name like ``$5 and $6`` would be drawn in italics. Names come from files and are text: the
    decorated function runs with ``text.parse_math`` off, so every title, legend entry and
    label it creates is drawn as written.

    Parameters
    ----------
    draw : callable
        A function that creates matplotlib texts (titles, labels, legends).

    Returns
    -------
    callable
        The same function, its texts never parsed as maths.

    Examples
    --------
    >>> @plain_text
    ... def titled(name):
    ...     ax = axes_or_new(None, (3, 2))
    ...     ax.set_title(name)
    ...     return ax
    >>> ax = titled("$\\frac{1$")
    >>> ax.title.get_parse_math(), ax.figure.canvas.get_width_height()[0] > 0
    (False, True)
    """
    @functools.wraps(draw)
    def drawn_as_text(*args, **kwargs):
        import matplotlib

        with matplotlib.rc_context({"text.parse_math": False}):
            return draw(*args, **kwargs)

    return drawn_as_text


def axes_or_new(ax, figsize):
    """``ax`` itself, or the axes of a new :class:`matplotlib.figure.Figure` (no pyplot state).

    Parameters
    ----------
    ax : matplotlib.axes.Axes or None
        Axes to draw into; ``None`` makes a new figure.
    figsize : tuple of float
        Size of the new figure, inches (width, height).

    Returns
    -------
    matplotlib.axes.Axes

    Examples
    --------
    >>> axes_or_new(None, (3, 2)).figure.get_size_inches().tolist()
    [3.0, 2.0]
    """
    if ax is not None:
        return ax
    from matplotlib.figure import Figure

    return Figure(figsize=figsize, layout="constrained").add_subplot()


def _to_kind(xy: np.ndarray, kind: str) -> np.ndarray:
    if kind == "xy":
        return xy
    from .coordinates import uv_1976

    return uv_1976(xy=xy)


def _from_kind(coords: np.ndarray, kind: str) -> np.ndarray:
    if kind == "xy":
        return coords
    from .coordinates import xy_from_uv_1976

    return xy_from_uv_1976(coords)


def _as_xy(values, argument: str) -> np.ndarray:
    """(N, 3) XYZ or (N, 2) CIE 1931 xy -> (N, 2) xy."""
    from .coordinates import xy

    a = np.asarray(values, dtype=float)
    if a.ndim == 1:
        a = a[None]
    if a.ndim != 2 or a.shape[1] not in (2, 3):
        raise ColorimetryError(
            f"{argument} must be (N, 3) XYZ or (N, 2) xy chromaticities, got shape {a.shape}"
        )
    return xy(a) if a.shape[1] == 3 else a


def planckian_locus_xy(temperatures_K, observer=DEFAULT_OBSERVER) -> np.ndarray:
    """xy of blackbody radiators (CIE summation at 1 nm over the observer's range), (N, 2).

    Parameters
    ----------
    temperatures_K : array_like, shape (N,)
        Temperatures, K.
    observer : str, default DEFAULT_OBSERVER
        Observer name or alias.

    Returns
    -------
    numpy.ndarray, shape (N, 2)
        CIE 1931 chromaticities (x, y).

    Examples
    --------
    >>> planckian_locus_xy([2856, 6504]).round(4).tolist()
    [[0.4475, 0.4074], [0.3135, 0.3236]]
    """
    from .colorimetry import tristimulus
    from .coordinates import xy
    from .radiators import blackbody
    from .spectrum import Spectrum

    temps = np.atleast_1d(np.asarray(temperatures_K, dtype=float))
    spectra = [blackbody(float(t)) for t in temps]
    batch = Spectrum(spectra[0].wavelengths_nm, np.stack([s.values for s in spectra]))
    return xy(tristimulus(batch, observer=observer))


def horseshoe_image(kind: str = "xy", observer=DEFAULT_OBSERVER, space="sRGB", resolution: int = 400):
    """RGBA image (H, W, 4) of the filled spectral-locus region and its extent.

    See the module docstring for how colours outside the display gamut are painted. The image
    holds ``space``'s encoded values; PNG files and browsers assume sRGB, so pictures meant for
    files use ``space="sRGB"``.

    Parameters
    ----------
    kind : {"xy", "uv"}, default "xy"
        CIE 1931 (x, y) or CIE 1976 (u', v').
    observer : str, default DEFAULT_OBSERVER
        Observer of the spectral locus.
    space : str or RGBSpace, default "sRGB"
        The space whose encoded values the image holds.
    resolution : int, default 400
        Pixels across the locus's x extent.

    Returns
    -------
    image : ndarray (H, W, 4) float in [0, 1] (transparent outside the locus)
        RGBA, for ``matplotlib``'s ``imshow``.
    extent : (left, right, bottom, top) in the diagram's coordinates
        The bounding box of the spectral locus.

    Raises
    ------
    ColorimetryError
        For an unknown kind, observer or space.

    Examples
    --------
    >>> image, extent = horseshoe_image(resolution=50)
    >>> image.shape, [round(float(e), 4) for e in extent]
    ((56, 50, 4), [0.0036, 0.7347, 0.0048, 0.8341])
    """
    from matplotlib.path import Path

    from .chromaticity import spectral_locus
    from .display.gamut import desaturate
    from .display.spaces import rgb_space

    kind = _kind(kind)
    sp = rgb_space(space)
    locus = _to_kind(np.asarray(spectral_locus(observer).xy), kind)
    lo, hi = locus.min(axis=0), locus.max(axis=0)
    n = int(resolution)
    xs = np.linspace(lo[0], hi[0], n)
    ys = np.linspace(lo[1], hi[1], max(2, int(n * (hi[1] - lo[1]) / (hi[0] - lo[0]))))
    gx, gy = np.meshgrid(xs, ys[::-1])
    coords = np.stack([gx, gy], axis=-1)
    inside = Path(np.vstack([locus, locus[:1]])).contains_points(coords.reshape(-1, 2))
    inside = inside.reshape(gx.shape)
    xy_ = _from_kind(coords[inside], kind)
    XYZ = np.column_stack([xy_[:, 0] / xy_[:, 1], np.ones(len(xy_)), (1 - xy_.sum(1)) / xy_[:, 1]])
    rgb = sp.rgb_linear_from_XYZ(XYZ)
    rgb = rgb / rgb.max(axis=1, keepdims=True)
    rgb = desaturate(rgb, sp.luminance_row)
    rgb = rgb / rgb.max(axis=1, keepdims=True)
    image = np.zeros((*gx.shape, 4))
    image[inside, :3] = sp.transfer.encode(rgb)
    image[inside, 3] = 1.0
    return image, (xs[0], xs[-1], ys[0], ys[-1])


def _kind(kind: str) -> str:
    if kind not in ("xy", "uv"):
        raise ColorimetryError(f"kind must be 'xy' or 'uv' (CIE 1976 u'v'), got {kind!r}")
    return kind


@plain_text
def chromaticity_diagram(
    kind: str = "xy",
    observer=DEFAULT_OBSERVER,
    spaces=("sRGB",),
    whites=("D65",),
    planckian: bool = True,
    points=None,
    labels=None,
    curves=None,
    curve_labels=None,
    fill: bool = True,
    ax=None,
    title: str | None = None,
):
    """The CIE 1931 xy or CIE 1976 u'v' chromaticity diagram.

    Parameters
    ----------
    kind : {"xy", "uv"}, default "xy"
        CIE 1931 (x, y) or CIE 1976 (u', v').
    observer : str, default DEFAULT_OBSERVER
        Observer of the spectral locus, the whites and the Planckian locus.
    spaces : sequence of RGB space names or RGBSpace
        Gamut triangles to draw (with their white points).
    whites : sequence of illuminant names, or dict label -> XYZ
        White points to mark.
    planckian : bool, default True
        Draw the Planckian locus (1000-20000 K) with a few temperatures labelled.
    points : array_like, shape (N, 3) or (N, 2), optional
        Points to mark, as XYZ (any scale) or CIE 1931 xy.
    labels : sequence of str, shape (N,), optional
        Names of ``points``.
    curves : list of array_like, shape (M, 3) or (M, 2), optional
        Curves to draw as XYZ or xy (e.g. the colours of a thin film).
    curve_labels : sequence of str, optional
        Legend entries of ``curves``.
    fill : bool, default True
        Paint the horseshoe in sRGB (the encoding of PNG files and browsers; see the module
        docstring for colours outside the sRGB gamut).
    ax : matplotlib.axes.Axes, optional
        Axes to draw into; default a new 6.4 × 6.4 inch figure.
    title : str, optional
        The axes' title.

    Returns
    -------
    matplotlib.axes.Axes
        The axes drawn into.

    Raises
    ------
    ColorimetryError
        For an unknown kind, observer, space or white, or malformed points or curves.

    References
    ----------
    CIE 015:2018 §7 (chromaticity coordinates), §8.1 (u'v' diagram), §9 (Planckian locus).

    Examples
    --------
    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> ax = chromaticity_diagram(points=[[0.64, 0.33]], labels=["sRGB red"], fill=False)
    >>> ax.get_xlabel()
    'x'
    >>> import matplotlib.pyplot as plt
    >>> plt.close(ax.figure)
    """
    from .display.spaces import rgb_space

    kind = _kind(kind)
    ax = axes_or_new(ax, (6.4, 6.4))
    _draw_spectral_locus(ax, kind, observer, fill)
    for i, spec in enumerate(spaces or ()):
        sp = rgb_space(spec)
        tri = _to_kind(sp.primaries_xy, kind)
        ax.fill(tri[:, 0], tri[:, 1], fill=False, lw=1.2, zorder=4, label=sp.name,
                color=f"C{i}")
    markers: list[tuple[np.ndarray, float]] = []  # (anchor, diameter in points): labels keep off every marker
    white_labels = _draw_whites(ax, kind, observer, whites, markers)
    planck_labels = _draw_planckian_locus(ax, kind, observer, markers) if planckian else []
    for i, curve in enumerate(curves or ()):
        c = _to_kind(_as_xy(curve, "curves"), kind)
        name = None if curve_labels is None else curve_labels[i]
        ax.plot(c[:, 0], c[:, 1], lw=1.2, zorder=7, color=f"C{i + 3}", label=name)
    pts = None
    if points is not None:
        pts = _to_kind(_as_xy(points, "points"), kind)
        if labels is not None and len(labels) != len(pts):
            raise ColorimetryError(f"labels must name each of the {len(pts)} points")
        ax.plot(pts[:, 0], pts[:, 1], "o", mfc="none", mec="black", ms=5, zorder=8)
        markers.extend((c, 5.0) for c in pts)
    _frame(ax, kind, observer, title)
    _place_labels(ax, kind, markers, white_labels + planck_labels, pts, labels)
    return ax


def _draw_spectral_locus(ax, kind: str, observer, fill: bool) -> None:
    """The horseshoe (filled in sRGB if asked), the purple line and the wavelength ticks."""
    from .chromaticity import spectral_locus

    locus_all = spectral_locus(observer)
    wl = np.asarray(locus_all.wavelengths_nm)
    locus = _to_kind(np.asarray(locus_all.xy), kind)
    if fill:
        image, extent = horseshoe_image(kind, observer, "sRGB")
        ax.imshow(image, extent=extent, origin="upper", interpolation="bilinear", zorder=0)
    ax.plot(locus[:, 0], locus[:, 1], color="black", lw=1.2, zorder=3)
    ax.plot(locus[[0, -1], 0], locus[[0, -1], 1], color="black", lw=1.0, ls="--", zorder=3,
            label="purple line")
    centre = locus.mean(axis=0)
    for nm in _LOCUS_LABELS_NM:
        if not wl[0] <= nm <= wl[-1]:
            continue
        p = np.array([np.interp(nm, wl, locus[:, 0]), np.interp(nm, wl, locus[:, 1])])
        out = (p - centre) / np.hypot(*(p - centre))
        ax.plot(*np.column_stack([p, p + 0.012 * out]), color="black", lw=0.8, zorder=3)
        ax.annotate(f"{nm}", p + 0.03 * out, ha="center", va="center", fontsize=7, zorder=4)


def _draw_whites(ax, kind: str, observer, whites, markers: list) -> list:
    """Mark the white points (names or a dict label -> XYZ); their labels are returned, unplaced."""
    from .colorimetry import white_point

    if isinstance(whites, dict):
        named_whites = {k: np.asarray(v, float) for k, v in whites.items()}
    else:
        named_whites = {name: white_point(name, observer=observer) for name in (whites or ())}
    white_labels = []
    for label, XYZ in named_whites.items():
        c = _to_kind(_as_xy(XYZ, "whites"), kind)[0]
        ax.plot(*c, marker="o", mfc="white", mec="black", ms=6, zorder=6, ls="none")
        markers.append((c, 6.0))
        white_labels.append(_Label(str(label), c, _ring_offsets(6.0), {"fontsize": 8}, 6))
    return white_labels


def _draw_planckian_locus(ax, kind: str, observer, markers: list) -> list:
    """The Planckian locus 1000-20000 K with ticks; the temperature labels are returned, unplaced."""
    temps = np.geomspace(1000, 20000, 60)
    pl = _to_kind(planckian_locus_xy(temps, observer), kind)
    ax.plot(pl[:, 0], pl[:, 1], color="0.25", lw=0.9, zorder=5, label="Planckian locus")
    marks = _to_kind(planckian_locus_xy(_PLANCK_LABELS_K, observer), kind)
    ax.plot(marks[:, 0], marks[:, 1], "|", color="0.25", ms=6, zorder=5)
    planck_labels = []
    for t, c in zip(_PLANCK_LABELS_K, marks, strict=True):
        markers.append((c, 6.0))
        planck_labels.append(_Label(f"{t} K", c, (), {"fontsize": 6, "color": "0.2"}, 5, across=pl))
    return planck_labels


def _frame(ax, kind: str, observer, title: str | None) -> None:
    """Axis names, equal aspect, the diagram's limits, the grid and the title."""
    names = ("x", "y") if kind == "xy" else ("u′", "v′")
    ax.set_xlabel(names[0])
    ax.set_ylabel(names[1])
    ax.set_aspect("equal")
    lim = (-0.02, 0.82, -0.02, 0.9) if kind == "xy" else (-0.06, 0.66, -0.02, 0.62)
    ax.set_xlim(lim[0], lim[1])
    ax.set_ylim(lim[2], lim[3])
    ax.grid(True, lw=0.3, color="0.85", zorder=-1)
    diagram = "CIE 1931 xy" if kind == "xy" else "CIE 1976 u′v′"
    ax.set_title(title if title is not None else f"{diagram} chromaticity diagram, observer {observer}")


def _place_labels(ax, kind: str, markers: list, fixed_labels: list, pts, labels) -> None:
    """Lay out the legend, then place the labels of whites, temperatures and points without overlap.

    The figure is laid out once with the longest legend the labels can lead to; labels are placed
    in display coordinates around it, the markers and the wavelength labels. Points closer than a
    marker share one label (``name +k``); a label with no free place is omitted and counted in the
    legend.
    """
    legend_loc = "upper right" if kind == "xy" else "lower right"
    point_handle = None
    if pts is not None and labels is not None:
        from matplotlib.lines import Line2D

        point_handle = Line2D([], [], ls="none", marker="o", mfc="none", mec="black", ms=5)
    count = 0 if pts is None else len(pts)
    _legend(ax, legend_loc, point_handle, _points_legend_text(count, count, count))
    ax.figure.draw_without_rendering()
    placer = _LabelPlacer(ax, markers)
    for item in fixed_labels:
        placer.place(item)
    merged = omitted = 0
    if pts is not None and labels is not None:
        for members in _clusters(ax, pts, radius_pt=5.0):
            text = str(labels[members[0]])
            if len(members) > 1:
                text += f" +{len(members) - 1}"
                merged += len(members) - 1
            offsets = _ring_offsets(5.0) + _ring_offsets(16.0) + _ring_offsets(28.0)
            omitted += not placer.place(_Label(text, pts[members[0]], offsets,
                                               {"fontsize": 7}, 8))
    if point_handle is not None:
        _legend(ax, legend_loc, point_handle, _points_legend_text(count, merged, omitted))


def _legend(ax, loc, point_handle, point_text):
    handles, texts = ax.get_legend_handles_labels()
    if point_handle is not None:
        handles, texts = [*handles, point_handle], [*texts, point_text]
    return ax.legend(handles, texts, loc=loc, fontsize=7, framealpha=0.9)


def _points_legend_text(count: int, merged: int, omitted: int) -> str:
    notes = []
    if merged:
        notes.append("'+n': n more at the same spot")
    if omitted:
        notes.append(f"{omitted} labels left out: no room")
    return "\n".join([f"{count} points", *notes])


class _Label:
    """A label to place: text, anchor (data coordinates), candidate offsets, text style.

    ``offsets`` are ``(dx, dy, ha, va)`` in points, tried in order. ``across`` (a curve, data
    coordinates) replaces them by positions on either side of the curve, perpendicular to it.
    """

    def __init__(self, text, anchor, offsets, style, zorder, across=None):
        self.text, self.anchor, self.offsets = text, np.asarray(anchor, float), tuple(offsets)
        self.style, self.zorder, self.across = style, zorder, across


def _ring_offsets(radius_pt: float):
    """Eight positions around a point at ``radius_pt``: right, left, below, above, diagonals."""
    r, d = radius_pt, radius_pt * 0.75
    return [(r, 0, "left", "center"), (-r, 0, "right", "center"), (0, -r, "center", "top"),
            (0, r, "center", "bottom"), (d, -d, "left", "top"), (d, d, "left", "bottom"),
            (-d, -d, "right", "top"), (-d, d, "right", "bottom")]


def _clusters(ax, pts: np.ndarray, radius_pt: float) -> list[list[int]]:
    """Groups of points whose markers overlap on the page (closer than ``radius_pt``).

    Single linkage in display coordinates, in the order the points were given, so that the
    result is deterministic; each group lists its members in input order.
    """
    scale = ax.figure.dpi / 72.0
    screen = ax.transData.transform(pts)
    near = np.hypot(*(screen[:, None, :] - screen[None, :, :]).transpose(2, 0, 1))
    near = near < radius_pt * scale
    group = np.arange(len(pts))
    for _ in range(len(pts)):  # propagate the smallest index through chains of neighbours
        updated = np.where(near, group[None, :], len(pts)).min(axis=1)
        if np.array_equal(updated, group):
            break
        group = updated
    return [np.flatnonzero(group == g).tolist() for g in np.unique(group)]


class _LabelPlacer:
    """Greedy, deterministic label placement in display coordinates.

    Each label takes the first candidate position whose text box lies inside the axes and
    overlaps neither an earlier label, a marker, the legend nor a text already on the axes
    (the wavelength labels); a label with no free position is not drawn.
    """

    _PAD_PT = 1.0
    #: Labels placed farther than this from their point get a leader line.
    _LEADER_PT = 14.0

    def __init__(self, ax, markers):
        self.ax = ax
        self.scale = ax.figure.dpi / 72.0
        pad = self._PAD_PT * self.scale
        boxes = []
        for anchor, size_pt in markers:
            x, y = ax.transData.transform(anchor)
            half = size_pt / 2 * self.scale + pad
            boxes.append((x - half, y - half, x + half, y + half))
        for artist in [*ax.texts, *([ax.get_legend()] if ax.get_legend() else [])]:
            b = artist.get_window_extent()
            boxes.append((b.x0 - pad, b.y0 - pad, b.x1 + pad, b.y1 + pad))
        self.boxes = np.array(boxes, dtype=float).reshape(-1, 4)
        self.frame = ax.get_window_extent()

    def _offsets(self, label):
        if label.across is None:
            return label.offsets
        curve = self.ax.transData.transform(label.across)
        anchor = self.ax.transData.transform(label.anchor)
        i = int(np.argmin(np.hypot(*(curve - anchor).T)))
        tangent = curve[min(i + 1, len(curve) - 1)] - curve[max(i - 1, 0)]
        normal = np.array([tangent[1], -tangent[0]]) / np.hypot(*tangent)
        if normal[1] > 0:  # first choice: below the curve
            normal = -normal
        offsets = []
        for distance in (5.5, 11.0):
            for side in (1, -1):
                dx, dy = side * distance * normal
                ha = "left" if dx > 0.3 * distance else "right" if dx < -0.3 * distance else "center"
                va = "bottom" if dy > 0.3 * distance else "top" if dy < -0.3 * distance else "center"
                offsets.append((dx, dy, ha, va))
        return offsets

    def place(self, label) -> bool:
        """Draw ``label`` at its first free position; return whether it was drawn."""
        ax = self.ax
        annotation = ax.annotate(label.text, label.anchor, xytext=(0, 0),
                                 textcoords="offset points", zorder=label.zorder, **label.style)
        annotation.set_in_layout(False)
        for dx, dy, ha, va in self._offsets(label):
            annotation.xyann = (dx, dy)
            annotation.set_horizontalalignment(ha)
            annotation.set_verticalalignment(va)
            b = annotation.get_window_extent()  # no arrow yet: the text's box
            box = np.array([b.x0, b.y0, b.x1, b.y1])
            inside = (box[0] >= self.frame.x0 and box[1] >= self.frame.y0
                      and box[2] <= self.frame.x1 and box[3] <= self.frame.y1)
            if inside and not np.any(_overlaps(self.boxes, box)):
                if np.hypot(dx, dy) > self._LEADER_PT:  # far away: a line shows whose it is
                    annotation.remove()
                    annotation = ax.annotate(
                        label.text, label.anchor, xytext=(dx, dy), textcoords="offset points",
                        ha=ha, va=va, zorder=label.zorder,
                        arrowprops={"arrowstyle": "-", "lw": 0.5, "color": "0.3",
                                    "shrinkA": 0, "shrinkB": 2},
                        **label.style)
                    annotation.set_in_layout(False)
                self.boxes = np.vstack([self.boxes, box])
                return True
        annotation.remove()
        return False


def _overlaps(boxes: np.ndarray, box: np.ndarray) -> np.ndarray:
    """Whether each of ``boxes`` (N, 4: x0, y0, x1, y1) overlaps ``box``."""
    return ((boxes[:, 0] < box[2]) & (box[0] < boxes[:, 2])
            & (boxes[:, 1] < box[3]) & (box[1] < boxes[:, 3]))


@plain_text
def spectrum_plot(spectrum, index=None, style: str = "bars", ax=None, title=None,
                  ylabel: str = "relative spectral power"):
    """Plot one spectrum as bars (or a filled area) tinted by wavelength (SPECTRA's palette).

    Parameters
    ----------
    spectrum : Spectrum
        A single spectrum, or a batch with ``index`` choosing one (``spectrum.values[index]``).
    index : int or tuple, optional
        Which spectrum of a batch to draw.
    style : {"bars", "area"}, default "bars"
        One bar per sample, or a filled area under the interpolated curve.
    ax : matplotlib.axes.Axes, optional
        Axes to draw into; default a new 6.4 × 3.2 inch figure.
    title : str, optional
        The axes' title.
    ylabel : str, default "relative spectral power"
        The y-axis label (say the scale: e.g. "reflectance factor (0–1)").

    Returns
    -------
    matplotlib.axes.Axes
        The axes drawn into (x: wavelength in nm).

    Raises
    ------
    ColorimetryError
        For a non-Spectrum, a batch without ``index``, or an unknown style.

    Examples
    --------
    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> from spectrocolor import illuminant, wavelength_grid
    >>> ax = spectrum_plot(illuminant("D65", wavelength_grid(400, 700, 10)))
    >>> ax.get_xlabel(), len(ax.patches)  # one tinted bar per sample
    ('wavelength (nm)', 31)
    >>> import matplotlib.pyplot as plt
    >>> plt.close(ax.figure)
    """
    from .pictures import wavelength_tint
    from .spectrum import Spectrum

    if not isinstance(spectrum, Spectrum):
        raise ColorimetryError(f"spectrum must be a Spectrum, got {type(spectrum).__name__}")
    values = spectrum.values if index is None else spectrum.values[index]
    if values.ndim != 1:
        raise ColorimetryError(
            f"spectrum holds a batch of shape {spectrum.batch_shape}; pass index= to pick one"
        )
    if style not in ("bars", "area"):
        raise ColorimetryError(f"style must be 'bars' or 'area', got {style!r}")
    wl = spectrum.wavelengths_nm
    tint = wavelength_tint(wl) / 255.0
    ax = axes_or_new(ax, (6.4, 3.2))
    if style == "bars":
        width = np.min(np.diff(wl)) * 0.9 if wl.size > 1 else 5.0
        ax.bar(wl, values, width=width, color=tint, edgecolor="0.3", linewidth=0.3)
    else:
        fine = np.linspace(wl[0], wl[-1], max(200, 4 * wl.size))
        v = np.interp(fine, wl, values)
        colours = wavelength_tint(fine) / 255.0
        for i in range(fine.size - 1):  # one polygon per slice of the area
            ax.fill_between(fine[i : i + 2], v[i : i + 2], color=colours[i], lw=0)
        ax.plot(wl, values, color="0.2", lw=0.8)
    ax.set_xlabel("wavelength (nm)")
    ax.set_ylabel(ylabel)
    ax.set_xlim(wl[0] - 5, wl[-1] + 5)
    if title is None and spectrum.names:
        title = spectrum.names[0 if index is None else int(np.ravel(index)[0])]
    if title:
        ax.set_title(title)
    return ax
