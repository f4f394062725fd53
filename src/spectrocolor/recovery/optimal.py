"""Optimal colours and the object-colour solid (Luther–Nyberg, Schrödinger, MacAdam).

With weights ``W`` (K, 3) from :func:`spectrocolor.weights`, the colours of all reflectances
``0 ≤ ρ ≤ 1`` form the object-colour solid, a zonotope whose boundary consists of the
*optimal colours*. Schrödinger's rule — optimal reflectances are 0 or 1 with at most two
transitions — holds for the continuous CIE observers only under West & Brill's conditions; on
sampled grids it fails (e.g. 156 of the 1 640 two-transition blocks on 380–780 nm at 10 nm
under D65 lie strictly inside the solid). Here the boundary is generated from supporting
hyperplanes instead: for a direction ``n``, the reflectance that is 1 where ``(W n)_k > 0``
and 0 where ``< 0`` maximises ``n · XYZ``, so its colour is on the boundary whatever the
number of transitions (``(W n)_k = 0`` marks a face: any value there stays on it). MacAdam
limits are the points where rays in the plane of constant Y leave the solid, found exactly
from its facets (normals are cross products of pairs of generators), as is membership.

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
from ..illuminants import DEFAULT_ILLUMINANT
from ..observers import DEFAULT_OBSERVER
from . import zonotope
from .inputs import DEFAULT_WAVELENGTHS, setup_for, xyz_array

#: Most hue angles :func:`macadam_limits` computes (0.01° apart; each costs one pass over the
#: solid's facets, so this bounds the time: a few seconds on the default 5 nm grid).
MAX_HUE_SAMPLES = 36_000


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
    XYZ, *, illuminant=DEFAULT_ILLUMINANT, observer=DEFAULT_OBSERVER, wavelengths=DEFAULT_WAVELENGTHS
) -> SolidMembership:
    """Exact membership test of ``XYZ`` (..., 3) (white ``Y = 100``) in the object-colour solid.

    Parameters
    ----------
    XYZ : array_like, shape (..., 3)
        Colours, XYZ100 (the perfect white under ``illuminant`` has Y = 100).
    illuminant : str or Spectrum, default "D65"
        The light the colours were computed under; see :term:`illuminant`.
    observer : str or Spectrum, default "1931"
        The observer the colours were computed with; see :term:`observer`.
    wavelengths : tuple of float or array_like, default (380.0, 780.0, 5.0)
        The grid of the solid's reflectances; see :term:`wavelength grid`.

    Returns
    -------
    SolidMembership
        ``inside`` (bool), ``relative_depth`` (> 0 inside, 0 on the boundary) and
        ``distance_outside`` (XYZ100 units), each of shape (...).

    References
    ----------
    E. Schrödinger, Ann. Phys. 62, 603–622 (1920) (optimal colours).

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


@dataclass(frozen=True)
class OptimalColours:
    """Points on the boundary of the object-colour solid, one per supporting direction.

    Attributes
    ----------
    normals : ndarray (M, 3)
        Unit outward directions (XYZ100 space) of the supporting planes.
    reflectances : ndarray (M, K)
        The maximising reflectances: 1 where ``(W n)_k > 0``, 0 where ``< 0``, 1/2 on the face.
    XYZ100 : ndarray (M, 3)
        Their colours (perfect white ``Y = 100``), each on the boundary.
    """

    normals: np.ndarray
    reflectances: np.ndarray
    XYZ100: np.ndarray


def optimal_colours(
    *, illuminant=DEFAULT_ILLUMINANT, observer=DEFAULT_OBSERVER, wavelengths=DEFAULT_WAVELENGTHS, directions=2000
) -> OptimalColours:
    """Optimal colours: the boundary of the object-colour solid from supporting hyperplanes.

    Parameters
    ----------
    illuminant : str or Spectrum, default "D65"
        The light the optimal colours are seen under; see :term:`illuminant`.
    observer : str or Spectrum, default "1931"
        Whose colour-matching functions give the optimal colours; see :term:`observer`.
    wavelengths : tuple of float or array_like, default (380.0, 780.0, 5.0)
        The samples of the optimal reflectances; see :term:`wavelength grid`.
    directions : int or array_like (M, 3)
        Number of directions spread evenly over the sphere, or the directions themselves.

    Returns
    -------
    OptimalColours
        For every direction the reflectance that maximises ``n · XYZ`` and its colour.

    References
    ----------
    E. Schrödinger, Ann. Phys. 62, 603–622 (1920); G. West, M. H. Brill, J. Opt. Soc. Am. 73,
    1223–1225 (1983).

    Examples
    --------
    >>> o = optimal_colours(wavelengths=(400, 700, 10), directions=50)
    >>> m = object_colour_membership(o.XYZ100, wavelengths=(400, 700, 10))
    >>> bool(abs(m.relative_depth).max() < 1e-12)
    True
    """
    setup, _, _ = setup_for(wavelengths, observer, illuminant)
    if isinstance(directions, int | np.integer) and not isinstance(directions, bool):
        if directions < 1:
            raise ColorimetryError(f"directions: expected at least 1, got {directions}")
        normals = zonotope.sphere_directions(int(directions))
    else:
        try:
            normals = np.asarray(directions, dtype=float)
        except (TypeError, ValueError):
            normals = np.zeros(0)
        if normals.ndim != 2 or normals.shape[1] != 3 or not np.all(np.isfinite(normals)):
            raise ColorimetryError(
                f"directions: expected an int or finite directions of shape (M, 3), got {directions!r}")
        norm = np.linalg.norm(normals, axis=1, keepdims=True)
        if np.any(norm == 0):
            raise ColorimetryError("directions: a direction of length 0 has no supporting plane")
        normals = normals / norm
    rho = zonotope.supporting_reflectances(setup.W, normals)
    return OptimalColours(normals, rho, rho @ setup.W)


def macadam_limits(
    luminance_factor: float,
    *,
    illuminant=DEFAULT_ILLUMINANT,
    observer=DEFAULT_OBSERVER,
    wavelengths=DEFAULT_WAVELENGTHS,
    samples: int = 720,
) -> np.ndarray:
    """The MacAdam limit: XYZ100 of the optimal colours with luminance factor ``Y``.

    Rays from the achromatic colour ``(Y / 100) · white`` in the plane of constant ``Y``, at
    ``samples`` hue angles (directions ``(cos θ · X_w, 0, sin θ · Z_w)``), leave the solid
    exactly where they meet its first facet plane: every returned point is on the boundary.

    Parameters
    ----------
    luminance_factor : float
        ``Y`` in percent of the perfect white, strictly between 0 and 100.
    illuminant : str or Spectrum, default "D65"
        The light the object colours are seen under; see :term:`illuminant`.
    observer : str or Spectrum, default "1931"
        The observer of the limits; see :term:`observer`.
    wavelengths : tuple of float or array_like, default (380.0, 780.0, 5.0)
        The optimal reflectances' samples; see :term:`wavelength grid`.
    samples : int, default 720
        Number of hue angles, spread uniformly over the full turn: 3 to
        :data:`MAX_HUE_SAMPLES` (each angle costs one pass over the solid's facets, so the
        limit bounds the time: a few seconds on the default grid).

    Returns
    -------
    ndarray (samples, 3)
        XYZ100 of the boundary points of the given ``Y``, ordered by hue angle: a closed
        locus; ``spectrocolor.xy`` gives the chromaticities.

    Examples
    --------
    >>> XYZ = macadam_limits(50.0, wavelengths=(400, 700, 10), samples=8)
    >>> bool(abs(XYZ[:, 1] - 50.0).max() < 1e-9)
    True
    """
    try:
        Y = float(luminance_factor)
    except (TypeError, ValueError):
        Y = np.nan
    if not 0.0 < Y < 100.0:
        raise ColorimetryError(f"luminance_factor: expected 0 < Y < 100 (percent), got {luminance_factor!r}")
    if isinstance(samples, bool) or not isinstance(samples, int | np.integer) \
            or not 3 <= samples <= MAX_HUE_SAMPLES:
        raise ColorimetryError(f"samples: expected an integer from 3 to {MAX_HUE_SAMPLES} hue angles "
                               f"({360 / MAX_HUE_SAMPLES:g}° apart), got {samples!r}")
    setup, _, _ = setup_for(wavelengths, observer, illuminant)
    white = setup.white
    origin = white * (Y / white[1])
    theta = np.linspace(0.0, 2 * np.pi, int(samples), endpoint=False)
    d = np.stack([np.cos(theta) * white[0], np.zeros_like(theta), np.sin(theta) * white[2]], axis=1)
    s = zonotope.ray_exit(setup.solid, origin, d)
    return origin + s[:, None] * d
