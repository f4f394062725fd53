"""The explorer in a real browser (Playwright driving Debian's Chromium).

For each of SPECTRA's settings: load the seed's presets with its keys, drag bars with the mouse,
and check the numbers on the page and the patch colour against the library's own results for
the same distributions. Screenshots go to the artifacts folder."""

from __future__ import annotations

import socket
import threading
import time

import numpy as np
import pytest

from spectrocolor.app import compute

pytestmark = pytest.mark.browser

CHROMIUM_ARGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
                 "--disable-background-networking", "--disable-component-update", "--disable-sync"]


def free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


@pytest.fixture(scope="module")
def base_url():
    import uvicorn

    from spectrocolor.app.server import create_app

    port = free_port()
    server = uvicorn.Server(uvicorn.Config(create_app(), host="127.0.0.1", port=port,
                                           log_level="warning"))
    thread = threading.Thread(target=server.run, daemon=True)
    thread.start()
    for _ in range(200):
        if server.started:
            break
        time.sleep(0.05)
    yield f"http://127.0.0.1:{port}/"
    server.should_exit = True
    thread.join(timeout=10)


@pytest.fixture(scope="module")
def browser():
    from playwright.sync_api import sync_playwright

    with sync_playwright() as p:
        chromium = p.chromium.launch(executable_path="/usr/bin/chromium", args=CHROMIUM_ARGS)
        yield chromium
        chromium.close()


@pytest.fixture(scope="module")
def page(browser, base_url):
    pg = browser.new_page(viewport={"width": 1280, "height": 800})
    errors = []
    pg.on("pageerror", lambda e: errors.append(str(e)))
    pg.goto(base_url)
    settle(pg)
    yield pg
    assert not errors, errors
    pg.close()


def settle(pg):
    pg.wait_for_function("window.__spectra && window.__spectra.settled && !window.__spectra.dirty")


def state(pg):
    return pg.evaluate("""() => { const S = window.__spectra;
        return {setting: S.setting, dists: S.dists[S.setting], server: S.server, local: S.local,
                normalise: S.normalise, step: S.step}; }""")


def library(st, illuminant=None, pairs=()):
    spectra = st["dists"]
    return compute.evaluate(float(st["step"]), "1931", "sRGB", st["normalise"], "flag", spectra,
                            illuminant, pairs)


def shown_numbers(pg, i):
    card = pg.locator(f"#numbers .card[data-i='{i}']")
    return {k: card.locator(f"td.{k}").inner_text().split() for k in ("XYZ", "xy", "rgb", "codes")}


def check_card(pg, i, c):
    got = shown_numbers(pg, i)
    assert got["XYZ"] == [f"{v:.2f}" for v in c["XYZ"]]
    assert got["xy"] == [f"{v:.4f}" for v in c["xy"]]
    assert got["rgb"] == [f"{v:.3f}" for v in c["rgb_unmapped"]]
    assert got["codes"] == [str(v) for v in c["codes"]]


def patch_rgb(pg, i):
    css = pg.locator(f"#patches .patch[data-i='{i}']").first.evaluate(
        "e => getComputedStyle(e).backgroundColor")
    return [float(v) for v in css[css.index("(") + 1:-1].split(",")[:3]]


def check_patch(pg, i, c):
    np.testing.assert_allclose(patch_rgb(pg, i), np.array(c["rgb_encoded"]) * 255, atol=0.51)


def choose(pg, setting):
    pg.click(f"#tabs button[data-setting='{setting}']")
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


def test_setting1_presets_keys_drag_and_numbers(page, artifacts_dir):
    choose(page, 1)
    for k in "12345678":
        key(page, k)
        st = state(page)
        lib = library(st)["colours"][0]
        check_card(page, 0, lib)
        check_patch(page, 0, lib)
    # key 8 again: the next sunset thickness (d = 0.15), as the seed's formula gives
    key(page, "8")
    st = state(page)
    np.testing.assert_allclose(st["dists"][0], 30 * np.exp(-((700 / compute.grid(10)) ** 4 - 1) * 0.15))
    key(page, "1")
    before = state(page)["dists"][0]
    drag(page, 0, 0.02, 0.9, 0.3, 0.9)  # pull the short-wave bars down, as the seed suggests
    after = state(page)["dists"][0]
    assert after[0] < before[0] and after[5] < before[5] and after[20:] == before[20:]
    lib = library(state(page))["colours"][0]
    check_card(page, 0, lib)
    check_patch(page, 0, lib)
    assert lib["purity"] > library({"dists": [before], "step": 10, "normalise": "fixed"})[
        "colours"][0]["purity"]
    # arrows: move to a bin and raise it by one level
    k = page.evaluate("window.__spectra.cursor['1:0']")
    key(page, "ArrowRight")
    key(page, "ArrowUp")
    st = state(page)
    assert st["dists"][0][k + 1] == after[k + 1] + 1
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
    page.screenshot(path=str(artifacts_dir / "app_setting1.png"))
    key(page, "x")


def test_setting1_cannot_be_reproduced_names_the_channel(page):
    choose(page, 1)
    key(page, "7")  # strong blue: drag everything but 450-470 nm to zero
    drag(page, 0, 0.2, 0.99, 0.99, 0.99)
    drag(page, 0, 0.01, 0.99, 0.08, 0.99)
    lib = library(state(page))["colours"][0]
    status = page.locator("#numbers .card[data-i='0'] .status").inner_text()
    if lib["in_gamut"]:
        pytest.fail(f"expected an out-of-gamut blue, library says {lib}")
    for ch in lib["negative"]:
        assert f"{ch}" in status
    assert status.startswith("cannot be reproduced")
    assert patch_rgb(page, 0) == [0.0, 0.0, 0.0]


def test_js_fast_path_equals_the_library(page):
    choose(page, 1)
    for k, norm in (("1", "fixed"), ("6", "fixed"), ("7", "per-colour")):
        if state(page)["normalise"] != norm:
            key(page, "x")
        key(page, k)
        st = state(page)
        local = st["local"][0]
        lib = library(st)["colours"][0]
        for name in ("XYZ", "xy", "rgb_unmapped", "rgb_linear", "rgb_encoded"):
            np.testing.assert_allclose(local[name], lib[name], rtol=1e-9, atol=1e-9, err_msg=name)
        assert local["codes"] == lib["codes"] and local["in_gamut"] == lib["in_gamut"]
    key(page, "x")


def test_setting2_d65_and_three_band_match_after_x_and_metamer(page, artifacts_dir):
    choose(page, 2)
    key(page, "7")
    key(page, " ")
    key(page, "7")
    st = state(page)
    lib = library(st, pairs=[(0, 1)])
    assert not page.locator("#patches .patchbox.split.metameric").count()
    key(page, "x")
    st = state(page)
    lib = library(st, pairs=[(0, 1)])
    check_card(page, 0, lib["colours"][0])
    check_card(page, 1, lib["colours"][1])
    assert lib["colours"][0]["codes"] == lib["colours"][1]["codes"]
    assert page.locator("#patches .patchbox.split.metameric").count() == 1
    page.screenshot(path=str(artifacts_dir / "app_setting2.png"))
    key(page, "x")
    key(page, " ")
    key(page, "4")  # left green
    page.click("#metamer")
    page.wait_for_function("window.__spectra.names[2][1] === 'smoothest metamer'")
    settle(page)
    lib = library(state(page), pairs=[(0, 1)])
    assert lib["delta_e_2000"][0] < 0.01
    assert page.locator("#patches .patchbox.split.metameric").count() == 1


def test_setting3_transfers_conserve_the_total(page, artifacts_dir):
    choose(page, 3)
    key(page, "6")
    drag(page, 0, 0.44, 0.95, 0.5, 0.95)  # take the light near 540 nm away from the left
    st = state(page)
    np.testing.assert_allclose(np.add(*st["dists"]), 30)
    assert min(st["dists"][0]) == 0 and max(st["dists"][1]) == 30
    lib = library(st, pairs=[(0, 1)])
    check_card(page, 0, lib["colours"][0])
    check_card(page, 1, lib["colours"][1])
    check_patch(page, 1, lib["colours"][1])
    key(page, "3")
    page.screenshot(path=str(artifacts_dir / "app_setting3.png"))


def test_setting4_metamers_under_illuminants(page, artifacts_dir):
    choose(page, 4)
    de = {}
    for ill in "24":
        key(page, ill)
        key(page, "6")
        st = state(page)
        spectra = [[30.0] * 31, st["dists"][1], st["dists"][2]]
        lib = compute.evaluate(10.0, "1931", "sRGB", st["normalise"], "flag", spectra,
                               st["dists"][0], [(1, 2)])
        for i in range(3):
            check_card(page, i, lib["colours"][i])
        check_patch(page, 1, lib["colours"][1])
        de[ill] = lib["delta_e_2000"][0]
        assert f"{de[ill]:.2f}" in page.locator("#numbers").inner_text()
        if ill == "2":
            page.screenshot(path=str(artifacts_dir / "app_setting4.png"))
    assert de["2"] < 0.3 < 1.5 < de["4"]


def test_setting5_moss_green_filters(page, artifacts_dir):
    choose(page, 5)
    key(page, "7")
    st = state(page)
    f1, f2 = np.array(st["dists"][0]), np.array(st["dists"][1])
    spectra = [[30.0] * 31, f1.tolist(), f2.tolist(), (f1 * f2 / 30).tolist()]
    lib = compute.evaluate(10.0, "1931", "sRGB", st["normalise"], "flag", spectra, None, [])
    for i in range(4):
        check_card(page, i, lib["colours"][i])
    check_patch(page, 3, lib["colours"][3])
    assert lib["colours"][3]["dominant_nm"] > 590
    page.screenshot(path=str(artifacts_dir / "app_setting5.png"))


def test_readable_on_a_tablet(page, artifacts_dir):
    page.set_viewport_size({"width": 820, "height": 1180})
    choose(page, 2)
    page.screenshot(path=str(artifacts_dir / "app_tablet.png"))
    width = page.evaluate("document.documentElement.scrollWidth")
    page.set_viewport_size({"width": 1280, "height": 800})
    assert width <= 820


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
    finally:
        context.close()
