"""Narrow-band colours and colours with a vanishing component (issue 27, part 3).

A narrow red band under the 1964 observer has ``Z = 8e-105`` beside ``X = 2``: it lies on the
face ``ρ = 0 wherever z̄ > 0`` to far below rounding of X and Y, yet the certificate holds Z to
its own size. No facet solution can meet that, and such colours used to end in exact rational
arithmetic (20-60 s each at 1 nm). :func:`.face.lift_component` solves the vanishing component
at its own scale. The answers are judged by the package's certificate and by the independent
KKT check of ``kkt_check.py`` (which sees only ρ), never by the solver's own state.
"""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import spectrocolor as sc
from kkt_check import assert_kkt
from spectrocolor.recovery import dense_active_set, face
from spectrocolor.recovery.certificate import certify
from spectrocolor.recovery.inputs import setup_for
from spectrocolor.recovery.smoothest import EXACT_METHOD, smoothest_reflectance

FWHM_TO_SIGMA = 1.0 / (2.0 * np.sqrt(2.0 * np.log(2.0)))


def _gaussian_colour(grid, observer, centre_nm, fwhm_nm):
    lam = np.asarray(sc.wavelength_grid(*grid))
    W = np.asarray(sc.weights(lam, observer=observer, illuminant="D65"))
    return W, np.exp(-0.5 * ((lam - centre_nm) / (fwhm_nm * FWHM_TO_SIGMA)) ** 2) @ W


@pytest.mark.slow
@pytest.mark.parametrize(("observer", "centre_nm", "fwhm_nm"), [
    ("1964", 650.0, 10.0),  # Z = 8.1e-105: 21-57 s in rational arithmetic before the lift
    ("1964", 700.0, 15.0),  # Z = 1.8e-111
    ("1964", 660.0, 5.0),   # Z = 0 exactly (z̄₁₀ = 0 from 560 nm)
    ("1931", 700.0, 5.0),   # Z = 5.4e-132 (z̄ = 0 from 650 nm)
])
def test_a_band_whose_z_vanishes_is_certified_in_floating_point(observer, centre_nm, fwhm_nm):
    grid = (380.0, 780.0, 1.0)
    W, b = _gaussian_colour(grid, observer, centre_nm, fwhm_nm)
    assert b[2] <= 1e-100 * b[0]  # the case this test is about
    r = smoothest_reflectance(b, wavelengths=grid, observer=observer)
    assert r.feasible and r.certificate.converged
    assert r.method != EXACT_METHOD
    rho = r.spectrum.values
    assert_kkt(W, grid[2], rho, 1.0, mu_hint=r.multipliers)
    # Z is reproduced relative to its own size: one product ρ_j z̄_j carries it (each rounded
    # once, the sum exact as the other terms are 0), so within a few ulps of Z (0 stays 0)
    assert abs(rho @ W[:, 2] - b[2]) <= 4 * np.finfo(float).eps * b[2]


def test_the_lift_reproduces_a_tiny_z_on_a_coarse_grid():
    """380–780/10 nm, 1931, D65: the band 660–720 nm (z̄ = 0 there) plus 1e-40 of one sample
    where z̄ > 0. The zeroed colour's solution has ρ = 0 wherever z̄ > 0; the lift puts
    ``Z / z̄_j`` on one sample and chooses ``μ_Z`` so that every other bound stays signed."""
    grid = (380.0, 780.0, 10.0)
    setup = setup_for(grid, "1931", "D65")[0]
    W, Q = setup.W, setup.problem.hessian_dense()
    lam = np.asarray(sc.wavelength_grid(*grid))
    rho0 = ((lam >= 660) & (lam <= 720)) * 0.5
    rho0[lam == 600] = 1e-40
    b = rho0 @ W
    assert 0 < b[2] < 1e-38
    assert face.liftable_components(W, b, 0.0) == [2]
    base = face.zero_component_solution(W, Q, b, 2, 0.0, 1.0)
    assert base is not None
    assert np.all(base[0][W[:, 2] > 0] == 0.0)  # exact: those samples are pinned at the bound
    rho, mu = face.lift_component(W, Q, b, 2, *base, 1.0)
    assert certify(W, grid[2], b[None], rho[None], mu[None], 0.0, 1.0, [True]).converged[0]
    assert_kkt(W, grid[2], rho, 1.0, mu_hint=mu)


def test_only_vanishing_components_over_zero_weights_are_lifted():
    setup = setup_for((380.0, 780.0, 10.0), "1931", "D65")[0]
    W = setup.W
    assert face.liftable_components(W, np.array([2.0, 1.0, 1e-30]), 0.0) == [2]
    assert face.liftable_components(W, np.array([2.0, 1.0, 0.0]), 0.0) == [2]
    assert face.liftable_components(W, np.array([2.0, 1.0, 1e-3]), 0.0) == []  # not vanishing
    assert face.liftable_components(W, np.array([1e-30, 1.0, 1.0]), 0.0) == []  # x̄ has no zeros
    assert face.liftable_components(W, np.zeros(3), 0.0) == []  # black is its own case
    assert face.liftable_components(W, np.array([2.0, 1.0, 0.0]), 0.1) == []  # lower bound not 0


def _random_kkt(rng, K, m, step_nm):
    """The roughness Hessian's free block for a random free set, and random weights on it."""
    Q = (2.0 / step_nm) * (np.diag(np.r_[1.0, np.full(K - 2, 2.0), 1.0])
                           - np.diag(np.ones(K - 1), 1) - np.diag(np.ones(K - 1), -1))
    free = np.sort(rng.choice(K, size=rng.integers(m, K), replace=False))
    W = rng.uniform(0.0, 2.0, size=(K, m))
    return Q, W, free


@settings(max_examples=60, deadline=None)
@given(seed=st.integers(0, 2**32 - 1), m=st.integers(1, 3))
def test_the_banded_kkt_solve_agrees_with_the_dense_one(seed, m):
    """The structured solve (banded Cholesky and Schur complement) against LAPACK's dense LU
    of the same KKT matrix. Both are backward stable for these well-conditioned systems
    (condition below 1e6 here); the tolerance is 1e4 ulps of the solution's scale, far above
    either's rounding and far below any wrong answer (a wrong band or sign is O(1))."""
    rng = np.random.default_rng(seed)
    Q, W, free = _random_kkt(rng, 24, m, 5.0)
    n = free.size
    kkt = np.zeros((n + m, n + m))
    kkt[:n, :n] = Q[np.ix_(free, free)]
    kkt[:n, n:] = -W[free]
    kkt[n:, :n] = W[free].T
    rhs = rng.normal(size=n + m)
    if np.linalg.cond(kkt) > 1e6:
        return
    dense = np.linalg.solve(kkt, rhs)
    diag = np.diagonal(Q)[free]
    off = np.where(np.diff(free) == 1, np.diagonal(Q, 1)[free[:-1]], 0.0)
    banded = dense_active_set._banded_kkt_solve(diag, off, W[free], rhs[:n], rhs[n:])
    assert banded is not None
    assert np.max(np.abs(banded - dense)) <= 1e4 * np.finfo(float).eps * np.abs(dense).max()


def test_a_hessian_that_is_not_tridiagonal_takes_the_dense_solve():
    """``equality_qp`` must not use the banded path for a Q with entries off its three
    diagonals: the answer then equals the dense KKT solution, not the banded one's."""
    rng = np.random.default_rng(7)
    Q, W, free = _random_kkt(rng, 12, 3, 10.0)
    Q = Q + 0.05 * np.eye(12, k=3) + 0.05 * np.eye(12, k=-3)
    assert not dense_active_set.is_tridiagonal(Q)
    active = np.ones(12, dtype=bool)
    active[free] = False
    rho = np.where(active, 0.3, 0.0)
    b = rng.uniform(1.0, 2.0, 3)
    got = dense_active_set.equality_qp(Q, W, b, rho, active)
    assert got is not None
    x, mu = got
    # stationarity on the free samples and the colour, with the full Q: to rounding of terms
    station = (Q @ x - W @ mu)[free]
    scale = np.abs(Q) @ np.abs(x) + np.abs(W) @ np.abs(mu)
    assert np.all(np.abs(station) <= 1e3 * np.finfo(float).eps * scale[free])
    assert np.allclose(x @ W, b, rtol=1e3 * np.finfo(float).eps, atol=0)
