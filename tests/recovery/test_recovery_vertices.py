"""Colours next to the object-colour solid's vertices and edges, and narrow-band colours at 1 nm.

The discrete solid's vertices are the 0/1 reflectances with two transitions at grid points (the
optimal colours; Schrödinger 1920, MacAdam 1935); its edges join two of them that differ in one
sample. Pulled toward grey by a relative depth of 1e-9 the feasible set is a sliver, all but a
few samples sit at a bound and the free weights are nearly dependent (condition up to about
1e8): these are the colours bench/bench_reflectance.py times as its vertex and edge sets. Every
one must come back certified, within the bounds, reproducing its colour, and optimal by the
independent KKT check of ``tests/support/kkt_check.py``. Nothing here is timed.
"""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import spectrocolor as sc
from kkt_check import assert_kkt
from spectrocolor.recovery import compiled
from spectrocolor.recovery.inputs import setup_for
from spectrocolor.recovery.smoothest import smoothest_reflectance

GRID = (380.0, 780.0, 10.0)
K = 41  # exact: samples of GRID, a test parameter


def _weights(grid=GRID, observer="1931"):
    return np.asarray(sc.weights(sc.wavelength_grid(*grid), observer=observer, illuminant="D65"))


def _pulled_in(W, rho, depth):
    centre = W.sum(axis=0) / 2
    return centre + (rho @ W - centre) * (1 - depth)


def _band(start, stop, partial=None):
    """1 on samples [start, stop), optionally ``partial`` at sample ``stop`` (an edge point)."""
    rho = np.zeros(K)
    rho[start:stop] = 1.0
    if partial is not None:
        rho[stop] = partial
    return rho


def _vertices():
    return np.array([_band(i, j) for i in range(K) for j in range(i + 1, K + 1) if j - i < K])


def _edges(rng):
    return np.array([_band(i, j, rng.uniform(0.05, 0.95)) for i in range(K) for j in range(i + 1, K)])


def _check(W, b, r, step):
    """Certified, in [0, 1], colour reproduced to rounding, optimal by the independent check.
    The round trip: 1e-12 of the colour's largest component is about 100 roundings of a 41-term
    sum of terms no larger than it (γ_41 ≈ 9e-15)."""
    rho = r.spectrum.values
    assert np.all(r.feasible) and np.all(r.certificate.converged)
    assert rho.min() >= 0.0 and rho.max() <= 1.0
    assert np.all(np.abs(rho @ W - b) <= 1e-12 * np.abs(b).max(axis=1, keepdims=True))
    for row in rho:
        assert_kkt(W, step, row, 1.0)


@pytest.mark.parametrize("depth", [1e-9, 1e-3])
def test_every_vertex_pulled_toward_grey_is_certified(depth):
    """All 1 720 vertices (bands and their complements) at relative depth 1e-9 and 1e-3."""
    W = _weights()
    rho = _vertices()
    b = _pulled_in(W, np.concatenate([rho, 1 - rho]), depth)
    _check(W, b, smoothest_reflectance(b, wavelengths=GRID), GRID[2])


@pytest.mark.parametrize("depth", [1e-9, 1e-3])
def test_every_edge_pulled_toward_grey_is_certified(depth):
    """1 640 points on edges (a band whose next sample is partial, and the complements)."""
    W = _weights()
    rho = _edges(np.random.default_rng(3))
    b = _pulled_in(W, np.concatenate([rho, 1 - rho]), depth)
    _check(W, b, smoothest_reflectance(b, wavelengths=GRID), GRID[2])


def test_vertex_colours_rarely_leave_the_batched_iterations():
    """Near the vertices at 1e-9 the batched active-set kernel settles almost every colour: the
    one-at-a-time dense primal active set (milliseconds a colour) takes at most 1 % (it took a
    quarter before the kernel solved ill-conditioned reduced systems on their dense KKT matrix)."""
    W = _weights()
    rho = _vertices()
    b = _pulled_in(W, np.concatenate([rho, 1 - rho]), 1e-9)
    r = smoothest_reflectance(b, wavelengths=GRID)
    assert np.mean(r.method == "dense primal active set") <= 0.01


@pytest.mark.skipif(compiled.kernels() is None, reason="numba is not installed")
def test_kernel_settles_on_ill_conditioned_free_sets():
    """From the optimal active sets, the kernel's active-set iterations settle in one iteration on
    every vertex colour at 1e-9, though most of their reduced matrices ``W_Fᵀ Q_FF⁻¹ W_F`` fail
    the determinant test (condition up to 1e16): the dense KKT solve of the free samples
    answers them, and the certificate accepts every result."""
    from spectrocolor.recovery import certificate

    setup = setup_for(GRID, "1931", "D65")[0]
    prob = setup.problem
    rho = _vertices()
    b = _pulled_in(prob.W, np.concatenate([rho, 1 - rho]), 1e-9)
    solved = smoothest_reflectance(b, wavelengths=GRID).spectrum.values
    found = compiled.kernels()
    # exact: values at a bound are held exactly (the certificate requires it): they are the sets
    out = compiled.pdas(found, prob, b, 0.0, 1.0, solved == 0.0, solved == 1.0, 60, 3)
    assert np.all(out[4]) and np.all(out[3] == 1)  # exact: iteration counts
    cert = certificate.certify(prob.W, prob.step_nm, b, out[0], out[1], 0.0, 1.0, out[4])
    assert np.all(cert.converged)


@settings(max_examples=40, deadline=None)
@given(start=st.integers(0, K - 1), length=st.integers(1, K - 1), complement=st.booleans(),
       partial=st.one_of(st.none(), st.floats(0.01, 0.99)),
       exponent=st.floats(-12.0, -2.0))
def test_property_colours_near_vertices_and_edges(start, length, complement, partial, exponent):
    """Any vertex or edge point (the band wraps to fit the grid), at any relative depth from 1e-12
    to 1e-2, comes back certified and optimal."""
    stop = min(start + length, K - (partial is not None))
    start = min(start, stop - 1)
    rho = _band(start, stop, partial if stop < K else None)
    if complement:
        rho = 1 - rho
    W = _weights()
    b = _pulled_in(W, rho[None], 10.0 ** exponent)
    _check(W, b, smoothest_reflectance(b, wavelengths=GRID), GRID[2])


@pytest.mark.parametrize("observer", ["1931", "1964"])
@pytest.mark.parametrize(("centre", "fwhm"), [(450.0, 5.0), (600.0, 15.0)])
def test_narrow_band_colours_at_1_nm_are_certified(observer, centre, fwhm):
    """Gaussian reflectances (FWHM 5 and 15 nm) at 1 nm: their colours lie within rounding of the
    solid's boundary (ρ underflows far from the band), and come back certified and optimal."""
    grid = (380.0, 780.0, 1.0)
    lam = np.asarray(sc.wavelength_grid(*grid))
    W = _weights(grid, observer)
    b = np.exp(-0.5 * ((lam - centre) / (fwhm / 2.3548200450309493)) ** 2) @ W
    r = smoothest_reflectance(b[None], wavelengths=grid, observer=observer)
    rho = r.spectrum.values
    assert np.all(r.certificate.converged)
    assert rho.min() >= 0.0 and rho.max() <= 1.0
    # 401-term sums: 1e-12 of the colour is about 30 γ_401 (γ_401 ≈ 9e-14)
    assert np.abs(rho[0] @ W - b).max() <= 1e-12 * np.abs(b).max()
    assert_kkt(W, grid[2], rho[0], 1.0)


@pytest.mark.skipif(compiled.kernels() is None, reason="the compiled kernels (numba) are not in use")
@pytest.mark.parametrize(("kind", "share"), [("vertex", 0.01), ("edge", 0.02)])
def test_compiled_iterations_rarely_need_the_interior_point_restart(kind, share):
    """With the kernels, the exchange step at exactly m free samples (a dual step of Goldfarb &
    Idnani) settles nearly every colour at 1e-9 from the vertices and edges in the batched
    iterations: the interior-point restart (NumPy, a fixed cost of tens of milliseconds a
    batch) takes at most 1 % of the vertices and 2 % of the edges (measured 0.6 % and 1.0 %;
    a fifth of either before the exchange)."""
    W = _weights()
    rho = _vertices() if kind == "vertex" else _edges(np.random.default_rng(3))
    b = _pulled_in(W, np.concatenate([rho, 1 - rho]), 1e-9)
    r = smoothest_reflectance(b, wavelengths=GRID)
    assert np.all(r.certificate.converged)
    assert np.mean(r.method == "active set restarted from interior point") <= share
