"""Issue 29, part 2: ``sc.explore`` in a real JupyterLab, driven through the page.

A JupyterLab server starts on loopback in a temporary folder holding a notebook this test writes;
Chromium opens it, runs the cell that creates the widget (a flat grey, level 15 everywhere), presses
a bar of the widget's editor at 550 nm to level 25 with the mouse, then runs the next cell, which
prints ``widget.levels`` and ``widget.spectrum``'s values: the edited bin must come back to Python;
a last cell assigns ``widget.levels`` and the page must redraw with them.
Screenshots at desktop and tablet sizes go to the artifacts folder (and /tmp/h29/).

Skipped only when JupyterLab or anywidget is not installed (the test extra installs both).
"""

from __future__ import annotations

import contextlib
import json
import os
import secrets
import socket
import subprocess
import sys
import time
import urllib.request
from pathlib import Path

import pytest

pytest.importorskip("jupyterlab", reason="JupyterLab is not installed (the test extra installs it)")
pytest.importorskip("anywidget", reason="anywidget is not installed (the test extra installs it)")

pytestmark = pytest.mark.browser

DESKTOP, TABLET = (1440, 900), (820, 1180)
PAD_TOP, PAD_BOTTOM = 14, 16  # the bar editor's plot margins, px (static/js/editors.js)
FULL = 30

CELLS = [
    "import numpy as np\n"
    "import spectrocolor as sc\n"
    "grey = sc.Spectrum(np.arange(400, 701, 10.0), np.full(31, 0.5), names=['flat grey'])\n"
    "widget = sc.explore(grey, scale='unit')\n"
    "widget",
    "print('LEVELS', json.dumps(widget.levels))\n"
    "print('SPECTRUM', json.dumps([round(float(v), 6) for v in widget.spectrum.values]))",
    "widget.levels = [10.0] * 31\n"
    "print('SET')",
]


def notebook(cells) -> dict:
    return {"nbformat": 4, "nbformat_minor": 5,
            "metadata": {"kernelspec": {"name": "python3", "display_name": "Python 3", "language": "python"}},
            "cells": [{"cell_type": "code", "id": f"c{i}", "metadata": {}, "execution_count": None, "outputs": [],
                       "source": ("import json\n" if i == 1 else "") + text} for i, text in enumerate(cells)]}


def free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


@contextlib.contextmanager
def jupyterlab(folder: Path):
    """A JupyterLab server on a free loopback port serving ``folder``; yields (url, token)."""
    token, port = secrets.token_hex(16), free_port()
    env = {**os.environ, "JUPYTER_RUNTIME_DIR": str(folder / ".runtime"), "IPYTHONDIR": str(folder / ".ipython"),
           "JUPYTER_CONFIG_DIR": str(folder / ".config")}
    src = str(Path(__file__).resolve().parents[2] / "src")
    env["PYTHONPATH"] = os.pathsep.join([src, *filter(None, [os.environ.get("PYTHONPATH")])])
    cmd = [sys.executable, "-m", "jupyterlab", "--no-browser", "--ServerApp.ip=127.0.0.1", f"--ServerApp.port={port}",
           f"--IdentityProvider.token={token}", f"--ServerApp.root_dir={folder}", "--ServerApp.port_retries=0",
           "--allow-root", "--ServerApp.terminals_enabled=False",
           "--LabApp.expose_app_in_browser=True", f"--LabApp.workspaces_dir={folder / '.workspaces'}",
           f"--LabApp.user_settings_dir={folder / '.settings'}"]
    news = folder / ".settings" / "@jupyterlab" / "apputils-extension" / "notification.jupyterlab-settings"
    news.parent.mkdir(parents=True)
    news.write_text('{"fetchNews": "false", "checkForUpdates": false}', encoding="utf-8")  # no news toast over the page
    log = open(folder / "jupyterlab.log", "wb")
    proc = subprocess.Popen(cmd, cwd=folder, env=env, stdout=log, stderr=subprocess.STDOUT)
    url = f"http://127.0.0.1:{port}/"
    try:
        deadline = time.monotonic() + 90
        while True:
            try:
                with urllib.request.urlopen(f"{url}api/status?token={token}", timeout=2) as r:
                    if r.status == 200:
                        break
            except OSError:
                pass
            if proc.poll() is not None or time.monotonic() > deadline:
                raise RuntimeError(f"JupyterLab did not start: {(folder / 'jupyterlab.log').read_text()[-2000:]}")
            time.sleep(0.5)
        yield url, token
    finally:
        with contextlib.suppress(OSError):
            req = urllib.request.Request(f"{url}api/shutdown", method="POST",
                                         headers={"Authorization": f"token {token}"})
            urllib.request.urlopen(req, timeout=10).close()
        try:
            proc.wait(timeout=20)
        except subprocess.TimeoutExpired:
            proc.terminate()
            proc.wait(timeout=10)
        log.close()


STATE = "() => { const h = document.querySelector('.spectrocolor-explorer'); return h && h.__spectrocolor.state(); }"
SETTLED = ("() => { const h = document.querySelector('.spectrocolor-explorer'); "
           "const S = h && h.__spectrocolor.state(); "
           "return Boolean(S && S.settled && S.server && !S.inflight && !S.dirty); }")


def run_cell(pg, index: int) -> None:
    pg.evaluate("""async (i) => { const app = window.jupyterapp;
        const panel = app.shell.currentWidget; panel.content.activeCellIndex = i;
        await app.commands.execute('notebook:run-cell'); }""", index)


def output_text(pg, index: int, marker: str, timeout_s: float = 60) -> str:
    deadline = time.monotonic() + timeout_s
    while time.monotonic() < deadline:
        text = pg.evaluate("""(i) => { const cells = window.jupyterapp.shell.currentWidget.content.widgets;
            const out = cells[i].node.querySelector('.jp-OutputArea'); return out ? out.innerText : ''; }""", index)
        if marker in text:
            return text
        pg.wait_for_timeout(250)
    raise AssertionError(f"cell {index} printed no {marker!r} within {timeout_s} s")


def test_a_bar_edited_in_jupyterlab_comes_back_to_python(browser, tmp_path, artifacts_dir):
    (tmp_path / "explore.ipynb").write_text(json.dumps(notebook(CELLS)), encoding="utf-8")
    shots = Path("/tmp/h29")
    shots.mkdir(exist_ok=True)
    with jupyterlab(tmp_path) as (url, token):
        context = browser.new_context(viewport={"width": DESKTOP[0], "height": DESKTOP[1]})
        pg = context.new_page()
        errors = []
        pg.on("pageerror", lambda e: errors.append(str(e)))
        try:
            pg.goto(f"{url}lab/tree/explore.ipynb?token={token}")
            pg.wait_for_function("() => { const w = window.jupyterapp && window.jupyterapp.shell.currentWidget; "
                                 "return Boolean(w && w.sessionContext && w.sessionContext.session "
                                 "&& w.sessionContext.session.kernel); }", timeout=90000)
            run_cell(pg, 0)
            try:
                pg.wait_for_selector(".spectrocolor-explorer #editors canvas", timeout=90000)
            except Exception:
                pg.screenshot(path=str(shots / "explore_not_shown.png"))
                raise AssertionError(f"the widget did not draw its bars; page errors: {errors}") from None
            pg.wait_for_function(SETTLED, timeout=90000)
            S = pg.evaluate(STATE)
            assert S["setting"] == 1 and S["step"] == 10
            assert S["dists"]["1"][0] == [15] * 31  # exact: 0.5 × 30 is 15 in binary; levels of the grey
            assert S["names"]["1"][0] == "flat grey"
            # the patch shows the library's colour of the grey (the kernel answered /api/evaluate)
            assert S["server"]["colours"][0]["in_gamut"]

            canvas = pg.locator(".spectrocolor-explorer #editors .editor[data-e='0'] canvas")
            canvas.scroll_into_view_if_needed()
            box = canvas.bounding_box()
            k, level = 15, 25  # 550 nm to level 25
            x = box["x"] + (k + 0.5) * box["width"] / 31
            y = box["y"] + PAD_TOP + (box["height"] - PAD_TOP - PAD_BOTTOM) * (1 - level / FULL)
            pg.mouse.move(x, y)
            pg.mouse.down()
            pg.mouse.up()
            pg.wait_for_function(SETTLED, timeout=60000)
            shown = pg.evaluate(STATE)["dists"]["1"][0]
            assert shown[k] == level and shown[:k] == [15] * k  # exact: whole levels on SPECTRA's grid
            pg.screenshot(path=str(shots / "explore_desktop.png"), full_page=True)
            pg.screenshot(path=str(artifacts_dir / "explore_jupyterlab_desktop.png"), full_page=True)

            run_cell(pg, 1)
            text = output_text(pg, 1, "SPECTRUM")
            levels = json.loads(text.split("LEVELS", 1)[1].split("\n", 1)[0])
            values = json.loads(text.split("SPECTRUM", 1)[1].split("\n", 1)[0])
            expected = [15.0] * 31
            expected[k] = float(level)
            assert levels == expected  # exact: whole levels sent as JSON numbers
            # the spectrum in the units it came in: levels × (1/30), printed rounded to 6 decimals
            assert values == [round(v / FULL, 6) for v in expected]  # exact: the same rounding both sides

            # and back: levels assigned in Python redraw the page (the bars, and the library's colour)
            run_cell(pg, 2)
            output_text(pg, 2, "SET")
            pg.wait_for_function("() => { const h = document.querySelector('.spectrocolor-explorer'); "
                                 "const S = h.__spectrocolor.state(); return S.dists[1][0].every((v) => v === 10) "
                                 "&& S.settled && !S.dirty && !S.inflight; }", timeout=60000)
            assert pg.evaluate(STATE)["server"]["colours"][0]["XYZ"][1] < S["server"]["colours"][0]["XYZ"][1]

            pg.set_viewport_size({"width": TABLET[0], "height": TABLET[1]})
            pg.wait_for_timeout(500)
            canvas.scroll_into_view_if_needed()
            pg.screenshot(path=str(shots / "explore_tablet.png"), full_page=True)
            pg.screenshot(path=str(artifacts_dir / "explore_jupyterlab_tablet.png"), full_page=True)
            assert not errors, errors
        finally:
            context.close()


# ---------------------------------------------------------------------------- a lab (sc.explore_lab)
LAB_CELLS = [
    "import spectrocolor as sc\n"
    "lab = sc.explore_lab('thinfilm', film='soap', d=420)\n"
    "lab",
    "print('STATE', json.dumps(lab.state))\n"
    "print('SPECTRUM', json.dumps(lab.spectrum.names), json.dumps(lab.result['film']))",
    "lab.state = {**lab.state, 'd': 0}\n"
    "print('SET')",
]
LAB = "() => { const h = document.querySelector('.spectrocolor-lab'); return h && h.__spectrocolor; }"


def test_a_thin_film_lab_edited_in_jupyterlab_comes_back_to_python(browser, tmp_path, artifacts_dir):
    (tmp_path / "lab.ipynb").write_text(json.dumps(notebook(LAB_CELLS)), encoding="utf-8")
    shots = Path("/tmp/nbwidget")
    shots.mkdir(exist_ok=True)
    with jupyterlab(tmp_path) as (url, token):
        context = browser.new_context(viewport={"width": DESKTOP[0], "height": DESKTOP[1]})
        pg = context.new_page()
        errors = []
        pg.on("pageerror", lambda e: errors.append(str(e)))
        try:
            pg.goto(f"{url}lab/tree/lab.ipynb?token={token}")
            pg.wait_for_function("() => { const w = window.jupyterapp && window.jupyterapp.shell.currentWidget; "
                                 "return Boolean(w && w.sessionContext && w.sessionContext.session "
                                 "&& w.sessionContext.session.kernel); }", timeout=90000)
            run_cell(pg, 0)
            try:  # the lab's page says it is ready once the kernel's table has been drawn
                pg.wait_for_function("() => { const h = document.querySelector('.spectrocolor-lab'); "
                                     "return h && h.__spectrocolor.body.dataset.ready === 'true'; }", timeout=120000)
            except Exception:
                pg.screenshot(path=str(shots / "lab_not_shown.png"))
                raise AssertionError(f"the lab did not draw; page errors: {errors}") from None
            lab = pg.locator(".spectrocolor-lab")
            assert lab.locator("#thickness-out").inner_text() == "420 nm"  # the state given in Python
            assert lab.locator("#film").input_value() == "soap"
            assert lab.locator("#error").is_hidden()
            patch = lab.locator("#patch").evaluate("(e) => getComputedStyle(e).backgroundColor")
            assert patch.startswith("rgb("), patch  # the film's colour from the kernel's table

            # five steps of the thickness slider with the keyboard: 420 -> 425 nm, in the page's address
            slider = lab.locator("#thickness")
            slider.scroll_into_view_if_needed()
            slider.focus()
            shown = ("() => document.querySelector('.spectrocolor-lab').shadowRoot"
                     ".getElementById('thickness-out').textContent")
            for d in range(421, 426):  # one step each, seen on the page before the next (none lost to a busy page)
                pg.keyboard.press("ArrowRight")
                pg.wait_for_function(f"() => ({shown})() === '{d} nm'", timeout=15000)
            try:
                pg.wait_for_function(f"() => ({LAB})().location.hash.includes('d=425')", timeout=30000)
            except Exception:
                pg.screenshot(path=str(shots / "lab_not_moved.png"))
                where = pg.evaluate(f"() => [({LAB})().location.hash, "
                                    "document.activeElement && document.activeElement.className]")
                raise AssertionError(f"the slider shows {lab.locator('#thickness-out').inner_text()!r}, the "
                                     f"address and focus are {where}; page errors: {errors}") from None
            assert lab.locator("#thickness-out").inner_text() == "425 nm"
            pg.screenshot(path=str(shots / "lab_desktop.png"), full_page=True)
            pg.screenshot(path=str(artifacts_dir / "lab_jupyterlab_desktop.png"), full_page=True)

            run_cell(pg, 1)
            text = output_text(pg, 1, "SPECTRUM")
            state = json.loads(text.split("STATE", 1)[1].split("\n", 1)[0])
            assert state["d"] == "425" and state["film"] == "soap"  # the slider's value, in Python
            assert '["soap 425 nm"] "soap"' in text  # the reflectance at that thickness, from the kernel's table

            # and back: a state assigned in Python moves the page
            run_cell(pg, 2)
            output_text(pg, 2, "SET")
            pg.wait_for_function(f"() => ({shown})() === '0 nm'", timeout=30000)
            assert lab.locator("#thickness").input_value() == "0"

            pg.set_viewport_size({"width": TABLET[0], "height": TABLET[1]})
            pg.wait_for_timeout(500)
            lab.scroll_into_view_if_needed()
            # the lab takes its narrow layout from the widget's width (a container query), not the window's:
            # nothing sticks out of the output area
            fits = pg.evaluate(f"() => {{ const b = ({LAB})().body; return [b.scrollWidth, b.clientWidth]; }}")
            assert fits[0] <= fits[1] + 1, fits
            pg.screenshot(path=str(shots / "lab_tablet.png"), full_page=True)
            pg.screenshot(path=str(artifacts_dir / "lab_jupyterlab_tablet.png"), full_page=True)
            assert not errors, errors
        finally:
            context.close()


OTHER_LABS = ["light", "reflectance", "solid"]


def test_the_other_labs_open_and_draw_in_jupyterlab(browser, tmp_path, artifacts_dir):
    cells = ["import spectrocolor as sc\nsc.explore_lab('light', name='FL2')",
             "sc.explore_lab('reflectance', x=0.45, y=0.4, Y=30, step=10)",
             "sc.explore_lab('solid', light='D65', Y=50)"]
    (tmp_path / "labs.ipynb").write_text(json.dumps(notebook(cells)), encoding="utf-8")
    shots = Path("/tmp/nbwidget")
    shots.mkdir(exist_ok=True)
    with jupyterlab(tmp_path) as (url, token):
        context = browser.new_context(viewport={"width": DESKTOP[0], "height": DESKTOP[1]})
        pg = context.new_page()
        errors = []
        pg.on("pageerror", lambda e: errors.append(str(e)))
        try:
            pg.goto(f"{url}lab/tree/labs.ipynb?token={token}")
            pg.wait_for_function("() => { const w = window.jupyterapp && window.jupyterapp.shell.currentWidget; "
                                 "return Boolean(w && w.sessionContext && w.sessionContext.session "
                                 "&& w.sessionContext.session.kernel); }", timeout=90000)
            for i, name in enumerate(OTHER_LABS):
                run_cell(pg, i)
                ready = (f"() => {{ const h = document.querySelector('.spectrocolor-lab-{name}'); "
                         "return h && h.__spectrocolor.body.dataset.ready === 'true'; }")
                try:
                    pg.wait_for_function(ready, timeout=120000)
                except Exception:
                    pg.screenshot(path=str(shots / f"lab_{name}_not_shown.png"))
                    text = pg.locator(f".spectrocolor-lab-{name} #error-text").all_inner_texts()
                    raise AssertionError(f"the {name} lab did not draw; banner {text}, page errors: {errors}") from None
                lab = pg.locator(f".spectrocolor-lab-{name}")
                assert lab.locator("#error").is_hidden(), lab.locator("#error-text").inner_text()
                lab.scroll_into_view_if_needed()
                pg.screenshot(path=str(shots / f"lab_{name}_desktop.png"))
            assert pg.locator(".spectrocolor-lab-light #name").input_value() == "FL2"  # the state given in Python
            assert not errors, errors
        finally:
            context.close()
