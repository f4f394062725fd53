"""The smoothest reflectance in exact rational arithmetic: the last resort for boundary colours.

Near degenerate faces of the object-colour solid (the red end of the 1931 observer, where
``z̄ = 0`` and ``x̄ / ȳ`` is constant to the table's rounding, so that the generators are
parallel to 1e-4) the floating-point face solutions can miss rounding level by orders of
magnitude. The programme itself is small and its data exact: the weights ``W`` and the colour
``b`` are binary floating-point numbers, hence rationals, and the Hessian is ``2 / h`` times
the integer Laplacian ``L`` of a path. So it can be solved with no rounding at all
(:class:`fractions.Fraction`), and the exact solution rounded to the nearest doubles meets the
certificate of :mod:`.certificate` (whose tolerances are several ulps of the terms summed,
while rounding ρ and μ costs half an ulp of each).

1. **Nearest feasible colour.** ``b`` was itself rounded (``b = fl(R @ W)``), so it can lie
   outside the exact solid by about ε of the white. A bounded-variable simplex method (Bland's
   rule, three rows) minimises ``‖W.T ρ − b‖₁`` exactly; it ends at a vertex ``ρ₀`` of the
   feasible set of ``b' = W.T ρ₀``. The solution for ``b'`` is accepted for ``b`` only when
   ``|b' − b|`` is within half the certificate's primal tolerance, so that the other half still
   covers the rounding of ρ and of the evaluation.
2. **Primal active-set method** (Nocedal & Wright, Alg. 16.3) from ``ρ₀``, with a working set
   of bounds that leaves the free weights ``W_F`` of full rank, so that the multipliers μ are
   unique; a bound that blocks a step is independent of the working set (the step is in its
   null space), so the rank is kept. A boundary colour is handled like any other: the bounds
   fixed by its face never move, whether or not they are in the working set.
3. **Each step** is an equality-constrained programme: ``L_FF`` is tridiagonal on each run of
   consecutive free samples (Thomas algorithm, O(K) rational operations), followed by an
   ``m × m`` solve for μ (with one more unknown where every bound is released and ``L`` is
   singular on constants).

References
----------
J. Nocedal, S. J. Wright, *Numerical Optimization*, 2nd ed., Springer (2006), Alg. 16.3
(primal active-set method) and §13.5 (bounded-variable simplex method).
R. G. Bland, "New finite pivoting rules for the simplex method", Math. Oper. Res. 2,
103–107 (1977).
"""

from __future__ import annotations

from fractions import Fraction

import numpy as np

from .certificate import PRIMAL_FACTOR, gamma

#: Iterations of each exact method, per sample of the grid, before giving up (the active-set
#: method took at most 2.8 K steps on 140 random two-transition blocks at 10 and 5 nm).
ITERATIONS_PER_SAMPLE = 8
#: Largest grid solved exactly (1 nm over 360–840 nm). A step costs O(K) rational operations
#: and a solve about K steps: 4 s for a red-end block at 1 nm over 380–780 nm (K = 401), so
#: finer grids would take minutes per colour; their colours stay flagged instead.
MAX_SAMPLES = 481

_ZERO = Fraction(0)


def _solve_small(A: list[list[Fraction]], y: list[Fraction]) -> list[Fraction] | None:
    """``A x = y`` by Gaussian elimination in rationals (A square); None if A is singular."""
    n = len(y)
    M = [row[:] + [y[i]] for i, row in enumerate(A)]
    for c in range(n):
        p = next((r for r in range(c, n) if M[r][c] != 0), None)
        if p is None:
            return None
        M[c], M[p] = M[p], M[c]
        for r in range(c + 1, n):
            if M[r][c] != 0:
                f = M[r][c] / M[c][c]
                M[r] = [a - f * b for a, b in zip(M[r], M[c], strict=True)]
    x = [_ZERO] * n
    for c in range(n - 1, -1, -1):
        x[c] = (M[c][n] - sum(M[c][j] * x[j] for j in range(c + 1, n))) / M[c][c]
    return x


def _rank(rows: list[list[Fraction]]) -> int:
    """Exact rank of a small matrix given by its rows."""
    M = [r[:] for r in rows]
    rank, cols = 0, len(M[0]) if M else 0
    for c in range(cols):
        p = next((r for r in range(rank, len(M)) if M[r][c] != 0), None)
        if p is None:
            continue
        M[rank], M[p] = M[p], M[rank]
        for r in range(rank + 1, len(M)):
            if M[r][c] != 0:
                f = M[r][c] / M[rank][c]
                M[r] = [a - f * b for a, b in zip(M[r], M[rank], strict=True)]
        rank += 1
    return rank


class _Programme:
    """``min ρ L ρ / 2`` subject to ``W.T ρ = b``, ``lower ≤ ρ ≤ upper``, all exact."""

    def __init__(self, W: np.ndarray, lower: float, upper: float):
        self.K, self.m = W.shape
        self.W = [[Fraction(float(v)) for v in row] for row in W]
        self.lower = Fraction(float(lower))
        self.upper = Fraction(float(upper)) if np.isfinite(upper) else None
        self.degree = [(k > 0) + (k < self.K - 1) for k in range(self.K)]
        # see _run_solutions: (start, stop, left, right) -> {sample: its row of L_FF⁻¹ [W_F, t]}
        self._runs: dict[tuple[int, int, Fraction | None, Fraction | None], dict[int, list[Fraction]]] = {}

    def colour(self, rho) -> list[Fraction]:
        return [sum(rho[k] * self.W[k][j] for k in range(self.K) if rho[k]) for j in range(self.m)]

    def laplacian_times(self, rho, k) -> Fraction:
        out = self.degree[k] * rho[k]
        if k > 0:
            out -= rho[k - 1]
        if k < self.K - 1:
            out -= rho[k + 1]
        return out

    # -- phase one: a vertex of the feasible set of the nearest feasible colour ----------------

    def nearest_vertex(self, b: list[Fraction]):
        """A vertex ``ρ₀`` nearest to ``b`` in the relative L1 norm ``Σ_j |W.T ρ − b|_j / |b_j|``
        and the basic samples, or None.

        Columns: ρ_k (bounds ``[lower, upper]``), then for each row j a surplus ``s⁺_j`` and a
        slack ``s⁻_j`` (≥ 0, cost ``1 / |b_j|``) with ``Σ_k W_kj ρ_k − s⁺_j + s⁻_j = b_j``.
        Relative, because the certificate's primal tolerance is relative per component: a
        colour with ``Z = 0`` (all its power where z̄ = 0) must keep ``Z = 0`` exactly, however
        cheaply a little Z would buy back an ulp of Y; so where ``b_j = 0`` (and ρ = lower
        meets it) both are held at 0.
        """
        K, m = self.K, self.m
        n = K + 2 * m
        column = [[self.W[k][j] for j in range(m)] for k in range(K)]
        for j in range(m):
            column.append([Fraction(-1 if i == j else 0) for i in range(m)])
        for j in range(m):
            column.append([Fraction(1 if i == j else 0) for i in range(m)])
        residual = [b[j] - sum(self.W[k][j] * self.lower for k in range(K)) for j in range(m)]
        weight = [1 / abs(b[j]) if b[j] else 1 / abs(residual[j]) if residual[j] else _ZERO
                  for j in range(m)]
        cost = [_ZERO] * K + weight + weight
        low = [self.lower] * K + [_ZERO] * (2 * m)
        high = [self.upper] * K + [None if w else _ZERO for w in weight] * 2
        x = low[:]
        basis = []
        for j in range(m):
            if residual[j] >= 0:
                basis.append(K + m + j)
                x[K + m + j] = residual[j]
            else:
                basis.append(K + j)
                x[K + j] = -residual[j]
        for _ in range(ITERATIONS_PER_SAMPLE * n):
            B = [[column[q][i] for q in basis] for i in range(m)]
            # prices y solve B.T y = c_B
            y = _solve_small([list(r) for r in zip(*B, strict=True)], [cost[q] for q in basis])
            if y is None:
                return None
            entering = None
            in_basis = set(basis)
            for q in range(n):  # Bland: the lowest-indexed improving column
                if q in in_basis:
                    continue
                d = cost[q] - sum(y[i] * column[q][i] for i in range(m))
                if d < 0 and ((ceiling := high[q]) is None or x[q] < ceiling):
                    entering, sign = q, 1
                    break
                if d > 0 and x[q] > low[q]:
                    entering, sign = q, -1
                    break
            if entering is None:
                return x[:K], [q for q in basis if q < K]
            # basic values move by -sign * t * B⁻¹ a_q as the entering one moves by sign * t
            direction = _solve_small(B, column[entering])
            if direction is None:
                return None
            step = None if (ceiling := high[entering]) is None else ceiling - low[entering]
            leave = None
            for i, q in enumerate(basis):
                rate = -sign * direction[i]
                if rate < 0:
                    t = (x[q] - low[q]) / -rate
                elif rate > 0 and high[q] is not None:
                    t = (high[q] - x[q]) / rate
                else:
                    continue
                if step is None or t < step or (t == step and leave is not None and q < basis[leave]):
                    step, leave = t, i
            if step is None:  # unbounded: cannot happen, the cost is bounded below by 0
                return None
            for i, q in enumerate(basis):
                x[q] -= sign * step * direction[i]
            x[entering] += sign * step
            if leave is not None:
                q = basis[leave]
                # the leaving value is exactly at the bound it reached
                x[q] = low[q] if -sign * direction[leave] < 0 else high[q]
                basis[leave] = entering
        return None

    # -- phase two: the primal active-set method ---------------------------------------------

    def equality_solution(self, rho, free: list[bool], target: list[Fraction]):
        """Minimiser with the bounds outside ``free`` held at ``rho`` and ``W.T ρ = target``.

        Returns the free values (dict sample -> value) and the multipliers ν of ``L`` (those of
        ``Q = 2 L / h`` are ``2 ν / h``), or None where ``W_F.T L_FF⁻¹ W_F`` is singular. With
        every sample free ``L`` is singular (constants); sample 0 is then an extra unknown
        ``t`` and its own stationarity the extra equation.
        """
        K, m = self.K, self.m
        ground = all(free)
        if ground:  # L_FF⁻¹ t below is then the response to t = 1 at sample 0
            free, rho = [False] + free[1:], [Fraction(1)] + rho[1:]
        G = self._run_solutions(rho, free)
        c = [target[j] - sum(self.W[a][j] * rho[a] for a in range(K) if not free[a] and rho[a])
             for j in range(m)]
        S = [[sum(self.W[i][r] * G[i][s] for i in G) for s in range(m)] for r in range(m)]
        if not ground:
            nu = _solve_small(S, [c[r] - sum(self.W[i][r] * G[i][m] for i in G) for r in range(m)])
            if nu is None:
                return None
            return {i: sum(g[j] * nu[j] for j in range(m)) + g[m] for i, g in G.items()}, nu
        # unknowns (ν, t): W.T x = target and t − x_1 − (W ν)_0 = 0, x_i = G_i ν + g_i t
        A = [S[r] + [sum(self.W[i][r] * G[i][m] for i in G) + self.W[0][r]] for r in range(m)]
        A.append([-G[1][j] - self.W[0][j] for j in range(m)] + [1 - G[1][m]])
        z = _solve_small(A, list(target) + [_ZERO])
        if z is None:
            return None
        nu, t = z[:m], z[m]
        values = {i: sum(g[j] * nu[j] for j in range(m)) + g[m] * t for i, g in G.items()}
        values[0] = t
        return values, nu

    def _run_solutions(self, rho, free):
        """Per free sample i, row i of ``L_FF⁻¹ [W_F, t]`` (t: the fixed neighbours' values).

        ``L_FF`` is block diagonal, one tridiagonal block per run of consecutive free samples,
        and an active-set step changes one or two runs: each run's rows are kept, keyed by the
        run and its neighbours' values."""
        G = {}
        k = 0
        while k < self.K:
            if not free[k]:
                k += 1
                continue
            start = k
            while k < self.K and free[k]:
                k += 1
            key = (start, k, rho[start - 1] if start > 0 else None,
                   rho[k] if k < self.K else None)
            if key not in self._runs:
                self._runs[key] = self._run(start, k, key[2], key[3])
            G.update(self._runs[key])
        return G

    def _run(self, start, stop, left, right):
        """Rows ``start … stop − 1`` of ``L_FF⁻¹ [W_F, t]`` by the Thomas algorithm (a run with a
        fixed neighbour is positive definite: every pivot is positive)."""
        pivots: list[Fraction] = []
        ys: list[list[Fraction]] = []
        for i in range(start, stop):
            rhs = list(self.W[i])
            t = _ZERO
            if i == start and left is not None:
                t += left
            if i == stop - 1 and right is not None:
                t += right
            rhs.append(t)
            if pivots:
                p = pivots[-1]
                pivots.append(self.degree[i] - 1 / p)
                rhs = [r + y / p for r, y in zip(rhs, ys[-1], strict=True)]
            else:
                pivots.append(Fraction(self.degree[i]))
            ys.append(rhs)
        x = [y / pivots[-1] for y in ys[-1]]
        rows = {stop - 1: x}
        for i in range(stop - 2, start - 1, -1):
            x = [(y + v) / pivots[i - start] for y, v in zip(ys[i - start], x, strict=True)]
            rows[i] = x
        return rows

    def sign_margin(self, rho, nu, k) -> Fraction:
        """``σ_k λ_k`` (in units of L): ≥ 0 when the bound at sample k is correctly signed."""
        lam = self.laplacian_times(rho, k) - sum(self.W[k][j] * nu[j] for j in range(self.m))
        return lam if rho[k] == self.lower else -lam

    def with_rank(self, free: list[bool]) -> list[bool] | None:
        """``free`` enlarged (fewest samples, lowest index first) until ``W_F`` has rank m."""
        free = free[:]
        rows = [self.W[k] for k in range(self.K) if free[k]]
        have = _rank(rows) if rows else 0
        for k in range(self.K):
            if have == self.m:
                break
            if not free[k] and _rank(rows + [self.W[k]]) > have:
                free[k] = True
                rows.append(self.W[k])
                have += 1
        return free if have == self.m else None

    def active_set(self, rho, free, target):
        """The optimum from the feasible ``rho`` with working set ``not free``: (ρ, ν) or None."""
        rho, free = rho[:], free[:]
        for _ in range(ITERATIONS_PER_SAMPLE * self.K):
            got = self.equality_solution(rho, free, target)
            if got is None:
                return None
            values, nu = got
            step = {i: v - rho[i] for i, v in values.items() if v != rho[i]}
            if not step:
                margins = {k: self.sign_margin(rho, nu, k) for k in range(self.K) if not free[k]}
                worst = min(margins, key=lambda k: (margins[k], k), default=None)
                if worst is None or margins[worst] >= 0:
                    return rho, nu
                free[worst] = True
                continue
            length, block = Fraction(1), None
            for i, d in step.items():
                room = None
                if d < 0:
                    room = (self.lower - rho[i]) / d
                elif self.upper is not None:
                    room = (self.upper - rho[i]) / d
                if room is not None and (room < length or (room == length and block is not None
                                                           and i < block)):
                    length, block = room, i
            for i, d in step.items():
                rho[i] += length * d
            if block is not None:
                rho[block] = self.lower if step[block] < 0 else self.upper
                free[block] = False
        return None


def exact_solution(W: np.ndarray, step_nm: float, b: np.ndarray, lower: float, upper: float):
    """The smoothest ρ for one colour, computed exactly and rounded to float64.

    Parameters
    ----------
    W : ndarray (K, m)
        Weights, ``colour = ρ @ W``.
    step_nm : float
        Grid step h, nm (the Hessian is ``2 L / h``, L the path Laplacian).
    b : ndarray (m,)
        The colour, on the scale of ``W``.
    lower, upper : float
        Bounds of ρ (``upper = inf`` for ``ρ ≥ 0``).

    Returns
    -------
    tuple or None
        ``(rho (K,), mu (m,))`` rounded to the nearest doubles from the exact optimum for a
        colour ``b'`` within half the certificate's primal tolerance of ``b`` (``b`` itself
        when it is in the exact feasible set); None where the colour is farther outside, where
        the grid has more than :data:`MAX_SAMPLES` samples, or where the method gives up
        (:data:`ITERATIONS_PER_SAMPLE`).

    References
    ----------
    J. Nocedal, S. J. Wright, *Numerical Optimization*, 2nd ed., Springer (2006), Alg. 16.3.

    Examples
    --------
    Half of the white on a 3-sample grid whose weights are the identity: ρ is the constant
    one half, and the multipliers vanish.

    >>> rho, mu = exact_solution(np.eye(3), 10.0, np.array([0.5, 0.5, 0.5]), 0.0, 1.0)
    >>> rho.tolist(), mu.tolist()
    ([0.5, 0.5, 0.5], [0.0, 0.0, 0.0])
    """
    if W.shape[0] > MAX_SAMPLES:
        return None
    half = PRIMAL_FACTOR / 2 * gamma(W.shape[0] + 1)
    prog = _Programme(W, lower, upper)
    target = [Fraction(float(v)) for v in b]
    vertex = prog.nearest_vertex(target)
    if vertex is None:
        return None
    rho, basic = vertex
    reached = prog.colour(rho)
    if prog.upper is not None and any(  # farther than half the largest primal tolerance
            abs(reached[j] - target[j]) > Fraction(half) * (
                sum(abs(prog.W[k][j]) for k in range(prog.K)) * max(abs(prog.lower), abs(prog.upper))
                + abs(target[j])) for j in range(prog.m)):
        return None
    free = prog.with_rank([k in basic for k in range(prog.K)])
    if free is None:
        return None
    got = prog.active_set(rho, free, reached)
    if got is None:
        return None
    rho, nu = got
    # b' may replace b only within half the certificate's primal tolerance
    for j in range(prog.m):
        size = sum(abs(rho[k] * prog.W[k][j]) for k in range(prog.K)) + abs(target[j])
        if abs(reached[j] - target[j]) > Fraction(half) * size:
            return None
    scale = Fraction(2) / Fraction(float(step_nm))
    return (np.array([float(v) for v in rho]), np.array([float(scale * v) for v in nu]))
