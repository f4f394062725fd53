"""render(): the whole chain, checked against values computed independently here."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

import spectrocolor as sc

IEC_XYZ_TO_RGB = np.array(
    [[3.2406, -1.5372, -0.4986], [-0.9689, 1.8758, 0.0415], [0.0557, -0.2040, 1.0570]]
)


def _srgb8(linear):
    v = np.where(linear <= 0.0031308, 12.92 * linear, 1.055 * linear ** (1 / 2.4) - 0.055)
    return np.rint(255 * v).astype(int)


def test_render_in_gamut_colours_against_colour_science():
    colour = pytest.importorskip("colour")
    XYZ100 = np.array([[20.0, 21.0, 22.0], [30.0, 20.0, 10.0], [30.0, 40.0, 20.0]])
    r = sc.render(XYZ100, "sRGB")
    assert r.in_gamut.all() and r.gamut == sc.display.gamut.DEFAULT_GAMUT == "desaturate"
    assert r.normalise == "none" and r.scale == 1.0  # exact: the default parameter itself, not a result
    npm = colour.models.normalised_primary_matrix(
        colour.RGB_COLOURSPACES["sRGB"].primaries, colour.RGB_COLOURSPACES["sRGB"].whitepoint
    )
    linear = XYZ100 / 100 @ np.linalg.inv(npm).T
    np.testing.assert_allclose(r.rgb_linear, linear, atol=1e-12)
    np.testing.assert_allclose(r.rgb_encoded, colour.models.eotf_inverse_sRGB(linear), atol=1e-12)
    # exact: codes of floats that agree to ~1e-13: a code moves only at a half-code tie, which these inputs do not
    # reach
    np.testing.assert_array_equal(r.codes, _srgb8(linear))
    assert r.codes.dtype == np.int64 and r.bit_depth == 8


def test_render_keeps_leading_shape_and_hex():
    XYZ = np.full((2, 3, 3), 50.0)
    r = sc.render(XYZ, "sRGB", gamut="clip")
    assert r.rgb_linear.shape == (2, 3, 3) and r.in_gamut.shape == (2, 3)
    assert r.hex.shape == (2, 3)
    w = sc.render(sc.rgb_space("sRGB").white_XYZ)
    assert w.hex == "#ffffff"


def test_flag_blacks_and_names_the_negative_channel():
    # a spectral green, far outside sRGB: R and B negative
    XYZ = np.array([[1.0, 60.0, 5.0], [30.0, 30.0, 30.0]])
    r = sc.render(XYZ, "sRGB", gamut="flag")
    assert not r.in_gamut[0] and r.in_gamut[1]
    np.testing.assert_array_equal(r.negative[0], [True, False, True])  # exact: booleans of clearly negative channels
    np.testing.assert_array_equal(r.codes[0], [0, 0, 0])  # exact: flagged colours get code 0, set
    linear = XYZ[0] / 100 @ np.linalg.inv(sc.rgb_space("sRGB").matrix_to_XYZ / 100).T
    np.testing.assert_allclose(r.rgb_unmapped[0], linear, atol=1e-12)


def test_normalisations():
    XYZ = np.array([[10.0, 10.0, 10.0], [40.0, 30.0, 20.0]])
    space = sc.rgb_space("sRGB")
    raw = space.rgb_linear_from_XYZ(XYZ)
    g = sc.render(XYZ, space, normalise="global-max", gamut="clip")
    assert g.scale == pytest.approx(raw.max())
    assert g.rgb_unmapped.max() == pytest.approx(1.0)
    p = sc.render(XYZ, space, normalise="per-colour", gamut="clip")
    np.testing.assert_allclose(p.scale, raw.max(axis=1))
    np.testing.assert_allclose(p.rgb_unmapped.max(axis=1), 1.0)
    f = sc.render(XYZ, space, normalise="fixed", scale=2.0)
    np.testing.assert_allclose(f.rgb_unmapped, raw / 2.0)
    with pytest.raises(sc.ColorimetryError, match='normalise="fixed" needs scale'):
        sc.render(XYZ, space, normalise="fixed")
    with pytest.raises(sc.ColorimetryError, match="only with"):
        sc.render(XYZ, space, normalise="none", scale=3.0)
    with pytest.raises(sc.ColorimetryError, match="normalise: 'auto' is not a normalisation; choose one of 'none'"):
        sc.render(XYZ, space, normalise="auto")


def test_white_scale():
    space = sc.rgb_space("sRGB")
    XYZ_A = np.array([109.85, 100.0, 35.585])
    s = sc.white_scale(space, XYZ_A)
    r = sc.render(XYZ_A, space, normalise="fixed", scale=s)
    assert r.rgb_unmapped.max() == pytest.approx(1.0)


def test_spectra_space_uses_its_64_level_table():
    space = sc.rgb_space("SPECTRA 7000K")
    # half the white's drive on every channel: level 46 of 63 (seed 002 Appendix)
    r = sc.render(space.white_XYZ * 0.5, space)
    # exact: codes of floats that agree to ~1e-13: a code moves only at a half-code tie, which these inputs do not
    # reach
    np.testing.assert_array_equal(r.codes, [46, 46, 46])
    assert r.bit_depth == 6
    with pytest.raises(sc.ColorimetryError, match="64 levels"):
        sc.render(space.white_XYZ, space, bit_depth=8)


def test_bit_depths():
    white = sc.rgb_space("sRGB").white_XYZ
    assert sc.render(white, bit_depth=10).codes.tolist() == [1023] * 3
    assert sc.render(white, bit_depth=16).codes.tolist() == [65535] * 3


def test_iec_printed_matrix_and_exact_matrix_agree_in_8_bit_codes_for_typical_colours():
    rng = np.random.default_rng(7)
    XYZ = rng.uniform(5, 60, (500, 3))
    r = sc.render(XYZ, "sRGB", gamut="clip")
    linear = np.clip(XYZ / 100 @ IEC_XYZ_TO_RGB.T, 0, 1)
    assert np.abs(r.codes - _srgb8(linear)).max() <= 1


@pytest.mark.parametrize("gamut", ["flag", "clip", "preserve-luminance", "desaturate"])
@settings(max_examples=30, deadline=None)
@given(XYZ=arrays(np.float64, (6, 3), elements=st.floats(0.0, 120.0)))
def test_render_properties(gamut, XYZ):
    r = sc.render(XYZ, "sRGB", gamut=gamut)
    assert np.all((r.rgb_linear >= 0) & (r.rgb_linear <= 1))
    assert np.all((r.codes >= 0) & (r.codes <= 255))
    inside = r.in_gamut
    np.testing.assert_allclose(r.rgb_linear[inside], r.rgb_unmapped[inside], atol=1e-9)
    expected_in = np.all((r.rgb_unmapped >= -1e-9) & (r.rgb_unmapped <= 1 + 1e-9), axis=1)
    np.testing.assert_array_equal(inside, expected_in)  # exact: booleans of the same tolerance test on the same numbers


def test_bad_input():
    with pytest.raises(sc.ColorimetryError, match=r"XYZ100 must have shape \(\.\.\., 3\)"):
        sc.render([1.0, 2.0])
    with pytest.raises(sc.ColorimetryError, match="NaN"):
        sc.render([np.nan, 1.0, 1.0])
    with pytest.raises(sc.ColorimetryError, match="gamut: 'squash' is not a gamut strategy"):
        sc.render([1.0, 1.0, 1.0], gamut="squash")


def test_bad_types_are_colorimetry_errors():
    with pytest.raises(sc.ColorimetryError, match="XYZ100 must be real numeric tristimulus values"):
        sc.render("abc")
    with pytest.raises(sc.ColorimetryError, match="needs scale, a positive number"):
        sc.render([10.0, 10.0, 10.0], normalise="fixed", scale="2")
    fixed = sc.render([10.0, 10.0, 10.0], normalise="fixed", scale=np.float64(2.0))
    assert fixed.scale == 2.0  # exact: the given scale itself, passed through


# --- small API slips are one clear error (issue 25) -----------------------------------------------


@pytest.mark.parametrize("weights", [[[1, 2, 3], [4, 5]], "W", [[1j, 0, 0]], None])
def test_max_object_rgb_refuses_weights_that_are_not_a_numeric_array(weights):
    with pytest.raises(sc.ColorimetryError, match="^weights: expected"):
        sc.max_object_rgb("sRGB", weights)


@pytest.mark.parametrize("white", ["D65", ["95", "100", "108"], 1j, [95 + 1j, 100, 108], [[95, 100], [1]]])
def test_white_scale_refuses_strings_complex_and_ragged_whites(white):
    with pytest.raises(sc.ColorimetryError, match="^white_XYZ: expected"):
        sc.white_scale("sRGB", white)
