"""The exact rational solver of the smoothest reflectance (recovery.exact), the boundary fallback.

Its answers are judged by the package's certificate and by the independent KKT check of
``kkt_check.py`` (which sees only ρ, and μ as a hint), never by the solver's own state.
"""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import spectrocolor as sc
from kkt_check import assert_kkt
from spectrocolor.recovery.certificate import certify
from spectrocolor.recovery.exact import MAX_SAMPLES, exact_solution
from spectrocolor.recovery.smoothest import smoothest_reflectance

RED_END = (380.0, 780.0, 10.0)

#: Two-transition block colours on 380–780/10 nm under D65 that the floating-point face and
#: dense solvers left flagged (measured before recovery.exact existed: 82 of 1 640 were, all
#: with an edge at 700–770 nm, where z̄ = 0 and the generators are parallel to 1e-4). Each is
#: (first, last) nm of the block of ones, or of the notch of zeros in the white.
FLAGGED_BLOCKS = [(400, 770), (420, 730), (510, 740), (550, 720), (640, 760)]
FLAGGED_NOTCHES = [(440, 730), (530, 750), (640, 700)]


def _weights(grid, illuminant="D65"):
    return np.asarray(sc.weights(sc.wavelength_grid(*grid), observer="1931", illuminant=illuminant))


def _flagged_colours():
    W = _weights(RED_END)
    grid = sc.wavelength_grid(*RED_END)
    R = []
    for (first, last), ones in [(p, True) for p in FLAGGED_BLOCKS] + [(p, False) for p in FLAGGED_NOTCHES]:
        inside = (grid >= first) & (grid <= last)
        R.append(np.where(inside == ones, 1.0, 0.0))
    return W, np.array(R)


def _certified(W, step, b, rho, mu, upper):
    return bool(certify(W, step, b[None], rho[None], mu[None], 0.0, upper, [True]).converged[0])


def test_previously_flagged_red_end_blocks_are_certified_by_the_exact_solver():
    W, R = _flagged_colours()
    for b in R @ W:
        got = exact_solution(W, RED_END[2], b, 0.0, 1.0)
        assert got is not None
        rho, mu = got
        assert _certified(W, RED_END[2], b, rho, mu, 1.0)
        assert_kkt(W, RED_END[2], rho, 1.0, mu_hint=mu)


@pytest.mark.slow
def test_previously_flagged_red_end_blocks_are_certified_by_smoothest_reflectance():
    W, R = _flagged_colours()
    r = smoothest_reflectance(R @ W, wavelengths=RED_END)
    # Which solver settles each colour (the compiled active set, the dense fallback, a face
    # solve, exact rationals) turns on rounding in the first iterations, so on the CPU's BLAS
    # kernel; what must hold on every CPU is the certificate and the independent KKT check.
    assert np.all(r.feasible) and np.all(r.certificate.converged)
    for rho, mu in zip(r.spectrum.values, r.multipliers, strict=True):
        assert_kkt(W, RED_END[2], rho, 1.0, mu_hint=mu)


@pytest.mark.slow
def test_a_red_notch_within_a_thousandth_of_the_white_is_certified():
    """380–780/1 nm, D65, the white with a notch at 712–765 nm: within 2⁻¹⁰ of the white, so
    first tried as ``white − XYZ`` in the cone, where ``Z`` (equal to the white's: z̄ = 0 in
    the notch) rounds to −1.4e-14 and the cone's answer cannot be certified. It was flagged
    (5 of 200 such blocks at 1 nm); the solid's own face solution now replaces the cone's."""
    grid = (380.0, 780.0, 1.0)
    W = _weights(grid)
    rho0 = np.where((sc.wavelength_grid(*grid) >= 712) & (sc.wavelength_grid(*grid) <= 765), 0.0, 1.0)
    r = smoothest_reflectance(rho0 @ W, wavelengths=grid)
    assert r.feasible and r.certificate.converged
    assert_kkt(W, grid[2], r.spectrum.values, 1.0, mu_hint=r.multipliers)


def test_a_vertex_of_a_three_sample_grid_has_the_multipliers_of_its_gradient():
    """W = I on three samples: b = (1, 0, 0) admits only ρ = (1, 0, 0); every sample's
    constraint is then its own, so μ = Q ρ = (2/h)(1, −1, 0) exactly (h = 10 nm: ±0.2 rounded)."""
    rho, mu = exact_solution(np.eye(3), 10.0, np.array([1.0, 0.0, 0.0]), 0.0, 1.0)
    # exact: exact rational arithmetic, each number rounded once to float (0.2 is 2/h rounded)
    assert rho.tolist() == [1.0, 0.0, 0.0] and mu.tolist() == [0.2, -0.2, 0.0]


def test_a_colour_outside_by_more_than_rounding_is_refused():
    """A block colour is on the boundary (its supporting plane does not pass through black), so
    1 + 1e-9 times it is outside the solid by 1e-9 of its size, far beyond the half primal
    tolerance (~1e-14) within which the nearest feasible colour may replace it."""
    W, R = _flagged_colours()
    assert exact_solution(W, RED_END[2], (R[2] @ W) * (1.0 + 1e-9), 0.0, 1.0) is None


def test_a_colour_with_no_z_keeps_z_exactly_zero():
    """Found by the hypothesis case below: the block 660–780 nm on 380–780/40 nm under E has
    Z = 0 (z̄ is zero there) and its rounded colour is 4e-16 outside the exact solid in Y. The
    nearest feasible colour in plain L1 buys that ulp back with 2e-20 of Z from 620 nm, which
    no tolerance relative to Z = 0 accepts; the relative L1 keeps Z = 0 exactly."""
    grid = (380.0, 780.0, 40.0)
    W = _weights(grid, "E")
    rho0 = np.zeros(W.shape[0])
    rho0[7:] = 1.0
    b = rho0 @ W
    assert b[2] == 0.0  # exact: each product is 0·z̄ or 1·0 (z̄ = 0 from 660 nm): any order sums to 0
    rho, mu = exact_solution(W, grid[2], b, 0.0, 1.0)
    assert _certified(W, grid[2], b, rho, mu, 1.0)
    # exact: ρ is exactly 0 wherever z̄ is not, so every product is 0 and any order sums to 0
    assert rho @ W[:, 2] == 0.0
    assert_kkt(W, grid[2], rho, 1.0, mu_hint=mu)


def test_grids_finer_than_the_limit_are_left_to_the_flag():
    """Above MAX_SAMPLES samples a solve would take minutes: no answer (the colour stays
    flagged), even for a colour the method solves (the constant half on W = [I; 0]; 30 s at
    MAX_SAMPLES samples, so that side is not run here)."""
    W = np.zeros((MAX_SAMPLES + 1, 3))
    W[:3] = np.eye(3)
    assert exact_solution(W, 1.0, np.array([0.5, 0.5, 0.5]), 0.0, 1.0) is None


def test_interior_colours_agree_with_the_floating_point_solver():
    """Two independent methods, one exact: on interior colours the float active-set solution is
    certified, and the optimum is unique (strictly convex programme), so they agree to the
    conditioning of the programme (1e-9 here is 1e4 times the certificate's own level)."""
    grid = (400.0, 700.0, 20.0)
    W = _weights(grid)
    rng = np.random.default_rng(7)
    b = rng.random((4, 16)) ** 3 @ W[:16] + 0.02 * W.sum(axis=0)
    r = smoothest_reflectance(b, wavelengths=grid)
    assert np.all(r.certificate.converged)
    for bi, rho_float in zip(b, r.spectrum.values, strict=True):
        rho, mu = exact_solution(W, grid[2], bi, 0.0, 1.0)
        assert _certified(W, grid[2], bi, rho, mu, 1.0)
        np.testing.assert_allclose(rho, rho_float, rtol=0, atol=1e-9)


def test_single_wavelength_colours_with_nonnegative_bounds():
    """Lines (one sample non-zero) are on edges of the cone of non-negative spectra; with
    ``upper = inf`` the simplex has no upper bounds on ρ."""
    grid = (380.0, 780.0, 5.0)
    W = _weights(grid)
    for k in (0, 50, 70, 80):  # 380, 630, 730, 780 nm
        b = W[k].copy()
        rho, mu = exact_solution(W, grid[2], b, 0.0, np.inf)
        assert _certified(W, grid[2], b, rho, mu, np.inf)
        assert_kkt(W, grid[2], rho, np.inf, mu_hint=mu)


@settings(max_examples=25, deadline=None)
@given(grid=st.sampled_from([(380.0, 780.0, 20.0), (380.0, 780.0, 40.0), (400.0, 700.0, 20.0),
                             (360.0, 820.0, 20.0)]),
       illuminant=st.sampled_from(["E", "D65", "A"]),
       data=st.data())
@pytest.mark.slow
def test_random_exact_boundary_and_vertex_sums_are_certified(grid, illuminant, data):
    """Random two-transition blocks (boundary colours) and random 0/1 spectra (sums of
    generators: on the boundary or inside) on coarse grids: the exact solver always certifies."""
    W = _weights(grid, illuminant)
    K = W.shape[0]
    if data.draw(st.booleans(), label="block"):
        first = data.draw(st.integers(0, K - 1), label="first")
        last = data.draw(st.integers(first, K - 1), label="last")
        rho0 = np.zeros(K)
        rho0[first:last + 1] = 1.0
        if data.draw(st.booleans(), label="notch"):
            rho0 = 1.0 - rho0
    else:
        rho0 = np.array(data.draw(st.lists(st.sampled_from([0.0, 1.0]), min_size=K, max_size=K),
                                  label="ones"))
    if rho0.min() == rho0.max():
        return  # black and white are exact by construction elsewhere
    b = rho0 @ W
    got = exact_solution(W, grid[2], b, 0.0, 1.0)
    assert got is not None
    rho, mu = got
    assert _certified(W, grid[2], b, rho, mu, 1.0)
    assert_kkt(W, grid[2], rho, 1.0, mu_hint=mu)
    assert smoothest_reflectance(b, illuminant=illuminant, wavelengths=grid).certificate.converged


@pytest.mark.slow
@pytest.mark.parametrize("illuminant", ["A"])
def test_every_red_end_block_is_certified(illuminant):
    """All 1 640 two-transition blocks on 380–780/10 nm: none flagged (57 under A were before
    the exact fallback; D65, 82 before, is guarded in test_smoothest.py), every one passes the
    independent check."""
    W = _weights(RED_END, illuminant)
    K = W.shape[0]
    R = []
    for i in range(K):
        for j in range(i, K):
            r = np.zeros(K)
            r[i:j + 1] = 1.0
            R += [r, 1.0 - r]
    R = np.unique(np.array(R), axis=0)
    R = R[(R.sum(axis=1) > 0) & (R.sum(axis=1) < K)]
    r = smoothest_reflectance(R @ W, illuminant=illuminant, wavelengths=RED_END)
    assert np.all(r.feasible) and np.all(r.certificate.converged)
    for rho, mu in zip(r.spectrum.values, r.multipliers, strict=True):
        assert_kkt(W, RED_END[2], rho, 1.0, mu_hint=mu)
