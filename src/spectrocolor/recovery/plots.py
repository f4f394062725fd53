"""Plots for reflectance recovery (matplotlib, imported only when a plot is made).

Recovered against measured reflectance curves (van Trigt 1990, Fig. 2), domains of validity
of the unconstrained solution (Figs. 7–12), MacAdam limits, and metamer mismatch regions.
Every function draws into ``ax`` when given and otherwise into a new
:class:`matplotlib.figure.Figure` (no pyplot state); it returns the axes.
"""

from __future__ import annotations

import numpy as np

from ..colorimetry import weights
from ..coordinates import lab, xy
from ..errors import SpectrumError
from ..plot import axes_or_new, chromaticity_diagram, plain_text
from ..spectrum import Spectrum
from .optimal import macadam_limits


@plain_text
def reflectance_curves(spectrum: Spectrum, measured: Spectrum | None = None, ax=None,
                       title: str | None = None, labels=None):
    """Reflectance curves (solid), optionally against measured ones (dashed, same colour).

    Parameters
    ----------
    spectrum : Spectrum (..., K)
        Reflectance factors (0–1), e.g. ``smoothest_reflectance(...).spectrum``.
    measured : Spectrum, optional
        The same number of curves, on any grid (e.g. the measured samples).
    ax : matplotlib.axes.Axes, optional
        Axes to draw into; default a new figure.
    title : str, optional
        The axes' title.
    labels : sequence of str, optional
        Legend entries (default: ``spectrum.names``).

    Returns
    -------
    matplotlib.axes.Axes
        The axes drawn into.

    Examples
    --------
    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> from spectrocolor import smoothest_reflectance
    >>> result = smoothest_reflectance([[40.0, 40.0, 40.0], [30.0, 20.0, 10.0]], wavelengths=(400, 700, 10))
    >>> len(reflectance_curves(result.spectrum, labels=["grey", "orange"]).lines)
    2
    >>> import matplotlib.pyplot as plt
    >>> plt.close("all")
    """
    values = np.atleast_2d(spectrum.values).reshape(-1, len(spectrum.wavelengths_nm))
    ref = None
    if measured is not None:
        ref = np.atleast_2d(measured.values).reshape(-1, len(measured.wavelengths_nm))
        if len(ref) != len(values):
            raise SpectrumError(f"measured: expected {len(values)} curves to compare, got {len(ref)}")
    names = labels if labels is not None else (spectrum.names or [None] * len(values))
    ax = axes_or_new(ax, (6.4, 4.0))
    for i, curve in enumerate(values):
        ax.plot(spectrum.wavelengths_nm, curve, color=f"C{i % 10}", lw=1.6, label=names[i])
        if ref is not None and measured is not None:  # ref is set exactly when measured is
            ax.plot(measured.wavelengths_nm, ref[i], color=f"C{i % 10}", lw=1.2, ls="--")
    ax.set_xlabel("wavelength (nm)")
    ax.set_ylabel("reflectance factor")
    ax.set_ylim(-0.02, 1.05)
    ax.grid(True, lw=0.3, color="0.85")
    if any(n is not None for n in names) and len(values) <= 12:
        ax.legend(fontsize=7, ncol=2 if len(values) > 6 else 1)
    if title is not None:
        ax.set_title(title)
    return ax


def _points_and_labels(points):
    """``points`` as (N, 2) chromaticities with labels: a mapping label → xy, or an array."""
    if isinstance(points, dict):
        labels = [str(k) for k in points]
        xy = np.asarray([points[k] for k in points], dtype=float).reshape(-1, 2)
    else:
        xy = np.asarray(points, dtype=float)
        if xy.ndim == 1:
            xy = xy[None]
        labels = [str(i + 1) for i in range(len(xy))]
    if xy.ndim != 2 or xy.shape[1] != 2:
        raise SpectrumError(f"points: expected chromaticities (N, 2) or a mapping of labels to (x, y), "
                            f"got shape {xy.shape}")
    return xy, labels


@plain_text
def domain_of_validity_plot(domain, ax=None, title: str | None = None, levels=None, *,
                            classes: bool = True, points=None, points_label: str = "marked points",
                            luminance: bool = True):
    """A domain of validity on the CIE 1931 xy diagram (van Trigt 1990, Figs. 7–8 and 11–12).

    Outline: the region where the unconstrained solution is non-negative; dashed: the straight
    lines where it vanishes at the first (λ_b) and the last (λ_e) sample. With ``luminance``,
    filled contours of the maximum luminance factor Y/Y0 for which it stays ≤ 1 (Figs. 11–12).
    With ``classes`` (Figs. 7–8), the regions of van Trigt's classes — the fan from the white to
    each class's stretch of the boundary, separated by straight lines from the white — with
    the classes' end points marked. ``points`` marks chromaticities such as the CIE test
    colours.

    Parameters
    ----------
    domain : DomainOfValidity
        From :func:`spectrocolor.domain_of_validity`.
    ax : matplotlib.axes.Axes, optional
        Axes to draw into; default a new figure.
    title : str, optional
        The axes' title (default: the illuminant and the range).
    levels : sequence of float, optional
        Contour levels of Y/Y0 (0–1).
    classes : bool, default True
        Draw the class regions and their end points (van Trigt Figs. 7–8).
    points : mapping of str to (x, y), or array_like (N, 2), optional
        Chromaticities to mark, labelled by the mapping's keys (or 1…N).
    points_label : str, default "marked points"
        The legend entry of ``points``.
    luminance : bool, default True
        Fill the maximum luminance factor (Figs. 11–12).

    Returns
    -------
    matplotlib.axes.Axes
        The axes drawn into.

    References
    ----------
    C. van Trigt, J. Opt. Soc. Am. A 7, 1891–1904 (1990), Figs. 7–8 and 11–12.

    Examples
    --------
    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> from spectrocolor import domain_of_validity
    >>> d = domain_of_validity("D65", wavelengths=(400, 700, 10))
    >>> domain_of_validity_plot(d, points={"white": (0.3127, 0.3290)}).get_title()
    'Domain of validity, D65, 400–700 nm'
    >>> import matplotlib.pyplot as plt
    >>> plt.close("all")
    """
    ax = chromaticity_diagram(spaces=(), whites=(domain.illuminant,), planckian=False,
                              fill=False, ax=axes_or_new(ax, (6.4, 6.4)),
                              title=title or f"Domain of validity, {domain.illuminant}, "
                              f"{domain.wavelengths_nm[0]:g}–{domain.wavelengths_nm[-1]:g} nm")
    if luminance:
        x, y = np.meshgrid(np.linspace(0.0, 0.8, 321), np.linspace(0.001, 0.9, 361))
        ymax = domain.max_luminance_factor(np.stack([x, y], axis=-1))
        levels = levels if levels is not None else np.linspace(0.0, 1.0, 11)
        cs = ax.contourf(x, y, ymax, levels=levels, cmap="viridis", zorder=1, alpha=0.85)
        ax.figure.colorbar(cs, ax=ax, shrink=0.7, label="max. luminance factor Y/Y0 with ρ ≤ 1")
    poly = np.vstack([domain.region_xy, domain.region_xy[:1]])
    ax.plot(poly[:, 0], poly[:, 1], color="black", lw=1.4, zorder=6, label="ρ ≥ 0 region")
    t = np.linspace(-0.1, 1.0, 2)
    for (a, b, c), name, style in zip(domain.end_lines(), ("λ_b", "λ_e"), ("--", ":"),
                                      strict=True):
        nm = domain.wavelengths_nm[0 if name == "λ_b" else -1]
        if abs(b) >= abs(a):
            xs, ys = t, -(a * t + c) / b
        else:
            xs, ys = -(b * t + c) / a, t
        ax.plot(xs, ys, color="crimson", lw=1.0, ls=style, zorder=6,
                label=f"ρ({name} = {nm:g} nm) = 0")
    if classes:
        _draw_classes(ax, domain, filled=not luminance)
    if points is not None:
        xy, labels = _points_and_labels(points)
        ax.plot(xy[:, 0], xy[:, 1], "o", mfc="white", mec="black", ms=5, zorder=8,
                label=points_label)
        for (px, py), text in zip(xy, labels, strict=True):
            ax.annotate(text, (px, py), xytext=(3, 3), textcoords="offset points", fontsize=6,
                        zorder=9)
    ax.set_xlim(-0.02, 0.82)
    ax.set_ylim(-0.02, 0.9)
    ax.legend(loc="upper right", fontsize=7, framealpha=0.9)
    return ax


def _draw_classes(ax, domain, filled: bool):
    """Van Trigt's class regions (fans from the white), their dividing lines and end points."""
    white = domain.white_xy
    ends = []
    colours = {"1": ("#f4a582", "#b2182b"), "2": ("#92c5de", "#2166ac")}
    for piece in domain.boundary_pieces():
        if not piece.solution_class:
            continue
        fan = np.vstack([white, piece.xy])
        light, dark = colours[piece.solution_class]
        if filled:
            ax.fill(fan[:, 0], fan[:, 1], color=light, alpha=0.6, zorder=2, lw=0)
        ax.plot(*piece.xy.T, color=dark, lw=2.2, zorder=5, solid_capstyle="butt")
        for corner in (piece.xy[0], piece.xy[-1]):
            ax.plot([white[0], corner[0]], [white[1], corner[1]], color="0.15", lw=0.8, zorder=5)
        ends.extend([piece.xy[0], piece.xy[-1]])
        middle = 0.5 * (piece.xy[(len(piece.xy) - 1) // 2] + piece.xy[len(piece.xy) // 2])
        inside = 0.35 * white + 0.65 * middle
        text = (f"1: ρ({piece.zero_nm:g}) = 0" if piece.solution_class == "1" else "2")
        ax.annotate(text, inside, fontsize=7, ha="center", va="center", color=dark, zorder=9,
                    fontweight="bold")
    if ends:
        corners = np.unique(np.round(np.asarray(ends), 12), axis=0)
        ax.plot(corners[:, 0], corners[:, 1], "D", color="black", ms=4, zorder=8,
                label="end points of the classes")


@plain_text
def macadam_limits_plot(luminance_factors=(10, 30, 50, 70, 90), illuminant="D65",
                        observer="1931", wavelengths=(380.0, 780.0, 5.0), ax=None):
    """MacAdam limits (optimal colours) at several luminance factors Y (percent).

    Parameters
    ----------
    luminance_factors : sequence of float, default (10, 30, 50, 70, 90)
        Y of each locus, percent of the perfect white (strictly between 0 and 100).
    illuminant : str or Spectrum, default "D65"
        The light.
    observer : str, default "1931"
        Observer name or alias.
    wavelengths : tuple of float, default (380.0, 780.0, 5.0)
        ``(start_nm, stop_nm, step_nm)`` of the optimal reflectances.
    ax : matplotlib.axes.Axes, optional
        Axes to draw into; default a new figure.

    Returns
    -------
    matplotlib.axes.Axes
        The axes drawn into.

    References
    ----------
    D. L. MacAdam, J. Opt. Soc. Am. 25, 249–252 (1935).

    Examples
    --------
    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> macadam_limits_plot((20, 60), wavelengths=(400, 700, 10)).get_title()
    'MacAdam limits, D65, observer 1931'
    >>> import matplotlib.pyplot as plt
    >>> plt.close("all")
    """
    curves = [np.vstack([c, c[:1]]) for c in (
        xy(macadam_limits(Y, illuminant=illuminant, observer=observer, wavelengths=wavelengths))
        for Y in luminance_factors)]
    return chromaticity_diagram(
        spaces=(), whites=(illuminant,), planckian=False, fill=False,
        curves=curves, curve_labels=[f"Y = {Y:g} %" for Y in luminance_factors],
        ax=axes_or_new(ax, (6.4, 6.4)), title=f"MacAdam limits, {illuminant}, observer {observer}")


@plain_text
def mismatch_region_plot(region, sample_XYZ100_second=None, metamers_XYZ100_second=None, ax=None):
    """A metamer mismatch region seen in CIELAB a*b* under the second illuminant.

    The outline is the convex hull of the boundary points projected on a*b* (the projection
    of the convex region in XYZ, curved by CIELAB's non-linearity); ``sample_XYZ100_second``
    and ``metamers_XYZ100_second`` (e.g. smooth metamers) are marked.

    Parameters
    ----------
    region : MismatchRegion
        From :func:`spectrocolor.metamer_mismatch_region`.
    sample_XYZ100_second : array_like, shape (3,), optional
        The sample's colour under the second illuminant, XYZ100.
    metamers_XYZ100_second : array_like, shape (M, 3), optional
        Colours of metamers under the second illuminant, XYZ100.
    ax : matplotlib.axes.Axes, optional
        Axes to draw into; default a new figure.

    Returns
    -------
    matplotlib.axes.Axes
        The axes drawn into.

    Examples
    --------
    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> import numpy as np
    >>> from spectrocolor import metamer_mismatch_region, wavelength_grid, weights
    >>> grey = np.full(31, 0.4)
    >>> region = metamer_mismatch_region(grey @ weights(wavelength_grid(400, 700, 10), illuminant="D65"),
    ...                                  wavelengths=(400, 700, 10), directions=50)
    >>> mismatch_region_plot(region).get_xlabel()
    'a*'
    >>> import matplotlib.pyplot as plt
    >>> plt.close("all")
    """
    from scipy.spatial import ConvexHull

    W_white = _second_white(region)
    ab = lab(region.boundary_XYZ100, W_white)[:, 1:]
    ax = axes_or_new(ax, (5.6, 5.2))
    hull = ConvexHull(ab)
    loop = np.append(hull.vertices, hull.vertices[0])
    ax.fill(ab[loop, 0], ab[loop, 1], color="0.85", zorder=1, label="mismatch region (a*b*)")
    ax.plot(ab[loop, 0], ab[loop, 1], color="0.3", lw=1.0, zorder=2)
    ax.plot(ab[:, 0], ab[:, 1], ".", color="0.4", ms=3, zorder=3, label="extreme metamers")
    if metamers_XYZ100_second is not None:
        m = lab(np.atleast_2d(metamers_XYZ100_second), W_white)[:, 1:]
        ax.plot(m[:, 0], m[:, 1], "o", mfc="C1", mec="black", ms=6, zorder=5,
                label="smooth metamers")
    if sample_XYZ100_second is not None:
        s = lab(np.asarray(sample_XYZ100_second), W_white)[1:]
        ax.plot(*s, "*", color="C3", mec="black", ms=13, zorder=6, label="sample")
    ax.set_xlabel("a*")
    ax.set_ylabel("b*")
    ax.set_aspect("equal")
    ax.grid(True, lw=0.3, color="0.85")
    ax.legend(fontsize=7)
    ax.set_title(f"Metamer mismatch: match under {region.illuminant}, seen under "
                 f"{region.second_illuminant}")
    return ax


def _second_white(region):
    grid = region.extreme_metamers.wavelengths_nm
    return np.asarray(weights(grid, observer=region.observer, illuminant=region.second_illuminant)).sum(axis=0)


@plain_text
def boundary_locus_plot(locus, generating=None, ax=None, title: str | None = None):
    """Van Trigt's boundary locus (Figs. 3–4): left and right branches on the xy diagram.

    ``locus`` is a :class:`~spectrocolor.recovery.validity.BoundaryLocus`; with
    ``generating`` (:class:`~spectrocolor.recovery.generating.GeneratingFunctions`) the
    chromaticities of the generating functions (the boundary of the domain of validity) are
    drawn too, with λ₁ marked every 50 nm.

    Parameters
    ----------
    locus : BoundaryLocus
        From :func:`spectrocolor.recovery.validity.boundary_locus`.
    generating : GeneratingFunctions, optional
        From :func:`spectrocolor.recovery.generating.generating_functions`.
    ax : matplotlib.axes.Axes, optional
        Axes to draw into; default a new figure.
    title : str, optional
        The axes' title (default "Boundary locus").

    Returns
    -------
    matplotlib.axes.Axes
        The axes drawn into.

    References
    ----------
    C. van Trigt, J. Opt. Soc. Am. A 7, 1891–1904 (1990), Figs. 3–4.

    Examples
    --------
    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> from spectrocolor.recovery.validity import boundary_locus
    >>> boundary_locus_plot(boundary_locus("D65", wavelengths=(400, 700, 10))).get_title()
    'Boundary locus'
    >>> import matplotlib.pyplot as plt
    >>> plt.close("all")
    """
    ax = chromaticity_diagram(spaces=(), whites=(), planckian=False, fill=False,
                              ax=axes_or_new(ax, (6.4, 6.4)), title=title or "Boundary locus")
    ax.plot(*locus.left_xy.T, color="C0", lw=1.5, zorder=5, label="left branch: λ_b … λ")
    ax.plot(*locus.right_xy.T, color="C3", lw=1.5, zorder=5, label="right branch: λ … λ_e")
    ax.plot(*locus.white_xy, "o", color="black", ms=5, zorder=6, label="white")
    for branch, color in ((locus.left_xy, "C0"), (locus.right_xy, "C3")):
        for nm in range(450, 701, 50):
            k = int(np.argmin(np.abs(locus.wavelengths_nm - nm)))
            if np.all(np.isfinite(branch[k])):
                ax.annotate(f"{nm}", branch[k], fontsize=6, color=color, zorder=7)
    if generating is not None:
        for rows, style, text in _families(generating):
            ax.plot(*generating.xy[rows].T, color="0.2", lw=1.0, ls=style, zorder=5,
                    label=f"ρ(λ; λ₁) chromaticities, {text}")
    ax.legend(loc="upper right", fontsize=7, framealpha=0.9)
    return ax


def _families(generating):
    """``(rows, line style, label)`` of each family in ``generating``: class 2, then class 1 per end."""
    out = []
    rows = generating.family("2")
    if len(rows):
        out.append((rows, "--", "class 2 (interior zero at λ₁)"))
    for end, style in zip(generating.wavelengths_nm[[0, -1]], (":", "-."), strict=True):
        rows = generating.family("1", end)
        if len(rows):
            out.append((rows, style, f"class 1 (zero at {end:g} nm)"))
    return out


def _with_gaps(x, y, step):
    """``x``, ``y`` with NaN between points more than one grid step apart (no line across gaps)."""
    if len(x) < 2:
        return x, y
    cut = np.flatnonzero(np.diff(x) > 1.5 * step) + 1
    return np.insert(x.astype(float), cut, np.nan), np.insert(y.astype(float), cut, np.nan)


@plain_text
def generating_luminance_plot(generating, ax=None, title: str | None = None):
    """``Y(λ₁)/Y₀`` (solid) and ``Y_M(λ₁)/Y₀`` (dashed) against λ₁, both classes (van Trigt Figs. 9–10).

    One colour per family: class 2 (interior zero with zero slope at λ₁) and class 1 on each end
    line (zero at λ_b or λ_e, inflection at λ₁). A class-1 family is drawn only over the λ₁ for
    which ρ(λ; λ₁) ≥ 0; lines break where that set has gaps.

    Parameters
    ----------
    generating : GeneratingFunctions
        From :func:`spectrocolor.recovery.generating.generating_functions`.
    ax : matplotlib.axes.Axes, optional
        Axes to draw into; default a new figure.
    title : str, optional
        The axes' title.

    Returns
    -------
    matplotlib.axes.Axes
        The axes drawn into.

    References
    ----------
    C. van Trigt, J. Opt. Soc. Am. A 7, 1891–1904 (1990), Figs. 9–10.

    Examples
    --------
    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> from spectrocolor.recovery.validity import generating_functions
    >>> generating_luminance_plot(generating_functions("D65", wavelengths=(400, 700, 10))).get_ylabel()
    'luminance factor Y/Y₀'
    >>> import matplotlib.pyplot as plt
    >>> plt.close("all")
    """
    ax = axes_or_new(ax, (6.4, 4.0))
    grid = generating.wavelengths_nm
    step = float(grid[1] - grid[0]) if len(grid) > 1 else 1.0
    for i, (rows, _, text) in enumerate(_families(generating)):
        colour = ("C0", "C3", "C2")[i % 3]
        lam = generating.lambda1_nm[rows]
        ax.plot(*_with_gaps(lam, generating.luminance_factor[rows], step), color=colour, lw=1.6,
                label=f"Y(λ₁)/Y₀, {text}")
        ax.plot(*_with_gaps(lam, generating.max_luminance_factor[rows], step), color=colour,
                lw=1.1, ls="--", label=f"Y_M(λ₁)/Y₀ (optimal colour), {text}")
    ax.set_xlabel("λ₁ (nm)")
    ax.set_ylabel("luminance factor Y/Y₀")
    ax.set_ylim(0, 1.02)
    ax.grid(True, lw=0.3, color="0.85")
    ax.legend(fontsize=6)
    if title is not None:
        ax.set_title(title)
    return ax
