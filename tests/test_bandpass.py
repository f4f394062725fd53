"""Bandpass correction (ASTM E308, Stearns & Stearns): the rule, what it corrects, colour-science, refusals."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from numpy.polynomial import Polynomial

import spectrocolor as sc
from spectrocolor import Spectrum, SpectrumError
from spectrocolor.bandpass import STEARNS_ALPHA, bandpass_correction, stearns_stearns_matrix

colour = pytest.importorskip("colour")


def _measured_with_triangular_bandpass(true: Polynomial, centres_nm: np.ndarray, fwhm_nm: float) -> np.ndarray:
    """What an instrument with a triangular bandpass (FWHM = ``fwhm_nm``) reports at ``centres_nm``.

    The unit-area triangle times a polynomial is a polynomial on each half, so the integral is exact.
    """
    rising = Polynomial([fwhm_nm, 1.0]) / fwhm_nm**2  # in u = λ − centre: 0 at −FWHM, 1/FWHM at 0
    falling = Polynomial([fwhm_nm, -1.0]) / fwhm_nm**2
    readings = []
    for centre in centres_nm:
        local = true(Polynomial([centre, 1.0]))  # the spectrum in u, so no large numbers cancel
        left, right = (local * rising).integ(), (local * falling).integ()
        readings.append(left(0.0) - left(-fwhm_nm) + right(fwhm_nm) - right(0.0))
    return np.array(readings)


@pytest.mark.parametrize("step", [5.0, 10.0, 20.0])
def test_a_quadratic_measured_with_a_triangular_bandpass_is_recovered_inside_to_the_rounding_of_alpha(step):
    """The triangle adds h²/12·f'' to a quadratic f; the rule removes α·h²·f''. What is left inside is
    exactly (1/12 − α)·h²·f'' (α = 0.083 is 1/12 rounded), at the ends the end rule's own error."""
    true = Polynomial([0.3, 2e-3, -4e-6])
    centres = np.arange(400.0, 701.0, step)
    measured = _measured_with_triangular_bandpass(true, centres, step)
    second_derivative = true.deriv(2)(0.0)
    np.testing.assert_allclose(measured - true(centres), step**2 / 12 * second_derivative, rtol=1e-9)
    corrected = bandpass_correction(Spectrum(centres, measured)).values
    residual = (1 / 12 - STEARNS_ALPHA) * step**2 * second_derivative
    np.testing.assert_allclose(corrected[1:-1] - true(centres[1:-1]), residual, rtol=1e-6)


def test_the_rule_typed_in_from_e308():
    """R'₁ = (1+α)R₁ − αR₂; R'ᵢ = −αRᵢ₋₁ + (1+2α)Rᵢ − αRᵢ₊₁; R'ₙ = (1+α)Rₙ − αRₙ₋₁, α = 0.083."""
    measured = np.array([0.10, 0.30, 0.80, 0.50])
    expected = [
        1.083 * 0.10 - 0.083 * 0.30,
        -0.083 * 0.10 + 1.166 * 0.30 - 0.083 * 0.80,
        -0.083 * 0.30 + 1.166 * 0.80 - 0.083 * 0.50,
        1.083 * 0.50 - 0.083 * 0.80,
    ]
    corrected = bandpass_correction(Spectrum([400, 410, 420, 430], measured)).values
    np.testing.assert_allclose(corrected, expected, rtol=1e-15)


def test_colour_science_differs_only_by_reusing_already_corrected_neighbours():
    """colour 0.4.7's bandpass_correction_Stearns1988 updates the values in place: it corrects both
    ends first, then each interior point with the *corrected* left neighbour (and, next to the last
    point, the corrected last one): cᵢ = oursᵢ − α(cᵢ₋₁ − Rᵢ₋₁) [− α(cₙ − Rₙ)]. Ours uses the
    measured values throughout, as E308 and Stearns & Stearns write the rule. Rebuilding colour's
    numbers from ours by that recursion checks every coefficient of both."""
    grid = np.arange(380.0, 781.0, 10)
    measured = np.random.default_rng(7).random(grid.size)
    ours = bandpass_correction(Spectrum(grid, measured)).values
    theirs = colour.colorimetry.bandpass_correction_Stearns1988(colour.SpectralDistribution(measured.copy(), grid))
    rebuilt = ours.copy()
    for i in range(1, grid.size - 1):
        rebuilt[i] = ours[i] - STEARNS_ALPHA * (rebuilt[i - 1] - measured[i - 1])
    rebuilt[-2] -= STEARNS_ALPHA * (ours[-1] - measured[-1])
    np.testing.assert_allclose(theirs.values, rebuilt, rtol=0, atol=1e-15)
    assert theirs.values[0] == pytest.approx(ours[0], abs=1e-16)
    assert theirs.values[-1] == pytest.approx(ours[-1], abs=1e-16)


def test_matrix_is_symmetric_and_keeps_constants():
    B = stearns_stearns_matrix(9)
    # exact: the tridiagonal entries are assigned, each from one formula, on both sides
    np.testing.assert_array_equal(B, B.T)
    np.testing.assert_allclose(B.sum(axis=0), 1.0, rtol=0, atol=1e-15)
    np.testing.assert_allclose(B.sum(axis=1), 1.0, rtol=0, atol=1e-15)


def test_batches_images_names_and_metadata_are_kept():
    grid = sc.wavelength_grid(400, 700, 10)
    cube = np.random.default_rng(1).random((2, 3, grid.size))
    out = bandpass_correction(Spectrum(grid, cube))
    np.testing.assert_allclose(out.values[1, 2], bandpass_correction(Spectrum(grid, cube[1, 2])).values, rtol=1e-15)
    named = bandpass_correction(Spectrum(grid, cube[0], names=["a", "b", "c"], metadata={"instrument": "i1"}))
    assert named.names == ("a", "b", "c")
    assert named.metadata["instrument"] == "i1"
    assert named.metadata["bandpass_correction"].endswith("triangular bandpass = the 10 nm interval")


@pytest.mark.parametrize("fwhm", [10.0, 9.6, 10.4, [10.0, 10.2, 9.9]])
def test_a_declared_bandpass_equal_to_the_interval_is_accepted(fwhm):
    grid = sc.wavelength_grid(400, 420, 10)
    values = np.array([0.2, 0.5, 0.3])
    expected = stearns_stearns_matrix(3) @ values
    by_argument = bandpass_correction(Spectrum(grid, values), bandpass_nm=fwhm)
    by_envi = bandpass_correction(Spectrum(grid, values, metadata={"fwhm_nm": np.broadcast_to(fwhm, 3)}))
    np.testing.assert_allclose(by_argument.values, expected, rtol=1e-15)
    np.testing.assert_allclose(by_envi.values, expected, rtol=1e-15)


@pytest.mark.parametrize(
    ("kwargs", "metadata", "message"),
    [
        ({"bandpass_nm": 5.0}, {}, r"bandpass_nm: a bandpass \(FWHM\) of 5 nm is not the data's 10 nm interval"),
        ({}, {"fwhm_nm": [10.0, 10.0, 12.0]}, r"metadata\['fwhm_nm'\]: a bandpass \(FWHM\) of 12 nm"),
        ({}, {"bandwidth_fwhm_nm": "2"}, r"metadata\['bandwidth_fwhm_nm'\]: a bandpass \(FWHM\) of 2 nm"),
        ({}, {"bandwidth_corrected": "true"}, "already bandwidth-corrected"),
        ({}, {"bandwidth_corrected": ("false", "TRUE")}, "already bandwidth-corrected"),
        ({"bandpass_nm": "ten"}, {}, "bandpass_nm: expected a bandpass"),
        ({"bandpass_nm": -10.0}, {}, "bandpass_nm: expected positive finite"),
        ({"bandpass_nm": float("nan")}, {}, "bandpass_nm: expected positive finite"),
        ({"method": "gaussian"}, {}, "method: 'gaussian' is not a bandpass correction method"),
    ],
)
def test_refusals_name_the_argument(kwargs, metadata, message):
    spectrum = Spectrum(sc.wavelength_grid(400, 420, 10), [0.2, 0.5, 0.3], metadata=metadata)
    with pytest.raises(SpectrumError, match=message):
        bandpass_correction(spectrum, **kwargs)


@pytest.mark.parametrize(
    ("spectrum", "message"),
    [
        (Spectrum([400, 410, 430], [0.1, 0.2, 0.3]), "uniform wavelength interval"),
        (Spectrum([400], [0.1]), "at least two wavelengths"),
        (np.array([0.1, 0.2]), "spectrum: expected a Spectrum, got ndarray"),
    ],
)
def test_data_the_rule_cannot_apply_to_are_refused(spectrum, message):
    with pytest.raises(SpectrumError, match=message):
        bandpass_correction(spectrum)


def _tm27(fwhm: str, corrected: str) -> str:
    samples = "".join(f'<SpectralData wavelength="{w}">{0.2 + w / 2000}</SpectralData>' for w in range(400, 701, 10))
    return (
        f'<IESTM2714 version="1.0"><SpectralDistribution><SpectralQuantity>reflectance</SpectralQuantity>'
        f"<BandwidthFWHM>{fwhm}</BandwidthFWHM><BandwidthCorrected>{corrected}</BandwidthCorrected>"
        f"{samples}</SpectralDistribution></IESTM2714>"
    )


def test_tm27_files_declare_what_the_correction_checks():
    """BandwidthFWHM and BandwidthCorrected, as the TM-27 reader keeps them, decide."""
    from spectrocolor.io import parse_spectra

    accepted = bandpass_correction(parse_spectra(_tm27("10", "false"), "a.spdx", percent=False))
    assert "10 nm interval" in accepted.metadata["bandpass_correction"]
    with pytest.raises(SpectrumError, match="bandwidth_fwhm_nm.*5 nm is not the data's 10 nm interval"):
        bandpass_correction(parse_spectra(_tm27("5", "false"), "b.spdx", percent=False))
    with pytest.raises(SpectrumError, match="already bandwidth-corrected"):
        bandpass_correction(parse_spectra(_tm27("10", "TRUE"), "c.spdx", percent=False))


def test_a_file_declaring_a_bandwidth_equal_to_the_interval_is_corrected():
    grid = sc.wavelength_grid(400, 700, 10)
    spectrum = Spectrum(grid, np.linspace(0.2, 0.6, grid.size), metadata={"bandwidth_fwhm_nm": "10"})
    assert "bandpass_correction" in bandpass_correction(spectrum).metadata


@pytest.mark.filterwarnings("error::RuntimeWarning")  # no inf − inf on the way to an answer
@settings(max_examples=60, deadline=None)
@given(
    values=st.lists(st.floats(allow_nan=True, allow_infinity=True, width=64), min_size=1, max_size=12),
    step=st.sampled_from([1.0, 5.0, 10.0, 20.0]),
    bandpass=st.one_of(
        st.none(),
        st.floats(allow_nan=True, allow_infinity=True),
        st.text(max_size=5),
        st.lists(st.floats(), max_size=3),
    ),
)
def test_fuzz_any_input_gives_a_result_or_one_spectrum_error(values, step, bandpass):
    spectrum = Spectrum(400.0 + step * np.arange(len(values)), values)
    try:
        out = bandpass_correction(spectrum, bandpass_nm=bandpass)
    except SpectrumError:
        return
    assert out.values.shape == spectrum.values.shape


@pytest.mark.parametrize("reading", [np.inf, -np.inf])
def test_an_infinite_reading_is_one_error_naming_its_wavelength(reading):
    grid = 400.0 + 10.0 * np.arange(5)
    with pytest.raises(SpectrumError, match=r"spectrum: infinite values at 420 nm;"):
        bandpass_correction(Spectrum(grid, [0.2, 0.3, reading, 0.4, 0.5]))
    rows = np.array([[0.2, 0.3, 0.3, 0.4, 0.5], [0.2, reading, 0.3, reading, 0.5]])
    with pytest.raises(SpectrumError, match=r"infinite values at 410 nm and elsewhere"):
        bandpass_correction(Spectrum(grid, rows))


def test_values_that_would_overflow_are_one_error_not_inf():
    grid = 400.0 + 10.0 * np.arange(5)
    with pytest.raises(SpectrumError, match="overflow float64"):
        bandpass_correction(Spectrum(grid, [1.0, 1.6e308, -1.6e308, 1.0, 1.0]))
    big = bandpass_correction(Spectrum(grid, [1e307] * 5))  # a flat line is its own correction
    assert np.all(np.isfinite(big.values)) and np.allclose(big.values, 1e307, rtol=1e-15)

