"""An independent optimality check for bounded smoothest reflectances, shared by the tests.

It sees only ρ (and, where the free samples leave the multipliers undetermined, the solver's
multipliers as a *hint* for the undetermined part only): it builds the roughness gradient
``g = Q ρ`` itself, fits the multipliers μ of ``ρ @ W = b`` by least squares on the samples
off the bounds, and checks that the bound multipliers ``λ = g − W μ`` vanish off the bounds
and have the right signs on them (≥ 0 at 0, ≤ 0 at the upper bound). The programme is convex,
so these conditions prove optimality.

Tolerance, derived from rounding (not fitted to the solver). Let ``s_k = (|Q||ρ| + |W||μ|)_k``
be the sizes of the terms summed in ``λ_k``. The rounded exact minimiser satisfies the
conditions to within ``c ε s_k`` (ρ itself rounded, ε = 2⁻⁵²; the evaluation adds ``γ_6 s_k``),
and a solver that ends with iterative refinement leaves about as much again: we allow
``c = 64``, twice the solver certificate's own factor (32, see
``spectrocolor.recovery.certificate``), so that the verdict does not depend on the summation
order. The least-squares fit spreads the error of the free samples into μ and so into every
λ through ``W pinv(W_F)``; the check adds exactly that amplification,
``c ε |W pinv(W_F)| s_F``, which is large only where the free weights are nearly dependent
(the check is then as weak as the data, and says so by its size, not by a fixed 1e-8).
"""

import numpy as np

EPS = np.finfo(float).eps
FACTOR = 64.0


def _gradient(rho, step):
    d = np.diff(rho) * (2.0 / step)
    g = np.zeros_like(rho)
    g[:-1] -= d
    g[1:] += d
    a = np.abs(rho) * (2.0 / step)
    size = 2.0 * a
    size[0], size[-1] = a[0], a[-1]
    size[:-1] += a[1:]
    size[1:] += a[:-1]
    return g, size


def kkt_violation(W, step, rho, upper=1.0, mu_hint=None):
    """The largest KKT violation of ρ divided by its rounding tolerance (≤ 1: optimal)."""
    g, size_q = _gradient(rho, step)
    at_low, at_up = rho == 0.0, rho == upper  # exact: a bound is held as the bound value itself (set, not computed)
    free = ~(at_low | at_up)
    F = np.flatnonzero(free)
    m = W.shape[1]
    if F.size:
        U, sv, Vt = np.linalg.svd(W[F], full_matrices=False)
        rank = int(np.count_nonzero(sv > max(F.size, m) * EPS * sv[0]))
    else:
        U, sv, Vt, rank = np.zeros((0, 0)), np.zeros(0), np.eye(m), 0
    pinv = Vt[:rank].T @ (U[:, :rank] / sv[:rank]).T  # (m, |F|)
    mu = pinv @ g[F]
    for _ in range(2):  # iterative refinement of the fit: the SVD solve is only normwise stable
        mu = mu + pinv @ (g[F] - W[F] @ mu)
    if rank < m:  # the free samples do not determine μ: take the rest from the hint
        if mu_hint is None:
            raise AssertionError(f"free weights of rank {rank} < {m}: pass the multipliers")
        null = Vt[rank:].T
        mu = mu + null @ (null.T @ np.asarray(mu_hint, dtype=float))
    lam = g - W @ mu
    size = size_q + np.abs(W) @ np.abs(mu)
    spread = np.abs(W @ pinv) @ size[F] if F.size else np.zeros_like(size)
    tol = FACTOR * EPS * (size + spread)
    tol = np.maximum(tol, np.finfo(float).tiny)
    wrong = np.where(free, np.abs(lam), np.where(at_low, -lam, lam)).clip(min=0.0)
    fitted = float(np.max(wrong / tol))
    if mu_hint is None:
        return fitted
    # Any μ that meets the conditions proves optimality, so the hint itself is also checked
    # (g and the tolerance built here): on faces whose free weights are nearly coplanar the
    # fit's normal component is rounding noise, while the solver's is exact by construction.
    return min(fitted, _violation(g, size_q, W, np.asarray(mu_hint, dtype=float), free, at_low))


def _violation(g, size_q, W, mu, free, at_low):
    lam = g - W @ mu
    tol = np.maximum(FACTOR * EPS * (size_q + np.abs(W) @ np.abs(mu)), np.finfo(float).tiny)
    wrong = np.where(free, np.abs(lam), np.where(at_low, -lam, lam)).clip(min=0.0)
    return float(np.max(wrong / tol))


def assert_kkt(W, step, rho, upper=1.0, mu_hint=None):
    """Optimality of ρ for min Σ(Δρ)²/h subject to ρ @ W = b, 0 ≤ ρ ≤ upper, shown from ρ."""
    assert np.all(np.isfinite(rho))
    assert rho.min() >= 0.0 and rho.max() <= upper
    ratio = kkt_violation(W, step, rho, upper, mu_hint)
    assert ratio <= 1.0, f"KKT violated: {ratio:.3g} times the rounding tolerance"
