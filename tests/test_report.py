"""Colour measurement reports (seed 001's workflow): values cross-checked with colour-science,
self-contained HTML, CSV/JSON with every sample, a few samples and many."""

from __future__ import annotations

import base64
import csv
import io
import json
import re

import numpy as np
import pytest

import spectrocolor as sc
from spectrocolor.cli import main
from spectrocolor.report import measurement_report, report_html, write_report

GRID = np.arange(380.0, 781.0, 5.0)


def _alloys() -> sc.Spectrum:
    """Stepped reflectances like Gardam's gold and copper alloys, a flat grey, a blue-green and
    a purple (complementary wavelength) -- synthetic, shaped after seed 001 section 1.9."""
    def step(centre, width, low, high):
        return low + (high - low) / (1 + np.exp(-(GRID - centre) / width))

    values = np.array([
        step(520, 20, 0.35, 0.95),  # gold-like
        step(580, 20, 0.50, 0.95),  # copper-like
        np.full(GRID.size, 0.6),  # grey: the white's chromaticity
        step(500, -30, 0.30, 0.90),  # bluish
        0.2 + 0.6 * np.exp(-0.5 * ((GRID - 420) / 25) ** 2)
        + 0.6 * np.exp(-0.5 * ((GRID - 680) / 30) ** 2),  # purple
    ])
    return sc.Spectrum(GRID, values, ["gold 18k", "copper", "grey", "blue", "purple"])


@pytest.fixture(scope="module")
def report():
    return measurement_report(_alloys(), illuminant="C", observer="1931")


def test_against_colour_science(report):
    colour = pytest.importorskip("colour")
    shape = colour.SpectralShape(380, 780, 5)
    cmfs = colour.MSDS_CMFS["CIE 1931 2 Degree Standard Observer"].copy().align(shape)
    illuminant = colour.SDS_ILLUMINANTS["C"].copy().align(shape)
    white = colour.sd_to_XYZ(colour.SpectralDistribution(np.ones(GRID.size), GRID), cmfs,
                             illuminant, method="Integration")
    np.testing.assert_allclose(report.white_XYZ, white, rtol=1e-9)
    white_xy = colour.XYZ_to_xy(white)
    for i, values in enumerate(_alloys().values):
        sd = colour.SpectralDistribution(values, GRID)
        XYZ = colour.sd_to_XYZ(sd, cmfs, illuminant, method="Integration")
        np.testing.assert_allclose(report.XYZ[i], XYZ, rtol=1e-9)
        np.testing.assert_allclose(report.lab[i], colour.XYZ_to_Lab(XYZ / 100, white_xy),
                                   atol=1e-9)
        xy = colour.XYZ_to_xy(XYZ)
        np.testing.assert_allclose(report.xy[i], xy, atol=1e-12)
        assert report.luminance_factor[i] == pytest.approx(XYZ[1], rel=1e-9)
        if report.names[i] == "grey":
            continue
        # colour-science snaps to the nearest 1 nm locus sample: agree to half a nanometre
        locus = colour.MSDS_CMFS["CIE 1931 2 Degree Standard Observer"]
        wavelength, _, _ = colour.dominant_wavelength(xy, white_xy, locus)
        purity = colour.excitation_purity(xy, white_xy, locus)
        assert report.complementary[i] == (wavelength < 0)
        assert report.dominant_wavelength_nm[i] == pytest.approx(abs(wavelength), abs=0.5)
        assert report.excitation_purity[i] == pytest.approx(purity, abs=5e-3)


def test_seed_001_properties(report):
    """Visser 1.9: metals are desaturated, of a limited range of dominant wavelengths, and of
    high luminance; a grey has the white's chromaticity (no hue) and Y = its reflectance."""
    gold, copper, grey, blue, purple = range(5)
    for metal in (gold, copper):
        assert 570 < report.dominant_wavelength_nm[metal] < 600
        assert report.excitation_purity[metal] < 0.5
        assert report.luminance_factor[metal] > 60
    assert np.isnan(report.dominant_wavelength_nm[grey]) and not report.complementary[grey]
    assert report.excitation_purity[grey] < 1e-9
    assert report.luminance_factor[grey] == pytest.approx(60.0, abs=1e-9)
    np.testing.assert_allclose(report.lab[grey, 1:], 0.0, atol=1e-9)
    assert 460 < report.dominant_wavelength_nm[blue] < 500 and not report.complementary[blue]
    assert report.complementary[purple]


def test_white_point_of_c(report):
    """The perfect white under C: CIE 015:2018 table 9, x = 0.31006, y = 0.31616."""
    np.testing.assert_allclose(report.white_xy, [0.31006, 0.31616], atol=5e-5)
    assert report.white_XYZ[1] == pytest.approx(100.0, abs=1e-12)


def _images(text: str) -> list[bytes]:
    return [base64.b64decode(b) for b in re.findall(r"data:image/png;base64,([A-Za-z0-9+/=]+)",
                                                    text)]


@pytest.mark.slow
def test_html_is_self_contained(report, tmp_path):
    path = write_report(report, tmp_path / "report.html")
    text = path.read_text()
    assert "http://" not in text and "https://" not in text and "<script" not in text
    images = _images(text)
    assert len(images) == 2 and all(b.startswith(b"\x89PNG") for b in images)
    assert text.count("<tr><td>") == 5  # one row per sample
    assert "gold 18k" in text and "illuminant</dt><dd>C" in text
    assert report.hex[0] in text  # the swatch colour
    assert " c</td>" in text  # the purple's complementary wavelength is marked


def test_csv_and_json_hold_every_sample(report, tmp_path):
    text = write_report(report, tmp_path / "r.csv").read_text()
    rows = list(csv.DictReader(io.StringIO("\n".join(text.splitlines()[1:]))))
    assert [row["name"] for row in rows] == list(report.names)
    assert float(rows[0]["Y"]) == pytest.approx(report.XYZ[0, 1], abs=1e-4)
    assert rows[2]["dominant_wavelength_nm"] == ""  # the grey has none
    data = json.loads(write_report(report, tmp_path / "r.json").read_text())
    assert data["illuminant"] == "C" and len(data["samples"]) == 5
    assert data["samples"][2]["dominant_wavelength_nm"] is None
    assert data["samples"][4]["complementary"] is True
    with pytest.raises(sc.ColorimetryError, match="format 'txt' is unknown"):
        write_report(report, tmp_path / "r.txt")


@pytest.mark.slow
def test_many_samples_are_summarised(tmp_path):
    rng = np.random.default_rng(5)
    n = 20_000
    centres = rng.uniform(400, 700, (n, 1))
    values = 0.2 + 0.6 * rng.random((n, 1)) * np.exp(-0.5 * ((GRID - centres) / 40) ** 2)
    report = measurement_report(sc.Spectrum(GRID, values), illuminant="D65", observer="1931")
    text = report_html(report, page_rows=100)
    assert "Summary of all samples" in text and "First 100 of 20000 samples" in text
    assert text.count("<tr><td>sample ") == 100
    assert len(text) < 2_000_000
    assert len(json.loads(write_report(report, tmp_path / "r.json").read_text())["samples"]) == n


@pytest.mark.slow
def test_cli_report(tmp_path, capsys):
    sc.write_spectra(_alloys(), tmp_path / "samples.csv")
    out = tmp_path / "report.html"
    code = main(["report", str(tmp_path / "samples.csv"), "--illuminant", "C", "--observer",
                 "1931", "--out", str(out)])
    assert code == 0 and out.exists()
    assert "5 samples" in capsys.readouterr().out
    assert main(["report", str(tmp_path / "samples.csv"), "--illuminant", "C",
                 "--out", str(tmp_path / "r.json")]) == 0
    assert len(json.loads((tmp_path / "r.json").read_text())["samples"]) == 5


def test_cli_report_percent(tmp_path, capsys):
    spectra = _alloys()
    sc.write_spectra(sc.Spectrum(GRID, spectra.values * 100, spectra.names),
                     tmp_path / "pct.csv")
    assert main(["report", str(tmp_path / "pct.csv"), "--illuminant", "C",
                 "--out", str(tmp_path / "r.csv")]) == 2
    assert "pass --percent" in capsys.readouterr().err
    assert main(["report", str(tmp_path / "pct.csv"), "--illuminant", "C", "--percent",
                 "--out", str(tmp_path / "r.csv")]) == 0
    rows = (tmp_path / "r.csv").read_text().splitlines()
    expected = measurement_report(spectra, illuminant="C")
    assert float(rows[2].split(",")[2]) == pytest.approx(expected.XYZ[0, 1], abs=1e-4)
    assert main(["report", str(tmp_path / "pct.csv"), "--illuminant", "C", "--percent",
                 "--out", str(tmp_path / "r.pdf")]) == 2


@pytest.mark.slow
def test_html_with_more_curves_than_are_drawn_individually(tmp_path):
    # 21-39 samples: more than the 20 drawn one by one, fewer than the 40 picked at random
    rng = np.random.default_rng(7)
    values = 0.2 + 0.6 * rng.random((30, GRID.size))
    report = measurement_report(sc.Spectrum(GRID, values), illuminant="D65", observer="1931")
    text = report_html(report)  # raised ValueError: larger sample than population
    assert "<img alt='reflectance curves'" in text and text.count("<tr><td>sample ") == 30


def test_cli_report_rejects_negative_reflectance(tmp_path, capsys):
    spectra = _alloys()
    sc.write_spectra(sc.Spectrum(GRID, -spectra.values, spectra.names), tmp_path / "neg.csv")
    assert main(["report", str(tmp_path / "neg.csv"), "--illuminant", "C",
                 "--out", str(tmp_path / "r.csv")]) == 2
    assert "negative reflectance" in capsys.readouterr().err
    assert not (tmp_path / "r.csv").exists()
