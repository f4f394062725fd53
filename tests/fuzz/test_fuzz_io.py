"""Fuzzing the file readers: generated malformed files get one clear SpectrumError, never a traceback.

Every reader is fed (a) text built from its own vocabulary (CGATS keywords, TM-27 elements, CSV
delimiters and wavelength headers), (b) valid corpus files with random cuts, insertions and
replacements, and (c) random bytes; ENVI headers get random field values and MATLAB files random
damage. A result is either a Spectrum/SpectralCube or a SpectrumError with a one-line message.
"""

import re
import tempfile
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, example, given, settings
from hypothesis import strategies as st

import spectrocolor as sc
from spectrocolor import Spectrum, SpectrumError
from spectrocolor.images import read_cube
from spectrocolor.io import parse_spectra
from spectrocolor.io.text import decode_text

CORPUS = Path(__file__).parents[1] / "data" / "io"
CORPUS_TEXTS = {p.name: decode_text(p.read_bytes(), p.name).text  # the corpus holds cp1252 and UTF-16 too
                for p in sorted(CORPUS.iterdir()) if p.suffix not in (".py", ".xlsx")}  # workbooks: test_fuzz_exchange
SETTINGS = settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.too_slow])

TOKENS = st.sampled_from(
    [
        "CGATS.17",
        "CTI3",
        "SPECT",
        "BEGIN_DATA_FORMAT",
        "END_DATA_FORMAT",
        "BEGIN_DATA",
        "END_DATA",
        "NUMBER_OF_SETS",
        "NUMBER_OF_FIELDS",
        "KEYWORD",
        '"SPECTRAL_NORM"',
        "SPECTRAL_NORM",
        "SAMPLE_NAME",
        "SAMPLE_ID",
        "SPECTRAL_NM380",
        "SPECTRAL_NM_390",
        "SPEC_400",
        "nm410",
        "LAB_L",
        '"',
        '""',
        "#",
        "0",
        "-1",
        "1e309",
        "nan",
        "inf",
        "0,5",
        "3.5",
        "380",
        "380nm",
        "wavelength_nm",
        "Sample",
        "Name",
        ",",
        ";",
        "\t",
        "\n",
        "\r\n",
        " ",
        "<IESTM2714>",
        "</IESTM2714>",
        "<SpectralDistribution>",
        "</SpectralDistribution>",
        '<SpectralData wavelength="400">',
        '<SpectralData wavelength="x">',
        "</SpectralData>",
        "<Header>",
        "</Header>",
        "{",
        "}",
        "[",
        "]",
        '"wavelengths_nm":',
        '"spectra":',
        "\x00",
        "é",
        "1" * 200,
    ]
)


def _outcome(call):
    """The call's result, or the SpectrumError it raised (checked to be one line)."""
    try:
        return call()
    except SpectrumError as exc:
        assert "\n" not in str(exc), str(exc)
        return exc


@SETTINGS
@given(st.lists(TOKENS, max_size=80))
def test_text_from_the_formats_vocabulary(tokens):
    result = _outcome(lambda: parse_spectra("".join(tokens), "fuzz"))
    assert isinstance(result, (Spectrum, SpectrumError))


@pytest.mark.parametrize("text", ['{"a":' * 100_000, "[" * 100_000, "<IESTM2714>" + "<a>" * 100_000])
def test_deeply_nested_json_and_xml(text):
    with pytest.raises(SpectrumError):
        parse_spectra(text, "deep")


@SETTINGS
@given(st.text(max_size=400))
def test_any_text(text):
    assert isinstance(_outcome(lambda: parse_spectra(text, "fuzz")), (Spectrum, SpectrumError))


@SETTINGS
@given(
    name=st.sampled_from(sorted(CORPUS_TEXTS)),
    edits=st.lists(
        st.tuples(st.floats(0, 1), st.integers(0, 40), st.lists(TOKENS, max_size=3).map("".join)),
        min_size=1,
        max_size=4,
    ),
    percent=st.sampled_from([None, True, False]),
)
def test_corpus_files_with_random_damage(name, edits, percent):
    text = CORPUS_TEXTS[name]
    for where, cut, insert in edits:
        at = int(where * len(text))
        text = text[:at] + insert + text[at + cut :]
    result = _outcome(lambda: parse_spectra(text, name, percent))
    assert isinstance(result, (Spectrum, SpectrumError))
    if isinstance(result, Spectrum):
        assert np.all(np.isfinite(result.values))


@SETTINGS
@given(st.binary(max_size=600))
def test_random_bytes_as_a_file(data):
    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder) / "fuzz.txt"
        path.write_bytes(data)
        assert isinstance(_outcome(lambda: sc.read_spectra(path)), (Spectrum, SpectrumError))


ENVI_VALUES = st.one_of(
    st.integers(-5, 70).map(str), st.sampled_from(["", "x", "{", "}", "{1, 0}", "nan", "-9999", "1e400", "{a, b}"])
)
ENVI_FIELDS = [
    "reflectance scale factor",
    "data ignore value",
    "bbl",
    "fwhm",
    "header offset",
    "data type",
    "byte order",
    "interleave",
    "bands",
    "wavelength units",
]


@SETTINGS
@given(st.dictionaries(st.sampled_from(ENVI_FIELDS), ENVI_VALUES, max_size=4))
def test_envi_headers_with_random_field_values(fields):
    header = {
        "samples": "2",
        "lines": "2",
        "bands": "3",
        "data type": "2",
        "interleave": "bsq",
        "byte order": "0",
        "wavelength": "{400, 500, 600}",
        "wavelength units": "nm",
    }
    header.update(fields)
    with tempfile.TemporaryDirectory() as folder:
        hdr = Path(folder) / "scene.hdr"
        hdr.write_text("ENVI\n" + "".join(f"{k} = {v}\n" for k, v in header.items()))
        (Path(folder) / "scene.img").write_bytes(np.arange(12, dtype="<i2").tobytes())
        result = _outcome(lambda: read_cube(hdr))
        if not isinstance(result, SpectrumError):
            np.asarray(result.values)  # reading the values is part of reading the file


@pytest.fixture(scope="module")
def mat_files(tmp_path_factory):
    import h5py
    import scipy.io

    folder = tmp_path_factory.mktemp("mat")
    cube = np.arange(2 * 3 * 4, dtype=np.float64).reshape(2, 3, 4)
    scipy.io.savemat(folder / "v5.mat", {"cube": cube, "wavelengths_nm": np.array([400.0, 500, 600, 700])})
    with h5py.File(folder / "v73.mat", "w", userblock_size=512) as handle:
        handle.create_dataset("cube", data=cube.T)
        handle.create_dataset("wavelengths_nm", data=np.array([400.0, 500, 600, 700]))
    with open(folder / "v73.mat", "r+b") as handle:
        handle.write(b"MATLAB 7.3 MAT-file")
    return {name: (folder / name).read_bytes() for name in ("v5.mat", "v73.mat")}


@settings(max_examples=100, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(
    name=st.sampled_from(["v5.mat", "v73.mat"]),
    where=st.floats(0, 1),
    junk=st.binary(min_size=1, max_size=64),
    truncate=st.booleans(),
)
def test_damaged_matlab_files(mat_files, name, where, junk, truncate):
    data = mat_files[name]
    at = int(where * (len(data) - 1))
    data = data[:at] if truncate else data[:at] + junk + data[at + len(junk) :]
    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder) / name
        path.write_bytes(data)
        result = _outcome(lambda: read_cube(path))
        if not isinstance(result, SpectrumError):
            _outcome(lambda: np.asarray(result.values))


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(
    name=st.sampled_from(sorted(CORPUS_TEXTS)),
    where=st.floats(0, 1),
    insert=st.lists(TOKENS, max_size=3).map("".join),
    command=st.sampled_from([["xyz", "--format", "cgats"], ["describe", "--format", "csv"], ["xyz", "--percent"]]),
)
def test_command_line_on_damaged_files_exits_0_or_2_with_one_line(capsys, name, where, insert, command):
    from spectrocolor.cli import main

    text = CORPUS_TEXTS[name]
    at = int(where * len(text))
    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder) / name
        path.write_text(text[:at] + insert + text[at + 5 :], encoding="utf-8")
        status = main([command[0], str(path), *command[1:]])
    err = capsys.readouterr().err
    assert status in (0, 2) and "Traceback" not in err
    if status == 2:  # an error: one line
        assert err.count("\n") == 1, err
    else:  # read: at most a warning (--percent on 0–1 data) and a note on the file's declared conditions
        lines = err.splitlines()
        assert len(lines) <= 2 and all(line.startswith(f"spectrocolor {command[0]}: ") for line in lines), err
        assert all(": warning: " in line or " declares " in line for line in lines), err


# --- strict XML and numbers, writers that keep files whole (issue 31) ----------------------------

TM27_BODY = ('<IESTM2714 version="1.0"><Header><Description>&e;</Description></Header>'
             '<SpectralDistribution><SpectralData wavelength="400">0.5</SpectralData>'
             '<SpectralData wavelength="410">1</SpectralData></SpectralDistribution></IESTM2714>')


@pytest.mark.parametrize("comment_bytes", [0, 70_000, 1_000_000])
@pytest.mark.parametrize("declaration", [
    '<!DOCTYPE IESTM2714 [<!ENTITY e "EXPANDED">]>',
    '<!DOCTYPE x [<!ENTITY e "EXPANDED">]>',
    '<!DOCTYPE IESTM2714 SYSTEM "file:///etc/passwd">',
])
def test_a_doctype_anywhere_is_refused_and_no_entity_expanded(comment_bytes, declaration):
    """The DOCTYPE check looked at the first 64 KiB only: after 70 kB of comment the entity was
    expanded. expat now reports any DOCTYPE or entity declaration wherever it is."""
    text = '<?xml version="1.0"?><!--' + "x" * comment_bytes + "-->" + declaration + TM27_BODY
    with pytest.raises(SpectrumError, match="DOCTYPE or ENTITY declaration is not accepted"):
        parse_spectra(text, "lamp.xml")
    with pytest.raises(SpectrumError, match="DOCTYPE"):
        sc.io.tm27.parse_tm27(text, "lamp.xml")


def test_a_long_comment_before_the_document_element_is_still_tm27():
    text = "<!--" + " " * 100_000 + "-->" + TM27_BODY.replace("&e;", "LED")
    assert parse_spectra(text, "lamp.xml").names == ("LED",)


def test_tm27_names_have_no_line_breaks():
    text = TM27_BODY.replace("&e;", "LED\n   lamp\r\n")
    assert parse_spectra(text, "lamp.xml").names == ("LED lamp",)


NOT_NUMBERS = ["0_5", "1_000", "٣", "５", "nan", "inf", "-Infinity", "0x10", "1e", ".", "+-1"]


@pytest.mark.parametrize("cell", NOT_NUMBERS)
@pytest.mark.parametrize("layout", ["csv-long", "csv-wide", "cgats", "tm27"])
def test_numbers_follow_the_formats_grammar(cell, layout):
    """``0_5`` was read as 5.0 (Python's digit separators) and '٣' as 3.0: now refused, naming it."""
    texts = {
        "csv-long": f"wavelength_nm,a\n400,{cell}\n500,0.5\n",
        "csv-wide": f"Sample,400,500,600\nx,0.1,{cell},0.3\n",
        "cgats": ("CGATS.17\nBEGIN_DATA_FORMAT\nSAMPLE_ID SPECTRAL_NM400 SPECTRAL_NM500\nEND_DATA_FORMAT\n"
                  f"BEGIN_DATA\n1 {cell} 0.5\nEND_DATA\n"),
        "tm27": ('<IESTM2714><SpectralDistribution><SpectralData wavelength="400">'
                 f"{cell}</SpectralData></SpectralDistribution></IESTM2714>"),
    }
    with pytest.raises(SpectrumError, match="not a (finite )?number") as info:
        parse_spectra(texts[layout], "tiles")
    assert cell.strip() in str(info.value) and "\n" not in str(info.value)


@pytest.mark.parametrize("cell", ["0.5", "5.", ".5", "+1", "-0", "1e-3", "2E+2", " 7 "])
def test_numbers_of_the_grammar_are_read(cell):
    spectrum = parse_spectra(f"wavelength_nm,a\n400,{cell}\n500,1\n", "tiles.csv")
    assert spectrum.values[0] == float(cell)  # exact: both parse the same decimal text, correctly rounded


def test_a_decimal_comma_file_keeps_its_grammar():
    # exact: decimal text parsed with correct rounding, as the literals are
    assert parse_spectra("Sample;400;500;600\nx;0,1;0,2;0,3\n", "x.csv").values.tolist() == [0.1, 0.2, 0.3]
    with pytest.raises(SpectrumError, match="'0_2' is not a number"):
        parse_spectra("Sample;400;500;600\nx;0,1;0_2;0,3\n", "x.csv")


@pytest.mark.parametrize("value", ['"0_5"', '"0.5"', "true", '"٣"'])
def test_json_values_must_be_json_numbers(value):
    with pytest.raises(SpectrumError, match="'spectra' must hold numbers"):
        parse_spectra('{"wavelengths_nm": [400, 500], "spectra": {"a": [1, ' + value + "]}}", "x.json")


@SETTINGS
@given(digits=st.lists(st.text("0123456789", min_size=1, max_size=4), min_size=2, max_size=4))
def test_digit_separators_are_never_read(digits):
    cell = "_".join(digits)
    with pytest.raises(SpectrumError, match="not a number"):
        parse_spectra(f"wavelength_nm,a\n400,{cell}\n500,1\n", "x.csv")


@pytest.mark.parametrize("norm", ["1e-320", "1e-310", "0", "-1", "nan", "inf"])
def test_a_declared_full_scale_must_keep_the_values_finite(norm):
    text = (f'CTI3\nSPECTRAL_NORM "{norm}"\nBEGIN_DATA_FORMAT\nSAMPLE_ID SPEC_400 SPEC_500\n'
            "END_DATA_FORMAT\nBEGIN_DATA\n1 10 20\nEND_DATA\n")
    with pytest.raises(SpectrumError, match="SPECTRAL_NORM"):
        parse_spectra(text, "x.ti3")


BREAKS = ["\n", "\r", "\r\n", "\x0b", "\x0c", "\x1c", "\x85", "\u2028", "\u2029", "\x00"]


@pytest.mark.parametrize("brk", BREAKS, ids=[repr(b) for b in BREAKS])
@pytest.mark.parametrize("suffix", [".cgats", ".csv"])
def test_a_name_with_a_line_break_is_refused_by_the_writers(tmp_path, brk, suffix):
    """A name holding a newline broke the CGATS file written: now refused, and nothing written."""
    spectrum = Spectrum([400, 500], [[0.1, 0.2], [0.3, 0.4]], ["good", f"bad{brk}name"])
    target = tmp_path / f"out{suffix}"
    with pytest.raises(SpectrumError, match=r"names\[1\].*line break"):
        sc.write_spectra(spectrum, target)
    assert not target.exists() and list(tmp_path.iterdir()) == []


def test_keywords_and_table_cells_with_line_breaks_are_refused():
    from spectrocolor.io.writers import spectra_to_cgats, table_to_cgats

    spectrum = Spectrum([400, 500], [0.1, 0.2], ["a"])
    with pytest.raises(SpectrumError, match="keywords"):
        spectra_to_cgats(spectrum, {"DESCRIPTOR": "two\nlines"})
    with pytest.raises(SpectrumError, match="not a CGATS keyword"):
        spectra_to_cgats(spectrum, {"BEGIN_DATA": "x"})
    with pytest.raises(SpectrumError, match="not a CGATS keyword"):
        spectra_to_cgats(spectrum, {"MY KEY": "x"})
    with pytest.raises(SpectrumError, match=r"rows\[0\]\['name'\]"):
        table_to_cgats([{"name": "a\rb", "X": 1.0}])


ONE_LINE_NAMES = st.text(
    st.characters(blacklist_categories=("Cc", "Cs", "Zl", "Zp"), blacklist_characters='"\u0085'),
    min_size=1, max_size=20).filter(lambda name: name.strip() == name and not name.startswith("#"))


@SETTINGS
@given(names=st.lists(ONE_LINE_NAMES, min_size=1, max_size=4, unique=True))
@pytest.mark.slow
def test_every_one_line_name_round_trips_through_every_text_writer(names):
    spectrum = Spectrum([400, 500, 600], np.linspace(0.1, 0.9, 3 * len(names)).reshape(len(names), 3), names)
    with tempfile.TemporaryDirectory() as folder:
        for suffix in (".cgats", ".csv", ".json"):
            back = sc.read_spectra(sc.write_spectra(spectrum, Path(folder) / f"s{suffix}"))
            assert back.names == spectrum.names, suffix
            # exact: the writers print the shortest text that reads back as the same double
            assert np.array_equal(back.values.reshape(spectrum.values.shape), spectrum.values)


@SETTINGS
@given(name=st.text(min_size=1, max_size=20))
def test_json_keeps_any_name_verbatim(name):
    spectrum = Spectrum([400, 500], [0.1, 0.2], [name])
    with tempfile.TemporaryDirectory() as folder:
        assert sc.read_spectra(sc.write_spectra(spectrum, Path(folder) / "s.json")).names == (name,)


# --- the decoder (issue 26 item 1): random bytes, marks and encodings --------------------------

BOMS = [b"", b"\xef\xbb\xbf", b"\xff\xfe", b"\xfe\xff", b"\xff\xfe\x00\x00", b"\x00\x00\xfe\xff"]


@SETTINGS
@given(mark=st.sampled_from(BOMS), data=st.binary(max_size=400),
       encoding=st.sampled_from([None, None, "utf-8", "cp1252", "latin-1", "utf-16", "utf-16-be", "mac-roman"]))
def test_random_bytes_with_any_mark_and_encoding(mark, data, encoding):
    result = _outcome(lambda: parse_spectra(mark + data, "fuzz", encoding=encoding))
    assert isinstance(result, (Spectrum, SpectrumError))
    if isinstance(result, Spectrum):
        assert result.metadata["encoding"] and result.metadata["encoding_note"]


@SETTINGS
@given(st.binary(max_size=400))
def test_the_decoder_never_guesses_against_the_rule(data):
    result = _outcome(lambda: decode_text(data, "fuzz"))
    if isinstance(result, SpectrumError):
        message = str(result)
        assert "encoding=" in message and re.search(r"byte \d+ \(0x[0-9A-F]{2}\)", message), message
        return
    if result.note.endswith("byte-order mark"):
        return
    try:
        utf8 = data.decode("utf-8")
    except UnicodeDecodeError:
        utf8 = None
    if utf8 is not None:  # valid UTF-8 is UTF-8
        assert result.encoding == "utf-8" and result.text == utf8
    else:  # cp1252 only when every byte is a printable cp1252 character
        assert result.encoding == "cp1252" and result.text == data.decode("cp1252")
        assert not set(data) & (set(range(0x20)) - set(b"\t\n\r") | {0x7F, 0x81, 0x8D, 0x8F, 0x90, 0x9D})


@SETTINGS
@given(names=st.lists(st.text(st.sampled_from("abcµ°–äé "), min_size=1, max_size=6).map(str.strip).filter(bool),
                      min_size=1, max_size=3, unique=True),
       encoding=st.sampled_from(["utf-8", "utf-8-sig", "cp1252", "utf-16"]),
       end=st.sampled_from(["", ",", ",,"]))
@example(names=["ä°°"], encoding="cp1252", end="")  # cp1252 bytes that are valid UTF-8 (found by hypothesis)
def test_a_table_reads_the_same_in_every_encoding_and_trailing_delimiter(names, encoding, end):
    lines = ["wavelength_nm," + ",".join(names) + end] + [f"{nm}," + ",".join("0.5" for _ in names) + end
                                                          for nm in (400, 500, 600)]
    text = "\r\n".join(lines) + "\r\n"
    data = text.encode(encoding)
    expected = tuple(names)
    if encoding == "cp1252":
        try:
            data.decode("utf-8")
        except UnicodeDecodeError:
            pass
        else:  # these cp1252 bytes are valid UTF-8 too ('ä°°' is E4 B0 B0, UTF-8 for '䰰'): the rule reads UTF-8
            expected = tuple(name.encode("cp1252").decode("utf-8") for name in names)
    spectra = parse_spectra(data, "fuzz")
    assert spectra.names == expected
    assert spectra.values.shape[-1] == 3
