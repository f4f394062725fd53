"""Gamut strategies: invariants checked independently, and hypothesis properties."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

import spectrocolor as sc
from spectrocolor.display.gamut import (
    apply_gamut,
    clip,
    desaturate,
    flag_black,
    gamut_flags,
    preserve_luminance,
)

SPACES = ("sRGB", "Rec. 2020", "SPECTRA 7000K")
STRATEGIES = ("flag", "clip", "preserve-luminance", "desaturate")
rgb_arrays = arrays(np.float64, (8, 3), elements=st.floats(-1.0, 2.0))


def _Y(space, rgb):
    return rgb @ space.luminance_row


def _angle(space, rgb):
    xyz = space.XYZ_from_rgb_linear(rgb)
    xy = xyz[..., :2] / xyz.sum(axis=-1, keepdims=True)
    d = xy - space.white_xy
    return np.arctan2(d[..., 1], d[..., 0])


@pytest.mark.parametrize("strategy", STRATEGIES)
@pytest.mark.parametrize("name", SPACES)
@settings(max_examples=30, deadline=None)
@given(rgb=arrays(np.float64, (8, 3), elements=st.floats(0.0, 1.0)))
def test_in_gamut_colours_pass_unchanged(strategy, name, rgb):
    out = apply_gamut(rgb, strategy, sc.rgb_space(name).luminance_row)
    np.testing.assert_array_equal(out, rgb)  # exact: in-gamut colours are returned as they are, without arithmetic


@pytest.mark.parametrize("strategy", STRATEGIES)
@settings(max_examples=40, deadline=None)
@given(rgb=rgb_arrays)
def test_every_strategy_lands_in_the_cube(strategy, rgb):
    out = apply_gamut(rgb, strategy, sc.rgb_space("sRGB").luminance_row)
    assert out.shape == rgb.shape
    assert np.all((out >= 0) & (out <= 1))


@settings(max_examples=60, deadline=None)
@given(rgb=rgb_arrays)
def test_flag_marks_exactly_the_out_of_gamut_colours_and_blacks_them(rgb):
    in_gamut, negative, over = gamut_flags(rgb, tolerance=0.0)
    expected = np.all((rgb >= 0) & (rgb <= 1), axis=1)
    # exact: booleans of comparisons with tolerance 0 on the same numbers
    np.testing.assert_array_equal(in_gamut, expected)
    np.testing.assert_array_equal(negative, rgb < 0)
    np.testing.assert_array_equal(over, rgb > 1)
    out = flag_black(rgb, tolerance=0.0)
    np.testing.assert_array_equal(out[~expected], 0.0)  # exact: flagged colours are set to exact 0
    # exact: in-gamut colours are returned as they are, without arithmetic
    np.testing.assert_array_equal(out[expected], rgb[expected])


@pytest.mark.parametrize("name", SPACES)
@settings(max_examples=60, deadline=None)
@given(rgb=arrays(np.float64, (8, 3), elements=st.floats(-0.5, 1.0)))
def test_preserve_luminance_keeps_Y_exactly_when_the_result_fits(name, rgb):
    space = sc.rgb_space(name)
    out = preserve_luminance(rgb, space.luminance_row, tolerance=0.0)
    Y_in, Y_out = _Y(space, rgb), _Y(space, out)
    # independent statement of eqs. 20-21 for all negatives at once: the positive channels
    # scaled by Y / (Y - sum of the negative contributions)
    pos = np.where(rgb > 0, rgb, 0.0)
    with np.errstate(all="ignore"):
        expected = pos * (Y_in / (pos @ space.luminance_row))[:, None]
    fits = (Y_in > 0) & np.all(expected <= 1, axis=1)
    np.testing.assert_allclose(out[fits], expected[fits], rtol=1e-12, atol=1e-15)
    np.testing.assert_allclose(Y_out[fits], Y_in[fits], rtol=1e-12, atol=1e-14)
    assert np.all(out[Y_in <= 0] == 0)


def test_preserve_luminance_two_negative_channels_at_once():
    space = sc.rgb_space("sRGB")
    rgb = np.array([0.9, -0.05, -0.02])
    out = preserve_luminance(rgb, space.luminance_row)
    y = space.luminance_row
    assert out[1] == 0 and out[2] == 0
    assert out[0] * y[0] == pytest.approx(rgb @ y, rel=1e-15)


def test_seed_000_fortran_loop_order_loses_luminance_and_ours_does_not():
    # Seed 000's loop: for each channel i, correct all channels if channel i is negative, then
    # encode and write channel i at once. A negative channel after a positive one therefore
    # no longer rescales the channel already written.
    space = sc.rgb_space("sRGB")
    y = space.luminance_row
    rgb = np.array([0.9, -0.05, -0.02])
    Yu = rgb @ y
    c = rgb.copy()
    written = np.zeros(3)
    for i in range(3):
        if c[i] < 0:
            c = c * (Yu / (Yu - c[i] * y[i]))
            c[i] = 0.0
        written[i] = c[i]
    assert abs(written @ y - Yu) / Yu > 0.2  # the seed's result is 24 % too bright
    ours = preserve_luminance(rgb, y)
    assert ours @ y == pytest.approx(Yu, rel=1e-14)


@pytest.mark.parametrize("name", SPACES)
@settings(max_examples=60, deadline=None)
@given(rgb=rgb_arrays)
def test_desaturate_keeps_Y_and_hue_angle_and_moves_minimally(name, rgb):
    space = sc.rgb_space(name)
    y = space.luminance_row
    g = (rgb @ y) / y.sum()
    ok = (g > 1e-3) & (g < 1 - 1e-3)
    out = desaturate(rgb, y, tolerance=0.0)
    np.testing.assert_allclose(_Y(space, out)[ok], _Y(space, rgb)[ok], rtol=1e-12, atol=1e-12)
    moved = ok & ~np.all((rgb >= 0) & (rgb <= 1), axis=1)
    far = moved & (np.abs(rgb - g[:, None]).max(axis=1) > 1e-6)
    far &= np.abs(out - g[:, None]).max(axis=1) > 1e-6
    # the chromatic part XYZ - (Y / Y_white) XYZ_white keeps its direction (hue in any linear
    # opponent space) ...
    def chroma(c):
        xyz = space.XYZ_from_rgb_linear(c)
        return xyz - xyz[:, 1:2] / space.white_XYZ[1] * space.white_XYZ

    a, b = chroma(rgb[far]), chroma(out[far])
    cos = (a * b).sum(1) / np.linalg.norm(a, axis=1) / np.linalg.norm(b, axis=1)
    np.testing.assert_allclose(cos, 1.0, atol=1e-9)
    # ... and so does the hue angle about the white in xy, for real colours (X + Y + Z > 0)
    real = space.XYZ_from_rgb_linear(rgb[far]).sum(1) > 1e-6
    a_in, a_out = _angle(space, rgb[far][real]), _angle(space, out[far][real])
    np.testing.assert_allclose(np.cos(a_in - a_out), 1.0, atol=1e-9)
    # minimal: the result is on the cube's surface (one channel at 0 or 1)
    on_face = np.isclose(out[moved], 0, atol=1e-12) | np.isclose(out[moved], 1, atol=1e-12)
    assert np.all(on_face.any(axis=1))
    # and a little less desaturation would leave the cube
    t_less = 1 - 1e-6
    grey = g[moved, None] * np.ones(3)
    back = grey + (out[moved] - grey) / t_less
    assert np.all(((back < 0) | (back > 1)).any(axis=1))


def test_desaturate_unreachable_luminance_goes_to_black_or_white():
    y = sc.rgb_space("sRGB").luminance_row
    out = desaturate(np.array([[1.5, 1.2, 1.1], [-0.2, 0.05, -0.1]]), y)
    # exact: far outside, every channel is clipped to exactly 1 or 0
    np.testing.assert_array_equal(out, [[1.0, 1.0, 1.0], [0.0, 0.0, 0.0]])


def test_clip_is_per_channel():
    # exact: clipping returns the bound or the input itself
    np.testing.assert_array_equal(clip([[1.3, -0.2, 0.5]]), [[1.0, 0.0, 0.5]])


def test_unknown_strategy_and_bad_shape():
    with pytest.raises(sc.ColorimetryError, match="gamut: 'compress' is not a gamut strategy; choose one of 'flag'"):
        apply_gamut(np.zeros(3), "compress", np.ones(3))
    with pytest.raises(sc.ColorimetryError, match=r"shape \(\.\.\., 3\)"):
        clip(np.zeros(4))
