"""The explorer on every device (issue 13, point 7), in Chromium with the real server.

A phone (390×844, touch): a compact header, the patch stays in view while the bars are edited,
touch buttons do what the keys S, 0, 9 and ↑/↓/←/→ do. A tablet (820×1180): the editors keep the
full width; the diagram sits beside the numbers, below them. Every setting is photographed at
desktop, phone and tablet sizes into the artifacts folder (docs/images/app_setting*.png are
copies of these, looked at by a person)."""

from __future__ import annotations

import pytest

from appbrowser import DESKTOP, PHONE, TABLET, check_card, choose, in_viewport, key, library, open_page, settle, state

pytestmark = pytest.mark.browser

# The demonstration shown for each setting in the screenshots (keys pressed after choosing it).
# Setting 2: D65 and the three-band light under B, as the seed shows them (the same colour).
SHOW = {1: "4", 2: "x", 3: "x3", 4: "46", 5: "3"}


def box(pg, selector):
    return pg.locator(selector).first.bounding_box()


def test_phone_header_is_compact_and_the_patch_stays_in_view(browser, base_url):
    with open_page(browser, base_url, PHONE, touch=True) as pg:
        assert box(pg, "header")["height"] <= 120
        assert pg.evaluate("document.documentElement.scrollWidth") <= PHONE[0]
        for setting in (1, 4):
            choose(pg, setting)
            last = pg.locator("#editors .editor").last
            last.scroll_into_view_if_needed()
            assert in_viewport(pg, "#editors .editor:last-child canvas")
            assert in_viewport(pg, "#patches")  # sticky: visible while the last editor is edited
            assert pg.evaluate("""() => { const r = document.querySelector('#patches').getBoundingClientRect();
                const hit = document.elementFromPoint(r.left + r.width / 2, r.top + r.height / 2);
                return Boolean(hit && hit.closest('#patches')); }""")  # not hidden under the header
            assert in_viewport(pg, "#touch") or pg.locator("#touch").is_visible()
        # the options are one tap away
        assert not pg.locator("#display").is_visible()
        pg.tap("#menu")
        assert pg.locator("#display").is_visible()
        pg.tap("#menu")


def test_touch_buttons_do_what_the_keys_do(browser, base_url):
    with open_page(browser, base_url, PHONE, touch=True) as pg:
        choose(pg, 2)
        key(pg, "4")  # left: green
        tap = lambda command: (pg.tap(f"#touch [data-command={command}]"), settle(pg))  # noqa: E731
        k = pg.evaluate("window.__spectra.cursor['2:0'] ?? 15")
        before, after = state(pg)["dists"][0][k:k + 2]
        tap("right")
        tap("up")
        tap("up")
        assert pg.evaluate("window.__spectra.cursor['2:0']") == k + 1
        assert state(pg)["dists"][0][k + 1] == after + 2
        tap("left")
        tap("down")
        assert state(pg)["dists"][0][k] == before - 1
        tap("save")
        saved = state(pg)["dists"]
        assert "saved" in pg.locator("#note").inner_text()
        key(pg, "7")
        assert state(pg)["dists"] != saved
        tap("recall")
        assert state(pg)["dists"] == saved
        choose(pg, 4)
        tap("pair")  # 9: setting 2's saved pair becomes the two samples
        st = state(pg)
        assert st["dists"][1:] == saved
        tap("next")
        assert pg.evaluate("window.__spectra.active[4]") == 1
        check_card(pg, 1, library(st)["colours"][1])


def test_tablet_keeps_the_editors_wide(browser, base_url):
    with open_page(browser, base_url, TABLET, touch=True) as pg:
        assert pg.evaluate("document.documentElement.scrollWidth") <= TABLET[0]
        for setting in (2, 4):
            choose(pg, setting)
            editors, chart = box(pg, "#editors"), box(pg, "#chroma")
            assert editors["width"] >= 0.9 * (TABLET[0] - 40)
            assert chart["y"] >= editors["y"] + editors["height"]  # below, not beside, the editors
            assert chart["width"] <= 0.5 * TABLET[0]


@pytest.mark.parametrize("size", [DESKTOP, PHONE, TABLET], ids=["desktop", "phone", "tablet"])
def test_screenshots_of_every_setting(browser, base_url, artifacts_dir, size):
    suffix = {DESKTOP: "", PHONE: "_phone", TABLET: "_tablet"}[size]
    with open_page(browser, base_url, size, touch=size != DESKTOP) as pg:
        for setting, keys in SHOW.items():
            choose(pg, setting)
            for k in keys:
                key(pg, k)
            pg.evaluate("window.scrollTo(0, 0)")
            st = state(pg)
            lib = library(st)
            for c in lib["colours"]:
                if c["XYZ"][1] > 1:  # every lit colour is shown as a colour, never black
                    assert max(c["codes"]) > 0, c
            pg.screenshot(path=str(artifacts_dir / f"app_setting{setting}{suffix}.png"))
