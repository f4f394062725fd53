"""Back after a demo (issue 28, items 2 and 6), in Chromium with the real server.

A demonstration is one step of the browser's history: on a page a teacher has edited, loading a
demo from the Demos panel and pressing Back returns the page to the edited state (its address and
its levels), and Forward returns to the demo. It is one undo step too: Ctrl+Z (or the Undo button)
right after a demo gives back the setting's levels from before it. A lab's demo is one history
step in the same way (its state is in the address's hash)."""

from __future__ import annotations

import pytest

from appbrowser import open_lab, open_page, settle, state

pytestmark = pytest.mark.browser

DEMO = "straw-short-waves"  # setting 1's demo (static/demos/straw-short-waves.json)


def _levels(pg):
    st = state(pg)
    return {"setting": st["setting"], "dists": st["dists"], "names": st["names"]}


def _edited_setting_1(pg):
    """Setting 1 with preset 4 and then one bar raised by a key press: not a demo's state."""
    pg.keyboard.press("4")
    settle(pg)
    pg.keyboard.press("ArrowUp")
    settle(pg)
    return pg.url, _levels(pg)


def _load_demo(pg, demo_id):
    pg.wait_for_selector("body[data-demos=ready]")
    if pg.locator("#demos-panel").is_hidden():
        pg.click("#demos-open")
    pg.click(f"#demos-list button[data-demo='{demo_id}']")
    pg.wait_for_selector(f"body[data-demo='{demo_id}:state']")
    settle(pg)
    return pg.url, _levels(pg)


def test_back_after_a_demo_returns_to_the_edited_page_and_forward_to_the_demo(browser, base_url):
    with open_page(browser, base_url + "?s=1") as pg:
        before_url, before = _edited_setting_1(pg)
        assert "(edited)" in pg.locator("#editors .pname").inner_text()
        demo_url, demo = _load_demo(pg, DEMO)
        assert demo_url != before_url and demo["dists"] != before["dists"]
        pg.go_back()
        settle(pg)
        assert pg.url == before_url
        assert _levels(pg) == before  # exact: whole levels 0-30, compared as the page holds them
        assert "(edited)" in pg.locator("#editors .pname").inner_text()
        pg.go_forward()
        settle(pg)
        assert pg.url == demo_url
        assert _levels(pg) == demo
        pg.go_back()  # and back again: the history holds both, in order
        settle(pg)
        assert _levels(pg) == before


def test_a_key_press_just_before_the_demo_is_kept_by_back(browser, base_url):
    """The address is written after the frame (at most every 120 ms): a demo chosen at once after
    a key press must not leave the press out of the history entry Back returns to."""
    with open_page(browser, base_url + "?s=1") as pg:
        _load_demo(pg, DEMO)  # once, so that the demo's second load waits for no request
        pg.go_back()
        settle(pg)
        pg.keyboard.press("4")
        settle(pg)
        preset = _levels(pg)
        # the press and the demo's click in one task: the address is not yet written when the
        # demo is chosen
        pressed = pg.evaluate("""() => { const cv = document.querySelector('#editors canvas'); cv.focus();
            cv.dispatchEvent(new KeyboardEvent('keydown', {key: 'ArrowUp', bubbles: true}));
            const dists = window.__spectra.dists[1].map((d) => d.slice());
            document.querySelector("#demos-list button[data-demo='straw-short-waves']").click();
            return dists; }""")
        assert pressed != preset["dists"]  # the press did change a bar
        pg.wait_for_selector(f"body[data-demo='{DEMO}:state']")
        settle(pg)
        pg.go_back()
        settle(pg)
        assert _levels(pg)["dists"] == pressed
        pg.reload()  # the address itself holds the press (not only the page's memory)
        settle(pg)
        assert "(edited)" in pg.locator("#editors .pname").inner_text()
        assert _levels(pg)["dists"] == pressed


def test_undo_after_a_demo_gives_back_the_levels_from_before_it(browser, base_url):
    with open_page(browser, base_url + "?s=1") as pg:
        _, before = _edited_setting_1(pg)
        _, demo = _load_demo(pg, DEMO)
        assert pg.locator("#undo").is_enabled()
        pg.keyboard.press("Control+z")
        settle(pg)
        assert _levels(pg) == before
        pg.keyboard.press("Control+Shift+z")  # redo: the demo again
        settle(pg)
        assert _levels(pg) == demo
        pg.click("#undo")
        settle(pg)
        assert _levels(pg) == before


def test_back_after_a_lab_demo_returns_to_the_lab_as_it_was(browser, base_url):
    page, errors = open_lab(browser, base_url + "labs/thinfilm#d=123", timeout_ms=60000)
    try:
        page.wait_for_selector("#thickness")
        assert page.input_value("#thickness") == "123"
        before_url = page.url
        page.wait_for_selector("body[data-demos=ready]")
        page.click("#demos-open")
        page.click("#demos-list button[data-demo='soap-film-thinning']")
        page.wait_for_selector("body[data-demo='soap-film-thinning:state']")
        demo_url = page.url
        assert demo_url != before_url
        demo_thickness = page.input_value("#thickness")
        page.go_back()
        page.wait_for_function("document.querySelector('#thickness').value === '123'")
        assert page.url == before_url
        page.go_forward()
        page.wait_for_function("(v) => document.querySelector('#thickness').value === v", arg=demo_thickness)
        assert page.url == demo_url
        assert not errors, errors
    finally:
        page.close()
