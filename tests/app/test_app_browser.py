"""The explorer in a real browser (Playwright driving Debian's Chromium).

For each of SPECTRA's settings: load the seed's presets with its keys, drag bars with the mouse,
and check the numbers on the page and the patch colour against the library's own results for
the same distributions. Screenshots go to the artifacts folder."""

from __future__ import annotations

import numpy as np
import pytest

from appbrowser import check_card, check_patch, choose, drag, key, library, patch_rgb, settle, state
from spectrocolor import mixing
from spectrocolor.app import compute

pytestmark = pytest.mark.browser


@pytest.fixture(scope="module")
def page(browser, base_url):
    context = browser.new_context(viewport={"width": 1280, "height": 800})
    pg = context.new_page()
    errors = []
    pg.on("pageerror", lambda e: errors.append(str(e)))
    pg.goto(base_url)
    settle(pg)
    yield pg
    assert not errors, errors
    context.close()


def test_setting1_presets_keys_drag_and_numbers(page, artifacts_dir):
    choose(page, 1)
    for k in "12345678":
        key(page, k)
        lib = library(state(page))["colours"][0]
        check_card(page, 0, lib)
        check_patch(page, 0, lib)
    # key 8 again: the next sunset thickness (d = 0.15), as the seed's formula gives
    key(page, "8")
    st = state(page)
    np.testing.assert_allclose(st["dists"][0], 30 * np.exp(-((700 / compute.grid(10)) ** 4 - 1) * 0.15),
                               atol=0.5)  # whole levels in SPECTRA's 31-level mode
    key(page, "1")
    before = state(page)
    drag(page, 0, 0.02, 0.9, 0.3, 0.9)  # pull the short-wave bars down, as the seed suggests
    after = state(page)
    assert after["dists"][0][0] < before["dists"][0][0] and after["dists"][0][5] < before["dists"][0][5]
    assert after["dists"][0][20:] == before["dists"][0][20:]
    assert "(edited)" in page.locator("#editors .editor[data-e='0'] .pname").inner_text()
    lib = library(after)["colours"][0]
    check_card(page, 0, lib)
    check_patch(page, 0, lib)
    assert lib["purity"] > library(before)["colours"][0]["purity"]
    # arrows: move to a bin and raise it by one level
    k = page.evaluate("window.__spectra.cursor['1:0']")
    key(page, "ArrowRight")
    key(page, "ArrowUp")
    st = state(page)
    assert st["dists"][0][k + 1] == after["dists"][0][k + 1] + 1
    # S saves, 0 recalls
    saved = st["dists"][0]
    key(page, "s")
    key(page, "5")
    key(page, "0")
    assert state(page)["dists"][0] == saved
    # X: alternative B, "Optimised!"
    key(page, "1")
    key(page, "x")
    st = state(page)
    assert st["normalise"] == "per-colour"
    assert "Optimised!" in page.locator("#numbers .card[data-i='0'] .status").inner_text()
    check_card(page, 0, library(st)["colours"][0])
    key(page, "x")
    assert state(page)["normalise"] == "fixed"


def strong_blue(page):
    """Setting 1, key 7 (blue), then everything but 450-470 nm dragged to zero: outside sRGB."""
    choose(page, 1)
    key(page, "7")
    drag(page, 0, 0.2, 0.99, 0.99, 0.99)
    drag(page, 0, 0.01, 0.99, 0.08, 0.99)
    lib = library(state(page))["colours"][0]
    assert not lib["in_gamut"], lib
    return lib


def test_out_of_gamut_default_shows_the_nearest_colour_with_a_badge(page):
    lib = strong_blue(page)
    card = page.locator("#numbers .card[data-i='0']")
    badge = card.locator(".badge")
    assert badge.is_visible()
    text = badge.locator(".badge-text").inner_text()
    assert lib["gamut_applied"] and lib["gamut_applied"] != "flag"
    for ch in lib["negative"]:
        assert f"{ch} negative" in text
    assert max(patch_rgb(page, 0)) > 20  # the nearest displayable colour, not a black patch
    check_patch(page, 0, lib)
    # SPECTRA's strict behaviour is one click away
    badge.locator("button").click()
    settle(page)
    st = state(page)
    assert st["gamut"] == "flag" and page.locator("#gamut").input_value() == "flag"
    status = card.locator(".status").inner_text()
    assert status.startswith("cannot be reproduced")
    for ch in lib["negative"]:
        assert ch in status
    assert patch_rgb(page, 0) == [0.0, 0.0, 0.0]  # exact: the flagged patch is painted black, codes 0
    card.locator(".badge button").click()  # and back
    settle(page)
    assert state(page)["gamut"] == lib["gamut_applied"]


def test_setting2_d65_and_three_band_match_after_x_and_metamer(page, artifacts_dir):
    choose(page, 2)
    key(page, "7")
    key(page, " ")
    key(page, "7")
    key(page, "x")
    st = state(page)
    lib = library(st)
    check_card(page, 0, lib["colours"][0])
    check_card(page, 1, lib["colours"][1])
    same = lib["colours"][0]["codes"] == lib["colours"][1]["codes"]
    assert page.locator("#patches .patchbox.split.metameric").count() == int(same)
    assert lib["delta_e_2000_shown"][0] < 1.0
    key(page, "x")
    key(page, " ")
    key(page, "4")  # left green
    page.click("#metamer")
    page.wait_for_function("window.__spectra.names[2][1] === 'smoothest metamer'")
    settle(page)
    lib = library(state(page))
    assert lib["delta_e_2000"][0] < 0.01
    assert page.locator("#patches .patchbox.split.metameric").count() == 1


def test_setting3_transfers_conserve_the_total(page):
    choose(page, 3)
    key(page, "6")
    drag(page, 0, 0.44, 0.95, 0.5, 0.95)  # take the light near 540 nm away from the left
    st = state(page)
    np.testing.assert_allclose(np.add(*st["dists"]), 30)
    assert min(st["dists"][0]) == 0 and max(st["dists"][1]) == 30
    lib = library(st)
    check_card(page, 0, lib["colours"][0])
    check_card(page, 1, lib["colours"][1])
    check_patch(page, 1, lib["colours"][1])
    # a key edit on either side is the library's complementary edit (clipped at 0 and 30)
    key(page, "1")
    for side, arrow in ((0, "ArrowUp"), (1, "ArrowDown"), (1, "ArrowUp")):
        if page.evaluate("window.__spectra.active[3]") != side:
            key(page, " ")
        before = state(page)["dists"]
        k = page.evaluate(f"window.__spectra.cursor['3:{side}'] ?? 15")
        key(page, arrow)
        mine, other = before[side], before[1 - side]
        level = mine[k] + (1 if arrow == "ArrowUp" else -1)
        want = mixing.complementary_edit(mine, other, k, level, full=30)
        got = state(page)["dists"]
        assert got[side] == want[0].tolist() and got[1 - side] == want[1].tolist()


def test_setting3_fig12_moves_make_the_pair_metameric(page):
    """Seed 002, Fig. 12: from default 2, move the light at 560-590 nm to the right side; the
    two sides then have the same colour. The button applies the library's suggested moves with
    the complementary rule (spectrocolor.mixing.complementary_edit)."""
    choose(page, 3)
    q = next(q for q in compute.presets(10.0)["setting3"] if q["key"] == "2")
    page.click("#actions [data-moves='2']")
    settle(page)
    left, right = np.array(q["left"], float), np.array(q["right"], float)
    for k, level in q["moves"]:
        left, right = mixing.complementary_edit(left, right, k, level, full=30)
    st = state(page)
    assert st["dists"] == [left.tolist(), right.tolist()]
    lib = library(st)
    check_card(page, 0, lib["colours"][0])
    assert lib["delta_e_2000"][0] < 0.5
    assert f"{lib['delta_e_2000'][0]:.2f}" in page.locator("#numbers .de-card").inner_text()
    key(page, "Control+z")  # one undo step back to before the button
    assert state(page)["dists"] != st["dists"]


def test_setting4_metamers_under_illuminants(page):
    choose(page, 4)
    de = {}
    for ill in "24":
        key(page, ill)
        key(page, "6")
        st = state(page)
        lib = library(st)
        for i in range(3):
            check_card(page, i, lib["colours"][i])
        check_patch(page, 1, lib["colours"][1])
        de[ill] = lib["delta_e_2000"][0]
        assert f"{de[ill]:.2f}" in page.locator("#numbers .de-card").inner_text()
    assert de["2"] < 0.5 < 1.5 < de["4"]


def test_setting5_moss_green_filters(page):
    choose(page, 5)
    key(page, "7")
    st = state(page)
    lib = library(st)
    for i in range(4):
        check_card(page, i, lib["colours"][i])
    check_patch(page, 3, lib["colours"][3])
    assert lib["colours"][3]["dominant_nm"] > 590
    # the light through both filters is the library's subtractive mix of the two
    both = mixing.subtractive_mix(st["dists"][0], st["dists"][1], full=30)
    np.testing.assert_allclose(st["server"]["colours"][3]["XYZ"], compute.evaluate(
        10.0, st["observer"], st["display"], st["normalise"], st["gamut"], [both.tolist()],
        adaptation=st["adaptation"])["colours"][0]["XYZ"], rtol=1e-12)


def test_touch_drag_edits_bars_on_a_tablet(browser, base_url, artifacts_dir):
    """A finger drag (real touch events through Chromium's input pipeline) edits the bars, and the
    numbers shown are the library's for the edited distribution."""
    context = browser.new_context(viewport={"width": 820, "height": 1180}, has_touch=True, is_mobile=True)
    try:
        pg = context.new_page()
        pg.goto(base_url)
        settle(pg)
        key(pg, "3")  # grey: every bar at the same level
        before = state(pg)["dists"][0][:]
        box = pg.locator("#editors .editor[data-e='0'] canvas").bounding_box()
        cdp = context.new_cdp_session(pg)
        y = box["y"] + 20  # near the top of the plot: a high level
        xs = [box["x"] + box["width"] * f for f in np.linspace(0.05, 0.45, 10)]
        cdp.send("Input.dispatchTouchEvent", {"type": "touchStart", "touchPoints": [{"x": xs[0], "y": y}]})
        for x in xs[1:]:
            cdp.send("Input.dispatchTouchEvent", {"type": "touchMove", "touchPoints": [{"x": x, "y": y}]})
        cdp.send("Input.dispatchTouchEvent", {"type": "touchEnd", "touchPoints": []})
        settle(pg)
        st = state(pg)
        after = st["dists"][0]
        changed = [k for k in range(len(after)) if after[k] != before[k]]
        assert len(changed) >= 8, changed  # the finger swept across about 40 % of the bars
        assert all(after[k] > before[k] for k in changed)
        check_card(pg, 0, library(st)["colours"][0])
        pg.screenshot(path=str(artifacts_dir / "app_touch.png"))
        assert "(edited)" in pg.locator("#editors .pname").inner_text()
    finally:
        context.close()


BLANK = """() => { const c = document.getElementById('ID');  // how many pixels are drawn
    const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
    let n = 0; for (let i = 3; i < d.length; i += 4) if (d[i] > 0) n++; return n; }"""


def test_self_explaining_numbers_diagram_and_step4(page):
    """Units and explanations on every number, hex beside the codes, a diagram with tick values
    and a legend in the patch colours, the emitted light of step 4 and the display's white."""
    choose(page, 1)
    key(page, "4")
    st = state(page)
    lib = library(st)["colours"][0]
    card = page.locator("#numbers .card[data-i='0']")
    heads = card.locator("th")
    assert heads.count() == 7  # X Y Z, L M S, x y, L*a*b*, linear RGB, codes, λd
    for i in range(heads.count()):
        assert len(heads.nth(i).get_attribute("title")) > 20  # an explanation, not just a label
    assert "Y = 100 for the full spectrum" in card.locator("th").first.get_attribute("title")
    assert card.locator("td.hex").inner_text() == "#" + "".join(f"{c:02x}" for c in lib["codes"])
    # the diagram: tick values on both axes, a legend whose swatch is the patch colour
    ticks = page.eval_on_selector_all("#chroma text.tick", "es => es.map((e) => e.textContent)")
    assert [f"{v / 10:.1f}" for v in range(9)] == sorted(set(ticks))
    swatch = page.locator("#legend li[data-i='0'] .key").evaluate(
        "e => getComputedStyle(e).backgroundColor")
    assert swatch == page.locator("#patches .patch[data-i='0']").evaluate(
        "e => getComputedStyle(e).backgroundColor")
    assert st["names"][0] in page.locator("#legend").inner_text()
    page.check("#locus-fill")
    assert page.locator("#chroma .locus.filled").count() == 1
    page.uncheck("#locus-fill")
    # step 4: the emitted light is drawn beside the patch (non-blank canvas)
    assert page.locator("#emitted-box").is_visible()
    assert page.evaluate(BLANK.replace("ID", "emitted")) > 200
    # the display's white point and correlated colour temperature, from the library
    for display in ("sRGB", "SPECTRA 7000K"):
        page.select_option("#display", display)
        settle(page)
        model = compute.model(10.0, "1931", display)
        note = page.locator("#white-note").inner_text()
        assert f"CCT {round(model['display_white']['cct_K'])} K" in note
        assert f"x {model['display_white']['xy'][0]:.4f}" in note
        # SPECTRA's Figs. 9 and 10 for this display: primaries' spectra and excitation function
        page.evaluate("document.getElementById('display-light').open = true")
        page.wait_for_function("document.getElementById('primary-sources').textContent.length > 0")
        assert page.locator("#primary-sources").inner_text() == "; ".join(
            dict.fromkeys(model["emission"]["sources"]))
        for canvas in ("primaries", "excitation"):
            assert page.evaluate(BLANK.replace("ID", canvas)) > 100
        page.evaluate("document.getElementById('display-light').open = false")
    page.select_option("#display", "sRGB")
    settle(page)
    choose(page, 2)
    assert not page.locator("#emitted-box").is_visible()  # step 4's graph belongs to setting 1
