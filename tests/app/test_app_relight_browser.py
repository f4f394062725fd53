"""Setting 4's photo in Debian's Chromium against the real server, started as a user starts it
(``spectrocolor app --port 0 --no-browser``): upload, relit under D65 (the same) and A (warmer),
adaptation, keyboard, axe, phone/tablet layout, offline, untrusted file names.

Writes artifacts/app_relight.png (desktop, under A), app_relight_d65.png and
app_relight_phone.png for a person to look at; the copies in docs/images were looked at
(docs/app.md says what they show) and are refreshed by copying these over them.
"""

from __future__ import annotations

import base64
import io
import os
import re
import subprocess
import sys
import time
import urllib.request
from pathlib import Path

import numpy as np
import pytest
from PIL import Image

from appbrowser import AXE, DESKTOP, PHONE, TABLET, settle

pytestmark = pytest.mark.browser

CHART = Path(__file__).parents[1] / "data" / "relight_chart.png"
RUN_AXE = """async () => {
  const r = await axe.run(document, {runOnly: {type: "tag",
    values: ["wcag2a", "wcag2aa", "wcag21a", "wcag21aa", "wcag22aa"]}});
  return r.violations.filter((v) => v.impact === "serious" || v.impact === "critical")
    .map((v) => ({id: v.id, help: v.help, nodes: v.nodes.slice(0, 3).map((n) => n.target.join(" "))}));
}"""


@pytest.fixture(scope="module")
def user_server():
    """The explorer as a user starts it, in its own process; yields its URL."""
    proc = subprocess.Popen([sys.executable, "-m", "spectrocolor", "app", "--port", "0",
                             "--no-browser"], stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                            text=True, env={**os.environ, "PYTHONUNBUFFERED": "1"})
    try:
        match = re.search(r"http://127\.0\.0\.1:\d+/", proc.stdout.readline())
        assert match, proc.stderr.read() if proc.poll() is not None else "no URL printed"
        url = match.group(0)
        for _ in range(200):
            try:
                with urllib.request.urlopen(url + "api/options", timeout=2) as r:
                    if r.status == 200:
                        break
            except OSError:
                time.sleep(0.05)
        yield url
    finally:
        proc.terminate()
        proc.wait(timeout=20)


def open_setting4(browser, url, size=DESKTOP, touch=False):
    context = browser.new_context(viewport={"width": size[0], "height": size[1]}, has_touch=touch,
                                  is_mobile=touch)
    page = context.new_page()
    page.errors, page.requests = [], []
    page.on("pageerror", lambda e: page.errors.append(str(e)))
    page.on("request", lambda r: page.requests.append(r.url))
    page.goto(url + "?s=4")
    settle(page)
    if page.evaluate("window.__spectra.setting") != 4:
        page.click("#tabs [data-setting='4']")
        settle(page)
    page.wait_for_selector("#photo:not([hidden])")
    return context, page


def upload(page, files=str(CHART)):
    before = page.evaluate("window.__spectra.photo ? window.__spectra.photo.answer.relit_png : null")
    page.set_input_files("#photo-file", files)
    return wait_photo(page, before)


def wait_photo(page, before):
    page.wait_for_function("(b) => window.__spectra.photo && window.__spectra.photo.answer.relit_png !== b"
                           " && !document.querySelector('#photo').hasAttribute('aria-busy')", arg=before,
                           timeout=60000)
    return page.evaluate("window.__spectra.photo")


def key(page, k):
    before = page.evaluate("window.__spectra.photo.answer.relit_png")
    page.keyboard.press(k)
    settle(page)
    return wait_photo(page, before)


def pictures(photo):
    decode = lambda b64: np.asarray(Image.open(io.BytesIO(base64.b64decode(b64))).convert("RGB"))  # noqa: E731
    return decode(photo["answer"]["taken_png"]).astype(int), decode(photo["answer"]["relit_png"]).astype(int)


def patches(codes):
    """The mean code of each of the chart's 24 patches (inner 28 x 28 px), shape (24, 3)."""
    return np.array([codes[8 + r * 40:36 + r * 40, 8 + c * 40:36 + c * 40].reshape(-1, 3).mean(0)
                     for r in range(4) for c in range(6)])


def test_photo_is_the_same_under_d65_and_warmer_under_a(browser, user_server, artifacts_dir):
    context, page = open_setting4(browser, user_server)
    try:
        page.keyboard.press("2")  # the setting's D65 (whole levels, SPECTRA's rounding)
        settle(page)
        photo = upload(page)
        taken, relit = pictures(photo)
        # exact: 8-bit codes of a lossless PNG, decoded
        assert np.array_equal(taken, np.asarray(Image.open(CHART).convert("RGB")))
        # the preset is D65 rounded to whole levels: within 3 codes, 1 on average
        assert np.abs(relit - taken).max() <= 3 and np.abs(relit - taken).mean() < 1
        assert "0 outside the object-colour solid (toward-grey)" in photo["status"]
        page.locator("#photo").screenshot(path=str(artifacts_dir / "app_relight_d65.png"))

        photo = key(page, "4")  # A
        taken, relit = pictures(photo)
        warmth = lambda p: (patches(p)[:, 0] - patches(p)[:, 2]).mean()  # noqa: E731
        assert warmth(relit) > warmth(taken) + 40, (warmth(relit), warmth(taken))
        white = patches(relit)[18]
        assert white[0] > 240 and white[2] < 0.6 * white[0], white  # an orange white (245 in the photo)
        assert "Under A" == page.inner_text("#photo-relit-caption")
        assert "Exposure ×0.5" in photo["status"]
        page.screenshot(path=str(artifacts_dir / "app_relight.png"), full_page=True)

        before = photo["answer"]["relit_png"]
        page.select_option("#photo-adaptation", "bradford")
        photo = wait_photo(page, before)
        white = patches(pictures(photo)[1])[18]
        assert np.ptp(white) <= 8, white  # the chart's white (245, 245, 240) is near-neutral again
        assert "Adaptation: Bradford" in photo["status"]
        assert all(u.startswith(user_server) or u.startswith("data:") for u in page.requests), \
            page.requests  # offline: nothing but its own server
        assert not page.errors, page.errors
    finally:
        context.close()


def test_an_edited_illuminant_relights_the_photo(browser, user_server):
    context, page = open_setting4(browser, user_server)
    try:
        photo = upload(page)
        before = pictures(photo)[1]
        preset = page.evaluate("window.__spectra.dists[4][0]")
        page.locator("#editors .editor[data-e='0'] canvas").focus()
        for _ in range(12):  # lower the illuminant's level at the cursor's bin, one level a press
            page.keyboard.press("ArrowDown")
        settle(page)
        photo = wait_photo(page, photo["answer"]["relit_png"])
        edited = page.evaluate("window.__spectra.dists[4][0]")
        assert edited != preset and photo["request"]["illuminant"] == edited
        assert np.abs(pictures(photo)[1] - before).max() > 0
        assert "(edited)" in page.inner_text("#photo-relit-caption")
    finally:
        context.close()


def test_keyboard_axe_and_untrusted_names(browser, user_server):
    context, page = open_setting4(browser, user_server)
    try:
        # Enter on the focused button opens the file dialog (recorded, and the dialog prevented)
        page.evaluate("""() => document.querySelector('#photo-file').addEventListener('click',
            (e) => { window.fileDialogAsked = true; e.preventDefault(); })""")
        page.focus("#photo-choose")
        page.keyboard.press("Enter")
        page.wait_for_function("window.fileDialogAsked === true", timeout=10000)
        name = '<img src=x onerror="window.hacked=1">.png'
        page.set_input_files("#photo-file", {"name": name, "mimeType": "image/png",
                                             "buffer": CHART.read_bytes()})
        photo = wait_photo(page, None)
        assert page.inner_text("#photo-name") == name
        assert page.locator("#photo-name img").count() == 0 and not page.evaluate("window.hacked")
        assert page.get_attribute("#photo-relit", "alt").startswith(name)
        assert photo["answer"]["pixels"] == 244 * 164
        if not page.evaluate("typeof axe !== 'undefined'"):
            page.add_script_tag(path=str(AXE))
        assert page.evaluate(RUN_AXE) == []

        page.set_input_files("#photo-file", {"name": "notes.png", "mimeType": "image/png",
                                             "buffer": b"just text"})
        page.wait_for_selector("#error:not([hidden])")
        assert "not a PNG or JPEG" in page.inner_text("#error-text")
    finally:
        context.close()


def test_a_file_over_the_upload_limit_is_reduced_in_the_browser_first(browser, user_server):
    noise = np.random.default_rng(3).integers(0, 256, (1300, 1500, 3), dtype=np.uint8)
    buffer = io.BytesIO()
    Image.fromarray(noise, "RGB").save(buffer, "PNG")
    assert len(buffer.getvalue()) > 1_400_000  # over the server's photo limit
    context, page = open_setting4(browser, user_server)
    try:
        photo = upload(page, {"name": "big.png", "mimeType": "image/png", "buffer": buffer.getvalue()})
        assert page.inner_text("#photo-name") == "big.png (reduced in the browser)"
        answer = photo["answer"]
        assert (answer["photo_width"], answer["photo_height"]) == (1024, 887)  # 1500 x 1300 at 1024
        assert (answer["width"], answer["height"], answer["downscaled"]) == (1024, 887, False)
        assert not page.errors, page.errors
    finally:
        context.close()


@pytest.mark.parametrize("size", [PHONE, TABLET], ids=["phone", "tablet"])
def test_phone_and_tablet_show_both_pictures_within_the_screen(browser, user_server, size,
                                                              artifacts_dir):
    context, page = open_setting4(browser, user_server, size, touch=True)
    try:
        upload(page)
        page.locator("#photo").scroll_into_view_if_needed()
        assert page.evaluate("document.documentElement.scrollWidth <= innerWidth")
        for sel in ("#photo-taken", "#photo-relit"):
            box = page.locator(sel).bounding_box()
            assert box["width"] > 100 and box["x"] >= 0 and box["x"] + box["width"] <= size[0] + 0.5
        if not page.evaluate("typeof axe !== 'undefined'"):
            page.add_script_tag(path=str(AXE))
        assert page.evaluate(RUN_AXE) == []
        if size == PHONE:
            page.keyboard.press("4")
            settle(page)
            page.wait_for_function("window.__spectra.photo.request.illuminant[0] < 10")
            page.wait_for_function("!document.querySelector('#photo').hasAttribute('aria-busy')")
            page.locator("#photo-relit").scroll_into_view_if_needed()
            page.screenshot(path=str(artifacts_dir / "app_relight_phone.png"))  # as seen: header, patch, photos
    finally:
        context.close()
