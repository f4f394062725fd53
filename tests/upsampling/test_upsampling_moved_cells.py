"""Every colour inside the object-colour solid comes back exact, in any RGB space (issue 27).

A query is *inside* when the recovery's certified solver, run independently here
(:func:`spectrocolor.smoothest_reflectance`, its own membership test and certificate), finds a
reflectance for it. The table must then give a spectrum in [0, 1] that reproduces the query's
colour to EXACT relative; a colour outside the solid keeps the table's blend, is flagged
``exact=False`` and its path says "outside the object-colour solid".
"""

import numpy as np
import pytest

import spectrocolor as sc
from spectrocolor.upsampling import PATHS, colours_under, upsample
from spectrocolor.upsampling.moved_cells import settle
from upsampling_tables import rec2020_table, srgb_table, wide_table

# The acceptance criterion: the colour reproduced to 1e-9 relative. The settled paths
# are checked at 1e-10 (moved_cells.EXACT_TOLERANCE: rounding of β, at most cond · ε ≈ 4e-11,
# plus the K-term sum ρ @ W, ~ K ε ≈ 2e-14), so 1e-9 has a margin of ten.
EXACT = 1e-9
CODE = {name: code for code, name in PATHS.items()}


def relative_colour_error(table, t, rho):
    target = np.asarray(t) @ table.matrix.T
    error = np.abs(rho @ table.weights - target).max(axis=-1)
    return error / np.maximum(np.abs(target).max(axis=-1), np.finfo(float).tiny)


def inside_solid(table, t):
    """Independent verdict: the certified solver finds a reflectance (feasible and certified)."""
    result = sc.smoothest_reflectance(np.asarray(t) @ table.matrix.T, illuminant="D65",
                                      wavelengths=(380, 780, 5))
    return np.asarray(result.feasible) & np.asarray(result.certificate.converged)


def check_exact_wherever_a_reflectance_exists(table, t):
    u = upsample(table, t)
    inside = inside_solid(table, t)
    assert u.reflectance.min() >= 0.0 and u.reflectance.max() <= 1.0
    np.testing.assert_array_equal(u.exact, inside)  # exact: booleans, the same verdict
    assert relative_colour_error(table, t[inside], u.reflectance[inside]).max() <= EXACT
    assert np.all(u.path[~inside] == CODE["outside the object-colour solid"])
    assert not np.any(u.path == CODE["not settled"])
    # the plain blend misses some of these colours: the set does reach cells with moved nodes
    plain = upsample(table, t, settle_moved=False)
    assert np.any(inside & ~plain.exact)
    # exact: the same kernel, the same blend, where the grid weights were already exact
    np.testing.assert_array_equal(u.reflectance[plain.exact], plain.reflectance[plain.exact])
    return u, inside


@pytest.mark.slow
def test_rec2020_every_colour_inside_the_solid_is_exact_over_10000_uniform_colours():
    table = wide_table("Rec. 2020")
    t = np.random.default_rng(27).random((10_000, 3))
    u, inside = check_exact_wherever_a_reflectance_exists(table, t)
    counts = {PATHS[k]: int(np.count_nonzero(u.path == k)) for k in PATHS}
    print("Rec. 2020, 10 000 uniform linear colours:", int(inside.sum()), "inside;", counts)
    assert counts["certified solve"] > 0 and counts["actual node colours"] > 0


@pytest.mark.parametrize("space", ["Display P3", "Adobe RGB (1998)"])
def test_p3_and_adobe_rgb_every_colour_inside_the_solid_is_exact(space):
    table = wide_table(space)
    t = np.random.default_rng(3).random((3000, 3))
    check_exact_wherever_a_reflectance_exists(table, t)


def test_a_user_space_every_colour_inside_the_solid_is_exact():
    # a user space with a primary beyond the spectrum locus (x + y = 1 line): no reflectance
    # reaches its blue corner, and coarse cells leave a wide gap for the solver
    space = sc.RGBSpace.from_chromaticities((0.70, 0.29), (0.17, 0.80), (0.14, 0.03),
                                            (0.3127, 0.3290), name="wide test space")
    table = sc.upsampling_table(space, "D65", resolution=5, measure_excess=False)
    assert not table.all_exact
    t = np.random.default_rng(4).random((1500, 3))
    check_exact_wherever_a_reflectance_exists(table, t)


def test_colours_under_another_light_follow_the_settled_spectra():
    table = rec2020_table()
    t = np.random.default_rng(5).random((3000, 3))
    W_A = np.asarray(sc.weights(table.wavelengths_nm, illuminant="A"))
    u = upsample(table, t)
    XYZ, exact = colours_under(table, t, W_A)
    np.testing.assert_array_equal(exact, u.exact)  # exact: booleans, the same settling
    # linear in the spectra: equal to the spectra's colours to the rounding of K-term sums
    np.testing.assert_allclose(XYZ, u.reflectance @ W_A, rtol=0, atol=1e-12 * 110)
    assert np.any(u.path == CODE["certified solve"]) and np.any(u.path == CODE["actual node colours"])


def test_srgb_is_untouched_every_query_blends_exact_nodes():
    table = srgb_table()
    t = np.random.default_rng(6).random((2000, 3))
    u = upsample(table, t)
    assert u.exact.all() and np.all(u.path == CODE["exact nodes"])


def test_nan_strategy_keeps_nan_only_outside_the_solid():
    table = rec2020_table()
    t = np.random.default_rng(7).random((2000, 3))
    u = upsample(table, t, "nan")
    assert np.array_equal(np.isnan(u.reflectance).any(axis=-1), ~u.exact)  # exact: booleans
    assert np.any(~u.exact) and np.any(u.path == CODE["certified solve"])


def test_settle_refuses_a_query_in_a_cell_of_exact_nodes():
    with pytest.raises(ValueError, match="cell whose nodes are all exact"):
        settle(rec2020_table(), np.array([[0.5, 0.5, 0.5]]))
