"""The note the page shows while the compiled kernels warm up, in Debian's Chromium.

The explorer is started as ``make run`` starts it, with numba's cache pointed at an empty folder
(a fresh machine): the smoothest-reflectance lab's first answer comes from the NumPy path, and
the page says so on screen. Nothing is timed (``tests/project/test_make_run.py`` says why).
"""

from __future__ import annotations

import pytest
from test_make_run import RunningServer, needs_script

pytestmark = pytest.mark.browser


def test_a_result_on_the_numpy_path_says_so_on_screen(browser, tmp_path, artifacts_dir):
    needs_script()
    pytest.importorskip("numba")
    server = RunningServer(tmp_path / "empty-numba-cache")
    try:
        page = browser.new_page(viewport={"width": 1280, "height": 800})
        errors = []
        page.on("pageerror", lambda e: errors.append(str(e)))
        page.goto(server.url + "labs/reflectance#light=D65&step=10&x=0.4&y=0.4&Y=20")
        page.wait_for_selector("body[data-ready=true]", timeout=120_000)
        note = page.wait_for_selector("#kernel-status", state="visible", timeout=30_000)
        assert note.text_content() == \
            "compiled kernels warming up — this result used the slower NumPy path"
        assert note.get_attribute("role") == "status"
        page.screenshot(path=str(artifacts_dir / "kernel_note.png"))
        assert not any("compiled kernels ready" in line for line in server.lines)
        assert not errors, errors
        page.close()
    finally:
        server.clean_up()
