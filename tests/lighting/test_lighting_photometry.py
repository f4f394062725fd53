"""Photometry, CIE S 026 α-opic quantities and CIECAM02/CAM02-UCS: published values, cross-checks."""

from __future__ import annotations

import colour
import numpy as np
import pytest

from spectrocolor import Spectrum, illuminant, wavelength_grid
from spectrocolor.errors import ColorimetryError, SpectrumError
from spectrocolor.lighting import (
    alpha_opic,
    alpha_opic_irradiance,
    d65_efficacies_W_per_lm,
    luminous_efficacy_of_radiation,
    luminous_quantity,
    radiant_quantity,
)
from spectrocolor.lighting.alpha_opic import action_spectra
from spectrocolor.lighting.cam02ucs import cam02ucs, cam02ucs_jab, ciecam02_jmh

# CIE S 026/E:2018 (Table 4 of the standard, and its toolbox): α-opic efficacies of luminous
# radiation of D65, mW/lm, printed to 4 decimals (s-cone, m-cone, l-cone, rhodopic, melanopic).
S026_D65_EFFICACY_MW_PER_LM = [0.8173, 1.4558, 1.6289, 1.4497, 1.3262]


def test_d65_efficacies_reproduce_the_published_constants():
    np.testing.assert_allclose(d65_efficacies_W_per_lm() * 1000, S026_D65_EFFICACY_MW_PER_LM, atol=0.5e-4, rtol=0)


def test_d65_has_der_one_and_edi_equal_to_its_illuminance():
    d65 = illuminant("D65", wavelength_grid(380, 780, 1))
    scaled = Spectrum(d65.wavelengths_nm, d65.values * 0.0123)  # some W·m⁻²·nm⁻¹
    result = alpha_opic(scaled)
    np.testing.assert_allclose(result.der, 1.0, rtol=1e-12)
    np.testing.assert_allclose(result.edi_lx, result.illuminance_lx, rtol=1e-12)


def test_alpha_opic_is_linear_and_its_ratios_scale_free():
    grid = wavelength_grid(380, 780, 5)
    a = illuminant("A", grid)
    twice = Spectrum(grid, 2 * a.values)
    np.testing.assert_allclose(alpha_opic_irradiance(twice), 2 * alpha_opic_irradiance(a), rtol=1e-14)
    np.testing.assert_allclose(alpha_opic(twice).der, alpha_opic(a).der, rtol=1e-14)


def test_melanopic_irradiance_of_a_monochromatic_line_is_the_action_spectrum():
    grid = wavelength_grid(380, 780, 1)  # the α-opic quantities need 380–780 nm
    line = Spectrum.block(490, 490, grid)  # 1 W·m⁻²·nm⁻¹ over Δλ = 1 nm at the melanopic peak
    assert float(alpha_opic_irradiance(line)[4]) == pytest.approx(1.0, abs=1e-15)
    np.testing.assert_allclose(action_spectra([490.0])[0], [0.185297, 0.456137, 0.282752, 0.904, 1.0])


def test_rhodopic_action_spectrum_is_the_scotopic_efficiency_of_colour_science():
    scotopic = colour.colorimetry.SDS_LEFS_SCOTOPIC["CIE 1951 Scotopic Standard Observer"]
    grid = np.arange(380.0, 781.0)
    np.testing.assert_allclose(action_spectra(grid)[:, 3], scotopic[grid], atol=1e-6)


def test_photopic_flux_and_ler_agree_with_colour_science():
    # colour-science integrates with the trapezoidal rule, CIE 015 (and we) sum S V Δλ at the
    # samples; the two are the same sum when the spectrum is zero at both ends
    for name in ("A", "D65", "FL2", "LED-B1"):
        light = illuminant(name).restrict(380, 780).resample(wavelength_grid(380, 780, 1))
        values = light.values.copy()
        values[[0, -1]] = 0.0
        light = Spectrum(light.wavelengths_nm, values)
        sd = colour.SpectralDistribution(values, light.wavelengths_nm)
        assert float(luminous_quantity(light)) == pytest.approx(colour.luminous_flux(sd), rel=1e-12)
        assert float(luminous_efficacy_of_radiation(light)) == pytest.approx(colour.luminous_efficacy(sd), rel=1e-12)
        scotopic = colour.colorimetry.SDS_LEFS_SCOTOPIC["CIE 1951 Scotopic Standard Observer"]
        assert float(luminous_quantity(light, "scotopic")) == pytest.approx(
            colour.luminous_flux(sd, scotopic, 1700.0), rel=1e-6)


def test_luminous_quantity_of_a_555_nm_watt_is_683_lumen():
    line = Spectrum.block(555, 555, wavelength_grid(380, 780, 1))  # photometry needs 380–780 nm
    assert float(luminous_quantity(line)) == pytest.approx(683.0, abs=1e-9)
    assert float(radiant_quantity(line)) == 1.0  # exact: one sample of 1 W/nm times 1 nm: a single exact product
    # scotopic: V'(555 nm) = 0.402 (CIE 1951), K'm = 1700 lm/W
    assert float(luminous_quantity(line, "scotopic")) == pytest.approx(1700 * 0.402, abs=1e-9)


def test_batched_photometry_keeps_the_batch_shape():
    grid = wavelength_grid(380, 780, 5)
    cube = Spectrum(grid, np.random.default_rng(0).uniform(0, 1, (2, 3, grid.size)))
    assert luminous_quantity(cube).shape == (2, 3)
    assert alpha_opic(cube).edi_lx.shape == (2, 3, 5)
    assert luminous_efficacy_of_radiation(cube).shape == (2, 3)


def test_bad_input_gets_one_clear_error():
    with pytest.raises(SpectrumError, match="Spectrum"):
        luminous_quantity(np.ones(10))
    with pytest.raises(ColorimetryError, match="vision"):
        luminous_quantity(illuminant("D65"), vision="mesopic")
    with pytest.raises(SpectrumError, match="finite"):
        alpha_opic(Spectrum([380, 780], [1.0, np.inf]))


# ---------------------------------------------------------------------------- CIECAM02 / CAM02-UCS
def test_ciecam02_matches_colour_science_on_random_colours():
    rng = np.random.default_rng(4)
    XYZ = rng.uniform(1, 95, (200, 3))
    white = np.array([95.05, 100.0, 108.88])
    for surround, discount in (("average", True), ("dim", False), ("dark", False)):
        conditions = colour.VIEWING_CONDITIONS_CIECAM02[surround.capitalize()]
        theirs = colour.XYZ_to_CIECAM02(XYZ, white, 64.0, 20.0, conditions, discount_illuminant=discount)
        ours = ciecam02_jmh(XYZ, white, 64.0, 20.0, surround, discount)
        np.testing.assert_allclose(ours.J, theirs.J, rtol=1e-12)
        np.testing.assert_allclose(ours.M, theirs.M, rtol=1e-10)
        np.testing.assert_allclose(ours.h, theirs.h, atol=1e-9)
        jab = colour.JMh_CIECAM02_to_CAM02UCS(np.stack([theirs.J, theirs.M, theirs.h], axis=-1))
        np.testing.assert_allclose(cam02ucs(ours), jab, atol=1e-10)
        np.testing.assert_allclose(cam02ucs_jab(XYZ, white, 64.0, 20.0, surround, discount), jab, atol=1e-10)


def test_ciecam02_bad_conditions_get_one_clear_error():
    with pytest.raises(ColorimetryError, match="surround"):
        ciecam02_jmh([20, 20, 20], [95, 100, 108], surround="bright")
    with pytest.raises(ColorimetryError, match="L_A"):
        ciecam02_jmh([20, 20, 20], [95, 100, 108], L_A=-1.0)
    with pytest.raises(ColorimetryError, match="XYZ100"):
        ciecam02_jmh([20, 20], [95, 100, 108])
