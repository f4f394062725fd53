"""The command line's input and output: instrument files in, CGATS/CSV out, --version, a missing
extra, ``| head``, one illuminant default, --method astm-e308 (run as a user would)."""

import csv
import io
import subprocess
import sys
from importlib import resources
from pathlib import Path

import numpy as np
import pytest

import spectrocolor as sc
from spectrocolor.cli import main
from spectrocolor.io.cgats import _tables

COLORCHECKER = str(resources.files("spectrocolor").joinpath("data", "reflectances_colorchecker_babel.csv"))
CORPUS = Path(__file__).parents[1] / "data" / "io"


def run(*args):
    return subprocess.run([sys.executable, "-m", "spectrocolor", *args], capture_output=True, text=True, timeout=120)


def _cgats_rows(text):
    ((identifier, keywords, fields, rows),) = list(_tables(text, "output"))
    return keywords, fields, [dict(zip(fields, row, strict=True)) for _, row in rows]


def test_version():
    result = run("--version")
    assert result.returncode == 0 and result.stdout.strip() == f"spectrocolor {sc.__version__}"


@pytest.mark.parametrize(
    ("blocked", "command", "extra"),
    [("matplotlib", "diagram", "plot"), ("PIL", "render", "images")],
)
def test_missing_extra_is_one_line_naming_pip_install(monkeypatch, capsys, tmp_path, blocked, command, extra):
    monkeypatch.setitem(sys.modules, blocked, None)  # import of it raises ModuleNotFoundError
    assert main([command, COLORCHECKER, "--out", str(tmp_path / "out.png")]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and f"(extra '{extra}')" in err and "Traceback" not in err
    assert " -m pip install " in err and "pip install spectrocolor" not in err  # not on the index


def test_piping_into_head_exits_quietly(tmp_path):
    grid = np.arange(380, 731, 10)
    big = tmp_path / "big.csv"
    rows = ["name," + ",".join(map(str, grid))] + [f"s{i}," + ",".join(["0.5"] * grid.size) for i in range(4000)]
    big.write_text("\n".join(rows) + "\n")
    command = f"set -o pipefail; '{sys.executable}' -m spectrocolor xyz '{big}' --format csv | head -n 2"
    result = subprocess.run(["bash", "-c", command], capture_output=True, text=True, timeout=120)
    assert result.stdout.splitlines()[0].startswith("name,X,Y,Z,x,y,L*,a*,b*")
    assert result.stderr == "" and result.returncode == 141


@pytest.mark.parametrize("command", ["xyz", "describe", "report"])
def test_one_illuminant_default_stated_in_help(command):
    result = run(command, "--help")
    assert result.returncode == 0 and "default D65" in " ".join(result.stdout.split())


def test_xyz_cgats_output_equals_the_library_with_lab():
    result = run("xyz", COLORCHECKER, "--format", "cgats", "--method", "astm-e308", "--observer", "1964")
    assert result.returncode == 0, result.stderr
    keywords, fields, rows = _cgats_rows(result.stdout)
    assert fields == [
        "SAMPLE_ID",
        "SAMPLE_NAME",
        "XYZ_X",
        "XYZ_Y",
        "XYZ_Z",
        "XYY_X",
        "XYY_Y",
        "LAB_L",
        "LAB_A",
        "LAB_B",
    ]
    assert keywords["ILLUMINANT"] == "D65" and keywords["SUMMATION_METHOD"] == "astm-e308"
    spectra = sc.read_spectra(COLORCHECKER)
    XYZ = sc.tristimulus(spectra, observer="1964", illuminant="D65", method="astm-e308")
    white = sc.white_point("D65", observer="1964", wavelengths_nm=spectra.wavelengths_nm, method="astm-e308")
    got = np.array([[float(r[f]) for f in ("XYZ_X", "XYZ_Y", "XYZ_Z")] for r in rows])
    # exact: the command runs the same calls on the same file here, and prints repr (17 digits)
    np.testing.assert_array_equal(got, XYZ)
    lab = np.array([[float(r[f]) for f in ("LAB_L", "LAB_A", "LAB_B")] for r in rows])
    np.testing.assert_array_equal(lab, sc.lab(XYZ, white))  # exact: as XYZ, one more same call
    assert rows[0]["SAMPLE_NAME"] == "dark_skin"


def test_describe_csv_and_cgats_carry_xyz_xy_lab_dominant_wavelength_and_purity():
    result = run("describe", COLORCHECKER, "--format", "csv")
    header = next(csv.reader(io.StringIO(result.stdout)))
    for column in ("X", "Y", "Z", "x", "y", "L*", "a*", "b*", "wavelength_nm", "purity"):
        assert column in header
    result = run("describe", COLORCHECKER, "--format", "cgats")
    _, fields, rows = _cgats_rows(result.stdout)
    assert {"XYZ_X", "XYY_X", "LAB_L", "WAVELENGTH_NM", "KIND", "PURITY"} <= set(fields) and len(rows) == 24


def test_instrument_file_percent_declared_by_the_file_needs_no_option():
    declared = run("xyz", str(CORPUS / "argyll.ti3"), "--format", "csv")
    fraction = run("xyz", str(CORPUS / "long.csv"), "--format", "csv")
    assert declared.returncode == 0 and fraction.returncode == 0
    header, *percent_rows = list(csv.reader(io.StringIO(declared.stdout)))
    assert header == next(csv.reader(io.StringIO(fraction.stdout)))
    assert header[1:] == ["X", "Y", "Z", "x", "y", "L*", "a*", "b*"]
    got = np.array([[float(v) for v in r[1:]] for r in percent_rows])
    expected = np.array([[float(v) for v in r[1:]] for r in list(csv.reader(io.StringIO(fraction.stdout)))[1:]])
    assert got.shape == expected.shape == (3, 8)
    K = sc.read_spectra(CORPUS / "long.csv").wavelengths_nm.size
    # p/100 rounds once more than the parsed fraction (1 ulp per ρ) and the K-term sum of ρ·w ≥ 0
    # rounds in the kernel's order ((K + 1) ulps of the sum): |ΔXYZ| ≤ (K + 2)·eps·XYZ; x, y
    # divide two such sums (twice that); L*, a*, b* are 116, 500, 200 × differences of
    # f = ∛(X/Xn) ≤ 1 (reflectances), each off by a third of that relative error.
    rtol = 2 * (K + 2) * np.finfo(float).eps
    np.testing.assert_allclose(got[:, :5], expected[:, :5], rtol=rtol, atol=0)
    np.testing.assert_allclose(got[:, 5:], expected[:, 5:], rtol=0, atol=500 * rtol)
    assert np.abs(got[:, 1] - expected[:, 1]).max() < 1e-3 * expected[:, 1].min()  # not ×100 apart
    agreeing = run("xyz", str(CORPUS / "argyll.ti3"), "--format", "csv", "--percent")  # not divided twice
    # the same file, read the same way (the file's own declaration and --percent agree): the same
    # numbers through the same calls, printed alike
    assert agreeing.returncode == 0 and agreeing.stdout == declared.stdout
    undeclared = run("xyz", str(CORPUS / "semicolon_decimal_comma_percent.csv"))
    assert undeclared.returncode == 2 and "--percent" in undeclared.stderr


def test_report_writes_cgats(tmp_path):
    out = tmp_path / "r.cgats"
    result = run("report", str(CORPUS / "i1profiler.txt"), "--out", str(out), "--method", "astm-e308")
    assert result.returncode == 0, result.stderr
    keywords, fields, rows = _cgats_rows(out.read_text())
    # the file declares MEASUREMENT_SOURCE "Illumination=D50 ObserverAngle=2": used, no option given
    assert keywords["ILLUMINANT"] == "D50" and len(rows) == 3 and "LAB_L" in fields
    assert result.stderr == ""  # nothing differs from the declaration: no note
    XYZ = sc.tristimulus(sc.read_spectra(CORPUS / "i1profiler.txt"), observer="1931", illuminant="D50",
                         method="astm-e308")
    # exact: the report's own call on the same file, rounded by the same np.round(…, 4)
    np.testing.assert_array_equal([float(r["XYZ_Y"]) for r in rows], np.round(XYZ[:, 1], 4))


def test_report_labels_the_swatch_strategy_it_applied(tmp_path):
    saturated = tmp_path / "saturated.csv"
    grid = np.arange(380, 781, 10)
    saturated.write_text(
        "name,"
        + ",".join(map(str, grid))
        + "\nblue,"
        + ",".join("1" if 440 <= nm <= 470 else "0" for nm in grid)
        + "\n"
    )
    out = tmp_path / "r.html"
    assert run("report", str(saturated), "--out", str(out)).returncode == 0
    html = out.read_text()
    assert "desaturated" in html and "clipped" not in html


def test_tristimulus_of_a_table_starting_below_the_observer_says_how_to_restrict():
    with pytest.raises(sc.ColorimetryError, match=r"restrict\(360, 830\)"):
        sc.tristimulus(sc.illuminant("D65"))
    XYZ = sc.tristimulus(sc.illuminant("D65").restrict(360, 830))
    assert XYZ[0] / XYZ[1] == pytest.approx(0.9505, abs=5e-4)


def test_every_command_has_the_same_shared_defaults():
    """One voice: wherever a command takes --illuminant, --observer or --gamut, its default is the
    library's (D65, CIE 1931 2°, desaturate), so no command surprises with its own."""
    import argparse

    from spectrocolor.cli import build_parser
    from spectrocolor.cli.options import DECLARED
    from spectrocolor.display.gamut import DEFAULT_GAMUT

    shared = {"illuminant": "D65", "observer": "1931", "gamut": DEFAULT_GAMUT}
    parser = build_parser()
    commands = next(a for a in parser._actions if isinstance(a, argparse._SubParsersAction)).choices
    seen = {}
    for name, command in commands.items():
        for action in command._actions:
            if action.dest in shared:
                seen.setdefault(action.dest, []).append(name)
                if action.default == DECLARED:  # a measurement file's own conditions, else the library's
                    assert name in ("xyz", "describe", "report") and shared[action.dest] in action.help
                    continue
                assert action.default == shared[action.dest], (name, action.dest, action.default)
    assert {"image", "render", "relight"} <= set(seen["gamut"])
