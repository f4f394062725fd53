"""``spectrocolor render`` and ``spectrocolor diagram`` end to end."""

from __future__ import annotations

import numpy as np
import pytest

import spectrocolor as sc
import spectrocolor.cli as cli

CSV = """wavelength_nm,grey,green
400,0.5,0.05
450,0.5,0.05
500,0.5,0.9
550,0.5,0.9
600,0.5,0.05
650,0.5,0.05
700,0.5,0.05
"""


def main(argv):
    return cli.main(argv)


@pytest.fixture(autouse=True)
def only_this_module(monkeypatch):
    """Test the render module on its own, whatever else the CLI registers."""
    assert "render" in cli.COMMAND_MODULES
    monkeypatch.setattr(cli, "COMMAND_MODULES", ("render",))


@pytest.fixture
def spectra_file(tmp_path):
    path = tmp_path / "s.csv"
    path.write_text(CSV)
    return path


def test_render_writes_swatches_with_the_library_codes(spectra_file, tmp_path, capsys):
    Image = pytest.importorskip("PIL.Image")
    out = tmp_path / "sw.png"
    code = main(["render", str(spectra_file), "--illuminant", "D65", "--space", "sRGB",
                 "--gamut", "desaturate", "--out", str(out), "--size", "8"])
    assert code == 0
    text = capsys.readouterr().out
    assert "gamut desaturate" in text and "bradford" in text
    # independent: grey 0.5 under D65 adapted to the display white is linear 0.5 -> 188
    img = np.asarray(Image.open(out).convert("RGB"))
    v = round(255 * (1.055 * 0.5 ** (1 / 2.4) - 0.055))
    assert img[4 + 3, 4 + 3].tolist() == [v, v, v]
    assert "grey" in text and f"{v} {v} {v}\tin gamut" in text
    # green: compare with the library chain written out here
    s = sc.read_spectra(spectra_file)
    XYZ = sc.tristimulus(s, observer="1931", illuminant="D65")
    W = sc.weights(s.wavelengths_nm, observer="1931", illuminant="D65")
    space = sc.rgb_space("sRGB")
    XYZ = sc.adapt(XYZ, W.sum(0), space.white_XYZ, "bradford")
    r = sc.render(XYZ, space, gamut="desaturate")
    assert img[4 + 2, 4 + 8 + 4 + 4].tolist() == r.codes[1].tolist()  # off the cross


def test_render_flag_reports_cannot_be_reproduced(spectra_file, tmp_path, capsys):
    out = tmp_path / "sw.ppm"
    assert main(["render", str(spectra_file), "--gamut", "flag", "--out", str(out)]) == 0
    text = capsys.readouterr().out
    assert "cannot be reproduced (R negative): shown black" in text  # the library's explain()
    assert out.read_bytes().startswith(b"P6\n")


def test_render_fixed_object_max(spectra_file, tmp_path, capsys):
    out = tmp_path / "sw.png"
    assert main(["render", str(spectra_file), "--normalise", "fixed", "--scale", "object-max",
                 "--gamut", "clip", "--out", str(out)]) == 0
    assert "normalise fixed" in capsys.readouterr().out


def test_user_errors_are_one_line(spectra_file, tmp_path, capsys):
    assert main(["render", str(spectra_file), "--out", str(tmp_path / "a.jpg")]) == 2
    assert "error: --out must end in .png or .ppm" in capsys.readouterr().err
    assert main(["render", str(spectra_file), "--space", "XYZ", "--out",
                 str(tmp_path / "a.png")]) == 2
    assert "space: 'XYZ' is not a built-in RGB space; choose one of 'sRGB'" in capsys.readouterr().err
    assert main(["render", str(spectra_file), "--normalise", "fixed", "--out",
                 str(tmp_path / "a.png")]) == 2
    assert "needs --scale" in capsys.readouterr().err


def test_diagram(spectra_file, tmp_path, capsys):
    pytest.importorskip("matplotlib")
    out = tmp_path / "d.png"
    assert main(["diagram", str(spectra_file), "--out", str(out), "--kind", "uv"]) == 0
    assert out.stat().st_size > 10_000
    assert "2 points" in capsys.readouterr().out


def test_swatch_size_and_reflectance_range_are_checked(spectra_file, tmp_path, capsys):
    out = tmp_path / "a.png"
    assert main(["render", str(spectra_file), "--size", "100000", "--out", str(out)]) == 2
    assert "--size must be 1-1024" in capsys.readouterr().err
    percent = tmp_path / "pct.csv"
    percent.write_text(CSV.replace("0.5,", "50,").replace("0.9", "90").replace("0.05", "5"))
    assert main(["render", str(percent), "--out", str(out)]) == 2
    assert "percentages" in capsys.readouterr().err
    negative = tmp_path / "neg.csv"
    negative.write_text(CSV.replace("0.5,", "-0.5,"))
    assert main(["render", str(negative), "--out", str(out)]) == 2
    assert "negative reflectance -0.5" in capsys.readouterr().err
    assert not out.exists()
    # lights may be any size and are normalised to the display
    assert main(["render", str(percent), "--illuminant", "none", "--out", str(out)]) == 0
