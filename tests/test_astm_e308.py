"""ASTM E308 / E2022 weights: colour-science cross-checks, exactness and range properties, errors."""

import warnings

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

import spectrocolor as sc
from spectrocolor import ColorimetryError, Spectrum, SpectrumError
from spectrocolor.astm_e308 import astm_e308_table6_weights, astm_e308_weights, illuminant_at_1nm, lagrange_matrix
from spectrocolor.bandpass import bandpass_correction

colour = pytest.importorskip("colour")

COLOUR_OBSERVERS = {"1931": "CIE 1931 2 Degree Standard Observer", "1964": "CIE 1964 10 Degree Standard Observer"}
FINE = np.arange(360.0, 781.0)


def _colour_illuminant_1nm(name):
    """colour-science's own illuminant data at 1 nm, 360–780 nm: A from its formula, D65 linearly."""
    shape = colour.SpectralShape(360, 780, 1)
    if name == "A":
        return colour.sd_CIE_standard_illuminant_A(shape)
    return colour.SDS_ILLUMINANTS[name].copy().interpolate(shape, interpolator=colour.LinearInterpolator)


def _colour_cmfs(observer):
    return colour.MSDS_CMFS[COLOUR_OBSERVERS[observer]].copy().trim(colour.SpectralShape(360, 780, 1))


@pytest.mark.parametrize("observer", ["1931", "1964"])
@pytest.mark.parametrize("illuminant", ["D65", "A"])
@pytest.mark.parametrize("step", [5, 10, 20])
def test_full_range_table_equals_colour_tristimulus_weighting_factors_ASTME2022(observer, illuminant, step):
    expected = colour.colorimetry.tristimulus_weighting_factors_ASTME2022(
        _colour_cmfs(observer), _colour_illuminant_1nm(illuminant), colour.SpectralShape(360, 780, step)
    )
    W = astm_e308_weights(np.arange(360.0, 781.0, step), observer, illuminant)
    np.testing.assert_allclose(W, expected, rtol=0, atol=1e-9)


@pytest.mark.parametrize("observer", ["1931", "1964"])
@pytest.mark.parametrize("illuminant", ["D65", "A"])
@pytest.mark.parametrize(
    ("step", "start", "stop"), [(10, 400, 700), (10, 380, 780), (20, 400, 700), (20, 360, 740), (5, 420, 730)]
)
def test_random_reflectances_equal_colour_sd_to_XYZ_ASTM_E308(observer, illuminant, step, start, stop):
    """Same method in colour: its E2022 table with the E308 range adjustment (no 20→10 nm or 5 nm
    shortcuts). colour runs on its own CIE tables, so this also checks our data."""
    grid = np.arange(float(start), stop + 1.0, step)
    reflectances = np.random.default_rng(start + step).random((40, grid.size))
    cmfs, spd = _colour_cmfs(observer), _colour_illuminant_1nm(illuminant)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # colour warns that it trims and aligns shapes
        expected = np.array(
            [
                colour.sd_to_XYZ(
                    colour.SpectralDistribution(r, grid),
                    cmfs,
                    spd,
                    method="ASTM E308",
                    mi_5nm_omission_method=False,
                    mi_20nm_interpolation_method=False,
                )
                for r in reflectances
            ]
        )
    ours = sc.tristimulus(Spectrum(grid, reflectances), observer=observer, illuminant=illuminant, method="astm-e308")
    np.testing.assert_allclose(ours, expected, rtol=0, atol=1e-9)


@pytest.mark.parametrize("step", [1, 5, 10, 20])
@pytest.mark.parametrize(("start", "stop"), [(360, 780), (400, 700), (380, 720)])
def test_perfect_white_has_Y_100_and_the_1nm_white_point_of_the_reference_range(step, start, stop):
    grid = sc.wavelength_grid(start, stop, step)
    white = sc.tristimulus(Spectrum.constant(1.0, grid), observer="1931", illuminant="D65", method="astm-e308")
    assert white[1] == pytest.approx(100.0, rel=1e-14)
    # E308's range adjustment keeps every 1 nm weight of 360–780 nm: the white is the 1 nm one.
    np.testing.assert_allclose(white, sc.white_point("D65", observer="1931", wavelengths_nm=FINE), rtol=1e-13)


@pytest.mark.parametrize("step", [5, 10, 20])
@pytest.mark.parametrize("observer", ["1931", "1964"])
def test_quadratic_reflectance_over_the_full_range_matches_1nm_summation_exactly(step, observer):
    """Lagrange interpolation (cubic inside, quadratic at the ends) reproduces a quadratic exactly."""
    grid = np.arange(360.0, 781.0, step)

    def reflectance(wavelength_nm):
        return 0.2 + 1e-3 * (wavelength_nm - 360) - 1.5e-6 * (wavelength_nm - 360) ** 2

    ours = sc.tristimulus(Spectrum(grid, reflectance(grid)), observer=observer, illuminant="A", method="astm-e308")
    one_nm = sc.tristimulus(Spectrum(FINE, reflectance(FINE)), observer=observer, illuminant="A", method="sum")
    np.testing.assert_allclose(ours, one_nm, rtol=1e-12)


@pytest.mark.parametrize("step", [1, 5, 10, 20])
def test_range_adjustment_equals_holding_the_end_values_on_the_full_range(step):
    full = np.arange(360.0, 781.0, step)
    grid = full[(full >= 400) & (full <= 700)]
    reflectances = np.random.default_rng(step).random((10, grid.size))
    held = reflectances[:, np.clip(np.searchsorted(grid, full), 0, grid.size - 1)]
    np.testing.assert_allclose(
        reflectances @ astm_e308_weights(grid, "1964", "D65"),
        held @ astm_e308_weights(full, "1964", "D65"),
        rtol=1e-12,
    )


def test_1nm_data_over_the_reference_range_is_plain_1nm_summation():
    np.testing.assert_allclose(
        astm_e308_weights(FINE, "1931", "D65"),
        sc.weights(FINE, observer="1931", illuminant="D65", method="sum"),
        rtol=1e-13,
    )


def test_grid_not_aligned_with_360_gets_the_uncovered_1nm_weights_at_its_ends():
    grid = sc.wavelength_grid(405, 705, 10)
    W = astm_e308_weights(grid, "1931", "D65")
    assert W.shape == (grid.size, 3)
    np.testing.assert_allclose(W.sum(axis=0), sc.white_point("D65", observer="1931", wavelengths_nm=FINE), rtol=1e-13)


def test_data_beyond_780_widen_the_reference_range():
    grid = sc.wavelength_grid(380, 830, 10)
    white = astm_e308_weights(grid, "1931", "A").sum(axis=0)
    np.testing.assert_allclose(
        white, sc.white_point("A", observer="1931", wavelengths_nm=np.arange(360.0, 831.0)), rtol=1e-13
    )


def test_fluorescent_illuminant_uses_its_own_range():
    grid = sc.wavelength_grid(380, 780, 10)
    fine = np.arange(380.0, 781.0)
    spd = Spectrum(fine, illuminant_at_1nm(fine, "FL2"))
    W = astm_e308_weights(grid, "1931", "FL2")
    np.testing.assert_allclose(W.sum(axis=0), sc.white_point(spd, observer="1931", wavelengths_nm=fine), rtol=1e-13)


def test_fluorescent_lamp_measured_from_360nm_is_accepted_as_a_spectrum():
    fine = np.arange(360.0, 781.0)
    lamp = Spectrum(fine, np.r_[np.full(20, 0.5), illuminant_at_1nm(np.arange(380.0, 781.0), "FL11")])
    W = astm_e308_weights(sc.wavelength_grid(360, 780, 10), "1931", lamp)
    np.testing.assert_allclose(W.sum(axis=0), sc.white_point(lamp, observer="1931", wavelengths_nm=fine), rtol=1e-13)


# ASTM E308 white points (the "white point" rows under each weight table of Tables 5 and 6, the
# same for every interval and range, since E308's range adjustment keeps every 1 nm weight), to
# three decimals, typed in from reprints of E308-01's table of white points, not from a copy of
# E308-17: 17 of the 18 agree with the colorjs color-space table (both observers; its 2° D65 is
# computed), the 2° A–D75 with Colors.jl's and Unicolour's. (X, Z); Y is 100.000 in every table.
E308_WHITE_POINTS = {
    ("1931", "A"): (109.850, 35.585),
    ("1931", "C"): (98.074, 118.232),
    ("1931", "D50"): (96.422, 82.521),
    ("1931", "D55"): (95.682, 92.149),
    ("1931", "D65"): (95.047, 108.883),
    ("1931", "D75"): (94.972, 122.638),
    ("1931", "F2"): (99.187, 67.395),
    ("1931", "F7"): (95.044, 108.755),
    ("1931", "F11"): (100.966, 64.370),
    ("1964", "A"): (111.144, 35.200),
    ("1964", "C"): (97.285, 116.145),
    ("1964", "D50"): (96.720, 81.427),
    ("1964", "D55"): (95.799, 90.926),
    ("1964", "D65"): (94.811, 107.304),
    ("1964", "D75"): (94.416, 120.641),
    ("1964", "F2"): (103.280, 69.026),
    ("1964", "F7"): (95.792, 107.687),
    ("1964", "F11"): (103.866, 65.627),
}
# Not reached with CIE 015:2018's 380–780 nm FL tables (misses up to 0.020 in Z for F11, both
# observers): E308's lamp data differ from CIE 015:2018's. What is known of the difference is pinned
# by test_diagnosis_* below and written up in docs/astm_e308.md ("Known gap").
_FL_REASON = "E308 F white points not reached with CIE 015:2018 FL tables (E308's lamp data differ)"
_FL_GAPS = {("1931", "F2"), ("1931", "F7"), ("1931", "F11"), ("1964", "F2"), ("1964", "F7"), ("1964", "F11")}


@pytest.mark.parametrize(
    ("observer", "name"),
    [
        pytest.param(*key, marks=pytest.mark.xfail(strict=True, reason=_FL_REASON)) if key in _FL_GAPS else key
        for key in E308_WHITE_POINTS
    ],
)
@pytest.mark.parametrize(("step", "start"), [(10, 360), (10, 380), (20, 360), (20, 380)])
def test_weight_sums_reproduce_e308_printed_white_points(observer, name, step, start):
    """Within one unit of the printed last digit (0.001) for every table: 10 and 20 nm, 360 and 380 nm."""
    illuminant = {"F2": "FL2", "F7": "FL7", "F11": "FL11"}.get(name, name)
    start = max(start, 380) if illuminant.startswith("FL") else start
    white = astm_e308_weights(sc.wavelength_grid(start, 780, step), observer, illuminant).sum(axis=0)
    X, Z = E308_WHITE_POINTS[observer, name]
    np.testing.assert_allclose(white, [X, 100.0, Z], rtol=0, atol=1e-3)


def _fl_lamp_from_360nm(name, value_at_425nm=None):
    """CIE 015:2018's 5 nm FL table, 360–375 nm held at the 380 nm value, optionally one value
    changed, at 1 nm by E2022's Lagrange scheme: a candidate for the lamp data E308 used."""
    table = sc.illuminant(name)
    values = table.values.copy()
    if value_at_425nm is not None:
        # exact: whole-nanometre wavelengths: small integers, exact in any arithmetic
        values[table.wavelengths_nm == 425.0] = value_at_425nm
    wavelengths = np.r_[360.0, 365.0, 370.0, 375.0, table.wavelengths_nm]
    values = np.r_[np.full(4, values[0]), values]
    return Spectrum(FINE, lagrange_matrix(wavelengths, FINE) @ values)


@pytest.mark.parametrize("observer", ["1931", "1964"])
def test_diagnosis_e308_f11_white_point_is_met_with_3_38_at_425nm(observer):
    """The F11 gap is one table value. CIE 015:2018's FL11 has 3.33 at 425 nm; with 3.38 there (the
    value in a vendor's copy of the F11/TL84 table, see docs/astm_e308.md) every E308 F11 white-point
    coordinate is met within 0.001, in both observers, while 3.33 misses Z by 0.017–0.020. One number
    explaining four coordinates (two observers) is the evidence (+0.03 at 445 nm would fit too; 3.38
    is the value seen in a real table); no printed E308 lamp table was available to confirm it, so
    the shipped CIE table is not changed."""
    grid = sc.wavelength_grid(360, 780, 10)
    X, Z = E308_WHITE_POINTS[observer, "F11"]
    cie = astm_e308_weights(grid, observer, _fl_lamp_from_360nm("FL11")).sum(axis=0)
    candidate = astm_e308_weights(grid, observer, _fl_lamp_from_360nm("FL11", 3.38)).sum(axis=0)
    assert abs(cie[2] - Z) > 0.015
    np.testing.assert_allclose(candidate, [X, 100.0, Z], rtol=0, atol=1e-3)


@pytest.mark.parametrize(("observer", "miss_from_380nm"), [("1931", 0.0086), ("1964", 0.0010)])
def test_diagnosis_e308_f7_white_point_is_met_with_lamp_power_below_380nm(observer, miss_from_380nm):
    """F7's gap is the 360–375 nm range E308's lamp tables cover and CIE 015:2018's do not: from
    380 nm the CIE table misses Z by 0.0086 in 2° but 0.0010 in 10° (x̄, z̄ below 380 nm are about
    nine times larger in 2°); held at its 380 nm value down to 360 nm it meets E308 within 0.001."""
    X, Z = E308_WHITE_POINTS[observer, "F7"]
    from_380 = astm_e308_weights(sc.wavelength_grid(380, 780, 10), observer, "FL7").sum(axis=0)
    from_360 = astm_e308_weights(sc.wavelength_grid(360, 780, 10), observer, _fl_lamp_from_360nm("FL7")).sum(axis=0)
    assert from_380[2] - Z == pytest.approx(-miss_from_380nm, abs=5e-5)
    np.testing.assert_allclose(from_360, [X, 100.0, Z], rtol=0, atol=1e-3)


def test_illuminant_spectrum_on_a_shorter_range_shortens_the_reference_range():
    spd = sc.illuminant("D65", np.arange(400.0, 701.0))
    W = astm_e308_weights(sc.wavelength_grid(400, 700, 10), "1931", spd)
    np.testing.assert_allclose(
        W.sum(axis=0), sc.white_point(spd, observer="1931", wavelengths_nm=np.arange(400.0, 701.0)), rtol=1e-13
    )


def test_illuminant_spectrum_at_1nm_equals_the_named_one():
    spd = sc.illuminant("D65", FINE)
    grid = sc.wavelength_grid(400, 700, 20)
    # exact: D65 is tabulated at 1 nm: both pick the same table values, no interpolation
    np.testing.assert_array_equal(astm_e308_weights(grid, "1931", spd), astm_e308_weights(grid, "1931", "D65"))


def test_weights_are_read_only_and_cached_through_the_public_function():
    grid = sc.wavelength_grid(400, 700, 10)
    W = sc.weights(grid, observer="1931", illuminant="D65", method="astm-e308")
    assert not W.flags.writeable
    assert sc.weights(grid, observer="1931", illuminant="D65", method="astm-e308") is W


@settings(max_examples=40, deadline=None)
@given(
    a=arrays(np.float64, 16, elements=st.floats(0, 1)),
    b=arrays(np.float64, 16, elements=st.floats(0, 1)),
    s=st.floats(-3, 3),
)
def test_tristimulus_is_linear(a, b, s):
    grid = sc.wavelength_grid(400, 700, 20)

    def xyz(values):
        return sc.tristimulus(Spectrum(grid, values), observer="1964", illuminant="D65", method="astm-e308")

    np.testing.assert_allclose(xyz(a + s * b), xyz(a) + s * xyz(b), rtol=1e-12, atol=1e-10)


@pytest.mark.parametrize(
    ("wavelengths", "message"),
    [
        (np.arange(400.0, 701.0, 2), "1, 5, 10 or 20 nm"),
        (np.r_[400.0, 410, 430, 440], "uniform interval"),
        (np.arange(400.5, 700, 10), "whole nanometres"),
        (np.arange(350.0, 701.0, 10), "reaches outside 360–830"),
        (np.array([500.0]), "at least two"),
    ],
)
def test_bad_grids_are_refused(wavelengths, message):
    with pytest.raises(ColorimetryError, match=message):
        astm_e308_weights(wavelengths, "1931", "D65")


def test_lights_are_refused():
    with pytest.raises(ColorimetryError, match="need an illuminant"):
        sc.weights(sc.wavelength_grid(400, 700, 10), observer="1931", illuminant=None, method="astm-e308")


def test_illuminant_spectrum_without_1nm_values_is_refused():
    with pytest.raises(ColorimetryError, match="every 1 nm from 360 to 780"):
        astm_e308_weights(
            sc.wavelength_grid(400, 700, 10), "1931", sc.illuminant("D65", sc.wavelength_grid(360, 780, 5))
        )


def test_data_outside_a_fluorescent_illuminants_range_are_refused():
    with pytest.raises(ColorimetryError, match="380–780"):
        astm_e308_weights(sc.wavelength_grid(360, 780, 10), "1931", "FL2")


@pytest.mark.parametrize(
    ("table", "observer", "illuminant", "step"),
    [
        ("TWF_A_CIE_1964_10_10", "1964", "A", 10),
        ("TWF_A_CIE_1964_10_20", "1964", "A", 20),
        ("TWF_D65_CIE_1931_2_20", "1931", "D65", 20),
    ],
)
def test_weights_reproduce_e308_table_5_as_typed_in_by_colour_science(table, observer, illuminant, step):
    """colour-science 0.4.7's tests carry three E308-15 weight tables (360–830 nm, three decimals
    as printed), cited there as "matching ASTM E308-15" without a table number; they are the weights
    without bandpass correction, E308's Table 5 (docs/astm_e308.md); ours round to the same digits."""
    printed = getattr(pytest.importorskip("colour.colorimetry.tests.test_tristimulus_values"), table)
    W = astm_e308_weights(np.arange(360.0, 831.0, step), observer, illuminant)
    # exact: printed digits of a value known to ~1e-13: it moves only at a tie of the last digit
    np.testing.assert_array_equal(np.round(W, 3) + 0.0, np.asarray(printed) + 0.0)


# ---------------------------------------------------------------- Table 6 (data not corrected for bandpass)
@pytest.mark.parametrize("observer", ["1931", "1964"])
@pytest.mark.parametrize("illuminant", ["D65", "A", "FL11"])
@pytest.mark.parametrize(("step", "start", "stop"), [(10, 380, 780), (10, 400, 700), (20, 380, 760), (20, 420, 700)])
def test_table6_on_uncorrected_data_equals_table5_on_stearns_stearns_corrected_data(
    observer, illuminant, step, start, stop
):
    """Table 6's defining property: E308's bandpass correction folded into the weights of the same grid."""
    grid = sc.wavelength_grid(start, stop, step)
    measured = Spectrum(grid, np.random.default_rng(start + step).random((20, grid.size)))
    table6 = sc.tristimulus(measured, observer=observer, illuminant=illuminant, method="astm-e308-table6")
    table5 = sc.tristimulus(bandpass_correction(measured), observer=observer, illuminant=illuminant, method="astm-e308")
    np.testing.assert_allclose(table6, table5, rtol=1e-12, atol=1e-12)


@pytest.mark.parametrize(("step", "start"), [(10, 360), (10, 380), (20, 360), (20, 380)])
def test_table6_has_table5s_white_point(step, start):
    grid = sc.wavelength_grid(start, 780, step)
    np.testing.assert_allclose(
        astm_e308_table6_weights(grid, "1964", "D50").sum(axis=0),
        astm_e308_weights(grid, "1964", "D50").sum(axis=0),
        rtol=1e-13,
    )


def test_table6_brings_triangular_bandpass_data_closer_to_the_1nm_truth():
    """The 14 CIE test colour samples at 1 nm (5 nm table, E2022 Lagrange to 1 nm) measured through
    a 10 nm triangular bandpass at 10 nm: Table 6 on the raw readings lands nearer the 1 nm XYZ
    than Table 5 does, for every sample."""
    from importlib.resources import files

    tcs = sc.read_spectra(files("spectrocolor") / "data" / "reflectances_cie_tcs.csv")
    fine = np.arange(360.0, 781.0)
    true = tcs.values @ lagrange_matrix(tcs.wavelengths_nm, fine).T
    grid = sc.wavelength_grid(370, 770, 10)
    triangle = np.clip(1 - np.abs(fine[None, :] - grid[:, None]) / 10.0, 0, None)
    measured = Spectrum(grid, true @ (triangle / triangle.sum(axis=1, keepdims=True)).T)
    reference = sc.tristimulus(Spectrum(fine, true), observer="1931", illuminant="D65", method="sum")
    errors = {
        table: np.abs(sc.tristimulus(measured, observer="1931", illuminant="D65", method=table) - reference).max(axis=1)
        for table in ("astm-e308", "astm-e308-table6")
    }
    assert np.all(errors["astm-e308-table6"] < errors["astm-e308"])


@pytest.mark.parametrize("step", [1, 5])
def test_table6_is_refused_for_intervals_e308_has_no_table6_for(step):
    with pytest.raises(ColorimetryError, match="Table 6 .* is for 10 or 20 nm data"):
        sc.weights(sc.wavelength_grid(400, 700, step), observer="1931", illuminant="D65", method="astm-e308-table6")


def test_the_uncorrected_alias_names_table6():
    grid = sc.wavelength_grid(400, 700, 20)
    # exact: the alias calls the same function with the same arguments
    np.testing.assert_array_equal(
        sc.weights(grid, observer="1931", illuminant="D65", method="astm-e308-uncorrected"),
        astm_e308_table6_weights(grid, "1931", "D65"),
    )


def test_cli_method_astm_e308_table6_equals_the_library(capsys):
    """``--method astm-e308-table6`` on the command line gives the library's Table 6 numbers."""
    import csv
    import io
    from importlib.resources import files

    from spectrocolor.cli import main

    path = str(files("spectrocolor") / "data" / "reflectances_colorchecker_babel.csv")  # 380–730 nm, 10 nm
    assert main(["xyz", path, "--method", "astm-e308-table6", "--format", "csv", "--observer", "1964"]) == 0
    rows = list(csv.DictReader(io.StringIO(capsys.readouterr().out)))
    XYZ = sc.tristimulus(sc.read_spectra(path), observer="1964", illuminant="D65", method="astm-e308-table6")
    got = np.array([[float(row[c]) for c in "XYZ"] for row in rows])
    # exact: the command runs the same calls on the same file here, and prints repr (17 digits)
    np.testing.assert_array_equal(got, XYZ)


@settings(max_examples=60, deadline=None)
@given(
    start=st.one_of(st.integers(300, 800), st.floats(allow_nan=True, allow_infinity=True)),
    step=st.one_of(st.sampled_from([1, 5, 10, 20, 2, 0, -10]), st.floats(-30, 30)),
    count=st.integers(0, 50),
    method=st.sampled_from(["astm-e308", "astm-e308-table6"]),
)
def test_fuzz_any_grid_gives_weights_with_y_100_or_one_clear_error(start, step, count, method):
    grid = start + step * np.arange(count, dtype=float)
    try:
        W = sc.weights(grid, observer="1931", illuminant="D65", method=method)
    except (ColorimetryError, SpectrumError):
        return
    assert W.shape == (grid.size, 3) and np.all(np.isfinite(W))
    assert W[:, 1].sum() == pytest.approx(100.0, rel=1e-12)
