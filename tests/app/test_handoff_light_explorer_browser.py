"""The explorer's own distribution in the light lab (issue 28, "one app"), in Chromium.

"Light → light lab" in setting 1 hands the distribution (levels 0-30 over 400-700 nm) to the
light lab through its address (``kind=explorer&r=<step>:<levels>&label=<name>``). Every metric the
lab shows takes samples from 380 to 780 nm (CIE 13.3, CIE 224 / TM-30, photometry, CIE S 026), so
for this light the library computes none of them and gives a reason for each; the lab says so,
in the library's words, and draws the distribution where it is known. Screenshots at desktop and
phone sizes go to ``/tmp/labs/`` for a person to look at."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from appbrowser import AXE, PHONE, open_lab, open_page, settle
from spectrocolor import Spectrum
from spectrocolor.app import light_lab
from spectrocolor.lighting.summary import light_report

pytestmark = pytest.mark.browser

SHOTS = Path("/tmp/labs")


def _library_reasons(levels, step):
    """What the library says for this light, independently of the lab's code path: the levels put
    on 380-780 nm with NaN outside 400-700 nm, as one light of a batch."""
    wl = np.arange(380.0, 781.0, 5.0)
    spd = np.full(wl.shape, np.nan)
    inside = (wl >= 400) & (wl <= 700)
    spd[inside] = np.interp(wl[inside], np.arange(400.0, 701.0, step), levels)
    report = light_report(Spectrum(wl, spd[None, :]))
    return [str(r[0]) for r in (report.cri.reason, report.fidelity.reason, report.ler_reason,
                                report.alpha_opic.reason)], report


def test_setting_1s_distribution_goes_to_the_light_lab_with_the_reasons(browser, base_url):
    with open_page(browser, base_url + "?s=1") as page:
        page.keyboard.press("4")
        settle(page)
        page.keyboard.press("ArrowUp")  # an edited distribution, not a preset
        settle(page)
        levels = page.evaluate("window.__spectra.dists[1][0]")
        name = page.evaluate("window.__spectra.names[1][0]")
        step = page.evaluate("window.__spectra.step")
        page.click("#handoff-light")
        page.wait_for_url("**/labs/light#*")
        page.wait_for_selector("body[data-ready=true]", timeout=60000)
        params = page.evaluate("Object.fromEntries(new URLSearchParams(location.hash.slice(1)))")
        assert params["kind"] == "explorer" and params["label"] == name
        assert params["r"] == f"{step:g}:" + ",".join(f"{v:g}" for v in levels)
        assert page.input_value("#kind") == "explorer"
        assert page.is_hidden("#error")
        # the library computes none of the metrics for 400-700 nm: the page says which and why
        reasons, report = _library_reasons(levels, step)
        assert all(np.isnan(v[0]) for v in report.headline().values())
        assert all("380–780 nm" in r for r in reasons)
        items = page.eval_on_selector_all("#reasons li", "ls => ls.map((l) => l.textContent)")
        assert len(items) == 4
        for item, reason, metric in zip(items, reasons, ("Ra", "Rf", "LER", "melanopic DER"), strict=True):
            assert metric in item and reason.split("; ")[-1] in item, (item, reason)
            assert "400–700 nm" in item
        assert "known over 400–700 nm only" in page.text_content("#reasons")
        shown = page.eval_on_selector_all("#numbers dd", "ds => ds.map((d) => d.textContent)")
        assert shown[0] == name and all(v.startswith("—") for v in shown[1:])
        # the distribution is drawn where it is known: the lab's plot has the theme's ink in it,
        # and the answer's SPD is the levels' shape (peak 1) between 400 and 700 nm
        answer = page.evaluate("""async ([step, levels]) => (await (await fetch('/api/lab/light', {method: 'POST',
            headers: {'Content-Type': 'application/json'}, body: JSON.stringify({source: {kind: 'explorer',
            step_nm: step, levels, label: 'x'}})})).json())""", [step, levels])
        expected = light_lab.explorer_spd(levels, step)
        got = np.array([np.nan if v is None else v for v in answer["spd"]])
        # the answer is rounded to 6 decimals (light_lab._part_measured): half a unit of the 6th
        np.testing.assert_allclose(got, expected, atol=5e-7)
        SHOTS.mkdir(exist_ok=True)
        page.screenshot(path=str(SHOTS / "light_from_explorer_desktop.png"), full_page=True)
        page.add_script_tag(path=str(AXE))
        result = json.loads(page.evaluate("async () => JSON.stringify(await axe.run(document))"))
        violations = [v for v in result["violations"] if v["impact"] in ("serious", "critical")]
        assert not violations, [(v["id"], v["help"], [n["target"] for n in v["nodes"]][:3]) for v in violations]
        page.go_back()  # the hand-off is a link: Back returns to the explorer as it was
        settle(page)
        assert page.evaluate("window.__spectra.dists[1][0]") == levels


def test_the_explorer_light_on_a_phone_says_why(browser, base_url):
    r = "10:" + ",".join(["0"] * 10 + ["20"] * 11 + ["0"] * 10)
    page, errors = open_lab(browser, base_url + f"labs/light#kind=explorer&r={r}&label=green%20band", PHONE,
                            timeout_ms=60000)
    try:
        assert page.is_visible("#reasons") and page.is_hidden("#error")
        assert page.eval_on_selector_all("#reasons li", "ls => ls.length") == 4
        SHOTS.mkdir(exist_ok=True)
        page.screenshot(path=str(SHOTS / "light_from_explorer_phone.png"), full_page=True)
        page.select_option("#kind", "named")  # and back to a named light: every number again
        page.wait_for_function("document.querySelector('#reasons').hidden")
        assert not page.text_content("#numbers").count("—")
        assert not errors, errors
    finally:
        page.close()


@pytest.mark.parametrize("r", ["garbage", "10:1,2,3", "10:" + ",".join(["31"] * 31), "7:" + ",".join(["1"] * 31),
                               "10:" + ",".join(["0"] * 31), "10:" + ",".join(["NaN"] * 31)])
def test_a_bad_explorer_address_gives_one_message(browser, base_url, r):
    page, errors = open_lab(browser, base_url + f"labs/light#kind=explorer&r={r}", timeout_ms=60000)
    try:
        assert "could not be read" in page.text_content("#error-text")
        assert page.input_value("#kind") == "named" and page.is_hidden("#reasons")
        assert not errors, errors
    finally:
        page.close()
