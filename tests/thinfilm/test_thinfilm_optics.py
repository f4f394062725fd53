"""Thin-film optics: two-beam model (seed 000), Airy single film, transfer matrices, media."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from spectrocolor.errors import SpectrumError
from spectrocolor.thinfilm import media
from spectrocolor.thinfilm.films import film_on_glass, oil_on_water, soap_film
from spectrocolor.thinfilm.optics import (
    optical_path_difference,
    stack_optics,
    thin_film,
    thin_film_reflectance,
    two_beam_reflectance,
)

WL = np.linspace(380.0, 780.0, 81)


# --- seed 000, eqs. (6)-(8) -------------------------------------------------------------


def test_two_beam_equals_seed_eq8_evaluated_independently():
    # eq. (8) numerator 1 + β² − 2β cos(2πs/λ), one (s, λ) pair at a time, in plain Python
    import math

    opd = np.array([0.0, 5.0, 123.4, 1000.0, 4995.0])
    beta = 0.95
    got = two_beam_reflectance(opd, WL, beta=beta)
    assert got.shape == (5, 81)
    for i, s in enumerate(opd):
        for k, lam in enumerate(WL):
            want = 1 + beta**2 - 2 * beta * math.cos(2 * math.pi * s / lam)
            assert got[i, k] == pytest.approx(want, rel=0, abs=1e-14)


def test_two_beam_extremes_and_beta():
    # s = λ: constructive for the back beam relative to the sign-flipped front beam -> minimum
    assert two_beam_reflectance(500.0, [500.0], beta=0.95)[0] == pytest.approx(0.05**2)
    assert two_beam_reflectance(250.0, [500.0], beta=0.95)[0] == pytest.approx(1.95**2)
    # exact: β = 0: 1 + 0 − 0 · cos(…) is exactly 1
    assert np.all(two_beam_reflectance(np.linspace(0, 3000, 7), WL, beta=0.0) == 1.0)
    # equal phase changes at both surfaces (β < 0): s = λ is now a maximum, s = λ/2 a minimum
    assert two_beam_reflectance(500.0, [500.0], beta=-0.3)[0] == pytest.approx(1.3**2)
    assert two_beam_reflectance(250.0, [500.0], beta=-0.3)[0] == pytest.approx(0.7**2)
    with pytest.raises(SpectrumError, match="beta"):
        two_beam_reflectance(100.0, WL, beta=1.5)
    with pytest.raises(SpectrumError, match="beta"):
        two_beam_reflectance(100.0, WL, beta=-1.01)
    with pytest.raises(SpectrumError, match="opd_nm"):
        two_beam_reflectance(-1.0, WL)


def test_optical_path_difference_is_2dn_at_normal_incidence():
    assert optical_path_difference(250.0, 1.33) == pytest.approx(2 * 250 * 1.33)
    # oblique: 2 d n cos θ_t with Snell's law
    theta_t = np.arcsin(np.sin(np.radians(40.0)) / 1.33)
    assert optical_path_difference(250.0, 1.33, 40.0) == pytest.approx(
        2 * 250 * 1.33 * np.cos(theta_t)
    )


def test_two_beam_matches_exact_film_in_the_weak_reflection_limit():
    # For a weakly reflecting film (n close to 1) the exact R ≈ α²(1 + 1 − 2cos) with β -> 1.
    n = 1.05
    alpha2 = ((n - 1) / (n + 1)) ** 2
    d = np.linspace(0, 2000, 41)
    exact = thin_film_reflectance(d, WL, n)
    approx = alpha2 * two_beam_reflectance(2 * d * n, WL, beta=1.0)
    np.testing.assert_allclose(exact, approx, atol=4 * alpha2**2 * 4)


# --- exact single film vs transfer matrices ----------------------------------------------


@pytest.mark.parametrize("polarisation", ["s", "p", "unpolarised"])
@pytest.mark.parametrize("angle", [0.0, 25.0, 50.0, 75.0, 89.0])
def test_tmm_equals_airy_closed_form(polarisation, angle):
    d = np.linspace(0.0, 1500.0, 301)
    film, sub = media.water(), media.bk7()
    airy = thin_film(d, WL, film, substrate=sub, angle_deg=angle, polarisation=polarisation)
    tmm = stack_optics(d[:, None], WL, [film], substrate=sub, angle_deg=angle,
                       polarisation=polarisation)
    np.testing.assert_allclose(tmm.reflectance, airy.reflectance, rtol=0, atol=1e-12)
    np.testing.assert_allclose(tmm.transmittance, airy.transmittance, rtol=0, atol=1e-12)


@pytest.mark.parametrize("polarisation", ["s", "p"])
def test_tmm_equals_airy_for_absorbing_film_and_metal_substrate(polarisation):
    d = np.linspace(0.0, 400.0, 81)
    film, metal = 2.0 + 0.3j, 0.15 + 3.5j
    airy = thin_film(d, WL, film, substrate=metal, angle_deg=35.0, polarisation=polarisation)
    tmm = stack_optics(d[:, None], WL, [film], substrate=metal, angle_deg=35.0,
                       polarisation=polarisation)
    np.testing.assert_allclose(tmm.reflectance, airy.reflectance, rtol=0, atol=1e-12)
    # power into the metal counts as transmitted; the film itself absorbs only when d > 0
    assert np.all(airy.transmittance >= 0) and np.all(airy.absorptance >= -1e-12)
    assert np.all(airy.absorptance[1:] > 0)


def test_zero_thickness_film_is_the_bare_interface():
    r = thin_film_reflectance(0.0, WL, 1.8, substrate=1.5)
    np.testing.assert_allclose(r, ((1 - 1.5) / (1 + 1.5)) ** 2, atol=1e-15)


def test_brewster_angle_p_reflectance_vanishes():
    # bare glass interface at Brewster's angle: R_p = 0
    brewster = np.degrees(np.arctan(1.5))
    out = stack_optics(np.zeros((0,)), WL, [], substrate=1.5, angle_deg=brewster,
                       polarisation="p")
    np.testing.assert_allclose(out.reflectance, 0.0, atol=1e-15)


lossless_index = st.floats(1.0, 3.0)


@settings(max_examples=60, deadline=None)
@given(
    indices=st.lists(lossless_index, min_size=1, max_size=5),
    thicknesses=st.lists(st.floats(0.0, 2000.0), min_size=5, max_size=5),
    ambient=st.floats(1.0, 1.6),
    substrate=lossless_index,
    angle=st.floats(0.0, 89.9),
    polarisation=st.sampled_from(["s", "p", "unpolarised"]),
)
def test_energy_is_conserved_in_lossless_stacks(indices, thicknesses, ambient, substrate, angle,
                                                polarisation):
    d = np.array(thicknesses[: len(indices)])
    out = stack_optics(d, WL, indices, ambient=ambient, substrate=substrate, angle_deg=angle,
                       polarisation=polarisation)
    np.testing.assert_allclose(out.reflectance + out.transmittance, 1.0, rtol=0, atol=1e-12)
    assert np.all(out.reflectance >= -1e-15) and np.all(out.reflectance <= 1 + 1e-12)


@settings(max_examples=40, deadline=None)
@given(
    n=st.floats(1.2, 3.0), k=st.floats(0.0, 2.0), d=st.floats(0.0, 500.0),
    angle=st.floats(0.0, 85.0), polarisation=st.sampled_from(["s", "p"]),
)
def test_absorbing_layers_never_create_energy(n, k, d, angle, polarisation):
    out = stack_optics(np.array([d, 100.0]), WL, [complex(n, k), 1.45], substrate=1.5,
                       angle_deg=angle, polarisation=polarisation)
    assert np.all(out.reflectance + out.transmittance <= 1 + 1e-12)
    assert np.all(out.transmittance >= 0)


@pytest.mark.parametrize("pairs", [1, 4, 10])
def test_quarter_wave_stack_textbook_reflectance(pairs):
    # (HL)^N H on glass at its design wavelength: R = ((1 − Y)/(1 + Y))², with the admittance
    # Y = (n_H/n_L)^(2N) n_H² / n_s  (Macleod, Thin-Film Optical Filters, §2.x / ch. 5)
    n_h, n_l, n_s, lam0 = 2.35, 1.38, 1.52, 550.0
    layers = [n_h, n_l] * pairs + [n_h]
    d = np.array([lam0 / (4 * n) for n in layers])
    out = stack_optics(d, [lam0], layers, substrate=n_s)
    y = (n_h / n_l) ** (2 * pairs) * n_h**2 / n_s
    assert out.reflectance[0] == pytest.approx(((1 - y) / (1 + y)) ** 2, rel=1e-12)


def test_quarter_wave_antireflection_coating():
    # single quarter-wave layer n = sqrt(n_s): zero reflectance at the design wavelength
    n_s = 1.52
    out = stack_optics(np.array([550 / (4 * np.sqrt(n_s))]), [550.0], [np.sqrt(n_s)],
                       substrate=n_s)
    assert out.reflectance[0] == pytest.approx(0.0, abs=1e-15)


def test_batch_and_angle_broadcasting():
    d = np.linspace(0, 600, 7)[:, None]  # (7, 1)
    angles = np.array([0.0, 30.0, 60.0])  # broadcasts to (7, 3)
    out = thin_film(d, WL, 1.33, angle_deg=angles)
    assert out.reflectance.shape == (7, 3, 81)
    one = thin_film(d[3, 0], WL, 1.33, angle_deg=60.0)
    np.testing.assert_allclose(out.reflectance[3, 2], one.reflectance, atol=0)


# --- incoherent thick substrate -----------------------------------------------------------


def test_bare_glass_plate_incoherent_sum():
    # textbook plate: R = 2 R1 / (1 + R1), T = (1 − R1)/(1 + R1) for a lossless slab
    out = film_on_glass(0.0, WL, 1.0, glass=1.5, glass_thickness_nm=1e6)
    r1 = 0.04
    np.testing.assert_allclose(out.reflectance, 2 * r1 / (1 + r1), atol=1e-14)
    np.testing.assert_allclose(out.transmittance, (1 - r1) / (1 + r1), atol=1e-14)


@settings(max_examples=30, deadline=None)
@given(d=st.floats(0.0, 1000.0), n=st.floats(1.2, 2.5), angle=st.floats(0.0, 85.0),
       polarisation=st.sampled_from(["s", "p", "unpolarised"]))
def test_incoherent_substrate_conserves_energy(d, n, angle, polarisation):
    out = film_on_glass(d, WL, n, glass_thickness_nm=1e6, angle_deg=angle,
                        polarisation=polarisation)
    np.testing.assert_allclose(out.reflectance + out.transmittance, 1.0, atol=1e-12)


def test_absorbing_thick_substrate_attenuates_by_beer_lambert():
    k = 1e-6
    lam = np.array([500.0])
    out = stack_optics(np.zeros((0,)), lam, [], substrate=complex(1.5, k),
                       substrate_thickness_nm=1e6, exit_medium=1.5)
    # index-matched exit: one pass, T = (1 − R1) exp(−4πk d/λ)
    assert out.transmittance[0] == pytest.approx(0.96 * np.exp(-4 * np.pi * k * 1e6 / 500), 1e-12)


# --- cross-check with colour-science (tests only) ------------------------------------------


@pytest.mark.parametrize("angles", [[0.0], [0.0, 30.0, 45.0, 70.0]])
def test_matches_colour_science_thin_film_tmm(angles):
    from colour.phenomena import thin_film_tmm

    d = np.linspace(0.0, 1500.0, 151)
    R, T = thin_film_tmm([1.0, 1.33, 1.52], d, WL, angles)  # (W, A, T, [s, p])
    for i, angle in enumerate(angles):
        for j, pol in enumerate("sp"):
            ours = thin_film(d, WL, 1.33, substrate=1.52, angle_deg=angle, polarisation=pol)
            np.testing.assert_allclose(ours.reflectance, R[:, i, :, j].T, rtol=0, atol=1e-12)
            np.testing.assert_allclose(ours.transmittance, T[:, i, :, j].T, rtol=0, atol=1e-12)


def test_matches_colour_science_multilayer_with_dispersion_and_absorption():
    # colour-science 0.4.7 takes the Snell angles from the FIRST wavelength's indices for all
    # wavelengths and real parts only, so with dispersion or absorption the comparison is exact
    # at normal incidence (all wavelengths) and at oblique incidence at the first wavelength.
    from colour.phenomena import multilayer_tmm

    water = media.water().refractive_index(WL)
    n = np.array([np.ones(81), water, np.full(81, 2.0 + 0.4j), np.full(81, 0.2 + 3.0j)])
    R, _ = multilayer_tmm(n, [300.0, 25.0], WL)
    ours = stack_optics(np.array([300.0, 25.0]), WL, [water, 2.0 + 0.4j], substrate=0.2 + 3.0j,
                        polarisation="s")
    np.testing.assert_allclose(ours.reflectance, R[:, 0, 0, 0], rtol=0, atol=1e-12)

    n_lossless = np.array([np.ones(81), water, np.full(81, 1.6), np.full(81, 1.52)])
    R, T = multilayer_tmm(n_lossless, [300.0, 120.0], WL, [0.0, 20.0, 65.0])
    for i, angle in enumerate([0.0, 20.0, 65.0]):
        upto = 81 if angle == 0 else 1
        for j, pol in enumerate("sp"):
            ours = stack_optics(np.array([300.0, 120.0]), WL, [water, 1.6], substrate=1.52,
                                angle_deg=angle, polarisation=pol)
            np.testing.assert_allclose(ours.reflectance[:upto], R[:upto, i, 0, j], atol=1e-12)
            np.testing.assert_allclose(ours.transmittance[:upto], T[:upto, i, 0, j], atol=1e-12)


def test_matches_colour_science_nondispersive_multilayer_at_oblique_incidence():
    from colour.phenomena import multilayer_tmm

    layers, d = [1.38, 2.1, 1.46], [95.0, 60.0, 180.0]
    R, T = multilayer_tmm([1.0, *layers, 1.52], d, WL, [10.0, 45.0, 80.0])
    for i, angle in enumerate([10.0, 45.0, 80.0]):
        for j, pol in enumerate("sp"):
            ours = stack_optics(np.array(d), WL, layers, substrate=1.52, angle_deg=angle,
                                polarisation=pol)
            np.testing.assert_allclose(ours.reflectance, R[:, i, 0, j], rtol=0, atol=1e-12)
            np.testing.assert_allclose(ours.transmittance, T[:, i, 0, j], rtol=0, atol=1e-12)


# --- helpers and media ----------------------------------------------------------------------


def test_helpers_use_the_right_media():
    d = np.array([0.0, 300.0])
    n_w = media.water().refractive_index(WL).real
    np.testing.assert_allclose(soap_film(d, WL).reflectance[0], 0.0, atol=1e-15)
    np.testing.assert_allclose(
        oil_on_water(d, WL).reflectance[0], ((1 - n_w) / (1 + n_w)) ** 2, atol=1e-15
    )
    n_g = media.bk7().refractive_index(WL).real
    np.testing.assert_allclose(
        film_on_glass(d, WL, 1.38).reflectance[0], ((1 - n_g) / (1 + n_g)) ** 2, atol=1e-15
    )


def test_water_formulations_agree():
    # Daimon & Masumura (2007) and IAPWS R9-97, two independent published formulations
    wl = np.linspace(400, 800, 41)
    a = media.water().refractive_index(wl).real
    b = media.water_iapws(293.15, 998.2).refractive_index(wl).real
    np.testing.assert_allclose(a, b, atol=2e-5)
    from colour.phenomena import light_water_refractive_index_Schiebener1990

    np.testing.assert_allclose(
        a, light_water_refractive_index_Schiebener1990(wl, 293.15, 998.2), atol=2e-5
    )


def test_glass_and_oil_reference_values():
    # N-BK7: n_d = 1.5168 (Schott catalogue); fused silica n_d = 1.4585 (Malitson 1965)
    assert media.bk7().refractive_index([587.56])[0].real == pytest.approx(1.5168, abs=1e-4)
    assert media.fused_silica().refractive_index([587.56])[0].real == pytest.approx(1.4585,
                                                                                     abs=1e-4)
    n_d, n_f, n_c = media.typical_oil().refractive_index([587.56, 486.13, 656.27]).real
    assert n_d == pytest.approx(1.470, abs=1e-4)
    assert (n_d - 1) / (n_f - n_c) == pytest.approx(50, abs=0.1)


def test_cauchy_and_sellmeier_formulas():
    m = media.cauchy(1.5, 0.004, 0.0001)
    lam = 0.5
    assert m.refractive_index([500.0])[0] == pytest.approx(1.5 + 0.004 / lam**2 + 0.0001 / lam**4)
    s = media.sellmeier([1.0], [0.01])
    assert s.refractive_index([500.0])[0] == pytest.approx(np.sqrt(1 + 0.25 / (0.25 - 0.01)))


def test_medium_tables_from_csv(tmp_path):
    path = tmp_path / "metal.csv"
    path.write_text("# silver-like test table\nwavelength_nm,n,k\n400,0.2,2.0\n800,0.1,5.0\n")
    m = media.read_medium_csv(path)
    np.testing.assert_allclose(m.refractive_index([400.0, 600.0]), [0.2 + 2.0j, 0.15 + 3.5j])
    with pytest.raises(SpectrumError, match="400-800 nm"):
        m.refractive_index([380.0, 500.0])
    bad = tmp_path / "bad.csv"
    bad.write_text("lambda,n\n400,1.5\n")
    with pytest.raises(SpectrumError, match="wavelength_nm"):
        media.read_medium_csv(bad)


def test_named_media_and_bad_input():
    assert media.medium("water").refractive_index([589.0])[0].real == pytest.approx(1.3333, 1e-4)
    assert media.medium("2.0+0.1j").refractive_index([500.0])[0] == 2.0 + 0.1j
    with pytest.raises(SpectrumError, match="unknown medium"):
        media.medium("unobtainium")
    with pytest.raises(SpectrumError, match="182-1129"):
        media.water().refractive_index([1500.0])
    with pytest.raises(SpectrumError, match="non-absorbing"):
        thin_film(100.0, WL, 1.5, ambient=1.0 + 0.1j)
    with pytest.raises(SpectrumError, match="angle_deg"):
        thin_film(100.0, WL, 1.5, angle_deg=90.0)
    with pytest.raises(SpectrumError, match="polarisation"):
        thin_film(100.0, WL, 1.5, polarisation="circular")
    with pytest.raises(SpectrumError, match="one thickness per layer"):
        stack_optics(np.array([1.0, 2.0]), WL, [1.5])
    with pytest.raises(SpectrumError, match="k >= 0"):
        thin_film(100.0, WL, 1.5 - 0.1j)


def test_bad_thickness_and_angle_types_are_short_spectrum_errors():
    wl = np.arange(400.0, 701.0, 10.0)
    with pytest.raises(SpectrumError, match="thickness.*expected numbers"):
        soap_film("thick", wl)
    with pytest.raises(SpectrumError, match="angle_deg: expected numbers"):
        soap_film([100.0], wl, angle_deg="steep")
    with pytest.raises(SpectrumError) as info:
        soap_film(np.full((100, 100), -5.0), wl)
    assert "-5.0" in str(info.value) and "\n" not in str(info.value)
