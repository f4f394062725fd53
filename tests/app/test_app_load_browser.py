"""The explorer's Load in a real browser: a cp1252 X-Rite ColorPort-like export, sent as bytes,
decoded on the server as the library decodes it; the page says which encoding was used and what
the file declares. The file is ``tests/data/io/colorport_d65_10_cp1252.cgats`` (``make_declared.py``)."""

from __future__ import annotations

from pathlib import Path

import pytest

from appbrowser import choose, settle, state

pytestmark = pytest.mark.browser

FILE = Path(__file__).parents[1] / "data" / "io" / "colorport_d65_10_cp1252.cgats"


def test_load_decodes_a_cp1252_colorport_export_and_says_what_it_declares(browser, base_url, artifacts_dir):
    context = browser.new_context(viewport={"width": 1280, "height": 800})
    page = context.new_page()
    errors: list[str] = []
    page.on("pageerror", lambda e: errors.append(str(e)))
    page.goto(base_url)
    settle(page)
    choose(page, 4)  # samples under illuminants: three editors for the file's three spectra
    page.select_option("#upload-scale", "unit")
    page.set_input_files("#file", str(FILE))
    page.wait_for_function("document.getElementById('note').textContent.includes('declares')", timeout=20000)
    note = page.locator("#note").inner_text()
    assert "encoding cp1252" in note
    assert "the file declares D65/10°; the page computes under its own light and the CIE 1931 2° observer" in note
    settle(page)
    names = state(page)["names"]
    assert names == ["Rot – glänzend", "Grün µ2", "Grau 10°"], names  # decoded by the server, not garbled
    page.screenshot(path="/tmp/h26c_load.png")
    page.screenshot(path=str(artifacts_dir / "load_cp1252_colorport.png"))
    assert not errors, errors
    context.close()
