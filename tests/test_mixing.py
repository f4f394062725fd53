"""Additive and subtractive mixing and complementary distributions (seed 002) as library functions.

The meaning is checked with colorimetry computed independently (colour-science's CIE 1931
table summed at the bins): superposition adds tristimulus values, a distribution and its
complement add up to the white, filters in series commute and darken."""

from __future__ import annotations

import colour
import numpy as np
import pytest

import spectrocolor as sc
from spectrocolor.mixing import additive_mix, complement, complementary_edit, subtractive_mix

WL = np.arange(400.0, 701.0, 10.0)
CMFS = colour.MSDS_CMFS["CIE 1931 2 Degree Standard Observer"]
XBAR = np.array([CMFS[w] for w in WL])


def xyz_of_levels(levels):
    """Independent XYZ of SPECTRA levels (0-30) relative to E: k = 100 / Σ ȳ at the bins."""
    return 100 / XBAR[:, 1].sum() * (np.asarray(levels, float) / 30) @ XBAR


rng = np.random.default_rng(13)
A = rng.integers(0, 31, 31).astype(float)
B = rng.integers(0, 31, 31).astype(float)


def test_additive_mix_adds_tristimulus_values():
    np.testing.assert_allclose(xyz_of_levels(additive_mix(A, B)),
                               xyz_of_levels(A) + xyz_of_levels(B), rtol=1e-12)
    np.testing.assert_allclose(additive_mix(A, B, weights=[2, 0.5]), 2 * A + 0.5 * B)


def test_complement_adds_up_to_the_white():
    # seed 002: "two filters r and 1 - r ... superimposed give colourless light"
    total = additive_mix(A, complement(A, full=30))
    np.testing.assert_array_equal(total, 30.0)  # exact: whole levels 0-30 and 30 minus them: small integers, exact
    np.testing.assert_allclose(xyz_of_levels(total), xyz_of_levels(np.full(31, 30.0)))
    # a yellow-making distribution has a blue-making complement
    yellow = np.where(WL >= 500, 30.0, 0.0)
    white_xy = sc.xy(xyz_of_levels(np.full(31, 30.0)))
    d_yellow = sc.dominant_wavelength(sc.xy(xyz_of_levels(yellow)), white_xy)
    d_blue = sc.dominant_wavelength(sc.xy(xyz_of_levels(complement(yellow, full=30))), white_xy)
    assert 565 < float(d_yellow.wavelength_nm) < 590
    assert 440 < float(d_blue.wavelength_nm) < 490


def test_subtractive_mix_is_the_product_commutes_and_darkens():
    np.testing.assert_allclose(subtractive_mix(A, B, full=30), A * B / 30, rtol=1e-15)
    np.testing.assert_allclose(subtractive_mix(A, B, full=30), subtractive_mix(B, A, full=30),
                               rtol=1e-15)
    # exact: whole levels times 30/30: small integers, exact
    np.testing.assert_array_equal(subtractive_mix(A, np.full(31, 30.0), full=30), A)
    assert xyz_of_levels(subtractive_mix(A, B, full=30))[1] <= min(xyz_of_levels(A)[1],
                                                                   xyz_of_levels(B)[1])
    # factors 0-1, three filters (the last one clear), broadcast over a batch of two
    batch = subtractive_mix(np.array([[0.5], [1.0]]), [0.5, 0.2], [1.0, 1.0])
    np.testing.assert_allclose(batch, [[0.25, 0.1], [0.5, 0.2]], rtol=1e-15)


def test_complementary_edit_conserves_the_pair_and_does_not_touch_its_inputs():
    left, right = np.full(31, 28.0), np.full(31, 2.0)
    a, b = complementary_edit(left, right, 18, 0)  # take 580 nm away from the left
    assert a[18] == 0 and b[18] == 30
    # exact: whole levels moved from one side to the other: small integers, exact
    np.testing.assert_array_equal(a + b, left + right)
    assert left[18] == 28 and right[18] == 2
    a, b = complementary_edit(left, right, -1, 99)  # clipped to the pair's sum
    assert a[-1] == 30 and b[-1] == 0
    a, b = complementary_edit([10.0], [25.0], 0, 0, full=30)  # right may not pass 30
    assert a[0] == 5 and b[0] == 30


@pytest.mark.parametrize(
    ("call", "needle"),
    [
        (lambda: subtractive_mix([0.5, 1.2]), "transmittances[0]"),
        (lambda: subtractive_mix([0.5, np.nan]), "NaN"),
        (lambda: subtractive_mix([1, 2], [1, 2, 3], full=30), "do not broadcast"),
        (lambda: subtractive_mix([1, 2], full=0), "full"),
        (lambda: subtractive_mix([1, 2], full=True), "full"),
        (lambda: subtractive_mix(), "at least one"),
        (lambda: additive_mix([1, -1]), "negative"),
        (lambda: additive_mix([1, 2], [3, 4], weights=[1]), "weights"),
        (lambda: additive_mix("abc"), "distributions[0]"),
        (lambda: complement([0, 31], full=30), "distribution"),
        (lambda: complement(3.0), "scalar"),
        (lambda: complementary_edit([1, 2], [1], 0, 1), "same length"),
        (lambda: complementary_edit([1, 2], [1, 2], 2, 1), "index"),
        (lambda: complementary_edit([1, 2], [1, 2], 0, float("nan")), "level"),
    ],
)
def test_hostile_input_gets_one_clear_error(call, needle):
    with pytest.raises(sc.SpectrumError) as info:
        call()
    assert needle in str(info.value)


def test_mixing_accepts_the_packages_spectrum_and_keeps_its_grid():
    """Issue 27: additive_mix and subtractive_mix (and complement) take Spectrum; the result is a
    Spectrum on the same grid whose colour is what mixing means (exact: the same products)."""
    grid = sc.wavelength_grid(380, 780, 5)
    d65, a = sc.illuminant("D65", grid), sc.illuminant("A", grid)
    mixed = additive_mix(d65, a, weights=[1.0, 0.5])
    assert isinstance(mixed, sc.Spectrum)
    np.testing.assert_array_equal(mixed.wavelengths_nm, grid)  # exact: the grid is carried, not computed
    # exact: the same function on the same arrays
    np.testing.assert_array_equal(mixed.values, additive_mix(d65.values, a.values, weights=[1.0, 0.5]))
    # superposition adds tristimulus values (sums of 81 products each: a few ulps per term)
    XYZ = sc.tristimulus(mixed, observer="1931", illuminant=None)
    np.testing.assert_allclose(XYZ, sc.tristimulus(d65, observer="1931", illuminant=None)
                               + 0.5 * sc.tristimulus(a, observer="1931", illuminant=None),
                               rtol=4 * 81 * np.finfo(float).eps)
    filters = sc.Spectrum(grid, np.stack([np.linspace(0.1, 0.9, grid.size), np.full(grid.size, 0.5)]))
    through = subtractive_mix(filters, np.linspace(1.0, 0.0, grid.size))  # a Spectrum and an array
    assert isinstance(through, sc.Spectrum) and through.values.shape == (2, grid.size)
    # exact: one IEEE product (and one difference) of the same operands
    np.testing.assert_array_equal(through.values, filters.values * np.linspace(1.0, 0.0, grid.size))
    np.testing.assert_array_equal(complement(filters).values, 1.0 - filters.values)  # exact: one IEEE difference
    # arrays alone still give arrays
    assert isinstance(additive_mix([1.0, 2.0], [3.0, 4.0]), np.ndarray)


def test_mixing_spectra_on_different_grids_is_refused_by_name():
    a = sc.Spectrum(sc.wavelength_grid(400, 700, 10), np.ones(31))
    b = sc.Spectrum(sc.wavelength_grid(400, 700, 5), np.ones(61))
    with pytest.raises(sc.SpectrumError, match=r"distributions\[1\]: .*resample"):
        additive_mix(a, b)
    with pytest.raises(sc.SpectrumError, match=r"transmittances\[1\]: .*K = 31"):
        subtractive_mix(a, np.ones(61))
