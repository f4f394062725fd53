"""Reading and writing spectral files: round trips and clear errors."""

import json

import numpy as np
import pytest

import spectrocolor as sc
from spectrocolor import Spectrum, SpectrumError


def test_csv_round_trip(tmp_path):
    g = sc.wavelength_grid(380, 780, 10)
    s = Spectrum(g, np.random.default_rng(0).random((3, g.size)), names=["red tile", "b", "c"])
    path = sc.write_spectra(s, tmp_path / "s.csv")
    back = sc.read_spectra(path)
    assert back.names == s.names
    # exact: a copy of the same numbers (written and read back, no arithmetic) (repr keeps 17 digits)
    np.testing.assert_array_equal(back.values, s.values)
    # exact: a copy of the same numbers (written and read back, no arithmetic)
    np.testing.assert_array_equal(back.wavelengths_nm, g)


def test_json_round_trip(tmp_path):
    s = Spectrum([400, 500, 600], [0.1, 0.2, 0.3], names=["one"])
    back = sc.read_spectra(sc.write_spectra(s, tmp_path / "s.json"))
    assert back.names == ("one",) and back.values.shape == (3,)
    # exact: a copy of the same numbers (written and read back, no arithmetic)
    np.testing.assert_array_equal(back.values, s.values)


def test_shipped_colorchecker_reads():
    from importlib import resources

    path = resources.files("spectrocolor").joinpath("data", "reflectances_colorchecker_babel.csv")
    s = sc.read_spectra(str(path))
    assert s.values.shape == (24, 36) and s.names[0] == "dark_skin"


def test_micrometre_header_is_converted(tmp_path):
    path = tmp_path / "um.csv"
    path.write_text("wavelength_um,a\n0.40,0.1\n0.50,0.2\n")
    np.testing.assert_allclose(sc.read_spectra(path).wavelengths_nm, [400, 500])


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ("400,0.1\n500,0.2\n", "missing header"),
        ("wavelength_nm,a\n400,0.1\n500,abc\n", "line 3, column 'a': 'abc' is not a number"),
        ("wavelength_nm,a\n500,0.1\n400,0.2\n600,0.3\n", "decreasing"),  # neither order (descending is read)
        ("wavelength_nm,a\n400,0.1\n400,0.2\n", "duplicate"),
        ("wavelength_nm,a\n0.4,0.1\n0.5,0.2\n", "micrometres"),
        ("wavelength_nm,a\n400,0.1,3\n", "3 cells"),
        ("colour,a\n400,0.1\n", "not recognisably a wavelength"),
        ("# only a comment\n", "no data"),
    ],
)
def test_malformed_files_get_clear_errors(tmp_path, text, message):
    path = tmp_path / "bad.csv"
    path.write_text(text)
    with pytest.raises(SpectrumError, match=message):
        sc.read_spectra(path)


def test_bad_json(tmp_path):
    path = tmp_path / "bad.json"
    path.write_text(json.dumps({"spectra": {"a": [1, 2]}}))
    with pytest.raises(SpectrumError, match="wavelengths_nm"):
        sc.read_spectra(path)


@pytest.mark.parametrize(
    ("content", "message"),
    [
        ('{"wavelengths_nm": [400, 500], "values": [NaN, 1]}', "NaN or infinite"),
        ('{"wavelengths_nm": [400, 500], "values": [1e400, 1]}', "NaN or infinite"),
        ('{"wavelengths_nm": [400, 500], "values": [[1, 2], [3]]}', "'values' must hold numbers"),
        ('{"wavelengths_nm": [400, 500], "values": {"a": 1}}', "'values' must hold numbers"),
        ('{"wavelengths_nm": [400, 500], "spectra": {"a": [1, "x"]}}', "'spectra' must hold numbers"),
        ('{"wavelengths_nm": [400, 500], "values": [1, 2], "names": 5}', "names: expected a sequence"),
    ],
)
def test_malformed_json_values_get_clear_errors(tmp_path, content, message):
    path = tmp_path / "bad.json"
    path.write_text(content)
    with pytest.raises(SpectrumError, match=message):
        sc.read_spectra(path)


def test_folder_binary_file_and_wrong_types_are_spectrum_errors(tmp_path):
    with pytest.raises(SpectrumError, match="is a folder"):
        sc.read_spectra(tmp_path)
    latin1 = tmp_path / "latin1.csv"  # not UTF-8, every byte a cp1252 character: read as cp1252
    latin1.write_bytes("wavelength_µm,a\n0.4,0.1\n0.5,0.2\n".encode("latin-1"))
    assert sc.read_spectra(latin1).metadata["encoding"] == "cp1252"
    binary = tmp_path / "binary.csv"
    binary.write_bytes(b"wavelength_nm,a\n\xb5\x00\x01")
    with pytest.raises(SpectrumError, match=r"byte 17 \(0x00\) is a NUL byte"):
        sc.read_spectra(binary)
    with pytest.raises(SpectrumError, match="path: expected a file name"):
        sc.read_spectra(None)
    with pytest.raises(SpectrumError, match="spectrum: expected a Spectrum"):
        sc.write_spectra(np.ones(3), tmp_path / "x.csv")
