"""Colour coordinates: golden values, cross-checks against colour-science, round trips."""

from __future__ import annotations

import colour
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

import spectrocolor as sc
from spectrocolor.errors import ColorimetryError

RNG = np.random.default_rng(20240601)
XYZ_RANDOM = RNG.uniform(0.0, 120.0, size=(2000, 3))
D65_XYZ = np.array([95.047, 100.0, 108.883])  # CIE 015 D65 2 deg white, Y = 100


def test_xy_of_equal_energy_is_one_third():
    np.testing.assert_allclose(sc.xy([7.0, 7.0, 7.0]), [1 / 3, 1 / 3], rtol=0, atol=1e-15)


def test_xy_keeps_leading_shape_and_matches_colour():
    XYZ = XYZ_RANDOM.reshape(20, 100, 3)
    result = sc.xy(XYZ)
    assert result.shape == (20, 100, 2)
    np.testing.assert_allclose(result, colour.XYZ_to_xy(XYZ), rtol=0, atol=1e-12)


def test_xyY_round_trip_and_matches_colour():
    xyY = sc.xyY(XYZ_RANDOM)
    np.testing.assert_allclose(xyY, colour.XYZ_to_xyY(XYZ_RANDOM), rtol=0, atol=1e-12)
    np.testing.assert_allclose(sc.XYZ_from_xyY(xyY), XYZ_RANDOM, rtol=1e-12, atol=1e-12)


def test_black_has_nan_chromaticity_and_round_trips():
    with np.errstate(all="raise"):  # documented NaN, no floating-point warning
        xyY = sc.xyY([[0.0, 0.0, 0.0], [1.0, 2.0, 3.0]])
        uv = sc.uv_1976([0.0, 0.0, 0.0])
    assert np.isnan(xyY[0, :2]).all() and xyY[0, 2] == 0.0  # exact: Y of black is the input's exact 0
    assert np.isnan(uv).all()
    np.testing.assert_array_equal(sc.XYZ_from_xyY(xyY)[0], [0.0, 0.0, 0.0])  # exact: black (Y = 0) gives exact zeros


def test_y_zero_with_luminance_is_an_error():
    with pytest.raises(ColorimetryError, match="y = 0"):
        sc.XYZ_from_xyY([0.3, 0.0, 10.0])


@pytest.mark.parametrize("func", [sc.xy, sc.xyY, sc.lch])
def test_wrong_last_axis_is_a_clear_error(func):
    with pytest.raises(ColorimetryError, match=r"shape \(\.\.\., 3\)"):
        func([0.3, 0.3])


def test_non_numeric_is_a_clear_error():
    with pytest.raises(ColorimetryError, match="numeric"):
        sc.xy(["a", "b", "c"])


def test_uv_1976_of_d65_matches_cie_published_value():
    # CIE 015:2018 Table T.3: D65 (2 deg) u' = 0.1978, v' = 0.4683
    np.testing.assert_allclose(sc.uv_1976(xy=[0.31272, 0.32903]), [0.1978, 0.4683], atol=5e-5)
    np.testing.assert_allclose(sc.uv_1976(D65_XYZ), [0.1978, 0.4683], atol=5e-5)


def test_uv_1960_and_1976_match_colour():
    uv60 = colour.UCS_to_uv(colour.XYZ_to_UCS(XYZ_RANDOM))
    np.testing.assert_allclose(sc.uv_1960(XYZ_RANDOM), uv60, rtol=0, atol=1e-12)
    xy = colour.XYZ_to_xy(XYZ_RANDOM)
    np.testing.assert_allclose(sc.uv_1960(xy=xy), colour.xy_to_UCS_uv(xy), rtol=0, atol=1e-12)
    np.testing.assert_allclose(sc.uv_1976(xy=xy), colour.xy_to_Luv_uv(xy), rtol=0, atol=1e-12)
    np.testing.assert_allclose(sc.uv_1976(XYZ_RANDOM), colour.xy_to_Luv_uv(xy), atol=1e-12)


def test_uv_needs_exactly_one_input():
    with pytest.raises(ColorimetryError, match="exactly one"):
        sc.uv_1976()
    with pytest.raises(ColorimetryError, match="exactly one"):
        sc.uv_1960([1.0, 1.0, 1.0], xy=[0.3, 0.3])
    with pytest.raises(ColorimetryError, match=r"xy=\.\.\."):
        sc.uv_1976([0.3, 0.3])  # chromaticities passed where XYZ is expected


def test_xy_from_uv_1976_inverts_and_matches_colour():
    xy = colour.XYZ_to_xy(XYZ_RANDOM)
    uv = sc.uv_1976(xy=xy)
    np.testing.assert_allclose(sc.xy_from_uv_1976(uv), xy, rtol=0, atol=1e-12)
    np.testing.assert_allclose(sc.xy_from_uv_1976(uv), colour.Luv_uv_to_xy(uv), atol=1e-12)


def test_xy_from_uv_1960_inverts_and_matches_colour():
    from spectrocolor.coordinates import xy_from_uv_1960

    xy = colour.XYZ_to_xy(XYZ_RANDOM)
    uv = sc.uv_1960(xy=xy)
    np.testing.assert_allclose(xy_from_uv_1960(uv), xy, rtol=0, atol=1e-12)
    np.testing.assert_allclose(xy_from_uv_1960(uv), colour.UCS_uv_to_xy(uv), atol=1e-12)


def test_lab_of_the_white_is_100_0_0():
    np.testing.assert_allclose(sc.lab(D65_XYZ, D65_XYZ), [100.0, 0.0, 0.0], atol=1e-12)
    np.testing.assert_allclose(sc.lab([0.0, 0.0, 0.0], D65_XYZ), [0.0, 0.0, 0.0], atol=1e-12)


def test_lab_matches_colour_both_branches():
    XYZ = np.concatenate([XYZ_RANDOM, RNG.uniform(0.0, 1.0, size=(500, 3))])  # dark: linear part
    white_xy = colour.XYZ_to_xy(D65_XYZ)
    expected = colour.XYZ_to_Lab(XYZ / 100.0, white_xy)
    np.testing.assert_allclose(sc.lab(XYZ, D65_XYZ), expected, rtol=0, atol=1e-9)
    np.testing.assert_allclose(sc.lch(expected), colour.Lab_to_LCHab(expected), atol=1e-9)


def test_lab_is_continuous_at_the_cie_break_point():
    t = 216.0 / 24389.0
    below, above = sc.lab(np.array([[t, t, t], [t * (1 + 1e-12)] * 3]) * D65_XYZ, D65_XYZ)
    assert abs(below[0] - above[0]) < 1e-9
    assert below[0] == pytest.approx(8.0, abs=1e-9)  # L* = 116 * 6/29 - 16 = 8 exactly


def test_lab_white_must_be_positive():
    with pytest.raises(ColorimetryError, match="white_XYZ must be positive"):
        sc.lab(D65_XYZ, [95.0, 0.0, 108.0])


def test_lch_hue_of_neutral_is_zero_and_range():
    result = sc.lch([[50.0, 0.0, 0.0], [50.0, 1e-300, -1e-310], [50.0, 0.0, -3.0]])
    np.testing.assert_allclose(result[:, 1], [0.0, 1e-300, 3.0], rtol=1e-12)
    assert result[0, 2] == 0.0  # exact: atan2(0, 0) is exactly 0
    assert np.all((result[:, 2] >= 0) & (result[:, 2] < 360))
    assert result[2, 2] == pytest.approx(270.0)


finite = st.floats(0.0, 200.0, allow_nan=False)


@settings(max_examples=200, deadline=None)
@given(arrays(np.float64, (5, 3), elements=finite))
def test_lab_round_trip(XYZ):
    back = sc.XYZ_from_lab(sc.lab(XYZ, D65_XYZ), D65_XYZ)
    np.testing.assert_allclose(back, XYZ, rtol=1e-9, atol=1e-9)


@settings(max_examples=200, deadline=None)
@given(arrays(np.float64, (3,), elements=st.floats(0.01, 200.0)), st.floats(0.001, 1000.0))
def test_chromaticity_is_scale_invariant(XYZ, factor):
    np.testing.assert_allclose(sc.xy(XYZ * factor), sc.xy(XYZ), rtol=1e-12, atol=1e-15)
    np.testing.assert_allclose(sc.uv_1976(XYZ * factor), sc.uv_1976(XYZ), rtol=1e-12)
