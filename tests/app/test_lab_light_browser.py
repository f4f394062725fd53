"""The light-source lab in Debian's Chromium: controls drive the numbers, the graphic and the samples."""

from __future__ import annotations

import json

import pytest

from appbrowser import AXE, DESKTOP, PHONE, open_lab
from spectrocolor.app import light_lab as lab

pytestmark = pytest.mark.browser


def shown_numbers(page) -> dict:
    terms = page.eval_on_selector_all("#numbers dt", "es => es.map(e => e.textContent)")
    values = page.eval_on_selector_all("#numbers dd", "es => es.map(e => e.textContent)")
    return dict(zip(terms, values, strict=True))


def test_a_named_light_shows_the_librarys_indices(browser, base_url, artifacts_dir):
    page, errors = open_lab(browser, base_url + "labs/light")
    expected = lab.light_lab({"kind": "named", "name": "FL2"})["summary"]
    numbers = shown_numbers(page)
    assert numbers["Ra (CIE 13.3)"] == f"{expected['Ra']:.1f}"
    assert numbers["Rf (TM-30 / CIE 224)"] == f"{expected['Rf']:.1f}"
    assert numbers["CCT"] == f"{expected['cct_K']:.0f} K"
    page.select_option("#name", "blackbody")
    page.wait_for_function("document.querySelector('#numbers').textContent.includes('blackbody 3000 K')")
    assert shown_numbers(page)["Ra (CIE 13.3)"] == "100.0"  # a Planckian radiator is its own reference
    page.select_option("#name", "FL2")
    page.wait_for_function("document.querySelector('#numbers dd').textContent === 'FL2'")
    page.screenshot(path=str(artifacts_dir / "lab_light.png"), full_page=True)
    assert not errors, errors


def test_led_sliders_change_the_light_and_the_url_reproduces_it(browser, base_url):
    page, errors = open_lab(browser, base_url + "labs/light")
    page.select_option("#kind", "leds")
    page.wait_for_function("document.querySelector('#numbers dd').textContent.startsWith('LED mixture')")
    peak = page.locator("#primaries input[type=range]").nth(6)  # primary 3's peak
    peak.evaluate("e => { e.value = 600; e.dispatchEvent(new Event('input', {bubbles: true}));"
                  " e.dispatchEvent(new Event('change', {bubbles: true})); }")
    page.wait_for_function("document.querySelector('#numbers dd').textContent === 'LED mixture (450, 540, 600 nm)'")
    page.wait_for_function("document.body.dataset.ready === 'true'")
    expected = lab.light_lab({"kind": "leds", "peaks_nm": [450, 540, 600], "widths_nm": [20, 60, 20],
                              "powers": [1.0, 0.7, 0.8]})
    assert shown_numbers(page)["Rf (TM-30 / CIE 224)"] == f"{expected['summary']['Rf']:.1f}"
    url = page.url
    again, more_errors = open_lab(browser, url)
    assert shown_numbers(again)["light"] == "LED mixture (450, 540, 600 nm)"
    again.close()
    page.keyboard.press("Control+z")
    page.wait_for_function("document.querySelector('#numbers dd').textContent === 'LED mixture (450, 540, 620 nm)'")
    assert not errors and not more_errors


def test_no_serious_accessibility_violations(browser, base_url, artifacts_dir):
    for name, size in (("desktop", DESKTOP), ("phone", PHONE)):
        page, errors = open_lab(browser, base_url + "labs/light#kind=leds", size)
        page.add_script_tag(path=str(AXE))
        result = json.loads(page.evaluate("async () => JSON.stringify(await axe.run(document))"))
        violations = [v for v in result["violations"] if v["impact"] in ("serious", "critical")]
        assert not violations, [(v["id"], v["help"], [n["target"] for n in v["nodes"]][:3]) for v in violations]
        if name == "phone":
            page.screenshot(path=str(artifacts_dir / "lab_light_phone.png"), full_page=True)
        page.close()
        assert not errors, errors
