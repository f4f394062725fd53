"""The thin-film lab in Debian's Chromium: the controls drive the picture with the library's numbers."""

from __future__ import annotations

import json

import pytest

from appbrowser import AXE, DESKTOP, PHONE
from spectrocolor.app import thinfilm_lab as lab
from spectrocolor.thinfilm.maps import draining_film

pytestmark = pytest.mark.browser


@pytest.fixture
def lab_page(browser, base_url):
    context = browser.new_context(viewport={"width": DESKTOP[0], "height": DESKTOP[1]})
    page = context.new_page()
    errors = []
    page.on("pageerror", lambda e: errors.append(str(e)))
    page.goto(base_url + "labs/thinfilm")
    page.wait_for_selector("body[data-ready=true]")
    yield page
    context.close()
    assert not errors, errors


def patch_rgb(page) -> list[int]:
    text = page.eval_on_selector("#patch", "e => getComputedStyle(e).backgroundColor")
    return [int(v) for v in text[text.index("(") + 1 : text.index(")")].split(",")]


def set_range(page, selector, value):
    page.eval_on_selector(selector, """(e, v) => { e.value = v;
        e.dispatchEvent(new Event('input', {bubbles: true}));
        e.dispatchEvent(new Event('change', {bubbles: true})); }""", str(value))


def test_the_thickness_slider_shows_the_librarys_colour(lab_page, artifacts_dir):
    table = lab.thinfilm_lab()  # the page's defaults: soap, Airy, 0°, blackbody 6504 K, sRGB
    for d in (0, 120, 350, 600, 1400):
        set_range(lab_page, "#thickness", d)
        assert patch_rgb(lab_page) == table["rgb8"][d], d
        assert f"{d} nm" in lab_page.text_content("#numbers")
    set_range(lab_page, "#thickness", 350)
    lab_page.screenshot(path=str(artifacts_dir / "lab_thinfilm.png"), full_page=True)


def test_the_keyboard_steps_the_thickness_by_one_nanometre(lab_page):
    table = lab.thinfilm_lab()
    lab_page.focus("#thickness")
    lab_page.keyboard.press("ArrowRight")
    assert lab_page.input_value("#thickness") == "351"
    assert patch_rgb(lab_page) == table["rgb8"][351]


def test_changing_the_film_model_and_angle_reloads_the_table(lab_page):
    lab_page.select_option("#film", "tio2")
    lab_page.select_option("#model", "two-beam")
    set_range(lab_page, "#angle", 40)
    lab_page.wait_for_function("document.querySelector('#model-note').textContent.includes('two-beam')")
    lab_page.wait_for_function("!document.querySelector('#model-note').textContent.includes('airy')")
    table = lab.thinfilm_lab("tio2", "two-beam", 40.0)
    lab_page.wait_for_function(f"getComputedStyle(document.querySelector('#patch')).backgroundColor === "
                               f"'rgb({', '.join(map(str, table['rgb8'][350]))})'")
    assert "two-beam" in lab_page.text_content("#model-note")


def test_the_url_holds_the_state_and_undo_restores(lab_page, browser, base_url):
    lab_page.select_option("#film", "oil")
    set_range(lab_page, "#thickness", 480)
    url = lab_page.url
    assert "film=oil" in url and "d=480" in url
    again = browser.new_page(viewport={"width": DESKTOP[0], "height": DESKTOP[1]})
    again.goto(url)
    again.wait_for_selector("body[data-ready=true]")
    assert again.input_value("#film") == "oil" and again.input_value("#thickness") == "480"
    assert patch_rgb(again) == lab.thinfilm_lab("oil")["rgb8"][480]
    again.close()
    lab_page.keyboard.press("Control+z")
    assert lab_page.input_value("#thickness") == "350"
    lab_page.click("#undo")
    lab_page.wait_for_function("document.querySelector('#film').value === 'soap'")
    lab_page.click("#redo")
    lab_page.wait_for_function("document.querySelector('#film').value === 'oil'")


def test_the_draining_film_uses_the_librarys_profile_and_the_table(lab_page):
    """Row colours of the animation = the table's colour at the library's draining-film thickness."""
    table = lab.thinfilm_lab()
    height = lab_page.eval_on_selector("#drain", "c => c.height")
    time_s = 40000.0
    rows = lab_page.evaluate(f"""async () => {{
        const m = await import('/static/labs/thinfilm.js');
        return Array.from({{length: {height}}}, (_, r) => m.drainThicknessNm((r + 0.5) / {height} * 0.05, {time_s}));
    }}""")
    library = draining_film(1, height, time_s=time_s)[:, 0]
    assert rows == pytest.approx(library.astype(float).tolist(), rel=1e-6)  # float32 map in the library
    lab_page.click("#play")
    lab_page.wait_for_timeout(400)
    assert lab_page.get_attribute("#play", "aria-pressed") == "true"
    lab_page.click("#play")
    bottom_pixel = "c => Array.from(c.getContext('2d').getImageData(5, c.height - 1, 1, 1).data)"
    shown = lab_page.eval_on_selector("#drain", bottom_pixel)
    assert shown[3] == 255 and shown[:3] != [0, 0, 0]  # the bottom is thick: coloured, not black
    assert any(shown[:3] == rgb for rgb in table["rgb8"])


def test_no_serious_accessibility_violations_on_desktop_and_phone(browser, base_url, artifacts_dir):
    for name, size in (("desktop", DESKTOP), ("phone", PHONE)):
        page = browser.new_page(viewport={"width": size[0], "height": size[1]})
        page.goto(base_url + "labs/thinfilm")
        page.wait_for_selector("body[data-ready=true]")
        page.add_script_tag(path=str(AXE))
        result = page.evaluate("async () => JSON.stringify(await axe.run(document))")
        violations = [v for v in json.loads(result)["violations"] if v["impact"] in ("serious", "critical")]
        assert not violations, [(v["id"], v["help"], [n["target"] for n in v["nodes"]][:3]) for v in violations]
        if name == "phone":
            page.screenshot(path=str(artifacts_dir / "lab_thinfilm_phone.png"), full_page=True)
        page.close()
