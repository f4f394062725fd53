"""Exact smoothest reflectance for colours on the boundary of the solid (or of the cone).

A colour on the boundary of the zonotope ``{W.T rho : lower <= rho <= upper}`` lies on a
face. With an outward normal ``n`` of a facet containing it, every feasible ``rho`` has
``rho_k = upper`` where ``n . w_k > 0`` and ``rho_k = lower`` where ``n . w_k < 0``; only the
generators in the facet plane (``n . w_k = 0``) remain free, and their colours form a
zonotope of one dimension less. Repeating on that zonotope while the remaining colour is
on its boundary ends either with nothing free (a vertex: the block spectrum itself) or
with a colour in the relative interior of a face, where the programme restricted to the
free generators and to the face's subspace is strictly feasible and is solved exactly by
the dense primal active-set method. Degenerate faces — many generators in one plane, as
where the 1931 z-bar is exactly zero beyond 650 nm — are handled like any other.

Multipliers for the whole programme follow from the face's and from one multiple of each
level's normal, chosen (innermost level first) so that every bound fixed at that level has a
correctly signed multiplier; together they certify the optimum.
"""

from __future__ import annotations

import numpy as np

from . import dense_active_set, qp, zonotope
from .certificate import dual_tolerance

#: A generator is in a facet plane when ``|n . w| <= PLANE_TOLERANCE * |w|``.
PLANE_TOLERANCE = 1e-10
#: A colour is on a facet when its distance to the facet's plane is at most this times the
#: colour's largest component (relative to the colour: tiny colours near black need it).
FACET_TOLERANCE = 1e-13


def _normals(G: np.ndarray) -> np.ndarray:
    """Candidate facet normals (both orientations) of the zonotope of generators G (n, r)."""
    r = G.shape[1]
    if r == 1:
        n = np.ones((1, 1))
    elif r == 2:
        n = np.stack([-G[:, 1], G[:, 0]], axis=1)
    else:
        i, j = np.triu_indices(len(G), 1)
        unit, norm = zonotope.unit_cross(G[i], G[j])
        n = unit * norm[:, None]
    norm = np.linalg.norm(n, axis=1)
    n = n[norm > 1e-12 * max(norm.max(initial=0.0), np.finfo(float).tiny)]
    n = n / np.linalg.norm(n, axis=1, keepdims=True)
    return np.concatenate([n, -n])


def _known_facets(facets, c, tol, choice):
    """:func:`_touching_facet` on the precomputed facets of the whole solid or cone
    (:class:`.zonotope.Facets`, from the setup's cache): the first level of a face solution
    then costs one product with the K (K − 1) normals instead of their projections on all K
    generators (K³ products: seconds at 1 nm)."""
    slack = facets.support - (c - facets.centre) @ facets.normals.T
    near = np.flatnonzero(slack <= tol)
    if near.size == 0:
        return None
    near = near[np.argsort(slack[near], kind="stable")[:4 * (choice + 1)]]
    distinct: list[np.ndarray] = []
    for k in near:
        if all(abs(float(facets.normals[k] @ d)) < 1.0 - 1e-9 for d in distinct):
            distinct.append(facets.normals[k])
        if len(distinct) > choice:
            return distinct[choice]
    return None


def _touching_facet(G, c, lower, upper, tol, choice=0):
    """The outward normal of a facet of the zonotope (or cone) of G containing c, or None.

    With ``choice = j``, the facet with the j-th smallest slack among the distinct facets within
    ``tol`` of c (a colour on an edge lies on several; rounding can rank one that does not
    quite hold it first). The candidate normals (n² of them) are projected on the generators
    in blocks, so memory stays O(n²) rather than O(n³)."""
    normals = _normals(G)
    in_plane = PLANE_TOLERANCE * np.linalg.norm(G, axis=1)
    slacks, found = [], []
    rows = max(1, zonotope.BLOCK // max(len(G), 1))
    for i in range(0, len(normals), rows):
        n = normals[i:i + rows]
        p = n @ G.T  # (block, generators)
        if np.isfinite(upper):
            support = np.where(p > 0, upper * p, lower * p).sum(axis=1)
        else:  # the cone: only normals with no generator on their positive side bound it
            ok = np.all(p <= in_plane, axis=1)
            n, support = n[ok], lower * p[ok].sum(axis=1)
        if len(n) == 0:
            continue
        slack = support - n @ c
        near = np.flatnonzero(slack <= tol)
        near = near[np.argsort(slack[near], kind="stable")[:4 * (choice + 1)]]
        slacks.append(slack[near])
        found.append(n[near])
    if not slacks or not sum(len(v) for v in slacks):
        return None
    slack, n = np.concatenate(slacks), np.concatenate(found)
    distinct: list[np.ndarray] = []
    for k in np.argsort(slack, kind="stable"):
        if all(abs(float(n[k] @ d)) < 1.0 - 1e-9 for d in distinct):
            distinct.append(n[k])
        if len(distinct) > choice:
            return distinct[choice]
    return None


def _strictly_feasible(W, b, lower, upper, rho, free):
    """A feasible point with the free values as far inside their bounds as possible (or, with
    as many free values as constraints, the only one)."""
    from scipy.optimize import linprog

    F = np.flatnonzero(free)
    target = b - np.delete(rho, F) @ np.delete(W, F, axis=0)
    if F.size == W.shape[1]:  # as many free values as constraints: they are determined
        x = np.linalg.solve(W[F].T, target)
        slack = 1e-12 * np.abs(x).max()  # rounding: a value at a bound may come out as -1e-30
        if np.any(x < lower - slack) or np.any(x > upper + slack):
            return None
        out = rho.copy()
        out[F] = np.clip(x, lower, upper)
        return out
    cap = 0.5 * (upper - lower) if np.isfinite(upper) else 1.0
    n = F.size
    # variables: x (n), s; maximise s with x - s >= lower, x + s <= upper, W.T x = target
    a_ub = np.zeros((2 * n, n + 1))
    a_ub[:n, :n], a_ub[:n, n] = -np.eye(n), 1.0
    a_ub[n:, :n], a_ub[n:, n] = np.eye(n), 1.0
    b_ub = np.concatenate([np.full(n, -lower), np.full(n, upper if np.isfinite(upper) else 1e300)])
    keep = np.r_[np.ones(n, dtype=bool), np.full(n, np.isfinite(upper))]
    a_eq = np.concatenate([W[F].T, np.zeros((W.shape[1], 1))], axis=1)
    cost = np.zeros(n + 1)
    cost[-1] = -1.0
    res = linprog(cost, A_ub=a_ub[keep], b_ub=b_ub[keep], A_eq=a_eq, b_eq=target,
                  bounds=[(None, None)] * n + [(0.0, cap)], method="highs",
                  options={"primal_feasibility_tolerance": 1e-10})
    if res.status != 0:
        return None
    x = res.x[:n]
    x += np.linalg.lstsq(W[F].T, target - x @ W[F], rcond=None)[0]
    if np.any(x <= lower) or np.any(x >= upper):
        return None
    out = rho.copy()
    out[F] = x
    return out


def _vertex_on_face(W, b, lower, upper, rho, free):
    """A feasible point of the face with the free values from a simplex vertex (HiGHS), made
    exact: values the vertex left at a bound join the working set, the others absorb the
    rounding. Returns (rho, working set) or (None, None)."""
    F = np.flatnonzero(free)
    target = b - np.delete(rho, F) @ np.delete(W, F, axis=0)
    got = qp._vertex_start(W[F], target, lower, upper)
    if got is None:
        return None, None
    out, working = rho.copy(), ~free
    out[F] = got[0]
    working[F] = got[1]
    return out, working


def _deepest_multipliers(W, Q, rho, mu, basis, fixed, lower):
    """Multipliers whose bound multipliers have the right signs with the widest margin.

    ``basis`` (m, r) spans the free generators, whose stationarity fixes ``μ`` there; the
    other components ``z`` (normals of the faces) are free. The normals were built level by
    level, and with nearly parallel generators their rounding can flip the sign of a small
    multiplier of an inner level once an outer level's large multiple is added. A linear
    programme instead maximises the smallest margin ``σ_k λ_k / |w_k|`` over a box ten times
    the size of the level-by-level solution (``σ = +1`` at ``lower``, ``-1`` at ``upper``);
    the certificate then checks the result (a margin of zero is a degenerate bound whose
    multiplier vanishes, rounding decides its sign). Returns None where the LP fails.
    """
    from scipy.optimize import linprog

    m = W.shape[1]
    r = basis.shape[1]
    free = np.flatnonzero(~fixed)
    if free.size >= r > 0:
        # the normals of the face, from the free generators themselves: orthogonal to them to
        # rounding (a cross product of two nearly parallel generators is not)
        N = np.linalg.svd(W[free])[2][r:].T
    else:
        N = np.linalg.svd(basis.T)[2][r:].T if r else np.eye(m)
    if N.shape[1] == 0:
        return mu
    base = mu - N @ (N.T @ mu)
    idx = np.flatnonzero(fixed)
    sigma = np.where(rho[idx] == lower, 1.0, -1.0)
    c = Q[idx] @ rho - W[idx] @ base
    a = W[idx] @ N
    size = np.linalg.norm(W[idx], axis=1)
    box = 10.0 * max(float(np.abs(mu).max()), 1.0)
    d = N.shape[1]
    cost = np.zeros(d + 1)
    cost[-1] = -1.0
    A = np.concatenate([sigma[:, None] * a, size[:, None]], axis=1)
    res = linprog(cost, A_ub=A, b_ub=sigma * c, bounds=[(-box, box)] * d + [(None, box)],
                  method="highs")
    if res.status != 0:
        return None
    return base + N @ res.x[:d]


def face_solution(W: np.ndarray, Q: np.ndarray, b: np.ndarray, lower: float, upper: float,
                  facet_tolerance: float = FACET_TOLERANCE, choice: int = 0,
                  facets: zonotope.Facets | None = None):
    """The smoothest ``rho`` with ``W.T rho = b`` and bounds, for a colour b on the boundary.

    ``facet_tolerance`` (relative, see :data:`FACET_TOLERANCE`) decides which facets the
    colour is on; ``choice`` picks, at the first level, the facet with that rank among those
    holding the colour (:func:`_touching_facet`); the caller checks the result. ``facets``,
    the precomputed facets of the whole solid (or cone) for these ``W`` and bounds, serve the
    first level (:func:`_known_facets`) in place of the candidates formed here.

    Returns rho (K,), mu (m,), lam (K,) and whether it was solved; NaN where not.
    """
    K, m = W.shape
    on_facet = facet_tolerance * max(np.abs(b).max(), np.finfo(float).tiny)
    rho = np.zeros(K)
    free = np.ones(K, dtype=bool)
    basis = np.eye(m)  # orthonormal columns: the subspace that the free generators span
    levels: list[tuple[np.ndarray, np.ndarray]] = []  # (normal in colour space, indices fixed at that level)
    failed = (np.full(K, np.nan), np.full(m, np.nan), np.full(K, np.nan), False)
    while free.any() and basis.shape[1] > 0:
        F = np.flatnonzero(free)
        G = W[F] @ basis
        _, sv, vt = np.linalg.svd(G, full_matrices=False)
        rank = int(np.count_nonzero(sv > len(F) * 64 * np.finfo(float).eps * sv[0])) if sv[0] > 0 else 0
        basis = basis @ vt[:rank].T
        if rank == 0:
            break
        G = W[F] @ basis
        c = (b - rho @ W) @ basis
        if facets is not None and not levels and rank == m:
            n = _known_facets(facets, b, on_facet, choice)  # basis is the identity here
        else:
            n = _touching_facet(G, c, lower, upper, on_facet, choice if not levels else 0)
        if n is None:
            break
        p = G @ n
        tol = PLANE_TOLERANCE * np.linalg.norm(G, axis=1)
        up, lo = p > tol, p < -tol
        rho[F[up]] = upper
        rho[F[lo]] = lower
        free[F[up | lo]] = False
        levels.append((basis @ n, F[up | lo]))
        # the remaining generators span the facet's plane: drop the normal from the basis
        null = np.linalg.svd(n[None, :])[2][1:].T
        basis = basis @ null
    if free.any() and basis.shape[1] == 0:
        # generators that no colour constrains (zero weights: an illuminant without power
        # there): only smoothness fixes them, ρ interpolates its fixed neighbours linearly
        # (a convex combination of bound values, so within the bounds)
        F, A = np.flatnonzero(free), np.flatnonzero(~free)
        rho[F] = np.linalg.solve(Q[np.ix_(F, F)], -Q[np.ix_(F, A)] @ rho[A])
        rho[F] = np.clip(rho[F], lower, upper)
        mu = np.zeros(m)
    elif free.any():
        Wb = W @ basis
        start, working = _strictly_feasible(Wb, b @ basis, lower, upper, rho, free), ~free
        if start is None:
            # the colour is on the boundary of the face's zonotope to rounding (below the
            # facet test's reach): start from a vertex of it, its bounds in the working set
            start, working = _vertex_on_face(Wb, b @ basis, lower, upper, rho, free)
        if start is None:
            return failed
        rho, mu_b, _, _, ok = qp.primal_active_set(Q, Wb, b @ basis, lower, upper, start,
                                                    working, pinned=~free)
        if not ok:
            return failed
        mu = basis @ mu_b
    else:
        mu = np.zeros(m)
    # a multiple of each level's normal makes the bounds fixed at that level correctly
    # signed; twice the smallest such multiple leaves each level's tightest bound a margin
    for normal, idx in reversed(levels):
        g = Q[idx] @ rho - W[idx] @ mu
        w_n = W[idx] @ normal
        mu = mu + normal * 2.0 * max(0.0, float(np.max(g / w_n)))
    if levels:
        mu = _deepest_multipliers(W, Q, rho, mu, basis, ~free, lower)
        if mu is None:
            return failed
    rho, mu = qp.polish(W, Q, b, rho, mu, lower, upper)
    lam = Q @ rho - W @ mu
    lam[free & (rho > lower) & (rho < upper)] = 0.0
    return rho, mu, lam, True


#: A colour component is lifted (:func:`lift_component`) when it is at most this fraction of the
#: colour's largest component: below what a face solution of the whole colour resolves.
LIFT_FRACTION = 1e-10
#: Steps per sample the primal active-set method may take for :func:`zero_component_solution`.
LIFT_STEPS_PER_SAMPLE = 3


def liftable_components(W: np.ndarray, b: np.ndarray, lower: float) -> list[int]:
    """The components ``c`` of ``b`` that :func:`lift_component` can restore: ``b_c`` zero or
    positive and at most ``LIFT_FRACTION`` of ``max |b|``, its weights ``W[:, c]`` non-negative
    with exact zeros somewhere (the 1931 z̄ beyond 650 nm, the 1964 z̄ beyond 559 nm), and the
    lower bound 0. (With ``b_c = 0`` the colour is on the face ``ρ_S = 0`` exactly, and the
    lift only chooses ``μ_c``.)"""
    top = float(np.abs(b).max())
    if lower != 0.0 or top == 0.0:
        return []
    return [c for c in range(W.shape[1])
            if 0.0 <= b[c] <= LIFT_FRACTION * top and np.all(W[:, c] >= 0) and np.any(W[:, c] == 0)]


def zero_component_solution(W: np.ndarray, Q: np.ndarray, b: np.ndarray, c: int, lower: float,
                            upper: float):
    """The smoothest ρ for ``b`` with component ``c`` taken as 0: every sample where
    ``W[:, c] > 0`` held at 0 (the face ``ρ_S = 0``, known here without a facet search), the
    others solved for the remaining components by the primal active-set method from a vertex.
    Returns ``(rho, mu)`` (``mu[c] = 0``) or None where no start or no solution is found."""
    S = W[:, c] > 0
    others = [i for i in range(W.shape[1]) if i != c]
    Wo = W[:, others]
    got = (_pinned_active_set_iterations(Q, Wo, b[others], lower, upper, S)
           or _pinned_from_vertex(Q, Wo, b[others], lower, upper, S))
    if got is None:
        return None
    mu = np.zeros(W.shape[1])
    mu[others] = got[1]
    return got[0], mu


def _pinned_from_vertex(Q, W, b, lower, upper, pinned):
    """The primal active-set method with the ``pinned`` samples held at 0, from a vertex of the
    others: ``(rho, mu)`` or None."""
    start = qp._vertex_start(W[~pinned], b, lower, upper)
    if start is None:
        return None
    rho = np.zeros(len(W))
    rho[~pinned] = start[0]
    working = np.ones(len(W), dtype=bool)
    working[~pinned] = start[1]
    # from a vertex the method frees about one sample a step (a narrow band at 1 nm: 300-430
    # steps for K = 401); one that has not settled in 3 K steps is left to the other routes
    rho, mu, _, _, ok = qp.primal_active_set(Q, W, b, lower, upper, rho, working, pinned=pinned,
                                             max_iter=LIFT_STEPS_PER_SAMPLE * len(W))
    return (rho, mu) if ok else None


#: Primal-dual active-set iterations :func:`_pinned_active_set_iterations` may take.
PINNED_ITERATIONS = 40


def _pinned_active_set_iterations(Q, W, b, lower, upper, pinned):
    """Primal-dual active-set iterations (the rule of :func:`.qp._pdas`, one colour, each step
    a banded KKT solve) with the ``pinned`` samples held at ``lower``: from the bounds the
    unbounded solution violates, usually settled in a few steps where the primal method from a
    vertex frees one sample a step. Returns ``(rho, mu)`` once the sets settle with the values
    within the bounds and every bound's multiplier signed to half the certificate's tolerance,
    or None (the caller goes on from a vertex)."""
    at_lower, at_upper = pinned.copy(), np.zeros(len(Q), dtype=bool)
    tridiagonal = dense_active_set.is_tridiagonal(Q)
    for _ in range(PINNED_ITERATIONS):
        active = at_lower | at_upper
        rho = np.where(at_upper, upper, np.where(at_lower, lower, 0.0))
        sol = dense_active_set.equality_qp(Q, W, b, rho, active, tridiagonal)
        if sol is None:
            return None
        rho, mu = sol
        lam = Q @ rho - W @ mu
        tol = 0.5 * dual_tolerance(W, 2.0 / Q[0, 0], rho, mu)
        new_lower = pinned | np.where(active, at_lower & (lam > -tol), rho < lower)
        new_upper = ~pinned & np.where(active, at_upper & (lam < tol), rho > upper)
        if np.array_equal(new_lower, at_lower) and np.array_equal(new_upper, at_upper):
            return rho, mu
        at_lower, at_upper = new_lower, new_upper
    return None


def lift_component(W: np.ndarray, Q: np.ndarray, b: np.ndarray, c: int, rho0: np.ndarray,
                   mu0: np.ndarray, upper: float):
    """A solution for ``b`` from one for ``b`` with component ``c`` set to 0, or None.

    Such a colour (a narrow red band under the 1964 observer: ``Z = 8e-105`` beside
    ``X = 2``) lies on the face ``ρ_S = 0`` of the samples ``S`` where ``W[:, c] > 0`` to far
    below rounding of its other components, but its ``c`` component is a number like any
    other, and the certificate holds the colour to it relative to its own size. With ``ρ⁰``,
    ``μ⁰`` the certified solution of the zeroed colour (every sample of ``S`` at 0), the
    solution of ``b`` differs only at the scale of ``b_c``: one sample ``j`` of ``S`` leaves
    the bound with ``ρ_j = b_c / W[j, c]``, and the multiplier ``μ_c`` is the largest that
    keeps every other bound of ``S`` correctly signed, ``μ_c = min_k g_k / W[k, c]`` over
    ``k`` in ``S`` with ``g = (Q ρ⁰ − W μ⁰)`` without its ``c`` term; ``j`` attains the minimum,
    so its stationarity holds to the ``b_c``-sized terms left out. Samples outside ``S``
    (``W[:, c] = 0``) do not see ``μ_c``. The caller certifies the result: this is a candidate.
    ``upper`` is the upper bound (1, or ∞ for the cone). Returns ``(rho, mu)`` or None where
    ``ρ⁰`` is not 0 on ``S``.
    """
    S = np.flatnonzero(W[:, c] > 0)
    if S.size == 0 or np.any(rho0[S] != 0.0):
        return None
    others = np.array([i for i in range(W.shape[1]) if i != c])

    def with_largest_mu_c(rho, mu):
        g = (Q[S] @ rho) - W[np.ix_(S, others)] @ mu[others]
        ratio = g / W[S, c]
        j = int(np.argmin(ratio))
        mu = mu.copy()
        mu[c] = ratio[j]
        return mu, j

    # with μ_c chosen every bound of S is signed, so the zeroed colour's certificate measures
    # the free samples alone, and refinement against it can tell a better iterate (on the
    # pinned problem the unsigned bounds of S hid every improvement)
    zeroed = b.copy()
    zeroed[c] = 0.0
    mu, _ = with_largest_mu_c(rho0, mu0)
    rho, mu = qp.polish(W, Q, zeroed, rho0, mu, 0.0, upper)
    mu, j = with_largest_mu_c(rho, mu)
    rho = rho.copy()
    rho[S[j]] = b[c] / W[S[j], c]
    # where b_c is not far below rounding of the rest, the left-out terms are not: the free
    # samples (j among them) are refined against the whole colour
    return qp.polish(W, Q, b, rho, mu, 0.0, upper)


def lifted_candidates(W: np.ndarray, Q: np.ndarray, b: np.ndarray, lower: float, upper: float):
    """For each of :func:`liftable_components`, the candidate ``(rho, mu)`` of
    :func:`zero_component_solution` lifted by :func:`lift_component` (the caller certifies)."""
    for c in liftable_components(W, b, lower):
        base = zero_component_solution(W, Q, b, c, lower, upper)
        lifted = None if base is None else lift_component(W, Q, b, c, base[0], base[1], upper)
        if lifted is not None:
            yield lifted
