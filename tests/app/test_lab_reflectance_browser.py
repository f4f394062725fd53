"""The smoothest-reflectance lab in Debian's Chromium: clicks and the Y slider drive the library's answers."""

from __future__ import annotations

import json

import pytest

from appbrowser import AXE, DESKTOP, PHONE, open_lab
from spectrocolor.app import reflectance_lab as lab

pytestmark = pytest.mark.browser


def patch_rgb(page) -> list[int]:
    text = page.eval_on_selector("#patch", "e => getComputedStyle(e).backgroundColor")
    return [int(v) for v in text[text.index("(") + 1 : text.index(")")].split(",")]


def test_the_page_shows_the_librarys_colour_and_verdict(browser, base_url, artifacts_dir):
    page, errors = open_lab(browser, base_url + "labs/reflectance#light=D65&step=5&x=0.6&y=0.33&Y=20")
    expected = lab.reflectance_lab(0.6, 0.33, 20.0)
    assert patch_rgb(page) == expected["srgb8"]
    assert "Outside the domain of validity" in page.text_content("#verdict")
    assert f"Y = {expected['max_Y']:.2f}" in page.text_content("#numbers")
    page.screenshot(path=str(artifacts_dir / "lab_reflectance.png"), full_page=True)
    assert not errors, errors


def test_too_bright_is_explained_and_a_click_picks_a_chromaticity(browser, base_url):
    page, errors = open_lab(browser, base_url + "labs/reflectance#light=D65&step=5&x=0.6&y=0.33&Y=60")
    assert "No object colour has this chromaticity at Y = 60.0" in page.text_content("#verdict")
    box = json.loads(page.eval_on_selector("#diagram", "c => c.dataset.box"))
    rect = page.eval_on_selector("#diagram", "c => { const r = c.getBoundingClientRect(); return [r.left, r.top]; }")
    x, y = 0.33, 0.35  # near the white: bright colours exist there
    page.mouse.click(rect[0] + box["x"] + x / 0.8 * box["w"], rect[1] + box["y"] + box["h"] - y / 0.9 * box["h"])
    page.wait_for_function("document.querySelector('#x').value !== '0.6'")
    page.wait_for_function("document.body.dataset.ready === 'true'")
    page.wait_for_function("!document.querySelector('#verdict').textContent.startsWith('No object colour')")
    assert abs(float(page.input_value("#x")) - x) < 0.01 and abs(float(page.input_value("#y")) - y) < 0.01
    page.keyboard.press("Control+z")
    page.wait_for_function("document.querySelector('#x').value === '0.6'")
    assert not errors, errors


def test_no_serious_accessibility_violations(browser, base_url):
    for size in (DESKTOP, PHONE):
        page, errors = open_lab(browser, base_url + "labs/reflectance", size)
        page.add_script_tag(path=str(AXE))
        result = json.loads(page.evaluate("async () => JSON.stringify(await axe.run(document))"))
        violations = [v for v in result["violations"] if v["impact"] in ("serious", "critical")]
        assert not violations, [(v["id"], v["help"], [n["target"] for n in v["nodes"]][:3]) for v in violations]
        page.close()
        assert not errors, errors
