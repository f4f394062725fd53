"""Optimal colours, MacAdam limits and the object-colour solid."""

import numpy as np
import pytest
from scipy.optimize import linprog
from scipy.spatial import ConvexHull

import spectrocolor as sc
from spectrocolor.recovery.optimal import macadam_limits, object_colour_membership, optimal_colours

GRID = (400.0, 700.0, 10.0)


def _weights(grid=GRID, illuminant="D65"):
    return np.asarray(sc.weights(sc.wavelength_grid(*grid), observer="1931", illuminant=illuminant))


def _lp_scale(W, XYZ):
    """Independent boundary test by linear programming: the largest t such that
    centre + t (XYZ − centre) is the colour of some 0 ≤ ρ ≤ 1 (t = 1 on the boundary)."""
    centre = W.sum(axis=0) / 2
    K = W.shape[0]
    out = []
    for x in XYZ:
        d = x - centre
        # variables ρ (K) and t: maximise t subject to ρ @ W − t d = centre
        res = linprog(np.r_[np.zeros(K), -1.0], A_eq=np.c_[W.T, -d], b_eq=centre,
                      bounds=[(0.0, 1.0)] * K + [(0.0, None)], method="highs")
        assert res.status == 0
        out.append(res.x[-1])
    return np.array(out)


@pytest.mark.parametrize(("grid", "illuminant"), [((400.0, 700.0, 10.0), "D65"),
                                                  ((380.0, 780.0, 10.0), "A"),
                                                  ((380.0, 780.0, 5.0), "D65")])
def test_optimal_colours_are_on_the_boundary(grid, illuminant):
    """Every point from a supporting hyperplane is on the boundary: the exact facet test gives
    depth 0 to rounding (1e-12), and so does an independent linear programme (to HiGHS's
    1e-7 feasibility tolerance); many of them have more than two transitions on these grids."""
    W = _weights(grid, illuminant)
    o = optimal_colours(illuminant=illuminant, wavelengths=grid, directions=400)
    np.testing.assert_allclose(o.reflectances @ W, o.XYZ100, rtol=0, atol=1e-12)
    m = object_colour_membership(o.XYZ100, illuminant=illuminant, wavelengths=grid)
    assert np.abs(m.relative_depth).max() < 1e-12
    np.testing.assert_allclose(_lp_scale(W, o.XYZ100[::20]), 1.0, atol=1e-7)
    # each maximises its direction: no 0/1 spectrum goes further
    blocks = (np.random.default_rng(0).random((2000, W.shape[0])) < 0.5) @ W
    assert np.all((blocks @ o.normals.T).max(axis=0) <= np.einsum("ij,ij->i", o.XYZ100, o.normals) + 1e-9)


def test_optimal_colours_agree_with_the_convex_hull_of_all_0_1_spectra():
    """On a grid small enough to list every 0/1 spectrum (400–700 nm at 50 nm: 2⁷), the hull of
    their colours is the solid: every optimal colour lies on it, and every hull vertex is the
    optimal colour of the directions of its normal cone."""
    grid = (400.0, 700.0, 50.0)
    W = _weights(grid)
    K = W.shape[0]
    R = ((np.arange(2**K)[:, None] >> np.arange(K)) & 1).astype(float)
    hull = ConvexHull(R @ W)
    o = optimal_colours(wavelengths=grid, directions=3000)
    offsets = o.XYZ100 @ hull.equations[:, :3].T + hull.equations[:, 3]
    scale = np.abs(R @ W).max()
    assert offsets.max() < 1e-12 * scale  # inside every facet of the hull ...
    assert np.all(np.abs(offsets).min(axis=1) < 1e-12 * scale)  # ... and on one of them
    # every vertex of the hull is the optimal colour of a direction inside its normal cone
    # (the sum of the normals of the hull's triangles that meet there)
    normals = np.array([hull.equations[np.any(hull.simplices == v, axis=1), :3].sum(axis=0)
                        for v in hull.vertices])
    at_vertices = optimal_colours(wavelengths=grid, directions=normals).XYZ100
    np.testing.assert_allclose(at_vertices, (R @ W)[hull.vertices], rtol=0, atol=1e-12 * scale)


def test_random_reflectances_inside_and_scaled_outside():
    W = _weights()
    rho = np.random.default_rng(0).random((500, W.shape[0]))
    m = object_colour_membership(rho @ W, wavelengths=GRID)
    assert np.all(m.inside) and np.all(m.relative_depth > 0)
    centre = W.sum(axis=0) / 2
    boundary = optimal_colours(wavelengths=GRID, directions=200).XYZ100
    out = centre + 1.01 * (boundary - centre)
    m_out = object_colour_membership(out, wavelengths=GRID)
    assert not m_out.inside.any() and np.all(m_out.distance_outside > 0)


@pytest.mark.parametrize(("grid", "illuminant", "Y"), [(GRID, "D65", 30.0), ((380.0, 780.0, 5.0), "A", 70.0),
                                                       ((380.0, 780.0, 20.0), "F2", 5.0)])
def test_macadam_limits_have_the_requested_luminance_and_are_on_the_boundary(grid, illuminant, Y):
    XYZ = macadam_limits(Y, illuminant=illuminant, wavelengths=grid, samples=90)
    np.testing.assert_allclose(XYZ[:, 1], Y, atol=1e-9)
    m = object_colour_membership(XYZ, illuminant=illuminant, wavelengths=grid)
    assert np.abs(m.relative_depth).max() < 1e-12
    np.testing.assert_allclose(_lp_scale(_weights(grid, illuminant), XYZ[::9]), 1.0, atol=1e-7)


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


def test_bad_arguments():
    with pytest.raises(sc.ColorimetryError, match="luminance_factor"):
        macadam_limits(100.0)
    with pytest.raises(sc.ColorimetryError, match="samples"):
        macadam_limits(50.0, samples=2)
    with pytest.raises(sc.ColorimetryError, match="directions"):
        optimal_colours(directions=[[0.0, 0.0, 0.0]])
    with pytest.raises(sc.ColorimetryError, match="directions"):
        optimal_colours(directions=0)
