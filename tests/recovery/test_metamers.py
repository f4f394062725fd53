"""Metamer mismatch regions and smooth metamers that differ under a second illuminant."""

import numpy as np
import pytest
from scipy.optimize import linprog

import spectrocolor as sc
from kkt_check import assert_kkt
from spectrocolor.recovery.metamerism import metamerism_index
from spectrocolor.recovery.metamers import (
    metamer_mismatch_region,
    most_different_metamer,
    smoothest_metamer,
)

GRID = (400.0, 700.0, 10.0)
GRID_NM = sc.wavelength_grid(*GRID)
W1 = np.asarray(sc.weights(GRID_NM, observer="1931", illuminant="D65"))
W2 = np.asarray(sc.weights(GRID_NM, observer="1931", illuminant="A"))


def _sample(i=1):
    tcs = sc.read_spectra(sc.__path__[0] + "/data/reflectances_cie_tcs.csv").resample(GRID_NM)
    return sc.Spectrum(GRID_NM, tcs.values[i])


def _random_metamers(rho, n, rng):
    """ρ plus metameric blacks (null space of W1ᵀ), scaled to stay within 0..1."""
    _, _, vt = np.linalg.svd(W1.T)
    null = vt[3:]
    out = []
    for _ in range(n):
        black = rng.normal(size=null.shape[0]) @ null
        with np.errstate(divide="ignore"):
            room = np.where(black > 0, (1 - rho) / black, np.where(black < 0, -rho / black, np.inf))
        out.append(rho + rng.random() * room.min() * black)
    return np.array(out)


def test_region_contains_random_metamers_and_extremes_are_exact():
    s = _sample()
    region = metamer_mismatch_region(s.values @ W1, wavelengths=GRID, directions=120)
    ext = region.extreme_metamers.values
    assert np.abs(ext @ W1 - region.XYZ100).max() <= 1e-10
    assert ext.min() >= 0 and ext.max() <= 1
    np.testing.assert_allclose(ext @ W2, region.boundary_XYZ100, atol=1e-12)
    # extreme metamers are 0/1 except at no more than three samples
    assert np.all(np.sum((ext > 1e-12) & (ext < 1 - 1e-12), axis=1) <= 3)
    others = _random_metamers(s.values, 300, np.random.default_rng(0))
    assert np.abs(others @ W1 - region.XYZ100).max() < 1e-10
    assert np.all(region.contains(others @ W2))
    assert region.contains(s.values @ W2)
    # the region is not a point: the colour differs under A between metamers
    assert np.ptp(region.boundary_XYZ100, axis=0).max() > 5


def test_support_agrees_with_an_interior_point_lp():
    """The support values equal those of an independent LP method (HiGHS interior point)."""
    s = _sample(5)
    region = metamer_mismatch_region(s.values @ W1, wavelengths=GRID, directions=12)
    for d, h in zip(region.directions, region.support, strict=True):
        res = linprog(-(W2 @ d), A_eq=W1.T, b_eq=s.values @ W1, bounds=[(0, 1)] * len(GRID_NM),
                      method="highs-ipm")
        assert -res.fun == pytest.approx(h, abs=1e-7)


def test_region_degenerates_on_the_boundary_of_the_solid():
    block = np.zeros(len(GRID_NM))
    block[:12] = 1.0  # a block spectrum from the short end: an optimal colour
    region = metamer_mismatch_region(block @ W1, wavelengths=GRID, directions=40)
    np.testing.assert_allclose(region.boundary_XYZ100, np.tile(block @ W2, (40, 1)), atol=1e-6)
    with pytest.raises(sc.ColorimetryError, match="outside the object-colour solid"):
        metamer_mismatch_region(1.01 * (block @ W1) - 0.01 * W1.sum(axis=0) / 2,
                                wavelengths=GRID)


def test_smoothest_metamer_matches_both_colours_exactly_and_is_optimal():
    s = _sample(3)
    region = metamer_mismatch_region(s.values @ W1, wavelengths=GRID, directions=30)
    ref2 = s.values @ W2
    targets = ref2 + np.linspace(0, 0.95, 6)[:, None] * (region.boundary_XYZ100[7] - ref2)
    r = smoothest_metamer(np.tile(s.values @ W1, (6, 1)), targets, wavelengths=GRID)
    rho = r.spectrum.values
    assert np.all(r.feasible) and np.all(r.certificate.converged)
    assert np.abs(rho @ W1 - s.values @ W1).max() <= 1e-10
    assert np.abs(rho @ W2 - targets).max() <= 1e-10
    assert rho.min() >= 0 and rho.max() <= 1
    W6 = np.concatenate([W1, W2], axis=1)
    for i in range(6):
        assert_kkt(W6, 10.0, rho[i])
    # smoother than the sample itself where the sample is one of the candidates (t = 0)
    assert r.roughness[0] <= np.sum(np.diff(s.values) ** 2) / 10.0 + 1e-12
    # roughness grows as the metamer is pushed towards the boundary of the region
    assert np.all(np.diff(r.roughness) > 0)


def test_infeasible_pairs():
    s = _sample()
    far = s.values @ W2 + np.array([30.0, -20.0, 0.0])
    with pytest.raises(sc.ColorimetryError, match="mismatch region"):
        smoothest_metamer(s.values @ W1, far, wavelengths=GRID)
    r = smoothest_metamer(np.stack([s.values @ W1] * 2), np.stack([far, s.values @ W2]),
                          wavelengths=GRID)
    assert r.feasible.tolist() == [False, True]
    assert np.all(np.isnan(r.spectrum.values[0]))


@pytest.mark.slow
def test_most_different_metamer_is_as_different_as_asked():
    s = _sample(7)
    results = [most_different_metamer(s, a, wavelengths=GRID, directions=60)
               for a in (0.0, 0.5, 0.9)]
    de = [r.delta_e_2000 for r in results]
    assert de[0] < 1e-6 and de[0] < de[1] < de[2] <= results[2].max_delta_e_2000
    for r in results:
        rho = r.metamer.spectrum.values
        assert np.abs(rho @ W1 - s.values @ W1).max() <= 1e-10
        assert rho.min() >= 0 and rho.max() <= 1
    # the CIE special metamerism index (change of illuminant) agrees
    m = results[2].metamer.spectrum
    assert metamerism_index(s, m) == pytest.approx(de[2], abs=1e-8)
    with pytest.raises(sc.ColorimetryError, match="amount"):
        most_different_metamer(s, 1.0, wavelengths=GRID)
