"""Batched exact solver for the discrete smoothest-reflectance quadratic programme.

The programme, for each colour ``b`` (3,), is

    minimise  J(rho) = sum_k (rho[k+1] - rho[k])**2 / h      (free ends)
    subject to  W.T @ rho = b,  lower <= rho <= upper

with ``W`` (K, 3) the tristimulus weights. ``J`` is the exact integral of the squared
derivative of the piecewise-linear interpolant of ``rho``; its Hessian ``Q = 2 D.T D / h``
is the tridiagonal Laplacian of a path, which is singular only on constants, and constants
are not in the null space of ``W.T`` (every weight column is non-negative and non-zero), so
the programme is strictly convex on its feasible set.

Bounded problems are solved by the primal-dual active-set method (a semismooth Newton
method on the KKT conditions), which both adds and releases bounds. Each iteration solves,
for every colour at once, one tridiagonal system of size K with four right-hand sides
(LAPACK ``gtsv`` on the block-diagonal system of the whole batch) and a 3 x 3 system.
Colours that do not settle (rare; cycling is possible when equality constraints are
present) are finished by an exact primal active-set method started from a feasible vertex.

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

_MAX_PDAS_ITER = 30
_TOL = 1e-13


@dataclass(frozen=True)
class Problem:
    """The fixed part of the programme: weights, step and the unconstrained solution map.

    Attributes
    ----------
    W : ndarray (K, 3)
        Tristimulus weights, ``XYZ100 = rho @ W``.
    step_nm : float
        Grid step ``h`` in nm.
    unconstrained : ndarray (3, K)
        ``rho = b @ unconstrained`` solves the programme without bounds.
    multipliers : ndarray (3, 3)
        ``mu = b @ multipliers`` are its Lagrange multipliers.
    """

    W: np.ndarray
    step_nm: float
    unconstrained: np.ndarray
    multipliers: np.ndarray

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
        return np.sum(np.diff(rho, axis=-1) ** 2, axis=-1) / self.step_nm

    def hess_times(self, rho: np.ndarray) -> np.ndarray:
        """``Q @ rho`` along the last axis."""
        d = np.diff(rho, axis=-1) * (2.0 / self.step_nm)
        out = np.zeros_like(rho)
        out[..., :-1] -= d
        out[..., 1:] += d
        return out


def make_problem(W: np.ndarray, step_nm: float) -> Problem:
    """Build the programme for weights ``W`` (K, 3) and step ``step_nm``; solve its KKT map."""
    W = np.ascontiguousarray(W, dtype=np.float64)
    K = W.shape[0]
    prob = Problem(W, float(step_nm), np.empty((3, K)), np.empty((3, 3)))
    kkt = np.zeros((K + 3, K + 3))
    kkt[:K, :K] = prob.hessian_dense()
    kkt[:K, K:] = -W
    kkt[K:, :K] = W.T
    rhs = np.zeros((K + 3, 3))
    rhs[K:] = np.eye(3)
    sol = np.linalg.solve(kkt, rhs)  # columns: response to b = e_j
    unconstrained = np.ascontiguousarray(sol[:K].T)
    multipliers = np.ascontiguousarray(sol[K:].T)
    unconstrained.setflags(write=False)
    multipliers.setflags(write=False)
    return Problem(W, float(step_nm), unconstrained, multipliers)


@dataclass
class Solution:
    """Per-colour results of the bounded solve (arrays with the batch as first axis)."""

    rho: np.ndarray  # (N, K)
    mu: np.ndarray  # (N, 3) multipliers of W.T rho = b  (Q rho - W mu - lam = 0)
    lam: np.ndarray  # (N, K) bound multipliers: > 0 at lower, < 0 at upper bound
    iterations: np.ndarray  # (N,) int
    converged: np.ndarray  # (N,) bool


def _reduced_solve(prob: Problem, b, lower_active, upper_active, lower, upper):
    """Solve the equality-constrained problem with the given bounds fixed.

    Every colour must have at least one active bound (so that the modified tridiagonal
    matrix is non-singular). Returns rho (N, K), mu (N, 3), ok (N,) bool (False where the
    3 x 3 reduced matrix is singular, i.e. the free part cannot reproduce ``b``).
    """
    N, K = lower_active.shape
    active = lower_active | upper_active
    diag_q, off_q = prob.hessian_bands()
    d = np.where(active, 1.0, diag_q)
    du = np.where(active[:, :-1], 0.0, off_q)
    dl = np.where(active[:, 1:], 0.0, off_q)
    # decouple consecutive colours in the stacked block-diagonal system
    du = np.concatenate([du, np.zeros((N, 1))], axis=1).ravel()[:-1]
    dl = np.concatenate([dl, np.zeros((N, 1))], axis=1).ravel()[:-1]
    rhs = np.empty((N, K, 4))
    rhs[..., 0] = np.where(lower_active, lower, 0.0) + np.where(upper_active, upper, 0.0)
    rhs[..., 1:] = np.where(active[..., None], 0.0, prob.W)
    _, _, _, x, info = lapack.dgtsv(dl, d.ravel(), du, rhs.reshape(N * K, 4),
                                    overwrite_dl=1, overwrite_d=1, overwrite_du=1,
                                    overwrite_b=1)
    if info != 0:  # pragma: no cover - cannot happen with at least one active bound
        raise np.linalg.LinAlgError(f"tridiagonal solve failed (info={info})")
    x = x.reshape(N, K, 4)
    p, P = x[..., 0], x[..., 1:]
    M = np.einsum("kj,nki->nji", prob.W, P)  # W.T P  (N, 3, 3)
    r = b - p @ prob.W
    det = np.linalg.det(M)
    scale = np.einsum("nij,nij->n", M, M) ** 1.5
    ok = np.abs(det) > 1e-13 * scale
    M[~ok] = np.eye(3)
    mu = np.linalg.solve(M, r[..., None])[..., 0]
    mu[~ok] = 0.0
    rho = p + np.einsum("nki,ni->nk", P, mu)
    rho = np.where(lower_active, lower, rho)
    rho = np.where(upper_active, upper, rho)
    return rho, mu, ok


def _pdas(prob, b, lower, upper, lo_act, up_act, max_iter):
    """Primal-dual active-set iterations from the given active sets, for every colour.

    Returns rho, mu, lam, iterations, converged; colours whose reduced system became
    singular or that did not settle within ``max_iter`` are returned unconverged.
    """
    N, K = b.shape[0], prob.size
    rho = np.full((N, K), np.nan)
    mu = np.full((N, 3), np.nan)
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
        m_i = np.empty((pending.size, 3))
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
        # rounding-level tolerances keep degenerate indices (bound and multiplier both
        # zero) from flipping forever
        tol_l = _TOL * (1.0 + np.abs(m_i @ prob.W.T).max(axis=1, keepdims=True))
        tol_r = _TOL * (1.0 + max(abs(lower), abs(upper) if np.isfinite(upper) else 0.0))
        new_lo = np.where(act, lo_act & (l_i > -tol_l), r_i < lower - tol_r)
        new_up = np.where(act, up_act & (l_i < tol_l), r_i > upper + tol_r)
        same = np.all(new_lo == lo_act, axis=1) & np.all(new_up == up_act, axis=1)
        done = ok & same
        idx = pending[done]
        rho[idx], mu[idx], lam[idx] = r_i[done], m_i[done], l_i[done]
        converged[idx] = True
        keep = ok & ~same
        pending, bp = pending[keep], bp[keep]
        lo_act, up_act = new_lo[keep], new_up[keep]
    return rho, mu, lam, iterations, converged


def _interior_point(prob, b, lower, upper, iterations=60):
    """Primal-dual interior-point iterations (Mehrotra predictor-corrector), batched.

    Used only to find the active set for colours on which the active-set iterations did
    not settle (typically colours very close to the boundary of the solid). Returns, per
    index, the complementarity ratio ``z / s`` at the nearer bound (large where the bound
    is active) and whether that bound is the upper one.
    """
    N, K = b.shape[0], prob.size
    has_upper = np.isfinite(upper)
    W = prob.W
    diag_q, off_q = prob.hessian_bands()
    scale = np.abs(b).max(axis=1, keepdims=True) / W.sum(axis=0).max() + 1e-3
    if has_upper:
        rho = np.full((N, K), 0.5 * (lower + upper))
    else:
        rho = np.full((N, K), lower) + scale
    z_l = np.ones((N, K))
    z_u = np.ones((N, K)) if has_upper else np.zeros((N, K))
    mu = np.zeros((N, 3))
    m = 2 * K if has_upper else K

    def newton(r_d, r_p, c_l, c_u, s_l, s_u):
        sig = z_l / s_l + (z_u / s_u if has_upper else 0.0)
        h = -r_d + c_l / s_l - (c_u / s_u if has_upper else 0.0)
        d = (diag_q + sig).ravel()
        off = np.concatenate([np.broadcast_to(off_q, (N, K - 1)), np.zeros((N, 1))], axis=1)
        off = off.ravel()[:-1]
        rhs = np.empty((N, K, 4))
        rhs[..., 0] = h
        rhs[..., 1:] = W
        _, _, _, x, _ = lapack.dgtsv(off.copy(), d, off.copy(), rhs.reshape(N * K, 4))
        x = x.reshape(N, K, 4)
        M = np.einsum("kj,nki->nji", W, x[..., 1:])
        M += 1e-14 * np.einsum("nii->n", M)[:, None, None] * np.eye(3)
        dmu = np.linalg.solve(M, (-r_p - x[..., 0] @ W)[..., None])[..., 0]
        drho = x[..., 0] + np.einsum("nki,ni->nk", x[..., 1:], dmu)
        dz_l = (c_l - z_l * drho) / s_l
        dz_u = (c_u + z_u * drho) / s_u if has_upper else np.zeros_like(drho)
        return drho, dmu, dz_l, dz_u

    def step_to_boundary(x, dx):
        with np.errstate(divide="ignore", invalid="ignore"):
            t = np.where(dx < 0, -x / dx, np.inf)
        return np.minimum(1.0, t.min(axis=1))

    # slacks are state variables: recomputing them from rho would lose them to cancellation
    s_l = rho - lower
    s_u = (upper - rho) if has_upper else np.ones_like(rho)
    for _ in range(iterations):
        gap = ((s_l * z_l).sum(axis=1) + ((s_u * z_u).sum(axis=1) if has_upper else 0)) / m
        r_d = prob.hess_times(rho) - mu @ W.T - z_l + z_u
        r_p = rho @ W - b
        # predictor
        a = newton(r_d, r_p, -s_l * z_l, -s_u * z_u, s_l, s_u)
        alpha = step_to_boundary(np.concatenate([s_l, s_u, z_l, z_u], 1),
                                 np.concatenate([a[0], -a[0], a[2], a[3]], 1))
        al = alpha[:, None]
        gap_aff = (((s_l + al * a[0]) * (z_l + al * a[2])).sum(axis=1)
                   + (((s_u - al * a[0]) * (z_u + al * a[3])).sum(axis=1) if has_upper else 0)) / m
        sigma = np.clip((gap_aff / gap) ** 3, 0.0, 1.0)[:, None]
        c_l = sigma * gap[:, None] - s_l * z_l - a[0] * a[2]
        c_u = sigma * gap[:, None] - s_u * z_u + a[0] * a[3]
        drho, dmu, dz_l, dz_u = newton(r_d, r_p, c_l, c_u, s_l, s_u)
        alpha = 0.995 * step_to_boundary(np.concatenate([s_l, s_u, z_l, z_u], 1),
                                         np.concatenate([drho, -drho, dz_l, dz_u], 1))
        al = np.where(gap > 1e-15 * (1.0 + np.abs(mu).max(axis=1)), alpha, 0.0)[:, None]
        rho = rho + al * drho
        s_l = s_l + al * drho
        if has_upper:
            s_u = s_u - al * drho
        mu = mu + al * dmu
        z_l = z_l + al * dz_l
        if has_upper:
            z_u = z_u + al * dz_u
    # complementarity ratio at the nearer bound: large = active, small = free
    at_upper = (s_u < s_l) if has_upper else np.zeros_like(rho, dtype=bool)
    with np.errstate(divide="ignore", invalid="ignore"):
        ratio = np.where(at_upper, z_u / s_u, z_l / s_l)
    return np.nan_to_num(ratio, nan=np.inf), at_upper


def solve_bounded(prob: Problem, b: np.ndarray, lower: float, upper: float) -> Solution:
    """Exact minimiser for each colour ``b`` (N, 3) with ``lower <= rho <= upper``.

    ``lower``/``upper`` are scalars (``upper`` may be ``inf``). All colours must be
    feasible (checked by the caller). Active-set iterations start from the bounds violated
    by the unconstrained solution; colours on which they do not settle are restarted from
    the active set predicted by an interior-point method.
    """
    N, K = b.shape[0], prob.size
    rho = b @ prob.unconstrained
    mu = b @ prob.multipliers
    lam = np.zeros((N, K))
    iterations = np.zeros(N, dtype=np.int64)
    converged = np.ones(N, dtype=bool)
    lo_act = rho < lower
    up_act = rho > upper
    pending = np.flatnonzero(lo_act.any(axis=1) | up_act.any(axis=1))
    if pending.size:
        r, m, lm, it, ok = _pdas(prob, b[pending], lower, upper,
                                 lo_act[pending], up_act[pending], _MAX_PDAS_ITER)
        rho[pending], mu[pending], lam[pending] = r, m, lm
        iterations[pending] = it
        converged[pending] = ok
        pending = pending[~ok]
    if pending.size:
        ratio, at_upper = _interior_point(prob, b[pending], lower, upper)
        # at least three free indices: fewer cannot reproduce a colour in the interior
        third = np.sort(ratio, axis=1)[:, 2:3]
        for threshold in (1.0, 1e-2, 1e2, 1e-4, 1e4):
            if pending.size == 0:
                break
            active = ratio > np.maximum(threshold, third)
            lo, up = active & ~at_upper, active & at_upper
            r, m, lm, it, ok = _pdas(prob, b[pending], lower, upper, lo, up, _MAX_PDAS_ITER)
            rho[pending], mu[pending], lam[pending] = r, m, lm
            iterations[pending] += it
            converged[pending] = ok
            pending, ratio, at_upper, third = (pending[~ok], ratio[~ok], at_upper[~ok],
                                               third[~ok])
    return Solution(rho, mu, lam, iterations, converged)
