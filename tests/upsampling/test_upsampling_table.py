"""The upsampling table: nodes certified and re-checked, moved nodes honest, excess bounded."""

import numpy as np
import pytest

import spectrocolor as sc
from kkt_check import assert_kkt
from spectrocolor.upsampling import upsample, upsampling_table
from spectrocolor.upsampling.table import NODE_TOLERANCE, node_coordinates
from upsampling_tables import rec2020_table, srgb_table

# Roughness values are ~1e-2 nm⁻¹ and each is a sum of K = 81 squares computed to ~1e-16
# relative; the exact optimum from the solver is certified to 1e-12 relative in colour. 1e-9
# (absolute, nm⁻¹) is far above both and far below the excesses measured (~1e-4).
ROUGHNESS_ROUNDING = 1e-9


def test_srgb_nodes_exact_and_reproduce_their_nominal_colour():
    table = srgb_table()
    assert table.all_exact
    t = node_coordinates(table.resolution)
    target = t @ table.matrix.T
    rho = table.reflectance
    assert rho.min() >= 0.0 and rho.max() <= 1.0
    error = np.abs(rho @ table.weights - target).max(axis=-1)
    assert np.all(error <= NODE_TOLERANCE * np.abs(target).max(axis=-1))
    np.testing.assert_array_equal(table.node_XYZ100, rho @ table.weights)  # exact: the table's own product


def test_black_grey_and_white_nodes():
    table = srgb_table()
    n = table.resolution
    assert np.all(table.reflectance[0, 0, 0] == 0.0)  # exact: black is solved as exact zeros
    # white: the perfect reflector is the only reflectance with that colour (solid's vertex)
    assert np.abs(table.reflectance[-1, -1, -1] - 1.0).max() < 1e-9
    # the centre of the solid: the constant 0.5 has roughness 0, so it is the optimum
    mid = table.reflectance[n // 2, n // 2, n // 2]
    assert np.abs(mid - 0.5).max() < 1e-9


def test_nodes_pass_an_independent_kkt_check():
    table = srgb_table()
    step = float(table.wavelengths_nm[1] - table.wavelengths_nm[0])
    flat = table.flat_reflectance
    rng = np.random.default_rng(3)
    for index in rng.choice(len(flat), 40, replace=False):
        assert_kkt(table.weights, step, flat[index],
                   mu_hint=table.multipliers.reshape(-1, 3)[index])


def test_node_roughness_is_the_roughness_of_the_node():
    table = srgb_table()
    step = float(table.wavelengths_nm[1] - table.wavelengths_nm[0])
    own = np.sum(np.diff(table.reflectance, axis=-1) ** 2, axis=-1) / step
    np.testing.assert_allclose(table.roughness, own, rtol=1e-12, atol=1e-15)


def test_roughness_excess_within_the_recorded_bound_at_random_points():
    table = srgb_table()
    rng = np.random.default_rng(7)
    t = rng.random((3000, 3))
    rho = upsample(table, t).reflectance
    step = float(table.wavelengths_nm[1] - table.wavelengths_nm[0])
    interpolated = np.sum(np.diff(rho, axis=-1) ** 2, axis=-1) / step
    optimum = sc.smoothest_reflectance(t @ table.matrix.T, illuminant="D65", observer="1931", wavelengths=(380, 780, 5))
    assert optimum.certificate.converged.all()
    excess = interpolated - optimum.roughness
    cell = np.minimum((t * (table.resolution - 1)).astype(int), table.resolution - 2)
    bound = table.cell_excess_bound[cell[:, 0], cell[:, 1], cell[:, 2]]
    assert np.all(excess >= -ROUGHNESS_ROUNDING)  # the optimum is optimal
    assert np.all(excess <= bound + ROUGHNESS_ROUNDING)
    assert excess.max() > 1e-6  # the interpolation is not the optimum: the test can see it


def test_measured_excess_below_bound_and_non_negative():
    table = srgb_table()
    assert np.all(table.cell_excess_measured >= -ROUGHNESS_ROUNDING)
    assert np.all(table.cell_excess_measured <= table.cell_excess_bound + ROUGHNESS_ROUNDING)


def test_rec2020_blue_corner_is_moved_toward_grey_and_reported():
    table = rec2020_table()
    status = table.node_status
    assert not table.all_exact
    assert status[0, 0, -1] == 1  # the Rec. 2020 blue primary (467 nm) is no object colour
    assert status[0, 0, 0] == 0 and status[-1, -1, -1] == 0
    t_nominal = node_coordinates(table.resolution)[status == 1]
    t_actual = table.node_XYZ100[status == 1] @ np.linalg.inv(table.matrix).T
    # the actual colour lies on the segment from grey to the nominal colour, short of it
    d_nominal, d_actual = t_nominal - 0.5, t_actual - 0.5
    s = (d_actual * d_nominal).sum(-1) / (d_nominal * d_nominal).sum(-1)
    assert np.all((s >= 0) & (s < 1))
    np.testing.assert_allclose(d_actual, s[:, None] * d_nominal, atol=1e-9)
    # every node, moved or not, reproduces the colour it records and stays in [0, 1]
    rho = table.reflectance
    assert rho.min() >= 0.0 and rho.max() <= 1.0
    np.testing.assert_array_equal(table.node_XYZ100, rho @ table.weights)  # exact: the table's own product


def test_cells_with_a_moved_node_claim_no_bound():
    table = rec2020_table()
    moved = table.node_status == 1
    n = table.resolution
    for i, j, k in np.ndindex(n - 1, n - 1, n - 1):
        touches = moved[i:i + 2, j:j + 2, k:k + 2].any()
        assert np.isnan(table.cell_excess_bound[i, j, k]) == touches


def test_xyz_table_covers_the_solid_with_moved_corners():
    table = upsampling_table("XYZ", "D65", resolution=3, measure_excess=False)
    white = table.weights.sum(axis=0)
    np.testing.assert_array_equal(table.matrix, np.diag(white))  # exact: the same sum, placed on the diagonal
    assert table.node_status[0, 0, 0] == 0 and table.node_status[-1, -1, -1] == 0
    assert table.node_status[-1, 0, 0] == 1  # X = white_X with Y = Z = 0: no object colour


@pytest.mark.parametrize("resolution", [1, 130, 2.5, "9", True, None])
def test_bad_resolution_is_refused_by_name(resolution):
    with pytest.raises(sc.ColorimetryError, match="resolution"):
        upsampling_table(resolution=resolution)


def test_unknown_space_is_refused():
    with pytest.raises(sc.ColorimetryError, match="space"):
        upsampling_table("not a space", resolution=2)


@pytest.mark.parametrize("illuminant", ["D65", "A", "F11"])
def test_the_white_corner_is_the_perfect_reflector_for_every_built_in_space(illuminant):
    """t = (1, 1, 1) is the solid's vertex: an ulp of rounding in the colour map must not move it."""
    from spectrocolor.display.spaces import RGB_SPACES

    for space in RGB_SPACES:
        table = upsampling_table(space, illuminant, resolution=2, measure_excess=False)
        assert table.node_status[-1, -1, -1] == 0, space
        # exact: its colour is set to W.sum(axis=0) itself, which the solver answers with ones
        assert np.all(table.reflectance[-1, -1, -1] == 1.0), space
        # node_XYZ100 is ones @ W, summed in the BLAS kernel's order, W.sum(axis=0) in NumPy's:
        # two orders of K non-negative terms, each within (K - 1) ulps of the sum
        W = table.weights
        atol = 2 * W.shape[0] * np.finfo(float).eps * np.abs(W).sum(axis=0)
        difference = np.abs(table.node_XYZ100[-1, -1, -1] - W.sum(axis=0))
        assert np.all(difference <= atol), (space, difference, atol)
