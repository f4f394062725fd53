"""The Spectrum type: grids, validation, arithmetic, constructors, resampling."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

import spectrocolor as sc
from spectrocolor import Spectrum, SpectrumError


def test_grid_and_shape():
    s = Spectrum(sc.wavelength_grid(400, 700, 10), np.zeros((4, 5, 31)))
    assert s.batch_shape == (4, 5)
    assert s.interval_nm == 10
    assert s.wavelengths_nm.flags.writeable is False


@pytest.mark.parametrize(
    ("wavelengths", "message"),
    [
        ([400, 400, 500], "duplicate"),
        ([500, 400, 600], "decreasing"),
        ([0.4, 0.5, 0.6], "micrometres"),
        ([400, np.nan, 600], "NaN"),
        ([[400, 500]], "1-D"),
    ],
)
def test_bad_grids_name_the_problem(wavelengths, message):
    with pytest.raises(SpectrumError, match=message):
        Spectrum(wavelengths, np.zeros(np.asarray(wavelengths).shape[-1]))


def test_values_must_match_grid():
    with pytest.raises(SpectrumError, match="one entry per wavelength"):
        Spectrum([400, 500, 600], [1.0, 2.0])


def test_names_must_match_batch():
    with pytest.raises(SpectrumError, match="names"):
        Spectrum([400, 500], [[1, 2], [3, 4]], names=["only one"])


def test_wavelength_grid_rejects_uneven_steps():
    with pytest.raises(SpectrumError, match="whole steps"):
        sc.wavelength_grid(400, 705, 10)


def test_arithmetic_on_same_grid():
    g = sc.wavelength_grid(400, 700, 100)
    r = Spectrum(g, [0.1, 0.2, 0.3, 0.4])
    s = Spectrum(g, [10.0, 20.0, 30.0, 40.0])
    np.testing.assert_allclose((r * s).values, [1, 4, 9, 16])
    np.testing.assert_allclose((1 - r).values, [0.9, 0.8, 0.7, 0.6])
    np.testing.assert_allclose((r + r).values, 2 * r.values)
    np.testing.assert_allclose((s / 10).values, [1, 2, 3, 4])


def test_combining_different_grids_is_an_error_not_a_guess():
    a = Spectrum([400, 500, 600], [1, 1, 1])
    b = Spectrum([400, 450, 600], [1, 1, 1])
    with pytest.raises(SpectrumError, match="resample"):
        a * b


def test_constructors():
    g = sc.wavelength_grid(400, 700, 10)
    block = Spectrum.block(500, 600, g)
    assert block.values.sum() == 11 and block.values[g == 500] == 1 and block.values[g == 490] == 0
    stop = Spectrum.block(600, 500, g)  # band-stop
    # exact: a block is built of exact ones and zeros
    np.testing.assert_array_equal(stop.values, np.where((g >= 600) | (g <= 500), 1.0, 0.0))
    gauss = Spectrum.gaussian(550, 40, sc.wavelength_grid(400, 700, 1))
    half = gauss.values[np.isin(gauss.wavelengths_nm, [530, 570])]
    np.testing.assert_allclose(half, 0.5, rtol=1e-12)
    bins = Spectrum.bins(np.arange(31), full_scale=30)
    np.testing.assert_allclose(bins.wavelengths_nm, g)
    assert bins.values[-1] == 1.0  # exact: 30 / 30 full scale: one exact division
    assert Spectrum.constant(0.5, g).values.sum() == pytest.approx(15.5)


def test_restrict_keeps_samples():
    s = Spectrum(sc.wavelength_grid(360, 830, 5), np.arange(95.0))
    r = s.restrict(380, 780)
    assert r.wavelengths_nm[0] == 380 and r.wavelengths_nm[-1] == 780
    np.testing.assert_array_equal(r.values, np.arange(4, 85))


def test_resample_never_extrapolates():
    s = Spectrum(sc.wavelength_grid(400, 700, 10), np.ones(31))
    with pytest.raises(SpectrumError, match="extrapolates"):
        s.resample(sc.wavelength_grid(380, 700, 1))


@pytest.mark.parametrize("method", ["linear", "sprague", "cubic"])
def test_resample_reproduces_nodes_and_polynomials(method):
    coarse = sc.wavelength_grid(380, 780, 5)
    fine = sc.wavelength_grid(380, 780, 1)
    line = Spectrum(coarse, 0.3 + 1e-3 * coarse)
    np.testing.assert_allclose(line.resample(fine, method).values, 0.3 + 1e-3 * fine, rtol=0, atol=1e-12)
    wiggly = Spectrum(coarse, np.sin(coarse / 17.0))
    back = wiggly.resample(fine, method).values[::5]
    # exact: at the nodes the interpolants' higher terms are multiplied by exact 0 (fine[::5] is coarse)
    np.testing.assert_array_equal(back, wiggly.values)


def test_sprague_matches_colour_science():
    colour = pytest.importorskip("colour")
    coarse = sc.wavelength_grid(380, 780, 5)
    rng = np.random.default_rng(1)
    y = rng.random(coarse.size)
    fine = sc.wavelength_grid(380, 780, 1)
    ours = Spectrum(coarse, y).resample(fine, "sprague").values
    theirs = colour.SpragueInterpolator(coarse, y)(fine)
    np.testing.assert_allclose(ours, theirs, rtol=0, atol=1e-12)


def test_batch_resample_equals_row_by_row():
    g = sc.wavelength_grid(400, 700, 10)
    rng = np.random.default_rng(2)
    batch = Spectrum(g, rng.random((3, 4, 31)))
    target = np.linspace(400, 700, 77)
    whole = batch.resample(target, "cubic").values
    one = Spectrum(g, batch.values[1, 2]).resample(target, "cubic").values
    np.testing.assert_allclose(whole[1, 2], one, rtol=0, atol=1e-14)


def test_indexing_keeps_names():
    s = Spectrum([400, 500], [[1, 2], [3, 4], [5, 6]], names=["a", "b", "c"])
    assert s[1].names == ("b",)
    assert s[1:].names == ("b", "c")


@settings(max_examples=50, deadline=None)
@given(arrays(np.float64, 31, elements=st.floats(-10, 10)), arrays(np.float64, 31, elements=st.floats(-10, 10)))
def test_linear_resampling_is_linear(a, b):
    g = sc.wavelength_grid(400, 700, 10)
    target = np.linspace(400, 700, 53)
    lhs = Spectrum(g, 2 * a + b).resample(target, "sprague").values
    rhs = 2 * Spectrum(g, a).resample(target, "sprague").values + Spectrum(g, b).resample(target, "sprague").values
    np.testing.assert_allclose(lhs, rhs, atol=1e-9)


def test_bad_arguments_are_spectrum_errors_naming_the_argument():
    grid = sc.wavelength_grid(400, 700, 10)
    s = Spectrum(grid, np.full(grid.size, 0.5))
    cases = [
        (lambda: Spectrum([400, 500], [1, 2], names=5), "names"),
        (lambda: Spectrum.constant("a", grid), "value"),
        (lambda: Spectrum.block("a", 600, grid), "start_nm"),
        (lambda: Spectrum.gaussian(np.nan, 10, grid), "peak_nm"),
        (lambda: s.resample(grid, "foo"), "method"),
        (lambda: s.restrict("a", "b"), "start_nm"),
        (lambda: s + np.ones(5), "addition"),
        (lambda: s / 0, "division"),
        (lambda: s / Spectrum(grid, np.zeros(grid.size)), "division"),
        (lambda: sc.wavelength_grid(400, 700, 1e-9), "step_nm"),
    ]
    for call, argument in cases:
        with pytest.raises(SpectrumError, match=argument):
            call()
    np.testing.assert_array_equal((s / 2).values, 0.25)  # exact: 0.5 / 2: one exact division


# --- small API slips are one clear error (issue 25) -----------------------------------------------


@pytest.mark.parametrize("levels", [["a"], "abc", [1j, 2], [[1, 2], [3]], [None, 1]])
def test_bins_refuses_levels_that_are_not_numbers(levels):
    with pytest.raises(sc.SpectrumError, match="^levels: expected"):
        sc.Spectrum.bins(levels)


@pytest.mark.parametrize("full_scale", ["30", 0, -1, float("nan"), True])
def test_bins_refuses_a_full_scale_that_is_not_a_positive_number(full_scale):
    with pytest.raises(sc.SpectrumError, match="^full_scale: expected"):
        sc.Spectrum.bins([1, 2], full_scale=full_scale)
