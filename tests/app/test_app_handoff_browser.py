"""The explorer's "Open in lab" hand-offs and the labs' tab bar in Debian's Chromium (issue 28 item 6).

Each hand-off opens its lab through the lab's URL state; the numbers the lab shows are checked
against the explorer's (the colour's x, y, Y) or against the library (the mismatch region of the
handed levels). A bad hand-off address gives one message and a working page.
"""

from __future__ import annotations

import json
import re

import pytest

from appbrowser import AXE, DESKTOP, PHONE, choose, open_lab, open_page, state
from spectrocolor.app import solid_lab

pytestmark = pytest.mark.browser


def lab_ready(pg, timeout=120000):
    pg.wait_for_selector("body[data-ready=true]", state="attached", timeout=timeout)


def test_the_shown_colour_goes_to_the_reflectance_lab(browser, base_url, artifacts_dir):
    with open_page(browser, base_url + "?s=1") as page:
        colour = state(page)["server"]["colours"][0]
        page.click("#handoff-reflectance")
        page.wait_for_url("**/labs/reflectance#*")
        lab_ready(page)
        # the address carries x, y to 4 decimals: the inputs hold the explorer's to that rounding
        assert abs(float(page.input_value("#x")) - colour["xy"][0]) <= 5e-5
        assert abs(float(page.input_value("#y")) - colour["xy"][1]) <= 5e-5
        numbers = page.text_content("#numbers")
        # the lab shows x, y to 4 decimals and Y to 1 (of the address's Y, rounded to 2): the
        # explorer's numbers within those roundings (half a unit of each, and 0.005 more for Y)
        shown = re.search(r"x ([0-9.]+), y ([0-9.]+), Y ([0-9.]+) under E", numbers)
        assert shown, numbers
        assert abs(float(shown[1]) - colour["xy"][0]) <= 5e-5 + 1e-12
        assert abs(float(shown[2]) - colour["xy"][1]) <= 5e-5 + 1e-12
        assert abs(float(shown[3]) - colour["XYZ"][1]) <= 0.05 + 0.005 + 1e-9
        assert page.is_hidden("#error")
        page.screenshot(path=str(artifacts_dir / "handoff_reflectance.png"))
        page.go_back()
        page.wait_for_function("window.__spectra && window.__spectra.settled", timeout=60000)
        assert state(page)["setting"] == 1


def test_setting_4s_sample_goes_to_the_solid_labs_mismatch_region(browser, base_url, artifacts_dir):
    with open_page(browser, base_url + "?s=4") as page:
        choose(page, 4)
        st = state(page)
        sample = st["dists"][1]
        page.click("#handoff-solid")
        page.wait_for_url("**/labs/solid#*")
        page.wait_for_function("document.querySelector('#status').textContent.startsWith('Sample from the explorer')",
                               timeout=120000)
        region = page.evaluate("__solid.region")
        light, second = page.input_value("#light"), page.input_value("#second")
        expected = solid_lab.mismatch_of_levels(tuple(float(v) for v in sample), float(st["step"]), light, second)
        assert region["sample_xy"] == expected["sample_xy"]  # exact: the same library call on the same whole levels
        assert region["region_xy"] == expected["region_xy"]  # exact: as above
        assert page.input_value("#sample") == "0"
        assert page.is_hidden("#error")
        page.screenshot(path=str(artifacts_dir / "handoff_solid.png"), full_page=True)


def test_setting_4s_named_illuminant_goes_to_the_light_lab(browser, base_url):
    with open_page(browser, base_url + "?s=4") as page:
        choose(page, 4)
        page.keyboard.press("2")  # setting 4's second default illuminant: D65
        page.wait_for_function("window.__spectra.names[4][0] === 'D65'")
        page.click("#handoff-light")
        page.wait_for_url("**/labs/light#*")
        lab_ready(page)
        assert page.evaluate("new URLSearchParams(location.hash.slice(1)).get('name')") == "D65"
        assert page.is_hidden("#error")


def test_a_hand_off_that_does_not_apply_says_why(browser, base_url):
    with open_page(browser, base_url + "?s=1") as page:
        page.click("#handoff-solid")
        assert "setting 4" in page.text_content("#handoff-status")
        assert page.evaluate("location.pathname") == "/"


@pytest.mark.parametrize("r", ["garbage", "10:1,2,3", "10:" + ",".join(["31"] * 31), "7:" + ",".join(["1"] * 31),
                               "10:" + ",".join(["NaN"] * 31)])
def test_a_bad_hand_off_address_gives_one_message(browser, base_url, r):
    page, errors = open_lab(browser, base_url + f"labs/solid#sample=0&mismatch=1&r={r}", timeout_ms=120000)
    assert "is not levels 0–30 on 400–700 nm" in page.text_content("#error-text")
    page.wait_for_function("document.querySelector('#status').textContent.startsWith('Sample 1')", timeout=120000)
    assert page.input_value("#sample") == "1"
    page.close()
    assert not errors, errors


def test_the_labs_tab_bar_links_the_settings_and_labs(browser, base_url, artifacts_dir):
    for size, name in ((DESKTOP, "desktop"), (PHONE, "phone")):
        page, errors = open_lab(browser, base_url + "labs/thinfilm", size, timeout_ms=120000)
        links = page.eval_on_selector_all(".tabbar a", "as => as.map(a => [a.getAttribute('href'), "
                                          "a.getAttribute('aria-current')])")
        assert [h for h, _ in links][:5] == [f"/?s={i}" for i in range(1, 6)]
        assert [h for h, c in links if c == "page"] == ["/labs/thinfilm"]
        page.screenshot(path=str(artifacts_dir / f"lab_tabbar_{name}.png"))
        page.add_script_tag(path=str(AXE))
        result = json.loads(page.evaluate("async () => JSON.stringify(await axe.run(document))"))
        violations = [v for v in result["violations"] if v["impact"] in ("serious", "critical")]
        assert not violations, [(v["id"], v["help"], [n["target"] for n in v["nodes"]][:3]) for v in violations]
        page.click(".tabbar a[href='/?s=2']")
        page.wait_for_function("window.__spectra && window.__spectra.settled", timeout=60000)
        assert page.evaluate("window.__spectra.setting") == 2
        page.close()
        assert not errors, errors


@pytest.mark.parametrize("size", [DESKTOP, PHONE], ids=["desktop", "phone"])
def test_the_explorer_with_the_hand_off_buttons_has_no_serious_violations(browser, base_url, artifacts_dir, size):
    with open_page(browser, base_url + "?s=4", size) as page:
        if page.is_visible("#menu") and not page.is_visible("#handoff-solid"):
            page.click("#menu")  # the phone's Options panel
        page.locator("#handoff").scroll_into_view_if_needed()
        page.screenshot(path=str(artifacts_dir / f"handoff_buttons_{size[0]}.png"))
        page.add_script_tag(path=str(AXE))
        result = json.loads(page.evaluate("async () => JSON.stringify(await axe.run(document))"))
        violations = [v for v in result["violations"] if v["impact"] in ("serious", "critical")]
        assert not violations, [(v["id"], v["help"], [n["target"] for n in v["nodes"]][:3]) for v in violations]
