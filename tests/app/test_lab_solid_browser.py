"""The object-colour solid lab in Debian's Chromium: it turns, cuts and shows a mismatch region."""

from __future__ import annotations

import json

import pytest

from appbrowser import AXE, DESKTOP, PHONE, open_lab

pytestmark = pytest.mark.browser


def test_turning_cutting_and_the_mismatch_region(browser, base_url, artifacts_dir):
    page, errors = open_lab(browser, base_url + "labs/solid", timeout_ms=60000)
    before = page.eval_on_selector("#solid", "c => c.toDataURL()")
    page.click("button[aria-label='Turn right']")
    page.wait_for_function("location.hash.includes('yaw=50')")
    assert page.eval_on_selector("#solid", "c => c.toDataURL()") != before  # the picture turned
    page.eval_on_selector("#Y", "e => { e.value = 20; e.dispatchEvent(new Event('change', {bubbles: true})); }")
    page.wait_for_function("location.hash.includes('Y=20')")
    page.select_option("#sample", "9")
    page.select_option("#second", "FL11")
    page.click("#mismatch")
    page.wait_for_function("document.querySelector('#status').textContent.startsWith('Sample 9')", timeout=60000)
    page.screenshot(path=str(artifacts_dir / "lab_solid.png"), full_page=True)
    page.keyboard.press("Control+z")
    page.wait_for_function("!location.hash.includes('mismatch=1')")
    assert not errors, errors


def test_no_serious_accessibility_violations(browser, base_url):
    for size in (DESKTOP, PHONE):
        page, errors = open_lab(browser, base_url + "labs/solid", size, timeout_ms=60000)
        page.add_script_tag(path=str(AXE))
        result = json.loads(page.evaluate("async () => JSON.stringify(await axe.run(document))"))
        violations = [v for v in result["violations"] if v["impact"] in ("serious", "critical")]
        assert not violations, [(v["id"], v["help"], [n["target"] for n in v["nodes"]][:3]) for v in violations]
        page.close()
        assert not errors, errors


# ---- issue 28, glitch 4: the solid turns by finger and mouse, fits a phone, and its points pick ----

PHONE_375 = (375, 740)
FAR_OUT = """() => { const v = __solid.view(), s = __solid.solid, out = [];
    for (const yaw of [0, 45, 90, 135, 180, 225, 270, 315]) for (const pitch of [-80, -20, 20, 80]) {
        __solid.state.yaw = yaw; __solid.state.pitch = pitch; const w = __solid.view();
        for (const level of s.levels) for (const lab of level.lab) {
            const [x, y] = w.P(lab); if (x < 0 || y < 0 || x > w.width || y > w.height) out.push([yaw, pitch, lab]); } }
    return out; }"""
# A MacAdam-limit point with no other pickable point within 7 px in the current view: a tap on it
# can only mean it.
ISOLATED = """() => { const v = __solid.view(), s = __solid.solid, pts = [];
    s.levels.forEach((level, i) => level.lab.forEach((lab, h) => pts.push({i, h, p: v.P(lab)})));
    s.cube_edges_lab.forEach((edge) => edge.forEach((lab) => pts.push({i: -1, p: v.P(lab)})));
    const r = document.querySelector('#solid').getBoundingClientRect();
    for (const a of pts) { if (a.i < 0) continue;
        if (pts.every((b) => b === a || Math.hypot(a.p[0] - b.p[0], a.p[1] - b.p[1]) > 7))
            return {i: a.i, h: a.h, x: r.left + a.p[0], y: r.top + a.p[1], lab: s.levels[a.i].lab[a.h],
                    rgb8: s.levels[a.i].rgb8[a.h]}; }
    return null; }"""


def touch_context(browser, size):
    context = browser.new_context(viewport={"width": size[0], "height": size[1]}, has_touch=True,
                                  is_mobile=True, device_scale_factor=2)
    page = context.new_page()
    errors = []
    page.on("pageerror", lambda e: errors.append(str(e)))
    return context, page, errors


def open_solid(page, base_url):
    page.goto(base_url + "labs/solid")
    page.wait_for_selector("body[data-ready=true]", state="attached", timeout=60000)


def expected_text(point):
    lab = point["lab"]
    return f"L* {lab[0]:.1f}, a* {lab[1]:.1f}, b* {lab[2]:.1f}; shown as rgb({', '.join(map(str, point['rgb8']))})"


def test_one_finger_turns_the_solid_and_the_page_does_not_scroll(browser, base_url, artifacts_dir):
    context, page, errors = touch_context(browser, PHONE_375)
    try:
        open_solid(page, base_url)
        page.locator("#solid").scroll_into_view_if_needed()
        box = page.locator("#solid").bounding_box()
        before = page.evaluate("[__solid.state.yaw, __solid.state.pitch, scrollY]")
        x, y = box["x"] + box["width"] / 2, box["y"] + box["height"] / 2
        cdp = context.new_cdp_session(page)
        cdp.send("Input.dispatchTouchEvent", {"type": "touchStart", "touchPoints": [{"x": x, "y": y}]})
        for step in range(1, 11):  # 80 px right and 40 px up, in ten moves
            cdp.send("Input.dispatchTouchEvent", {"type": "touchMove",
                                                  "touchPoints": [{"x": x + 8 * step, "y": y - 4 * step}]})
        cdp.send("Input.dispatchTouchEvent", {"type": "touchEnd", "touchPoints": []})
        # 0.5 degree per pixel: yaw 35 + 40 = 75, pitch 20 - 20 = 0; the URL keeps the view
        page.wait_for_function("location.hash.includes('yaw=75')")
        yaw, pitch, scroll = page.evaluate("[__solid.state.yaw, __solid.state.pitch, scrollY]")
        assert (before[0], before[1]) == (35, 20)  # exact: the lab's default view, whole degrees
        assert (yaw, pitch) == (75, 0)  # exact: whole degrees, rounded when the drag ends
        assert scroll == before[2]  # exact: pixels; the finger turned the solid, not the page
        page.screenshot(path=str(artifacts_dir / "lab_solid_touch_turned.png"))
        assert not errors, errors
    finally:
        context.close()


def test_the_mouse_turns_it_too(browser, base_url):
    page, errors = open_lab(browser, base_url + "labs/solid", timeout_ms=60000)
    box = page.locator("#solid").bounding_box()
    x, y = box["x"] + box["width"] / 2, box["y"] + box["height"] / 2
    page.mouse.move(x, y)
    page.mouse.down()
    for step in range(1, 6):
        page.mouse.move(x - 6 * step, y + 4 * step)
    page.mouse.up()
    page.wait_for_function("location.hash.includes('yaw=20')")  # 35 - 30 / 2
    assert page.evaluate("__solid.state.pitch") == 30  # exact: whole degrees, 20 + 20 / 2
    assert not errors, errors


def test_on_a_phone_the_solid_fits_at_every_angle(browser, base_url, artifacts_dir):
    context, page, errors = touch_context(browser, PHONE_375)
    try:
        open_solid(page, base_url)
        assert page.evaluate("document.documentElement.scrollWidth <= innerWidth")  # no sideways scroll
        assert in_viewport_x(page, "#solid")
        ratio = page.eval_on_selector("#solid", "c => c.width / c.clientWidth")
        assert ratio == pytest.approx(2, abs=0.01)  # the backing store follows devicePixelRatio 2 (rounding)
        assert page.evaluate(FAR_OUT) == []  # no MacAdam point drawn outside the canvas, whatever the angle
        page.screenshot(path=str(artifacts_dir / "lab_solid_phone.png"), full_page=True)
        assert not errors, errors
    finally:
        context.close()


def in_viewport_x(page, selector):
    return page.evaluate("""(sel) => { const r = document.querySelector(sel).getBoundingClientRect();
        return r.width > 0 && r.left >= 0 && r.right <= innerWidth + 0.5; }""", selector)


def test_a_tap_picks_the_point_under_the_finger(browser, base_url, artifacts_dir):
    context, page, errors = touch_context(browser, PHONE_375)
    try:
        open_solid(page, base_url)
        page.locator("#solid").scroll_into_view_if_needed()
        point = page.evaluate(ISOLATED)
        assert point is not None
        page.touchscreen.tap(point["x"] + 2, point["y"] - 1)  # a finger lands 2 px off: still nearest
        page.wait_for_function("__solid.picked !== null")
        picked = page.evaluate("__solid.picked")
        assert (picked["kind"], picked["i"], picked["h"]) == ("level", point["i"], point["h"])
        shown = page.inner_text("#pick-out")
        assert expected_text(point) in shown, shown
        level_Y = page.evaluate(f"__solid.solid.levels[{point['i']}].Y")
        assert f"Y = {level_Y:g} %" in shown
        swatch = page.eval_on_selector("#pick-swatch", "e => getComputedStyle(e).backgroundColor")
        assert swatch == f"rgb({', '.join(map(str, point['rgb8']))})"
        assert page.evaluate("location.hash.includes('yaw=35')")  # a tap picks; it does not turn
        page.screenshot(path=str(artifacts_dir / "lab_solid_picked.png"))
        assert not errors, errors
    finally:
        context.close()


def test_the_keyboard_picks_points_too(browser, base_url):
    page, errors = open_lab(browser, base_url + "labs/solid", timeout_ms=60000)
    page.focus("#pick-level")
    page.keyboard.press("ArrowDown")  # Y = 10 %
    page.focus("#pick-hue")
    for _ in range(3):
        page.keyboard.press("ArrowRight")  # hue 4 of 72
    point = page.evaluate("({lab: __solid.solid.levels[1].lab[3], rgb8: __solid.solid.levels[1].rgb8[3]})")
    assert page.evaluate("__solid.picked") == {"kind": "level", "i": 1, "h": 3}
    shown = page.inner_text("#pick-out")
    assert "Y = 10 %, hue 4 of 72" in shown and expected_text(point) in shown, shown
    assert not errors, errors
