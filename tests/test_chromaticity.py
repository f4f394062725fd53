"""Spectral locus, dominant/complementary wavelength and purity.

Golden checks by construction (mixtures of a white with a point of the locus or of the purple
line have known wavelength and purity), seed 001's definitions, and cross-checks against
colour-science 0.4.7 on thousands of random chromaticities.
"""

from __future__ import annotations

import tracemalloc

import colour
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import spectrocolor as sc
from spectrocolor.errors import ColorimetryError

D65_XY = np.array([0.3127, 0.3290])
E_XY = np.array([1 / 3, 1 / 3])
RNG = np.random.default_rng(1986)
COLOUR_CMFS = {
    "1931": colour.MSDS_CMFS["CIE 1931 2 Degree Standard Observer"],
    "1964": colour.MSDS_CMFS["CIE 1964 10 Degree Standard Observer"],
}


def locus_point(observer: str, wavelength_nm):
    """Chromaticity on the locus at a (fractional) wavelength, linear between 1 nm samples."""
    locus = sc.spectral_locus(observer)
    return np.stack(
        [np.interp(wavelength_nm, locus.wavelengths_nm, locus.xy[:, i]) for i in (0, 1)], -1
    )


# --- the spectral locus ------------------------------------------------------------------

@pytest.mark.parametrize(
    ("observer", "first", "last"),
    [("1931", 360, 699), ("1964", 360, 699), ("2015-2", 390, 697), ("2015-10", 390, 697)],
)
def test_locus_is_trimmed_to_its_monotonic_part(observer, first, last):
    locus = sc.spectral_locus(observer)
    assert locus.wavelengths_nm[0] == first and locus.wavelengths_nm[-1] == last
    # exact: whole-nanometre wavelengths: small integers, exact in any arithmetic
    np.testing.assert_array_equal(np.diff(locus.wavelengths_nm), 1.0)
    offsets = locus.xy - E_XY
    angle = np.unwrap(np.arctan2(offsets[:, 1], offsets[:, 0]))
    assert np.all(np.diff(angle) < 0)  # turns clockwise around E, never back
    # everything cut off at the red end lies within 1e-5 of the kept end, or turns back
    full = sc.spectral_locus(observer, full=True)
    tail = full.xy[full.wavelengths_nm > last]
    tail_angle = np.arctan2(*(tail - E_XY).T[::-1])
    assert np.all(tail_angle >= angle[-1] - np.hypot(*(tail - locus.xy[-1]).T).max() * 10)


def test_locus_is_the_cmf_chromaticity_and_read_only():
    cmfs = sc.observer("1931")
    full = sc.spectral_locus("1931", full=True)
    # exact: a copy of the observer's wavelengths
    np.testing.assert_array_equal(full.wavelengths_nm, cmfs.wavelengths_nm)
    expected = (cmfs.values[:2] / cmfs.values.sum(axis=0)).T
    np.testing.assert_allclose(full.xy, expected, rtol=1e-15)
    np.testing.assert_allclose(full.xy, colour.XYZ_to_xy(COLOUR_CMFS["1931"].values), atol=1e-15)
    with pytest.raises(ValueError):
        sc.spectral_locus("1931").xy[0, 0] = 0.0


def test_1931_red_tail_is_one_chromaticity():
    # CIE 015: x = 0.73469, y = 0.26531 from 699 nm to 830 nm
    full = sc.spectral_locus("1931", full=True)
    tail = full.xy[full.wavelengths_nm >= 699]
    np.testing.assert_allclose(tail, np.broadcast_to([0.73469, 0.26531], tail.shape), atol=5e-6)


# --- dominant wavelength by construction ---------------------------------------------------

@pytest.mark.parametrize("observer", ["1931", "1964", "2015-2", "2015-10"])
@pytest.mark.parametrize("white", [D65_XY, E_XY, "A", "C"])
def test_mixtures_with_the_locus_recover_wavelength_and_purity(observer, white):
    locus = sc.spectral_locus(observer)
    wavelengths = RNG.uniform(locus.wavelengths_nm[0] + 0.01, locus.wavelengths_nm[-1], 500)
    purity = RNG.uniform(0.01, 1.2, 500)
    white_xy = white if not isinstance(white, str) else sc.xy(sc.white_point(white, observer=observer))
    points = white_xy + purity[:, None] * (locus_point(observer, wavelengths) - white_xy)
    result = sc.dominant_wavelength(points, white, observer)
    assert not result.complementary.any()
    np.testing.assert_allclose(result.wavelength_nm, wavelengths, rtol=0, atol=1e-6)
    np.testing.assert_allclose(result.excitation_purity, purity, rtol=1e-9)
    np.testing.assert_array_equal(result.outside_locus, purity > 1 + 1e-9)


@pytest.mark.parametrize("observer", ["1931", "1964"])
def test_purples_are_complementary_with_purity_on_the_purple_line(observer):
    locus = sc.spectral_locus(observer)
    blue_end, red_end = locus.xy[0], locus.xy[-1]
    share = RNG.uniform(0.001, 0.999, 400)[:, None]
    on_purple_line = blue_end + share * (red_end - blue_end)
    purity = RNG.uniform(0.05, 1.0, 400)
    points = D65_XY + purity[:, None] * (on_purple_line - D65_XY)
    result = sc.dominant_wavelength(points, D65_XY, observer)
    assert result.complementary.all()
    np.testing.assert_allclose(result.excitation_purity, purity, rtol=1e-9)
    # the complementary wavelength lies on the opposite ray: W between the point and the locus
    opposite = locus_point(observer, result.wavelength_nm) - D65_XY
    direction = points - D65_XY
    cross = direction[:, 0] * opposite[:, 1] - direction[:, 1] * opposite[:, 0]
    np.testing.assert_allclose(cross / np.hypot(*direction.T), 0.0, atol=1e-9)
    assert np.all(np.sum(direction * opposite, axis=1) < 0)
    assert np.all((result.wavelength_nm > 480) & (result.wavelength_nm < 575))  # greens


def test_white_point_itself_nan_input_and_shape():
    points = np.array([[[0.3127, 0.3290], [np.nan, 0.3]], [[0.6, 0.3], [0.2, 0.6]]])
    result = sc.dominant_wavelength(points, D65_XY)
    assert result.wavelength_nm.shape == (2, 2)
    # exact: the white itself has purity set to 0, not computed
    assert np.isnan(result.wavelength_nm[0, 0]) and result.excitation_purity[0, 0] == 0.0
    assert not result.complementary[0, 0] and not result.outside_locus[0, 0]
    assert np.isnan(result.wavelength_nm[0, 1]) and np.isnan(result.excitation_purity[0, 1])
    assert np.all(np.isfinite(result.wavelength_nm[1]))
    assert sc.colorimetric_purity(D65_XY, D65_XY) == 0.0  # exact: the white itself has purity set to 0, not computed


def test_outside_the_locus_is_flagged_with_purity_above_one():
    result = sc.dominant_wavelength([[0.05, 0.9], [0.76, 0.27], [0.3, 0.0]], D65_XY)
    assert result.outside_locus.all()
    assert np.all(result.excitation_purity > 1)
    assert result.complementary.tolist() == [False, False, True]


def test_illuminant_name_equals_its_white_point():
    points = RNG.uniform([0.1, 0.1], [0.6, 0.6], (200, 2))
    by_name = sc.dominant_wavelength(points, "C", "1964")
    white = sc.xy(sc.white_point("C", observer="1964"))
    by_xy = sc.dominant_wavelength(points, white, "1964")
    for a, b in zip(by_name, by_xy, strict=True):
        # exact: a name is turned into xy(white_point(name, observer)), the same calls as here
        np.testing.assert_array_equal(a, b)


@pytest.mark.parametrize("name", ["A", "B", "C", "D50", "D65", "E", "FL2", "FL11", "LED-B3"])
def test_every_standard_white_is_usable(name):
    for observer in ("1931", "1964"):
        result = sc.dominant_wavelength([0.4, 0.4], name, observer)
        assert np.isfinite(result.wavelength_nm)


def test_bad_whites_and_points_are_clear_errors():
    with pytest.raises(ColorimetryError, match="outside the gamut"):
        sc.dominant_wavelength([0.3, 0.3], [0.8, 0.8])
    with pytest.raises(ColorimetryError, match="white must be one finite"):
        sc.dominant_wavelength([0.3, 0.3], [[0.3, 0.3], [0.31, 0.31]])
    with pytest.raises(ColorimetryError, match=r"xy must have shape \(\.\.\., 2\)"):
        sc.dominant_wavelength([0.3, 0.3, 0.4], D65_XY)
    with pytest.raises(ColorimetryError, match="is not a shipped observer"):
        sc.dominant_wavelength([0.3, 0.3], D65_XY, "1940")
    # a white a hair inside the locus near a slight concavity: rays meet the locus twice
    near_locus = locus_point("1931", 445.0) + 2e-6 * (D65_XY - locus_point("1931", 445.0))
    with pytest.raises(ColorimetryError, match="ambiguous"):
        sc.dominant_wavelength([0.3, 0.3], near_locus)


@settings(max_examples=200, deadline=None)
@given(st.floats(0.05, 0.7), st.floats(0.05, 0.8), st.floats(0.01, 3.0))
def test_scaling_towards_white_scales_purity_only(x, y, factor):
    point = np.array([x, y])
    if np.hypot(*(point - D65_XY)) < 1e-6:
        return
    base = sc.dominant_wavelength(point, D65_XY)
    moved = sc.dominant_wavelength(D65_XY + factor * (point - D65_XY), D65_XY)
    assert moved.complementary == base.complementary
    assert moved.wavelength_nm == pytest.approx(float(base.wavelength_nm), abs=1e-9)
    assert moved.excitation_purity == pytest.approx(factor * base.excitation_purity, rel=1e-9)


# --- seed 001 -------------------------------------------------------------------------------

# Seed 001, Table 38 (CIE 1931 spectral locus), rows printed to 4 decimals (its 5-decimal rows
# are Le Grand's and differ from CIE 015, see test_seed001_tables.py). The dominant wavelength
# of a point of the locus is its own wavelength and its purity is 100 % (seed 001 §1.7),
# whatever the white: E as in Fig. 1.4, or illuminant B as in Fig. 1.6.
TABLE_38_ROWS = [
    (420, 0.1714, 0.0051), (470, 0.1241, 0.0578), (500, 0.0082, 0.5384),
    (520, 0.0743, 0.8338), (540, 0.2296, 0.7543), (620, 0.6915, 0.30834),
    (660, 0.7300, 0.2700), (680, 0.7334, 0.2666),
]


@pytest.mark.parametrize("white", [E_XY, "B"])
def test_seed001_table38_points_are_their_own_dominant_wavelength(white):
    wavelengths = np.array([row[0] for row in TABLE_38_ROWS], dtype=float)
    points = np.array([row[1:] for row in TABLE_38_ROWS])
    result = sc.dominant_wavelength(points, white)
    # tolerance: the table's rounding (half a unit in the last printed digit) divided by the
    # distance the locus moves per nm there
    speed = np.hypot(*(locus_point("1931", wavelengths + 0.5)
                       - locus_point("1931", wavelengths - 0.5)).T)
    rounding = 0.5e-4 * np.sqrt(2)
    assert np.all(np.abs(result.wavelength_nm - wavelengths) <= rounding / speed + 1e-9)
    np.testing.assert_allclose(result.excitation_purity, 1.0, atol=2e-3)
    assert not result.complementary.any()


def test_seed001_white_has_zero_purity():
    # "White (point E) is considered to have zero purity" (seed 001 §1.7)
    result = sc.dominant_wavelength(E_XY, E_XY)
    # exact: the white itself has purity set to 0, not computed
    assert result.excitation_purity == 0.0 and np.isnan(result.wavelength_nm)


# --- colour-science 0.4.7 -------------------------------------------------------------------

@pytest.mark.parametrize("white", [D65_XY, np.array([0.31006, 0.31616]), np.array([0.44757, 0.40745])])
def test_matches_colour_on_random_points_1931(white):
    points = RNG.uniform([0.0, 0.0], [0.75, 0.85], (3000, 2))
    cmfs = COLOUR_CMFS["1931"]
    wl, _, _ = colour.dominant_wavelength(points, white, cmfs)
    ours = sc.dominant_wavelength(points, white, "1931")
    np.testing.assert_array_equal(ours.complementary, wl < 0)
    # colour snaps to the nearest tabulated wavelength; its red tail (699-830 nm) is one point
    theirs = np.abs(wl)
    snapped = np.where(theirs >= 699, 699.0, theirs)
    assert np.all(np.abs(ours.wavelength_nm - snapped) <= 1.0)
    np.testing.assert_allclose(ours.excitation_purity,
                               colour.excitation_purity(points, white, cmfs), rtol=0, atol=1e-6)
    np.testing.assert_allclose(sc.colorimetric_purity(points, white),
                               colour.colorimetric_purity(points, white, cmfs), rtol=1e-6)


def test_matches_colour_1964_away_from_the_red_end():
    # colour-science's purple line joins 360 and 830 nm and it snaps to the nearest sample of
    # the whole table; the 1964 locus turns back after 701 nm, so beyond ~640 nm colour calls
    # saturated reds purples (about -487 nm) or snaps to the returning tail. Compare below.
    rng = np.random.default_rng(1964)
    wavelengths = rng.uniform(380, 640, 2000)
    purity = rng.uniform(0.02, 1.0, 2000)
    points = D65_XY + purity[:, None] * (locus_point("1964", wavelengths) - D65_XY)
    wl, _, _ = colour.dominant_wavelength(points, D65_XY, COLOUR_CMFS["1964"])
    ours = sc.dominant_wavelength(points, D65_XY, "1964")
    assert np.all(wl > 0) and not ours.complementary.any()
    assert np.all(np.abs(ours.wavelength_nm - wl) <= 1.0)
    np.testing.assert_allclose(
        ours.excitation_purity,
        colour.excitation_purity(points, D65_XY, COLOUR_CMFS["1964"]), rtol=0, atol=1e-6)
    deep_red = D65_XY + 0.5 * (locus_point("1964", np.array([680.0])) - D65_XY)
    assert colour.dominant_wavelength(deep_red, D65_XY, COLOUR_CMFS["1964"])[0] < 0
    assert sc.dominant_wavelength(deep_red, D65_XY, "1964").wavelength_nm == pytest.approx(680.0)


def test_memory_is_linear_in_the_number_of_points():
    points = RNG.uniform([0.1, 0.1], [0.6, 0.6], (100_000, 2))
    sc.dominant_wavelength(points[:10], D65_XY)  # warm the caches
    tracemalloc.start()
    sc.dominant_wavelength(points, D65_XY)
    _, peak = tracemalloc.get_traced_memory()
    tracemalloc.stop()
    segments = len(sc.spectral_locus("1931").wavelengths_nm)
    # an N x segments float64 intermediate alone would take 8 * segments bytes per point
    assert peak / len(points) < 8 * segments / 4


def test_grey_reflectances_are_neutral_not_a_rounding_artefact():
    # A flat grey under D65 has the illuminant's chromaticity up to float rounding; its
    # hue is undefined, so no wavelength may be invented for it (NaN, purity 0).
    grid = sc.wavelength_grid(380, 780, 5)
    greys = sc.Spectrum(grid, np.linspace(0.05, 0.95, 19)[:, None] * np.ones(grid.size))
    XYZ = sc.tristimulus(greys, observer="1931", illuminant="D65")
    result = sc.dominant_wavelength(sc.xy(XYZ), sc.xy(sc.weights(grid, observer="1931", illuminant="D65").sum(0)))
    assert np.all(np.isnan(result.wavelength_nm))
    # exact: neutral colours (within the library's tolerance of the white) get purity 0, set
    np.testing.assert_array_equal(result.excitation_purity, 0.0)
    assert not result.complementary.any()
