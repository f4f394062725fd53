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


# --- overflow and batches (issue 25) --------------------------------------------------------------


@pytest.mark.parametrize("level", [1e307, 1e308])
def test_reflectances_whose_colours_overflow_are_an_error(level):
    import warnings

    wl = sc.wavelength_grid(400, 700, 10)
    huge, grey = sc.Spectrum(wl, np.full(wl.size, level)), sc.Spectrum(wl, np.full(wl.size, 0.5))
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        with pytest.raises(sc.ColorimetryError, match="^spectrum1, spectrum2: values this large overflow"):
            sc.metamerism_index(huge, grey)
        with pytest.raises(sc.ColorimetryError, match="^spectrum: values this large overflow"):
            sc.colour_shift(huge)
    # At 1e300 the cube roots of CIELAB are ~1e100 and a*, b* are differences of them: zero on one
    # BLAS kernel, ~1e86 after a one-ulp difference on another, whose 7th power in CIEDE2000
    # overflows. Which happens is the CPU's; that it is never a silent non-finite number is ours.
    try:
        index = sc.metamerism_index(sc.Spectrum(wl, np.full(wl.size, 1e300)), grey)
    except sc.ColorimetryError as error:
        assert str(error).startswith("spectrum1, spectrum2: values this large overflow")
    else:
        assert np.isfinite(index)


def test_batches_that_do_not_broadcast_and_empty_batches():
    wl = sc.wavelength_grid(400, 700, 10)
    empty, two = sc.Spectrum(wl, np.full((0, wl.size), 0.5)), sc.Spectrum(wl, np.full((2, wl.size), 0.5))
    for first, second in ((empty, two), (two, empty)):
        with pytest.raises(sc.SpectrumError, match="spectrum1, spectrum2: batches of shapes .* do not broadcast"):
            sc.metamerism_index(first, second)
    assert sc.metamerism_index(empty, empty).shape == (0,)
    masked = sc.Spectrum(wl, np.vstack([np.full(wl.size, np.nan), np.full(wl.size, 0.5)]))
    index = sc.metamerism_index(masked, two)
    assert np.isnan(index[0]) and index[1] == 0.0  # exact: the same sample twice (correction 1 exactly)
