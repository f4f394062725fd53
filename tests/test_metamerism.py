"""Metamers: Cohen's decomposition, metamerism index, colour shifts."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import spectrocolor as sc
from spectrocolor.recovery.metamerism import (
    colour_shift,
    fundamental_metamer,
    metameric_black,
    metamerism_index,
)
from spectrocolor.recovery.smoothest import smoothest_reflectance

GRID = sc.wavelength_grid(400, 700, 10)


@settings(max_examples=30, deadline=None)
@given(st.lists(st.floats(0.0, 1.0), min_size=31, max_size=31))
def test_property_cohen_decomposition(values):
    s = sc.Spectrum(GRID, values)
    fm, black = fundamental_metamer(s), metameric_black(s)
    np.testing.assert_allclose(fm.values + black.values, s.values, atol=1e-12)
    np.testing.assert_allclose(sc.tristimulus(fm, observer="1931", illuminant="D65"),
                               sc.tristimulus(s, observer="1931", illuminant="D65"), atol=1e-10)
    assert np.abs(sc.tristimulus(black, observer="1931", illuminant="D65")).max() < 1e-10
    # projector: idempotent; metamers share the fundamental metamer
    np.testing.assert_allclose(fundamental_metamer(fm).values, fm.values, atol=1e-12)


def test_metamers_share_fundamental_and_differ_under_A():
    tcs = sc.read_spectra(sc.__path__[0] + "/data/reflectances_cie_tcs.csv").resample(GRID)
    sample = tcs[1]
    XYZ = sc.tristimulus(sample, observer="1931", illuminant="D65")
    smooth = smoothest_reflectance(XYZ, wavelengths=(400, 700, 10)).spectrum
    np.testing.assert_allclose(fundamental_metamer(smooth).values, fundamental_metamer(sample).values, atol=1e-10)
    assert metamerism_index(sample, sample)[()] == pytest.approx(0.0, abs=1e-12)
    mi = metamerism_index(sample, smooth)
    assert mi > 0.0
    colour = pytest.importorskip("colour")
    W_A = np.asarray(sc.weights(GRID, observer="1931", illuminant="A"))
    white = W_A.sum(axis=0)
    expected = colour.delta_E(colour.XYZ_to_Lab(sample.values @ W_A / 100, colour.XYZ_to_xy(white / 100)),
                              colour.XYZ_to_Lab(smooth.values @ W_A / 100, colour.XYZ_to_xy(white / 100)),
                              method="CIE 2000")
    assert mi == pytest.approx(expected, abs=1e-6)


def test_colour_shift_of_a_grey_is_zero_and_of_colours_is_not():
    grey = sc.Spectrum(GRID, np.full(31, 0.4))
    shift = colour_shift(grey)
    assert np.abs(shift.shift_ab).max() < 1e-9
    tcs = sc.read_spectra(sc.__path__[0] + "/data/reflectances_cie_tcs.csv").resample(GRID)
    assert np.abs(colour_shift(tcs).shift_ab).max() > 0.5
