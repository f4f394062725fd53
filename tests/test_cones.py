"""Cone responses: the CIE 2006 tables against CVRL's, the CIE 170-2 transform to the shipped
CIE 2015 XYZ functions, colour-science as an independent sum, the normalisations, hostile input."""

from __future__ import annotations

import numpy as np
import pytest

import spectrocolor as sc
from spectrocolor import ColorimetryError, Spectrum, wavelength_grid
from spectrocolor.cones import cone_weights

# CVRL (www.cvrl.org), linss2_10e_5 (the 2° energy fundamentals of CIE 170-1:2006 at 5 nm, whose
# rows are the 1 nm file's linss2_10e_1 rows at those wavelengths), typed as printed (6 digits);
# CVRL leaves s̄ blank beyond 615 nm (0 here).
CVRL_2DEG = {
    400: (2.40836e-03, 2.26991e-03, 5.66498e-02),
    440: (4.02563e-02, 6.47782e-02, 9.91020e-01),
    500: (2.88959e-01, 4.27764e-01, 1.22839e-01),
    550: (9.40198e-01, 9.77193e-01, 1.95896e-03),
    570: (9.99993e-01, 8.13509e-01, 2.81800e-04),
    600: (8.33982e-01, 3.34429e-01, 1.83459e-05),
    650: (1.65141e-01, 1.54480e-02, 0.0),
    700: (5.89749e-03, 3.65317e-04, 0.0),
}
# CVRL linss10e_1 (10°, CIE 170-1:2006), typed as printed.
CVRL_10DEG = {
    400: (2.54073e-03, 2.37208e-03, 3.96308e-02),
    450: (7.95647e-02, 1.39493e-01, 9.91329e-01),
    550: (9.44527e-01, 9.61876e-01, 1.08230e-03),
    600: (8.03173e-01, 3.04378e-01, 1.01356e-05),
}


@pytest.mark.parametrize(("field", "table"), [("2°", CVRL_2DEG), ("10°", CVRL_10DEG)])
def test_the_tables_are_cvrls(field, table):
    lms = sc.cone_fundamentals(field)
    assert lms.names == ("l_bar", "m_bar", "s_bar")
    # exact: the table's wavelengths are whole numbers parsed from the file
    assert (lms.wavelengths_nm[0], lms.wavelengths_nm[-1], lms.wavelengths_nm.size) == (390.0, 830.0, 441)
    for nm, expected in table.items():
        # the shipped file holds the printed 6-digit numbers; parsing both gives the same double
        # to within one ulp, so 1e-12 relative is tight
        np.testing.assert_allclose(lms.values[:, lms.wavelengths_nm == nm].ravel(), expected, rtol=1e-12, atol=0)
    # every function has peak 1 (to the table's 6 digits: the 1 nm maxima are 0.99993–0.999993)
    np.testing.assert_allclose(lms.values.max(axis=1), 1.0, atol=1e-4)


# CIE 170-2:2015, eqs. 8.4 (2°) and 8.5 (10°): XYZ functions from the energy cone fundamentals.
M_2015 = {
    "2": np.array([[1.94735469, -1.41445123, 0.36476327], [0.68990272, 0.34832189, 0.0], [0.0, 0.0, 1.93485343]]),
    "10": np.array([[1.93986443, -1.34664359, 0.43044935], [0.69283932, 0.34967567, 0.0],
                    [0.0, 0.0, 2.14687945]]),
}


@pytest.mark.parametrize("degrees", ["2", "10"])
def test_the_cie_2015_xyz_functions_are_the_cie_170_2_transform_of_the_cone_tables(degrees):
    lms = sc.cone_fundamentals(f"{degrees}°")
    cmfs = sc.observer(f"2015-{degrees}")
    np.testing.assert_array_equal(cmfs.wavelengths_nm, lms.wavelengths_nm)  # exact: both tables' 1 nm grid
    computed = M_2015[degrees] @ lms.values
    # Rounding: each l̄, m̄, s̄ is printed to 6 significant digits, so it is within 5e-6 |v| of the
    # value CVRL transformed; each x̄, ȳ, z̄ is printed to 7 significant digits (within 5e-7 |v|).
    # The transform's error is then at most Σ_j |M_ij| 5e-6 |lms_j| + 5e-7 |xyz_i| (plus a few
    # ulps of double arithmetic); where s̄ is blank (0), z̄ is 0 too and the bound is 0.
    bound = np.abs(M_2015[degrees]) @ (5e-6 * np.abs(lms.values)) + 5e-7 * np.abs(cmfs.values) + 1e-15
    assert np.all(np.abs(computed - cmfs.values) <= bound)
    # and the bound is not vacuous: a 1 % change of one matrix coefficient breaks it
    wrong = M_2015[degrees].copy()
    wrong[1, 0] *= 1.01
    assert not np.all(np.abs(wrong @ lms.values - cmfs.values) <= bound)


def test_each_field_spelling_and_observer_alias_gives_its_table():
    two, ten = sc.cone_fundamentals("2°"), sc.cone_fundamentals("10°")
    for spelling in (2, 2.0, "2", "2deg", "2 degree", "2015-2", "CIE 2015 2°", sc.resolve_observer("2015-2")):
        assert sc.cone_fundamentals(spelling) is two
    for spelling in (10, "10", "10deg", "10°", "2015-10", "1964"):
        assert sc.cone_fundamentals(spelling) is ten
    assert not two.values.flags.writeable


GRID_1NM = wavelength_grid(390, 830, 1)


def _tcs_1nm(name):
    tcs = sc.sample_data("cie_tcs")
    values = tcs.values[list(tcs.names).index(name)]
    return np.interp(GRID_1NM, tcs.wavelengths_nm, values)


@pytest.mark.parametrize("light", ["D65", "A", "FL11"])
@pytest.mark.parametrize("field", ["2", "10"])
def test_reflectances_agree_with_colour_science(light, field):
    colour = pytest.importorskip("colour")
    cmfs = colour.MSDS_CMFS[f"Stockman & Sharpe {field} Degree Cone Fundamentals"]
    spd = sc.illuminant(light, GRID_1NM).values if light != "FL11" else np.interp(
        GRID_1NM, *(lambda s: (s.wavelengths_nm, s.values))(sc.illuminant("FL11")), right=0.0)
    shape = colour.SpectralShape(390, 830, 1)
    illum = colour.SpectralDistribution(dict(zip(GRID_1NM, spd, strict=True)))
    samples = np.array([_tcs_1nm(n) for n in ("TCS01", "TCS05", "TCS09", "TCS12")])
    ours = sc.cone_responses(Spectrum(GRID_1NM, samples), illuminant=Spectrum(GRID_1NM, spd), field=f"{field}°")
    for row, values in zip(ours, samples, strict=True):
        # colour-science's own summation Σ R S l̄ Δλ (k = 1), divided by its white's
        raw = colour.colorimetry.sd_to_XYZ_integration(values, cmfs=cmfs, illuminant=illum, k=1, shape=shape)
        white = colour.colorimetry.sd_to_XYZ_integration(np.ones_like(values), cmfs=cmfs, illuminant=illum, k=1,
                                                            shape=shape)
        # same products in another order: 441 terms, relative rounding well under 1e-12
        np.testing.assert_allclose(row, 100 * np.asarray(raw) / np.asarray(white), rtol=1e-10)


def test_equal_energy_gives_equal_responses():
    grid = wavelength_grid(380, 780, 5)  # reaches below the tables' 390 nm: those samples count 0
    white = Spectrum.constant(1.0, grid)
    np.testing.assert_allclose(sc.cone_responses(white, illuminant="E"), [100, 100, 100], rtol=1e-13)
    # the light E itself (100 everywhere) under "equal-energy"
    light_e = sc.illuminant("E", grid)
    np.testing.assert_allclose(sc.cone_responses(light_e), [100, 100, 100], rtol=1e-13)
    # a grey of 40 % reads 40 under any light, any field
    grey = Spectrum.constant(0.4, grid)
    for light in ("D65", "A", "FL2"):
        np.testing.assert_allclose(sc.cone_responses(grey, illuminant=light, field="10°"), [40, 40, 40], rtol=1e-13)


def test_peak_normalisation_is_the_raw_sum_with_the_table():
    # a 1 nm monochromatic-ish light: 1 at 570 nm alone; Δλ = 1 nm, so L, M, S are the table's row
    grid = wavelength_grid(560, 580, 1)
    line = Spectrum(grid, (grid == 570).astype(float))
    np.testing.assert_allclose(sc.cone_responses(line, normalisation="peak"), CVRL_2DEG[570], rtol=1e-12)
    W = cone_weights(grid)
    np.testing.assert_allclose(W[10], CVRL_2DEG[570], rtol=1e-12)
    W[10] = 0.0  # the caller's copy: the cached weights behind cone_responses are not touched
    np.testing.assert_allclose(sc.cone_responses(line, normalisation="peak"), CVRL_2DEG[570], rtol=1e-12)


def test_the_cones_order_as_the_light_would_suggest():
    grid = wavelength_grid(390, 780, 5)
    red = Spectrum(grid, (grid >= 610).astype(float))
    blue = Spectrum(grid, (grid <= 470).astype(float))
    L, M, S = sc.cone_responses(red, illuminant="D65")
    assert L > M > S >= 0
    L, M, S = sc.cone_responses(blue, illuminant="D65")
    assert S > M and S > L


def test_batches_keep_their_shape_and_match_one_by_one():
    grid = wavelength_grid(400, 700, 10)
    rng = np.random.default_rng(7)
    batch = rng.uniform(0, 1, (2, 3, grid.size))
    out = sc.cone_responses(Spectrum(grid, batch), illuminant="D50")
    assert out.shape == (2, 3, 3)
    # the same weights applied row by row: identical arithmetic per row except BLAS blocking
    np.testing.assert_allclose(out[1, 2], sc.cone_responses(Spectrum(grid, batch[1, 2]), illuminant="D50"),
                               rtol=1e-13)


@pytest.mark.parametrize(
    ("kwargs", "argument"),
    [
        ({"field": 5}, "field"),
        ({"field": "12deg"}, "field"),
        ({"field": True}, "field"),
        ({"field": None}, "field"),
        ({"field": Spectrum(wavelength_grid(400, 700, 10), np.ones((3, 31)))}, "field"),
        ({"normalisation": "max"}, "normalisation"),
        ({"normalisation": "white"}, "normalisation"),
        ({"normalisation": "peak", "illuminant": "D65"}, "normalisation"),
        ({"illuminant": "D99"}, "illuminant"),
    ],
)
def test_hostile_arguments_get_one_error_naming_them(kwargs, argument):
    spectrum = Spectrum.constant(1.0, wavelength_grid(400, 700, 10))
    with pytest.raises(ColorimetryError) as info:
        sc.cone_responses(spectrum, **kwargs)
    assert str(info.value).startswith(argument)


def test_hostile_spectra():
    with pytest.raises(ColorimetryError, match="^spectrum: expected a spectrocolor.Spectrum"):
        sc.cone_responses(np.ones(31))
    with pytest.raises(ColorimetryError, match="^wavelengths_nm: summation needs at least two"):
        sc.cone_responses(Spectrum([550.0], [1.0]))
    # entirely outside the tables: nothing to normalise by, said once
    far = Spectrum.constant(1.0, wavelength_grid(850, 900, 10))
    with pytest.raises(ColorimetryError, match="^spectrum: an equal-energy light excites the cones"):
        sc.cone_responses(far)
    # a red-only light leaves the S cones unexcited: the white cannot be 100 for S
    grid = wavelength_grid(400, 700, 10)
    with pytest.raises(ColorimetryError, match="^illuminant: the illuminant's white excites"):
        sc.cone_responses(Spectrum.constant(1.0, grid), illuminant=Spectrum(grid, (grid >= 650).astype(float)))
    assert np.isnan(sc.cone_responses(Spectrum(grid, np.full(grid.size, np.nan)), illuminant="D65")).all()


def test_the_explorer_cards_carry_l_m_s_scaled_to_their_white():
    from spectrocolor.app import compute

    wl = compute.grid(10)
    full, half = [30.0] * wl.size, [15.0] * wl.size
    r = compute.evaluate(10, "2015-10", "sRGB", compute.DEFAULT_NORMALISE, "clip", [full, half])
    # the full spectrum is the white of settings 1–3 and 5: 100 each; half of it, 50 each
    np.testing.assert_allclose([c["LMS"] for c in r["colours"]], [[100] * 3, [50] * 3], rtol=1e-13)
    assert r["lms_note"] is None
    # the page's own numbers are the library's, with the observer's field (10° here)
    sample = (np.arange(wl.size) % 7 + 1) * 4.0
    r = compute.evaluate(10, "2015-10", "sRGB", compute.DEFAULT_NORMALISE, "clip", [sample.tolist()])
    expected = sc.cone_responses(Spectrum(wl, sample / 30), illuminant="E", field="10°")
    np.testing.assert_allclose(r["colours"][0]["LMS"], expected, rtol=1e-13)
    # a red line illuminant (650 nm) leaves the S cones of its white unexcited: no L M S, and why
    red = [0.0] * wl.size
    red[25] = 30.0
    r = compute.evaluate(10, "1931", "sRGB", compute.DEFAULT_NORMALISE, "clip", [full, half], red)
    assert r["colours"][1]["LMS"] == [None, None, None] and r["lms_note"].startswith("L M S undefined")
