"""Issue 28, glitch 5: after a burst of 40 fast key presses the page is exactly right.

The explorer writes only what a repaint changes, keeps its canvases' sizes, and writes the
address and storage once the keys pause (js/view.js, js/editors.js, js/main.js). This checks that
none of that loses a press: once the 40 presses (real key events, as fast as the browser takes
them) are in, the focused bar, its slider value, the patch colours, the numbers, the address and
the undo history all agree with the level the presses reach, worked out here from SPECTRA's rule
(whole levels 0-30, one level per press, clamped at both ends). Timing is measured by
bench/bench_app_latency.py, not here.
"""

from __future__ import annotations

from urllib.parse import parse_qs, urlsplit

import pytest

from appbrowser import check_card, check_patch, library, open_page, settle, state

pytestmark = pytest.mark.browser

SIZE = (1440, 900)
FULL = 30  # SPECTRA's top level
DIGITS = "0123456789abcdefghijklmnopqrstuvwxyz"  # the address's whole-level code (one digit a bin)
PAD_TOP, PAD_BOTTOM = 14, 16  # the bar editor's margins above and below the bars (editors.js)

# 40 presses: 28 up (past the top from any level above 1: the clamp is exercised), then 12 down,
# so the last level lies well inside the bars (16-18), where its top can be read from the pixels
PRESSES = ["ArrowUp"] * 28 + ["ArrowDown"] * 12


def reached(level, presses):
    """The level `presses` reach from `level` on SPECTRA's grid (whole levels, clamped 0-30)."""
    for k in presses:
        level = min(FULL, max(0, level + (1 if k == "ArrowUp" else -1)))
    return level


def decode_whole_levels(text):
    """The address's l<i> parameter for whole levels: "i" and one base-36 digit per bin."""
    assert text[0] == "i", text
    return [DIGITS.index(ch) for ch in text[1:]]


# The painted bar of the cursor's bin: from the canvas's pixels, the first row (from the top, in
# CSS px) in the middle of the bin whose colour is the bin's tint. The cursor's frame covers the
# bin's edges only, the outline is 1.5 px at the level, the labels sit at the left and bottom.
BAR_TOP = """([i, k]) => {
    const cv = document.querySelector(`#editors .editor[data-e='${i}'] canvas`);
    const dpr = cv.width / cv.clientWidth, g = cv.getContext("2d");
    const K = window.__spectra.wl.length, x = Math.floor((k + 0.5) * cv.width / K);
    const t = window.__spectra.model.tints[k].map((v) => v * 255);
    const px = g.getImageData(x, 0, 1, cv.height).data;
    for (let y = 0; y < cv.height; y++) {
        const d = Math.abs(px[4 * y] - t[0]) + Math.abs(px[4 * y + 1] - t[1]) + Math.abs(px[4 * y + 2] - t[2]);
        if (d <= 6 && y > 14 * dpr + 2) return [y / dpr, cv.clientHeight];
    }
    return [null, cv.clientHeight];
}"""


@pytest.mark.parametrize(("setting", "editor"), [(1, 0), (4, 0)])
def test_forty_fast_presses_leave_bar_patches_numbers_address_and_undo_at_the_last_level(
        browser, base_url, setting, editor):
    with open_page(browser, f"{base_url}?s={setting}&b=10", SIZE) as pg:
        bars = f"#editors .editor[data-e='{editor}'] canvas"
        pg.focus(bars)
        settle(pg)
        before = state(pg)
        k = pg.evaluate(f"window.__spectra.cursor['{setting}:{editor}'] ?? Math.floor(window.__spectra.wl.length / 2)")
        undo_before = pg.evaluate(f"window.__spectra.undo[{setting}].length")
        expected = reached(int(before["dists"][editor][k]), PRESSES)
        assert 0 < expected <= FULL  # a visible bar: its top can be found in the pixels

        for key in PRESSES:  # real key events, back to back (no pause for frames or the server)
            pg.keyboard.press(key)

        # at once, before the server's answer or the address is written: the bar shows the level
        assert pg.get_attribute(bars, "aria-valuenow") == str(expected)
        shown = pg.locator(f"#editors .editor[data-e='{editor}'] .cur").inner_text()
        assert shown.endswith(f": {expected} of {FULL}"), shown
        settle(pg)

        after = state(pg)
        assert after["dists"][editor][k] == expected  # exact: whole levels
        untouched = [j for j in range(len(before["dists"][editor])) if j != k]
        # exact: whole levels, the other bins as they were
        assert [after["dists"][editor][j] for j in untouched] == [before["dists"][editor][j] for j in untouched]
        assert pg.get_attribute(bars, "aria-valuenow") == str(expected)

        # the painted bar: its top at the level's height (1 px rounding of the canvas, 1 px slack)
        top, height = pg.evaluate(BAR_TOP, [editor, k])
        assert top is not None
        want = PAD_TOP + (height - PAD_TOP - PAD_BOTTOM) * (1 - expected / FULL)
        assert abs(top - want) <= 2.0, (top, want)

        # patches and numbers: the library's colours for the final distributions
        answer = library(after)
        for i, colour in enumerate(answer["colours"]):
            if pg.locator(f"#patches .patch[data-i='{i}']").count():
                check_patch(pg, i, colour)
            check_card(pg, i, colour)

        # the address holds the final distributions, and one undo step was kept per press
        query = parse_qs(urlsplit(pg.url).query)
        assert query["s"] == [str(setting)]
        assert decode_whole_levels(query[f"l{editor}"][0]) == after["dists"][editor]  # exact: whole levels
        assert pg.evaluate(f"window.__spectra.undo[{setting}].length") == undo_before + len(PRESSES)

        # and a reload of that address (fresh page state) shows the same level
        pg.reload()
        settle(pg)
        assert state(pg)["dists"] == after["dists"]  # exact: whole levels
        assert pg.get_attribute(bars, "aria-valuenow") == str(expected)
