"""Pictures of the explorer's view for slides and worksheets (issue 28, item 5), in real Chromium.

"Picture SVG" and "Picture PNG" download the current view (patches, the distributions' graphs, the
chromaticity diagram) through the browser's download path. The files are opened and checked: the
SVG parses as XML, names the samples as text (a hostile name escaped, never markup) and the units
(wavelength λ in nm, the level's meaning, CIE x and y), and its patch rectangles have the page's
patch colours, which are the library's for the page's state (``compute.evaluate``); the PNG decodes
with the project's own PNG reader at the chosen scale, its patch pixels have those colours, and it
carries the names and units as an iTXt Description. Screenshots of the page's controls at four sizes
go to the artifacts folder and /tmp/h28p.
"""

from __future__ import annotations

import re
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest

from appbrowser import DESKTOP, PHONE, TABLET, choose, key, library, open_page, patch_rgb, settle, state, warm_server
from spectrocolor.imagefiles import decode_png

pytestmark = pytest.mark.browser

NS = "{http://www.w3.org/2000/svg}"
SHOTS = Path("/tmp/h28p")
HOSTILE = 'red <script>alert(1)</script> & "paint"'


@pytest.fixture(autouse=True, scope="module")
def _warm(base_url):
    warm_server(base_url)


def download(pg, button, tmp_path):
    with pg.expect_download() as d:
        pg.click(button)
    path = tmp_path / d.value.suggested_filename
    d.value.save_as(path)
    return path


def rgb(css):
    return [float(v) for v in re.findall(r"[\d.]+", css)[:3]]


def texts(root):
    return ["".join(t.itertext()) for t in root.iter(f"{NS}text")]


def open_tools(pg):
    if pg.locator("#menu").is_visible():
        pg.click("#menu")


def test_svg_has_names_units_and_the_page_colours(browser, base_url, tmp_path):
    with open_page(browser, base_url) as pg:
        choose(pg, 2)
        # a name as a file could bring it, then an edit: shown as "… (edited)"
        pg.evaluate(f"window.__spectra.names[2][0] = {HOSTILE!r}")
        pg.locator("#editors .editor[data-e='0'] canvas").focus()
        key(pg, "ArrowUp")
        name = f"{HOSTILE} (edited)"
        assert pg.locator("#patches .patch[data-i='0'] > .tag").inner_text() == name
        path = download(pg, "#save-svg", tmp_path)
        assert path.name == "spectra-setting2.svg"
        raw = path.read_text(encoding="utf-8")
        assert "<script" not in raw and "&lt;script&gt;" in raw  # escaped text, never markup
        root = ET.fromstring(raw)
        words = texts(root)
        assert name in words and "three-band" in words
        assert "wavelength λ (nm)" in words and "level (0–30)" in words
        assert any(w.startswith("spectral power") for w in words)
        assert any(w.startswith("CIE x") for w in words) and any(w.startswith("CIE y") for w in words)
        assert any("nm" in w and w.split()[0] == "520" for w in words)  # the locus labelled in nm
        assert any(w.startswith("ΔE00") for w in words)
        assert name in root.find(f"{NS}desc").text
        lib = library(state(pg))["colours"]
        rects = {int(r.get("data-i")): r for r in root.iter(f"{NS}rect") if r.get("class") == "patch"}
        assert sorted(rects) == [0, 1]
        for i, r in rects.items():
            # exact: both are the browser's computed colour of the same painted patch
            assert rgb(r.get("fill")) == patch_rgb(pg, i)
            np.testing.assert_allclose(rgb(r.get("fill")), np.array(lib[i]["rgb_encoded"]) * 255, atol=0.51)


def test_png_at_2x_decodes_with_the_patch_colours_names_and_units(browser, base_url, tmp_path):
    with open_page(browser, base_url) as pg:
        choose(pg, 4)
        key(pg, "6")
        svg = ET.fromstring(download(pg, "#save-svg", tmp_path).read_text(encoding="utf-8"))
        words = texts(svg)
        assert any(w.startswith("reflectance (level 0–30 = 0–100 %)") for w in words)
        assert any(w.startswith("relative spectral power") for w in words)
        open_tools(pg)
        pg.select_option("#png-scale", "2")
        path = download(pg, "#save-png", tmp_path)
        assert path.name == "spectra-setting4@2x.png"
        data = path.read_bytes()
        SHOTS.mkdir(exist_ok=True)
        (SHOTS / path.name).write_bytes(data)  # for a person to look at
        img = decode_png(data, path.name)
        assert img.shape[:2] == (2 * int(svg.get("height")), 2 * int(svg.get("width")))
        lib = library(state(pg))["colours"]
        for r in svg.iter(f"{NS}rect"):
            if r.get("class") != "patch":
                continue
            i = int(r.get("data-i"))
            x, y = 2 * (float(r.get("x")) + float(r.get("width")) / 2), 2 * (float(r.get("y")) + 20)
            # the canvas draws the SVG's 8-bit colour: equal to the encoded value within half a code
            np.testing.assert_allclose(img[int(y), int(x), :3], np.array(lib[i]["rgb_encoded"]) * 255, atol=0.51)
        # names and units in the file itself (iTXt "Description", UTF-8)
        at = data.index(b"iTXt")
        length = int.from_bytes(data[at - 4:at], "big")
        keyword, _, rest = data[at + 4:at + 4 + length].partition(b"\0")
        text = rest[4:].decode("utf-8")
        assert keyword == b"Description" and "metameric yellow 1" in text and "nm" in text
        pytest.importorskip("PIL")
        from PIL import Image

        with Image.open(path) as im:  # an independent reader agrees (chunk CRCs checked)
            im.load()
            assert im.size == (img.shape[1], img.shape[0]) and im.text["Description"] == text


@pytest.mark.parametrize("setting", [1, 3, 5])
def test_every_setting_exports_its_patches_and_graphs(browser, base_url, tmp_path, setting):
    with open_page(browser, base_url) as pg:
        choose(pg, setting)
        svg = ET.fromstring(download(pg, "#save-svg", tmp_path).read_text(encoding="utf-8"))
        patches = [r for r in svg.iter(f"{NS}rect") if r.get("class") == "patch"]
        assert len(patches) == pg.locator("#patches .patch").count()
        graphs = [g for g in svg.iter(f"{NS}g") if g.get("class") == "graph"]
        assert len(graphs) == {1: 1, 3: 2, 5: 3}[setting]
        words = texts(svg)
        assert words.count("wavelength λ (nm)") == len(graphs)
        if setting == 5:
            assert any(w.startswith("transmittance") for w in words)


@pytest.mark.parametrize("size", [DESKTOP, (1366, 768), TABLET, PHONE], ids=["desktop", "laptop", "tablet", "phone"])
def test_buttons_visible_at_four_sizes(browser, base_url, size, artifacts_dir):
    SHOTS.mkdir(exist_ok=True)
    with open_page(browser, base_url, size) as pg:
        open_tools(pg)
        opener = "#projector-touch" if size == PHONE else "#projector-open"
        assert pg.locator(opener).is_visible()
        for sel in ("#save-svg", "#save-png", "#png-scale", opener):
            box = pg.locator(sel).bounding_box()
            assert box and box["x"] >= 0 and box["x"] + box["width"] <= size[0] + 0.5, sel
        settle(pg)
        name = f"explorer_{size[0]}x{size[1]}_tools.png"
        pg.screenshot(path=str(SHOTS / name))
        pg.screenshot(path=str(artifacts_dir / name))
