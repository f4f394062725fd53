"""Batched exact solver for the discrete smoothest-reflectance quadratic programme.

The programme, for each colour ``b`` (m,), is

    minimise  J(rho) = sum_k (rho[k+1] - rho[k])**2 / h      (free ends)
    subject to  W.T @ rho = b,  lower <= rho <= upper

with ``W`` (K, m) the tristimulus weights (m = 3; m = 6 for a metamer that matches
under two illuminants). ``J`` is the exact integral of the squared
derivative of the piecewise-linear interpolant of ``rho``; its Hessian ``Q = 2 D.T D / h``
is the tridiagonal Laplacian of a path, which is singular only on constants, and constants
are not in the null space of ``W.T`` (every weight column is non-negative and non-zero), so
the programme is strictly convex on its feasible set.

Bounded problems are solved by the primal-dual active-set method (a semismooth Newton
method on the KKT conditions), which both adds and releases bounds. Each iteration solves,
for every colour at once, one tridiagonal system of size K with four right-hand sides
(LAPACK ``gtsv`` on the block-diagonal system of the whole batch) and an m x m system.
Colours that do not settle (rare, and only very near the boundary of the solid: cycling
is possible when equality constraints are present, and the reduced systems become
ill-conditioned) are restarted from the active set predicted by a batched interior-point
method (:mod:`.interior_point`), and any still unsettled are finished one by one by an exact,
dense primal active-set method started from a feasible point (:mod:`.dense_active_set`).
Both the batched reduced solve and the dense one end with iterative refinement: near the
boundary the free weights are nearly dependent, and without it ``W.T rho = b`` can miss
rounding level by orders of magnitude.

References
----------
M. Hintermüller, K. Ito, K. Kunisch, "The primal-dual active set strategy as a semismooth
Newton method", SIAM J. Optim. 13, 865-888 (2002).
J. Nocedal, S. J. Wright, *Numerical Optimization*, 2nd ed., Springer (2006), Alg. 16.3.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.linalg import lapack

from ..errors import ColorimetryError
from . import certificate, compiled
from .dense_active_set import _feasible_start, polish, primal_active_set
from .dense_active_set import _vertex_start as _vertex_start  # .face and .smoothest call qp._vertex_start
from .interior_point import _interior_point
from .pinned_kkt import PinnedKKT, _pinned_kkt
from .tolerances import REFINE_STEPS as _REFINE_STEPS

_MAX_PDAS_ITER = 60
#: Values of :attr:`Solution.method`: how each colour was solved.
METHODS = ("unconstrained", "active set", "active set restarted from interior point",
           "dense primal active set")
#: Colours per block in :func:`solve_unconstrained` (its arrays then stay in cache).
_BLOCK = 2048


@dataclass(frozen=True)
class Problem:
    """The fixed part of the programme: weights, step and the unconstrained solution map.

    Attributes
    ----------
    W : ndarray (K, m)
        Tristimulus weights, ``XYZ100 = rho @ W``.
    step_nm : float
        Grid step ``h`` in nm.
    unconstrained : ndarray (m, K)
        ``rho = b @ unconstrained`` solves the programme without bounds.
    multipliers : ndarray (m, m)
        ``mu = b @ multipliers`` are its Lagrange multipliers.
    kkt_inverse : ndarray (K + m, K + m)
        Inverse of the KKT matrix ``[[Q, -W], [W.T, 0]]`` (for iterative refinement).
    pinned : PinnedKKT or None
        The same KKT system solved in O(K) (the compiled refinement; see :class:`PinnedKKT`).
    basis : ClosedFormBasis or None
        The closed form in a basis where its terms rarely cancel (the compiled closed form).
    """

    W: np.ndarray
    step_nm: float
    unconstrained: np.ndarray
    multipliers: np.ndarray
    kkt_inverse: np.ndarray
    pinned: PinnedKKT | None = None
    basis: ClosedFormBasis | None = None

    @property
    def size(self) -> int:
        return self.W.shape[0]

    def hessian_bands(self) -> tuple[np.ndarray, np.ndarray]:
        """Diagonal (K,) and off-diagonal (K-1,) of ``Q`` (so that ``J = rho Q rho / 2``)."""
        K = self.size
        diag = np.full(K, 4.0 / self.step_nm)
        diag[0] = diag[-1] = 2.0 / self.step_nm
        return diag, np.full(K - 1, -2.0 / self.step_nm)

    def hessian_dense(self) -> np.ndarray:
        diag, off = self.hessian_bands()
        return np.diag(diag) + np.diag(off, 1) + np.diag(off, -1)

    def objective(self, rho: np.ndarray) -> np.ndarray:
        """``J(rho) = sum (diff rho)^2 / h`` for ``rho`` (..., K)."""
        found = compiled.kernels()
        if found is not None and rho.ndim == 2:
            return compiled.roughness(found, rho, self.step_nm)
        return np.sum(np.diff(rho, axis=-1) ** 2, axis=-1) / self.step_nm

    def hess_times(self, rho: np.ndarray) -> np.ndarray:
        """``Q @ rho`` along the last axis."""
        return certificate.hess_times(rho, self.step_nm)


def make_problem(W: np.ndarray, step_nm: float) -> Problem:
    """Build the programme for weights ``W`` (K, m) and step ``step_nm``; solve its KKT map."""
    W = np.ascontiguousarray(W, dtype=np.float64)
    K = W.shape[0]
    m = W.shape[1]
    sv = np.linalg.svd(W, compute_uv=False)
    rank = int(np.count_nonzero(sv > 1e-10 * sv[0])) if sv[0] > 0 else 0
    if rank < m:
        raise ColorimetryError(
            f"weights: the {m} tristimulus weight functions on this grid are linearly dependent "
            f"(rank {rank} < {m}), so the colour does not determine {m} independent "
            "constraints; this happens when the illuminant has power in fewer than "
            f"{m} wavelength bands (or is zero almost everywhere); use an illuminant with "
            "power across the spectrum")
    prob = Problem(W, float(step_nm), np.empty((0, 0)), np.empty((0, 0)), np.empty((0, 0)))
    kkt = np.zeros((K + m, K + m))
    kkt[:K, :K] = prob.hessian_dense()
    kkt[:K, K:] = -W
    kkt[K:, :K] = W.T
    inverse = np.linalg.inv(kkt)
    solution = _refined_solutions(kkt, inverse, np.eye(m))  # [ρ; μ] for b = e_j
    unconstrained = np.ascontiguousarray(solution[:K].T)  # rows: response to b = e_j
    multipliers = np.ascontiguousarray(solution[K:].T)
    basis = _block_basis(W, kkt, inverse)
    for a in (inverse, unconstrained, multipliers, *vars(basis).values()):
        a.setflags(write=False)
    prob = Problem(W, float(step_nm), unconstrained, multipliers, inverse)
    return Problem(W, float(step_nm), unconstrained, multipliers, inverse, _pinned_kkt(prob),
                   basis)


def _refined_solutions(kkt, inverse, colours):
    """``[ρ; μ]`` (K + m, n) solving the KKT system for the colours (n, m), refined with
    residuals in extended precision: the explicit inverse is only normwise accurate, and its
    error, not the rounding of the product, is what keeps a closed form off the certificate's
    rounding level."""
    K = kkt.shape[0] - colours.shape[1]
    exact = np.zeros((kkt.shape[0], len(colours)), dtype=np.longdouble)
    exact[K:] = colours.T
    solution = inverse @ exact.astype(float)
    kkt_long = kkt.astype(np.longdouble)
    for _ in range(_REFINE_STEPS):
        residual = exact - kkt_long @ solution.astype(np.longdouble)
        solution = solution + inverse @ residual.astype(float)
    return solution


@dataclass(frozen=True)
class ClosedFormBasis:
    """The closed form in a basis of block colours: ``ρ = (b @ inverse) @ solutions``.

    ``b @ U`` sums three terms per sample whose signs differ for most colours (the rows of
    ``U`` are the solutions for ``X``, ``Y`` and ``Z`` alone, which no reflectance produces),
    and the cancellation leaves about one colour in ten off the certificate's rounding level.
    In the basis of the colours of three block reflectances — 1 on the first quarter of the
    grid, on the next 30 % and on the rest (short, middle and long wavelengths) — real colours
    have mostly positive coefficients and the basis solutions are smooth, so the terms rarely
    cancel: the fraction of sRGB-cube colours that need a refinement step falls from 9 % to
    2 % at 10 nm (17 % to 4 % at 5 nm). With ``m ≠ 3`` (metamers) the basis is the identity.

    Attributes
    ----------
    inverse : ndarray (m, m)
        Coefficients ``c = b @ inverse`` of a colour in the basis colours.
    solutions : ndarray (m, K)
        The unconstrained minimisers for the basis colours (reflectance factors).
    multipliers : ndarray (m, m)
        Their multipliers.
    """

    inverse: np.ndarray
    solutions: np.ndarray
    multipliers: np.ndarray


def _block_basis(W, kkt, inverse) -> ClosedFormBasis:
    K, m = W.shape
    if m == 3:
        index = np.arange(K) / max(K - 1, 1)
        blocks = np.stack([index <= 0.25, (index > 0.25) & (index <= 0.55), index > 0.55])
        colours = blocks.astype(float) @ W
        if np.linalg.cond(colours) > 1e6:  # an illuminant dark in a band
            colours = np.eye(m)
    else:
        colours = np.eye(m)
    solution = _refined_solutions(kkt, inverse, colours)
    return ClosedFormBasis(np.linalg.inv(colours), np.ascontiguousarray(solution[:K].T),
                           np.ascontiguousarray(solution[K:].T))


#: Closed-form values this far beyond a bound are outside it whatever the refinement does (it
#: moves them by a few roundings): :func:`solve_unconstrained` leaves such colours unrefined.
WITHIN_MARGIN = 1e-9


def solve_unconstrained(prob: Problem, b: np.ndarray, within=None) -> tuple[np.ndarray, np.ndarray]:
    """The minimiser without bounds and its multipliers for colours ``b`` (N, m).

    The closed form ``b @ unconstrained`` loses accuracy to cancellation among the terms of
    the product; iterative refinement (one step of the KKT solve, compiled: the O(K)
    :class:`PinnedKKT`, else the inverse KKT matrix) brings it to the certificate's rounding
    level. With ``within = (lower, upper)``, colours whose closed form leaves
    ``[lower, upper]`` by more than :data:`WITHIN_MARGIN` are returned unrefined: for the
    bounded programme their closed form only says which bounds to start from.
    """
    lower, upper = (-np.inf, np.inf) if within is None else within
    found = compiled.kernels()
    if found is not None and prob.basis is not None:
        rho, mu, _, _ = compiled.closed_form(found, prob, b, _REFINE_STEPS,
                                             lower - WITHIN_MARGIN, upper + WITHIN_MARGIN)
        return rho, mu
    N, K = len(b), prob.size
    rho = np.empty((N, K))
    mu = np.empty((N, prob.W.shape[1]))
    for start in range(0, N, _BLOCK):
        part = slice(start, start + _BLOCK)
        rho[part], mu[part] = b[part] @ prob.unconstrained, b[part] @ prob.multipliers
        inside = np.flatnonzero(np.all((rho[part] >= lower - WITHIN_MARGIN)
                                       & (rho[part] <= upper + WITHIN_MARGIN), axis=1)) + start
        rho[inside], mu[inside] = refine_unconstrained(prob, b[inside], rho[inside], mu[inside])
    return rho, mu


def solve_unconstrained_certified(prob: Problem, b: np.ndarray):
    """:func:`solve_unconstrained` with each result's certificate and roughness: rho, mu,
    Certificate, ``Σ (Δρ)² / h``.

    Compiled, the certificate's measures and the roughness come from the same pass over each
    colour that forms and refines it; otherwise :func:`.certificate.certify` and
    :meth:`Problem.objective` measure the results afterwards.
    """
    settled = np.ones(len(b), dtype=bool)
    found = compiled.kernels()
    if found is not None and prob.basis is not None:
        rho, mu, measures, roughness = compiled.closed_form(found, prob, b, _REFINE_STEPS)
        return rho, mu, certificate.from_measures(measures, settled), roughness
    rho, mu = solve_unconstrained(prob, b)
    with np.errstate(over="ignore"):
        roughness = prob.objective(rho)
    return (rho, mu, certificate.certify(prob.W, prob.step_nm, b, rho, mu, None, None, settled),
            roughness)


def refine_unconstrained(prob: Problem, b, rho, mu):
    """One step of iterative refinement of unconstrained solutions (rho, mu) for colours b."""
    residuals = np.concatenate([mu @ prob.W.T - prob.hess_times(rho), b - rho @ prob.W], axis=1)
    correction = residuals @ prob.kkt_inverse.T
    K = prob.size
    return rho + correction[:, :K], mu + correction[:, K:]


@dataclass
class Solution:
    """Per-colour results of the bounded solve (arrays with the batch as first axis)."""

    rho: np.ndarray  # (N, K)
    mu: np.ndarray  # (N, m) multipliers of W.T rho = b  (Q rho - W mu - lam = 0)
    lam: np.ndarray  # (N, K) bound multipliers: > 0 at lower, < 0 at upper bound
    iterations: np.ndarray  # (N,) int
    converged: np.ndarray  # (N,) bool
    method: np.ndarray  # (N,) int, index into METHODS


def _reduced_solve(prob: Problem, b, lower_active, upper_active, lower, upper):
    """Solve the equality-constrained problem with the given bounds fixed.

    Every colour must have at least one active bound (so that the modified tridiagonal
    matrix is non-singular). Returns rho (N, K), mu (N, m), ok (N,) bool (False where the
    m x m reduced matrix is singular, i.e. the free part cannot reproduce ``b``).
    """
    N, K = lower_active.shape
    m = prob.W.shape[1]
    active = lower_active | upper_active
    free = (~active).astype(float)
    diag_q, off_q = prob.hessian_bands()
    d = np.where(active, 1.0, diag_q).ravel()
    # off-diagonals of the stacked block-diagonal system; the link from the last sample
    # of one colour to the first of the next is zero (it decouples consecutive colours)
    off = np.zeros((N, K))
    off[:, :-1] = off_q[0]
    du = (off * free).ravel()[:-1]
    dl = (off[:, :-1] * free[:, 1:])
    dl = np.concatenate([dl, np.zeros((N, 1))], axis=1).ravel()[:-1]
    factors = lapack.dgttrf(dl, d, du)
    if factors[-1] != 0:  # pragma: no cover - cannot happen with at least one active bound
        raise np.linalg.LinAlgError(f"tridiagonal factorisation failed (info={factors[-1]})")
    factors = factors[:-1]
    # right-hand sides in Fortran order, as LAPACK wants them (no hidden copy)
    rhs = np.empty((1 + m, N * K)).T
    rhs[:, 0] = (np.where(lower_active, lower, 0.0) + np.where(upper_active, upper, 0.0)).ravel()
    for j in range(m):
        rhs[:, 1 + j] = (free * prob.W[:, j]).ravel()
    x, _ = lapack.dgttrs(*factors, rhs, overwrite_b=1)
    p = x[:, 0].reshape(N, K)
    P = [x[:, 1 + i].reshape(N, K) for i in range(m)]
    M = np.stack([Pi @ prob.W for Pi in P], axis=2)  # W.T P  (N, m, m)
    r = b - p @ prob.W
    det = np.linalg.det(M)
    scale = np.einsum("nij,nij->n", M, M) ** (0.5 * m)
    ok = np.abs(det) > 1e-13 * scale
    M[~ok] = np.eye(m)
    mu = np.linalg.solve(M, r[..., None])[..., 0]
    mu[~ok] = 0.0
    rho = p + sum(Pi * mu[:, i, None] for i, Pi in enumerate(P))
    rho = np.where(lower_active, lower, rho)
    rho = np.where(upper_active, upper, rho)
    # Iterative refinement of both KKT equations (stationarity on the free samples and
    # W.T rho = b), with the same factors: near the boundary M is ill-conditioned (the free
    # weights are nearly dependent), and the first solve misses the certificate's rounding
    # level by orders of magnitude. The active values stay exact (P and the correction
    # vanish on them).
    for _ in range(_REFINE_STEPS):
        r = b - rho @ prob.W
        s = (mu @ prob.W.T - prob.hess_times(rho)) * free
        bad = ok & (np.any(np.abs(r) > 0.25 * certificate.primal_tolerance(prob.W, b, rho), axis=1)
                    | np.any(np.abs(s) > 0.25 * certificate.dual_tolerance(
                        prob.W, prob.step_nm, rho, mu), axis=1))
        if not bad.any():
            break
        s[~bad] = 0.0
        y, _ = lapack.dgttrs(*factors, s.reshape(-1, 1))
        y = y.reshape(N, K)[bad]
        dmu = np.linalg.solve(M[bad], (r[bad] - y @ prob.W)[..., None])[..., 0]
        mu[bad] += dmu
        # pivoting can leave rounding-sized values on the identity rows: keep them exact
        rho[bad] += (y + sum(Pi[bad] * dmu[:, i, None] for i, Pi in enumerate(P))) * free[bad]
    return rho, mu, ok


def _pdas(prob, b, lower, upper, lo_act, up_act, max_iter):
    """Primal-dual active-set iterations from the given active sets, for every colour.

    Returns rho, mu, lam, iterations, converged; colours whose reduced system became
    singular or that did not settle within ``max_iter`` are returned unconverged.
    """
    found = compiled.kernels()
    if found is not None:
        return compiled.pdas(found, prob, b, lower, upper, lo_act, up_act, max_iter, _REFINE_STEPS)
    N, K = b.shape[0], prob.size
    rho = np.full((N, K), np.nan)
    mu = np.full((N, prob.W.shape[1]), np.nan)
    lam = np.full((N, K), np.nan)
    iterations = np.zeros(N, dtype=np.int64)
    converged = np.zeros(N, dtype=bool)
    pending = np.arange(N)
    bp = b
    for it in range(1, max_iter + 1):
        if pending.size == 0:
            break
        iterations[pending] = it
        empty = ~(lo_act | up_act).any(axis=1)
        r_i = np.empty((pending.size, K))
        m_i = np.empty((pending.size, prob.W.shape[1]))
        ok = np.ones(pending.size, dtype=bool)
        if empty.any():
            r_i[empty] = bp[empty] @ prob.unconstrained
            m_i[empty] = bp[empty] @ prob.multipliers
        full = ~empty
        if full.any():
            r_i[full], m_i[full], ok[full] = _reduced_solve(
                prob, bp[full], lo_act[full], up_act[full], lower, upper)
        l_i = prob.hess_times(r_i) - m_i @ prob.W.T
        act = lo_act | up_act
        l_i[~act] = 0.0
        # a bound stays while its multiplier has the right sign to within half the
        # certificate's rounding tolerance (so that a degenerate index, bound and multiplier
        # both zero, does not flip forever, and a settled result passes the certificate);
        # any value beyond a bound joins the active set (the bounds must hold exactly)
        tol_l = 0.5 * certificate.dual_tolerance(prob.W, prob.step_nm, r_i, m_i)
        new_lo = np.where(act, lo_act & (l_i > -tol_l), r_i < lower)
        new_up = np.where(act, up_act & (l_i < tol_l), r_i > upper)
        same = np.all(new_lo == lo_act, axis=1) & np.all(new_up == up_act, axis=1)
        done = ok & same
        idx = pending[done]
        rho[idx], mu[idx], lam[idx] = r_i[done], m_i[done], l_i[done]
        converged[idx] = True
        keep = ok & ~same
        pending, bp = pending[keep], bp[keep]
        lo_act, up_act = new_lo[keep], new_up[keep]
    return rho, mu, lam, iterations, converged


def solve_bounded(prob: Problem, b: np.ndarray, lower: float, upper: float) -> Solution:
    """Exact minimiser for each colour ``b`` (N, m) with ``lower <= rho <= upper``.

    ``lower``/``upper`` are scalars (``upper`` may be ``inf``). All colours must be
    feasible (checked by the caller). Active-set iterations start from the bounds violated
    by the unconstrained solution; colours on which they do not settle are restarted from
    the active set predicted by an interior-point method.
    """
    N, K = b.shape[0], prob.size
    found = compiled.kernels()
    if found is not None:  # the kernel forms the closed form and its violated bounds itself
        rho, mu, lam, iterations, converged = compiled.pdas(
            found, prob, b, lower, upper, None, None, _MAX_PDAS_ITER, _REFINE_STEPS)
        method = (iterations > 0).astype(np.int8)
        pending = np.flatnonzero(~converged)
    else:
        rho = b @ prob.unconstrained
        mu = b @ prob.multipliers
        lam = np.zeros((N, K))
        iterations = np.zeros(N, dtype=np.int64)
        converged = np.ones(N, dtype=bool)
        method = np.zeros(N, dtype=np.int8)
        lo_act = rho < lower
        up_act = rho > upper
        pending = np.flatnonzero(lo_act.any(axis=1) | up_act.any(axis=1))
        method[pending] = 1
        if pending.size:
            r, mu_i, lm, it, ok = _pdas(prob, b[pending], lower, upper,
                                     lo_act[pending], up_act[pending], _MAX_PDAS_ITER)
            rho[pending], mu[pending], lam[pending] = r, mu_i, lm
            iterations[pending] = it
            converged[pending] = ok
            pending = pending[~ok]
    method[pending] = 2
    if pending.size:
        rho_ip, ratio, at_upper = _interior_point(prob, b[pending], lower, upper)
        # at least m free indices: fewer cannot reproduce a colour in the interior
        n_eq = prob.W.shape[1]
        third = np.sort(ratio, axis=1)[:, n_eq - 1:n_eq]
        for threshold in (1.0, 1e-2, 1e2, 1e-4, 1e4):
            if pending.size == 0:
                break
            active = ratio > np.maximum(threshold, third)
            lo, up = active & ~at_upper, active & at_upper
            r, mu_i, lm, it, ok = _pdas(prob, b[pending], lower, upper, lo, up, _MAX_PDAS_ITER)
            rho[pending], mu[pending], lam[pending] = r, mu_i, lm
            iterations[pending] += it
            converged[pending] = ok
            pending, ratio, at_upper, third, rho_ip = (
                pending[~ok], ratio[~ok], at_upper[~ok], third[~ok], rho_ip[~ok])
    method[pending] = 3
    Q = prob.hessian_dense() if pending.size else None
    for n, i in enumerate(pending):
        start = _feasible_start(prob, Q, b[i], lower, upper, rho_ip[n], ratio[n], at_upper[n])
        if start is None:  # never seen in testing; reported as not converged, never guessed
            converged[i] = False
            rho[i], mu[i], lam[i] = np.nan, np.nan, np.nan
            continue
        r, mu_i, lm, it, ok = primal_active_set(Q, prob.W, b[i], lower, upper, *start)
        if ok:
            r, mu_i = polish(prob.W, Q, b[i], r, mu_i, lower, upper)
        rho[i], mu[i], lam[i] = r, mu_i, lm
        iterations[i] += it
        converged[i] = ok
    return Solution(rho, mu, lam, iterations, converged, method)
