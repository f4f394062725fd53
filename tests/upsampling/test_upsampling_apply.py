"""Applying a table: exact colour, exact bounds, honest strategies, streaming and dask paths."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

import spectrocolor as sc
from spectrocolor.upsampling import (
    colours_under,
    lookup,
    texel_coefficients,
    upsample,
    upsample_blocks,
    upsample_spectra,
)
from spectrocolor.upsampling.table import node_coordinates
from upsampling_tables import rec2020_table, srgb_table

# The acceptance criterion of the issue: the input colour reproduced to 1e-9 relative.
EXACT = 1e-9

unit = st.floats(0.0, 1.0, allow_nan=False)
queries = arrays(np.float64, st.tuples(st.integers(1, 40), st.just(3)), elements=unit)


def relative_colour_error(table, t, rho):
    target = np.asarray(t) @ table.matrix.T
    error = np.abs(rho @ table.weights - target).max(axis=-1)
    return error / np.maximum(np.abs(target).max(axis=-1), np.finfo(float).tiny)


@settings(max_examples=60, deadline=None)
@given(queries)
def test_every_output_reproduces_its_colour_and_lies_in_the_unit_interval(t):
    table = srgb_table()
    u = upsample(table, t)
    assert u.exact.all() and not u.moved.any()
    assert u.reflectance.min() >= 0.0 and u.reflectance.max() <= 1.0
    black = np.all(t == 0, axis=-1)
    assert np.all(u.reflectance[black] == 0.0)  # exact: black nodes are exact zeros, blended with weights ≥ 0
    assert np.all(relative_colour_error(table, t[~black], u.reflectance[~black]) <= EXACT)


@settings(max_examples=40, deadline=None)
@given(queries)
def test_barycentric_weights_are_convex_and_reproduce_the_query(t):
    table = srgb_table()
    found = lookup(table, t)
    assert found.weights.min() >= 0.0
    np.testing.assert_allclose(found.weights.sum(-1), 1.0, rtol=0, atol=4 * np.finfo(float).eps)
    positions = node_coordinates(table.resolution).reshape(-1, 3)[found.nodes]
    np.testing.assert_allclose((found.weights[..., None] * positions).sum(-2), t, atol=1e-15)


def test_rec2020_exact_where_reported_and_bounded_everywhere():
    table = rec2020_table()
    t = np.random.default_rng(11).random((20000, 3))
    u = upsample(table, t)
    assert 0 < u.exact.mean() < 1
    assert u.reflectance.min() >= 0.0 and u.reflectance.max() <= 1.0
    err = relative_colour_error(table, t, u.reflectance)
    assert np.all(err[u.exact] <= EXACT)
    assert np.median(err[~u.exact]) > 1e-6  # the inexact ones really are not exact


def test_leading_shape_is_kept_and_a_node_returns_its_spectrum():
    table = srgb_table()
    image = np.random.default_rng(2).random((4, 5, 3))
    assert upsample(table, image).reflectance.shape == (4, 5, 81)
    assert upsample(table, [0.25, 0.5, 0.75]).reflectance.shape == (81,)
    node = table.reflectance[2, 4, 6]
    # exact: at a node the weights are exactly 1 and 0 (2/8 · 8 = 2), so the blend is the node
    np.testing.assert_array_equal(upsample(table, [2 / 8, 4 / 8, 6 / 8]).reflectance, node)


def test_toward_grey_moves_hdr_white_to_white_and_reports_it():
    table = srgb_table()
    u = upsample(table, [[2.0, 2.0, 2.0], [-0.1, 0.5, 0.5]])
    assert u.moved.tolist() == [True, True] and u.exact.tolist() == [False, False]
    np.testing.assert_allclose(u.reflectance[0], 1.0, atol=1e-9)
    # (-0.1, 0.5, 0.5) moves along the segment to grey onto the face r = 0: (0, 0.5, 0.5)
    expected = upsample(table, [0.0, 0.5, 0.5]).reflectance
    np.testing.assert_allclose(u.reflectance[1], expected, atol=1e-15)


def test_clip_and_nan_strategies():
    table = srgb_table()
    t = [[1.2, 0.3, -0.4], [0.2, 0.3, 0.4]]
    clipped = upsample(table, t, out_of_range="clip")
    # exact: per-pixel blend of 4 nodes in a fixed order (no BLAS, no sum across pixels), whatever the batch or block
    np.testing.assert_array_equal(clipped.reflectance[0],
                                  upsample(table, [1.0, 0.3, 0.0]).reflectance)
    refused = upsample(table, t, out_of_range="nan")
    assert np.isnan(refused.reflectance[0]).all() and not np.isnan(refused.reflectance[1]).any()
    assert refused.out_of_range == "nan"
    inexact = upsample(rec2020_table(), [[0.0, 0.0, 0.99]], out_of_range="nan")
    assert np.isnan(inexact.reflectance).all()


def test_unknown_strategy_and_bad_input_are_refused_by_name():
    table = srgb_table()
    with pytest.raises(sc.ColorimetryError, match="out_of_range"):
        upsample(table, [0.1, 0.2, 0.3], out_of_range="wrap")
    with pytest.raises(sc.ColorimetryError, match="rgb_linear"):
        upsample(table, [0.1, np.nan, 0.3])
    with pytest.raises(sc.ColorimetryError, match="rgb_linear"):
        upsample(table, [[0.1, 0.2]])
    with pytest.raises(sc.ColorimetryError, match="table"):
        upsample("srgb.scup", [0.1, 0.2, 0.3])


def test_colours_under_another_light_equal_the_spectral_route():
    table = srgb_table()
    t = np.random.default_rng(5).random((500, 3))
    W_A = sc.weights(table.wavelengths_nm, illuminant="A")
    XYZ, exact = colours_under(table, t, W_A)
    spectral = upsample(table, t).reflectance @ W_A
    assert exact.all()
    np.testing.assert_allclose(XYZ, spectral, rtol=1e-12, atol=1e-12)


def test_texel_coefficients_rebuild_the_spectrum_to_float32_rounding():
    table = srgb_table()
    t = np.random.default_rng(6).random((300, 3))
    nodes, weights, exact = texel_coefficients(table, t)
    assert nodes.dtype == np.uint32 and weights.dtype == np.float32 and exact.all()
    rebuilt = np.einsum("nj,njk->nk", weights.astype(float), table.flat_reflectance[nodes])
    # float32 weights: each carries ~6e-8 relative rounding, spectra are <= 1
    np.testing.assert_allclose(rebuilt, upsample(table, t).reflectance, rtol=0, atol=2.5e-7)


def test_streaming_blocks_of_a_memmap_equal_the_whole(tmp_path):
    table = srgb_table()
    image = np.lib.format.open_memmap(tmp_path / "img.npy", mode="w+", dtype=np.float64,
                                      shape=(37, 11, 3))
    image[:] = np.random.default_rng(8).random((37, 11, 3))
    whole = upsample_spectra(table, np.asarray(image))
    blocks = list(upsample_blocks(table, image, max_block_mib=0.5))
    assert len(blocks) > 1
    assert sum(b.stop - b.start for b, _ in blocks) == 37
    for rows, spectra in blocks:
        # exact: per-pixel blend of 4 nodes in a fixed order (no BLAS, no sum across pixels), whatever the batch or
        # block
        np.testing.assert_array_equal(spectra, whole[rows])


def test_dask_equals_numpy():
    da = pytest.importorskip("dask.array")
    from spectrocolor.upsampling import upsample_dask

    table = srgb_table()
    image = np.random.default_rng(9).random((30, 20, 3)) * 1.2 - 0.1
    lazy = upsample_dask(table, da.from_array(image, chunks=(7, 9, 3)))
    assert lazy.shape == (30, 20, 81)
    # exact: per-pixel blend of 4 nodes in a fixed order (no BLAS, no sum across pixels), whatever the batch or block
    np.testing.assert_array_equal(lazy.compute(), upsample_spectra(table, image))


def test_streaming_memory_is_bounded_by_the_block_budget(tmp_path):
    import tracemalloc

    table = srgb_table()
    shape = (400, 500, 3)  # all spectra at once: 400 * 500 * 81 * 8 B = 130 MB
    image = np.lib.format.open_memmap(tmp_path / "big.npy", mode="w+", dtype=np.float64,
                                      shape=shape)
    image[:] = 0.5
    image.flush()
    tracemalloc.start()
    try:
        rows = 0
        for block, spectra in upsample_blocks(table, image, max_block_mib=2.0):
            rows += block.stop - block.start
            assert spectra.shape[-1] == 81
        _, peak = tracemalloc.get_traced_memory()
    finally:
        tracemalloc.stop()
    assert rows == 400
    # a 2 MiB budget of spectra per block, plus the lookup's temporaries (~3x): far below 130 MB
    assert peak < 16 * 2**20
