"""``sc.explore``'s kernel side (issue 29, part 2): the explorer's modules assembled into one ES
module, the widget's messages answered as the server answers the same requests, and edits checked
before they reach ``widget.spectrum``. (The page itself in JupyterLab:
tests/notebook/test_explore_jupyterlab_browser.py.)"""

from __future__ import annotations

import json
import re
import shutil
import subprocess
import sys

import numpy as np
import pytest

pytest.importorskip("fastapi")

from spectrocolor import Spectrum, SpectrumError  # noqa: E402
from spectrocolor.app import notebook_frontend as front  # noqa: E402
from spectrocolor.app import notebook_widget as nw  # noqa: E402

STATEMENT = re.compile(r"^\s*(import|export)\b(?!\.)", re.M)
NODE = shutil.which("node")


def request(method, path, body=None, rid=1):
    return nw.handle_message({"kind": "request", "id": rid, "method": method, "path": path,
                              "body": None if body is None else json.dumps(body)})


# ---------------------------------------------------------------------------- assembly
def test_the_assembled_explorer_has_no_import_left_and_holds_every_module_main_imports():
    sources = front.explorer_sources()
    text = nw.assemble_esm(sources)
    assert not STATEMENT.findall(text)
    assert "./" not in "".join(re.findall(r"from\s+\S+", text))
    # every module main.js reaches, found here by reading the import lines independently
    reached, todo = set(), ["main.js"]
    while todo:
        name = todo.pop()
        if name not in reached:
            reached.add(name)
            todo += re.findall(r'from\s+"\./([\w-]+\.js)"', sources[name])
    assert {"view.js", "editors.js", "colour.js", "state.js", "api.js", "dom.js"} <= reached
    placed = re.findall(r'^  __spectrocolorModules\["([\w-]+\.js)"\] = ', text, re.M)
    assert set(placed) == reached and len(placed) == len(reached)
    # dependencies first: each module comes after every module it imports
    for name in placed:
        for need in re.findall(r'from\s+"\./([\w-]+\.js)"', sources[name]):
            assert placed.index(need) < placed.index(name), (need, name)


def test_the_widget_module_has_one_default_export_and_the_page_without_scripts():
    esm = nw.widget_esm()
    assert STATEMENT.findall(esm) == ["export"] and "export default {render};" in esm
    markup = front.page_markup()
    assert 'id="editors"' in markup and "<script" not in markup
    css = front.page_css()
    assert ":root" not in css and ":host" in css and not re.search(r"(?<![\w.#-])body\b", css)


@pytest.mark.skipif(NODE is None, reason="node is not installed: the syntax check needs it")
def test_the_widget_module_parses_and_the_assembly_runs_modules_in_order(tmp_path):
    (tmp_path / "widget.mjs").write_text(nw.widget_esm(), encoding="utf-8")
    subprocess.run([NODE, "--check", str(tmp_path / "widget.mjs")], check=True)
    text = nw.assemble_esm({
        "a.js": "export const A = 2;\nexport function twice(x) { return 2 * x; }",
        "b.js": 'import {A, twice as double} from "./a.js";\nexport class B { get v() { return double(A); } }',
        "main.js": 'import {B} from "./b.js";\nimport {A} from "./a.js";\n'
                   'console.log(new B().v + A, typeof document);'},
        "main.js")
    (tmp_path / "run.mjs").write_text(text + "createExplorer({document: 'doc'});\n", encoding="utf-8")
    out = subprocess.run([NODE, str(tmp_path / "run.mjs")], check=True, capture_output=True, text=True).stdout
    assert out.strip() == "6 string"  # 2·2 + 2, and `document` is the one the widget gives


def test_an_import_with_a_comment_after_it_is_rewritten():
    text = nw.assemble_esm({"a.js": "export const A = 1;", "main.js": 'import {A} from "./a.js";  // issue 28\nA;'})
    assert 'const {A} = __spectrocolorModules["a.js"];' in text and not STATEMENT.findall(text)


@pytest.mark.parametrize("sources, says", [
    ({"main.js": 'import * as m from "./a.js";', "a.js": ""}, "main.js, line 1"),
    ({"main.js": "export default 3;"}, "main.js, line 1"),
    ({"main.js": "export let n = 1;"}, "main.js, line 1"),
    ({"main.js": "const m = import('./a.js');"}, "main.js, line 1"),
    ({"main.js": 'import {x} from "./gone.js";'}, "imports gone.js"),
    ({"main.js": 'import {a} from "./a.js";', "a.js": 'import {m} from "./main.js";\nexport const a = 1;'},
     "circle: main.js -> a.js -> main.js"),
    ({"main.js": 'import {a-b} from "./a.js";', "a.js": ""}, "cannot rewrite the imported name"),
])
def test_forms_the_assembly_cannot_rewrite_are_refused_by_name(sources, says):
    with pytest.raises(nw.AssemblyError, match=re.escape(says)):
        nw.assemble_esm(sources)


# ---------------------------------------------------------------------------- requests
def test_requests_are_answered_as_the_server_answers_them():
    from fastapi.testclient import TestClient

    from spectrocolor.app.server import create_app

    client = TestClient(create_app(), base_url="http://127.0.0.1")
    body = {"step_nm": 10, "observer": "1931", "display": "sRGB", "normalise": "fixed", "gamut": "flag",
            "spectra": [[15] * 31, list(range(31))], "pairs": [[0, 1]]}
    for method, path, payload in [("GET", "/api/options", None), ("GET", "/api/presets?step_nm=5", None),
                                  ("GET", "/api/demos", None),
                                  ("POST", "/api/model", {"step_nm": 5}), ("POST", "/api/evaluate", body),
                                  ("POST", "/api/metamer", {"target": [15] * 31}),
                                  ("POST", "/api/evaluate", {**body, "spectra": [[15] * 30]})]:
        mine = request(method, path, payload, rid=7)
        theirs = client.request(method, path, json=payload)
        assert mine["kind"] == "response" and mine["id"] == 7
        assert mine["status"] == theirs.status_code, (path, mine["body"][:200])
        assert json.loads(mine["body"]) == theirs.json()  # exact: the same functions, the same JSON


def test_an_export_is_the_file_the_server_writes():
    r = request("POST", "/api/export", {"format": "csv", "step_nm": 10, "names": ["grey"], "spectra": [[15] * 31]})
    assert r["status"] == 200 and r["media"] == "text/csv"
    assert "SPECTRA levels 0-30" in r["body"] and "grey" in r["body"]


@pytest.mark.parametrize("message, status, says", [
    ({"kind": "request", "id": 1, "method": "GET", "path": "/api/nothing"}, 404, "/api/nothing is not available"),
    ({"kind": "request", "id": 1, "method": "POST", "path": "/api/import", "body": "{}"}, 404, "sc.read_spectra"),
    ({"kind": "request", "id": 1, "method": "POST", "path": "/api/evaluate", "body": "{nope"}, 422, "not JSON"),
    ({"kind": "request", "id": 1, "method": "POST", "path": "/api/evaluate", "body": "[" * 100_000}, 413, "at most"),
    ({"kind": "request", "id": 1, "method": "DELETE", "path": "/api/options"}, 405, "GET or POST"),
    ({"kind": "request", "id": 1, "method": "GET", "path": "api/options"}, 404, "'path'"),
    ({"kind": "request", "id": 1, "method": "POST", "path": "/api/model", "body": 5}, 422, "'body' must be text"),
    ({"kind": "request", "id": 1, "method": "GET", "path": "/api/presets?step_nm=3"}, 422, "step_nm"),
])
def test_refused_requests_get_the_servers_one_error_shape(message, status, says):
    r = nw.handle_message(message)
    assert r["kind"] == "response" and r["status"] == status
    assert says in json.loads(r["body"])["error"]


@pytest.mark.parametrize("message, says", [
    ([1, 2], "expected an object, got list"),
    ({"kind": "request", "id": True, "method": "GET", "path": "/api/options"}, "'id'"),
    ({"kind": "request", "id": -1}, "'id'"),
    ({"kind": None}, "'kind' must be"),
    ({"kind": "edited", "levels": [15] * 30, "step_nm": 10}, "30 levels"),
    ({"kind": "edited", "levels": [15] * 31, "step_nm": 3}, "step_nm"),
    ({"kind": "edited", "levels": [15] * 30 + [float("nan")], "step_nm": 10}, "levels[30]"),
    ({"kind": "edited", "levels": [15] * 30 + [31], "step_nm": 10}, "levels[30]: expected a number in 0-30"),
    ({"kind": "edited", "levels": [15] * 30 + [True], "step_nm": 10}, "levels[30]"),
    ({"kind": "edited", "levels": "15" * 31, "step_nm": 10}, "expected a list of 31 numbers"),
])
def test_malformed_messages_get_one_line(message, says):
    r = nw.handle_message(message)
    assert r["kind"] == "error" and says in r["message"] and "\n" not in r["message"]


# ---------------------------------------------------------------------------- levels
def test_a_spectrum_becomes_levels_as_the_explorers_load_scales_a_file():
    wl = np.arange(380, 781, 5.0)
    ramp = Spectrum(wl, 2 + (wl - 380) / 10)  # 2 at 380 nm, 34 at 700 nm, 42 at 780 nm
    levels, unit = nw.levels_of(ramp, 10, "peak")
    assert len(levels) == 31 and abs(max(levels) - 30) < 1e-12  # the peak in 400-700 nm is level 30
    assert abs(unit - 34 / 30) < 1e-15 and abs(levels[0] - 4 / unit) < 1e-12  # 4 at 400 nm
    levels, unit = nw.levels_of(Spectrum(wl, np.full(wl.size, 0.5)), 5, "unit")
    assert levels == [15.0] * 61  # exact: 0.5 × 30 and a flat line resampled
    with pytest.raises(SpectrumError, match="0-30"):
        nw.levels_of(ramp, 10, "levels")
    with pytest.raises(SpectrumError, match="never extrapolates"):
        nw.levels_of(Spectrum(np.arange(450, 701, 10.0), np.ones(26)), 10)
    with pytest.raises(SpectrumError, match="one distribution"):
        nw.levels_of(Spectrum(wl, np.ones((2, wl.size))), 10)
    with pytest.raises(SpectrumError, match="scale"):
        nw.levels_of(ramp, 10, "percent")
    with pytest.raises(SpectrumError, match="step_nm"):
        nw.levels_of(ramp, 7)


# ---------------------------------------------------------------------------- the widget
@pytest.fixture
def widget():
    pytest.importorskip("anywidget")
    wl = np.arange(400, 701, 10.0)
    return nw.explore(Spectrum(wl, np.full(31, 0.5), names=["grey"]), scale="unit")


def test_an_edit_from_the_page_is_the_widgets_spectrum(widget):
    assert widget.levels == [15.0] * 31 and widget.name == "grey"  # exact: 0.5 × 30
    edited = [15.0] * 31
    edited[15] = 25.0
    widget._on_message(widget, {"kind": "edited", "levels": edited, "step_nm": 10}, [])
    assert widget.levels == edited  # exact: whole levels
    s = widget.spectrum
    assert s.names == ("grey",) and s.wavelengths_nm[15] == 550  # exact: the 10 nm grid
    assert np.allclose(s.values, np.array(edited) / 30, rtol=0, atol=1e-15)  # one division each
    # the bins changed in the page (5 nm): the spectrum follows onto the new grid
    widget._on_message(widget, {"kind": "edited", "levels": [3] * 61, "step_nm": 5}, [])
    assert widget.step_nm == 5 and widget.spectrum.values.shape == (61,)


def test_a_refused_edit_leaves_the_spectrum_and_says_why(widget):
    sent = []
    widget.send = sent.append
    widget._on_message(widget, {"kind": "edited", "levels": [15] * 30, "step_nm": 10}, [])
    assert widget.levels == [15.0] * 31  # exact: unchanged
    assert sent == [{"kind": "error", "message": widget.last_error}] and "30 levels" in widget.last_error
    with pytest.raises(SpectrumError, match="levels"):
        widget.levels = [40] * 31
    widget._on_message(widget, {"kind": "request", "id": 3, "method": "GET", "path": "/api/options"}, [])
    assert sent[-1]["id"] == 3 and sent[-1]["status"] == 200


def test_assigning_a_spectrum_in_python_sets_the_levels(widget):
    wl = np.arange(400, 701, 5.0)
    widget.spectrum = Spectrum(wl, 1 + (wl - 400) / 300)  # 1 to 2: peak 2 at 700 nm
    assert widget.levels[-1] == 30 and abs(widget.levels[0] - 15) < 1e-12
    assert abs(widget.spectrum.values[0] - 1) < 1e-12


def test_the_package_imports_without_the_notebook_extra_and_explore_names_it():
    code = ("import sys; sys.modules['anywidget'] = None\n"
            "import spectrocolor as sc\n"
            "try:\n    sc.explore()\nexcept ImportError as e:\n    print(e)\n")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert "sc.explore needs the notebook extra" in out and "spectrocolor[notebook]" in out
