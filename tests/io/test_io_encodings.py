"""Measurement files as they arrive (issue 26, items 1 and 2): any encoding a lab's software writes,
trailing delimiters, two-row headers and Cary's paired wavelength/value columns.

The corpus (``tests/data/io/make_dialects.py``) holds the same three samples as ``make_corpus.py``
in each encoding and dialect; every file reads to those values and gives the same XYZ to 1e-12.
"""

import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import spectrocolor as sc
from spectrocolor import Spectrum, SpectrumError
from spectrocolor.io.text import decode_text

CORPUS = Path(__file__).parents[1] / "data" / "io"
GRID = np.arange(380, 731, 10)
NAMES = ("Rot – glänzend", "Grün µ2", "Grau 10°")


def _counts(i, nm):  # make_dialects.py's samples, integers of 1e-4
    if i == 0:
        return 500 + int(8000 / (1 + 2.0 ** ((600 - nm) / 12)))
    if i == 1:
        return 400 + int(5000 * 2.0 ** (-(((nm - 530) / 40) ** 2)))
    return 1800 + (nm - 380) // 10


COUNTS = np.array([[_counts(i, int(nm)) for nm in GRID] for i in range(3)])

#: file: (encoding reported, how it was chosen, names, format, percent option)
CASES = {
    "colorport_latin1.cgats": ("cp1252", "not UTF-8", tuple(n.replace("–", "-") for n in NAMES), "CGATS", None),
    "excel_cp1252.csv": ("cp1252", "not UTF-8", NAMES, "CSV, wide", None),
    "utf16le_bom.tsv": ("utf-16-le", "UTF-16 LE byte-order mark", NAMES, "TSV, long", None),
    "utf8_bom.csv": ("utf-8", "UTF-8 byte-order mark", NAMES, "CSV, long", None),
    "comma_trailing.csv": ("utf-8", "valid UTF-8", NAMES, "CSV, long", None),
    "semicolon_trailing.csv": ("utf-8", "valid UTF-8", NAMES, "CSV (; with decimal comma), wide", None),
    "cary_paired.csv": ("utf-8", "valid UTF-8", NAMES, "CSV, paired wavelength/value columns", None),  # %R says
}


def _read(name, **options):
    return sc.read_spectra(CORPUS / name, percent=CASES[name][4], **options)


@pytest.mark.parametrize("name", sorted(CASES))
def test_each_file_reads_to_its_samples_and_says_its_encoding(name):
    encoding, how, names, kind, _ = CASES[name]
    spectra = _read(name)
    assert spectra.names == names
    assert spectra.metadata["encoding"] == encoding and how in spectra.metadata["encoding_note"]
    assert spectra.metadata["format"].startswith(kind)
    # exact: decimal text parsed by float(): correctly rounded, the same double on every CPU
    assert np.array_equal(spectra.wavelengths_nm, GRID)
    np.testing.assert_allclose(spectra.values, COUNTS / 10000, rtol=0, atol=1e-15)


def test_the_same_samples_through_every_encoding_and_dialect_give_the_same_xyz():
    reference = sc.tristimulus(Spectrum(GRID, COUNTS / 10000), illuminant="D65", method="astm-e308")
    for name in CASES:
        XYZ = sc.tristimulus(_read(name), illuminant="D65", method="astm-e308")
        np.testing.assert_allclose(XYZ, reference, rtol=0, atol=1e-12, err_msg=name)


def test_colorport_keeps_its_degree_sign_and_cary_says_what_it_did():
    colorport = _read("colorport_latin1.cgats")
    assert "ObserverAngle=2°" in str(colorport.metadata["keywords"]["MEASUREMENT_SOURCE"])
    cary = _read("cary_paired.csv")
    assert "descending" in cary.metadata["wavelength_order"] and cary.metadata["value_kinds"] == ("%R",) * 3
    assert cary.metadata["lines_after_data"] == 5 and "resampled" not in cary.metadata
    assert cary.metadata["value_scale"] == "divided by 100 as the file declares (value columns titled %R)"


def test_cary_percent_columns_are_a_declaration_that_percent_false_contradicts():
    with pytest.raises(SpectrumError, match=r"declares its values on percent \(value columns titled %R\); "
                                            r"percent=False contradicts it"):
        sc.read_spectra(CORPUS / "cary_paired.csv", percent=False)
    asked = sc.read_spectra(CORPUS / "cary_paired.csv", percent=True)
    # exact: the same text read twice, divided by the same 100
    assert np.array_equal(asked.values, _read("cary_paired.csv").values)


def test_encoding_argument_overrides_detection():
    path = CORPUS / "excel_cp1252.csv"
    assert _read("excel_cp1252.csv", encoding="cp1252").metadata["encoding_note"] == "as given (encoding='cp1252')"
    as_latin1 = _read("excel_cp1252.csv", encoding="latin-1")  # 0x96 is a C1 control in Latin-1
    assert as_latin1.metadata["encoding"] == "iso8859-1" and as_latin1.names[0] == "Rot \x96 glänzend"
    with pytest.raises(SpectrumError, match=r"byte \d+ \(0x96\) is not valid utf-8 \(encoding='utf-8'\)") as err:
        sc.read_spectra(path, encoding="utf-8")
    assert str(path) in str(err.value)
    with pytest.raises(SpectrumError, match="encoding: unknown encoding 'klingon'; expected utf-8, .*cp1252"):
        sc.read_spectra(path, encoding="klingon")
    data = path.read_bytes()
    assert sc.parse_spectra(data, "x.csv").names == NAMES
    with pytest.raises(SpectrumError, match="encoding: applies to bytes"):
        sc.parse_spectra(data.decode("cp1252"), "x.csv", encoding="cp1252")


@pytest.mark.parametrize(
    ("data", "offending"),
    [
        (b"wavelength_nm,a\n400,0.5\n\xb5\x81\n", r"byte 24 \(0xB5\) is not valid UTF-8, and byte 25 \(0x81\) is "
                                                   r"undefined in cp1252, so it is not cp1252 either"),
        # (a workbook's "PK\x03\x04" is now named by io/sniff.py: tests/io/test_io_exchange.py)
        (b"XY\x03\x04\x14\x10\x06\xb0[Content_Types].xml", r"byte 7 \(0xB0\) is not valid UTF-8, and byte 2 "
                                                            r"\(0x03\) is a control character"),
        ("wavelength_nm,a\n400,0.5\n".encode("utf-16-le"), r"byte 1 \(0x00\) is a NUL byte, .*\(UTF-16 without"),
    ],
    ids=["undefined-in-cp1252", "control-bytes", "utf16-without-bom"],
)
def test_an_ambiguous_or_binary_file_gets_one_clear_error(tmp_path, data, offending):
    path = tmp_path / "export.csv"
    path.write_bytes(data)
    with pytest.raises(SpectrumError) as err:
        sc.read_spectra(path)
    message = str(err.value)
    assert message.startswith(f"{path}: not text in a known encoding: byte ")
    assert "\n" not in message and "pass encoding= (--encoding on the command line)" in message
    assert "cp1252, latin-1" in message  # what is accepted
    assert re.search(offending, message), message


def test_a_wrong_byte_order_mark_says_so():
    with pytest.raises(SpectrumError, match=r"starts with a UTF-16 LE byte-order mark but byte 2 \(0x00\) is not"):
        decode_text(b"\xff\xfe\x00\xd8", "x.csv")  # a lone surrogate


@pytest.mark.parametrize(
    "text",
    [
        "wavelength_nm;a;\n400;0,1;\n500;0,2;\n",   # header and rows end in ';'
        "wavelength_nm;a\n400;0,1;\n500;0,2;;\n",   # rows only, any number of empty cells
        "wavelength_nm;a;;\n400;0,1\n500;0,2\n",    # header only
    ],
)
def test_empty_trailing_columns_are_dropped(text):
    spectra = sc.parse_spectra(text, "x.csv")
    assert spectra.names == ("a",)
    np.testing.assert_allclose(spectra.values, [0.1, 0.2], rtol=0, atol=1e-15)


def test_a_value_under_an_empty_header_cell_is_an_error():
    with pytest.raises(SpectrumError, match=r"x.csv, line 3: 3 cells, but the header has 2 \(cell 3 holds '7'"):
        sc.parse_spectra("wavelength_nm,a,\n400,0.1,\n500,0.2,7\n", "x.csv")


def test_descending_long_and_wide_tables_are_sorted_ascending():
    long = sc.parse_spectra("nm,a\n500,0.5\n450,0.4\n400,0.3\n", "x.csv")
    wide = sc.parse_spectra("Sample,500,450,400\na,0.5,0.4,0.3\n", "x.csv")
    for spectra in (long, wide):
        # exact: decimal text parsed by float(): correctly rounded, the same double on every CPU
        assert spectra.wavelengths_nm.tolist() == [400, 450, 500] and spectra.values.tolist() == [0.3, 0.4, 0.5]
        assert "descending" in spectra.metadata["wavelength_order"]


def test_paired_columns_on_one_header_row_and_on_different_grids():
    one_row = sc.parse_spectra("Wavelength (nm),%T,Wavelength (nm),%T\n500,1,500,2\n400,3,400,4\n", "x.csv")
    assert one_row.names == ("%T 1", "%T 2") and "titled %T" in one_row.metadata["value_scale"]
    np.testing.assert_allclose(one_row.values, [[0.03, 0.01], [0.04, 0.02]], rtol=1e-15)  # %T: divided by 100
    differ = sc.parse_spectra(
        "a,,b,\nWavelength (nm),Abs,Wavelength (nm),Abs,\n400,1,410,5,\n420,3,430,7,\n440,5,450,9,\n", "x.csv")
    assert differ.wavelengths_nm.tolist() == [420, 440]
    assert "interpolated linearly" in differ.metadata["resampled"]
    np.testing.assert_allclose(differ.values, [[3.0, 5.0], [6.0, 8.0]], rtol=0, atol=1e-15)


def test_a_half_empty_pair_is_an_error():
    with pytest.raises(SpectrumError, match=r"line 3: sample 'b': cell 4 is empty but its pair is not"):
        sc.parse_spectra("a,,b,\nWavelength (nm),%R,Wavelength (nm),%R,\n400,1,400,,\n", "x.csv")


def test_cli_encoding_through_the_real_entry_point():
    path = CORPUS / "excel_cp1252.csv"

    def xyz(*extra):
        return subprocess.run([sys.executable, "-m", "spectrocolor", "xyz", str(path), "--illuminant", "D65",
                               "--format", "csv", *extra], capture_output=True, text=True, timeout=120)

    detected, given, wrong = xyz(), xyz("--encoding", "cp1252"), xyz("--encoding", "utf-8")
    assert detected.returncode == 0 and given.returncode == 0, detected.stderr + given.stderr
    assert given.stdout == detected.stdout and "Grün µ2" in given.stdout
    assert wrong.returncode == 2 and wrong.stderr.count("\n") == 1 and "(0x96) is not valid utf-8" in wrong.stderr
