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
    # exact: Y = 40 is 8 × 5 and enters last: scaling by a power of two commutes with every rounding (no
    # under/overflow), so the same path on the same CPU gives exactly scaled numbers
    np.testing.assert_array_equal(signs[0], signs[1])  # linear in XYZ: Y only scales ρ
    # away from the boundary (rounding), polygon, predicate and brute force agree
    margin = np.abs(d._levels(xy)).min(axis=1) > 1e-9
    # exact: booleans, compared only 1e-9 or more away from the boundary
    np.testing.assert_array_equal(d.nonnegative(xy)[margin], signs[0][margin])
    # exact: booleans, compared only 1e-9 or more away from the boundary
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
def test_generating_functions_of_both_classes_and_their_luminance(illuminant):
    """ρ(λ; λ₁): the unconstrained smoothest reflectance of its chromaticity (independently
    recomputed), maximum 1, non-negative; class 2 zero with zero slope at λ₁, class 1 zero at an
    end with an inflection at λ₁; its luminance factor Y(λ₁) is the domain's maximum luminance
    factor there and never exceeds Y_M(λ₁), which is on the boundary of the solid."""
    from spectrocolor.recovery.optimal import object_colour_membership
    from spectrocolor.recovery.validity import generating_functions

    g = generating_functions(illuminant, wavelengths=GRID)
    K = len(g.wavelengths_nm)
    # ρ ≤ 1 computed twice, each from sums of at most 2K + 8 rounded terms (validity.
    # _rounding_bound); 64 K ε leaves room for terms up to 16 times the result
    tol = 64 * K * np.finfo(float).eps
    XYZ = g.luminance_factor[:, None] * 100 * _xyz(g.xy, 1.0)
    rho = smoothest_reflectance(XYZ, illuminant=illuminant, wavelengths=GRID, bounds=None).spectrum.values
    np.testing.assert_allclose(rho, g.reflectance, atol=tol)
    np.testing.assert_allclose(g.reflectance.max(axis=1), 1.0, atol=tol)
    assert g.reflectance.min() >= -tol
    on_grid = np.isin(g.lambda1_nm, g.wavelengths_nm)
    k = np.searchsorted(g.wavelengths_nm, g.lambda1_nm)
    rows = np.arange(len(k))
    two = (g.solution_class == "2") & on_grid
    r, kk = g.reflectance[two], k[two]
    assert two.sum() > 20 and np.all(g.zero_nm[two] == g.lambda1_nm[two])
    assert np.abs(r[rows[:len(kk)], kk]).max() <= tol  # zero at λ₁ ...
    assert np.abs(r[rows[:len(kk)], kk + 1] - r[rows[:len(kk)], kk - 1]).max() <= 2 * tol  # ... flat
    d = domain_of_validity(illuminant, wavelengths=GRID)
    for end in (0, -1):
        one = (g.solution_class == "1") & (g.zero_nm == g.wavelengths_nm[end])
        assert np.abs(g.reflectance[one, end]).max() <= tol
        inner = one & on_grid & (k > 0) & (k < K - 1)
        assert inner.sum() > 5
        r, kk = g.reflectance[inner], k[inner]
        n = rows[:len(kk)]
        bend = r[n, kk - 1] - 2 * r[n, kk] + r[n, kk + 1]  # inflection: no curvature at λ₁
        assert np.abs(bend).max() <= 4 * tol
        # each function is on its end line
        np.testing.assert_allclose(d._levels(g.xy[one])[:, end], 0.0, atol=tol)
    ymax = d.max_luminance_factor(g.xy)
    finite = np.isfinite(ymax)  # NaN where rounding puts a boundary point just outside
    assert finite.sum() > len(ymax) // 3
    np.testing.assert_allclose(g.luminance_factor[finite], ymax[finite], atol=tol)
    assert np.all(g.luminance_factor <= g.max_luminance_factor + tol)
    optimal = g.max_luminance_factor[:, None] * 100 * _xyz(g.xy, 1.0)
    depth = object_colour_membership(optimal, illuminant=illuminant, wavelengths=GRID).relative_depth
    assert np.abs(depth).max() < 1e-12


@pytest.mark.parametrize("illuminant", ["A", "D65"])
def test_class_1_family_covers_each_end_line_and_classes_agree_with_the_domain(illuminant):
    """The class-1 functions reach along each straight end line from one end point to the
    other (issue 27: at 1 nm there used to be 3 on the end lines in all); the class of each
    function's own chromaticity, read from the domain's boundary, is the function's class."""
    from spectrocolor.recovery.validity import _Family, generating_functions

    g = generating_functions(illuminant, wavelengths=GRID)
    d = domain_of_validity(illuminant, wavelengths=GRID)
    pieces = [p for p in d.boundary_pieces() if p.solution_class == "1"]
    assert sorted(p.zero_nm for p in pieces) == [GRID[0], GRID[1]]
    for piece in pieces:
        a, b = piece.xy[0], piece.xy[-1]
        rows = g.family("1", piece.zero_nm)
        t = (g.xy[rows] - a) @ (b - a) / ((b - a) @ (b - a))
        gaps = np.diff(np.sort(np.concatenate([[0.0, 1.0], t]))) * np.linalg.norm(b - a)
        # refined until neighbours are at most XY_STEP apart (and 1e-4 of a step in λ₁)
        assert gaps.max() <= _Family.XY_STEP * (1 + 1e-9)
    c = d.solution_class(g.xy)
    ends = np.concatenate([[p.xy[0], p.xy[-1]] for p in d.boundary_pieces()])
    clear = np.min(np.linalg.norm(g.xy[:, None] - ends[None], axis=-1), axis=1) > 1e-6
    # exact: class labels, compared only 1e-6 or more away from the ends of the classes
    np.testing.assert_array_equal(c.solution_class[clear], g.solution_class[clear])
    one = clear & (g.solution_class == "1")
    np.testing.assert_array_equal(c.zero_nm[one], g.zero_nm[one])  # exact: end wavelengths of the grid


def test_boundary_locus_branches_run_from_the_ends_to_the_white():
    from spectrocolor.recovery.validity import boundary_locus

    loc = boundary_locus("D65", wavelengths=GRID)
    np.testing.assert_allclose(loc.left_xy[-1], loc.white_xy, atol=1e-12)
    np.testing.assert_allclose(loc.right_xy[0], loc.white_xy, atol=1e-12)
    first = sc.xy(np.asarray(sc.weights(sc.wavelength_grid(*GRID), observer="1931", illuminant="D65"))[0])
    np.testing.assert_allclose(loc.left_xy[0], first, atol=1e-12)


# --- van Trigt's printed numbers (seed 004; values as quoted in issue 27, see docs/reflectance.md)
# Our copy of the seed marks the coordinates and line equations of the captions of Figs. 5–8
# "[withheld]"; issue 27 quotes them from the published captions. The paper's integrals are
# reproduced by our sums on 360–830 nm at 1 nm (the CIE tables' range and native step).
FULL = (360.0, 830.0, 1.0)


def test_end_line_equations_as_printed_for_A():
    """Fig. 7 caption (light source A, 360–830 nm): 0.8584x + 1.2291y = 1 and
    −26.58x + 20.60y = 1; tolerance: half a unit of the last printed digit."""
    (alpha_b, beta_b), (alpha_e, beta_e) = domain_of_validity("A", wavelengths=FULL).end_line_equations()
    assert abs(alpha_b - 0.8584) <= 0.5e-4 and abs(beta_b - 1.2291) <= 0.5e-4
    assert abs(alpha_e - -26.58) <= 0.5e-2 and abs(beta_e - 20.60) <= 0.5e-2


# Fig. 5 (D65): "Class 2b", λ₁ = 500 and 564 nm; Fig. 6 (D65): "Class 1b", λ₁ = 500 and 564 nm.
FIG5 = {500.0: (0.5455, 0.3829), 564.0: (0.1657, 0.0957)}
FIG6 = {500.0: (0.4500, 0.4707), 564.0: (0.5242, 0.4478)}
# one unit of the last printed digit: half for his rounding to 4 decimals, half for the
# difference between his quadrature and our 1 nm sums (the line equations above agree to
# every printed digit; our 2 nm sums move these points by at most 0.5e-4)
PRINTED_XY = 1e-4


def test_van_trigt_printed_points_land_in_the_class_his_captions_name():
    d = domain_of_validity("D65", wavelengths=FULL)
    c = d.solution_class(np.array([*FIG5.values(), *FIG6.values()]))
    # Fig. 5: interior zero (class 2) at the sample of λ₁; Fig. 6: zero at λ_b = 360 nm (class 1)
    assert c.solution_class.tolist() == ["2", "2", "1", "1"]
    assert c.zero_nm.tolist() == [500.0, 564.0, 360.0, 360.0]  # exact: wavelengths of the grid
    # each printed point is on the boundary to within the printed digits
    assert np.abs(c.boundary_xy - [*FIG5.values(), *FIG6.values()]).max() <= PRINTED_XY
    # independently: the unconstrained solution at the Fig. 5 points has its minimum at λ₁
    # and that minimum is zero to within what a move of PRINTED_XY in xy can change
    # ρ/max ρ (ρ_k ∝ a_k x + b_k y + c_k)
    levels = d._levels(np.array(list(FIG5.values())))
    slope = np.hypot(d.line_coefficients[:, 0], d.line_coefficients[:, 1]).max()
    rho = smoothest_reflectance(_xyz(np.array(list(FIG5.values())), 20.0), illuminant="D65",
                                wavelengths=FULL, bounds=None).spectrum.values
    # exact: wavelengths of the grid, picked where ρ has its zero (its neighbours are larger by
    # the curvature, far above rounding)
    np.testing.assert_array_equal(d.wavelengths_nm[rho.argmin(axis=1)], list(FIG5))
    assert np.all(np.abs(levels.min(axis=1)) <= 2 * PRINTED_XY * slope)


def test_generating_functions_reproduce_the_printed_points():
    from spectrocolor.recovery.validity import generating_functions

    g = generating_functions("D65", wavelengths=FULL, lambda1_nm=[500.0, 564.0])
    for cls, end, printed in (("2", None, FIG5), ("1", 360.0, FIG6)):
        rows = g.family(cls, end)
        assert g.lambda1_nm[rows].tolist() == list(printed)
        assert np.abs(g.xy[rows] - np.array(list(printed.values()))).max() <= PRINTED_XY


def test_cie_test_colours_all_but_9_and_12_inside_the_domain_under_D65():
    """Fig. 8: the CIE 13.3 test colour samples shipped with the package lie in the domain
    of validity under D65, all but 9 and 12."""
    from spectrocolor.lighting.spectra import tcs_reflectances

    grid = sc.wavelength_grid(*FULL)
    XYZ = tcs_reflectances(grid) @ np.asarray(sc.weights(grid, observer="1931", illuminant="D65"))
    inside = domain_of_validity("D65", wavelengths=FULL).nonnegative(sc.xy(XYZ))
    assert (np.flatnonzero(~inside) + 1).tolist() == [9, 12]
