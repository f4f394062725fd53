"""Fuzzing the exchange-format readers (issue 26 item 4): CxF3, QTX, .xlsx workbooks and the sniffer.

Every reader is fed text from its own vocabulary, the corpus files with random damage, workbooks
with random bytes changed, cut short or with generated sheet XML, and random bytes behind each
recognised signature. A result is a Spectrum or one SpectrumError (a BudgetError is one) whose
message is one line; the CxF3 writer round-trips every name XML can hold and refuses the rest by
name.
"""

import io
import tempfile
import zipfile
from pathlib import Path

import numpy as np
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import spectrocolor as sc
from spectrocolor import Spectrum, SpectrumError
from spectrocolor.io import parse_spectra
from spectrocolor.io.cxf import spectra_to_cxf
from spectrocolor.io.text import decode_text
from spectrocolor.io.xlsx import parse_xlsx

CORPUS = Path(__file__).parents[1] / "data" / "io"
TEXTS = {name: decode_text((CORPUS / name).read_bytes(), name).text for name in ("xrite.cxf", "datacolor.qtx")}
BOOKS = {name: (CORPUS / name).read_bytes() for name in ("workbook.xlsx", "workbook_long.xlsx")}
SETTINGS = settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.too_slow])

TOKENS = st.sampled_from([
    '<cc:CxF xmlns:cc="http://colorexchangeformat.com/CxF3-core">', "</cc:CxF>", "<cc:Resources>",
    "</cc:Resources>", "<cc:ObjectCollection>", "</cc:ObjectCollection>", '<cc:Object Name="a">',
    "</cc:Object>", "<cc:ColorValues>", "</cc:ColorValues>", '<cc:ReflectanceSpectrum ColorSpecification="c">',
    '<cc:ReflectanceSpectrum ColorSpecification="c" StartWL="1e308">', "</cc:ReflectanceSpectrum>",
    '<cc:ColorSpecification Id="c">', "</cc:ColorSpecification>", "<cc:MeasurementSpec>", "</cc:MeasurementSpec>",
    '<cc:WavelengthRange StartWL="380" Increment="10"/>', '<cc:WavelengthRange StartWL="380" Increment="0"/>',
    '<cc:WavelengthRange StartWL="380" Increment="-1e308"/>', "<!DOCTYPE x>", '<!ENTITY e "x">', "&e;", "&#10;",
    "[STANDARD_DATA 0]", "[BATCH_DATA 1]", "[X TRIAL_DATA 2]", "STD_NAME=", "STD_R=", "STD_REFLLOW=",
    "STD_REFLINTERVAL=", "STD_REFLPOINTS=", "BATCH_R=", "BATCH_REFLPOINTS=99999999999", "TRIAL_R=",
    "0", "1", "-1", "0.5", "1e309", "nan", ",", " ", "\n", "\r\n", "=", "[", "]", "<", ">", '"',
])


def _outcome(call):
    """The call's result, or the SpectrumError it raised (checked to be one line)."""
    try:
        return call()
    except SpectrumError as exc:
        assert "\n" not in str(exc), str(exc)
        return exc


@SETTINGS
@given(st.lists(TOKENS, max_size=60))
def test_text_from_the_exchange_vocabulary(tokens):
    result = _outcome(lambda: parse_spectra("".join(tokens), "fuzz"))
    assert isinstance(result, (Spectrum, SpectrumError))
    if isinstance(result, Spectrum):
        assert np.all(np.isfinite(result.values)) and np.all(np.isfinite(result.wavelengths_nm))


@SETTINGS
@given(name=st.sampled_from(sorted(TEXTS)),
       edits=st.lists(st.tuples(st.floats(0, 1), st.integers(0, 40), st.lists(TOKENS, max_size=3).map("".join)),
                      min_size=1, max_size=4),
       percent=st.sampled_from([None, True, False]))
def test_cxf_and_qtx_with_random_damage(name, edits, percent):
    text = TEXTS[name]
    for where, cut, insert in edits:
        at = int(where * len(text))
        text = text[:at] + insert + text[at + cut:]
    result = _outcome(lambda: parse_spectra(text, name, percent))
    assert isinstance(result, (Spectrum, SpectrumError))
    if isinstance(result, Spectrum):
        assert np.all(np.isfinite(result.values))


@SETTINGS
@given(name=st.sampled_from(sorted(BOOKS)),
       changes=st.lists(st.tuples(st.floats(0, 1), st.binary(min_size=1, max_size=4)), max_size=4),
       keep=st.floats(0.05, 1))
def test_workbooks_with_random_bytes_changed_or_cut(name, changes, keep):
    data = bytearray(BOOKS[name])
    for where, junk in changes:
        at = int(where * (len(data) - 1))
        data[at:at + len(junk)] = junk
    data = bytes(data[:max(1, int(keep * len(data)))])
    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder) / name
        path.write_bytes(data)
        result = _outcome(lambda: sc.read_spectra(path, percent=False))
    assert isinstance(result, (Spectrum, SpectrumError))


CELLS = st.one_of(
    st.builds(lambda r, v: f'<c r="{r}"><v>{v}</v></c>', st.sampled_from(["A1", "B1", "C2", "XFD9", "A0", "1A", ""]),
              st.sampled_from(["380", "0.5", "x", "", "1e400", "-0"])),
    st.builds(lambda v: f'<c t="s"><v>{v}</v></c>', st.sampled_from(["0", "1", "-1", "99", "a"])),
    st.builds(lambda t: f'<c t="inlineStr"><is><t>{t}</t></is></c>', st.sampled_from(["nm", "380", "red", "#x", ""])),
    st.sampled_from(['<c t="b"><v>1</v></c>', '<c t="e"><v>#N/A</v></c>', "<c/>", '<c r="B2" t="str"/>']),
)
ROWS = st.lists(st.builds(lambda r, cells: f'<row{r}>{"".join(cells)}</row>',
                          st.sampled_from(["", ' r="1"', ' r="2"', ' r="1048577"', ' r="x"']),
                          st.lists(CELLS, max_size=6)), max_size=8)


@SETTINGS
@given(rows=ROWS, sheet=st.sampled_from([None, 0, 1, -1, "Data", "nope", 1.5]))
def test_generated_sheets(rows, sheet):
    main = 'xmlns="http://schemas.openxmlformats.org/spreadsheetml/2006/main"'
    buffer = io.BytesIO()
    with zipfile.ZipFile(buffer, "w", zipfile.ZIP_DEFLATED) as book:
        book.writestr("xl/workbook.xml", f'<workbook {main}><sheets><sheet name="Data"/></sheets></workbook>')
        book.writestr("xl/sharedStrings.xml",
                      f"<sst {main}><si><t>nm</t></si><si><r><t>re</t></r><r><t>d</t></r></si></sst>")
        book.writestr("xl/worksheets/sheet1.xml",
                      f'<worksheet {main}><sheetData>{"".join(rows)}</sheetData></worksheet>')
    result = _outcome(lambda: parse_xlsx(buffer.getvalue(), "fuzz.xlsx", sheet=sheet))
    assert isinstance(result, (Spectrum, SpectrumError))


SIGNATURES = [b"\xd0\xcf\x11\xe0\xa1\xb1\x1a\xe1", b"%PDF-", b"\x89PNG\r\n\x1a\n", b"\xff\xd8\xff", b"II*\x00",
              b"MM\x00*", b"\x89HDF\r\n\x1a\n", b"CDF\x01", b"MATLAB 5.0 MAT-file", b"\x93NUMPY", b"\x1f\x8b",
              b"7z\xbc\xaf\x27\x1c", b"Rar!\x1a\x07", b"PK\x03\x04", b"PK\x05\x06"]


@SETTINGS
@given(signature=st.sampled_from(SIGNATURES), rest=st.binary(max_size=300))
def test_random_bytes_behind_a_signature_are_named(signature, rest):
    result = _outcome(lambda: parse_spectra(signature + rest, "fuzz.bin"))
    assert isinstance(result, SpectrumError)
    message = str(result)
    assert "this is" in message or "ZIP archive" in message, message
    assert "Formats tried" not in message and len(message) < 300


XML_NAMES = st.text(st.characters(blacklist_categories=("Cs",)), min_size=1, max_size=20)


@SETTINGS
@given(names=st.lists(XML_NAMES, min_size=1, max_size=4, unique=True))
def test_cxf_writer_round_trips_every_name_xml_can_hold_and_refuses_the_rest(names):
    spectrum = Spectrum([400, 500, 600], np.linspace(0.1, 0.9, 3 * len(names)).reshape(len(names), 3), names)
    result = _outcome(lambda: parse_spectra(spectra_to_cxf(spectrum), "s.cxf"))
    if isinstance(result, SpectrumError):
        assert "a character an XML document cannot hold" in str(result)
        assert any(ord(c) < 0x20 and c not in "\t\n\r" or c in "\ufffe\uffff" for name in names for c in name)
        return
    assert result.names == spectrum.names
    # exact: repr() writes the shortest decimal that reads back as the same double
    assert np.array_equal(result.values.reshape(spectrum.values.shape), spectrum.values)


@SETTINGS
@given(values=st.lists(st.floats(0, 1), min_size=4, max_size=4), start=st.integers(360, 400))
def test_report_to_cxf_round_trips_the_spectra(values, start):
    from spectrocolor.io.cxf import report_to_cxf

    spectrum = Spectrum(np.arange(start, start + 400, 100), values, ["tile"])
    result = _outcome(lambda: report_to_cxf(spectrum, sc.measurement_report(spectrum, illuminant="D65")))
    if isinstance(result, SpectrumError):  # a grid the report cannot use is refused in one line
        return
    back = parse_spectra(result, "r.cxf")
    # exact: repr() writes the shortest decimal that reads back as the same double
    assert back == spectrum and back.metadata["illuminant"] == "D65"
