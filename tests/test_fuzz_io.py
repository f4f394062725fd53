"""Fuzzing the file readers: generated malformed files get one clear SpectrumError, never a traceback.

Every reader is fed (a) text built from its own vocabulary (CGATS keywords, TM-27 elements, CSV
delimiters and wavelength headers), (b) valid corpus files with random cuts, insertions and
replacements, and (c) random bytes; ENVI headers get random field values and MATLAB files random
damage. A result is either a Spectrum/SpectralCube or a SpectrumError with a one-line message.
"""

import tempfile
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import spectrocolor as sc
from spectrocolor import Spectrum, SpectrumError
from spectrocolor.images import read_cube
from spectrocolor.io import parse_spectra

CORPUS = Path(__file__).parent / "data" / "io"
CORPUS_TEXTS = {p.name: p.read_text(encoding="utf-8") for p in sorted(CORPUS.iterdir()) if p.suffix != ".py"}
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
    assert (status == 0) == (err == "") and err.count("\n") <= 1
