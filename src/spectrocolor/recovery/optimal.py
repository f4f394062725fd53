"""Optimal colours and the object-colour solid (Luther–Nyberg, Schrödinger, MacAdam).

With weights ``W`` (K, 3) from :func:`spectrocolor.weights`, the colours of all reflectances
``0 ≤ ρ ≤ 1`` form the object-colour solid, a zonotope whose boundary consists of the
*optimal colours*: for the CIE observers, reflectances that are 0 or 1 with at most two
transitions (band-pass or band-stop "block" spectra; Schrödinger 1920, MacAdam 1935). Here a
block may begin and end inside a sample interval (each sample counts as a bin of width one
step, so partial bins give the continuous boundary between the discrete vertices).

Membership is decided exactly from the facets of the zonotope (normals are cross products of
pairs of generators), so it holds even where the two-transition rule fails.

References
----------
E. Schrödinger, "Theorie der Pigmente von größter Leuchtkraft", Ann. Phys. 62, 603–622 (1920).
D. L. MacAdam, "Maximum visual efficiency of colored materials", J. Opt. Soc. Am. 25, 361–367
(1935).
G. West, M. H. Brill, "Conditions under which Schrödinger object colors are optimal",
J. Opt. Soc. Am. 73, 1223–1225 (1983).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..errors import ColorimetryError
from . import zonotope
from .inputs import DEFAULT_WAVELENGTHS, setup_for, xyz_array


@dataclass(frozen=True)
class SolidMembership:
    """Where colours lie relative to the object-colour solid (arrays of the batch shape).

    Attributes
    ----------
    inside : ndarray of bool
        Some reflectance 0 ≤ ρ ≤ 1 produces the colour (boundary included, to 1e-12).
    relative_depth : ndarray
        ``1 − g`` with ``g`` the gauge of the solid about its centre (half the white): the
        colour may move a fraction ``1 − g`` further from the centre and stay inside;
        negative outside.
    distance_outside : ndarray
        0 inside; outside, the distance (XYZ100 units) to the farthest violated facet plane.
    """

    inside: np.ndarray
    relative_depth: np.ndarray
    distance_outside: np.ndarray


def object_colour_membership(
    XYZ, illuminant="D65", observer="1931", wavelengths=DEFAULT_WAVELENGTHS
) -> SolidMembership:
    """Exact membership test of ``XYZ`` (..., 3) (white ``Y = 100``) in the object-colour solid.

    Examples
    --------
    >>> m = object_colour_membership([[40.0, 40.0, 40.0], [90.0, 10.0, 5.0]])
    >>> m.inside.tolist()
    [True, False]
    """
    b = xyz_array(XYZ)
    setup, _, _ = setup_for(wavelengths, observer, illuminant)
    flat = b.reshape(-1, 3)
    ratio, excess, _ = zonotope.gauge(setup.solid, flat, cone=False)
    depth = 1.0 - ratio
    shape = b.shape[:-1]
    return SolidMembership(
        inside=(depth >= -1e-12).reshape(shape),
        relative_depth=depth.reshape(shape),
        distance_outside=np.maximum(excess, 0.0).reshape(shape),
    )


def _cumulative(W: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Positions 0..2K and the cumulative weights over two periods (cyclic blocks)."""
    K = W.shape[0]
    cum = np.concatenate([np.zeros((1, 3)), np.cumsum(W, axis=0)])
    ext = np.concatenate([cum, cum[-1] + cum[1:]])
    return np.arange(2 * K + 1, dtype=float), ext


def optimal_colours(
    illuminant="D65", observer="1931", wavelengths=DEFAULT_WAVELENGTHS
) -> tuple[np.ndarray, np.ndarray]:
    """XYZ100 of every block spectrum with two transitions on the grid's sample bins.

    Returns
    -------
    (starts, XYZ100) : ndarray (M, 2) int, ndarray (M, 3)
        ``starts[i] = (first, count)``: the block covers ``count`` bins cyclically from bin
        ``first`` (a block that wraps round is a band-stop). These are the vertices of the
        discrete object-colour solid that lie on its two-transition boundary.
    """
    setup, _, _ = setup_for(wavelengths, observer, illuminant)
    K = setup.W.shape[0]
    _, ext = _cumulative(setup.W)
    first, count = np.meshgrid(np.arange(K), np.arange(1, K), indexing="ij")
    first, count = first.ravel(), count.ravel()
    XYZ = ext[first + count] - ext[first]
    return np.stack([first, count], axis=1), XYZ


def macadam_limits(
    luminance_factor: float,
    illuminant="D65",
    observer="1931",
    wavelengths=DEFAULT_WAVELENGTHS,
    samples: int = 720,
) -> np.ndarray:
    """The MacAdam limit: XYZ100 of the optimal colours with luminance factor ``Y``.

    Parameters
    ----------
    luminance_factor
        ``Y`` in percent of the perfect white, strictly between 0 and 100.
    samples
        Number of block start positions, spread uniformly (cyclically) over the range.

    Returns
    -------
    ndarray (samples, 3)
        XYZ100 of two-transition block spectra (with fractional ends) of the given ``Y``,
        ordered by block start: a closed locus; ``spectrocolor.xy`` gives the chromaticities.
    """
    Y = float(luminance_factor)
    if not 0.0 < Y < 100.0:
        raise ColorimetryError(f"luminance_factor: expected 0 < Y < 100 (percent), got {luminance_factor!r}")
    setup, _, _ = setup_for(wavelengths, observer, illuminant)
    K = setup.W.shape[0]
    t, ext = _cumulative(setup.W)
    start = np.linspace(0.0, K, samples, endpoint=False)
    start_xyz = np.stack([np.interp(start, t, ext[:, j]) for j in range(3)], axis=1)
    end = np.interp(start_xyz[:, 1] + Y, ext[:, 1], t)
    end_xyz = np.stack([np.interp(end, t, ext[:, j]) for j in range(3)], axis=1)
    return end_xyz - start_xyz
