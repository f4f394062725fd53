"""The exact, dense primal active-set method: the last resort for one colour at a time.

The batched solvers of :mod:`.qp` settle almost every colour; the few that do not (very near the
boundary of the object-colour solid, where the free weights are nearly dependent) are finished
here, one by one: a feasible start (:func:`_feasible_start`, :func:`_vertex_start`), the primal
active-set method of Nocedal & Wright (:func:`primal_active_set`) and iterative refinement with
residuals in extended precision (:func:`polish`). :mod:`.smoothest` and :mod:`.face` use them too.

References
----------
J. Nocedal, S. J. Wright, *Numerical Optimization*, 2nd ed., Springer (2006), Alg. 16.3.
N. J. Higham, *Accuracy and Stability of Numerical Algorithms*, 2nd ed., SIAM (2002), ch. 12.
"""

from __future__ import annotations

import warnings

import numpy as np
from scipy.linalg import LinAlgWarning, lu_factor, lu_solve

from . import certificate
from .tolerances import REFINE_STEPS as _REFINE_STEPS

__all__ = ["equality_qp", "is_tridiagonal", "polish", "primal_active_set"]


def polish(W, Q, b, rho, mu, lower, upper, steps=2):
    """Iterative refinement of a solution's free part with residuals in extended precision.

    On a face the free generators are nearly dependent and the multipliers large, so
    refinement with residuals in working precision stalls a few times above the
    certificate's rounding level. Here the residuals of stationarity on the free samples,
    ``(Q ρ − W μ)_F``, and of the colour, ``b − ρ @ W``, are summed in ``np.longdouble``
    (64-bit significand on x86), and the correction solves the KKT system of the free samples
    in the least-squares sense (the normals of a face are not reachable from its free
    generators; their multiplier components stay as they are). Values at a bound stay there
    exactly; a correction that would move a free value past a bound is not taken, and the
    iterate with the smallest certificate ratio is returned (refinement of an ill-conditioned
    system can also make things worse). Where ``np.longdouble`` is float64 (some platforms)
    this is plain refinement, and the certificate still decides.

    Parameters
    ----------
    W : numpy.ndarray, shape (K, m)
        Tristimulus weights (XYZ100 per unit reflectance).
    Q : numpy.ndarray, shape (K, K)
        Hessian of the roughness, nm⁻¹ (:meth:`Problem.hessian_dense`).
    b : numpy.ndarray, shape (m,)
        The colour, XYZ100.
    rho, mu : numpy.ndarray, shapes (K,) and (m,)
        A solution (reflectance factors within ``[lower, upper]``) and its multipliers.
    lower, upper : float
        The bounds (``upper`` may be ``inf``).
    steps : int, default 2
        Refinement steps.

    Returns
    -------
    rho, mu : numpy.ndarray
        New arrays: the best of the iterates by the certificate's rounding ratio.

    References
    ----------
    N. J. Higham, *Accuracy and Stability of Numerical Algorithms*, 2nd ed., SIAM (2002),
    ch. 12 (iterative refinement with residuals in extra precision).

    Examples
    --------
    >>> from spectrocolor import wavelength_grid, weights
    >>> from spectrocolor.recovery.qp import make_problem
    >>> W = np.asarray(weights(wavelength_grid(400, 700, 20), illuminant="D65"))
    >>> prob = make_problem(W, 20.0)
    >>> b = np.array([30.0, 30.0, 30.0])
    >>> rho, mu = polish(W, prob.hessian_dense(), b, b @ prob.unconstrained, b @ prob.multipliers, 0.0, 1.0)
    >>> bool(np.abs(rho @ W - b).max() < 1e-12)
    True
    """
    F = np.flatnonzero((rho > lower) & (rho < upper))
    if F.size == 0:
        return rho, mu
    m = W.shape[1]
    Wl, Ql, bl = W.astype(np.longdouble), Q.astype(np.longdouble), b.astype(np.longdouble)
    kkt = np.zeros((F.size + m, F.size + m))
    kkt[:F.size, :F.size] = Q[np.ix_(F, F)]
    kkt[:F.size, F.size:] = -W[F]
    kkt[F.size:, :F.size] = W[F].T
    # with free weights of full rank and a tridiagonal Q the KKT matrix is nonsingular, and
    # its banded solve (O(K m)) is the least-squares step; a weight column that is zero on every
    # free sample (z̄ beyond 560 nm on a face ρ = 0 wherever z̄ > 0) decouples: its multiplier
    # and colour row cannot move, as in the least-squares step; else the dense least squares
    seen = np.flatnonzero(np.any(W[F] != 0, axis=0))
    sv = np.linalg.svd(W[np.ix_(F, seen)], compute_uv=False) if F.size >= seen.size else np.zeros(1)
    banded = (seen.size > 0 and F.size < len(Q) and sv.size == seen.size
              and sv[-1] > 1e-12 * sv[0] and is_tridiagonal(Q))
    diag, off = free_bands(Q, F)
    def ratio(rho, mu):
        return float(certificate.certify(W, 2.0 / Q[0, 0], b[None], rho[None], mu[None], lower,
                                         upper, [True]).rounding_ratio[0])

    best = (ratio(rho, mu), rho, mu)
    rho, mu = rho.copy(), mu.copy()
    for _ in range(steps):
        r_l, m_l = rho.astype(np.longdouble), mu.astype(np.longdouble)
        stationarity = (Ql[F] @ r_l - Wl[F] @ m_l)
        colour = bl - r_l @ Wl
        rhs = np.concatenate([-stationarity, colour]).astype(float)
        step = None
        if banded:
            part = _banded_kkt_solve(diag, off, W[np.ix_(F, seen)], rhs[:F.size],
                                     rhs[F.size + seen])
            if part is not None:
                step = np.zeros(F.size + m)
                step[:F.size] = part[:F.size]
                step[F.size + seen] = part[F.size:]
        if step is None:
            step = np.linalg.lstsq(kkt, rhs, rcond=None)[0]
        new = rho[F] + step[:F.size]
        if np.any(new <= lower) or np.any(new >= upper):
            break
        rho, mu = rho.copy(), mu + step[F.size:]
        rho[F] = new
        best = min(best, (ratio(rho, mu), rho, mu), key=lambda t: t[0])
    return best[1], best[2]


def equality_qp(Q, W, b, rho, active, tridiagonal=None):
    """Minimiser of ``rho Q rho / 2`` with ``W.T rho = b`` and ``rho[active]`` held fixed.

    KKT solve on the free indices; returns (rho, mu) or None where the free weights cannot
    reproduce ``b`` reliably (rank below m to within 1e-12 relative). Where ``Q`` is
    tridiagonal (the roughness Hessian, as every caller's is) its free block is too, and
    positive definite unless every sample is free: the solve then goes through the block's
    banded Cholesky factor and the ``m × m`` Schur complement (:func:`_banded_kkt_solve`,
    O(K m) a step instead of the dense LU's O(K³), which made a face at 1 nm take seconds),
    and falls back to the dense LU where that does not reach rounding level.

    Parameters
    ----------
    Q : numpy.ndarray, shape (K, K)
        Hessian of the roughness, nm⁻¹ (:meth:`.qp.Problem.hessian_dense`).
    W : numpy.ndarray, shape (K, m)
        Weights (XYZ100 per unit reflectance, or their projection on a face).
    b : numpy.ndarray, shape (m,)
        The colour (same units as ``W``).
    rho : numpy.ndarray, shape (K,)
        Values of the held samples (the others are ignored).
    active : numpy.ndarray of bool, shape (K,)
        The samples held fixed.
    tridiagonal : bool or None, default None
        Whether ``Q`` is tridiagonal (tested here when None; a caller solving many steps with
        one ``Q`` tests once, :func:`is_tridiagonal`).

    Returns
    -------
    tuple of numpy.ndarray or None
        ``(rho, mu)``: all K values (held ones unchanged) and the m multipliers.

    Examples
    --------
    >>> from spectrocolor import wavelength_grid, weights
    >>> from spectrocolor.recovery.qp import make_problem
    >>> W = np.asarray(weights(wavelength_grid(400, 700, 20), illuminant="D65"))
    >>> Q = make_problem(W, 20.0).hessian_dense()
    >>> held = np.zeros(len(W), dtype=bool); held[0] = True
    >>> rho, mu = equality_qp(Q, W, np.array([30.0, 30.0, 30.0]), np.zeros(len(W)), held)
    >>> float(rho[0]), bool(np.allclose(rho @ W, 30.0))
    (0.0, True)
    """
    F = np.flatnonzero(~active)
    m = W.shape[1]
    if F.size < m:
        return None
    sv = np.linalg.svd(W[F], compute_uv=False)
    if sv[m - 1] <= 1e-12 * sv[0]:
        return None
    n = F.size
    fixed = np.where(active, rho, 0.0)
    sol = None
    if tridiagonal is None:
        tridiagonal = is_tridiagonal(Q)
    if n < Q.shape[0] and tridiagonal:
        diag, off = np.diagonal(Q), np.diagonal(Q, 1)
        Q_fixed = diag * fixed
        Q_fixed[:-1] += off * fixed[1:]
        Q_fixed[1:] += off * fixed[:-1]
        free_diag, free_off = free_bands(Q, F)
        sol = _banded_kkt_solve(free_diag, free_off, W[F], -Q_fixed[F], b - fixed @ W)
    if sol is None:
        kkt = np.zeros((n + m, n + m))
        kkt[:n, :n] = Q[np.ix_(F, F)]
        kkt[:n, n:] = -W[F]
        kkt[n:, :n] = W[F].T
        sol = _dense_kkt_solve(kkt, np.concatenate([-Q[F] @ fixed, b - fixed @ W]))
    if sol is None or not np.all(np.isfinite(sol)):
        return None
    out = fixed.copy()
    out[F] = sol[:n]
    return out, sol[n:]


def free_bands(Q, F):
    """The diagonal and superdiagonal of the tridiagonal ``Q``'s block on the sorted indices
    ``F``: samples that are neighbours in ``F`` couple only where they are neighbours on the grid."""
    return np.diagonal(Q)[F], np.where(np.diff(F) == 1, np.diagonal(Q, 1)[F[:-1]], 0.0)


def is_tridiagonal(Q):
    """Whether the square matrix ``Q`` has nothing off its three central diagonals."""
    return not np.any(np.triu(Q, 2)) and not np.any(np.tril(Q, -2))


#: A structured KKT solve is taken when every residual is within this many ulps of its terms
#: (``|kkt| |x| + |rhs|``, row by row); the dense LU with refinement reaches a few.
_BANDED_ACCEPT_ULPS = 1024


def _banded_kkt_solve(diag, off, WF, r_free, r_colour):
    """The KKT system ``[[T, −W_F], [W_F.T, 0]] [x; μ] = [r_free; r_colour]`` for the
    tridiagonal positive definite ``T`` (``diag`` (n,), ``off`` (n − 1,)): ``x = T⁻¹ (r_free
    + W_F μ)`` with μ from the Schur complement ``W_F.T T⁻¹ W_F``, then refinement with
    residuals of the whole system. Returns ``[x; μ]``, or None where the factorisation fails
    or the residual stays above rounding level (the caller then takes the dense LU)."""
    from scipy.linalg import cho_solve_banded, cholesky_banded

    n = len(diag)
    bands = np.zeros((2, n))
    bands[0, 1:] = off
    bands[1] = diag
    try:
        factor = cholesky_banded(bands, check_finite=False)
        Y = cho_solve_banded((factor, False), WF, check_finite=False)
        schur_inverse = np.linalg.inv(WF.T @ Y)
    except (np.linalg.LinAlgError, ValueError):
        return None

    def solve(r1, r2):
        y0 = cho_solve_banded((factor, False), r1, check_finite=False)
        mu = schur_inverse @ (r2 - WF.T @ y0)
        return y0 + Y @ mu, mu

    def tri(v):  # (T v, |T| |v|)
        tv, av = diag * v, np.abs(diag) * np.abs(v)
        tv[:-1] += off * v[1:]
        tv[1:] += off * v[:-1]
        av[:-1] += np.abs(off) * np.abs(v[1:])
        av[1:] += np.abs(off) * np.abs(v[:-1])
        return tv, av

    x, mu = solve(r_free, r_colour)
    limit = _BANDED_ACCEPT_ULPS * np.finfo(float).eps
    for step in range(_REFINE_STEPS + 2):
        tx, atx = tri(x)
        res1 = r_free - (tx - WF @ mu)
        res2 = r_colour - x @ WF
        if (np.all(np.abs(res1) <= limit * (atx + np.abs(WF) @ np.abs(mu) + np.abs(r_free)))
                and np.all(np.abs(res2) <= limit * (np.abs(x) @ np.abs(WF) + np.abs(r_colour)))):
            return np.concatenate([x, mu])
        if step == _REFINE_STEPS + 1:
            return None
        dx, dmu = solve(res1, res2)
        x, mu = x + dx, mu + dmu
    return None


def _dense_kkt_solve(kkt, rhs):
    """``kkt @ x = rhs`` by LU with partial pivoting and refinement; None if singular."""
    try:
        with warnings.catch_warnings():  # an exactly singular matrix is answered just below
            warnings.simplefilter("ignore", LinAlgWarning)
            lu = lu_factor(kkt, check_finite=False)
    except (np.linalg.LinAlgError, ValueError):
        return None
    if np.any(np.diag(lu[0]) == 0.0):  # the free weights lost rank exactly
        return None
    sol = lu_solve(lu, rhs, check_finite=False)
    # the multipliers are orders of magnitude larger than rho, so the normwise backward
    # error of the solve leaves W.T rho = b off by far more than rounding; refinement
    # (residuals in working precision) restores a componentwise small residual
    for _ in range(_REFINE_STEPS):
        sol = sol + lu_solve(lu, rhs - kkt @ sol, check_finite=False)
    return sol


def _feasible_start(prob, Q, b, lower, upper, rho_ip, ratio, at_upper):
    """An exactly feasible point and working set from the interior-point iterate.

    Indices are freed in order of increasing complementarity ratio (most clearly free
    first), the others held at their nearer bound, until the minimiser with those bounds
    fixed lies within the bounds; failing that, a vertex from the simplex method, or the
    interior iterate moved onto ``W.T rho = b`` by a minimum-norm correction on its most
    interior indices.
    """
    W = prob.W
    K, m = W.shape
    order = np.argsort(ratio)
    fixed = np.where(at_upper, upper, lower)
    for count in range(m, K + 1):
        active = np.ones(K, dtype=bool)
        active[order[:count]] = False
        sol = equality_qp(Q, W, b, fixed, active)
        if sol is not None and np.all((sol[0] >= lower) & (sol[0] <= upper)) and _exact(
                W, b, sol[0]):
            return sol[0], active
    vertex = _vertex_start(W, b, lower, upper)
    if vertex is not None:
        return vertex
    rho = np.clip(rho_ip, lower, upper)
    margin = np.minimum(rho - lower, upper - rho)
    for count in range(m, K + 1):
        M = np.argsort(margin)[::-1][:count]
        sv = np.linalg.svd(W[M], compute_uv=False)
        if sv[m - 1] <= 1e-12 * sv[0]:
            continue
        delta = np.linalg.lstsq(W[M].T, b - rho @ W, rcond=None)[0]
        out = rho.copy()
        out[M] += delta
        if np.all(np.abs(delta) < margin[M]) and _exact(W, b, out):
            return out, np.zeros(K, dtype=bool)
    return None


def _exact(W, b, rho):
    """``W.T rho = b`` to rounding (1e-13 relative to the largest contribution)."""
    return bool(np.abs(rho @ W - b).max() <= 1e-13 * (1.0 + np.abs(W).sum(axis=0).max()))


def _vertex_start(W, b, lower, upper):
    """A feasible point, exactly: a vertex from the dual simplex method (HiGHS) or, where its
    feasibility tolerance is too coarse (colours 1e-12 of the solid's size from its boundary,
    where the feasible set is a sliver), the bounded least-squares point of the exact active-set
    method BVLS. Values at a bound stay there (working set), the others absorb the rounding."""
    for point in (_simplex_point, _bvls_point):
        x = point(W, b, lower, upper)
        if x is None:
            continue
        x = np.clip(x, lower, upper)
        active = (x == lower) | (x == upper)
        F = np.flatnonzero(~active)
        if F.size:
            x[F] += np.linalg.lstsq(W[F].T, b - x @ W, rcond=None)[0]
        if np.all((x >= lower) & (x <= upper)) and _exact(W, b, x):
            return _with_rank(W, x, active)
    return None


def _simplex_point(W, b, lower, upper):
    from scipy.optimize import linprog

    res = linprog(np.zeros(W.shape[0]), A_eq=W.T, b_eq=b,
                  bounds=[(lower, None if not np.isfinite(upper) else upper)] * W.shape[0],
                  method="highs-ds", options={"primal_feasibility_tolerance": 1e-10})
    return res.x if res.status == 0 else None


def _bvls_point(W, b, lower, upper):
    from scipy.optimize import lsq_linear

    res = lsq_linear(W.T, b, bounds=(lower, upper), method="bvls", tol=1e-15)
    return res.x if res.status >= 0 else None


def _with_rank(W, x, active):
    """``(x, active)`` with values at a bound freed (staying where they are) until the free
    weights have rank m, as the primal active-set method needs (a degenerate vertex has fewer
    than m values off the bounds); None if no such set exists."""
    def rank(free):
        sv = np.linalg.svd(W[free], compute_uv=False) if free.any() else np.zeros(1)
        return int(np.count_nonzero(sv > 1e-12 * max(sv[0], np.finfo(float).tiny)))

    m = W.shape[1]
    have = rank(~active)
    for k in np.flatnonzero(active):
        if have >= m:
            break
        trial = ~active
        trial[k] = True
        if rank(trial) > have:
            active[k], have = False, have + 1
    return (x, active) if have >= m else None


def _keeps_rank(W, active, index):
    """Whether the free weights keep rank m when ``index`` joins the working set."""
    free = ~active
    free[index] = False
    if np.count_nonzero(free) < W.shape[1]:
        return False
    sv = np.linalg.svd(W[free], compute_uv=False)
    return bool(sv[W.shape[1] - 1] > 1e-12 * sv[0])


def primal_active_set(Q, W, b, lower, upper, rho, active, pinned=None, max_iter=None):
    """Exact primal active-set method (Nocedal & Wright, Alg. 16.3) for one colour.

    Dense and sequential, so only used for the rare colours on which the batched
    iterations do not settle, and for colours on the boundary of the solid. ``rho`` (K,)
    must be feasible, with ``active`` its working set of bounds; ``pinned`` indices (held
    at their values by the caller) never leave it. Each step goes to the minimiser of
    the programme with the working set held fixed, stopping at the first bound in the way
    (which joins the working set); at a minimiser the bound with the most wrong-signed
    multiplier leaves the working set. Ends when every multiplier has the right sign (to
    rounding), which certifies the optimum. Returns rho, mu, lam, iterations, converged.
    """
    K = W.shape[0]
    nan = (np.full(K, np.nan), np.full(W.shape[1], np.nan), np.full(K, np.nan))
    pinned = np.zeros(K, dtype=bool) if pinned is None else pinned
    rho, active = rho.copy(), active | pinned
    max_iter = 10 * K if max_iter is None else max_iter
    tridiagonal = is_tridiagonal(Q)
    for it in range(1, max_iter + 1):
        sol = equality_qp(Q, W, b, rho, active, tridiagonal)
        if sol is None:  # the working set keeps W[free] of rank m, up to rounding
            return (*nan, it, False)
        target, mu = sol
        step = target - rho
        with np.errstate(divide="ignore", invalid="ignore"):
            room = np.where(step < 0, (lower - rho) / step,
                            np.where(step > 0, (upper - rho) / step, np.inf))
        room[active] = np.inf
        block = int(np.argmin(room))
        if room[block] < 1.0 and _keeps_rank(W, active, block):
            rho = np.clip(rho + room[block] * step, lower, upper)
            rho[block] = lower if step[block] < 0 else upper
            active[block] = True
            continue
        if room[block] < 1.0:
            # the free values are fixed by the equality alone: a step that is not
            # rounding-sized means the iterate was not feasible
            if np.max(np.maximum(lower - target, target - upper)) > 1e-12:
                return (*nan, it, False)
            target = np.clip(target, lower, upper)
        rho = target
        lam = Q @ rho - W @ mu
        lam[~active] = 0.0
        step_nm = 2.0 / Q[0, 0]
        tol = np.maximum(0.5 * certificate.dual_tolerance(W, step_nm, rho, mu), np.finfo(float).tiny)
        wrong = np.where(rho == lower, -lam, lam) / tol
        wrong[~active | pinned] = 0.0
        worst = int(np.argmax(wrong))
        if wrong[worst] <= 1.0:
            return rho, mu, lam, it, True
        active[worst] = False
    return (*nan, max_iter, False)
