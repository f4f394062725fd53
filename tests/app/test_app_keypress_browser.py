"""Issue 28, glitch 5: a burst of arrow keys on the bars. The page used to write the address and
localStorage on every press (a frame missed on up to 39 % of presses, and Chromium ignores an
address changed more than 200 times in 10 s); now it writes them after the frame, at most once
per frame, and always ends with the last press: the address reloads exactly what was on screen.
This checks behaviour, not timing (bench/bench_app_latency.py measures the time per press)."""

from __future__ import annotations

import json

import pytest

from appbrowser import open_page, settle, state

pytestmark = pytest.mark.browser

SIZE = (1280, 800)

# Every write of the address or of storage, with the number of the animation frame it fell in.
COUNT_WRITES = """(() => {
    window.__frame = 0; window.__writes = [];
    const tick = () => { window.__frame++; requestAnimationFrame(tick); }; requestAnimationFrame(tick);
    for (const kind of ['pushState', 'replaceState']) {
        const original = History.prototype[kind];
        History.prototype[kind] = function (...args) { window.__writes.push([kind, window.__frame]);
            return original.apply(this, args); };
    }
    const setItem = Storage.prototype.setItem;
    Storage.prototype.setItem = function (...args) { window.__writes.push(['setItem', window.__frame]);
        return setItem.apply(this, args); };
})()"""

# Bursts of presses as a fast keyboard (or a test) delivers them: `per` presses within one frame,
# `bursts` times, each burst in its own frame.
BURSTS = """async ([keys, per]) => {
    const target = document.querySelector("#editors .editor[data-e='0'] canvas");
    target.focus();
    for (let i = 0; i < keys.length; i += per) {
        for (const key of keys.slice(i, i + per)) {
            target.dispatchEvent(new KeyboardEvent('keydown', {key, bubbles: true, cancelable: true}));
        }
        await new Promise((done) => requestAnimationFrame(() => done()));
    }
}"""


def test_a_burst_of_key_presses_writes_once_per_frame_and_keeps_the_last_press(browser, base_url):
    with open_page(browser, base_url, SIZE) as pg:
        pg.evaluate(COUNT_WRITES)
        before = state(pg)
        cursor = pg.evaluate("window.__spectra.cursor['1:0'] ?? Math.floor(window.__spectra.wl.length / 2)")
        level = before["dists"][0][cursor]
        keys = ["ArrowUp"] * 40 + ["ArrowDown"] * 25  # 65 presses, 5 to a frame
        pg.evaluate("window.__writes = []")
        pg.evaluate(BURSTS, [keys, 5])
        settle(pg)
        after = state(pg)
        # SPECTRA's bars hold whole levels 0-30: 40 up from `level` stops at 30, then 25 down
        expected = min(30, level + 40) - 25
        assert after["dists"][0][cursor] == expected  # exact: whole levels
        writes = pg.evaluate("window.__writes")
        for kind in ("replaceState", "setItem"):
            frames = [f for k, f in writes if k == kind]
            assert frames, kind  # the state was written
            assert len(frames) == len(set(frames)), (kind, frames)  # never twice in one frame
            assert len(frames) < len(keys) / 5, (kind, len(frames))  # coalesced: fewer than the bursts
        assert not [k for k, _ in writes if k == "pushState"]  # a key press adds no history entry
        stored = json.loads(pg.evaluate("localStorage.getItem('spectrocolor:work')"))
        assert stored["dists"]["1"][0] == after["dists"][0]  # exact: whole levels, the last press
        pg.reload()
        settle(pg)
        assert state(pg)["dists"] == after["dists"]  # exact: the address reproduces the last press


def test_the_last_press_is_written_when_the_page_is_left_at_once(browser, base_url):
    with open_page(browser, base_url, SIZE) as pg:
        pg.focus("#editors .editor[data-e='0'] canvas")
        pg.evaluate(BURSTS, [["ArrowDown"] * 3, 3])
        dists = pg.evaluate("window.__spectra.dists[1]")  # read at once, before anything settles
        pg.evaluate("window.dispatchEvent(new PageTransitionEvent('pagehide'))")
        stored = json.loads(pg.evaluate("localStorage.getItem('spectrocolor:work')"))
        assert stored["dists"]["1"] == dists  # exact: whole levels
        settle(pg)
