"""What a measurement file declares (illuminant, observer, geometry, scale) is read and honoured.

Files of ``tests/data/io/make_declared.py`` and ``make_dialects.py`` (written from the CGATS.17
keyword descriptions and X-Rite's ``MEASUREMENT_SOURCE`` line); the XYZ golden values come from
colour-science's integration (an independent implementation), not from our own output.
"""

from __future__ import annotations

import json
import warnings
from pathlib import Path

import numpy as np
import pytest

import spectrocolor as sc
from spectrocolor.errors import SpectrumError
from spectrocolor.io import choose_conditions, declared_conditions
from spectrocolor.io.conditions import parse_declaration
from spectrocolor.report import measurement_report

CORPUS = Path(__file__).parents[1] / "data" / "io"


@pytest.mark.parametrize(
    ("keywords", "illuminant", "observer"),
    [
        ({"MEASUREMENT_SOURCE": "Illumination=D50  ObserverAngle=2°  WhiteBase=Abs  Filter=No"}, "D50", "CIE 1931 2°"),
        ({"MEASUREMENT_SOURCE": "Illumination=D65\tObserverAngle=10\tWhiteBase=Abs"}, "D65", "CIE 1964 10°"),
        ({"WEIGHTING_FUNCTION": "ILLUMINANT, D50; OBSERVER, 2 degree"}, "D50", "CIE 1931 2°"),
        ({"ILLUMINANT": "A", "OBSERVER": "10°"}, "A", "CIE 1964 10°"),
        ({"ILLUMINANT": "F11", "OBSERVER": "CIE 1931"}, "FL11", "CIE 1931 2°"),
        ({"OBSERVER": "2"}, None, "CIE 1931 2°"),
        ({"ORIGINATOR": "nothing declared"}, None, None),
    ],
)
def test_declarations_are_normalised(keywords, illuminant, observer):
    found = parse_declaration(keywords)
    assert found.get("declared_illuminant") == illuminant
    assert found.get("declared_observer") == observer


def test_an_unknown_illuminant_is_named_and_not_used():
    found = parse_declaration({"MEASUREMENT_SOURCE": "Illumination=Tungsten9 ObserverAngle=2"})
    assert "declared_illuminant" not in found and "Tungsten9" in found["declared_unknown"]
    assert found["declared_observer"] == "CIE 1931 2°"


@pytest.mark.parametrize(
    ("name", "label", "geometry", "encoding"),
    [
        ("colorport_d65_10_cp1252.cgats", "D65/10°", None, "cp1252"),
        ("colorport_latin1.cgats", "D50/2°", None, "cp1252"),
        ("eci_weighting_d50_2.cgats", "D50/2°", "45/0", "utf-8"),
        ("i1profiler.txt", "D50/2°", "45/0", "utf-8"),
    ],
)
def test_files_declare_their_conditions(name, label, geometry, encoding):
    spectra = sc.read_spectra(CORPUS / name)
    declared = declared_conditions(spectra)
    assert declared.label == label and declared.geometry == geometry
    assert spectra.metadata["encoding"] == encoding
    assert spectra.names[0] in ("Rot – glänzend", "Rot - glänzend", "red tile")  # decoded, not garbled


def test_a_file_without_declaration_keeps_the_library_defaults():
    spectra = sc.read_spectra(CORPUS / "wide.csv")
    assert not declared_conditions(spectra)
    assert choose_conditions(spectra) == ("D65", "CIE 1931 2°", "")


def _colour_xyz(spectra, illuminant: str, observer: str) -> np.ndarray:
    colour = pytest.importorskip("colour")
    grid = spectra.wavelengths_nm
    shape = colour.SpectralShape(grid[0], grid[-1], grid[1] - grid[0])
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return colour.colorimetry.msds_to_XYZ_integration(
            np.atleast_2d(spectra.values), colour.MSDS_CMFS[observer], colour.SDS_ILLUMINANTS[illuminant], shape=shape)


def test_the_report_computes_under_the_declared_d65_10():
    spectra = sc.read_spectra(CORPUS / "colorport_d65_10_cp1252.cgats")
    report = measurement_report(spectra)  # no conditions named: the file's
    assert report.illuminant == "D65" and report.observer == "CIE 1964 10°" and report.conditions_note == ""
    theirs = _colour_xyz(spectra, "D65", "CIE 1964 10 Degree Standard Observer")
    # two implementations of the same 36-term sums: agreement to ~1e-12 relative; 1e-9 leaves room
    np.testing.assert_allclose(report.XYZ, theirs, rtol=1e-9, atol=1e-9)
    under_2deg = _colour_xyz(spectra, "D65", "CIE 1931 2 Degree Standard Observer")
    assert np.abs(report.XYZ - under_2deg).max() > 0.5  # the old silent 2° result is far off


def test_the_report_says_when_the_caller_differs_from_the_file():
    spectra = sc.read_spectra(CORPUS / "eci_weighting_d50_2.cgats")
    report = measurement_report(spectra, illuminant="D65", observer="10deg")
    assert report.conditions_note == "the file declares D50/2°; computed under D65/10° as asked"
    assert report.illuminant == "D65" and report.observer == "CIE 1964 10°"
    theirs = _colour_xyz(spectra, "D50", "CIE 1931 2 Degree Standard Observer")
    np.testing.assert_allclose(measurement_report(spectra).XYZ, theirs, rtol=1e-9, atol=1e-9)
    # the same conditions named explicitly: no note
    assert measurement_report(spectra, illuminant="d50", observer="1931").conditions_note == ""


def test_the_note_is_in_every_report_format(tmp_path):
    from spectrocolor.report import write_report

    spectra = sc.read_spectra(CORPUS / "eci_weighting_d50_2.cgats")
    report = measurement_report(spectra, illuminant="C")
    note = "the file declares D50/2°; computed under C/2° as asked"
    assert report.conditions_note == note
    for fmt in ("csv", "html"):
        text = write_report(report, tmp_path / f"r.{fmt}", fmt).read_text(encoding="utf-8")
        assert note in text, fmt
    assert json.loads(write_report(report, tmp_path / "r.json", "json").read_text())["conditions_note"] == note


def test_undeclared_percent_is_refused_as_on_the_command_line():
    spectra = sc.read_spectra(CORPUS / "semicolon_decimal_comma_percent.csv")
    with pytest.raises(SpectrumError, match=r"reflectance values reach .*percent=True"):
        measurement_report(spectra)
    read = sc.read_spectra(CORPUS / "semicolon_decimal_comma_percent.csv", percent=True)
    assert measurement_report(read).XYZ.shape == (3, 3)


def test_percent_said_of_fractions_warns():
    with pytest.warns(UserWarning, match=r"percent was asked, but no value exceeds 1"):
        spectra = sc.read_spectra(CORPUS / "wide.csv", percent=True)
    assert spectra.values.max() < 0.01  # still divided, as asked
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # percentages said to be percentages: no warning
        sc.read_spectra(CORPUS / "semicolon_decimal_comma_percent.csv", percent=True)
