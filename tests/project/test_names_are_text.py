"""Names are text (issue 25): a name from a file is never parsed as maths by any renderer.

Matplotlib reads a string with two ``$`` as mathtext: a light named ``$\\frac{1$`` stopped
``spectrocolor light`` with the maths parser's traceback, and ``$5 and $6`` would be drawn in
italics. Every figure the library draws (plots, the report's pictures, the vector graphic) runs
with ``text.parse_math`` off (:func:`spectrocolor.plot.plain_text`); HTML escapes the names.
"""

from __future__ import annotations

import numpy as np
import pytest

import spectrocolor as sc
from spectrocolor.cli import main

NAMES = ["$\\frac{1$", "a $\\undefinedmacro$ b", "$5 and $6", "<b>x</b>"]
WL = np.arange(380.0, 781.0, 5.0)


def _csv(path, values):
    rows = ["wavelength_nm," + ",".join(NAMES)]
    rows += [f"{w:g}," + ",".join(f"{v:.6g}" for v in column) for w, column in zip(WL, values.T, strict=True)]
    path.write_text("\n".join(rows) + "\n", encoding="utf-8")
    return path


@pytest.fixture
def lights(tmp_path):
    lamp = sc.illuminant("FL2")
    values = np.interp(WL, lamp.wavelengths_nm, lamp.values)
    return _csv(tmp_path / "lights.csv", np.tile(values, (len(NAMES), 1)))


@pytest.fixture
def samples(tmp_path):
    return _csv(tmp_path / "samples.csv", np.linspace(0.2, 0.8, len(NAMES))[:, None] * np.ones(WL.size))


@pytest.mark.parametrize("graphic", ["g.svg", "g.png"])
@pytest.mark.slow
def test_light_report_and_vector_graphic_draw_names_as_text(lights, tmp_path, capsys, graphic):
    assert main(["light", str(lights), "--out", str(tmp_path / "r.html"), "--graphic",
                 str(tmp_path / graphic)]) == 0, capsys.readouterr().err
    page = (tmp_path / "r.html").read_text(encoding="utf-8")
    assert "$\\frac{1$" in page and "&lt;b&gt;x&lt;/b&gt;" in page
    if graphic.endswith(".svg"):
        assert "$\\frac{1$" in (tmp_path / graphic).read_text(encoding="utf-8")


@pytest.mark.parametrize("argv", [["report", "--out", "r.html"], ["diagram", "--out", "d.png"],
                                  ["diagram", "--out", "d.svg"]])
@pytest.mark.slow
def test_reports_and_diagrams_draw_names_as_text(samples, tmp_path, capsys, argv):
    command, *rest = argv
    rest[-1] = str(tmp_path / rest[-1])
    assert main([command, str(samples), *rest]) == 0, capsys.readouterr().err


@pytest.mark.slow
def test_plots_keep_names_verbatim():
    import io

    XYZ = np.array([[20.0, 21.0, 22.0], [40.0, 30.0, 10.0], [10.0, 20.0, 30.0], [30.0, 30.0, 30.0]])
    ax = sc.chromaticity_diagram(points=XYZ, labels=NAMES, title=NAMES[0])
    ax.figure.savefig(io.BytesIO(), format="svg")
    drawn = [t for t in ax.figure.findobj(lambda o: hasattr(o, "get_parse_math")) if t.get_text() in NAMES]
    assert drawn and not any(t.get_parse_math() for t in drawn)
    spectra = sc.Spectrum(WL, np.linspace(0.2, 0.8, len(NAMES))[:, None] * np.ones(WL.size), names=NAMES)
    ax = sc.spectrum_plot(spectra, index=0, title=NAMES[1])
    ax.figure.savefig(io.BytesIO(), format="png")
    assert ax.get_title() == NAMES[1] and not ax.title.get_parse_math()
