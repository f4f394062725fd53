"""The `spectrocolor xyz` and `describe` commands, run as a user would (a real subprocess)."""

import csv
import io
import json
import subprocess
import sys
from importlib import resources

import numpy as np
import pytest

import spectrocolor as sc

COLORCHECKER = str(resources.files("spectrocolor").joinpath("data", "reflectances_colorchecker_babel.csv"))


def run(*args):
    return subprocess.run([sys.executable, "-m", "spectrocolor", *args], capture_output=True, text=True, timeout=120)


def test_xyz_csv_equals_library():
    result = run("xyz", COLORCHECKER, "--illuminant", "D65", "--format", "csv")
    assert result.returncode == 0, result.stderr
    rows = list(csv.DictReader(io.StringIO(result.stdout)))
    expected = sc.tristimulus(sc.read_spectra(COLORCHECKER), observer="1931", illuminant="D65")
    got = np.array([[float(r["X"]), float(r["Y"]), float(r["Z"])] for r in rows])
    np.testing.assert_allclose(got, expected, rtol=1e-12)
    assert rows[0]["name"] == "dark_skin"


def test_xyz_interval_subsamples_like_the_seed(tmp_path):
    g = sc.wavelength_grid(380, 780, 10)
    path = sc.write_spectra(sc.Spectrum(g, np.linspace(0.2, 0.8, g.size), ["ramp"]), tmp_path / "r.csv")
    result = run("xyz", str(path), "--interval", "20", "--format", "json")
    assert result.returncode == 0, result.stderr
    got = json.loads(result.stdout)[0]
    spectrum = sc.Spectrum(g[::2], np.linspace(0.2, 0.8, g.size)[::2])
    expected = sc.tristimulus(spectrum, observer="1931", illuminant="D65")
    np.testing.assert_allclose([got["X"], got["Y"], got["Z"]], expected, rtol=1e-12)


def test_describe_matches_library_and_the_known_colorchecker_swatch():
    result = run("describe", COLORCHECKER, "--illuminant", "D65", "--format", "json")
    assert result.returncode == 0, result.stderr
    rows = json.loads(result.stdout)
    spectra = sc.read_spectra(COLORCHECKER)
    XYZ = sc.tristimulus(spectra, observer="1931", illuminant="D65")
    white = sc.weights(spectra.wavelengths_nm, observer="1931", illuminant="D65").sum(0)
    dominant = sc.dominant_wavelength(sc.xy(XYZ), sc.xy(white))
    np.testing.assert_allclose([r["wavelength_nm"] for r in rows], dominant.wavelength_nm, rtol=1e-12)
    np.testing.assert_allclose([r["purity"] for r in rows], dominant.excitation_purity, rtol=1e-12)
    assert rows[16]["kind"] == "complementary"  # magenta
    # The BabelColor 'dark skin' patch is #735244 in the published sRGB (D65) values.
    assert rows[0]["srgb"] == "#735244"


def test_describe_table_is_readable():
    result = run("describe", COLORCHECKER)
    assert result.returncode == 0, result.stderr
    header = result.stdout.splitlines()[0].split()
    assert header[:6] == ["name", "X", "Y", "Z", "x", "y"] and "purity" in header


@pytest.mark.parametrize(
    ("content", "message"),
    [
        ("400,0.1\n500,0.2\n", "missing header"),
        ("wavelength_nm,a\n400,0.1\n500,x\n", "'x' is not a number"),
        ("wavelength_nm,a\n400,0.1\n500,0.2\n450,0.3\n", "increasing"),
        ("wavelength_nm,a\n400,0.1\n500,-0.2\n", "negative reflectance"),
        ("wavelength_nm,a\n400,10\n500,20\n", "--percent"),
        ("wavelength_nm,a\n0.4,0.1\n0.5,0.2\n", "micrometres"),
        ("wavelength_nm,a\n300,0.1\n500,0.2\n", "outside"),
    ],
)
def test_malformed_files_give_one_line_not_a_traceback(tmp_path, content, message):
    path = tmp_path / "bad.csv"
    path.write_text(content)
    result = run("describe", str(path))
    assert result.returncode == 2
    assert message in result.stderr and "Traceback" not in result.stderr


def test_missing_file():
    result = run("xyz", "/no/such/file.csv")
    assert result.returncode == 2 and "no such file" in result.stderr


@pytest.mark.parametrize("interval", ["0", "-10", "nan"])
def test_interval_must_be_positive(interval, capsys):
    from spectrocolor.cli import main

    assert main(["xyz", COLORCHECKER, f"--interval={interval}"]) == 2
    assert "--interval: must be a positive number" in capsys.readouterr().err


def test_range_errors_name_the_command_line_option(tmp_path, capsys):
    from spectrocolor.cli import main

    # the 2015 observers start at 390 nm; the ColorChecker data at 380 nm
    assert main(["describe", COLORCHECKER, "--observer", "2015-10", "--illuminant", "D65"]) == 2
    assert "--range START STOP" in capsys.readouterr().err
    assert (
        main(["describe", COLORCHECKER, "--observer", "2015-10", "--illuminant", "D65", "--range", "390", "730"]) == 0
    )


def test_binary_file_is_one_line(tmp_path, capsys):
    from spectrocolor.cli import main

    path = tmp_path / "photo.csv"
    path.write_bytes(bytes(range(256)))
    assert main(["xyz", str(path)]) == 2
    err = capsys.readouterr().err
    assert "not text" in err and "encoding" in err and err.count("\n") == 1, err


@pytest.mark.slow
def test_lights_are_said_one_way_and_describe_refuses_them(tmp_path):
    """--illuminant none is the one way to say the spectra are lights (as None in the library)."""
    lights = run("xyz", COLORCHECKER, "--illuminant", "none", "--format", "csv")
    assert lights.returncode == 0, lights.stderr
    assert run("xyz", COLORCHECKER, "--light").returncode == 2  # no second spelling
    refused = run("describe", COLORCHECKER, "--illuminant", "none")
    assert refused.returncode == 2 and "argument --illuminant" in refused.stderr
    assert "'none' is for lights" in refused.stderr
    unknown = run("xyz", COLORCHECKER, "--illuminant", "D66")
    assert unknown.returncode == 2 and "'D66' is not a CIE illuminant name" in unknown.stderr
    assert run("xyz", COLORCHECKER, "--illuminant", "blackbody:3000").returncode == 0


def test_report_refuses_a_format_that_contradicts_the_file_name(tmp_path):
    result = run("report", COLORCHECKER, "--illuminant", "C", "--format", "csv", "--out", str(tmp_path / "r.html"))
    assert result.returncode == 2 and "make them agree" in result.stderr
    assert not (tmp_path / "r.html").exists()


def test_report_and_describe_agree_on_what_looks_like_percent(tmp_path):
    path = tmp_path / "p.csv"
    path.write_text("wavelength_nm,a\n400,1.8\n500,1.9\n")  # 1.8 is no reflectance factor
    for command in (
        ("describe", str(path)),
        ("report", str(path), "--illuminant", "C", "--out", str(tmp_path / "r.csv")),
    ):
        result = run(*command)
        assert result.returncode == 2 and "--percent" in result.stderr, command
