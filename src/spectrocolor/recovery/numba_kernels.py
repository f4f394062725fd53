"""numba kernels of the smoothest-reflectance solvers (imported only by :mod:`.compiled`).

One colour at a time, with its ``K`` samples in the processor's cache, each kernel does what
the NumPy path of :mod:`.qp` and :mod:`.certificate` does with whole-batch arrays:

* ``closed_form``: the unconstrained minimiser ``b @ U``, its multipliers and its certificate's
  measures, refined by the O(K) KKT solve of :class:`.pinned_kkt.PinnedKKT` where the ratio exceeds a
  quarter (:func:`.qp.solve_unconstrained`);
* ``pdas``: the primal-dual active-set iterations of :func:`.qp._pdas` (the same reduced
  solve, refinement and rule for keeping a bound; the tridiagonal systems are solved by the
  Thomas algorithm, stable here because every run of free samples is a positive definite path
  Laplacian), and where the reduced matrix fails its determinant test (next to the solid's
  vertices and edges), the dense KKT system of the free samples (``_dense_free_solve``);
* ``measures``: the certificate's five measures (:func:`.certificate.certify`);
* ``facet_maxima``: the facet each colour is farthest beyond (:func:`.zonotope.gauge`);
* ``roughness``: the objective of each result (:meth:`.qp.Problem.objective`).

The kernels run on one thread: a batch is a loop over colours that allocates its work arrays
once, and parallelism belongs to the caller: the kernels release the GIL, so dask's worker
threads run chunks side by side. The per-sample helpers are inlined
into the per-colour functions (``inline="always"``); the per-colour functions are not inlined
into the loops, which keeps compilation to a few tens of seconds, once per machine (cached).
The weights are passed transposed (``WT``, ``m × K``) so that the loops over samples are
contiguous. Sums may be reassociated (``fastmath={"reassoc"}``: vectorised, no assumption
about NaN or infinity), so results agree with the NumPy path to rounding, not bit for bit; the
certificate's tolerances hold for any order of summation (:mod:`.certificate`), and the
certificate decides every verdict.

Why this file is long: it is the compiled twin of the NumPy solvers, one unit. The per-sample
helpers at its top are inlined into every kernel below them (closed form, active-set
iterations, measures, membership, roughness: one section each, marked ``# ---``), and each
kernel follows the NumPy function its docstring names step for step, so that the two paths can
be read side by side; the measurement behind keeping every kernel (5.7 to 28 times the NumPy
path's speed) is in ``tests/recovery/test_recovery_kernel_pairs.py``, which holds each pair together.
"""

from __future__ import annotations

import numpy as np

from ..numba_support import jit

__all__ = ["closed_form", "facet_maxima", "measures", "pdas", "roughness"]

EPS = float(np.finfo(np.float64).eps)
TINY = float(np.finfo(np.float64).tiny)
#: Sums may be reassociated (vectorised); NaN and infinity keep their meaning.
_FAST = {"reassoc"}


def _inline(function):
    return jit(inline="always", fastmath=_FAST, error_model="numpy")(function)


def _compiled(function):
    # nogil: threads (dask's workers) run the kernels side by side
    return jit(fastmath=_FAST, nogil=True, error_model="numpy")(function)


@_inline
def _hess_times(rho, t, out):
    """``Q ρ`` for the path Laplacian ``Q`` with ``t = 2/h`` (:func:`.certificate.hess_times`)."""
    K = rho.shape[0]
    out[0] = (rho[0] - rho[1]) * t
    for k in range(1, K - 1):
        out[k] = ((rho[k] - rho[k - 1]) - (rho[k + 1] - rho[k])) * t
    out[K - 1] = (rho[K - 1] - rho[K - 2]) * t


@_inline
def _abs_hess_times(rho, t, out):
    """``|Q| |ρ|`` (:func:`.certificate.abs_hess_times`)."""
    K = rho.shape[0]
    out[0] = (abs(rho[0]) + abs(rho[1])) * t
    for k in range(1, K - 1):
        out[k] = (abs(rho[k - 1]) + 2.0 * abs(rho[k]) + abs(rho[k + 1])) * t
    out[K - 1] = (abs(rho[K - 2]) + abs(rho[K - 1])) * t


@_inline
def _weighted(WT, mu, out):
    """``W μ`` (K,)."""
    K = WT.shape[1]
    for k in range(K):
        out[k] = mu[0] * WT[0, k]
    for j in range(1, WT.shape[0]):
        for k in range(K):
            out[k] += mu[j] * WT[j, k]


@_inline
def _dual_tolerance(absWT, mu, abs_q_rho, dual_factor, out):
    """``DUAL_FACTOR ε (|Q||ρ| + |W||μ|)`` (K,)."""
    K = absWT.shape[1]
    for k in range(K):
        out[k] = abs_q_rho[k]
    for j in range(absWT.shape[0]):
        for k in range(K):
            out[k] += abs(mu[j]) * absWT[j, k]
    for k in range(K):
        out[k] *= dual_factor * EPS


@_inline
def _colour_residual(WT, absWT, b, rho, r, size):
    """``r = b − ρ W`` and ``size = |b| + |ρ| |W|`` (m,)."""
    K = WT.shape[1]
    for j in range(WT.shape[0]):
        total = 0.0
        scale = 0.0
        for k in range(K):
            total += rho[k] * WT[j, k]
            scale += abs(rho[k]) * absWT[j, k]
        r[j] = b[j] - total
        size[j] = abs(b[j]) + scale


@_inline
def _residuals(WT, absWT, b, rho, mu, t, free, primal_factor, dual_factor, check, work, r,
               size):
    """The colour residual ``r`` and the stationarity residual ``s = (W μ − Q ρ)`` on the free
    samples (``work[0]``); with ``check``, whether either exceeds a quarter of the
    certificate's tolerance (else False)."""
    K = WT.shape[1]
    s, q_rho, w_mu, tol = work[0], work[1], work[2], work[3]
    _colour_residual(WT, absWT, b, rho, r, size)
    _hess_times(rho, t, q_rho)
    _weighted(WT, mu, w_mu)
    for k in range(K):
        s[k] = (w_mu[k] - q_rho[k]) * free[k]
    if not check:
        return False
    for j in range(WT.shape[0]):
        if abs(r[j]) > 0.25 * primal_factor * size[j]:
            return True
    _abs_hess_times(rho, t, q_rho)
    _dual_tolerance(absWT, mu, q_rho, dual_factor, tol)
    for k in range(K):
        if abs(s[k]) > 0.25 * tol[k]:
            return True
    return False


@_inline
def _lu_small(M, piv):
    """In-place LU with partial pivoting of the small square ``M``; returns its determinant."""
    n = M.shape[0]
    det = 1.0
    for c in range(n):
        p = c
        for i in range(c + 1, n):
            if abs(M[i, c]) > abs(M[p, c]):
                p = i
        piv[c] = p
        if p != c:
            det = -det
            for j in range(n):
                M[c, j], M[p, j] = M[p, j], M[c, j]
        det *= M[c, c]
        if M[c, c] != 0.0:
            for i in range(c + 1, n):
                M[i, c] /= M[c, c]
                for j in range(c + 1, n):
                    M[i, j] -= M[i, c] * M[c, j]
    return det


@_inline
def _lu_solve_small(LU, piv, x):
    """Solve in place with the factors of :func:`_lu_small` (or ``scipy.linalg.lu_factor``)."""
    n = LU.shape[0]
    for c in range(n):
        p = piv[c]
        if p != c:
            x[c], x[p] = x[p], x[c]
    for i in range(n):
        for j in range(i):
            x[i] -= LU[i, j] * x[j]
    for i in range(n - 1, -1, -1):
        for j in range(i + 1, n):
            x[i] -= LU[i, j] * x[j]
        x[i] /= LU[i, i]


@_inline
def _thomas_solve(sub, sup_factor, inverse_denominator, rhs, out):
    """Solve ``T x = rhs`` with the Thomas factors of ``T`` (``sub[k]`` couples row k to k − 1)."""
    K = rhs.shape[0]
    y = rhs[0] * inverse_denominator[0]
    out[0] = y
    for k in range(1, K):
        y = (rhs[k] - sub[k] * y) * inverse_denominator[k]
        out[k] = y
    for k in range(K - 2, -1, -1):
        out[k] -= sup_factor[k] * out[k + 1]


@_inline
def _linear_map(b, U, out):
    """``b @ U`` for one colour (``U`` (m, n))."""
    for i in range(U.shape[1]):
        out[i] = b[0] * U[0, i]
    for j in range(1, U.shape[0]):
        for i in range(U.shape[1]):
            out[i] += b[j] * U[j, i]


# --- the closed form ----------------------------------------------------------------------


#: A closed form is refined while its certificate ratio exceeds this (a quarter of the
#: tolerance: the verdict then holds for any order of summation).
REFINE_ABOVE = 0.25


@_inline
def _closed_form_three(WT, absWT, b, A, V, Mv, t, primal_factor, dual_factor, lowest, highest,
                       rho, mu, out, rough, n, work):
    """The closed form of one colour for three weights (tristimulus values), with its
    certificate's measures and roughness, in two passes over the samples; returns the number
    of values below ``lowest`` or above ``highest``.

    The same arithmetic as :func:`_linear_map` and :func:`_measures_one` (unbounded) with
    the three weights unrolled, so that each pass vectorises: the first forms ``ρ`` and the
    colour residual with the size of its terms, the second ``λ = Q ρ − W μ`` with the size of
    its terms, the stationarity ratio and ``Σ (Δρ)²``."""
    K = WT.shape[1]
    W0, W1, W2, a0, a1, a2 = WT[0], WT[1], WT[2], absWT[0], absWT[1], absWT[2]
    V0, V1, V2 = V[0], V[1], V[2]
    # the colour in the basis colours (qp.ClosedFormBasis), then ρ and μ
    c0 = b[0] * A[0, 0] + b[1] * A[1, 0] + b[2] * A[2, 0]
    c1 = b[0] * A[0, 1] + b[1] * A[1, 1] + b[2] * A[2, 1]
    c2 = b[0] * A[0, 2] + b[1] * A[1, 2] + b[2] * A[2, 2]
    m0 = c0 * Mv[0, 0] + c1 * Mv[1, 0] + c2 * Mv[2, 0]
    m1 = c0 * Mv[0, 1] + c1 * Mv[1, 1] + c2 * Mv[2, 1]
    m2 = c0 * Mv[0, 2] + c1 * Mv[1, 2] + c2 * Mv[2, 2]
    mu[0], mu[1], mu[2] = m0, m1, m2
    # 0 · x is 0 for every finite x and NaN for NaN and ±∞ (see _measures_one)
    probe = 0.0 * m0 + 0.0 * m1 + 0.0 * m2
    outside = 0
    x0 = x1 = x2 = s0 = s1 = s2 = 0.0
    for k in range(K):
        v = c0 * V0[k] + c1 * V1[k] + c2 * V2[k]
        rho[k] = v
        probe += 0.0 * v
        outside += (v < lowest) | (v > highest)
        x0 += v * W0[k]
        x1 += v * W1[k]
        x2 += v * W2[k]
        s0 += abs(v) * a0[k]
        s1 += abs(v) * a1[k]
        s2 += abs(v) * a2[k]
    r0, r1, r2 = abs(b[0] - x0), abs(b[1] - x1), abs(b[2] - x2)
    ratio = max(r0 / max(primal_factor * (abs(b[0]) + s0), TINY),
                r1 / max(primal_factor * (abs(b[1]) + s1), TINY),
                r2 / max(primal_factor * (abs(b[2]) + s2), TINY))
    n0, n1, n2 = abs(m0), abs(m1), abs(m2)
    scale = dual_factor * EPS
    # |λ_k| and its ratio to the tolerance into work rows, their maxima after the loop (a
    # running maximum in the loop would keep it from vectorising)
    off, quotient = work[0], work[1]
    L = K - 1
    d = rho[1] - rho[0]  # the ends: half rows of Q
    smooth = d * d
    lam = -d * t - (m0 * W0[0] + m1 * W1[0] + m2 * W2[0])
    size = (abs(rho[0]) + abs(rho[1])) * t + (n0 * a0[0] + n1 * a1[0] + n2 * a2[0])
    off[0], quotient[0] = abs(lam), abs(lam) / max(scale * size, TINY)
    lam = (rho[L] - rho[L - 1]) * t - (m0 * W0[L] + m1 * W1[L] + m2 * W2[L])
    size = (abs(rho[L - 1]) + abs(rho[L])) * t + (n0 * a0[L] + n1 * a1[L] + n2 * a2[L])
    off[L], quotient[L] = abs(lam), abs(lam) / max(scale * size, TINY)
    for k in range(1, L):
        d = rho[k + 1] - rho[k]
        smooth += d * d
        lam = ((rho[k] - rho[k - 1]) - d) * t - (m0 * W0[k] + m1 * W1[k] + m2 * W2[k])
        size = ((abs(rho[k - 1]) + 2.0 * abs(rho[k]) + abs(rho[k + 1])) * t
                + (n0 * a0[k] + n1 * a1[k] + n2 * a2[k]))
        off[k] = abs(lam)
        quotient[k] = abs(lam) / max(scale * size, TINY)
    off_max = _maximum(off)
    ratio = max(ratio, _maximum(quotient))
    out[0, n] = max(r0, r1, r2)
    out[1, n] = 0.0
    out[2, n] = 0.0
    out[3, n] = off_max
    # a row holding NaN or infinity is measured again by the NumPy path (its NaN semantics)
    out[4, n] = ratio if probe == 0.0 else np.inf
    rough[n] = smooth * (0.5 * t)  # Σ (Δρ)² / h
    return outside


@_inline
def _maximum(values):
    """The largest of ``values`` and 0 (NaN entries are skipped), with four running maxima:
    one running maximum is a chain of dependent comparisons."""
    n = values.shape[0]
    m0 = m1 = m2 = m3 = 0.0
    k = 0
    while k + 4 <= n:
        m0 = max(m0, values[k])
        m1 = max(m1, values[k + 1])
        m2 = max(m2, values[k + 2])
        m3 = max(m3, values[k + 3])
        k += 4
    while k < n:
        m0 = max(m0, values[k])
        k += 1
    return max(max(m0, m1), max(m2, m3))


@_inline
def _closed_form_general(WT, absWT, b, A, V, Mv, t, primal_factor, dual_factor, lowest,
                         highest, rho, mu, out, rough, n, work, small):
    """:func:`_closed_form_three` for any number of weights (metamers under several
    illuminants), with the general helpers."""
    K = WT.shape[1]
    c = small[2]
    _linear_map(b, A, c)  # the colour in the basis colours (qp.ClosedFormBasis)
    _linear_map(c, V, rho)
    _linear_map(c, Mv, mu)
    outside = 0
    for k in range(K):
        outside += (rho[k] < lowest) | (rho[k] > highest)
    _measure_closed_form(WT, absWT, t, b, rho, mu, primal_factor, dual_factor, out, n, work,
                         small)
    rough[n] = _smoothness(rho) * (0.5 * t)
    return outside


@_inline
def _smoothness(rho):
    """``Σ (Δρ)²``."""
    total = 0.0
    for k in range(rho.shape[0] - 1):
        d = rho[k + 1] - rho[k]
        total += d * d
    return total


@_compiled
def _measure_closed_form(WT, absWT, t, b, rho, mu, primal_factor, dual_factor, out, n, work,
                         small):
    """:func:`_measures_one` of an unbounded result, compiled once for the general loop and
    the refinement (neither is hot; inlined into both, it doubled their compilation)."""
    _measures_one(WT, absWT, t, b, rho, mu, 0.0, 0.0, False, primal_factor, dual_factor, out, n,
                  work, small)


@_compiled
def _refine_closed_form(WT, absWT, b, t, pin, S_lu, S_piv, refine_steps, primal_factor,
                        dual_factor, rho, mu, out, rough, n, work, small):
    """Refine one closed form by the O(K) KKT solve of :class:`.pinned_kkt.PinnedKKT` while its ratio
    exceeds :data:`REFINE_ABOVE` (at most ``refine_steps`` times), measuring it again after
    each step. Compiled apart from the loop over colours: few colours need it."""
    K, m = WT.shape[1], WT.shape[0]
    sub, sup_factor, inverse_denominator, P = pin[0], pin[1], pin[2], pin[3:]
    free, y = work[4], work[5]
    for k in range(K):
        free[k] = 1.0
    r, size, rhs = small[0], small[1], small[2]
    for _ in range(refine_steps):
        _residuals(WT, absWT, b, rho, mu, t, free, primal_factor, dual_factor, False, work, r,
                   size)
        # [[Q, −W], [Wᵀ, 0]] [δρ; δμ] = [s; r]: δρ = y + P [δμ; τ], y = Q̂⁻¹ s (pinned_kkt.PinnedKKT)
        _thomas_solve(sub, sup_factor, inverse_denominator, work[0], y)
        for j in range(m):
            total = 0.0
            for k in range(K):
                total += WT[j, k] * y[k]
            rhs[j] = r[j] - total
        rhs[m] = -y[0]
        _lu_solve_small(S_lu, S_piv, rhs)
        for j in range(m + 1):
            for k in range(K):
                y[k] += P[j, k] * rhs[j]
        for k in range(K):
            rho[k] += y[k]
        for j in range(m):
            mu[j] += rhs[j]
        _measure_closed_form(WT, absWT, t, b, rho, mu, primal_factor, dual_factor, out, n,
                             work, small)
        if out[4, n] <= REFINE_ABOVE:
            break
    rough[n] = _smoothness(rho) * (0.5 * t)


@_compiled
def closed_form(WT, absWT, b, A, V, Mv, t, pin, S_lu, S_piv, refine_steps, primal_factor,
                dual_factor, lowest, highest, rho, mu, out, rough):
    """Unconstrained minimisers ``rho`` (N, K) and multipliers ``mu`` (N, m) of colours ``b``,
    their certificate's measures ``out`` (5, N) (:func:`measures`) and roughness ``rough``
    (N,) (:func:`roughness`).

    ``A``, ``V`` and ``Mv`` are the inverse, solutions and multipliers of
    :class:`.qp.ClosedFormBasis`; ``t = 2/h``; ``primal_factor`` is ``PRIMAL_FACTOR γ_{K+1}`` and ``dual_factor``
    ``DUAL_FACTOR`` of :mod:`.certificate`; ``pin`` stacks the sub-diagonal, the forward-sweep
    factors, the inverse denominators and ``Pᵀ`` of :class:`.pinned_kkt.PinnedKKT`. Each closed form
    is refined while its ratio exceeds :data:`REFINE_ABOVE` (at most ``refine_steps`` times).
    Colours with a value below ``lowest`` or above ``highest`` are neither refined nor
    measured (ratio ∞, roughness NaN).
    """
    # one compiled loop per case (with both cases in one loop the unrolled one runs at half
    # its speed), then the few colours that need it are refined
    if WT.shape[0] == 3:
        _closed_forms_three(WT, absWT, b, A, V, Mv, t, primal_factor, dual_factor, lowest,
                            highest, rho, mu, out, rough)
    else:
        _closed_forms_general(WT, absWT, b, A, V, Mv, t, primal_factor, dual_factor, lowest,
                              highest, rho, mu, out, rough)
    if refine_steps > 0:
        work = np.empty((6, WT.shape[1]))
        small = np.empty((3, WT.shape[0] + 1))
        for n in range(b.shape[0]):
            # ∞: unmeasured (out of range) or not finite; neither is refined
            if REFINE_ABOVE < out[4, n] < np.inf:
                _refine_closed_form(WT, absWT, b[n], t, pin, S_lu, S_piv, refine_steps,
                                    primal_factor, dual_factor, rho[n], mu[n], out, rough, n,
                                    work, small)


@_compiled
def _closed_forms_three(WT, absWT, b, A, V, Mv, t, primal_factor, dual_factor, lowest, highest,
                        rho, mu, out, rough):
    """The closed forms and measures of :func:`closed_form` for three weights, unrefined."""
    work = np.empty((2, WT.shape[1]))
    for n in range(b.shape[0]):
        if _closed_form_three(WT, absWT, b[n], A, V, Mv, t, primal_factor, dual_factor, lowest,
                              highest, rho[n], mu[n], out, rough, n, work):
            _leave_unmeasured(out, rough, n)


@_compiled
def _closed_forms_general(WT, absWT, b, A, V, Mv, t, primal_factor, dual_factor, lowest,
                          highest, rho, mu, out, rough):
    """The closed forms and measures of :func:`closed_form` for any number of weights,
    unrefined."""
    work = np.empty((4, WT.shape[1]))
    small = np.empty((3, WT.shape[0] + 1))
    for n in range(b.shape[0]):
        if _closed_form_general(WT, absWT, b[n], A, V, Mv, t, primal_factor, dual_factor,
                                lowest, highest, rho[n], mu[n], out, rough, n, work, small):
            _leave_unmeasured(out, rough, n)


@_inline
def _leave_unmeasured(out, rough, n):
    """Colour ``n`` has values out of range: the bounded solver takes it over (ratio ∞,
    roughness NaN)."""
    for i in range(4):
        out[i, n] = 0.0
    out[4, n] = np.inf
    rough[n] = np.nan


# --- the active-set iterations --------------------------------------------------------------


@_inline
def _thomas_solve_rows(sub, sup_factor, inverse_denominator, rhs, out):
    """:func:`_thomas_solve` for every row of ``rhs`` (q, K) at once (their recurrences are
    independent, so the processor overlaps them)."""
    q, K = rhs.shape
    for i in range(q):
        out[i, 0] = rhs[i, 0] * inverse_denominator[0]
    for k in range(1, K):
        a, d = sub[k], inverse_denominator[k]
        for i in range(q):
            out[i, k] = (rhs[i, k] - a * out[i, k - 1]) * d
    for k in range(K - 2, -1, -1):
        c = sup_factor[k]
        for i in range(q):
            out[i, k] -= c * out[i, k + 1]


@_inline
def _reduced_solve(WT, absWT, b, U, Mu, off_q, t, lower, upper, lo, up, rho, mu, work, R, X, M,
                   piv, small):
    """One reduced solve of :func:`.qp._reduced_solve` for one colour, without its refinement
    (:func:`_refine_reduced`); returns 0 where the reduced matrix is singular, 2 where no
    bound is active (the closed form), else 1.

    ``R`` and ``X`` (m + 1, K) hold the right-hand sides (bounds; free weights) and their
    solutions ``p`` and ``P``."""
    K, m = WT.shape[1], WT.shape[0]
    free, sub, sup_factor, inverse_denominator = work[4], work[5], work[6], work[7]
    r = small[0]
    active_count = 0
    for k in range(K):
        free[k] = 0.0 if (lo[k] or up[k]) else 1.0
        active_count += 1 - int(free[k])
    if active_count == 0:
        _linear_map(b, U, rho)
        _linear_map(b, Mu, mu)
        return 2
    # The tridiagonal matrix with identity rows on the active samples. Its Thomas pivots are
    # known in closed form (so no chain of divisions): in units of 2/h, a run of free samples
    # from the first sample has pivots 1; a run after an active sample is a path Laplacian
    # with a fixed left end, whose n-th pivot is (n + 1)/n, or 1/n at the last sample (half
    # diagonal). Identity rows have pivot 1 and no couplings.
    run, from_start = 0, True
    for k in range(K):
        if free[k] == 0.0:
            run, from_start = 0, False
            sub[k], inverse_denominator[k], sup_factor[k] = 0.0, 1.0, 0.0
            continue
        run += 1
        sub[k] = off_q if k > 0 else 0.0
        if from_start:
            inverse_scaled = 1.0
        elif k == K - 1:
            inverse_scaled = float(run)
        else:
            inverse_scaled = run / (run + 1.0)
        inverse_denominator[k] = inverse_scaled / t
        sup_factor[k] = -inverse_scaled if k < K - 1 else 0.0
    for k in range(K):
        R[0, k] = lower if lo[k] else (upper if up[k] else 0.0)
    for j in range(m):
        for k in range(K):
            R[1 + j, k] = WT[j, k] * free[k]
    _thomas_solve_rows(sub, sup_factor, inverse_denominator, R, X)
    p, P = X[0], X[1:]
    for i in range(m):
        total = 0.0
        for k in range(K):
            total += p[k] * WT[i, k]
        r[i] = b[i] - total
    # M = Wᵀ P = W_Fᵀ Q_FF⁻¹ W_F is symmetric: one triangle is summed
    scale = 0.0
    for i in range(m):
        for j in range(i, m):
            value = 0.0
            for k in range(K):
                value += WT[i, k] * P[j, k]
            M[i, j] = M[j, i] = value
            scale += value * value if i == j else 2.0 * value * value
    det = _lu_small(M, piv)
    if not abs(det) > 1e-13 * scale ** (0.5 * m):
        return 0
    for i in range(m):
        mu[i] = r[i]
    _lu_solve_small(M, piv, mu)
    for k in range(K):
        rho[k] = p[k]
    for j in range(m):
        for k in range(K):
            rho[k] += P[j, k] * mu[j]
    for k in range(K):
        if lo[k]:
            rho[k] = lower
        elif up[k]:
            rho[k] = upper
    return 1


#: Most free samples for which :func:`_dense_free_solve` takes over an ill-conditioned reduced
#: solve (its dense KKT matrix has at most ``DENSE_FREE + m`` rows: a few tens of microseconds).
DENSE_FREE = 64
#: Iterations of the full active-set rule after which :func:`_pdas_one` changes one index at a
#: time (the full rule can cycle next to the solid's vertices; a settled run takes at most 12).
CYCLE_GUARD = 15


@_compiled
def _dense_free_solve(WT, absWT, b, t, lower, upper, lo, up, rho_out, mu_out, work, small, D,
                      dpiv, x, index, trial, refine_steps, primal_factor, dual_factor):
    """The reduced solve of :func:`_reduced_solve` on the dense KKT system of the free samples,
    for the sets whose reduced matrix ``M = W_Fᵀ Q_FF⁻¹ W_F`` failed its determinant test.

    Next to the solid's vertices and edges only a few samples are free and their weights are
    nearly dependent (cond ``W_F`` up to about 1e8); ``M`` squares that condition and its
    determinant test rejects it, yet the KKT matrix ``[[Q_FF, −W_F], [W_Fᵀ, 0]]`` itself is
    solved by LU with partial pivoting and iterative refinement (Higham 2002, ch. 12) to the
    certificate's rounding level, as :func:`.dense_active_set.equality_qp` does. Returns 3
    where the refined residuals are within a quarter of the certificate's tolerance, else 0
    (more than ``DENSE_FREE`` or fewer than m free samples, a zero pivot, or residuals that
    refinement could not bring down: the caller treats the sets as singular). ``rho_out`` and
    ``mu_out`` are written only on success (the caller's fallback needs the last solve's)."""
    K, m = WT.shape[1], WT.shape[0]
    rho, mu = trial[:K], trial[K:K + m]
    free = work[4]
    n = 0
    for k in range(K):
        if lo[k] or up[k]:
            free[k] = 0.0
            rho[k] = lower if lo[k] else upper
        else:
            free[k] = 1.0
            rho[k] = 0.0
            if n < index.shape[0]:
                index[n] = k
            n += 1
    if n < m or n > DENSE_FREE:
        return 0
    size = n + m
    A = D[:size, :size]
    for i in range(size):
        for j in range(size):
            A[i, j] = 0.0
    for a in range(n):
        k = index[a]
        A[a, a] = t if (k == 0 or k == K - 1) else 2.0 * t
        if a + 1 < n and index[a + 1] == k + 1:
            A[a, a + 1] = -t
            A[a + 1, a] = -t
        for j in range(m):
            A[a, n + j] = -WT[j, k]
            A[n + j, a] = WT[j, k]
    _lu_small(A, dpiv)
    for i in range(size):  # the pivots, not their product (which can underflow)
        if not (A[i, i] != 0.0 and np.isfinite(A[i, i])):
            return 0
    for j in range(m):
        mu[j] = 0.0
    r, sizes = small[0], small[1]
    s = work[0]
    # the first solve is a refinement step from ρ_F = 0, μ = 0 (its residuals are the
    # right-hand side), and so is every later one
    for step in range(refine_steps + 3):
        bad = _residuals(WT, absWT, b, rho, mu, t, free, primal_factor, dual_factor, True, work,
                         r, sizes)
        if step > 0 and not bad:
            for k in range(K):
                rho_out[k] = rho[k]
            for j in range(m):
                mu_out[j] = mu[j]
            return 3
        if step == refine_steps + 2:
            break
        for a in range(n):
            x[a] = s[index[a]]
        for j in range(m):
            x[n + j] = r[j]
        _lu_solve_small(A, dpiv[:size], x[:size])
        for a in range(n):
            rho[index[a]] += x[a]
        for j in range(m):
            mu[j] += x[n + j]
    return 0


@_compiled
def _refine_reduced(WT, absWT, b, t, refine_steps, primal_factor, dual_factor, rho, mu, work, X,
                    M, piv, small):
    """Iterative refinement of the last :func:`_reduced_solve` (its factors are still in
    ``work``, ``X``, ``M`` and ``piv``), while a residual exceeds a quarter of the certificate's
    tolerance; the active values stay exact."""
    K, m = WT.shape[1], WT.shape[0]
    free, sub, sup_factor, inverse_denominator = work[4], work[5], work[6], work[7]
    y = work[9]
    r, size, dmu = small[0], small[1], small[2]
    P = X[1:]
    for _ in range(refine_steps):
        if not _residuals(WT, absWT, b, rho, mu, t, free, primal_factor, dual_factor, True,
                          work, r, size):
            break
        _thomas_solve(sub, sup_factor, inverse_denominator, work[0], y)
        for i in range(m):
            total = 0.0
            for k in range(K):
                total += y[k] * WT[i, k]
            dmu[i] = r[i] - total
        _lu_solve_small(M, piv, dmu)
        for j in range(m):
            mu[j] += dmu[j]
            for k in range(K):
                y[k] += P[j, k] * dmu[j]
        for k in range(K):
            rho[k] += y[k] * free[k]


@_inline
def _stationarity(WT, absWT, t, rho, mu, lam, size):
    """``λ = Q ρ − W μ`` and the sizes of its terms ``|Q||ρ| + |W||μ|`` (K,), in one pass for
    ``Q ρ`` and one per weight (each vectorises), as :func:`_hess_times`,
    :func:`_abs_hess_times` and :func:`_dual_tolerance` form them."""
    K, m = WT.shape[1], WT.shape[0]
    for k in range(1, K - 1):
        lam[k] = ((rho[k] - rho[k - 1]) - (rho[k + 1] - rho[k])) * t
        size[k] = (abs(rho[k - 1]) + 2.0 * abs(rho[k]) + abs(rho[k + 1])) * t
    lam[0] = (rho[0] - rho[1]) * t
    size[0] = (abs(rho[0]) + abs(rho[1])) * t
    lam[K - 1] = (rho[K - 1] - rho[K - 2]) * t
    size[K - 1] = (abs(rho[K - 2]) + abs(rho[K - 1])) * t
    for j in range(m):
        weight, size_weight = mu[j], abs(mu[j])
        for k in range(K):
            lam[k] -= weight * WT[j, k]
            size[k] += size_weight * absWT[j, k]


@_compiled
def _update_active_sets(WT, absWT, t, dual_factor, lower, upper, rho, mu, lam, lo, up, size):
    """The bound multipliers ``lam`` and the next active sets (in place, :func:`.qp._pdas`'s
    rule); returns whether the sets stayed the same. ``size`` (K,) is scratch."""
    K = WT.shape[1]
    _stationarity(WT, absWT, t, rho, mu, lam, size)
    same = True
    for k in range(K):
        if lo[k] or up[k]:
            q, tol = lam[k], dual_factor * EPS * size[k]
            # a bound stays while its multiplier has the right sign to within half the
            # certificate's tolerance
            new_lo = lo[k] and q > -0.5 * tol
            new_up = up[k] and q < 0.5 * tol
        else:
            lam[k] = 0.0
            new_lo = rho[k] < lower
            new_up = rho[k] > upper
        if new_lo != lo[k] or new_up != up[k]:
            same = False
        lo[k], up[k] = new_lo, new_up
    return same


@_inline
def _dual_swap(WT, lower, upper, rho, lam, lo, up, enter):
    """The bound that leaves when the free value ``enter`` joins its bound while exactly m
    samples are free (joining alone would leave fewer free weights than the colour has
    components: a singular reduced system). The dual step of Goldfarb & Idnani (1983) for a
    constraint dependent on the active ones: with ``s e_enter = W r_w + Σ_A r_j σ_j e_j``
    (``σ_j`` +1 at a lower, −1 at an upper bound), the multipliers move as ``u − τ r`` and the
    first active bound whose multiplier ``u_j = σ_j λ_j`` reaches zero leaves (the dual simplex
    ratio test). Returns its index, or −1 (no ``r_j > 0``, a singular ``W_F``, or not exactly m
    free samples)."""
    K, m = WT.shape[1], WT.shape[0]
    A = np.empty((m, m))
    piv = np.empty(m, dtype=np.int64)
    r_w = np.empty(m)
    n = 0
    for k in range(K):
        if not (lo[k] or up[k]):
            if n == m:
                return -1
            for i in range(m):
                A[n, i] = WT[i, k]
            r_w[n] = 0.0
            if k == enter:
                r_w[n] = 1.0 if rho[k] < lower else -1.0
            n += 1
    if n != m:
        return -1
    det = _lu_small(A, piv)
    if not (det != 0.0 and np.isfinite(det)):
        return -1
    _lu_solve_small(A, piv, r_w)
    leave, best = -1, np.inf
    for k in range(K):
        if lo[k] or up[k]:
            sigma = 1.0 if lo[k] else -1.0
            w = 0.0
            for i in range(m):
                w += WT[i, k] * r_w[i]
            r = -sigma * w
            if r > 0.0:
                ratio = max(sigma * lam[k], 0.0) / r
                if ratio < best:
                    leave, best = k, ratio
    return leave


@_compiled
def _single_change(WT, absWT, t, dual_factor, lower, upper, rho, mu, lam, lo, up, size,
                   banned):
    """The safeguarded step of :func:`_pdas_one`: ``lam`` as in :func:`_update_active_sets`, and
    at most one change of the active sets (in place): the free value farthest beyond a bound
    joins it, or, with none beyond, the bound whose multiplier has the most wrong sign
    (relative to the rule's tolerance) is released. Where exactly m samples are free, a value
    beyond its bound joins it in exchange for the bound :func:`_dual_swap` picks (joining alone
    would make the free weights singular). Indices ``banned`` (K,) do not join alone (their
    bound made the free weights singular from these sets). Returns whether nothing had to
    change."""
    K, m = WT.shape[1], WT.shape[0]
    _stationarity(WT, absWT, t, rho, mu, lam, size)
    add, add_score, release, release_score = -1, 0.0, -1, 1.0
    swap, swap_score, free = -1, 0.0, 0
    for k in range(K):
        if lo[k] or up[k]:
            q = lam[k]
            wrong = (-q if lo[k] else q) / max(0.5 * dual_factor * EPS * size[k], TINY)
            if wrong > release_score:
                release, release_score = k, wrong
        else:
            free += 1
            lam[k] = 0.0
            beyond = max(lower - rho[k], rho[k] - upper)
            if beyond > add_score and not banned[k]:
                add, add_score = k, beyond
            if beyond > swap_score:
                swap, swap_score = k, beyond
    if swap >= 0 and free == m:
        leave = _dual_swap(WT, lower, upper, rho, lam, lo, up, swap)
        if leave >= 0:
            lo[swap], up[swap] = rho[swap] < lower, rho[swap] > upper
            lo[leave], up[leave] = False, False
            return False
    if add >= 0:
        lo[add], up[add] = rho[add] < lower, rho[add] > upper
        return False
    if release >= 0:
        lo[release], up[release] = False, False
        return False
    return True


@_inline
def _apply_rule(single, WT, absWT, t, dual_factor, lower, upper, rho, mu, lam, lo, up, size,
                banned):
    """The next active sets by the full rule, or by one change where ``single``; returns
    whether they stayed the same."""
    if single:
        return _single_change(WT, absWT, t, dual_factor, lower, upper, rho, mu, lam, lo, up,
                              size, banned)
    return _update_active_sets(WT, absWT, t, dual_factor, lower, upper, rho, mu, lam, lo, up,
                               size)


@_inline
def _pdas_one(WT, absWT, b, U, Mu, off_q, t, lower, upper, lo, up, max_iter, refine_steps,
              primal_factor, dual_factor, rho, mu, lam, work, R, X, M, piv, small, saved, D, dpiv,
              x, index, trial):
    """:func:`.qp._pdas` for one colour from the active sets ``lo``/``up`` (updated in place).
    Returns (iterations, converged); on failure the outputs are NaN.

    The NumPy path refines every reduced solve; here the iterations run unrefined until the
    active sets settle, the settled solution is refined, and the rule is applied once more
    to the refined values (from then on every solve is refined). The sets of the last
    iteration are those a refined solve keeps, as on the NumPy path.

    A safeguard the NumPy path lacks: where an update leaves free weights that cannot
    reproduce the colour (a singular reduced matrix; typical of colours within 1e-9 of the
    boundary, where all but a few samples sit at a bound), the sets go back to those of the
    last solve and change one index at a time from then on (:func:`_single_change`). Where
    exactly m samples are free that change is an exchange (:func:`_dual_swap`: a value beyond
    its bound joins it and the bound the dual ratio test picks leaves), without which a fifth
    of the colours at 1e-9 from the solid's vertices and edges ended unsettled. The one-at-a-time
    phase may take a change per sample: the iterations run to ``max_iter + K``."""
    K, m = WT.shape[1], WT.shape[0]
    status = 1
    it = 0
    precise = False
    single = False
    banned = saved[2]
    for k in range(K):
        banned[k] = False
    # the one-change-at-a-time phase after the cycle guard may need a change per sample
    for it in range(1, max_iter + K + 1):
        if it == CYCLE_GUARD + 1:  # the full rule is cycling: one change at a time from here
            single = True
        status = _reduced_solve(WT, absWT, b, U, Mu, off_q, t, lower, upper, lo, up, rho, mu,
                                work, R, X, M, piv, small)
        if status == 0:
            status = _dense_free_solve(WT, absWT, b, t, lower, upper, lo, up, rho, mu, work,
                                       small, D, dpiv, x, index, trial, refine_steps,
                                       primal_factor, dual_factor)
        if status == 0:
            if it == 1:
                break
            # back to the sets of the last solve (rho, mu and lam are still its), one change;
            # where a single change made the sets singular (a bound joined that the free
            # weights cannot spare), that index may not join from these sets: the next
            # candidate joins, or a bound is released
            for k in range(K):
                if single and (lo[k] or up[k]) and not (saved[0, k] or saved[1, k]):
                    banned[k] = True
                lo[k], up[k] = saved[0, k], saved[1, k]
            single = True
            if _single_change(WT, absWT, t, dual_factor, lower, upper, rho, mu, lam, lo, up,
                              work[3], banned):
                break
            continue
        for k in range(K):
            banned[k] = False
        if precise and status == 1:
            _refine_reduced(WT, absWT, b, t, refine_steps, primal_factor, dual_factor, rho, mu,
                            work, X, M, piv, small)
        for k in range(K):
            saved[0, k], saved[1, k] = lo[k], up[k]
        settled = _apply_rule(single, WT, absWT, t, dual_factor, lower, upper, rho, mu, lam, lo,
                              up, work[3], banned)
        if not settled:
            continue
        if precise or status >= 2:  # the closed form, or a dense solve (refined already)
            return it, True
        _refine_reduced(WT, absWT, b, t, refine_steps, primal_factor, dual_factor, rho, mu, work,
                        X, M, piv, small)
        settled = _apply_rule(single, WT, absWT, t, dual_factor, lower, upper, rho, mu, lam, lo,
                              up, work[3], banned)
        if settled:
            return it, True
        precise = True
    for k in range(K):
        rho[k] = np.nan
        lam[k] = np.nan
    for j in range(m):
        mu[j] = np.nan
    return it, False


@_compiled
def pdas(WT, absWT, b, U, Mu, off_q, t, lower, upper, lo, up, from_closed_form, max_iter,
         refine_steps, primal_factor, dual_factor, rho, mu, lam, iterations, converged):
    """:func:`.qp._pdas` for colours ``b`` (N, m) from the active sets ``lo``/``up`` (N, K),
    which are updated in place; with ``from_closed_form`` the sets are first made from the
    bounds that the closed form violates (a colour violating none keeps its closed form,
    converged after 0 iterations)."""
    K, m = WT.shape[1], WT.shape[0]
    work = np.empty((10, K))
    R, X = np.empty((m + 1, K)), np.empty((m + 1, K))
    M = np.empty((m, m))
    piv = np.empty(m, dtype=np.int64)
    small = np.empty((3, m))
    saved = np.empty((3, K), dtype=np.bool_)  # the last solve's sets; indices banned
    D = np.empty((DENSE_FREE + m, DENSE_FREE + m))
    dpiv = np.empty(DENSE_FREE + m, dtype=np.int64)
    x = np.empty(DENSE_FREE + m)
    index = np.empty(DENSE_FREE + 1, dtype=np.int64)
    trial = np.empty(K + m)
    for n in range(b.shape[0]):
        if from_closed_form:
            _linear_map(b[n], U, rho[n])
            violated = False
            for k in range(K):
                lo[n, k] = rho[n, k] < lower
                up[n, k] = rho[n, k] > upper
                violated = violated or lo[n, k] or up[n, k]
            if not violated:
                _linear_map(b[n], Mu, mu[n])
                for k in range(K):
                    lam[n, k] = 0.0
                iterations[n], converged[n] = 0, True
                continue
        iterations[n], converged[n] = _pdas_one(
            WT, absWT, b[n], U, Mu, off_q, t, lower, upper, lo[n], up[n], max_iter, refine_steps,
            primal_factor, dual_factor, rho[n], mu[n], lam[n], work, R, X, M, piv, small, saved,
            D, dpiv, x, index, trial)


# --- the certificate's measures --------------------------------------------------------------


@_inline
def _measures_one(WT, absWT, t, b, rho, mu, lower, upper, bounded, primal_factor, dual_factor,
                  out, n, work, small):
    K, m = WT.shape[1], WT.shape[0]
    # 0 · x is 0 for every finite x and NaN for NaN and ±∞: one sum tells (and vectorises)
    probe = 0.0
    for k in range(K):
        probe += 0.0 * rho[k]
    for j in range(m):
        probe += 0.0 * mu[j]
    finite = probe == 0.0
    r, size = small[0], small[1]
    _colour_residual(WT, absWT, b, rho, r, size)
    residual_max, ratio = 0.0, 0.0
    for j in range(m):
        residual_max = max(residual_max, abs(r[j]))
        ratio = max(ratio, abs(r[j]) / max(primal_factor * size[j], TINY))
    lam, size_lam = work[0], work[2]
    _stationarity(WT, absWT, t, rho, mu, lam, size_lam)
    scale = dual_factor * EPS
    # per sample into work rows (each over the λ or size it was formed from), maxima after
    # the loop: a running maximum in the loop would keep it from vectorising
    off, quotient, wrong, excess = work[0], work[1], work[2], work[3]
    violation, wrong_max = 0.0, 0.0
    if not bounded:  # every |λ_k| must vanish
        for k in range(K):
            a = abs(lam[k])
            quotient[k] = a / max(scale * size_lam[k], TINY)
            off[k] = a
    else:
        for k in range(K):
            value, tolerance = lam[k], max(scale * size_lam[k], TINY)
            excess[k] = max(lower - rho[k], rho[k] - upper)
            w, o = 0.0, abs(value)
            if rho[k] == lower:
                w, o = max(-value, 0.0), 0.0
            elif rho[k] == upper:
                w, o = max(value, 0.0), 0.0
            wrong[k], off[k] = w, o
            quotient[k] = max(o, w) / tolerance
        violation = _maximum(excess)
        wrong_max = _maximum(wrong)
    off_max = _maximum(off)
    ratio = max(ratio, _maximum(quotient))
    out[0, n] = residual_max
    out[1, n] = violation
    out[2, n] = wrong_max
    out[3, n] = off_max
    # a row holding NaN or infinity is measured again by the NumPy path (its NaN semantics)
    out[4, n] = ratio if finite else np.inf


@_compiled
def measures(WT, absWT, t, b, rho, mu, lower, upper, bounded, primal_factor, dual_factor, out):
    """The certificate's measures (:func:`.certificate.certify`) into ``out`` (5, N): primal
    residual, bound violation, sign violation, stationarity and rounding ratio."""
    work = np.empty((4, WT.shape[1]))
    small = np.empty((2, WT.shape[0]))
    for n in range(b.shape[0]):
        _measures_one(WT, absWT, t, b[n], rho[n], mu[n], lower, upper, bounded, primal_factor,
                      dual_factor, out, n, work, small)


# --- membership --------------------------------------------------------------------------------


@_compiled
def facet_maxima(b, centre, NT, absolute, top, index):
    """Per colour ``b[n]`` (N, 3), the facet ``f`` of the normals ``NT`` (3, F) with the largest
    ``v_f = NT[:, f] · (b[n] − centre)`` (or ``|v_f|`` with ``absolute``; the first on ties,
    as ``numpy.argmax``): ``index[n] = f`` and ``top[n] = v_f`` (:func:`.zonotope.gauge`)."""
    F = NT.shape[1]
    values = np.empty(F)
    for n in range(b.shape[0]):
        d0, d1, d2 = b[n, 0] - centre[0], b[n, 1] - centre[1], b[n, 2] - centre[2]
        for f in range(F):
            values[f] = d0 * NT[0, f] + d1 * NT[1, f] + d2 * NT[2, f]
        if absolute:
            for f in range(F):
                values[f] = abs(values[f])
        best, k = -np.inf, 0
        for f in range(F):
            if values[f] > best:
                best, k = values[f], f
        index[n] = k
        top[n] = d0 * NT[0, k] + d1 * NT[1, k] + d2 * NT[2, k]


@_compiled
def roughness(rho, step_nm, out):
    """``Σ (ρ_{k+1} − ρ_k)² / h`` of each row of ``rho`` (N, K) into ``out`` (N,)
    (:meth:`.qp.Problem.objective`)."""
    for n in range(rho.shape[0]):
        out[n] = _smoothness(rho[n]) / step_nm
