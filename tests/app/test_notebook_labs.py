"""``sc.explore_lab`` (issue 29 item 2, the labs): each lab's modules joined across folders into one
ES module, the lab widget's requests answered as the server answers the same lab routes, its state
checked before it reaches ``widget.state``, and the read-back (``widget.result``,
``widget.spectrum``). (The page itself in JupyterLab: tests/notebook/test_explore_jupyterlab_browser.py.)"""

from __future__ import annotations

import json
import re
import shutil
import subprocess

import numpy as np
import pytest

pytest.importorskip("fastapi")

from spectrocolor import Spectrum, SpectrumError  # noqa: E402
from spectrocolor.app import notebook_frontend as front  # noqa: E402
from spectrocolor.app import notebook_labs as nl  # noqa: E402

STATEMENT = re.compile(r"^\s*(import|export)\b(?!\.)", re.M)
NODE = shutil.which("node")
# an import line of the lab pages, read here independently of the joiner: (names, specifier)
IMPORT_LINE = re.compile(r'^import\s*\{[^}]*\}\s*from\s*"([^"]+)"', re.M)


def reached_from(sources, entries):
    """Every module the entries reach, following the import lines by hand (posix paths)."""
    import posixpath

    reached, todo = [], list(entries)
    while todo:
        name = todo.pop()
        if name in reached:
            continue
        reached.append(name)
        for spec in IMPORT_LINE.findall(sources[name]):
            todo.append(posixpath.normpath(posixpath.join(posixpath.dirname(name), spec)))
    return set(reached)


# ---------------------------------------------------------------------------- joining
@pytest.mark.parametrize("lab", nl.LABS)
def test_a_labs_modules_are_joined_across_folders_each_once(lab):
    sources = front.static_sources()
    _markup, _css, entries = front.lab_page(lab)
    assert entries[0] == f"labs/{lab}.js"
    text = front.assemble_esm(sources, entries)
    assert not STATEMENT.findall(text)
    placed = re.findall(r'^  __spectrocolorModules\["([\w/.-]+\.js)"\] = ', text, re.M)
    assert len(placed) == len(set(placed))  # each module once, keyed by its resolved path
    assert set(placed) == reached_from(sources, entries)
    assert {f"labs/{lab}.js", "labs/common.js", "js/client.js", "js/kernels.js"} <= set(placed)
    # dependencies first: labs/common.js imports ../js/client.js, which must run before it
    assert placed.index("js/client.js") < placed.index("labs/common.js") < placed.index(f"labs/{lab}.js")
    assert 'const {clientHeaders} = __spectrocolorModules["js/client.js"];' in text


def test_a_module_reached_by_two_paths_is_one_module():
    text = front.assemble_esm({
        "js/a.js": "export const A = 1;",
        "js/b.js": 'import {A} from "./a.js";\nexport const B = A;',
        "labs/c.js": 'import {A} from "../js/a.js";\nimport {B} from "../js/./b.js";\nA + B;'}, "labs/c.js")
    assert text.count('__spectrocolorModules["js/a.js"] = ') == 1
    assert text.count('__spectrocolorModules["js/a.js"];') == 2  # read by b.js and by c.js


def test_an_export_list_is_rewritten():
    text = front.assemble_esm({"a.js": "const a = 1, b = 2;\nexport { a, b as c };", "main.js":
                               'import {a, c} from "./a.js";\na + c;'}, "main.js")
    assert "return {a, c: b};" in text and not STATEMENT.findall(text)


@pytest.mark.parametrize("sources, says", [
    ({"labs/x.js": 'import {a} from "../../a.js";'}, "leaves the modules' folder"),
    ({"labs/x.js": 'import {a} from "../js/gone.js";'}, "labs/x.js imports js/gone.js"),
    ({"labs/x.js": "export let busy = false;"}, "labs/x.js, line 1"),
    ({"labs/x.js": "export {a-b};"}, "cannot rewrite the exported name"),
    ({"labs/x.js": 'import {a} from "../js/a.js";', "js/a.js": 'import {x} from "../labs/x.js";\nexport const a=1;'},
     "circle: labs/x.js -> js/a.js -> labs/x.js"),
])
def test_forms_the_joiner_cannot_rewrite_are_refused_by_name(sources, says):
    with pytest.raises(front.AssemblyError, match=re.escape(says)):
        front.assemble_esm(sources, "labs/x.js")


def test_a_page_with_a_script_the_widget_cannot_run_is_refused(monkeypatch):
    page = '<html><body><p id="x">x</p><script>alert(1)</script></body></html>'
    monkeypatch.setattr(front, "_static", lambda *parts: page)
    with pytest.raises(front.AssemblyError, match=r"static/labs/light.html: only <script type=\"module\""):
        front.lab_page("light")
    with pytest.raises(front.AssemblyError, match="lab: expected one of light, reflectance, solid, thinfilm"):
        front.lab_page("kitchen")


@pytest.mark.skipif(NODE is None, reason="node is not installed: the syntax check needs it")
@pytest.mark.parametrize("lab", nl.LABS)
def test_each_lab_widget_module_parses_with_one_default_export(lab, tmp_path):
    esm = front.lab_widget_esm(lab)
    assert STATEMENT.findall(esm) == ["export"] and "export default {render};" in esm
    (tmp_path / "widget.mjs").write_text(esm, encoding="utf-8")
    subprocess.run([NODE, "--check", str(tmp_path / "widget.mjs")], check=True)
    markup, css, _ = front.lab_page(lab)
    assert "<script" not in markup and 'id="error-text"' in markup
    assert ":root" not in css and not re.search(r"(?<![\w.#-])body\b", css)
    # the narrow layouts follow the widget's width, not the window's
    assert "@container (max-width: 760px)" in css and not re.search(r"@media\s*\(\s*max-width", css)


@pytest.mark.parametrize("lab", nl.LABS)
def test_the_address_keys_are_the_ones_the_labs_page_reads(lab):
    text = front.static_sources()[f"labs/{lab}.js"]
    for key in nl.ADDRESS_KEYS[lab]:  # a DEFAULTS entry or a params.get/has of the key
        assert re.search(rf'(\b{key}\s*:|params\.(get|has)\("{key}"\))', text), (lab, key)


# ---------------------------------------------------------------------------- requests
LAB_BODIES = [
    ("GET", "/api/lab/light/options", None),
    ("GET", "/api/lab/thinfilm/options", None),
    ("GET", "/api/lab/reflectance/options", None),
    ("GET", "/api/lab/solid/options", None),
    ("POST", "/api/lab/light", {"source": {"kind": "named", "name": "FL2"}, "display": "sRGB"}),
    ("POST", "/api/lab/light", {"source": {"kind": "temperature", "light": "blackbody", "temperature_K": 3000}}),
    ("POST", "/api/lab/light", {"source": {"kind": "leds", "peaks_nm": [450, 550], "widths_nm": [20, 30],
                                           "powers": [1, 0.8]}}),
    ("POST", "/api/lab/light", {"source": {"kind": "named", "name": "nope"}}),  # the library refuses: 422
    ("POST", "/api/lab/light", {"source": {"kind": "leds", "peaks_nm": [450] * 9, "widths_nm": [20],
                                           "powers": [1]}}),  # the model refuses
    ("POST", "/api/lab/thinfilm", {"film": "soap", "model": "airy", "angle_deg": 10}),
    ("POST", "/api/lab/thinfilm", {"film": "tar"}),
    ("POST", "/api/lab/reflectance", {"x": 0.45, "y": 0.4, "Y": 30, "illuminant": "D65", "step_nm": "10"}),
    ("POST", "/api/lab/reflectance", {"x": 0.45, "y": 0.4, "Y": 300}),
    ("POST", "/api/lab/reflectance/macadam", {"x": 0.3, "y": 0.3, "Y": 40, "step_nm": "10"}),
    ("POST", "/api/lab/solid", {"illuminant": "D65", "display": "sRGB"}),
    ("POST", "/api/lab/solid/section", {"Y": 37.25}),
    ("POST", "/api/lab/solid/mismatch", {"sample": 3, "second_illuminant": "F11"}),
    ("POST", "/api/lab/solid/mismatch", {"sample": 3.0}),  # strict: a whole number only
    ("POST", "/api/lab/solid", {"extra": 1}),
    ("GET", "/api/demos", None),
]


def test_every_lab_route_is_answered_and_in_the_parity_list():
    from fastapi.routing import APIRoute

    from spectrocolor.app.lab_routes import router

    served = {(m, r.path) for r in router.routes if isinstance(r, APIRoute) and r.path.startswith("/api/")
              for m in r.methods}
    assert set(nl.lab_routes()) == served
    assert served == {(m, p) for m, p, _ in LAB_BODIES if p.startswith("/api/lab/")}


def test_lab_requests_are_answered_as_the_server_answers_them():
    from fastapi.testclient import TestClient

    from spectrocolor.app.server import create_app

    with TestClient(create_app(), base_url="http://127.0.0.1") as client:
        for method, path, payload in LAB_BODIES:
            mine = nl.handle_lab_message("light", {"kind": "request", "id": 4, "method": method, "path": path,
                                                   "body": None if payload is None else json.dumps(payload)})
            theirs = client.request(method, path, json=payload)
            assert mine["kind"] == "response" and mine["id"] == 4
            assert mine["status"] == theirs.status_code, (path, payload, mine["body"][:200], theirs.text[:200])
            # exact: the same functions, the same JSON
            assert json.loads(mine["body"]) == theirs.json(), (path, payload)


@pytest.mark.parametrize("message, status, says", [
    ({"kind": "request", "id": 1, "method": "GET", "path": "/api/lab/solid"}, 405, "Method Not Allowed"),
    ({"kind": "request", "id": 1, "method": "POST", "path": "/api/lab/solid", "body": "{nope"}, 422, "not JSON"),
    ({"kind": "request", "id": 1, "method": "POST", "path": "/api/lab/solid", "body": "[" * 70_000}, 413, "at most"),
    ({"kind": "request", "id": 1, "method": "POST", "path": "/api/lab/kitchen", "body": "{}"}, 404, "not available"),
])
def test_refused_lab_requests_get_the_servers_one_error_shape(message, status, says):
    r = nl.handle_lab_message("solid", message)
    assert r["kind"] == "response" and r["status"] == status and says in json.loads(r["body"])["error"]


@pytest.mark.parametrize("lab, message, says", [
    ("light", [1], "expected an object, got list"),
    ("light", {"kind": "edited"}, "'kind' must be 'request' or 'state'"),
    ("light", {"kind": "state", "address": 5}, "expected text"),
    ("light", {"kind": "state", "address": "a=" + "x" * 2100}, "at most 2000"),
    ("light", {"kind": "state", "address": "a=" + "x" * 300}, "a's value has 300 characters"),
    ("light", {"kind": "state", "address": "&".join(f"k{i}=1" for i in range(50))}, "more than 40 parameters"),
    ("light", {"kind": "state", "address": "a%20b=1"}, "not a plain name"),
])
def test_malformed_lab_messages_get_one_line(lab, message, says):
    r = nl.handle_lab_message(lab, message)
    assert r["kind"] == "error" and says in r["message"] and "\n" not in r["message"]


# ---------------------------------------------------------------------------- explore_lab
def test_explore_lab_names_the_labs_and_their_settings():
    with pytest.raises(SpectrumError, match="lab: expected one of 'light', 'reflectance', 'solid', 'thinfilm'"):
        nl.initial_address("kitchen")
    with pytest.raises(SpectrumError, match="thickness: not a setting of the thinfilm lab; expected one of film"):
        nl.initial_address("thinfilm", thickness=3)
    with pytest.raises(SpectrumError, match="d: expected a finite number"):
        nl.initial_address("thinfilm", d=float("nan"))
    with pytest.raises(SpectrumError, match="only the reflectance lab starts from a spectrum"):
        nl.initial_address("light", Spectrum(np.arange(380, 781, 5.0), np.ones(81)))
    assert nl.initial_address("thinfilm", film="oil", angle=12.5, d=420) == "film=oil&angle=12.5&d=420"
    assert nl.initial_address("light", name="FL2 & more") == "name=FL2+%26+more"


def test_the_reflectance_lab_starts_from_a_spectrums_colour():
    # a flat 50 % reflectance under D65: the white point of D65 (CIE 015:2018 Table 11.3,
    # x 0.31272, y 0.32903 for the 1931 observer) at Y 50; printed to 6 digits
    wl = np.arange(380, 781, 5.0)
    state = nl.check_address(nl.initial_address("reflectance", Spectrum(wl, np.full(wl.size, 0.5))))
    assert abs(float(state["x"]) - 0.31272) < 2e-5 and abs(float(state["y"]) - 0.32903) < 2e-5
    assert state["Y"] == "50"
    with pytest.raises(SpectrumError, match="either a spectrum or x, y, Y"):
        nl.initial_address("reflectance", Spectrum(wl, np.full(wl.size, 0.5)), x=0.3)
    with pytest.raises(SpectrumError, match="Y in \\(0, 100\\]"):
        nl.initial_address("reflectance", Spectrum(wl, np.zeros(wl.size)))


@pytest.fixture
def thinfilm():
    pytest.importorskip("anywidget")
    return nl.explore_lab("thinfilm", film="soap", d=420)


def test_the_labs_state_and_result_flow_back_to_python(thinfilm):
    sent = []
    thinfilm.send = sent.append
    assert thinfilm.state == {"film": "soap", "d": "420"} and thinfilm.lab == "thinfilm"
    with pytest.raises(SpectrumError, match="has not shown a result yet"):
        _ = thinfilm.spectrum
    # the page asks for its table and moves the thickness slider: both reach the kernel
    thinfilm._on_message(thinfilm, {"kind": "request", "id": 1, "method": "POST", "path": "/api/lab/thinfilm",
                                    "body": json.dumps({"film": "soap", "model": "airy"})}, [])
    assert sent[-1]["status"] == 200 and thinfilm.result["film"] == "soap"
    thinfilm._on_message(thinfilm, {"kind": "state", "address": "film=soap&model=airy&d=0"}, [])
    assert thinfilm.state["d"] == "0"
    s = thinfilm.spectrum
    # a free-standing film far thinner than the light's wavelength reflects nothing: the two faces'
    # reflections cancel (the black film, Newton's "black spot"); printed to 6 digits
    assert s.values.shape == (len(thinfilm.result["wavelengths_nm"]),) and s.names == ("soap 0 nm",)
    assert np.all(np.abs(s.values) <= 5e-7)
    thinfilm._on_message(thinfilm, {"kind": "state", "address": "film=soap&model=airy&d=420"}, [])
    assert thinfilm.spectrum.names == ("soap 420 nm",) and thinfilm.spectrum.values.max() > 0.05
    # a refused state leaves it and says why
    thinfilm._on_message(thinfilm, {"kind": "state", "address": 7}, [])
    assert thinfilm.state["d"] == "420" and "expected text" in thinfilm.last_error
    thinfilm.state = {**thinfilm.state, "d": 350}
    assert thinfilm.address == "film=soap&model=airy&d=350"


def test_the_reflectance_labs_spectrum_has_the_colour_asked_for():
    pytest.importorskip("anywidget")
    from spectrocolor.colorimetry import tristimulus

    w = nl.explore_lab("reflectance", x=0.45, y=0.4, Y=30)
    w.send = lambda _m: None
    w._on_message(w, {"kind": "request", "id": 2, "method": "POST", "path": "/api/lab/reflectance",
                      "body": json.dumps({"x": 0.45, "y": 0.4, "Y": 30, "step_nm": "10"})}, [])
    s = w.spectrum
    assert s.values.ndim == 2 and len(s.names) == s.values.shape[0] >= 1
    XYZ = tristimulus(s, illuminant="D65")
    xy = XYZ[:, :2] / XYZ.sum(axis=1, keepdims=True)
    # the reflectances are printed to 6 digits: the colour to about 1e-5
    assert np.allclose(xy, [0.45, 0.4], atol=1e-4) and np.allclose(XYZ[:, 1], 30, atol=1e-2)
