"""The TM-30 colour vector graphic: how a light shifts chroma and hue in each of 16 hue bins.

Laid out as ANSI/IES TM-30-20 §6.2 draws it: the reference's 16 bin means are normalised onto
the unit circle (black), each at its own hue angle θ_j; the light's bin means are placed at
``(cos θ_j, sin θ_j) + (a'_t − a'_r, b'_t − b'_r) / |r_j|`` (red polygon), with an arrow from
the reference to the light in every bin. Arrows pointing outward mean more saturated, inward
less saturated, sideways a hue shift. Rf, Rg, CCT and Duv are printed in the corners. The
arrow colours are sRGB renderings (under D65) of the most colourful evaluation sample of each
bin, so the picture reads like the standard's.

matplotlib is an optional extra, imported when a graphic is drawn.

References
----------
ANSI/IES TM-30-20 *IES method for evaluating light source color rendition*, §6.2 (colour
vector graphic) and §4.6 (hue bins).
"""

from __future__ import annotations

from functools import cache
from pathlib import Path

import numpy as np

from ..errors import ColorimetryError
from ..plot import plain_text
from ..safe_write import write_bytes
from .fidelity import HUE_BINS, Fidelity

#: Picture formats :func:`write_vector_graphic` writes.
FORMATS = ("png", "svg")


def normalised_graphic(fidelity: Fidelity, index=()) -> tuple[np.ndarray, np.ndarray]:
    """Reference (unit circle) and test corners (16, 2) of the vector graphic of one light.

    Parameters
    ----------
    fidelity : Fidelity
        From :func:`~spectrocolor.lighting.colour_fidelity`.
    index : int or tuple, default ()
        Which light of a batch (``()`` for a single light).

    Returns
    -------
    reference : numpy.ndarray, shape (16, 2)
        The reference's hue-bin corners, normalised to the unit circle.
    test : numpy.ndarray, shape (16, 2)
        The light's corners, with the same normalisation.

    Raises
    ------
    ColorimetryError
        For an ``index`` that does not pick one light.

    References
    ----------
    ANSI/IES TM-30-20, §6 (colour vector graphic).

    Examples
    --------
    >>> from spectrocolor import illuminant
    >>> from spectrocolor.lighting import colour_fidelity
    >>> reference, test = normalised_graphic(colour_fidelity(illuminant("D65")))
    >>> bool(np.allclose(np.hypot(*reference.T), 1.0) and np.allclose(test, reference))
    True
    """
    ref = np.asarray(fidelity.reference_ab[index], dtype=float)
    test = np.asarray(fidelity.test_ab[index], dtype=float)
    if ref.shape != (HUE_BINS, 2):
        raise ColorimetryError(
            f"index: pick one light of the batch {np.shape(fidelity.Rf)} (e.g. index=0), got {index!r}"
        )
    norm = np.linalg.norm(ref, axis=-1, keepdims=True)
    unit = ref / norm
    return unit, unit + (test - ref) / norm


@cache
def bin_colours_rgb8() -> np.ndarray:
    """sRGB codes (16, 3) of the most colourful CES of each hue bin under D65.

    Examples
    --------
    >>> bin_colours_rgb8().shape
    (16, 3)
    """
    from ..colorimetry import weights
    from ..display.adaptation import adapt
    from ..display.render import render
    from ..display.spaces import rgb_space
    from ..spectrum import wavelength_grid
    from .cam02ucs import cam02ucs_jab
    from .spectra import ces_reflectances

    grid = wavelength_grid(380, 780, 5)
    W = weights(grid, observer="1931", illuminant="D65")
    XYZ = ces_reflectances(grid) @ W
    white = W.sum(axis=0)
    jab = cam02ucs_jab(XYZ, white)
    hue = np.degrees(np.arctan2(jab[:, 2], jab[:, 1])) % 360.0
    chroma = np.hypot(jab[:, 1], jab[:, 2])
    bins = np.floor(hue / (360.0 / HUE_BINS)).astype(int)
    picks = [np.flatnonzero(bins == j)[np.argmax(chroma[bins == j])] for j in range(HUE_BINS)]
    adapted = adapt(XYZ[picks], white, rgb_space("sRGB").white_XYZ)
    return render(adapted, "sRGB", gamut="desaturate").codes


@plain_text
def vector_graphic(fidelity: Fidelity, index=(), *, ax=None, title: str | None = None):
    """Draw the TM-30 colour vector graphic of one light; returns the matplotlib Figure.

    Parameters
    ----------
    fidelity : Fidelity
        From :func:`~spectrocolor.lighting.colour_fidelity`.
    index : int or tuple
        Which light of a batch (``()`` for a single light).
    ax : matplotlib Axes, optional
        Draw into these axes; default: a new 5 × 5 inch figure.
    title : str, optional
        The graphic's title.

    Returns
    -------
    matplotlib.figure.Figure
        The figure drawn into.

    References
    ----------
    ANSI/IES TM-30-20, §6 (colour vector graphic).

    Examples
    --------
    >>> from spectrocolor import illuminant
    >>> from spectrocolor.lighting import colour_fidelity
    >>> figure = vector_graphic(colour_fidelity(illuminant("FL2")), title="FL2")
    >>> len(figure.axes)
    1
    """
    from matplotlib.figure import Figure

    reference, test = normalised_graphic(fidelity, index)
    if ax is None:
        figure = Figure(figsize=(5, 5))
        ax = figure.add_subplot()
    else:
        figure = ax.figure
    colours = bin_colours_rgb8() / 255.0
    for angle in np.radians(np.arange(HUE_BINS) * 360.0 / HUE_BINS):
        ax.plot([0, 1.5 * np.cos(angle)], [0, 1.5 * np.sin(angle)], color="0.85", lw=0.6, zorder=0)
    for radius in (0.8, 1.2):
        circle = np.radians(np.linspace(0, 360, 361))
        ax.plot(radius * np.cos(circle), radius * np.sin(circle), color="0.7", lw=0.6, ls=":", zorder=0)
    closed = np.vstack([reference, reference[:1]])
    ax.plot(*closed.T, color="black", lw=1.6, zorder=2, label="reference")
    closed = np.vstack([test, test[:1]])
    ax.plot(*closed.T, color="#d62728", lw=1.8, zorder=3, label="test")
    for j in range(HUE_BINS):
        ax.annotate("", xy=test[j], xytext=reference[j], zorder=4,
                    arrowprops={"arrowstyle": "-|>", "color": colours[j], "lw": 2.0, "shrinkA": 0, "shrinkB": 0})
        label = 1.38 * reference[j]
        ax.text(*label, str(j + 1), ha="center", va="center", fontsize=8, color="0.3")
    ax.set_xlim(-1.5, 1.5)
    ax.set_ylim(-1.5, 1.5)
    ax.set_aspect("equal")
    ax.set_xticks([])
    ax.set_yticks([])
    Rf, Rg, cct_K, duv = (float(np.asarray(v)[index]) for v in (fidelity.Rf, fidelity.Rg, fidelity.cct_K, fidelity.duv))
    ax.text(-1.45, 1.45, f"Rf {Rf:.0f}", va="top", fontsize=12, weight="bold")
    ax.text(1.45, 1.45, f"Rg {Rg:.0f}", va="top", ha="right", fontsize=12, weight="bold")
    ax.text(-1.45, -1.45, f"CCT {cct_K:.0f} K", fontsize=10)
    ax.text(1.45, -1.45, f"Duv {duv:.4f}", ha="right", fontsize=10)
    if title:
        ax.set_title(title)
    return figure


def write_vector_graphic(fidelity: Fidelity, path, index=(), *, title: str | None = None) -> Path:
    """Write the colour vector graphic of one light as PNG or SVG (by the file suffix).

    The file is written beside ``path`` and renamed over it when complete.

    Parameters
    ----------
    fidelity : Fidelity
        From :func:`~spectrocolor.lighting.colour_fidelity`.
    path : str or os.PathLike
        Output file ending in ``.png`` or ``.svg``.
    index : int or tuple, default ()
        Which light of a batch.
    title : str, keyword-only, optional
        The graphic's title.

    Returns
    -------
    pathlib.Path
        ``path``, the graphic.

    Raises
    ------
    ColorimetryError
        For another suffix or an ``index`` that does not pick one light.
    spectrocolor.safe_write.OutputError
        The graphic could not be written; see :term:`atomic write`.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> from spectrocolor import illuminant
    >>> from spectrocolor.lighting import colour_fidelity
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     path = write_vector_graphic(colour_fidelity(illuminant("FL2")), pathlib.Path(folder) / "fl2.svg")
    ...     path.read_text().count("<svg") >= 1
    True
    """
    import io

    path = Path(path)
    fmt = path.suffix.lstrip(".").lower()
    if fmt not in FORMATS:
        raise ColorimetryError(f"path: {str(path)!r} must end in one of {', '.join('.' + f for f in FORMATS)}")
    buffer = io.BytesIO()
    vector_graphic(fidelity, index, title=title).savefig(buffer, format=fmt, dpi=120, bbox_inches="tight")
    return write_bytes(path, buffer.getvalue())
