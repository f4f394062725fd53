"""Helpers for the explorer's browser tests: the real server, Debian's Chromium, and the page's
state read back and checked against the library (``spectrocolor.app.compute``)."""

from __future__ import annotations

import contextlib
import json
import socket
import threading
import time
import urllib.error
import urllib.request
from pathlib import Path

import numpy as np

from spectrocolor.app import compute
from spectrocolor.mixing import additive_mix

CHROMIUM_ARGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
                 "--disable-background-networking", "--disable-component-update", "--disable-sync"]
AXE = Path(__file__).parents[1] / "vendor" / "axe-core" / "axe.min.js"
DESKTOP, PHONE, TABLET = (1440, 900), (390, 844), (820, 1180)


@contextlib.contextmanager
def serve():
    """Run the explorer's server on a free loopback port; yield its URL."""
    import uvicorn

    from spectrocolor.app.server import create_app

    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        port = s.getsockname()[1]
    server = uvicorn.Server(uvicorn.Config(create_app(), host="127.0.0.1", port=port,
                                           log_level="warning"))
    thread = threading.Thread(target=server.run, daemon=True)
    thread.start()
    for _ in range(400):
        if server.started:
            break
        time.sleep(0.05)
    url = f"http://127.0.0.1:{port}/"
    try:
        # A page opened before the interactive lane's workers run is refused with 429 and never
        # settles; every browser test starts after the lane has answered once.
        warm_server(url)
        yield url
    finally:
        server.should_exit = True
        thread.join(timeout=10)


@contextlib.contextmanager
def chromium():
    from playwright.sync_api import sync_playwright

    with sync_playwright() as p:
        b = p.chromium.launch(executable_path="/usr/bin/chromium", args=CHROMIUM_ARGS)
        try:
            yield b
        finally:
            b.close()


@contextlib.contextmanager
def open_page(browser, url, size=DESKTOP, touch=False):
    """A fresh context (own storage) and page at `url`, settled; fails on any page error."""
    context = browser.new_context(viewport={"width": size[0], "height": size[1]}, has_touch=touch,
                                  is_mobile=touch)
    page = context.new_page()
    errors = []
    page.on("pageerror", lambda e: errors.append(str(e)))
    try:
        page.goto(url)
        settle(page)
        yield page
        assert not errors, errors
    finally:
        context.close()


def settle(pg):
    pg.wait_for_function("window.__spectra && window.__spectra.settled && !window.__spectra.dirty"
                         " && !window.__spectra.inflight")


def state(pg):
    return pg.evaluate("""() => { const S = window.__spectra;
        return {setting: S.setting, dists: S.dists[S.setting], names: S.names[S.setting],
                server: S.server, local: S.local, normalise: S.normalise, step: S.step,
                gamut: S.gamut, display: S.display, observer: S.observer,
                adaptation: S.adaptation, stale: S.stale, mode5: S.mode5}; }""")


def evaluated(st):
    """The spectra, illuminant and pairs the page's setting evaluates (as the page builds them)."""
    d, k = st["dists"], len(st["dists"][0])
    full = [30.0] * k
    match st["setting"]:
        case 1:
            return [d[0]], None, []
        case 2 | 3:
            return [d[0], d[1]], None, [(0, 1)]
        case 4:
            return [full, d[1], d[2]], d[0], [(1, 2)]
        case 5 if st.get("mode5") == "additive":  # two spotlights: the server adds the lights
            return [full, d[0], d[1], additive_mix(d[0], d[1]).tolist()], None, []
        case 5:
            product = (np.array(d[0]) * np.array(d[1]) / 30).tolist()
            return [full, d[0], d[1], product], None, []


def library(st):
    """The library's answer for what the page shows now, with the page's own options."""
    spectra, illuminant, pairs = evaluated(st)
    return compute.evaluate(float(st["step"]), st["observer"], st["display"], st["normalise"],
                            st["gamut"], spectra, illuminant, pairs, adaptation=st["adaptation"])


def shown_numbers(pg, i):
    card = pg.locator(f"#numbers .card[data-i='{i}']")
    return {k: card.locator(f"td.{k}").inner_text().split()
            for k in ("XYZ", "xy", "lab", "rgb", "codes", "hex")}


def check_card(pg, i, c):
    got = shown_numbers(pg, i)
    # the X Y Z row shows XYZ_row: CIE XYZ, or SPECTRA's one k per channel in "spectra-exact"
    assert got["XYZ"] == [f"{v:.2f}" for v in c.get("XYZ_row", c["XYZ"])]
    assert got["xy"] == [f"{v:.4f}" for v in c["xy"]]
    assert got["lab"] == [f"{v:.1f}" for v in c["lab"]]
    assert got["rgb"] == [f"{v:.3f}" for v in c["rgb_unmapped"]]
    assert got["codes"] == [str(v) for v in c["codes"]]


def patch_rgb(pg, i):
    css = pg.locator(f"#patches .patch[data-i='{i}']").first.evaluate(
        "e => getComputedStyle(e).backgroundColor")
    return [float(v) for v in css[css.index("(") + 1:-1].split(",")[:3]]


def check_patch(pg, i, c):
    np.testing.assert_allclose(patch_rgb(pg, i), np.array(c["rgb_encoded"]) * 255, atol=0.51)


def choose(pg, setting):
    pg.click(f"#tabs [data-setting='{setting}']")
    settle(pg)


def key(pg, k):
    pg.keyboard.press(k)
    settle(pg)


def drag(pg, editor, x0, y0, x1, y1):
    box = pg.locator(f"#editors .editor[data-e='{editor}'] canvas").bounding_box()
    pg.mouse.move(box["x"] + box["width"] * x0, box["y"] + box["height"] * y0)
    pg.mouse.down()
    for t in np.linspace(0, 1, 8)[1:]:
        pg.mouse.move(box["x"] + box["width"] * (x0 + (x1 - x0) * t),
                      box["y"] + box["height"] * (y0 + (y1 - y0) * t))
    pg.mouse.up()
    settle(pg)


def in_viewport(pg, selector):
    """True when the element's box lies wholly inside the viewport."""
    return pg.evaluate("""(sel) => { const r = document.querySelector(sel).getBoundingClientRect();
        return r.height > 0 && r.top >= 0 && r.left >= 0 && r.bottom <= innerHeight + 0.5
            && r.right <= innerWidth + 0.5; }""", selector)


def open_lab(browser, url, size=DESKTOP, timeout_ms=30000):
    """A lab page at ``url`` once its first answer is drawn (``body[data-ready]``); returns the page
    and the list that collects its page errors."""
    page = browser.new_page(viewport={"width": size[0], "height": size[1]})
    errors = []
    page.on("pageerror", lambda e: errors.append(str(e)))
    page.goto(url)
    page.wait_for_selector("body[data-ready=true]", timeout=timeout_ms)
    return page, errors


def warm_server(base_url, limit_s=180.0):
    """Wait until the interactive lane answers (its workers start slowly on a loaded machine,
    and a page started before that is refused with 429)."""
    end = time.monotonic() + limit_s
    while True:
        req = urllib.request.Request(f"{base_url}api/model", data=json.dumps({}).encode(),
                                     headers={"Content-Type": "application/json"})
        try:
            with urllib.request.urlopen(req, timeout=60) as r:
                if r.status == 200:
                    return
        except (urllib.error.URLError, TimeoutError):
            if time.monotonic() > end:
                raise
        time.sleep(1)
