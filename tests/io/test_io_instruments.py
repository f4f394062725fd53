"""Exports of real spectrometers and light meters (issue 26, item 4): OceanView/SpectraSuite, UPRtek,
Sekonic, Konica Minolta CL-500A/CL-70F and Agilent Cary WinUV, each told by its content.

The corpus (``tests/data/io/make_instruments.py``) writes one light, CIE illuminant A from its
defining formula, through every light meter's format, and D65 through one more; the golden
values here are the CIE formula and the CIE's published CCT and chromaticities, not our output.
"""

import math
from pathlib import Path

import numpy as np
import pytest

import spectrocolor as sc
from spectrocolor import Spectrum, SpectrumError
from spectrocolor.io import parse_spectra
from spectrocolor.io.lightmeters import identify
from spectrocolor.io.text import decode_text
from spectrocolor.lighting import colour_rendering_index, luminous_quantity

CORPUS = Path(__file__).parents[1] / "data" / "io"


def illuminant_a(nm):
    """CIE 015:2018 §4.1, the defining formula of illuminant A (100 at 560 nm)."""
    c = 1.435e7
    return 100 * (560 / nm) ** 5 * (math.exp(c / (2848 * 560)) - 1) / np.expm1(c / (2848 * nm))


GRID = np.arange(360, 781)
#: The corpus light, W·m⁻²·nm⁻¹: A in mW·m⁻²·nm⁻¹ rounded to whole µW (six decimals in W).
LIGHT = np.round(illuminant_a(GRID) * 1000) / 1e6
#: CIE 015:2018: CCT of A 2856 K, chromaticity (0.44757, 0.40745); D65 6504 K, (0.31271, 0.32902).
PUBLISHED = {"A": (2856.0, 0.44757, 0.40745), "D65": (6504.0, 0.31271, 0.32902)}

#: file: (encoding, format starts with, instrument, names, first wavelength nm)
LIGHTS = {
    "uprtek_mk350.xls": ("utf-8", "UPRtek", "UPRtek MK350N Premium", ("lamp A",), 380),
    "sekonic_c800.csv": ("utf-8", "Sekonic", "Sekonic C-700/C-800/C-7000", ("Lamp A 2°",), 380),
    "cl500a_memory.csv": ("utf-8", "Konica Minolta", "Konica Minolta CL-500A/CL-70F",
                          ("2024/5/1 10:12:13", "2024/5/1 10:12:15"), 360),
    "cl_s10w_utf16.txt": ("utf-16-le", "Konica Minolta", "Konica Minolta CL-500A", ("Lamp A",), 360),
}


def _first(spectrum):
    return spectrum[0] if spectrum.values.ndim == 2 else spectrum


@pytest.mark.parametrize("name", sorted(LIGHTS))
def test_each_light_meter_file_reads_to_illuminant_a_in_w_per_m2_nm(name):
    encoding, kind, instrument, names, start = LIGHTS[name]
    light = sc.read_spectra(CORPUS / name)
    assert light.names == names and light.metadata["encoding"] == encoding
    assert light.metadata["format"].startswith(kind) and light.metadata["instrument"] == instrument
    assert light.metadata["quantity"] == "spectral irradiance" and light.metadata["unit"] == "W·m⁻²·nm⁻¹"
    # exact: whole-nm labels parsed by float() are exact integers
    assert np.array_equal(light.wavelengths_nm, GRID[GRID >= start])
    # six-decimal text (or UPRtek's mW divided by 1000): within 2 ulp of the decimal value
    np.testing.assert_allclose(_first(light).values, LIGHT[GRID >= start], rtol=5e-16, atol=0)
    stated = light.metadata["stated"]
    assert stated["cct_K"][0] == 2856 and stated["x"][0] == 0.4476  # exact: decimal text as the meter wrote it


def test_uprtek_values_were_milliwatts_and_sekonic_read_its_finest_block():
    uprtek = sc.read_spectra(CORPUS / "uprtek_mk350.xls")
    assert "mW" in uprtek.metadata["value_scale"] and "divided by 1000" in uprtek.metadata["value_scale"]
    assert uprtek.metadata["sample_fields"]["Serial Number"] == ("21A00123",)
    sekonic = sc.read_spectra(CORPUS / "sekonic_c800.csv")
    blocks = sekonic.metadata["spectral_blocks"]
    assert "2 spectral blocks" in blocks and "block 2" in blocks
    assert sekonic.metadata["sample_fields"]["⊿uv"] == ("0.0000",)


def test_the_same_light_through_every_format_gives_the_same_xyz():
    # Each value is the same six-decimal number in every file (UPRtek: three decimals more in
    # mW, then /1000): parsed values differ by at most 2 ulp (2 × 1.1e-16 relative), and XYZ is
    # a sum of positive terms, so its relative difference is at most that: far below 1e-12.
    reference = sc.tristimulus(Spectrum(GRID[20:], LIGHT[20:]))
    for name in LIGHTS:
        XYZ = sc.tristimulus(_first(sc.read_spectra(CORPUS / name)).restrict(380, 780))
        np.testing.assert_allclose(XYZ, reference, rtol=1e-12, atol=0, err_msg=name)
    # OceanView holds A at 2048 irregular pixels in µW/cm²/nm (× 0.01 to W/m²/nm): the same
    # light on another grid, so the trapezoid sums agree to the grid's own error (~1e-6)
    pixels = sc.read_spectra(CORPUS / "oceanview_flame.txt").restrict(380, 780)
    np.testing.assert_allclose(sc.tristimulus(pixels) * 0.01, reference, rtol=5e-6)


@pytest.mark.parametrize("name", sorted(LIGHTS))
def test_our_illuminance_and_cct_agree_with_the_meter_and_the_published_values(name):
    light = sc.read_spectra(CORPUS / name)
    lux = np.atleast_1d(luminous_quantity(light))
    # the file's lux is 683 Σ E ȳ Δλ summed by the corpus script from the CIE table, printed to
    # 0.1 lx at worst (Sekonic); the CL-500A's second row is A/2 rounded again to 1e-6 W
    # (≤ 0.5e-6 × 683 × Σ ȳ Δλ = 0.04 lx)
    np.testing.assert_allclose(lux, light.metadata["stated"]["illuminance_lx"], rtol=0, atol=0.06)
    XYZ = sc.tristimulus(_first(light).restrict(380, 780))
    cct, x, y = PUBLISHED["A"]
    # A is Planckian at 2848 K with c2 = 1.435e-2, i.e. 2855.54 K today, published as 2856 K
    assert abs(float(sc.cct(XYZ=XYZ).cct_K) - cct) < 1.0
    np.testing.assert_allclose(XYZ[:2] / XYZ.sum(), [x, y], atol=5e-5)  # 1 nm data vs 5-decimal table


def test_sekonic_d65_in_milliwatts_matches_the_published_cct():
    d65 = sc.read_spectra(CORPUS / "sekonic_c7000_d65.csv")
    assert d65.metadata["value_scale"].startswith("the file's mW/m²nm divided by 1000")
    assert d65.interval_nm == 5 and d65.values[0] == pytest.approx(0.0499755 * 1, rel=1e-12)
    XYZ = sc.tristimulus(d65)
    cct, x, y = PUBLISHED["D65"]
    # 5 nm data truncated to 380–780 nm: xy within 2e-5 of the table's, about 1 K of CCT
    assert abs(float(sc.cct(XYZ=XYZ).cct_K) - cct) < 2.0
    np.testing.assert_allclose(XYZ[:2] / XYZ.sum(), [x, y], atol=5e-5)


def test_oceanview_keeps_the_pixel_wavelengths_and_says_how_to_resample():
    s = sc.read_spectra(CORPUS / "oceanview_flame.txt")
    p = np.arange(2048)
    # exact: three-decimal text parsed by float(), compared with the same text's value
    assert np.array_equal(s.wavelengths_nm, [float(f"{v:.3f}") for v in 178.2 + 0.3795 * p - 1.56e-5 * p * p])
    assert s.interval_nm is None and s.metadata["grid"].startswith("irregular: 2048 pixel wavelengths")
    assert "resample_nm=1" in s.metadata["grid"]
    assert s.metadata["pixels"] == 2048 and s.metadata["integration_time_s"] == 0.1  # exact: 1.000000E-1 parsed
    assert s.metadata["scans_to_average"] == 10 and s.metadata["boxcar_width"] == 2
    assert s.metadata["quantity"] == "spectral irradiance" and s.metadata["unit"].startswith("µW·cm⁻²·nm⁻¹")
    assert s.metadata["instrument"] == "Ocean Optics FLMS01234" and s.names == ("FLMS01234",)
    with pytest.raises(SpectrumError, match="irregular grid.*resample_nm=1"):
        colour_rendering_index(s)
    uniform = sc.read_spectra(CORPUS / "oceanview_flame.txt", resample_nm=1)
    # exact: a generated grid of whole nanometres
    assert uniform.interval_nm == 1 and uniform.wavelengths_nm[0] == 179 and uniform.wavelengths_nm[-1] == 889
    assert "interpolated linearly from 2048 wavelengths" in uniform.metadata["resampled"]
    # A is its own CIE 13.3 reference (Planckian below 5000 K): Ra = 100 by definition
    assert colour_rendering_index(uniform.restrict(380, 780)).Ra == pytest.approx(100, abs=0.05)


def test_spectrasuite_processed_spectrum_in_cp1252():
    s = sc.read_spectra(CORPUS / "spectrasuite_usb2000.txt")
    assert s.metadata["format"] == "Ocean Optics SpectraSuite text export" and s.metadata["encoding"] == "cp1252"
    assert s.metadata["keywords"]["User"] == "Müller" and s.metadata["integration_time_s"] == pytest.approx(0.1)
    assert s.values.shape == (2048,) and s.metadata["quantity"].startswith("counts")
    p = np.arange(2048)
    nm = 339.4 + 0.3662 * p - 1.4e-5 * p * p  # the calibration polynomial; the file rounds it to 0.01 nm
    np.testing.assert_allclose(s.wavelengths_nm, nm, rtol=0, atol=0.0051)
    expected = np.round(1000 + 3000 * np.exp(-(((nm - 550) / 80) ** 2)), 2)
    np.testing.assert_allclose(s.values, expected, rtol=0, atol=0.0051)  # printed to 0.01


def test_cary_winuv_is_named_with_its_instrument_and_method_block():
    s = sc.read_spectra(CORPUS / "cary_winuv_cp1252.csv", percent=True)
    assert s.metadata["format"].endswith("(Agilent Cary WinUV)") and s.metadata["instrument"] == "Agilent Cary 60"
    assert s.metadata["date"] == "01.05.2024 10:12:13" and s.metadata["encoding"] == "cp1252"
    assert s.names == ("Filter BG38", "Filter OG550") and "Operator Name,Müller" in s.metadata["notes_after_data"]
    nm = np.arange(380, 801, 10)
    blue = np.round(90 * np.exp(-(((nm - 480) / 90) ** 2)), 4)
    np.testing.assert_allclose(s.values[0], blue / 100, rtol=0, atol=1e-15)
    older = sc.read_spectra(CORPUS / "cary_paired.csv", percent=True)
    assert older.metadata["instrument"] == "Agilent Cary 5000"


def test_a_paired_table_without_cary_signs_keeps_the_generic_name():
    s = parse_spectra("Wavelength (nm),%R,Wavelength (nm),%R\n400,1,400,2\n410,3,410,4\n", "pairs.csv")
    assert "Cary" not in s.metadata["format"] and "instrument" not in s.metadata


OCEANVIEW = (CORPUS / "oceanview_flame.txt").read_text(encoding="ascii")
UPRTEK = decode_text((CORPUS / "uprtek_mk350.xls").read_bytes(), "u").text
SEKONIC = decode_text((CORPUS / "sekonic_c800.csv").read_bytes(), "s").text
CL500A = (CORPUS / "cl500a_memory.csv").read_text(encoding="ascii")


@pytest.mark.parametrize("text, message", [
    (OCEANVIEW.replace("Spectrum: 2048", "Spectrum: 2049"),
     r"this is an Ocean Optics OceanView export; the header claims 2049 pixels .* 2048 rows"),
    (OCEANVIEW.replace("Spectrum: 2048", "Spectrum: 999999999999"), r"OceanView export; .*can hold at most"),
    (OCEANVIEW.replace("Spectrum: 2048", "Spectrum: 20x"), r"OceanView export; .*not a whole number"),
    (OCEANVIEW.replace("XAxis mode: Wavelengths", "XAxis mode: Pixels"), r"OceanView export; its x axis is 'Pixels'"),
    (OCEANVIEW.replace("\n178.579\t", "\n178.579\tx"), r"OceanView export; line 15: 'x0.0000' is not a number"),
    (OCEANVIEW.replace("\n178.579\t", "\n178.000\t"), r"OceanView export; line 14: pixel wavelengths must increase"),
    (OCEANVIEW.replace("\n178.579\t", "\n178.579 1 "), r"OceanView export; line 15: 3 cells"),
    (UPRTEK.replace("381nm\t", "381nm\tabc"), r"this is a UPRtek light-meter export; line 18, '381nm': 'abc"),
    (SEKONIC.replace("Spectral Data 385[nm],", "Spectral Data 385[nm],1,"),
     r"this is a Sekonic .* export; line 18: 'Spectral Data 385\[nm\]' holds 2 value"),
    (SEKONIC.replace("380[nm]", "380nm [lm]"), r"Sekonic .*spectral unit 'lm' is not one"),
    (CL500A.replace(",0.447600,", ",", 1), r"Konica Minolta CL-500A/CL-70F export; line 2: 434 cells, but the header"),
    (CL500A.replace(f",{LIGHT[0]:.6f},", ",0.0x,", 1), r"Konica Minolta .*; line 2, column 'Spectrum\[0\]': '0.0x'"),
])
def test_a_recognised_but_malformed_file_gets_one_line_naming_its_format(text, message):
    with pytest.raises(SpectrumError, match=message) as caught:
        parse_spectra(text, "export")
    assert "\n" not in str(caught.value) and "Formats tried" not in str(caught.value)


@pytest.mark.parametrize("name", ["uprtek_mk350.xls", "sekonic_c800.csv", "cl500a_memory.csv", "oceanview_flame.txt"])
def test_percent_true_on_a_light_is_refused(name):
    with pytest.raises(SpectrumError, match="percent: .*leave percent unset"):
        sc.read_spectra(CORPUS / name, percent=True)


@pytest.mark.parametrize("step, message", [(0, "positive step"), (-1, "positive step"), (float("nan"), "positive"),
                                           ("1", "positive step"), (True, "positive step"),
                                           (1000, "fewer than two points")])
def test_resample_nm_gets_one_clear_error(step, message):
    with pytest.raises(SpectrumError, match=f"resample_nm: .*{message}"):
        sc.read_spectra(CORPUS / "oceanview_flame.txt", resample_nm=step)


def test_resample_nm_applies_to_any_format_and_says_so():
    s = sc.read_spectra(CORPUS / "sekonic_c7000_d65.csv", resample_nm=1)
    assert s.interval_nm == 1 and "onto a uniform 1 nm grid, 380–780 nm" in s.metadata["resampled"]


@pytest.mark.parametrize("text, maker", [
    ("Model Name\tMK350\nLUX\t10\n380nm\t1\n381nm\t1\n", "UPRtek"),
    ("Title,x\nSpectral Data 380[nm],1\n", "Sekonic"),
    ("Date,Time,Tcp,Spectrum[0],Spectrum[1],Spectrum[2]\n", "Konica Minolta"),
    ("Ev,1\nTcp,2856\n360nm,1\n361nm,1\n", "Konica Minolta"),
    ("wavelength_nm,Tcp lamp\n380,1\n390,2\n", None),
    ("Sample,380,390,400\nLUX,1,2,3\n", None),
])
def test_makers_are_told_by_content(text, maker):
    assert identify(text) == maker


def test_oceanview_from_a_decimal_comma_windows_machine_with_crlf():
    text = OCEANVIEW.replace(".", ",").replace("\n", "\r\n").replace("1,000000E-1", "1.000000E-1")
    s = parse_spectra(text, "komma.txt")
    # exact: the same digits with a comma for the point, parsed as the same decimal numbers
    assert np.array_equal(s.wavelengths_nm, sc.read_spectra(CORPUS / "oceanview_flame.txt").wavelengths_nm)
    assert s.metadata["pixels"] == 2048


def test_a_generic_table_is_not_taken_for_an_instrument_export():
    for text in ("wavelength_nm,Tcp lamp\n380,1\n390,2\n", "Sample,380,390,400\nLUX,1,2,3\n"):
        assert parse_spectra(text, "t.csv").metadata["format"].startswith("CSV")
