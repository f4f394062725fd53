"""Projector mode of the explorer (issue 28, item 4), in real Chromium with the real server.

Key P or the Projector button enters it, P, Escape or the Leave button leaves it (focus goes back
to where it was); N or a button hides and shows the numbers; B, G, W or the buttons choose a black,
mid-grey or white surround (the seed's "piece of white cardboard" with a hole, seed 002, question 1).
The large patches must have exactly the colours of the explorer's own patches (the same
computation), which must be the library's for the page's state (``compute.evaluate``, independent of
the page); the explorer's state and the mode's choices survive leaving and entering; axe finds
nothing serious; at desktop, laptop, tablet and phone sizes every patch, name and control lies
inside the viewport and the names are large. Screenshots go to the artifacts folder and /tmp/h28p.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from appbrowser import AXE, DESKTOP, PHONE, TABLET, choose, key, library, open_page, settle, state, warm_server

pytestmark = pytest.mark.browser

LAPTOP = (1366, 768)
SHOTS = Path("/tmp/h28p")
#: The patches the mode shows per setting (data-i of the explorer's patches): the colour(s) compared.
SHOWN = {1: [0], 2: [0, 1], 3: [0, 1], 4: [1, 2], 5: [1, 2, 3]}
SURROUND_RGB = {"black": "rgb(0, 0, 0)", "grey": "rgb(128, 128, 128)", "white": "rgb(255, 255, 255)"}


@pytest.fixture(autouse=True, scope="module")
def _warm(base_url):
    warm_server(base_url)


def is_open(pg):
    return pg.evaluate("Boolean(document.querySelector('#projector') && document.querySelector('#projector').open)")


def projected(pg, i):
    return pg.locator(f"#projector .pj-item[data-i='{i}'] .pj-patch").evaluate(
        "e => getComputedStyle(e).backgroundColor")


def explorer(pg, i):
    return pg.locator(f"#patches .patch[data-i='{i}']").first.evaluate("e => getComputedStyle(e).backgroundColor")


def rgb(css):
    return [float(v) for v in css[css.index("(") + 1:-1].split(",")[:3]]


def wait_projected(pg):
    """The mode copies the explorer's repaint in the next animation frame."""
    pg.evaluate("() => new Promise((ok) => requestAnimationFrame(() => requestAnimationFrame(ok)))")


def check_colours(pg):
    st = state(pg)
    lib = library(st)["colours"]
    for i in SHOWN[st["setting"]]:
        # exact: the mode copies the explorer's own colour string, so the computed colours are equal
        assert projected(pg, i) == explorer(pg, i), (st["setting"], i)
        # and that colour is the library's (8-bit rounding of the encoded value: half a code)
        np.testing.assert_allclose(rgb(projected(pg, i)), np.array(lib[i]["rgb_encoded"]) * 255, atol=0.51)
        assert pg.locator(f"#projector .pj-item[data-i='{i}'] .pj-name").inner_text() == \
            pg.locator(f"#patches .patch[data-i='{i}'] > .tag").inner_text()


def test_key_p_enters_escape_and_p_leave_focus_returns(browser, base_url):
    with open_page(browser, base_url) as pg:
        choose(pg, 2)
        pg.locator("#tab-2").focus()
        key(pg, "p")
        assert is_open(pg)
        assert pg.evaluate("document.activeElement.closest('#projector') !== null")
        assert pg.locator("#projector .pj-item").count() == 2
        wait_projected(pg)
        check_colours(pg)
        pg.keyboard.press("Escape")
        assert not is_open(pg)
        assert pg.evaluate("document.activeElement.id") == "tab-2"
        key(pg, "P")
        assert is_open(pg)
        pg.keyboard.press("p")
        assert not is_open(pg)
        # typing a "p" into a field does not open it
        pg.locator("#display").focus()
        pg.keyboard.press("p")
        assert not is_open(pg)


def test_buttons_numbers_and_surrounds_and_they_are_kept(browser, base_url):
    with open_page(browser, base_url, DESKTOP) as pg:
        choose(pg, 3)
        pg.click("#projector-open")
        assert is_open(pg)
        wait_projected(pg)
        num = pg.locator("#projector .pj-item[data-i='0'] .pj-num")
        assert num.is_visible() and "x y 0." in num.inner_text()
        assert pg.locator("#projector #pj-de").inner_text().startswith("ΔE00 ")
        pg.click("#pj-numbers")
        assert not num.is_visible() and not pg.locator("#pj-de").is_visible()
        assert pg.get_attribute("#pj-numbers", "aria-pressed") == "false"
        # the patch's text alternative loses its hex code too
        assert "#" not in pg.get_attribute("#projector .pj-item[data-i='0'] .pj-patch", "aria-label")
        pg.keyboard.press("n")
        assert num.is_visible() and pg.get_attribute("#pj-numbers", "aria-pressed") == "true"
        surround = pg.locator("#projector")
        for name, k in (("white", "w"), ("grey", "g"), ("black", "b")):
            pg.keyboard.press(k)
            assert surround.evaluate("e => getComputedStyle(e).backgroundColor") == SURROUND_RGB[name]
            assert pg.get_attribute(f"#projector [data-surround='{name}']", "aria-pressed") == "true"
        pg.click("#projector [data-surround='white']")
        assert surround.evaluate("e => getComputedStyle(e).backgroundColor") == SURROUND_RGB["white"]
        pg.keyboard.press("n")  # numbers hidden
        pg.click("#pj-leave")
        assert not is_open(pg)
        assert pg.evaluate("document.activeElement.id") == "projector-open"
        pg.reload()
        settle(pg)
        pg.click("#projector-open")  # the mode's choices came back (localStorage), after a reload too
        assert surround.evaluate("e => getComputedStyle(e).backgroundColor") == SURROUND_RGB["white"]
        assert not pg.locator("#projector .pj-item[data-i='0'] .pj-num").is_visible()


def test_colours_equal_the_explorer_in_every_setting_and_state_survives(browser, base_url):
    with open_page(browser, base_url) as pg:
        for setting in (1, 2, 3, 4, 5):
            choose(pg, setting)
            key(pg, "3")
            before = state(pg)["dists"]
            key(pg, "p")
            wait_projected(pg)
            assert pg.locator("#projector .pj-item").count() == len(SHOWN[setting])
            check_colours(pg)
            pg.keyboard.press("Escape")
            assert state(pg)["dists"] == before  # exact: the mode never touches the levels
        # the explorer's keys 1–8 and X work inside the mode, and the patches follow
        choose(pg, 4)
        key(pg, "p")
        old = [projected(pg, i) for i in (1, 2)]
        key(pg, "6")  # setting 4's key 6: the metameric yellow samples (the grey ones were shown)
        wait_projected(pg)
        check_colours(pg)
        assert [projected(pg, i) for i in (1, 2)] != old
        after = state(pg)
        pg.keyboard.press("Escape")
        assert state(pg)["dists"] == after["dists"] and state(pg)["names"] == after["names"]
        key(pg, "p")  # and in again: the same patches
        wait_projected(pg)
        check_colours(pg)


@pytest.mark.parametrize("size", [DESKTOP, PHONE], ids=["desktop", "phone"])
def test_axe_finds_nothing_serious_in_projector_mode(browser, base_url, size):
    run = """async () => { const r = await axe.run(document, {runOnly: {type: "tag",
        values: ["wcag2a", "wcag2aa", "wcag21a", "wcag21aa", "wcag22aa"]}});
      return r.violations.filter((v) => v.impact === "serious" || v.impact === "critical")
        .map((v) => ({id: v.id, nodes: v.nodes.slice(0, 3).map((n) => n.target.join(" "))})); }"""
    with open_page(browser, base_url, size) as pg:
        pg.add_script_tag(path=str(AXE))
        choose(pg, 4)
        key(pg, "p")
        found = {}
        for k in ("b", "g", "w"):
            pg.keyboard.press(k)
            found[k] = pg.evaluate(run)
        pg.keyboard.press("n")
        found["hidden numbers"] = pg.evaluate(run)
        assert not any(found.values()), found


@pytest.mark.parametrize("size", [DESKTOP, LAPTOP, TABLET, PHONE], ids=["desktop", "laptop", "tablet", "phone"])
def test_readable_and_nothing_clipped_at_four_sizes(browser, base_url, size, artifacts_dir):
    SHOTS.mkdir(exist_ok=True)
    phone = size == PHONE
    with open_page(browser, base_url, size, touch=phone) as pg:
        for setting in (2, 5):
            choose(pg, setting)
            if phone:  # a finger on the button under the bars (the header has no room for one)
                assert not pg.locator("#projector-open").is_visible()
                pg.tap("#projector-touch")
            else:
                pg.click("#projector-open")
            assert is_open(pg)
            wait_projected(pg)
            inside = pg.evaluate("""() => [...document.querySelectorAll(
                '#projector .pj-patch, #projector .pj-name, #projector .pj-num, #projector .pj-bar button,'
                + ' #pj-de, #pj-caption')]
                .filter((e) => e.getClientRects().length).map((e) => { const r = e.getBoundingClientRect();
                  return [e.className || e.id, r.left >= 0 && r.top >= 0 && r.right <= innerWidth + 0.5
                    && r.bottom <= innerHeight + 0.5 && r.width > 0]; })""")
            assert inside and all(ok for _, ok in inside), [n for n, ok in inside if not ok]
            # readable from the back of a room: names at least 16 px, patches a good part of the screen
            px = pg.locator("#projector .pj-name").first.evaluate("e => parseFloat(getComputedStyle(e).fontSize)")
            assert px >= 16
            box = pg.locator("#projector .pj-patch").first.bounding_box()
            assert min(box["width"], box["height"]) >= 0.2 * min(size)
            name = f"projector_{size[0]}x{size[1]}_setting{setting}.png"
            pg.screenshot(path=str(SHOTS / name))
            pg.screenshot(path=str(artifacts_dir / name))
            if setting == 2:  # the seed's cardboard: a white surround, numbers hidden
                pg.keyboard.press("w")
                pg.keyboard.press("n")
                name = f"projector_{size[0]}x{size[1]}_setting2_white_no_numbers.png"
                pg.screenshot(path=str(SHOTS / name))
                pg.screenshot(path=str(artifacts_dir / name))
                pg.keyboard.press("b")
                pg.keyboard.press("n")
            pg.keyboard.press("Escape")
