"""Optimal colours, MacAdam limits and the object-colour solid."""

import numpy as np
import pytest

import spectrocolor as sc
from spectrocolor.recovery.optimal import macadam_limits, object_colour_membership, optimal_colours

GRID = (400.0, 700.0, 10.0)


def test_block_spectra_lie_on_the_boundary():
    """Schrödinger: two-transition block spectra are optimal (gauge 1) for D65 and A — on the
    discrete grid not all of them (West & Brill's conditions fail in the long-wavelength tail,
    where x̄/ȳ is nearly constant), but the blocks that start at the short end all are."""
    for ill in ("D65", "A"):
        starts, XYZ = optimal_colours(ill, wavelengths=GRID)
        m = object_colour_membership(XYZ, ill, wavelengths=GRID)
        assert np.all(m.inside)
        assert np.abs(m.relative_depth[starts[:, 0] == 0]).max() < 1e-12
        assert np.mean(np.abs(m.relative_depth) < 1e-12) > 0.5


def test_random_reflectances_inside_and_scaled_outside():
    W = np.asarray(sc.weights(sc.wavelength_grid(*GRID), "1931", "D65"))
    rho = np.random.default_rng(0).random((500, W.shape[0]))
    m = object_colour_membership(rho @ W, wavelengths=GRID)
    assert np.all(m.inside) and np.all(m.relative_depth > 0)
    centre = W.sum(axis=0) / 2
    _, boundary = optimal_colours(wavelengths=GRID)
    out = centre + 1.01 * (boundary - centre)
    m_out = object_colour_membership(out, wavelengths=GRID)
    assert not m_out.inside.any() and np.all(m_out.distance_outside > 0)


def test_macadam_limits_have_the_requested_luminance_and_are_optimal():
    XYZ = macadam_limits(30.0, wavelengths=GRID)
    np.testing.assert_allclose(XYZ[:, 1], 30.0, atol=1e-9)
    m = object_colour_membership(XYZ, wavelengths=GRID)
    assert np.all(m.inside)
    assert np.median(np.abs(m.relative_depth)) < 1e-12  # see the Schrödinger caveat above


def test_macadam_limits_agree_with_colour_science():
    """Points just inside/outside our Y = 20 % limit are inside/outside colour-science's."""
    colour = pytest.importorskip("colour")
    xy = sc.xy(macadam_limits(20.0, wavelengths=(380, 780, 5), samples=60))
    white = np.array([0.3127, 0.3290])
    for factor, expected in ((0.97, True), (1.03, False)):
        pts = white + factor * (xy - white)
        xyY = np.concatenate([pts, np.full((len(pts), 1), 0.2)], axis=1)
        inside = [colour.volume.is_within_macadam_limits(p, "D65") for p in xyY]
        assert np.mean(np.array(inside) == expected) > 0.9


def test_bad_luminance():
    with pytest.raises(sc.ColorimetryError, match="luminance_factor"):
        macadam_limits(100.0)
