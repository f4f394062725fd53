"""The command line honours what a measurement file says: declared conditions, percent, XYZ scale.

Files of ``tests/data/io/make_declared.py``/``make_dialects.py``. The reference XYZ are the
library's with the declared conditions named explicitly (the same computation, so equality is
exact), and colour-science's in ``tests/io/test_io_declared.py``.
"""

from __future__ import annotations

import csv
import io
from pathlib import Path

import numpy as np
import pytest

import spectrocolor as sc
from spectrocolor import cli

CORPUS = Path(__file__).parents[1] / "data" / "io"
D65_10 = str(CORPUS / "colorport_d65_10_cp1252.cgats")
D50_2 = str(CORPUS / "eci_weighting_d50_2.cgats")


def _rows(text: str) -> list[dict]:
    return list(csv.DictReader(io.StringIO(text)))


def test_xyz_uses_the_declared_d65_10_without_a_word(capsys):
    assert cli.main(["xyz", D65_10, "--format", "csv"]) == 0
    out, err = capsys.readouterr()
    assert err == ""  # nothing named, nothing differs: no note
    assert cli.main(["xyz", D65_10, "--format", "csv", "--illuminant", "D65", "--observer", "1964"]) == 0
    named, err = capsys.readouterr()
    assert err == ""  # named the same as declared: no note
    assert out == named  # exact: the same computation, printed the same way
    XYZ = sc.tristimulus(sc.read_spectra(D65_10), illuminant="D65", observer="1964")
    # the CSV prints repr(float): the round trip is exact
    assert [float(r["Y"]) for r in _rows(out)] == XYZ[:, 1].tolist()


def test_the_declaration_survives_range_and_interval(capsys):
    assert cli.main(["xyz", D65_10, "--format", "cgats", "--interval", "20", "--range", "400", "700"]) == 0
    out = capsys.readouterr().out
    assert 'ILLUMINANT "D65"' in out and 'OBSERVER "CIE 1964 10°"' in out


def test_a_differing_choice_is_one_line_on_stderr(capsys):
    assert cli.main(["describe", D50_2, "--format", "json", "--illuminant", "D65", "--observer", "10deg"]) == 0
    err = capsys.readouterr().err.strip().splitlines()
    assert err == [f"spectrocolor describe: {D50_2}: the file declares D50/2°; computed under D65/10° as asked"]


def test_cgats_output_states_the_conditions_used(capsys):
    assert cli.main(["xyz", D50_2, "--format", "cgats"]) == 0
    out = capsys.readouterr().out
    assert 'ILLUMINANT "D50"' in out and 'OBSERVER "CIE 1931 2°"' in out


def test_report_says_it_on_stderr_and_in_the_page(tmp_path, capsys):
    page = tmp_path / "r.html"
    assert cli.main(["report", D65_10, "--out", str(page), "--observer", "1931"]) == 0
    note = "the file declares D65/10°; computed under D65/2° as asked"
    assert note in capsys.readouterr().err and note in page.read_text(encoding="utf-8")


def test_percent_on_fractions_warns_on_stderr(capsys):
    assert cli.main(["xyz", str(CORPUS / "wide.csv"), "--percent", "--format", "csv"]) == 0
    err = capsys.readouterr().err
    assert "warning:" in err and "--percent was given, but no value exceeds 1" in err
    assert "leave out --percent" in err


def test_undeclared_percent_is_still_refused(capsys):
    assert cli.main(["xyz", str(CORPUS / "semicolon_decimal_comma_percent.csv")]) == 2
    assert "pass --percent" in capsys.readouterr().err


def test_recover_asks_about_a_0_1_colour(tmp_path, capsys):
    out = tmp_path / "r.csv"
    assert cli.main(["recover", "--xyz", "0.41", "0.21", "0.02", "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert "every value is at most 1" in err and "--xyz-scale 1" in err and not out.exists()
    assert cli.main(["recover", "--xyz", "0.41", "0.21", "0.02", "--xyz-scale", "1", "--out", str(out)]) == 0
    hundred = tmp_path / "h.csv"
    assert cli.main(["recover", "--xyz", "41", "21", "2", "--out", str(hundred)]) == 0
    # 0.41 * 100 is 41.00000000000001 in floats: the recoveries agree to the solver's tolerance
    np.testing.assert_allclose(sc.read_spectra(out).values, sc.read_spectra(hundred).values, atol=1e-7)
    dark = tmp_path / "d.csv"
    assert cli.main(["recover", "--xyz", "0.41", "0.21", "0.02", "--xyz-scale", "100", "--out", str(dark)]) == 0
    assert sc.read_spectra(dark).values.max() < 0.05  # as asked: a very dark colour


def test_recover_xyz_scale_is_not_for_hex(tmp_path, capsys):
    assert cli.main(["recover", "--hex", "808080", "--xyz-scale", "1", "--out", str(tmp_path / "x.csv")]) == 2
    assert "--xyz-scale applies to --xyz and --csv" in capsys.readouterr().err
    with pytest.raises(SystemExit) as exited:
        cli.main(["recover", "--xyz", "1", "1", "1", "--xyz-scale", "7", "--out", str(tmp_path / "x.csv")])
    assert exited.value.code == 2
    assert "--xyz-scale: expected 1 (white Y = 1) or 100" in capsys.readouterr().err
