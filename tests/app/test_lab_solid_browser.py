"""The object-colour solid lab in Debian's Chromium: it turns, cuts and shows a mismatch region."""

from __future__ import annotations

import json

import pytest

from appbrowser import AXE, DESKTOP, PHONE, open_lab

pytestmark = pytest.mark.browser


def test_turning_cutting_and_the_mismatch_region(browser, base_url, artifacts_dir):
    page, errors = open_lab(browser, base_url + "labs/solid", timeout_ms=60000)
    before = page.eval_on_selector("#solid", "c => c.toDataURL()")
    page.click("button[aria-label='Turn right']")
    page.wait_for_function("location.hash.includes('yaw=50')")
    assert page.eval_on_selector("#solid", "c => c.toDataURL()") != before  # the picture turned
    page.eval_on_selector("#Y", "e => { e.value = 20; e.dispatchEvent(new Event('change', {bubbles: true})); }")
    page.wait_for_function("location.hash.includes('Y=20')")
    page.select_option("#sample", "9")
    page.select_option("#second", "FL11")
    page.click("#mismatch")
    page.wait_for_function("document.querySelector('#status').textContent.startsWith('Sample 9')", timeout=60000)
    page.screenshot(path=str(artifacts_dir / "lab_solid.png"), full_page=True)
    page.keyboard.press("Control+z")
    page.wait_for_function("!location.hash.includes('mismatch=1')")
    assert not errors, errors


def test_no_serious_accessibility_violations(browser, base_url):
    for size in (DESKTOP, PHONE):
        page, errors = open_lab(browser, base_url + "labs/solid", size, timeout_ms=60000)
        page.add_script_tag(path=str(AXE))
        result = json.loads(page.evaluate("async () => JSON.stringify(await axe.run(document))"))
        violations = [v for v in result["violations"] if v["impact"] in ("serious", "critical")]
        assert not violations, [(v["id"], v["help"], [n["target"] for n in v["nodes"]][:3]) for v in violations]
        page.close()
        assert not errors, errors
