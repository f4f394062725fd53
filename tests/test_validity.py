"""Domains of validity of the unconstrained smoothest reflectance (van Trigt 1990, Figs. 7–12)."""

import numpy as np
import pytest

import spectrocolor as sc
from spectrocolor.recovery.smoothest import smoothest_reflectance
from spectrocolor.recovery.validity import domain_of_validity

GRID = (380.0, 780.0, 10.0)


def _xyz(xy, Y):
    x, y = xy[..., 0], xy[..., 1]
    return np.stack([x / y * Y, np.full_like(x, Y), (1 - x - y) / y * Y], axis=-1)


def _chromaticity_grid(step=0.01):
    x, y = np.meshgrid(np.arange(0.005, 0.8, step), np.arange(0.005, 0.85, step))
    xy = np.stack([x.ravel(), y.ravel()], axis=1)
    return xy[xy.sum(axis=1) < 1]


def _inside_polygon(poly, pts):
    """Inside a counter-clockwise convex polygon: left of every edge."""
    e = np.roll(poly, -1, axis=0) - poly
    rel = pts[:, None, :] - poly[None]
    return np.all(e[None, :, 0] * rel[..., 1] - e[None, :, 1] * rel[..., 0] >= 0, axis=1)


@pytest.mark.parametrize("illuminant", ["D65", "A"])
def test_region_matches_brute_force_and_does_not_depend_on_Y(illuminant):
    d = domain_of_validity(illuminant, wavelengths=GRID)
    xy = _chromaticity_grid()
    signs = []
    for Y in (5.0, 40.0):
        rho = smoothest_reflectance(_xyz(xy, Y), illuminant=illuminant, wavelengths=GRID,
                                    bounds=None).spectrum.values
        signs.append(rho.min(axis=1) >= 0)
    np.testing.assert_array_equal(signs[0], signs[1])  # linear in XYZ: Y only scales ρ
    # away from the boundary (rounding), polygon, predicate and brute force agree
    margin = np.abs(d._levels(xy)).min(axis=1) > 1e-9
    np.testing.assert_array_equal(d.nonnegative(xy)[margin], signs[0][margin])
    np.testing.assert_array_equal(_inside_polygon(d.region_xy, xy)[margin], signs[0][margin])
    assert signs[0].sum() > 100  # a real region
    # white is inside; the region lies within the spectral locus
    assert d.nonnegative(sc.xy(sc.white_point(illuminant)))
    _, locus = sc.spectral_locus("1931")
    assert np.all(d.region_xy[:, 1] > 0)
    assert d.region_xy[:, 0].max() < np.max(locus[:, 0]) + 1e-9


def test_boundary_contains_the_end_lines():
    """Van Trigt: straight lines where ρ vanishes at λ_b and at λ_e bound the region (the
    rest of the boundary is the envelope of interior minima touching zero)."""
    for ill in ("D65", "A"):
        d = domain_of_validity(ill, wavelengths=GRID)
        assert 380.0 in d.edge_wavelengths_nm and 780.0 in d.edge_wavelengths_nm
        for k, line in zip((0, -1), d.end_lines(), strict=True):
            edge = np.flatnonzero(d.edge_wavelengths_nm == d.wavelengths_nm[k])[0]
            ends = d.region_xy[[edge, (edge + 1) % len(d.region_xy)]]
            np.testing.assert_allclose(ends @ line[:2] + line[2], 0, atol=1e-12)
            # on that edge the solution is zero at the end sample and positive elsewhere
            rho = smoothest_reflectance(_xyz(ends.mean(axis=0), 30.0), illuminant=ill, wavelengths=GRID,
                                        bounds=None).spectrum.values
            assert abs(rho[k]) < 1e-12 and np.delete(rho, k).min() > 0


@pytest.mark.parametrize("illuminant", ["D65", "A"])
def test_max_luminance_factor_is_where_rho_reaches_one(illuminant):
    d = domain_of_validity(illuminant, wavelengths=GRID)
    xy = _chromaticity_grid(0.03)
    xy = xy[d.nonnegative(xy) & (np.abs(d._levels(xy)).min(axis=1) > 1e-6)]
    ymax = d.max_luminance_factor(xy)
    assert np.all((ymax > 0) & (ymax <= 1 + 1e-9))
    for factor, below in ((0.999, True), (1.001, False)):
        r = smoothest_reflectance(_xyz(xy, 100 * factor * ymax), illuminant=illuminant,
                                  wavelengths=GRID, bounds=None).spectrum.values
        assert np.all((r.max(axis=1) <= 1) == below)
    # below the limit the bounded (unit) and unconstrained solutions coincide
    b = _xyz(xy, 90 * ymax)
    np.testing.assert_allclose(
        smoothest_reflectance(b, illuminant=illuminant, wavelengths=GRID).spectrum.values,
        smoothest_reflectance(b, illuminant=illuminant, wavelengths=GRID, bounds=None).spectrum.values,
        atol=1e-12)
    # the white of the same weights reaches Y/Y0 = 1 (the constant reflectance 1)
    white = np.asarray(sc.weights(sc.wavelength_grid(*GRID), observer="1931", illuminant=illuminant)).sum(axis=0)
    assert d.max_luminance_factor(sc.xy(white)) == pytest.approx(1.0, abs=1e-12)
    assert np.isnan(d.max_luminance_factor([0.7, 0.25]))


def test_bad_chromaticities():
    d = domain_of_validity("D65", wavelengths=GRID)
    with pytest.raises(sc.ColorimetryError, match="xy"):
        d.nonnegative([0.3, 0.3, 0.4])


@pytest.mark.parametrize("illuminant", ["A", "D65"])
def test_generating_functions_touch_zero_with_zero_slope_and_stay_below_the_optimal_colour(illuminant):
    """ρ(λ; λ₁): the unconstrained smoothest reflectance of its chromaticity (independently
    recomputed), maximum 1, zero at the two samples around λ₁ (zero slope there); its
    luminance factor Y(λ₁) never exceeds Y_M(λ₁), which is on the boundary of the solid."""
    from spectrocolor.recovery.optimal import object_colour_membership
    from spectrocolor.recovery.validity import generating_functions

    g = generating_functions(illuminant, wavelengths=GRID)
    XYZ = g.luminance_factor[:, None] * 100 * _xyz(g.xy, 1.0)
    rho = smoothest_reflectance(XYZ, illuminant=illuminant, wavelengths=GRID, bounds=None).spectrum.values
    np.testing.assert_allclose(rho, g.reflectance, atol=1e-9)
    np.testing.assert_allclose(g.reflectance.max(axis=1), 1.0, atol=1e-12)
    interior = g.solution_class == "1"
    assert interior.sum() > 20 and (~interior).sum() >= 2
    k = np.searchsorted(g.wavelengths_nm, g.touch_nm[interior])
    rows = g.reflectance[interior]
    around = np.abs(np.stack([rows[np.arange(len(k)), k - 1], rows[np.arange(len(k)), k]]))
    assert around.max() < 1e-9 and rows.min() > -1e-9
    assert np.all(g.luminance_factor <= g.max_luminance_factor + 1e-12)
    optimal = g.max_luminance_factor[:, None] * 100 * _xyz(g.xy, 1.0)
    depth = object_colour_membership(optimal, illuminant=illuminant, wavelengths=GRID).relative_depth
    assert np.abs(depth).max() < 1e-12


def test_boundary_locus_branches_run_from_the_ends_to_the_white():
    from spectrocolor.recovery.validity import boundary_locus

    loc = boundary_locus("D65", wavelengths=GRID)
    np.testing.assert_allclose(loc.left_xy[-1], loc.white_xy, atol=1e-12)
    np.testing.assert_allclose(loc.right_xy[0], loc.white_xy, atol=1e-12)
    first = sc.xy(np.asarray(sc.weights(sc.wavelength_grid(*GRID), observer="1931", illuminant="D65"))[0])
    np.testing.assert_allclose(loc.left_xy[0], first, atol=1e-12)
