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
method, and any still unsettled are finished one by one by an exact, dense primal
active-set method started from a feasible point. Both the batched reduced solve and the
dense one end with iterative refinement: near the boundary the free weights are nearly
dependent, and without it ``W.T rho = b`` can miss rounding level by orders of magnitude.

References
----------
M. Hintermüller, K. Ito, K. Kunisch, "The primal-dual active set strategy as a semismooth
Newton method", SIAM J. Optim. 13, 865-888 (2002).
J. Nocedal, S. J. Wright, *Numerical Optimization*, 2nd ed., Springer (2006), Alg. 16.3.
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass

import numpy as np
from scipy.linalg import LinAlgWarning, lapack, lu_factor, lu_solve

from ..errors import ColorimetryError
from . import certificate, compiled

_MAX_PDAS_ITER = 30
#: Values of :attr:`Solution.method`: how each colour was solved.
METHODS = ("unconstrained", "active set", "active set restarted from interior point",
           "dense primal active set")
#: Iterative-refinement steps of the reduced solves (:func:`_reduced_solve`, :func:`_equality_qp`).
_REFINE_STEPS = 3
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


@dataclass(frozen=True)
class PinnedKKT:
    """The KKT system ``[[Q, −W], [Wᵀ, 0]] [δρ; δμ] = [s; r]`` solved in O(K) per right-hand side.

    ``Q`` is singular (constants), so it is pinned at the first sample:
    ``Q̂ = Q + c e₀ e₀ᵀ`` with ``c = 2/h`` is a positive definite tridiagonal matrix, factored
    once by the Thomas algorithm. With ``t = δρ₀``, ``Q̂ δρ = s + W δμ + c e₀ t``, so
    ``δρ = y + P [δμ; t]`` with ``y = Q̂⁻¹ s`` and ``P = Q̂⁻¹ [W, c e₀]``, and the ``m + 1``
    unknowns ``[δμ; t]`` solve ``S [δμ; t] = [r − Wᵀ y; −y₀]`` with
    ``S = [[Wᵀ P], [P₀ − e_m]]``. Each refinement step then costs a tridiagonal solve and
    ``O(K m)`` products, where the dense inverse of :attr:`Problem.kkt_inverse` costs
    ``O((K + m)²)``.

    Attributes
    ----------
    sub : ndarray (K,)
        Sub-diagonal of ``Q̂`` (``sub[k]`` couples sample k to k − 1; ``sub[0] = 0``), nm⁻¹.
    sup_factor, inverse_denominator : ndarray (K,)
        The Thomas algorithm's forward-sweep factors (super-diagonal over pivot; 1 / pivot).
    P : ndarray (K, m + 1)
        ``Q̂⁻¹ [W, c e₀]``.
    S_lu : ndarray (m + 1, m + 1)
        LU factors of ``S`` (``scipy.linalg.lu_factor`` layout), with pivots ``S_piv``.
    S_piv : ndarray (m + 1,) of int64

    References
    ----------
    G. H. Golub, C. F. Van Loan, *Matrix Computations*, 4th ed., Johns Hopkins (2013), §4.3
    (tridiagonal systems) and §2.1.4 (rank-one changes).
    """

    sub: np.ndarray
    sup_factor: np.ndarray
    inverse_denominator: np.ndarray
    P: np.ndarray
    S_lu: np.ndarray
    S_piv: np.ndarray


def _pinned_kkt(prob: Problem) -> PinnedKKT:
    """Factor the pinned Hessian and form ``P`` and ``S`` (see :class:`PinnedKKT`)."""
    from scipy.linalg import solve_banded

    W = prob.W
    K, m = W.shape
    diag, off = prob.hessian_bands()
    c = 2.0 / prob.step_nm
    diag = diag.copy()
    diag[0] += c
    sub = np.concatenate([[0.0], off])
    sup_factor, inverse_denominator = np.empty(K), np.empty(K)
    previous = 0.0
    for k in range(K):
        inverse_denominator[k] = 1.0 / (diag[k] - sub[k] * previous)
        previous = (off[k] if k < K - 1 else 0.0) * inverse_denominator[k]
        sup_factor[k] = previous
    rhs = np.zeros((K, m + 1))
    rhs[:, :m] = W
    rhs[0, m] = c
    bands = np.zeros((3, K))
    bands[0, 1:], bands[1], bands[2, :-1] = off, diag, off
    P = solve_banded((1, 1), bands, rhs)
    S = np.concatenate([W.T @ P, P[:1]], axis=0)
    S[m, m] -= 1.0
    S_lu, S_piv = lu_factor(S)
    return PinnedKKT(sub, sup_factor, inverse_denominator, np.ascontiguousarray(P), S_lu,
                     S_piv.astype(np.int64))


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
    prob = Problem(W, float(step_nm), *(np.empty((n, n)) for n in (0, 0, 0)))
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
        step = np.linalg.lstsq(kkt, rhs, rcond=None)[0]
        new = rho[F] + step[:F.size]
        if np.any(new <= lower) or np.any(new >= upper):
            break
        rho, mu = rho.copy(), mu + step[F.size:]
        rho[F] = new
        best = min(best, (ratio(rho, mu), rho, mu), key=lambda t: t[0])
    return best[1], best[2]


def _equality_qp(Q, W, b, rho, active):
    """Minimiser of ``rho Q rho / 2`` with ``W.T rho = b`` and ``rho[active]`` held fixed.

    Dense KKT solve on the free indices; returns (rho, mu) or None where the free weights
    cannot reproduce ``b`` reliably (rank below m to within 1e-12 relative).
    """
    F = np.flatnonzero(~active)
    m = W.shape[1]
    if F.size < m:
        return None
    sv = np.linalg.svd(W[F], compute_uv=False)
    if sv[m - 1] <= 1e-12 * sv[0]:
        return None
    n = F.size
    kkt = np.zeros((n + m, n + m))
    kkt[:n, :n] = Q[np.ix_(F, F)]
    kkt[:n, n:] = -W[F]
    kkt[n:, :n] = W[F].T
    fixed = np.where(active, rho, 0.0)
    rhs = np.concatenate([-Q[F] @ fixed, b - fixed @ W])
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
    if not np.all(np.isfinite(sol)):
        return None
    out = fixed.copy()
    out[F] = sol[:n]
    return out, sol[n:]


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
        sol = _equality_qp(Q, W, b, fixed, active)
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
    for it in range(1, max_iter + 1):
        sol = _equality_qp(Q, W, b, rho, active)
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
