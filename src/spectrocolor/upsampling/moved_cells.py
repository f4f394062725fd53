"""Exact answers in the cells of a table whose nodes were moved toward grey.

A table node whose colour lies outside the object-colour solid is moved toward grey onto the
solid's boundary (:mod:`spectrocolor.upsampling.table`). Blending by the grid weights then no
longer reproduces the query in the tetrahedra that touch such a node. This module settles
those queries (inside the cube ``[0, 1]^3``), each by the first of these that applies:

1. **The nodes' actual colours.** Blending is linear in the node spectra, so if the query's
   colour ``q = matrix @ t`` is a convex combination ``q = Σ β_i X_i`` of the colours
   ``X_i = ρ_i @ W`` that four nodes actually produce, then ``ρ = Σ β_i ρ_i`` reproduces it
   and, as a convex combination of spectra in [0, 1], stays in [0, 1]. The six tetrahedra
   of the query's cell are tried, with ``β`` from the inverse of each tetrahedron's edge
   matrix of actual colours (precomputed per table; nearly flat tetrahedra, condition number
   above :data:`MAX_CONDITION`, are skipped).
2. **Outside the solid.** A facet plane of the solid that the colour violates proves it lies
   outside (the solid is convex): no reflectance produces it. The facets tried are those on
   which the solid's gauge peaks at the 27 points ``(i + a/2, j + b/2, k + c/2)`` of the cell
   (a necessary test only; a colour it cannot place goes on, and 4.'s membership test is
   complete). Such a colour keeps the table's blend and is flagged (its documented move).
3. **Neighbouring cells.** Moved nodes bend the tetrahedra of actual colours across cell
   walls, so the tetrahedra of the 26 neighbouring cells with moved nodes are tried as in 1.
4. **A certified exact solve.** The rest (the thin gap between the tetrahedra of actual
   colours and the curved boundary of the solid) is solved by the smoothest-reflectance
   solver of :mod:`spectrocolor.recovery.smoothest` on the table's own weights: its
   membership test decides inside or outside, and an inside answer is kept only if its
   certificate passes and it reproduces ``q`` to :data:`EXACT_TOLERANCE`.

With numba (extra ``fast``) steps 1 and 3 run in a compiled kernel
(:mod:`spectrocolor.upsampling.compiled`) that blends straight into the output.

Every answer of 1., 3. and 4. is checked here on its colour before it is called exact.
:data:`PATHS` names the path each query took (:attr:`spectrocolor.upsampling.Upsampled.path`).

References
----------
C. van Trigt, "Smoothest reflectance functions. I. Definition and main results", J. Opt. Soc.
Am. A 7, 1891–1904 (1990) (the solver of path 3).
"""

from __future__ import annotations

import weakref
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from .table import UpsamplingTable, tetrahedron_corners

if TYPE_CHECKING:
    from ..recovery.inputs import Setup

__all__ = ["PATHS", "EXACT_TOLERANCE"]

#: How each query was answered (``Upsampled.path``, uint8): 0 blend of exact nodes by the grid
#: weights; 1 blend by the actual colours of the nodes of a cell with moved nodes (exact); 2 a
#: certified exact solve (exact); 3 outside the object-colour solid: the table's blend, not
#: exact; 4 outside the cube: moved by the out-of-range strategy, not exact; 5 inside the
#: solid but no certified answer (not exact; not seen in the tests).
PATHS = {0: "exact nodes", 1: "actual node colours", 2: "certified solve",
         3: "outside the object-colour solid", 4: "outside the cube, moved", 5: "not settled"}
EXACT_NODES, ACTUAL, SOLVED, OUTSIDE_SOLID, OUTSIDE_CUBE, UNSETTLED = range(6)

#: Relative colour error accepted for paths 1 and 2: ``max|ρ @ W − q| ≤ EXACT_TOLERANCE ·
#: max|q|``. Path 1's error is the rounding of ``β`` (about cond(edge matrix) · ε, below 1e-11
#: for the worst tetrahedron of the Rec. 2020 table at 17 nodes, cond 1.6e5) plus the
#: blend's (four terms) and ``ρ @ W``'s (K terms, ~ K ε = 2e-14 at K = 81); path 2's is the
#: certificate's rounding level. 1e-10 leaves a factor of ten under the 1e-9 that
#: ``exact`` promises.
EXACT_TOLERANCE = 1e-10
#: Barycentric weights down to ``-BARYCENTRIC_SLACK`` count as inside the tetrahedron; they
#: are then clipped to 0, which moves the colour by at most ``4 · BARYCENTRIC_SLACK · max|X|``
#: (far below :data:`EXACT_TOLERANCE`; the colour is checked afterwards all the same).
BARYCENTRIC_SLACK = 1e-13
#: A colour is certainly outside when it is this far (relative gauge) beyond a facet plane:
#: the solver's own boundary tolerance is 1e-12, so nothing it would call inside is refused.
OUTSIDE_MARGIN = 1e-9
#: Edge matrices whose condition number exceeds this are not used for path 1 (nodes moved to
#: nearly the same point): their β would carry more than ~1e-4 relative rounding.
MAX_CONDITION = 1e12


@dataclass(frozen=True)
class _Cells:
    """Per table: the cells with moved nodes and what paths 1 and 2 need about them."""

    row: np.ndarray        # (c³,) intp: row of each cell in the arrays below, -1 if all exact
    near: np.ndarray       # (M, 27) rows of the cell and its 26 neighbours (-1: none or exact)
    nodes: np.ndarray      # (M, 6, 4) flat node indices of each tetrahedron's corners
    origin: np.ndarray     # (M, 6, 3) actual colour of corner 0
    inverse: np.ndarray    # (M, 6, 3, 3) inverse of [X1 − X0, X2 − X0, X3 − X0]; NaN if unusable
    facets: np.ndarray     # (M, F, 3) facet normals / support (the gauge's scaled normals)
    offsets: np.ndarray    # (M, F) scaled normals · centre
    setup: Setup           # the recovery's setup on the table's own weights


_CELLS: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()


def _cells(table: UpsamplingTable) -> _Cells:
    found = _CELLS.get(table)
    if found is None:
        found = _CELLS[table] = _build(table)
    return found


def _build(table: UpsamplingTable) -> _Cells:
    from ..recovery import zonotope
    from ..recovery.inputs import Setup

    n = table.resolution
    c = n - 1
    moved = table.node_status != 0
    # a cell has a moved node if any of its eight corners is moved
    touched = np.zeros((c, c, c), dtype=bool)
    for di in (0, 1):
        for dj in (0, 1):
            for dk in (0, 1):
                touched |= moved[di:di + c, dj:dj + c, dk:dk + c]
    cells = np.argwhere(touched)  # (M, 3)
    row = np.full(c ** 3, -1, dtype=np.intp)
    row[(cells[:, 0] * c + cells[:, 1]) * c + cells[:, 2]] = np.arange(len(cells))
    corners = cells[:, None, None, :] + tetrahedron_corners()  # (M, 6, 4, 3)
    nodes = (corners[..., 0] * n + corners[..., 1]) * n + corners[..., 2]
    X = table.node_XYZ100.reshape(-1, 3)[nodes]  # (M, 6, 4, 3)
    edges = np.stack([X[:, :, 1] - X[:, :, 0], X[:, :, 2] - X[:, :, 0],
                      X[:, :, 3] - X[:, :, 0]], axis=-1)
    inverse = np.full(edges.shape, np.nan)
    if len(cells):
        with np.errstate(all="ignore"):
            cond = np.linalg.cond(edges)
        usable = np.isfinite(cond) & (cond <= MAX_CONDITION)
        inverse[usable] = np.linalg.inv(edges[usable])
    setup = Setup(table.wavelengths_nm, table.weights)
    solid = setup.solid
    scaled = solid.normals / solid.support[:, None]
    # facets where the gauge peaks at the half-step lattice of each cell (shared points once)
    half = (2 * cells[:, None, :] + np.stack(np.meshgrid(*(np.arange(3),) * 3, indexing="ij"),
                                             axis=-1).reshape(-1, 3)).reshape(-1, 3)
    points, where = np.unique(half, axis=0, return_inverse=True)
    if len(points):
        _, _, peak = zonotope.gauge(solid, (points / (2.0 * c)) @ table.matrix.T, cone=False)
        chosen = peak[where.reshape(len(cells), 27)]
    else:
        chosen = np.zeros((0, 27), dtype=np.int64)
    facets = scaled[chosen]
    shifts = np.stack(np.meshgrid(*(np.arange(-1, 2),) * 3, indexing="ij"), axis=-1).reshape(-1, 3)
    around = cells[:, None, :] + shifts                        # (M, 27, 3)
    valid = np.all((around >= 0) & (around < c), axis=-1)
    around = np.clip(around, 0, c - 1)
    near = np.where(valid, row[(around[..., 0] * c + around[..., 1]) * c + around[..., 2]], -1)
    return _Cells(row, near, nodes, X[:, :, 0], inverse, facets, facets @ solid.centre, setup)


@dataclass(frozen=True)
class Settled:
    """What :func:`settle` found for the queries it was given (indices into them).

    Attributes
    ----------
    path : ndarray (m,) uint8
        A code of :data:`PATHS` for each query.
    blended : ndarray (b,) intp
        Queries answered by path 1, with ``nodes`` (b, 4) and ``weights`` (b, 4).
    nodes, weights : ndarray
        The tetrahedron of actual colours holding each and the barycentric weights.
    solved : ndarray (s,) intp
        Queries answered by path 2, with their ``spectra`` (s, K).
    spectra : ndarray (s, K)
    """

    path: np.ndarray
    blended: np.ndarray
    nodes: np.ndarray
    weights: np.ndarray
    solved: np.ndarray
    spectra: np.ndarray


def settle(table: UpsamplingTable, t: np.ndarray, values: np.ndarray | None = None,
           clamp: bool = True, out: np.ndarray | None = None,
           rows: np.ndarray | None = None) -> Settled:
    """Settle queries ``t`` (m, 3), inside the cube, that lie in tetrahedra with moved nodes.

    Parameters
    ----------
    table : UpsamplingTable
        The table.
    t : numpy.ndarray, shape (m, 3)
        Table coordinates in ``[0, 1]^3``, each in a tetrahedron with a moved node.
    values : numpy.ndarray, shape (n³, C), optional
        Node rows to blend for path 1 (default: the node reflectances).
    clamp : bool, default True
        Clamp path 1's blends to [0, 1] (reflectances; its weights are ≥ 0 and sum to 1 within
        rounding, so this moves them by a few ulps at most).
    out : numpy.ndarray, shape (N, C), optional
        Where path 1 writes its blends: row ``rows[i]`` for query ``i``.
    rows : numpy.ndarray of intp, shape (m,), optional
        The rows of ``out`` (default ``0 .. m − 1``).

    Returns
    -------
    Settled
        Each query's path (:data:`PATHS`: 1, 2, 3 or 5) and the answers of paths 1 and 2.

    Examples
    --------
    >>> from spectrocolor.upsampling import upsampling_table
    >>> table = upsampling_table("Rec. 2020", "D65", resolution=3, measure_excess=False)
    >>> got = settle(table, np.array([[0.1, 0.1, 0.9], [0.0, 0.0, 1.0]]))
    >>> [PATHS[int(p)] for p in got.path]
    ['actual node colours', 'outside the object-colour solid']
    """
    m = len(t)
    K = table.wavelengths_nm.size
    values = table.flat_reflectance if values is None else values
    out = np.empty((m, values.shape[1])) if out is None else out
    rows = np.arange(m) if rows is None else rows
    path = np.full(m, UNSETTLED, dtype=np.uint8)
    empty = np.zeros(0, dtype=np.intp)
    if m == 0:
        return Settled(path, empty, np.zeros((0, 4), np.intp), np.zeros((0, 4)), empty,
                       np.zeros((0, K)))
    cells = _cells(table)
    c = table.resolution - 1
    base = np.minimum((t * c).astype(np.intp), c - 1)
    row = cells.row[(base[:, 0] * c + base[:, 1]) * c + base[:, 2]]
    if np.any(row < 0):  # a query in a cell without moved nodes (the grid blend is exact)
        raise ValueError("settle: a query lies in a cell whose nodes are all exact")
    # per row in a fixed order (a BLAS product would round a row differently in another batch)
    M = table.matrix
    q = t[:, :1] * M[:, 0] + t[:, 1:2] * M[:, 1] + t[:, 2:] * M[:, 2]
    scale = np.abs(q).max(axis=1)
    blend = _Blend(table, cells, values, clamp, out, rows, q, scale)
    # path 1: the six tetrahedra of the query's own cell
    blend(row[:, None], np.arange(m))
    path[blend.done] = ACTUAL
    # path 2's gate: a violated facet plane proves the colour outside the solid
    rest = np.flatnonzero(path == UNSETTLED)
    if rest.size:
        gauge = (np.einsum("mfj,mj->mf", cells.facets[row[rest]], q[rest])
                 - cells.offsets[row[rest]]).max(axis=1)
        path[rest[gauge > 1.0 + OUTSIDE_MARGIN]] = OUTSIDE_SOLID
    # path 1 again: the tetrahedra of the 26 neighbouring cells with moved nodes (moved
    # nodes bend tetrahedra of actual colours across cell walls)
    rest = np.flatnonzero(path == UNSETTLED)
    if rest.size:
        blend(cells.near[row[rest]], rest)
        path[blend.done] = ACTUAL
    rest = np.flatnonzero(path == UNSETTLED)
    solved, spectra = empty, np.zeros((0, K))
    if rest.size:
        from ..recovery.smoothest import _solve_unit
        from .table import verify_reflectances

        rho, _, feasible, _, _, certificate = _solve_unit(cells.setup, q[rest])
        ok = (feasible & certificate.converged
              & verify_reflectances(rho, q[rest], table.weights, EXACT_TOLERANCE))
        path[rest[~feasible]] = OUTSIDE_SOLID
        path[rest[ok]] = SOLVED
        solved, spectra = rest[ok], rho[ok]
    blended = np.flatnonzero(path == ACTUAL)
    return Settled(path, blended, blend.nodes[blended], blend.weights[blended], solved, spectra)


class _Blend:
    """Path 1, run over candidate cells and accumulated: ``done``, ``nodes``, ``weights``."""

    def __init__(self, table, cells, values, clamp, out, rows, q, scale):
        self.table, self.cells, self.values, self.clamp = table, cells, values, clamp
        self.out, self.rows, self.q, self.scale = out, rows, q, scale
        m = len(q)
        self.nodes = np.zeros((m, 4), dtype=np.intp)
        self.weights = np.zeros((m, 4))
        self.done = np.zeros(0, dtype=np.intp)

    def __call__(self, candidates: np.ndarray, which: np.ndarray) -> None:
        from .compiled import kernels, run_actual

        cells = self.cells
        found_kernels = kernels()
        if found_kernels is not None:
            found, nodes, weights = run_actual(
                found_kernels, np.ascontiguousarray(self.q[which]), self.scale[which],
                np.ascontiguousarray(candidates, dtype=np.intp), cells.origin, cells.inverse,
                cells.nodes, np.ascontiguousarray(self.table.node_XYZ100.reshape(-1, 3)),
                BARYCENTRIC_SLACK, EXACT_TOLERANCE, np.ascontiguousarray(self.values, dtype=np.float64),
                self.clamp, self.rows[which], self.out)
            got = np.flatnonzero(found)
            nodes, weights = nodes[got], weights[got]
        else:
            got, nodes, weights = _actual(self.table, cells, self.q[which], self.scale[which],
                                          candidates)
            v = self.values
            blend = v[nodes[:, 0]] * weights[:, :1]  # the kernel's order
            blend += v[nodes[:, 1]] * weights[:, 1:2]
            blend += v[nodes[:, 2]] * weights[:, 2:3]
            blend += v[nodes[:, 3]] * weights[:, 3:]
            if self.clamp:
                np.clip(blend, 0.0, 1.0, out=blend)
            self.out[self.rows[which[got]]] = blend
        self.nodes[which[got]], self.weights[which[got]] = nodes, weights
        self.done = which[got]


def _actual(table, cells: _Cells, q, scale, rows):
    """Path 1 in NumPy for queries ``q`` (w, 3) over the tetrahedra of the cells ``rows``
    (w, R) (-1: none): the indices of the queries settled, the nodes and the weights of the
    first tetrahedron of actual colours that holds each."""
    R = rows.shape[1]
    usable = rows >= 0
    safe = np.where(usable, rows, 0)
    # the operations of the compiled kernel (numba_kernels._actual_one), in its order
    d = q[:, None, None, :] - cells.origin[safe]                     # (w, R, 6, 3)
    inv = cells.inverse[safe]                                        # (w, R, 6, 3, 3)
    with np.errstate(invalid="ignore"):
        s = (inv[..., 0] * d[..., :1] + inv[..., 1] * d[..., 1:2]) + inv[..., 2] * d[..., 2:]
        beta = np.concatenate([1.0 - ((s[..., :1] + s[..., 1:2]) + s[..., 2:]), s], axis=-1)
        fits = np.all(beta >= -BARYCENTRIC_SLACK, axis=-1) & usable[..., None]  # NaN fails
    fits = fits.reshape(len(q), R * 6)
    has = np.flatnonzero(fits.any(axis=1))
    first = np.argmax(fits[has], axis=1)
    r, p = first // 6, first % 6
    nodes = cells.nodes[safe[has, r], p]                              # (b, 4)
    weights = np.maximum(beta[has, r, p], 0.0)
    X = table.node_XYZ100.reshape(-1, 3)[nodes]
    colour = ((weights[:, :1] * X[:, 0] + weights[:, 1:2] * X[:, 1]) + weights[:, 2:3] * X[:, 2]
              + weights[:, 3:] * X[:, 3])
    error = np.abs(colour - q[has]).max(axis=1)
    good = error <= EXACT_TOLERANCE * scale[has]
    return has[good], nodes[good], weights[good]
