"""Every supported spectral file format, read from a corpus written to each format's description.

tests/data/io/ holds the same three reflectance samples (380–730 nm, 10 nm) as long and wide CSV,
TSV, ``;`` with decimal commas in percent, CGATS.17 (i1Profiler and X-Rite field names, CRLF),
ArgyllCMS .ti3 (percent) and .sp (SPECTRAL_NORM 100), IES TM-27-14 and -20 XML and JSON; see
tests/data/io/make_corpus.py for how each was written.
"""

import importlib.util
from pathlib import Path

import numpy as np
import pytest

import spectrocolor as sc
from spectrocolor import Spectrum, SpectrumError
from spectrocolor.io import parse_spectra
from spectrocolor.io.writers import spectra_to_cgats, table_to_cgats

CORPUS = Path(__file__).parents[1] / "data" / "io"
_spec = importlib.util.spec_from_file_location("make_corpus", CORPUS / "make_corpus.py")
make_corpus = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(make_corpus)

GRID = np.arange(380.0, 731.0, 10.0)
NAMES = ("red tile", "green tile", "grey card")
EXPECTED = np.array(make_corpus.COUNTS) / 10000  # reflectance factors, 0–1

# file -> (percent option the format needs, samples it holds, names it gives)
FILES = {
    "long.csv": (False, 3, NAMES),
    "long.tsv": (False, 3, NAMES),
    "wide.csv": (False, 3, NAMES),
    "wide_named_dated.csv": (False, 3, NAMES),
    "semicolon_decimal_comma_percent.csv": (True, 3, NAMES),
    "i1profiler.txt": (False, 3, NAMES),
    "xrite_underscore.cgats": (False, 3, NAMES),
    "argyll.ti3": (None, 3, ("1", "2", "3")),  # CTI3: percent by Argyll's convention
    "argyll.sp": (None, 1, ("sample_1",)),  # SPECTRAL_NORM "100"
    "tm27_14.xml": (False, 1, ("Tiles Inc. – R-1 – red tile",)),
    "tm27_20.spdx": (False, 3, ("Tiles Inc. – tiles 1", "Tiles Inc. – tiles 2", "Tiles Inc. – tiles 3")),
    "samples.json": (False, 3, NAMES),
}


def _read(name):
    percent, _, _ = FILES[name]
    return sc.read_spectra(CORPUS / name, percent=percent)


@pytest.mark.parametrize("name", FILES)
def test_each_file_reads_to_the_values_it_was_written_with(name):
    _, count, names = FILES[name]
    s = _read(name)
    # exact: decimal text parsed by float(): correctly rounded, the same double on every CPU
    np.testing.assert_array_equal(s.wavelengths_nm, GRID)
    assert s.names == names
    # four decimals as fractions or two as percent: equal to 1 ulp of the division by 100
    np.testing.assert_allclose(np.atleast_2d(s.values), EXPECTED[:count], rtol=2e-16, atol=0)


def test_spot_values_typed_from_the_files():
    # exact: decimal text parsed by float(): correctly rounded, the same double on every CPU
    assert _read("i1profiler.txt").values[0, 22] == 0.4500  # red tile, SPECTRAL_NM600
    assert _read("argyll.ti3").values[1, 15] == pytest.approx(0.5400, abs=1e-16)  # SPEC_530 54.00 %
    assert _read("semicolon_decimal_comma_percent.csv").values[2, 0] == pytest.approx(0.18, abs=1e-16)  # "18,00"


@pytest.mark.parametrize("observer", ["1931", "1964"])
@pytest.mark.parametrize("method", ["sum", "astm-e308"])
def test_the_same_samples_in_every_format_give_the_same_XYZ(observer, method):
    reference = sc.tristimulus(Spectrum(GRID, EXPECTED), observer=observer, illuminant="D65", method=method)
    for name, (_, count, _) in FILES.items():
        XYZ = sc.tristimulus(_read(name), observer=observer, illuminant="D65", method=method)
        np.testing.assert_allclose(np.atleast_2d(XYZ), reference[:count], rtol=0, atol=1e-12, err_msg=name)


def test_format_is_told_by_content_not_by_the_file_name(tmp_path):
    disguised = tmp_path / "really_a_ti3.csv"
    disguised.write_bytes((CORPUS / "argyll.ti3").read_bytes())
    assert sc.read_spectra(disguised).metadata["format"] == "ArgyllCMS .ti3"


def test_metadata_kept_from_cgats_keywords_and_fields():
    s = _read("i1profiler.txt")
    m = s.metadata
    assert m["format"] == "CGATS (CGATS.17)" and m["originator"] == "i1Profiler"
    assert m["instrument"] == "i1Pro 2" and m["geometry"] == "45/0" and m["date"] == "May 01, 2024"
    assert m["illuminant"].startswith("Illumination=D50")
    assert m["sample_fields"]["LAB_L"] == ("50.00",) * 3 and m["sample_fields"]["SAMPLE_ID"] == ("1", "2", "3")
    assert "as written" in m["value_scale"]
    ti3 = _read("argyll.ti3").metadata
    assert ti3["instrument"] == "X-Rite i1 Pro 2" and "CTI3" in ti3["value_scale"]
    assert ti3["sample_fields"]["XYZ_Y"] == ("25.0",) * 3


def test_metadata_kept_from_wide_csv_and_tm27():
    wide = _read("wide_named_dated.csv").metadata
    assert wide["format"] == "CSV, wide" and wide["sample_fields"]["Date"] == ("2024-05-01", "2024-05-02", "2024-05-03")
    tm = _read("tm27_14.xml").metadata
    assert tm["format"] == "IES TM-27 XML (version 1.0)" and tm["instrument"] == "i1Pro 2"
    assert tm["geometry"] == "45/0" and tm["bandwidth_fwhm_nm"] == "10" and tm["date"] == "2024-05-01"
    assert tm["spectral_quantity"] == "reflectance"
    assert _read("tm27_20.spdx").metadata["format"] == "IES TM-27 XML (version 2.0)"


def test_selecting_samples_selects_their_fields():
    s = _read("wide_named_dated.csv")[1:]
    assert s.names == NAMES[1:] and s.metadata["sample_fields"]["Date"] == ("2024-05-02", "2024-05-03")


def test_tm27_14_agrees_with_colour_science_reader():
    colour = pytest.importorskip("colour")
    theirs = colour.SpectralDistribution_IESTM2714(str(CORPUS / "tm27_14.xml"))
    theirs.read()
    # exact: decimal text parsed by float(): correctly rounded, the same double on every CPU
    np.testing.assert_array_equal(theirs.wavelengths, GRID)
    # exact: decimal text parsed by float(): correctly rounded, the same double on every CPU
    np.testing.assert_array_equal(theirs.values, _read("tm27_14.xml").values)


def test_cgats_to_cgats_round_trip_is_exact(tmp_path):
    first = _read("i1profiler.txt")
    path = sc.write_spectra(first, tmp_path / "out.cgats")
    second = sc.read_spectra(path)  # SPECTRAL_NORM "1" written: no percent option needed
    assert second == first and second.names == first.names
    assert second.metadata["sample_fields"]["LAB_B"] == first.metadata["sample_fields"]["LAB_B"]
    assert second.metadata["instrument"] == "i1Pro 2" and "SPECTRAL_NORM" in second.metadata["value_scale"]
    assert spectra_to_cgats(second) == spectra_to_cgats(first)


def test_percent_option_contradicting_the_file_is_refused():
    with pytest.raises(SpectrumError, match="percent: .* declares its values on percent .*CTI3"):
        sc.read_spectra(CORPUS / "argyll.ti3", percent=False)
    with pytest.raises(SpectrumError, match="percent: expected True, False or None"):
        sc.read_spectra(CORPUS / "long.csv", percent="yes")


def test_percent_is_never_guessed():
    s = sc.read_spectra(CORPUS / "semicolon_decimal_comma_percent.csv")
    assert s.values.max() > 1 and "does not declare" in s.metadata["value_scale"]


def test_a_file_that_is_none_of_them_names_the_formats_tried(tmp_path):
    path = tmp_path / "notes.txt"
    path.write_text("colour,notes\nred,nice\n")
    with pytest.raises(SpectrumError) as info:
        sc.read_spectra(path)
    message = str(info.value)
    assert "\n" not in message
    # the list names the formats only (issue 26 item 4: short); docs/measurement_data.md describes them
    for expected in ("JSON", "TM-27", "CGATS", "CxF3", "QTX", "OceanView", "light meters", "CSV/TSV", ".xlsx",
                     "not recognisably a wavelength"):
        assert expected in message
    assert len(message) - len(str(path)) < 350  # short whatever the folder's name (pytest's tmp_path varies)


@pytest.mark.parametrize(
    ("text", "message"),
    [
        (
            "CGATS.17\nBEGIN_DATA_FORMAT\nSAMPLE_NAME LAB_L\nEND_DATA_FORMAT\nBEGIN_DATA\na 1\nEND_DATA\n",
            "without spectral",
        ),
        ("CGATS.17\nBEGIN_DATA_FORMAT\nSPEC_400 SPEC_410\nEND_DATA_FORMAT\nBEGIN_DATA\n1 2\n", "cut short"),
        (
            "CGATS.17\nNUMBER_OF_SETS 2\nBEGIN_DATA_FORMAT\nSPEC_400 SPEC_410\nEND_DATA_FORMAT\n"
            "BEGIN_DATA\n1 2\nEND_DATA\n",
            "NUMBER_OF_SETS says 2",
        ),
        (
            "CGATS.17\nBEGIN_DATA_FORMAT\nSPEC_400 SPEC_410\nEND_DATA_FORMAT\nBEGIN_DATA\n1 x\nEND_DATA\n",
            "line 6, field SPEC_410: 'x' is not a number",
        ),
        ("CGATS.17\nBEGIN_DATA_FORMAT\nSPEC_400 SPEC_410\nEND_DATA_FORMAT\nBEGIN_DATA\n1\nEND_DATA\n", "1 values"),
        ("<IESTM2714><SpectralDistribution/></IESTM2714>", "no <SpectralData"),
        ("<IESTM2714><Header>", "not well-formed XML"),
        ("<svg></svg>", "not IES TM-27"),
        ('<!DOCTYPE x [<!ENTITY a "b">]><IESTM2714/>', "DOCTYPE"),
        ("Sample,400,410,420\na,0.1,0.2\n", "line 2: 3 cells"),
        ("Sample;400;410;420\na;0,1;zero;0,3\n", "column '410': 'zero' is not a number"),
    ],
)
def test_malformed_instrument_files_get_one_clear_line(text, message):
    with pytest.raises(SpectrumError, match=message) as info:
        parse_spectra(text, "f")
    assert "\n" not in str(info.value)


def test_cgats_comments_after_values_are_ignored():
    text = "CGATS.17 # exported\nBEGIN_DATA_FORMAT\nSPEC_400 SPEC_410 # two bands\nEND_DATA_FORMAT\n"
    text += "BEGIN_DATA\n1 2 # first row\nEND_DATA\n"
    s = parse_spectra(text, "f", percent=False)
    # exact: decimal text parsed by float(): correctly rounded, the same double on every CPU
    assert s.values.tolist() == [1.0, 2.0] and s.metadata["file_identifier"] == "CGATS.17"


def test_table_to_cgats_uses_standard_field_names_and_reads_back_its_numbers():
    text = table_to_cgats([{"name": "a", "X": 41.2, "Y": 21.3, "Z": 1.9, "L*": 53.3, "purity": 0.5}])
    assert "SAMPLE_ID SAMPLE_NAME XYZ_X XYZ_Y XYZ_Z LAB_L PURITY" in text and text.endswith("END_DATA\r\n")
    assert '1 "a" 41.200000000000003 21.300000000000001' in text
