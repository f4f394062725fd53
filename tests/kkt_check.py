"""An independent optimality check for bounded smoothest reflectances, shared by the tests."""

import numpy as np


def assert_kkt(W, step, rho, upper=1.0):
    """Optimality shown from ρ alone: fit the multipliers μ on the free set, then check the signs
    of the bound multipliers (min Σ(Δρ)²/h subject to ρ @ W = b, 0 ≤ ρ ≤ upper)."""
    K = W.shape[0]
    D = (np.eye(K, k=1) - np.eye(K))[:-1]
    g = 2 * D.T @ D @ rho / step
    at_low, at_up = rho == 0.0, rho == upper
    free = ~(at_low | at_up)
    mu = np.linalg.lstsq(W[free], g[free], rcond=None)[0]
    lam = g - W @ mu
    scale = 1 + np.abs(g).max()
    assert np.abs(lam[free]).max(initial=0) < 1e-8 * scale
    assert lam[at_low].min(initial=0) > -1e-8 * scale
    assert lam[at_up].max(initial=0) < 1e-8 * scale
