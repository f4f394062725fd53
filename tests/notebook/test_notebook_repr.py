"""Every record shows itself in a notebook: the right numbers, the right colours, names as text, offline.

Each repr is parsed as XML (the HTML is written XHTML-compatible, so a stray ``<`` from a name
would break the parse), its table cells are compared with the library's own numbers rounded to
the printed digits, and its swatch fills with the library's sRGB codes of the same colours,
computed by an independent route where one exists (:func:`spectrocolor.measurement_report`).
"""

from __future__ import annotations

import math
import re
import subprocess
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest

import spectrocolor as sc
from spectrocolor import Spectrum, notebook_hooks
from spectrocolor.display.explain import GAMUT_ACTIONS, out_of_gamut_channels
from spectrocolor.notebook import BUILDERS, spectrum_view
from spectrocolor.notebook import spectrum_records as spectrum_records
from spectrocolor.notebook.markup import number
from spectrocolor.notebook.svg import SVG_NAMESPACE

GRID = sc.wavelength_grid(380, 780, 5)
HOSTILE = ("<script>alert(1)</script>", "$x$", "a & b \"c\" 'd'", "tab\tnul\x00")
SVG = f"{{{SVG_NAMESPACE}}}"


def _tiles(names=("grey", "red", "blue")) -> Spectrum:
    values = np.stack([np.full(GRID.size, 0.5), np.where(GRID > 600, 0.9, 0.05), np.where(GRID < 480, 0.8, 0.02)])
    return Spectrum(GRID, values[: len(names)], names)


def parse(markup: str) -> ET.Element:
    """The repr as an XML tree (fails on anything not well formed)."""
    return ET.fromstring(markup)


def table_rows(markup: str, table: int = 0) -> list[list[str]]:
    """The body rows of the ``table``-th table, as the text of each cell."""
    tables = parse(markup).iter("table")
    for _ in range(table):
        next(tables)
    body = next(tables).find("tbody")
    return [["".join(td.itertext()) for td in tr.findall("td")] for tr in body.findall("tr")]


def header(markup: str, table: int = 0) -> list[str]:
    tables = list(parse(markup).iter("table"))
    return ["".join(th.itertext()) for th in tables[table].find("thead").iter("th")]


def swatch_colours(markup: str, table: int = 0) -> list[str]:
    """Background colours of the swatches in the first cell of each row."""
    tables = list(parse(markup).iter("table"))
    colours = []
    for tr in tables[table].find("tbody").findall("tr"):
        span = tr.find("td").find("span")
        colours.append(re.search(r"background: (#[0-9a-f]{6})", span.get("style")).group(1) if span is not None
                       else None)
    return colours


def assert_offline(markup: str, standalone_svg: bool = False) -> None:
    """No script and no network reference (the SVG namespace identifier of a standalone SVG excepted)."""
    text = markup.replace(f'xmlns="{SVG_NAMESPACE}"', "") if standalone_svg else markup
    lowered = text.lower()
    for forbidden in ("<script", "http:", "https:", "//", "javascript:", "<link", "<iframe", "url("):
        assert forbidden not in lowered, forbidden
    assert "onload" not in lowered and "onerror" not in lowered


def all_text(markup: str) -> str:
    return "".join(parse(markup).itertext())


# ----------------------------------------------------------------------------- Spectrum


def test_spectrum_numbers_are_the_librarys_tristimulus_to_the_printed_digits():
    tiles = _tiles()
    markup = tiles._repr_html_()
    assert header(markup)[2:10] == ["X", "Y", "Z", "x", "y", "λd nm", "purity", "sRGB"]
    XYZ = sc.tristimulus(tiles, illuminant="D65")
    xy = sc.xy(XYZ)
    white = sc.white_point("D65", wavelengths_nm=GRID)
    dominant = sc.dominant_wavelength(xy, sc.xy(white))
    for row, name, XYZ_i, xy_i, wl in zip(table_rows(markup), tiles.names, XYZ, xy, dominant.wavelength_nm,
                                          strict=True):
        assert row[1] == name
        assert [float(v) for v in row[2:5]] == [round(v, 2) for v in XYZ_i]
        assert [float(v) for v in row[5:7]] == [round(v, 4) for v in xy_i]
        assert row[7] == number(wl, 1)
    assert "under D65" in all_text(markup) and "380–780 nm, 5 nm, K = 81" in all_text(markup)


def test_spectrum_swatches_are_the_librarys_srgb8_of_the_same_colours():
    tiles = _tiles()
    markup = tiles._repr_html_()
    expected = list(sc.measurement_report(tiles, illuminant="D65").srgb_hex)  # an independent route
    assert swatch_colours(markup) == expected
    assert [row[9] for row in table_rows(markup)] == expected
    curves = [path.get("stroke") for path in parse(markup).iter("path") if path.get("stroke", "").startswith("#")]
    assert curves == expected  # each curve tinted by its colour
    svg_fills = [r.get("fill") for r in parse(tiles._repr_svg_()).iter(f"{SVG}rect") if r.find(f"{SVG}title")
                 is not None]
    assert svg_fills == expected


def test_a_colour_outside_the_display_carries_the_explorers_badge():
    narrow = Spectrum(GRID, np.where((GRID >= 505) & (GRID <= 535), 1.0, 0.0), ["green band"])
    XYZ = sc.tristimulus(narrow, illuminant="D65")
    white = sc.white_point("D65", wavelengths_nm=GRID)
    srgb = sc.rgb_space("sRGB")
    rendering = sc.render(sc.adapt(XYZ[None], white, srgb.white_XYZ), srgb)
    assert not rendering.in_gamut[0]
    negative, over = out_of_gamut_channels(rendering)
    channels = [f"{c} negative" for c in negative[0]] + [f"{c} above 1" for c in over[0]]
    expected = f"{', '.join(channels)}: {GAMUT_ACTIONS['desaturate']}"
    assert table_rows(narrow._repr_html_())[0][10] == expected
    assert swatch_colours(narrow._repr_html_()) == [rendering.hex[0]]


def test_lights_are_read_as_lights_and_summed_over_the_observers_range():
    d65 = sc.illuminant("D65")  # tabulated 300-830 nm, values up to ~118
    view = spectrum_view(d65)
    assert view.reading == "light" and view.summed_nm == (360.0, 830.0)  # exact: whole-nm grid limits
    expected = sc.tristimulus(d65.restrict(360, 830))
    np.testing.assert_allclose(view.XYZ[0], expected, rtol=1e-12)
    markup = d65._repr_html_()
    assert [float(v) for v in table_rows(markup)[0][2:5]] == [round(v, 2) for v in expected]
    assert "read as lights" in all_text(markup) and "summed over 360–830 nm" in all_text(markup)


def test_the_reading_can_be_chosen():
    tiles = _tiles()
    view = spectrum_view(tiles, illuminant="A")
    np.testing.assert_allclose(view.XYZ, sc.tristimulus(tiles, illuminant="A"), rtol=1e-12)
    assert "under A" in all_text(view._repr_html_())
    as_light = spectrum_view(tiles, illuminant=None)
    assert as_light.reading == "light"
    np.testing.assert_allclose(as_light.XYZ, sc.tristimulus(tiles), rtol=1e-12)
    with pytest.raises(sc.SpectrumError, match="rows"):
        spectrum_view(tiles, rows=0)


@pytest.mark.parametrize("name", HOSTILE)
def test_hostile_names_are_shown_as_text(name):
    spectrum = Spectrum(GRID, np.full(GRID.size, 0.4), [name])
    for markup in (spectrum._repr_html_(), sc.measurement_report(spectrum)._repr_html_()):
        root = parse(markup)  # a raw "<" or "&" would not parse
        shown = name.replace("\x00", "\ufffd")
        assert shown in "".join(root.itertext())
        assert "<script" not in markup
        assert {"tex2jax_ignore", "mathjax_ignore"} <= set(root.get("class").split())  # "$x$" is not typeset
        assert_offline(markup)
    parse(spectrum._repr_svg_())


def test_batch_of_ten_thousand_shows_the_first_few_and_the_count_and_colours_only_those(monkeypatch):
    rng = np.random.default_rng(7)
    batch = Spectrum(GRID, rng.random((10_000, GRID.size)))
    calls = []
    real = spectrum_records.tristimulus

    def counting(spectrum, **options):
        calls.append(spectrum.values.shape)
        return real(spectrum, **options)

    monkeypatch.setattr(spectrum_records, "tristimulus", counting)
    markup = batch._repr_html_()
    rows = table_rows(markup)
    assert len(rows) == spectrum_records.SHOWN_ROWS
    assert [row[1] for row in rows] == [f"#{i}" for i in range(len(rows))]
    text = all_text(markup)
    assert "10,000 spectra" in text and "first 8 of 10,000 spectra shown" in text
    assert calls and all(math.prod(shape[:-1]) <= spectrum_records.SHOWN_ROWS for shape in calls)
    expected = sc.tristimulus(batch[:2], illuminant="D65")
    assert [float(v) for v in rows[1][2:5]] == [round(v, 2) for v in expected[1]]
    lo, hi = batch.values.min(), batch.values.max()  # the summary covers the whole batch
    assert f"values {number(lo, 4)}–{number(hi, 4)}" in text
    assert len(markup) < 60_000


def test_an_image_batch_names_its_rows_by_index_and_a_grid_the_observer_misses_says_so():
    cube = Spectrum(GRID, np.full((3, 4, GRID.size), 0.25))
    rows = table_rows(cube._repr_html_())
    assert [row[1] for row in rows[:5]] == ["(0, 0)", "(0, 1)", "(0, 2)", "(0, 3)", "(1, 0)"]
    infrared = Spectrum(sc.wavelength_grid(900, 1000, 10), np.full(11, 0.5))
    markup = infrared._repr_html_()
    assert "colours not computed" in all_text(markup)
    assert swatch_colours(markup) == [None]


@pytest.mark.slow
def test_building_reprs_never_imports_matplotlib():
    code = """
import sys, numpy as np, spectrocolor as sc
grid = sc.wavelength_grid(380, 780, 5)
s = sc.Spectrum(grid, np.full((3, grid.size), 0.5))
records = [s, sc.render([[20.0, 21.0, 22.0]]), sc.colour_rendering_index(sc.illuminant("FL2")),
           sc.colour_fidelity(sc.illuminant("FL2")), sc.smoothest_reflectance([40.0, 40.0, 40.0]),
           sc.film_colours(sc.soap_film([100.0, 300.0], grid)), sc.measurement_report(s),
           sc.zawischa_strip(columns=100),
           sc.upsampling_table("sRGB", "D65", resolution=3, measure_excess=False)]
for r in records:
    r._repr_html_(); r._repr_svg_(); repr(r)
print("matplotlib" in sys.modules)
"""
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert out.strip() == "False"


# ----------------------------------------------------------------------------- Rendering


def test_rendering_shows_its_swatches_and_what_the_gamut_strategy_did():
    XYZ = [[20.0, 21.0, 22.0], [1.0, 60.0, 5.0]]
    for gamut in ("flag", "clip", "preserve-luminance", "desaturate"):
        rendering = sc.render(XYZ, gamut=gamut)
        markup = rendering._repr_html_()
        assert swatch_colours(markup) == list(rendering.hex)
        rows = table_rows(markup)
        assert rows[0][5] == "in gamut"
        assert rows[1][5] == f"R negative, B negative, G above 1: {GAMUT_ACTIONS[gamut]}"
        assert rows[1][3] == "  ".join(str(c) for c in rendering.codes[1])
        assert f"gamut={gamut!r}" in repr(rendering) and "1 outside the display" in repr(rendering)
        assert_offline(markup)
        assert_offline(rendering._repr_svg_(), standalone_svg=True)


def test_a_large_rendering_draws_a_bounded_number_of_swatches():
    rendering = sc.render(np.tile([[20.0, 21.0, 22.0]], (100_000, 1)))
    svg = rendering._repr_svg_()
    assert len(list(parse(svg).iter(f"{SVG}rect"))) == 24
    assert len(table_rows(rendering._repr_html_())) == 8
    assert "100,000 colours" in repr(rendering) and len(repr(rendering)) < 200


# ----------------------------------------------------------------------------- lighting


def test_cri_shows_its_numbers_and_bars_in_the_test_samples_colours():
    from spectrocolor.lighting.spectra import tcs_reflectances

    cri = sc.colour_rendering_index(sc.illuminant("FL2"))
    markup = cri._repr_html_()
    row = table_rows(markup)[0]
    assert row[1:5] == [number(cri.Ra, 1), number(cri.R9, 1), number(cri.cct_K, 0), number(cri.duv, 4)]
    bars = [r for r in parse(markup).iter("rect") if r.find("title") is not None]
    assert [b.find("title").text.split(" = ")[1].split(" ")[0] for b in bars] == [number(v, 1) for v in cri.Ri]
    tcs = Spectrum(GRID, tcs_reflectances(GRID))
    assert [b.get("fill") for b in bars] == list(sc.measurement_report(tcs, illuminant="D65").srgb_hex)
    assert repr(cri) == f"CRI(Ra={number(cri.Ra, 1)}, R9={number(cri.R9, 1)}, CCT={number(cri.cct_K, 0)} K, " \
                        f"Duv={number(cri.duv, 4)}, meaningful)"
    assert_offline(markup)


def test_fidelity_shows_its_numbers_and_the_vector_graphic():
    from spectrocolor.lighting.vector_graphic import normalised_graphic

    fidelity = sc.colour_fidelity(sc.illuminant("FL2"))
    markup = fidelity._repr_html_()
    assert table_rows(markup)[0][1:] == [number(fidelity.Rf, 1), number(fidelity.Rg, 1), number(fidelity.cct_K, 0),
                                         number(fidelity.duv, 4)]
    polygon = next(p for p in parse(markup).iter("polygon") if p.get("stroke") == "#d62728")
    points = np.array([[float(v) for v in pair.split(",")] for pair in polygon.get("points").split()])
    size = 260
    data = np.column_stack([(points[:, 0] - size / 2), (size / 2 - points[:, 1])]) / (size / 3)
    np.testing.assert_allclose(data, normalised_graphic(fidelity)[1], atol=0.06 / (size / 3) * 3)
    bins = table_rows(markup, table=1)
    assert bins[0][1:] == [number(v, 0) for v in fidelity.Rf_h]
    assert "Rf 70" in all_text(markup) and repr(fidelity).startswith(f"Fidelity(Rf={number(fidelity.Rf, 1)}")
    assert_offline(markup)
    assert_offline(fidelity._repr_svg_(), standalone_svg=True)


def test_a_batch_of_lights_lists_them():
    lights = Spectrum(sc.illuminant("FL2").wavelengths_nm,
                      np.stack([sc.illuminant(name).values for name in ("FL2", "FL7", "FL11")]))
    cri = sc.colour_rendering_index(lights)
    rows = table_rows(cri._repr_html_())
    assert [row[1] for row in rows] == [number(v, 1) for v in cri.Ra]
    assert repr(cri).startswith("CRI(3 lights, batch shape (3,), first: ")


# ----------------------------------------------------------------------------- recovery


def test_smoothest_result_shows_the_reflectance_in_its_colour_and_its_certificate():
    result = sc.smoothest_reflectance([[40.0, 40.0, 40.0], [20.0, 10.0, 5.0], [200.0, 1.0, 1.0]])
    markup = result._repr_html_()
    rows = table_rows(markup)
    # exact: the printed digits of the target colour, which the result meets to 1e-12 relative
    assert [float(v) for v in rows[1][2:5]] == [20.0, 10.0, 5.0]
    assert [row[5].split(" ")[0] for row in rows] == ["certified", "certified", "infeasible"]
    assert rows[0][10] == f"{float(result.certificate.rounding_ratio[0]):.3g}"
    feasible = Spectrum(result.spectrum.wavelengths_nm, result.spectrum.values[:2])
    expected = list(sc.measurement_report(feasible, illuminant="D65").srgb_hex)
    assert swatch_colours(markup)[:2] == expected
    curves = [p.get("stroke") for p in parse(markup).iter("path") if p.get("stroke", "").startswith("#")]
    assert curves[:2] == expected
    assert "2 certified" in repr(result) and "3 colours" in repr(result)
    assert_offline(markup)


# ----------------------------------------------------------------------------- thin films


def test_film_colours_show_the_strip_in_order():
    colours = sc.film_colours(sc.soap_film(np.linspace(0.0, 1200.0, 60), GRID))
    markup = colours._repr_html_()
    strip = [r.get("fill") for r in parse(markup).iter("rect") if r.get("fill", "").startswith("#")]
    assert strip == list(colours.rendering.hex)
    assert [row[7] for row in table_rows(markup)] == list(colours.rendering.hex[:6])
    assert "60 films" in repr(colours) and "exposure 'global-max'" in repr(colours)
    assert_offline(markup)


def test_zawischas_strip_has_its_ticks_every_500_nm():
    strip = sc.zawischa_strip(columns=400)
    svg = strip._repr_svg_()
    ticks = [t.text for t in parse(svg).iter(f"{SVG}text") if t.text and t.text.isdigit()]
    assert ticks == ["500", "1000", "1500", "2000"]
    fills = [r.get("fill") for r in parse(svg).iter(f"{SVG}rect") if r.get("fill", "").startswith("#")]
    assert fills == list(strip.colours.rendering.hex)
    assert_offline(svg, standalone_svg=True)


# ----------------------------------------------------------------------------- report and table


def test_measurement_report_shows_its_table():
    report = sc.measurement_report(_tiles(), illuminant="C")
    markup = report._repr_html_()
    for row, record in zip(table_rows(markup), report.records(), strict=True):
        assert row[1] == record["name"]
        assert [float(v) for v in row[2:5]] == [round(record[k], 2) for k in ("X", "Y", "Z")]
        assert row[9] == number(record["luminance_factor_percent"], 2)
        assert row[13] == record["sRGB"]
    assert swatch_colours(markup) == list(report.srgb_hex)
    assert repr(report).startswith("MeasurementReport(3 samples · illuminant C")
    assert_offline(markup)


def test_upsampling_table_shows_its_coverage():
    table = sc.upsampling_table("Rec. 2020", "D65", resolution=5, measure_excess=False)
    moved = int(np.count_nonzero(table.node_status))
    assert 0 < moved < table.node_status.size
    markup = table._repr_html_()
    coverage = dict(table_rows(markup))
    nodes = table.node_status.size
    assert coverage["exact nodes"].startswith(f"{nodes - moved} of {nodes}")
    assert coverage["moved toward grey"] == str(moved)
    crosses = [p for p in parse(markup).iter("path") if p.get("stroke") == "currentColor"]
    assert len(crosses) == moved  # resolution 5: every node of every slice is drawn
    assert_offline(markup)


# ----------------------------------------------------------------------------- the hooks


def test_every_record_class_delegates_to_the_notebook_package():
    import importlib

    for qualified in BUILDERS:
        module, name = qualified.rsplit(".", 1)
        cls = getattr(importlib.import_module(module), name)
        assert cls._repr_html_ is notebook_hooks.html, qualified
        assert cls._repr_svg_ is notebook_hooks.svg, qualified


def test_only_the_hook_module_names_the_notebook_package_below_the_presentation_layer():
    package = Path(sc.__file__).parent
    naming = sorted(str(p.relative_to(package)) for p in package.rglob("*.py")
                    if "spectrocolor.notebook\"" in p.read_text(encoding="utf-8")
                    and p.parts[len(package.parts)] != "notebook")
    assert naming == ["notebook_hooks.py"]
