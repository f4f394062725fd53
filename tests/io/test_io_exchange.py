"""Exchange formats (issue 26, item 4): X-Rite CxF3 read and written, Datacolor QTX, .xlsx
workbooks, and binary formats that are recognised but not read, named in one line.

The corpus (``tests/data/io/make_exchange.py``, written from each format's public description)
holds make_dialects.py's three samples in CGATS, CxF3, QTX and two workbooks; each file reads to
those values, and all give the same XYZ.
"""

import io
import re
import zipfile
from pathlib import Path

import numpy as np
import pytest

import spectrocolor as sc
from spectrocolor import Spectrum, SpectrumError
from spectrocolor.io import parse_spectra, read_spectra, write_spectra
from spectrocolor.io.cxf import spectra_to_cxf
from spectrocolor.io.xlsx import parse_xlsx, sheet_names

CORPUS = Path(__file__).parents[1] / "data" / "io"
GRID = np.arange(380, 731, 10)
NAMES = ("Rot – glänzend", "Grün µ2", "Grau 10°")


def _counts(i, nm):  # make_exchange.py's samples, integers of 1e-4
    if i == 0:
        return 500 + int(8000 / (1 + 2.0 ** ((600 - nm) / 12)))
    if i == 1:
        return 400 + int(5000 * 2.0 ** (-(((nm - 530) / 40) ** 2)))
    return 1800 + (nm - 380) // 10


COUNTS = np.array([[_counts(i, int(nm)) for nm in GRID] for i in range(3)])
#: file: (format starts with, percent option)
CASES = {
    "exchange.cgats": ("CGATS", False),
    "xrite.cxf": ("X-Rite CxF3", None),
    "datacolor.qtx": ("Datacolor QTX", None),
    "workbook.xlsx": ("Excel workbook (.xlsx), sheet 'Spectra', wide", False),
    "workbook_long.xlsx": ("Excel workbook (.xlsx), sheet 'Messung', long", True),
}


def _read(name):
    return read_spectra(CORPUS / name, percent=CASES[name][1])


@pytest.mark.parametrize("name", sorted(CASES))
def test_each_file_reads_to_its_samples(name):
    spectra = _read(name)
    assert spectra.names == NAMES
    assert spectra.metadata["format"].startswith(CASES[name][0])
    # exact: integer wavelengths (decimal text, or StartWL + k × Increment with small integers)
    assert np.array_equal(spectra.wavelengths_nm, GRID)
    # values are c/10000 written as 4-decimal fractions or 2-decimal percent; one rounding each
    np.testing.assert_allclose(spectra.values, COUNTS / 10000, rtol=0, atol=1e-15)


def test_the_same_samples_through_cgats_cxf_qtx_and_xlsx_give_the_same_xyz():
    # Every file stores each value as the decimal c/10000 (CGATS, CxF3, .xlsx: "0.0500") or c/100
    # (QTX, the long workbook: "5.00"). float() of the fraction is correctly rounded; the percent
    # path is float("5.00") / 100, two correctly rounded steps, so each value differs from the
    # reference c/10000 by at most 1 ulp (2.2e-16 relative). XYZ is a sum of 36 products with
    # non-negative weights, so its relative difference is at most ~1 ulp plus the summation's own
    # identical rounding: 1e-12 relative leaves a margin of 10^3.
    reference = sc.tristimulus(Spectrum(GRID, COUNTS / 10000), illuminant="D50", method="astm-e308")
    for name in CASES:
        XYZ = sc.tristimulus(_read(name), illuminant="D50", method="astm-e308")
        np.testing.assert_allclose(XYZ, reference, rtol=1e-12, atol=0, err_msg=name)


def test_cxf_declares_its_illuminant_observer_and_geometry():
    cxf = _read("xrite.cxf")
    assert (cxf.metadata["illuminant"], cxf.metadata["observer"], cxf.metadata["cxf_observer"]) == (
        "D50", "2°", "2_Degree")
    assert cxf.metadata["geometry"] == "45/0 (Annular)" and cxf.metadata["instrument"] == "i1Pro 2"
    assert cxf.metadata["measurement_type"] == "Spectrum_Reflectance" and "0–1" in cxf.metadata["value_scale"]
    assert sc.observers.resolve_observer(cxf.metadata["observer"]).name == "CIE 1931 2°"


def test_qtx_names_standards_and_batches_and_says_it_was_percent():
    qtx = _read("datacolor.qtx")
    fields = qtx.metadata["sample_fields"]
    assert fields["kind"] == ("standard", "batch", "batch") and fields["standard"] == (NAMES[0],) * 3
    assert "percent" in qtx.metadata["value_scale"] and qtx.metadata["encoding"] == "cp1252"
    with pytest.raises(SpectrumError, match="percent=False contradicts"):
        read_spectra(CORPUS / "datacolor.qtx", percent=False)


def test_workbook_sheets_by_name_and_index():
    data = (CORPUS / "workbook.xlsx").read_bytes()
    assert sheet_names(data, "workbook.xlsx") == ["Spectra", "Notes"]
    assert parse_spectra(data, "workbook.xlsx").metadata["sheet"] == "Spectra"
    assert parse_xlsx(data, "workbook.xlsx", sheet=0).names == NAMES
    assert parse_spectra(data, "w.xlsx").metadata["sample_fields"]["Date"] == ("45413", "45414", "45415")
    with pytest.raises(SpectrumError, match=r"sheet 'Notes'.*other sheets: 'Spectra'"):
        parse_xlsx(data, "workbook.xlsx", sheet="Notes")
    with pytest.raises(SpectrumError, match=r"sheet: 'Daten' is not a sheet of workbook.xlsx; its sheets are 'Spe"):
        parse_xlsx(data, "workbook.xlsx", sheet="Daten")


# --- CxF3 writing -------------------------------------------------------------------------------


def test_cxf_round_trip_keeps_values_names_and_conditions(tmp_path):
    names = ["a < b & c", 'quote " and \' apostrophe', "line\nbreak\tand tab", "ü°µ–"]
    values = np.random.default_rng(7).uniform(0, 1, (4, 31))
    spectrum = Spectrum(np.arange(400, 701, 10), values, names,
                        {"illuminant": "D65", "observer": "10°", "geometry": "d/8 (SCI)"})
    back = read_spectra(write_spectra(spectrum, tmp_path / "x.cxf"))
    assert back == spectrum and back.names == tuple(names)  # == compares grid and values exactly
    assert (back.metadata["illuminant"], back.metadata["observer"], back.metadata["geometry"]) == (
        "D65", "10°", "d/8 (SCI)")
    # exact: repr() writes the shortest decimal that reads back as the same double
    assert np.array_equal(back.values, values)


def test_cxf_writer_refuses_what_cxf_cannot_hold(tmp_path):
    with pytest.raises(SpectrumError, match=r"spectrum name 'bell\\x07' holds '\\x07'"):
        spectra_to_cxf(Spectrum([400, 500], [0.1, 0.2], ["bell\x07"]))
    with pytest.raises(SpectrumError, match="regular wavelength grid"):
        spectra_to_cxf(Spectrum([400, 500, 650], [0.1, 0.2, 0.3]))
    with pytest.raises(SpectrumError, match=r"\.csv, \.json, \.cgats or \.cxf"):
        write_spectra(Spectrum([400, 500], [0.1, 0.2]), tmp_path / "x.xml")


def test_written_cxf_has_the_cxf3_structure():
    import xml.etree.ElementTree as ElementTree

    root = ElementTree.fromstring(spectra_to_cxf(Spectrum([400, 410], [[0.1, 0.2]], ["t"])))
    ns = {"cc": "http://colorexchangeformat.com/CxF3-core"}
    assert root.tag == "{http://colorexchangeformat.com/CxF3-core}CxF"
    spectrum = root.find("cc:Resources/cc:ObjectCollection/cc:Object/cc:ColorValues/cc:ReflectanceSpectrum", ns)
    assert spectrum is not None and spectrum.get("ColorSpecification") == "cs1" and spectrum.get("StartWL") == "400.0"
    grid = root.find("cc:Resources/cc:ColorSpecificationCollection/cc:ColorSpecification/cc:MeasurementSpec/"
                     "cc:WavelengthRange", ns)
    assert grid is not None and grid.get("Increment") == "10.0"


# --- malformed files: one clear line each ----------------------------------------------------------

_CXF = (CORPUS / "xrite.cxf").read_text(encoding="utf-8")
_QTX = (CORPUS / "datacolor.qtx").read_bytes().decode("cp1252")

MALFORMED_TEXT = {
    "cxf DOCTYPE": ('<?xml version="1.0"?>\n<!DOCTYPE cc:CxF [<!ENTITY x "y">]>\n' + _CXF.split("\n", 1)[1],
                    "DOCTYPE or ENTITY declaration is not accepted"),
    "cxf DOCTYPE after a long comment": (
        _CXF.replace("<cc:CxF ", "<!--" + " " * 70000 + "-->\n<!DOCTYPE x>\n<cc:CxF ", 1),
        "not accepted|not well-formed"),
    "cxf unknown specification": (_CXF.replace('ColorSpecification="CS_D50_2" StartWL', 'ColorSpecification="CS9" '
                                               "StartWL", 1), "ColorSpecification 'CS9' is not in"),
    "cxf no increment": (_CXF.replace(' Increment="10"', ""), "gives no WavelengthRange Increment"),
    "cxf not a number": (_CXF.replace("0.0500 ", "0.05x0 ", 1), r"value 1: '0.05x0' is not a number"),
    "cxf cut short": (_CXF[:-40], "not well-formed XML"),
    "cxf no spectra": (re.sub(r"<cc:ReflectanceSpectrum.*?</cc:ReflectanceSpectrum>", "", _CXF),
                       "CxF3 file without spectra .4 objects holding ColorCIELab"),
    "cxf different grids": (_CXF.replace('StartWL="380">', 'StartWL="390">', 1), "different wavelength grids"),
    "qtx point count": (_QTX.replace("STD_REFLPOINTS=36", "STD_REFLPOINTS=9999999999"),
                        r"STD_REFLPOINTS says 9999999999 but STD_R \(line \d+\) holds 36 values"),
    "qtx missing low": (_QTX.replace("BATCH_REFLLOW=380\r\n", "", 1), r"\[BATCH_DATA 0\].*no BATCH_REFLLOW= field"),
    "qtx bad value": (_QTX.replace("STD_R=5.00", "STD_R=5,00", 1), "STD_R value 2: '00'|STD_REFLPOINTS says"),
    "qtx grid": (_QTX.replace("BATCH_REFLINTERVAL=10", "BATCH_REFLINTERVAL=20", 1), "must share one grid"),
    "qtx no equals": (_QTX.replace("STD_VIEWING=SCI", "STD_VIEWING SCI"), "'STD_VIEWING SCI' is not FIELD=VALUE"),
}


@pytest.mark.parametrize("case", sorted(MALFORMED_TEXT))
def test_malformed_exchange_text_gets_one_clear_line(case):
    text, expected = MALFORMED_TEXT[case]
    with pytest.raises(SpectrumError, match=expected) as raised:
        parse_spectra(text, "bad." + case.split()[0])
    message = str(raised.value)
    assert "\n" not in message and len(message) < 400 and message.startswith("bad.")


def _zip(members, compress=zipfile.ZIP_DEFLATED):
    buffer = io.BytesIO()
    with zipfile.ZipFile(buffer, "w", compress) as archive:
        for name, data in members.items():
            archive.writestr(name, data)
    return buffer.getvalue()


def _book_members():
    with zipfile.ZipFile(CORPUS / "workbook.xlsx") as archive:
        return {name: archive.read(name) for name in archive.namelist()}


def _bomb():
    data = bytearray(_zip({**_book_members(), "xl/worksheets/sheet1.xml": b"<a/>" + b" " * 200000}))
    # the sheet's central-directory entry claims 10 GB uncompressed (offset 24 of the entry)
    at = data.rfind(b"PK\x01\x02", 0, data.rfind(b"xl/worksheets/sheet1.xml"))
    data[at + 24:at + 28] = (4_000_000_000).to_bytes(4, "little")
    return bytes(data)


def _edited(name, old, new):
    members = _book_members()
    members[name] = members[name].replace(old, new)
    return _zip(members)


MALFORMED_BOOKS = {
    "zip bomb claim": (_bomb(), r"member xl/worksheets/sheet1.xml claims 3.73 GiB"),
    "damaged zip": ((CORPUS / "workbook.xlsx").read_bytes()[:-30], "cannot be opened|not a readable"),
    "sheet DOCTYPE": (_edited("xl/worksheets/sheet1.xml", b"<worksheet", b'<!DOCTYPE w [<!ENTITY a "b">]><worksheet'),
                      "DOCTYPE or ENTITY declaration is not accepted .SpreadsheetML needs none."),
    "shared string out of range": (_edited("xl/worksheets/sheet1.xml", b"<v>0</v>", b"<v>99</v>"),
                                   "shared string '99' is not one of the workbook's"),
    "cell beyond XFD": (_edited("xl/worksheets/sheet1.xml", b'r="A1"', b'r="ZZZ1"'), "beyond a sheet's 16384 columns"),
    "text among numbers": (_edited("xl/worksheets/sheet1.xml", b'<c r="C2"><v>0.05</v>',
                                   b'<c r="C2" t="e"><v>#N/A</v>'),
                           r"sheet 'Spectra', line 2, column '380 nm': '#N/A' is not a number"),
    "no workbook part": (_zip({k: v for k, v in _book_members().items() if k != "xl/worksheets/sheet1.xml"}),
                         "has no xl/worksheets/sheet1.xml part"),
    "stored claim": (_zip({**_book_members()}, zipfile.ZIP_STORED), None),
}


@pytest.mark.parametrize("case", sorted(MALFORMED_BOOKS))
def test_malformed_workbooks_get_one_clear_line(case, tmp_path):
    data, expected = MALFORMED_BOOKS[case]
    path = tmp_path / "book.xlsx"
    path.write_bytes(data)
    if expected is None:  # a stored (uncompressed) workbook is valid too
        assert read_spectra(path, percent=False).names == NAMES
        return
    with pytest.raises(SpectrumError, match=expected) as raised:
        read_spectra(path)
    assert "\n" not in str(raised.value) and len(str(raised.value)) < 400


# --- recognised but not read ---------------------------------------------------------------------

RECOGNISED = {
    "legacy.xls": (b"\xd0\xcf\x11\xe0\xa1\xb1\x1a\xe1" + bytes(504), "legacy Excel .xls workbook.*save it as .xlsx"),
    "report.pdf": (b"%PDF-1.7\n%\xe2\xe3\xcf\xd3\n", "PDF document; spectra printed in a PDF"),
    "photo.png": (b"\x89PNG\r\n\x1a\n" + bytes(20), "PNG image;.*spectrocolor.read_cube"),
    "photo.jpg": (b"\xff\xd8\xff\xe0\x00\x10JFIF", "JPEG image"),
    "cube.tif": (b"II*\x00\x08\x00\x00\x00", "TIFF image;.*read_cube"),
    "cube.mat": (b"\x89HDF\r\n\x1a\n" + bytes(10), "HDF5 file .MATLAB v7.3"),
    "display.icc": (bytes(36) + b"acsp" + bytes(90), "ICC colour profile"),
    "archive.zip": (_zip({"data/red.csv": b"nm,a\n"}), r"ZIP archive \(1 members: 'data/red.csv'\); unpack it"),
    "sheet.ods": (_zip({"mimetype": b"application/vnd.oasis.opendocument.spreadsheet", "content.xml": b"<a/>"}),
                  "OpenDocument"),
    "book.xlsb": (_zip({"xl/workbook.bin": b"\x00"}), "Excel binary workbook"),
    "data.gz": (b"\x1f\x8b\x08\x00", "gzip-compressed"),
}


@pytest.mark.parametrize("name", sorted(RECOGNISED))
def test_recognised_formats_are_named_not_listed(name, tmp_path):
    data, expected = RECOGNISED[name]
    path = tmp_path / name
    path.write_bytes(data)
    for call in (lambda: read_spectra(path), lambda: parse_spectra(data, name)):
        with pytest.raises(SpectrumError, match=expected) as raised:
            call()
        message = str(raised.value)
        assert "this is" in message and "Formats tried" not in message and "not UTF-8" not in message
        assert "\n" not in message and len(message) < 300


def test_the_generic_list_is_short():
    with pytest.raises(SpectrumError, match="Formats tried") as raised:
        parse_spectra("colour,size\nred,3\n", "notes.txt")
    assert len(str(raised.value)) < 350 and "CxF3" in str(raised.value)


def test_cli_reads_a_workbook_through_the_real_entry_point():
    import subprocess
    import sys

    done = subprocess.run([sys.executable, "-m", "spectrocolor", "xyz", str(CORPUS / "workbook.xlsx"),
                           "--illuminant", "D50"], capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    assert NAMES[0] in done.stdout


def test_cli_report_writes_cxf_with_the_spectra_and_their_colours(tmp_path):
    import subprocess
    import sys
    import xml.etree.ElementTree as ElementTree

    out = tmp_path / "report.cxf"
    done = subprocess.run([sys.executable, "-m", "spectrocolor", "report", str(CORPUS / "xrite.cxf"), "--illuminant",
                           "D50", "--out", str(out)], capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    back = read_spectra(out)
    assert back == _read("xrite.cxf") and back.names == NAMES  # == compares grid and values exactly
    assert (back.metadata["illuminant"], back.metadata["observer"]) == ("D50", "2°")
    ns = {"cc": "http://colorexchangeformat.com/CxF3-core"}
    lab = ElementTree.parse(out).getroot().findall(".//cc:ColorCIELab", ns)
    assert len(lab) == 3
    report = sc.measurement_report(_read("xrite.cxf"), illuminant="D50").records()
    # the report's rounded numbers, written by repr() and read back by float(): the same doubles
    assert float(lab[0].find("cc:L", ns).text) == report[0]["L*"]  # exact: repr/float round trip


def test_qtx_section_words_and_prefixes_vary_by_software():
    text = ("[PRODUCT STANDARD_DATA 0]\nSTANDARD_NAME=Navy\nSTANDARD_REFLLOW=400\nSTANDARD_REFLINTERVAL=20\n"
            "STANDARD_REFLPOINTS=3\nSTANDARD_R=10.5,20,30,\n\n[PRODUCT TRIAL_DATA 0]\nTRIAL_NAME=Navy lot 7\n"
            "TRIAL_REFLLOW=400\nTRIAL_REFLINTERVAL=20\nTRIAL_REFLPOINTS=3\nTRIAL_R=11,21,29\n")
    s = parse_spectra(text, "navy.qtx")
    assert s.names == ("Navy", "Navy lot 7") and s.metadata["sample_fields"]["kind"] == ("standard", "batch")
    # exact: small integers times 20 added to 400
    assert np.array_equal(s.wavelengths_nm, [400, 420, 440])
    np.testing.assert_allclose(s.values, [[0.105, 0.2, 0.3], [0.11, 0.21, 0.29]], rtol=0, atol=1e-16)


def test_cxf_object_with_several_measurement_conditions_names_each():
    two = _CXF.replace("</cc:ReflectanceSpectrum>\n        </cc:ColorValues>",
                       '</cc:ReflectanceSpectrum>\n<cc:ReflectanceSpectrum ColorSpecification="CS_M2">'
                       + " ".join(["0.5"] * 36) + "</cc:ReflectanceSpectrum>\n        </cc:ColorValues>", 1)
    two = two.replace("</cc:ColorSpecificationCollection>",
                      '<cc:ColorSpecification Id="CS_M2"><cc:TristimulusSpec><cc:Illuminant>D65</cc:Illuminant>'
                      "<cc:Observer>10_Degree</cc:Observer></cc:TristimulusSpec><cc:MeasurementSpec>"
                      '<cc:WavelengthRange StartWL="380" Increment="10"/></cc:MeasurementSpec>'
                      "</cc:ColorSpecification></cc:ColorSpecificationCollection>")
    s = parse_spectra(two, "two.cxf")
    assert s.names == (f"{NAMES[0]} [CS_D50_2]", f"{NAMES[0]} [CS_M2]", NAMES[1], NAMES[2])
    assert s.metadata["illuminant"] == ("D50", "D65", "D50", "D50")
    assert s.metadata["observer"] == ("2°", "10°", "2°", "2°")
