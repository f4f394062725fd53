"""``spectrocolor recover`` end to end."""

import numpy as np
import pytest

import spectrocolor as sc
from spectrocolor import cli


def main(argv):
    """The CLI's own dispatch and parser, global options (``--memory-budget``) included."""
    return cli.main(argv)


def test_recover_xyz_round_trip(tmp_path):
    out = tmp_path / "refl.csv"
    assert main(["recover", "--xyz", "30", "25", "10", "--range", "400", "700", "10",
                 "--out", str(out)]) == 0
    s = sc.read_spectra(out)
    np.testing.assert_allclose(sc.tristimulus(s, observer="1931", illuminant="D65"), [30, 25, 10], atol=1e-8)
    assert s.values.min() >= 0 and s.values.max() <= 1


def test_recover_hex_and_csv_with_plot(tmp_path):
    out, png = tmp_path / "hex.csv", tmp_path / "hex.png"
    assert main(["recover", "--hex", "#ff0000", "808080", "--range", "400", "700", "10",
                 "--out", str(out), "--plot", str(png)]) == 0
    assert sc.read_spectra(out).values.shape == (2, 31) and png.stat().st_size > 1000
    table = tmp_path / "colours.csv"
    table.write_text("X,Y,Z\n20,20,20\n90,10,5\n")
    assert main(["recover", "--csv", str(table), "--out", str(tmp_path / "c.csv")]) == 1
    s = sc.read_spectra(tmp_path / "c.csv")
    assert s.names == ("colour_1",)  # the infeasible colour is reported and skipped


def test_recover_bad_hex_is_one_line(tmp_path, capsys):
    assert main(["recover", "--hex", "zz0000", "--out", str(tmp_path / "x.csv")]) == 2
    assert "RRGGBB" in capsys.readouterr().err


@pytest.mark.parametrize("args", [["--xyz", "1", "1", "1", "--bounds", "weird"]])
def test_recover_bad_bounds(args, tmp_path):
    with pytest.raises(SystemExit):
        main(["recover", *args, "--out", str(tmp_path / "x.csv")])


def test_cie_d65_white_outside_the_grid_white_is_one_helpful_line(tmp_path, capsys):
    """The tabulated D65 white is not the 5 nm grid's white: one line, naming this grid's white."""
    white = np.asarray(sc.weights(sc.wavelength_grid(380, 780, 5), observer="1931", illuminant="D65")).sum(axis=0)
    assert main(["recover", "--xyz", "95.047", "100", "108.883", "--illuminant", "D65",
                 "--out", str(tmp_path / "x.csv")]) == 2
    got = capsys.readouterr()
    assert got.out == ""
    lines = got.err.strip().splitlines()
    assert len(lines) == 1 and "perfect white is XYZ" in lines[0]
    assert f"{white[0]:.8g}" in lines[0] and not (tmp_path / "x.csv").exists()


def test_missing_csv_and_short_row_are_one_clear_line(tmp_path, capsys):
    assert main(["recover", "--csv", str(tmp_path / "nope.csv"),
                 "--out", str(tmp_path / "x.csv")]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "no such file" in err[0] and "Errno" not in err[0]
    table = tmp_path / "short.csv"
    table.write_text("X,Y,Z\n20,20,20\n# a comment\n10,10\n")
    assert main(["recover", "--csv", str(table), "--out", str(tmp_path / "x.csv")]) == 2
    err = capsys.readouterr().err
    assert "line 4" in err and "expected 3 values" in err


def test_help_shows_defaults(capsys):
    with pytest.raises(SystemExit):
        main(["recover", "--help"])
    text = " ".join(capsys.readouterr().out.split())
    for needle in ("(default D65)", "(default 1931)", "(default: 380 780 5)",
                   "(default: unit)", "scale of this grid"):
        assert needle in text
