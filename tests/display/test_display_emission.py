"""SPECTRA's step 4: the primaries' emission spectra and the emitted light C(λ) (seed 002).

XYZ are recomputed independently from colour-science's CIE 1931 table, summed at the bins with
k = 100 / Σ ȳ (the equal-energy spectrum has Y = 100), and compared with the display's primaries
(for SPECTRA's monitor, the seed's measured table typed in from the Appendix)."""

from __future__ import annotations

import colour
import numpy as np
import pytest

import spectrocolor as sc
from spectrocolor.display_emission import (
    emission_sources,
    emitted_light,
    excitation_function,
    measured_primaries,
    primary_emission,
)

CMFS = colour.MSDS_CMFS["CIE 1931 2 Degree Standard Observer"]

# Seed 002, Appendix: X, Y, Z of the phosphors R, G, B of SPECTRA's monitor (columns).
SEED_PHOSPHORS = np.array([[44.68, 34.08, 20.12], [24.81, 73.16, 8.864], [2.586, 13.02, 105.5]])


def xyz_of_light(spectrum):
    """Independent XYZ of a light on the 'E at Y = 100 is 1.0' scale: 100 Σ S c̄ / Σ ȳ."""
    wl = spectrum.wavelengths_nm
    cmf = np.array([CMFS[w] for w in wl])
    return 100 * np.asarray(spectrum.values) @ cmf / cmf[:, 1].sum()


@pytest.mark.parametrize("step", [10.0, 5.0, 1.0])
def test_spectra_monitor_primaries_have_the_seeds_measured_tristimulus_values(step):
    wl = sc.wavelength_grid(400, 700, step)
    p = primary_emission("SPECTRA 7000K", wl)
    # the fit is exact to 1e-9 relative; the table itself is given to 4 significant figures
    np.testing.assert_allclose(xyz_of_light(p), SEED_PHOSPHORS.T, rtol=1e-8, atol=1e-8)
    assert emission_sources("SPECTRA 7000K", wl) == ("typical CRT, P22 phosphors (Brainard 1997),"
                                                     " reshaped",) * 3


@pytest.mark.parametrize("display", ["sRGB", "Display P3"])
def test_srgb_and_p3_primaries_have_the_spaces_chromaticities(display):
    space = sc.rgb_space(display)
    p = primary_emission(display)
    XYZ = xyz_of_light(p)
    xy = XYZ[:, :2] / XYZ.sum(axis=1, keepdims=True)
    expected = {"sRGB": [[0.64, 0.33], [0.30, 0.60], [0.15, 0.06]],  # IEC 61966-2-1
                "Display P3": [[0.680, 0.320], [0.265, 0.690], [0.150, 0.060]]}[display]
    sources = emission_sources(display)
    for c in range(3):
        # P3's red lies on the locus edge (x + y = 1): the model says how far it misses
        tol = 2e-4 if "off by" in sources[c] else 1e-9
        np.testing.assert_allclose(xy[c], expected[c], atol=tol)
    np.testing.assert_allclose(XYZ.sum(axis=0)[1], space.white_XYZ[1], rtol=1e-3)
    assert "model band" in sources[0] and "model" not in sources[1] + sources[2]


@pytest.mark.parametrize("step", [10.0, 5.0, 1.0])
def test_srgb_red_has_no_spike_at_the_700_nm_edge(step):
    # issue 28, glitch 7: the reshaped CRT red peaked at 700 nm (the 705 nm europium line lifted
    # ninefold). A display primary's emission peaks inside the visible range and falls towards
    # its edges; the red's XYZ stays exact, so the emitted light still matches the colour.
    wl = sc.wavelength_grid(400, 700, step)
    red = primary_emission("sRGB", wl).values[0]
    peak = wl[np.argmax(red)]
    assert 600 <= peak <= 640  # the orange-red band of a red primary, well inside 400-700 nm
    assert red[-1] < 0.05 * red.max() and red[-1] <= red[-2]  # the edge falls off, no spike
    assert np.all(red >= 0)
    XYZ = xyz_of_light(primary_emission("sRGB", wl))[0]
    # the fit is one 3 x 3 linear solve: exact to rounding (1e-9 relative is ample)
    np.testing.assert_allclose(XYZ, sc.rgb_space("sRGB").matrix_to_XYZ[:, 0], rtol=1e-9)


def test_measured_primaries_are_the_published_table():
    table = colour.characterisation.MSDS_DISPLAY_PRIMARIES["Typical CRT Brainard 1997"]
    wl = np.asarray(table.wavelengths)
    # exact: the published table's own numbers at its own wavelengths
    np.testing.assert_array_equal(measured_primaries(wl).values, np.asarray(table.values).T)


def test_figure_9_shapes_red_green_blue_peaks():
    # seed 002 Fig. 9: orange-red, yellow-green and blue phosphors
    p = primary_emission("SPECTRA 7000K", sc.wavelength_grid(400, 700, 1))
    peaks = p.wavelengths_nm[np.argmax(p.values, axis=1)]
    assert 610 <= peaks[0] <= 635 and 510 <= peaks[1] <= 560 and 440 <= peaks[2] <= 465
    assert np.all(p.values >= 0)


def test_figure_10_excitation_function():
    codes, g = excitation_function("SPECTRA 7000K")
    np.testing.assert_allclose(g, (np.arange(64) / 63) ** 2.204, rtol=1e-15)  # seed's c.dat
    assert codes[np.abs(g - 0.5).argmin()] == 46  # "50% excitation at level 46"
    codes, g = excitation_function("sRGB")
    # IEC 61966-2-1: code 128 -> ((128/255 + 0.055)/1.055)^2.4
    assert g[128] == pytest.approx(((128 / 255 + 0.055) / 1.055) ** 2.4, rel=1e-12)
    assert len(codes) == 256 and g[0] == 0 and g[255] == 1


def test_emitted_light_is_the_sum_of_excited_primaries():
    p = primary_emission("SPECTRA 7000K")
    c = emitted_light([[46, 0, 63], [0, 0, 0]], "SPECTRA 7000K")
    gamma = (np.array([46, 0, 63]) / 63) ** 2.204
    np.testing.assert_allclose(c.values[0], gamma @ p.values, rtol=1e-12)
    np.testing.assert_array_equal(c.values[1], 0.0)  # exact: zero drive gives exact zeros (0 times finite values)
    white = emitted_light([255, 255, 255], "sRGB")
    np.testing.assert_allclose(xyz_of_light(white), sc.rgb_space("sRGB").white_XYZ, rtol=1e-9)


@pytest.mark.parametrize(
    ("call", "needle"),
    [
        (lambda: primary_emission("sRGB", [360.0, 400.0, 500.0]), "wavelengths_nm"),
        (lambda: primary_emission("sRGB", [500.0, 400.0, 600.0]), "increasing"),
        (lambda: primary_emission("CRT"), "space"),
        (lambda: emitted_light([64, 0, 0], "SPECTRA 7000K"), "codes"),
        (lambda: emitted_light([1.5, 0, 0], "sRGB"), "codes"),
        (lambda: emitted_light([1, 2], "sRGB"), "codes"),
        (lambda: excitation_function("SPECTRA 7000K", bit_depth=8), "bit_depth"),
    ],
)
def test_hostile_input_gets_one_clear_error(call, needle):
    with pytest.raises(sc.ColorimetryError) as info:
        call()
    assert needle in str(info.value)
