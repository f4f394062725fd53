"""Light reports (summary, HTML/CSV/JSON), the vector graphic and the ``spectrocolor light`` command."""

from __future__ import annotations

import csv
import json

import numpy as np
import pytest

from spectrocolor import Spectrum, illuminant, wavelength_grid, write_spectra
from spectrocolor.cli import main
from spectrocolor.errors import ColorimetryError
from spectrocolor.lighting import (
    alpha_opic,
    colour_fidelity,
    colour_rendering_index,
    light_report,
    luminous_efficacy_of_radiation,
    summary,
)
from spectrocolor.lighting.report import write_light_report
from spectrocolor.lighting.vector_graphic import normalised_graphic, write_vector_graphic


@pytest.fixture
def lamps() -> Spectrum:
    names = ("FL2", "FL11", "LED-B3")
    values = np.stack([illuminant(name).values for name in names])
    return Spectrum(illuminant("FL2").wavelengths_nm, values, names)


def test_summary_collects_the_metrics_of_one_light_as_plain_values():
    fl2 = illuminant("FL2")
    values = summary(fl2)
    assert all(type(v) is float for k, v in values.items() if k != "cri_meaningful")
    assert values["Ra"] == pytest.approx(float(colour_rendering_index(fl2).Ra), abs=1e-12)
    assert values["R9"] == pytest.approx(float(colour_rendering_index(fl2).R9), abs=1e-12)
    fidelity = colour_fidelity(fl2)
    assert (values["Rf"], values["Rg"], values["cct_K"]) == pytest.approx(
        (float(fidelity.Rf), float(fidelity.Rg), float(fidelity.cct_K)), abs=1e-12)
    assert values["LER_lm_per_W"] == pytest.approx(float(luminous_efficacy_of_radiation(fl2)), abs=1e-12)
    assert values["melanopic_DER"] == pytest.approx(float(alpha_opic(fl2).melanopic_der), abs=1e-12)
    assert values["cri_meaningful"] is True
    with pytest.raises(ColorimetryError, match="one light"):
        summary(Spectrum(fl2.wavelengths_nm, np.stack([fl2.values, fl2.values])))


def test_report_formats_hold_the_same_numbers(lamps, tmp_path):
    report = light_report(lamps)
    write_light_report(report, tmp_path / "r.json")
    write_light_report(report, tmp_path / "r.csv")
    write_light_report(report, tmp_path / "r.html", title="Three lamps")
    lights = json.loads((tmp_path / "r.json").read_text())["lights"]
    rows = list(csv.DictReader((tmp_path / "r.csv").open()))
    assert [light["name"] for light in lights] == [row["name"] for row in rows] == list(lamps.names)
    for i, (light, row) in enumerate(zip(lights, rows, strict=True)):
        assert light["Rf"] == pytest.approx(float(report.fidelity.Rf[i]), abs=0.005)
        assert float(row["Ra"]) == light["Ra"]
        assert len(light["Rf_hj"]) == 16 and len(light["R1_R14"]) == 14
        assert float(row["R9"]) == light["R1_R14"][8]
    page = (tmp_path / "r.html").read_text()
    assert page.count("<svg") == 3 and "Three lamps" in page and "LED-B3" in page


def test_report_csv_neutralises_formula_names_and_json_has_null_for_undefined(tmp_path):
    grid = wavelength_grid(380, 780, 5)
    spectra = Spectrum(grid, np.stack([illuminant("D65", grid).values, np.zeros(grid.size)]), ("=cmd", "dark"))
    report = light_report(spectra)
    write_light_report(report, tmp_path / "r.csv")
    write_light_report(report, tmp_path / "r.json")
    assert (tmp_path / "r.csv").read_text().splitlines()[1].startswith("'=cmd")
    dark = json.loads((tmp_path / "r.json").read_text())["lights"][1]
    assert dark["Rf"] is None and dark["cct_K"] is None
    with pytest.raises(ColorimetryError, match="format"):
        write_light_report(report, tmp_path / "r.txt")


def test_vector_graphic_places_the_reference_on_the_unit_circle_and_the_shift_relative_to_it(tmp_path):
    fidelity = colour_fidelity(illuminant("FL2"))
    reference, test = normalised_graphic(fidelity)
    np.testing.assert_allclose(np.hypot(*reference.T), 1.0, rtol=1e-12)
    shift = (fidelity.test_ab - fidelity.reference_ab) / np.linalg.norm(fidelity.reference_ab, axis=-1)[:, None]
    np.testing.assert_allclose(test - reference, shift, rtol=1e-12)
    # the radial component of the normalised shift is the chroma shift Rcs,hj up to the angle
    # between the bin's middle and the reference mean (< 11.25°)
    radial = np.sum((test - reference) * reference, axis=-1)
    clear = np.abs(fidelity.Rcs_h) > 0.03
    assert clear.sum() >= 8
    assert np.all(np.sign(radial[clear]) == np.sign(fidelity.Rcs_h[clear]))
    pytest.importorskip("matplotlib")
    for suffix in ("png", "svg"):
        path = write_vector_graphic(fidelity, tmp_path / f"cvg.{suffix}", title="FL2")
        assert path.stat().st_size > 1000
    with pytest.raises(ColorimetryError, match="index"):
        normalised_graphic(colour_fidelity(Spectrum(illuminant("FL2").wavelengths_nm,
                                                    np.stack([illuminant("FL2").values] * 2))))


# ---------------------------------------------------------------------------- command line
def test_light_command_writes_the_report_and_prints_the_table(lamps, tmp_path, capsys):
    source = write_spectra(lamps, tmp_path / "lamps.csv")
    out = tmp_path / "report.json"
    assert main(["light", str(source), "--out", str(out), "--graphic", str(tmp_path / "cvg.svg")]) == 0
    printed = capsys.readouterr().out
    assert "FL11" in printed and "wrote" in printed
    lights = json.loads(out.read_text())["lights"]
    assert lights[0]["Ra"] == pytest.approx(float(colour_rendering_index(illuminant("FL2")).Ra), abs=0.005)
    assert (tmp_path / "cvg.svg").exists()


def test_light_command_resamples_on_request_and_refuses_otherwise(tmp_path, capsys):
    grid = wavelength_grid(380, 780, 10)
    source = write_spectra(Spectrum(grid, illuminant("D65", grid).values, ("D65 at 10 nm",)), tmp_path / "d65.csv")
    assert main(["light", str(source), "--out", str(tmp_path / "a.csv")]) == 2
    assert "1 nm or 5 nm" in capsys.readouterr().err
    assert main(["light", str(source), "--out", str(tmp_path / "a.csv"), "--resample", "sprague"]) == 0
    row = next(csv.DictReader((tmp_path / "a.csv").open()))
    assert float(row["Rf"]) > 99.0


@pytest.mark.parametrize(
    "arguments, message",
    [
        (["--out", "x.txt"], "give a .html, .csv or .json"),
        (["--out", "x.csv", "--format", "json"], "make them agree"),
        (["--out", "x.csv", "--graphic", "g.jpg"], "--graphic"),
    ],
)
def test_light_command_bad_options_get_one_line(lamps, tmp_path, capsys, arguments, message, monkeypatch):
    monkeypatch.chdir(tmp_path)
    source = write_spectra(lamps, tmp_path / "lamps.csv")
    assert main(["light", str(source), *arguments]) == 2
    err = capsys.readouterr().err
    assert message in err and err.count("\n") == 1
