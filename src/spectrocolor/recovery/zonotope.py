"""Exact membership in the set of colours a reflectance can produce, for given weights.

With weights ``W`` (K, 3), the colours ``b = W.T @ rho`` of reflectances ``0 <= rho <= 1``
form a zonotope (the discrete object-colour solid), and those of ``rho >= 0`` a convex
cone. Both are polyhedra whose facet normals are cross products of pairs of generators
(rows of ``W``), so membership is decided exactly by a finite set of linear inequalities.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from . import compiled

#: Elements (colours × facets) of one block of the membership test: bounds its memory (32 MiB
#: per array) whatever the grid (the solid has K (K − 1) facets) and the batch.
BLOCK = 1 << 22


@dataclass(frozen=True)
class Facets:
    """Unit facet normals ``normals`` (F, 3) with offsets: inside iff ``normals @ (b - centre)
    <= support`` for every facet (for the cone, ``centre = 0`` and ``support = 0``)."""

    normals: np.ndarray
    support: np.ndarray
    centre: np.ndarray
    pairs: np.ndarray  # (F, 2) generator indices spanning each facet


def unit_cross(a: np.ndarray, b: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Unit vectors along ``a × b`` (rows; 0 where ``a × b = 0``) and ``|a × b|``, formed in
    extended precision.

    Two nearly parallel generators (the red end of the spectrum, at an angle θ of 1e-4 or
    less) have a cross product whose float64 rounding turns the normal by about ε/θ, and the
    generators then miss their own facet plane by that much: a boundary colour can look
    inside the solid by that much. In ``np.longdouble`` (64-bit significand on x86) the
    products and their difference carry 11 more bits, so that error shrinks 2048-fold before
    the normal is rounded to float64. Where ``np.longdouble`` is float64 this is the plain
    cross product.

    Parameters
    ----------
    a, b : numpy.ndarray, shape (..., 3)
        Generators (rows of the weights, XYZ100 per unit reflectance).

    Returns
    -------
    unit : numpy.ndarray, shape (..., 3)
        Unit normals, float64.
    norm : numpy.ndarray, shape (...)
        ``|a × b|``, float64 (XYZ100²).

    References
    ----------
    N. J. Higham, *Accuracy and Stability of Numerical Algorithms*, 2nd ed., SIAM (2002), §1.7
    (cancellation magnifies the rounding errors of the terms subtracted).

    Examples
    --------
    >>> unit, norm = unit_cross(np.array([[1.0, 0.0, 0.0]]), np.array([[1.0, 1e-9, 0.0]]))
    >>> unit.tolist(), bool(abs(norm[0] - 1e-9) < 1e-24)
    ([[0.0, 0.0, 1.0]], True)
    """
    a, b = a.astype(np.longdouble), b.astype(np.longdouble)
    n = np.cross(a, b)
    norm = np.sqrt((n * n).sum(axis=-1))
    unit = (n / np.where(norm > 0, norm, 1)[..., None]).astype(float)  # 0 for parallel rows
    return unit, norm.astype(float)


def _pair_normals(W: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    K = W.shape[0]
    i, j = np.triu_indices(K, 1)
    n, norm = unit_cross(W[i], W[j])
    scale = np.linalg.norm(W[i], axis=1) * np.linalg.norm(W[j], axis=1)
    keep = norm > 1e-12 * np.maximum(scale, np.finfo(float).tiny)
    return n[keep], np.stack([i[keep], j[keep]], axis=1)


def _blocked(normals: np.ndarray, W: np.ndarray, reduce) -> np.ndarray:
    """``reduce(normals @ W.T)`` row by row in blocks: the full (F, K) product has K³ entries."""
    rows = max(1, BLOCK // max(W.shape[0], 1))
    return np.concatenate([reduce(normals[i:i + rows] @ W.T) for i in range(0, len(normals), rows)]
                          or [reduce(np.zeros((0, W.shape[0])))])


def solid_facets(W: np.ndarray) -> Facets:
    """Facets of the zonotope ``{W.T rho : 0 <= rho <= 1}`` (both orientations)."""
    n, pairs = _pair_normals(W)
    n = np.concatenate([n, -n])
    pairs = np.concatenate([pairs, pairs])
    support = 0.5 * _blocked(n, W, lambda p: np.abs(p).sum(axis=1))
    centre = 0.5 * W.sum(axis=0)
    return Facets(n, support, centre, pairs)


def cone_facets(W: np.ndarray) -> Facets:
    """Facets of the cone ``{W.T rho : rho >= 0}``, normals pointing outwards."""
    n, pairs = _pair_normals(W)
    def sides(p):  # (F, K) projections of the generators on each normal, in blocks
        tol = 1e-12 * np.abs(p).max(axis=1, keepdims=True)
        return np.stack([np.all(p <= tol, axis=1), np.all(p >= -tol, axis=1)], axis=1)

    below, above = _blocked(n, W, sides).T
    n = np.concatenate([n[below], -n[above]])
    pairs = np.concatenate([pairs[below], pairs[above]])
    return Facets(n, np.zeros(len(n)), np.zeros(3), pairs)


def gauge(facets: Facets, b: np.ndarray, cone: bool) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Membership of colours ``b`` (N, 3).

    Parameters
    ----------
    facets : Facets
        From :func:`solid_facets` (the object-colour solid) or :func:`cone_facets`.
    b : numpy.ndarray, shape (N, 3)
        Colours, XYZ100.
    cone : bool
        Whether ``facets`` describe the cone of non-negative spectra (else the solid).

    Returns
    -------
    ratio : (N,)
        For the solid, the gauge ``max_f n_f.(b - c) / s_f`` (inside iff <= 1; ``1 - ratio``
        is the relative depth: the fraction by which ``b - c`` could grow and stay inside).
        For the cone, ``max_f n_f.b / |b|`` (inside iff <= 0), 0 for ``b = 0``.
    excess : (N,)
        ``max_f n_f.(b - c) - s_f``: the distance (XYZ100 units) from ``b`` to the farthest
        violated facet plane; computed only outside (for the solid, ``-inf`` inside; for the
        cone, ``max_f n_f.b``, <= 0 inside). Outside, it is the Euclidean distance to the
        solid when the nearest boundary point lies inside a facet, and a lower bound otherwise.
    facet : (N,) int
        Index of the facet attaining ``ratio``.

    Examples
    --------
    >>> from spectrocolor import wavelength_grid, weights
    >>> W = weights(wavelength_grid(400, 700, 10), illuminant="D65")
    >>> ratio, excess, facet = gauge(solid_facets(W), np.array([[40.0, 40.0, 40.0], [90.0, 10.0, 5.0]]), cone=False)
    >>> (ratio <= 1).tolist(), bool(excess[1] > 0)
    ([True, False], True)
    """
    N = b.shape[0]
    ratio = np.empty(N)
    excess = np.empty(N)
    facet = np.empty(N, dtype=np.int64)
    scaled = facets.normals if cone else facets.normals / facets.support[:, None]
    half = len(scaled) // 2
    chunk = max(1, BLOCK // max(len(scaled), 1))
    found = compiled.kernels()
    for start in range(0, N, chunk):
        d = b[start:start + chunk] - facets.centre
        rows = np.arange(len(d))
        if cone:
            if found is not None:
                top, k = compiled.facet_maxima(found, d, np.zeros(3), scaled, False)
            else:
                rel = d @ scaled.T
                k = np.argmax(rel, axis=1)
                top = rel[rows, k]
        else:  # the solid's facets come in opposite pairs (n, -n) with equal support
            if found is not None:
                top, k = compiled.facet_maxima(found, d, np.zeros(3), scaled[:half], True)
            else:
                rel = d @ scaled[:half].T
                k = np.argmax(np.abs(rel), axis=1)
                top = rel[rows, k]
            k = np.where(top >= 0, k, k + half)
            top = np.abs(top)
        if cone:
            norm = np.linalg.norm(d, axis=1)
            ratio[start:start + len(d)] = np.where(norm > 0, top / np.where(norm > 0, norm, 1), 0)
            excess[start:start + len(d)] = top
        else:
            ratio[start:start + len(d)] = top
            out = np.flatnonzero(top > 1.0)
            exc = np.full(len(d), -np.inf)
            if out.size:
                exc[out] = np.max(d[out] @ facets.normals.T - facets.support, axis=1)
            excess[start:start + len(d)] = exc
        facet[start:start + len(d)] = k
    return ratio, excess, facet


def sphere_directions(n: int) -> np.ndarray:
    """``n`` unit vectors (n, 3) spread evenly over the sphere (a Fibonacci lattice).

    Parameters
    ----------
    n : int
        Number of directions.

    Returns
    -------
    numpy.ndarray, shape (n, 3)
        Unit vectors.

    Examples
    --------
    >>> d = sphere_directions(10)
    >>> bool(np.allclose(np.linalg.norm(d, axis=1), 1.0))
    True
    """
    i = np.arange(n) + 0.5
    z = 1 - 2 * i / n
    phi = np.pi * (1 + 5**0.5) * i
    r = np.sqrt(1 - z**2)
    return np.stack([r * np.cos(phi), r * np.sin(phi), z], axis=1)


def supporting_reflectances(W: np.ndarray, normals: np.ndarray) -> np.ndarray:
    """The reflectances (M, K) whose colours maximise ``n · XYZ`` over ``0 ≤ ρ ≤ 1``.

    For each direction ``n`` (rows of ``normals``, (M, 3)): ``ρ_k = 1`` where ``(W n)_k > 0``,
    0 where ``< 0``, and 1/2 where it is 0 to rounding (``|(W n)_k| ≤ 4 γ_3 (|W| |n|)_k``): any
    value there gives a colour on the same face, 1/2 its centre. Each colour ``ρ @ W`` lies on
    the boundary of the solid, however many transitions ρ has.
    """
    p = normals @ W.T  # (M, K)
    eps = np.finfo(float).eps
    tol = 4 * (3 * eps / (1 - 3 * eps)) * (np.abs(normals) @ np.abs(W).T)
    return np.where(p > tol, 1.0, np.where(p < -tol, 0.0, 0.5))


def ray_exit(facets: Facets, origin: np.ndarray, directions: np.ndarray) -> np.ndarray:
    """Largest ``s`` with ``origin + s d`` in the solid, for each direction ``d`` (M, 3).

    ``origin`` (3,) must be inside. The exit point lies on the facet plane that the ray meets
    first: ``s = min over facets with n·d > 0 of (support − n·(origin − centre)) / (n·d)``.
    """
    slack = facets.support - facets.normals @ (origin - facets.centre)
    out = np.empty(len(directions))
    chunk = max(1, BLOCK // max(len(facets.normals), 1))
    for start in range(0, len(directions), chunk):
        nd = directions[start:start + chunk] @ facets.normals.T
        with np.errstate(divide="ignore", invalid="ignore"):
            s = np.where(nd > 0, slack / nd, np.inf)
        out[start:start + chunk] = s.min(axis=1)
    return out
