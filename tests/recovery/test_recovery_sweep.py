"""Every colour answered: property tests over grids, ranges and built-in illuminants.

Grids of 1, 5, 10 and 20 nm over 360–830, 380–780 and 400–700 nm, under every built-in
illuminant, with ``bounds="unit"`` and ``"nonnegative"``. The default run samples the set with
hypothesis; the exhaustive sweep (every combination, thousands of colours each) runs when
``SPECTROCOLOR_SWEEP=1`` is set and prints the counts it measured (docs/reflectance.md).

The independent check for each colour: no exception ever; feasible colours are feasible;
a converged result reproduces the colour to 1e-9 relative, keeps the bounds exactly and passes
the KKT check of ``tests/support/kkt_check.py``; infeasible colours are ``feasible=False`` with a
positive distance.
"""

import os

import numpy as np
import pytest
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

import spectrocolor as sc
from kkt_check import assert_kkt
from spectrocolor.illuminants import illuminant_names
from spectrocolor.recovery.optimal import optimal_colours
from spectrocolor.recovery.smoothest import smoothest_reflectance

STEPS = (1.0, 5.0, 10.0, 20.0)
RANGES = ((360.0, 830.0), (380.0, 780.0), (400.0, 700.0))
ILLUMINANTS = illuminant_names()


def _weights(grid, illuminant):
    """The weights, or None where the combination does not exist (a step that does not divide
    the range, an illuminant tabulated over a shorter range: both a clear error, tested
    where they are raised)."""
    try:
        grid_nm = sc.wavelength_grid(*grid)
        return np.asarray(sc.weights(grid_nm, observer="1931", illuminant=illuminant))
    except (sc.SpectrumError, sc.ColorimetryError):
        return None


def _colours(W, rng, n, hard=True):
    """Interior colours (random reflectances), colours at relative depth 1e-9 and on the
    boundary (vertices of the solid; only with ``hard``), black, white and colours 1 %
    outside."""
    K = W.shape[0]
    centre = W.sum(axis=0) / 2
    interior = rng.random((n, K)) ** 3 @ W
    edge = (rng.normal(size=(n, 3)) @ W.T > 0).astype(float) @ W
    near = centre + (edge - centre) * (1 - 1e-9)
    outside = centre + (edge[: n // 4] - centre) * 1.01
    special = np.stack([np.zeros(3), W.sum(axis=0)])
    if not hard:
        kinds = np.repeat(["interior", "special", "outside"], [n, 2, len(outside)])
        return np.concatenate([interior, special, outside]), kinds
    kinds = np.repeat(["interior", "near", "boundary", "special", "outside"],
                      [n, n, n, 2, len(outside)])
    return np.concatenate([interior, near, edge, special, outside]), kinds


def _check(grid, illuminant, bounds, b, kinds, W):
    """The property; returns the number of feasible colours flagged not converged by kind."""
    r = smoothest_reflectance(b, illuminant=illuminant, wavelengths=grid, bounds=bounds)  # never raises
    upper = 1.0 if bounds == "unit" else np.inf
    inside = kinds != "outside"
    assert np.all(r.feasible[inside])
    if bounds == "unit":
        assert not r.feasible[~inside].any() and np.all(r.distance_outside[~inside] > 0)
        assert np.all(np.isnan(r.spectrum.values[~inside]))
    ok = r.certificate.converged & r.feasible
    rho = r.spectrum.values
    assert np.all(ok[kinds == "interior"])  # ordinary colours are always certified
    scale = np.maximum(np.abs(b).max(axis=1), 1e-300)
    assert np.all(np.abs(rho[ok] @ W - b[ok]).max(axis=1) <= 1e-9 * scale[ok])
    assert rho[ok].min(initial=0.0) >= 0.0 and rho[ok].max(initial=0.0) <= upper
    for i in np.flatnonzero(ok)[:: max(1, ok.sum() // 40)]:
        assert_kkt(W, grid[2], rho[i], upper, mu_hint=r.multipliers[i])
    flagged = r.feasible & ~r.certificate.converged
    return {k: int(np.count_nonzero(flagged & (kinds == k))) for k in np.unique(kinds)}


@settings(max_examples=12, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(step=st.sampled_from(STEPS[1:]), span=st.sampled_from(RANGES),
       illuminant=st.sampled_from(ILLUMINANTS), bounds=st.sampled_from(["unit", "nonnegative"]),
       seed=st.integers(0, 2**32 - 1))
@pytest.mark.slow
def test_every_colour_answered_sampled(step, span, illuminant, bounds, seed):
    grid = (*span, step)
    W = _weights(grid, illuminant)
    assume(W is not None)
    b, kinds = _colours(W, np.random.default_rng(seed), 20)
    _check(grid, illuminant, bounds, b, kinds, W)


@pytest.mark.slow
def test_every_colour_answered_on_a_1_nm_grid():
    """K = 471: interior colours, black, white and outside ones (boundary colours on this grid
    take the dense one-at-a-time solvers: the exhaustive sweep covers them)."""
    grid = (360.0, 830.0, 1.0)
    W = _weights(grid, "D65")
    b, kinds = _colours(W, np.random.default_rng(1), 200, hard=False)
    _check(grid, "D65", "unit", b, kinds, W)


@pytest.mark.slow
def test_boundary_colours_from_supporting_planes_are_answered():
    """Optimal colours (on the boundary, many transitions): answered, exact where converged."""
    grid = (380.0, 780.0, 10.0)
    W = _weights(grid, "D65")
    b = optimal_colours(illuminant="D65", wavelengths=grid, directions=300).XYZ100
    _check(grid, "D65", "unit", b, np.full(len(b), "boundary"), W)


@pytest.mark.slow
@pytest.mark.skipif(not os.environ.get("SPECTROCOLOR_SWEEP"), reason="set SPECTROCOLOR_SWEEP=1")
def test_exhaustive_sweep(capsys):
    """Every combination; prints the flagged counts per combination and in total."""
    totals = {}
    for step in STEPS:
        for span in RANGES:
            for illuminant in ILLUMINANTS:
                grid = (*span, step)
                W = _weights(grid, illuminant)
                if W is None:
                    continue
                b, kinds = _colours(W, np.random.default_rng(0), 60, hard=step > 1)
                for bounds in ("unit", "nonnegative"):
                    counts = _check(grid, illuminant, bounds, b, kinds, W)
                    with capsys.disabled():
                        print(grid, illuminant, bounds, counts, flush=True)
                    for k, v in counts.items():
                        n = int(np.count_nonzero(kinds == k))
                        flagged, total = totals.get((bounds, k), (0, 0))
                        totals[(bounds, k)] = (flagged + v, total + n)
    with capsys.disabled():
        for (bounds, kind), (flagged, total) in sorted(totals.items()):
            print(f"{bounds:12} {kind:9} flagged {flagged} of {total}")
