"""A batched primal-dual interior-point method that predicts the active bounds (Mehrotra).

:func:`.qp.solve_bounded` restarts the colours on which the active-set iterations did not settle
from the active set this method predicts (the complementarity ratio at each bound).

References
----------
J. Nocedal, S. J. Wright, *Numerical Optimization*, 2nd ed., Springer (2006), §16.6 and Alg. 14.3
(Mehrotra's predictor-corrector).
"""

from __future__ import annotations

import numpy as np
from scipy.linalg import lapack


def _interior_point(prob, b, lower, upper, iterations=60):
    """Primal-dual interior-point iterations (Mehrotra predictor-corrector), batched.

    Used only to find the active set for colours on which the active-set iterations did
    not settle (typically colours very close to the boundary of the solid). Returns the
    final (strictly interior, nearly feasible) iterate ``rho`` and, per index, the
    complementarity ratio ``z / s`` at the nearer bound (large where the bound is active)
    and whether that bound is the upper one.
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
    mu = np.zeros((N, W.shape[1]))
    m = 2 * K if has_upper else K

    def newton(r_d, r_p, c_l, c_u, s_l, s_u, z_l, z_u):
        n = len(r_d)
        sig = z_l / s_l + (z_u / s_u if has_upper else 0.0)
        h = -r_d + c_l / s_l - (c_u / s_u if has_upper else 0.0)
        d = (diag_q + sig).ravel()
        off = np.concatenate([np.broadcast_to(off_q, (n, K - 1)), np.zeros((n, 1))], axis=1)
        off = off.ravel()[:-1]
        rhs = np.empty((n, K, 1 + W.shape[1]))
        rhs[..., 0] = h
        rhs[..., 1:] = W
        _, _, _, x, _ = lapack.dgtsv(off.copy(), d, off.copy(), rhs.reshape(n * K, -1))
        x = x.reshape(n, K, -1)
        M = np.einsum("kj,nki->nji", W, x[..., 1:])
        M += 1e-14 * np.einsum("nii->n", M)[:, None, None] * np.eye(W.shape[1])
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
    # a colour whose gap has closed never moves again: iterate on the others only
    live = np.arange(N)
    for _ in range(iterations):
        r, u, sl, su, zl, zu = rho[live], mu[live], s_l[live], s_u[live], z_l[live], z_u[live]
        gap = ((sl * zl).sum(axis=1) + ((su * zu).sum(axis=1) if has_upper else 0)) / m
        keep = gap > 1e-15 * (1.0 + np.abs(u).max(axis=1))
        if not keep.any():
            break
        live, gap = live[keep], gap[keep]
        r, u, sl, su, zl, zu = r[keep], u[keep], sl[keep], su[keep], zl[keep], zu[keep]
        r_d = prob.hess_times(r) - u @ W.T - zl + zu
        r_p = r @ W - b[live]
        # predictor
        a = newton(r_d, r_p, -sl * zl, -su * zu, sl, su, zl, zu)
        alpha = step_to_boundary(np.concatenate([sl, su, zl, zu], 1),
                                 np.concatenate([a[0], -a[0], a[2], a[3]], 1))
        al = alpha[:, None]
        gap_aff = (((sl + al * a[0]) * (zl + al * a[2])).sum(axis=1)
                   + (((su - al * a[0]) * (zu + al * a[3])).sum(axis=1) if has_upper else 0)) / m
        sigma = np.clip((gap_aff / gap) ** 3, 0.0, 1.0)[:, None]
        c_l = sigma * gap[:, None] - sl * zl - a[0] * a[2]
        c_u = sigma * gap[:, None] - su * zu + a[0] * a[3]
        drho, dmu, dz_l, dz_u = newton(r_d, r_p, c_l, c_u, sl, su, zl, zu)
        al = 0.995 * step_to_boundary(np.concatenate([sl, su, zl, zu], 1),
                                      np.concatenate([drho, -drho, dz_l, dz_u], 1))[:, None]
        rho[live] = r + al * drho
        s_l[live] = sl + al * drho
        if has_upper:
            s_u[live] = su - al * drho
        mu[live] = u + al * dmu
        z_l[live] = zl + al * dz_l
        if has_upper:
            z_u[live] = zu + al * dz_u
    # complementarity ratio at the nearer bound: large = active, small = free
    at_upper = (s_u < s_l) if has_upper else np.zeros_like(rho, dtype=bool)
    with np.errstate(divide="ignore", invalid="ignore"):
        ratio = np.where(at_upper, z_u / s_u, z_l / s_l)
    return rho, np.nan_to_num(ratio, nan=np.inf), at_upper
