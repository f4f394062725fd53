"""RGB spaces: matrices from primaries (seed 000 eqs. 13-19), IEC 61966-2-1, colour-science."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

from spectrocolor import ColorimetryError, RGBSpace, rgb_space, rgb_space_names

# IEC 61966-2-1:1999, section 5.2 (forward) and 5.3 (inverse), as printed (4 decimals)
IEC_RGB_TO_XYZ = np.array(
    [[0.4124, 0.3576, 0.1805], [0.2126, 0.7152, 0.0722], [0.0193, 0.1192, 0.9505]]
)
IEC_XYZ_TO_RGB = np.array(
    [[3.2406, -1.5372, -0.4986], [-0.9689, 1.8758, 0.0415], [0.0557, -0.2040, 1.0570]]
)


def test_srgb_forward_matrix_from_primaries_matches_iec_printed_digits():
    derived = rgb_space("sRGB").matrix_to_XYZ / 100  # XYZ100 -> the standard's XYZ1 scale
    # exact: printed digits of a value known to ~1e-13: it moves only at a tie of the last digit
    np.testing.assert_array_equal(np.round(derived, 4), IEC_RGB_TO_XYZ)


def test_srgb_inverse_matrix_iec_digits_come_from_its_rounded_forward_matrix():
    # The standard prints the inverse of its 4-digit forward matrix; the exact inverse of the
    # primaries' matrix differs from the printed one by up to 4e-4 (documented in display.md).
    # exact: printed digits of a value known to ~1e-13: it moves only at a tie of the last digit
    np.testing.assert_array_equal(np.round(np.linalg.inv(IEC_RGB_TO_XYZ), 4), IEC_XYZ_TO_RGB)
    exact = rgb_space("sRGB").matrix_from_XYZ * 100
    assert np.abs(exact - IEC_XYZ_TO_RGB).max() < 5e-4
    assert np.abs(exact - IEC_XYZ_TO_RGB).max() > 1e-4  # the difference is real


@pytest.mark.parametrize(
    "name, colour_name",
    [
        ("sRGB", "sRGB"),
        ("Display P3", "Display P3"),
        ("Adobe RGB (1998)", "Adobe RGB (1998)"),
        ("Rec. 2020", "ITU-R BT.2020"),
    ],
)
def test_matrices_match_colour_science_normalised_primary_matrix(name, colour_name):
    colour = pytest.importorskip("colour")
    ref = colour.RGB_COLOURSPACES[colour_name]
    npm = colour.models.normalised_primary_matrix(ref.primaries, ref.whitepoint)
    ours = rgb_space(name)
    np.testing.assert_allclose(ours.matrix_to_XYZ / 100, npm, rtol=0, atol=1e-12)
    np.testing.assert_allclose(ours.matrix_from_XYZ * 100, np.linalg.inv(npm), atol=1e-10)
    np.testing.assert_allclose(ours.primaries_xy, ref.primaries, atol=1e-12)
    np.testing.assert_allclose(ours.white_xy, ref.whitepoint, atol=1e-12)


@pytest.mark.parametrize("name", rgb_space_names())
@settings(max_examples=40, deadline=None)
@given(rgb=arrays(np.float64, (5, 3), elements=st.floats(-2, 3)))
def test_round_trip_rgb_xyz_rgb_every_space(name, rgb):
    space = rgb_space(name)
    back = space.rgb_linear_from_XYZ(space.XYZ_from_rgb_linear(rgb))
    np.testing.assert_allclose(back, rgb, rtol=0, atol=1e-12)


@pytest.mark.parametrize("name", rgb_space_names())
def test_white_is_full_drive(name):
    space = rgb_space(name)
    np.testing.assert_allclose(space.rgb_linear_from_XYZ(space.white_XYZ), 1.0, atol=1e-13)


def test_chromaticity_spaces_have_white_Y_100():
    for name in ("sRGB", "Display P3", "Adobe RGB (1998)", "Rec. 2020", "SPECTRA equal-energy"):
        assert rgb_space(name).white_XYZ[1] == pytest.approx(100.0, abs=1e-12)


def test_from_chromaticities_solves_eq15_r_plus_g_plus_b_is_white():
    s = RGBSpace.from_chromaticities((0.7, 0.3), (0.2, 0.7), (0.15, 0.05), (0.32, 0.34))
    w = s.white_XYZ
    np.testing.assert_allclose(w / w[1], [0.32 / 0.34, 1.0, 0.34 / 0.34], atol=1e-14)
    np.testing.assert_allclose(s.primaries_xy, [(0.7, 0.3), (0.2, 0.7), (0.15, 0.05)], atol=1e-14)


def test_lookup_is_case_insensitive_and_passes_spaces_through():
    assert rgb_space("srgb") is rgb_space("sRGB")
    assert rgb_space(" rec2020 ").name == "Rec. 2020"
    s = rgb_space("P3")
    assert rgb_space(s) is s


def test_bad_inputs_raise_clear_errors():
    with pytest.raises(ColorimetryError, match="space: 'CMYK' is not a built-in RGB space; choose one of 'sRGB'"):
        rgb_space("CMYK")
    with pytest.raises(ColorimetryError, match="red_xy"):
        RGBSpace.from_chromaticities((0.7,), (0.2, 0.7), (0.15, 0.05), (0.3, 0.3))
    with pytest.raises(ColorimetryError, match="one line"):
        RGBSpace.from_chromaticities((0.1, 0.1), (0.2, 0.2), (0.3, 0.3), (0.3, 0.3))
    with pytest.raises(ColorimetryError, match="inside the triangle"):
        RGBSpace.from_chromaticities((0.64, 0.33), (0.3, 0.6), (0.15, 0.06), (0.05, 0.8))
    with pytest.raises(ColorimetryError, match="linearly independent"):
        RGBSpace.from_primaries_XYZ([1, 1, 1], [2, 2, 2], [0, 0, 1])
    m = rgb_space("sRGB").matrix_from_XYZ
    with pytest.raises(ValueError):
        m[0, 0] = 1.0  # read-only
