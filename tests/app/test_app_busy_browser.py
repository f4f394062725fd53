"""The "computing…" / "busy — queued, retrying…" note (js/busy.js) in Debian's Chromium (issue 28
item 6, issue 30 item 3): a request the server refuses with 429 because its workers are all busy
is sent again, the note says so meanwhile, and the answer arrives without an error banner."""

from __future__ import annotations

import pytest

from appbrowser import open_lab, open_page, settle
from spectrocolor.app import reflectance_lab as lab

pytestmark = pytest.mark.browser

REFLECTANCE = "labs/reflectance#light=D65&step=5&x=0.3&y=0.33&Y=20"

# Records every text the note shows (a poll every 10 ms: the note may come and go quickly).
WATCH = """() => { window.__busySeen = new Set();
    setInterval(() => { const n = document.getElementById('busy-status');
        if (n && !n.hidden) window.__busySeen.add(n.textContent); }, 10); }"""


def busy_then_answer(page, pattern, refusals, retry_after="0.4"):
    """Answer the first `refusals` requests to `pattern` as the server's busy pool does (429 with
    Retry-After), then let them through; returns the list of request counts seen."""
    seen = []

    def handle(route):
        seen.append(route.request.url)
        if len(seen) <= refusals:
            route.fulfill(status=429, headers={"Retry-After": retry_after, "Content-Type": "application/json"},
                          body='{"error": "the server is busy computing for other pages; try again"}')
        else:
            route.continue_()

    page.route(pattern, handle)
    return seen


def test_a_busy_lab_request_is_queued_retried_and_answered(browser, base_url, artifacts_dir):
    page, errors = open_lab(browser, base_url + REFLECTANCE, timeout_ms=120000)
    page.evaluate(WATCH)
    seen = busy_then_answer(page, "**/api/lab/reflectance", refusals=2)
    page.fill("#x", "0.6")
    page.dispatch_event("#x", "change")
    page.wait_for_function("window.__busySeen.has('busy — queued, retrying…')", timeout=10000)
    page.screenshot(path=str(artifacts_dir / "busy_lab_queued.png"))
    expected = lab.reflectance_lab(0.6, 0.33, 20.0)
    page.wait_for_function(f"getComputedStyle(document.querySelector('#patch')).backgroundColor === "
                           f"'rgb({expected['srgb8'][0]}, {expected['srgb8'][1]}, {expected['srgb8'][2]})'",
                           timeout=30000)
    page.wait_for_function("document.getElementById('busy-status').hidden", timeout=10000)
    assert len(seen) == 3  # two refusals, then the answer
    assert page.is_hidden("#error"), page.text_content("#error")
    note = page.locator("#busy-status")
    assert note.get_attribute("role") == "status"
    assert page.eval_on_selector("#busy-status", "n => getComputedStyle(n).position") == "fixed"
    assert not errors, errors


def test_a_slow_lab_request_shows_computing(browser, base_url):
    page, errors = open_lab(browser, base_url + REFLECTANCE, timeout_ms=120000)
    page.evaluate(WATCH)

    def slow(route):
        page.wait_for_timeout(600)
        route.continue_()

    page.route("**/api/lab/reflectance", slow)
    page.fill("#x", "0.4")
    page.dispatch_event("#x", "change")
    page.wait_for_function("window.__busySeen.has('computing…')", timeout=10000)
    page.wait_for_function("document.getElementById('busy-status').hidden && document.body.dataset.ready === 'true'"
                           " && document.querySelector('#x').value === '0.4'", timeout=30000)
    assert page.is_hidden("#error")
    assert not errors, errors


def test_the_explorer_retries_a_busy_evaluate(browser, base_url, artifacts_dir):
    with open_page(browser, base_url + "?s=1") as page:
        page.evaluate(WATCH)
        seen = busy_then_answer(page, "**/api/evaluate", refusals=1, retry_after="0.5")
        before = page.evaluate("window.__spectra.server.colours[0].XYZ")
        page.keyboard.press("ArrowUp")
        page.wait_for_function("window.__busySeen.has('busy — queued, retrying…')", timeout=10000)
        page.screenshot(path=str(artifacts_dir / "busy_explorer_queued.png"))
        settle(page)
        page.wait_for_function("document.getElementById('busy-status').hidden")
        assert len(seen) >= 2
        assert page.evaluate("window.__spectra.server.colours[0].XYZ") != before  # the new answer shown
        assert page.is_hidden("#error"), page.text_content("#error")
        assert not page.evaluate("window.__spectra.stale")
