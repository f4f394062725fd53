"""The registries drive every interface: a gamut strategy -- and a kind of light -- added in ONE
place -- the library's registry -- is offered by ``/api/options``, accepted by the request
validation, listed on the page and in the command line's ``--help``; an unknown name is refused
with a 422 naming the accepted values. This is the worked example of ``docs/design.md``.

The new strategy and the new light kind are registered inside the test, after every module was
imported (the app's request models included), and removed again afterwards.
"""

from __future__ import annotations

import numpy as np
import pytest
from fastapi.testclient import TestClient

import spectrocolor as sc
from spectrocolor.app.server import EvaluateRequest, create_app
from spectrocolor.cli import main
from spectrocolor.display.gamut import GAMUT_STRATEGIES, clip
from spectrocolor.display.render import render
from spectrocolor.illuminants import ILLUMINANT_KINDS, LIGHT_KINDS, LightKind
from spectrocolor.radiators import blackbody

NAME = "halve-then-clip"
LABEL = "halve, then clip"
ACTION = "halved, then each channel clipped to 0-1"


def _halve_then_clip(rgb, luminance_row, tolerance):
    """A stand-in strategy: halve a colour the display cannot show, then clip what remains."""
    return clip(np.asarray(rgb, dtype=float) / 2, tolerance)


@pytest.fixture
def new_strategy():
    """The one place: ``GAMUT_STRATEGIES.add`` (with the label and the action the interfaces show)."""
    GAMUT_STRATEGIES.add(NAME, _halve_then_clip, "halve the colour, then clip each channel to [0, 1]",
                         label=LABEL, extra={"action": ACTION})
    try:
        yield NAME
    finally:
        GAMUT_STRATEGIES.remove(NAME)


@pytest.fixture(scope="module")
def client():
    return TestClient(create_app(), base_url="http://127.0.0.1")  # the Host a browser sends


def _evaluate(client, gamut):
    # a saturated green line: out of gamut on sRGB, so the strategy is applied
    levels = [0.0] * 31
    levels[12] = 30.0
    return client.post("/api/evaluate", json={"spectra": [levels], "gamut": gamut, "normalise": "per-colour"})


def test_the_new_strategy_is_offered_by_api_options(client, new_strategy):
    options = client.get("/api/options").json()
    assert new_strategy in options["gamuts"]
    assert [new_strategy, LABEL, ACTION] in options["choices"]["gamut"]
    assert options["gamut_actions"][new_strategy] == ACTION
    # before registration and after cleanup it is not there: the options are read live
    GAMUT_STRATEGIES.remove(new_strategy)
    try:
        assert new_strategy not in client.get("/api/options").json()["gamuts"]
    finally:
        GAMUT_STRATEGIES.add(new_strategy, _halve_then_clip, "again", label=LABEL, extra={"action": ACTION})


def test_the_request_validation_accepts_it_and_the_library_applies_it(client, new_strategy):
    r = _evaluate(client, new_strategy)
    assert r.status_code == 200, r.text
    colour = r.json()["colours"][0]
    assert colour["in_gamut"] is False and colour["gamut_applied"] == new_strategy
    assert colour["explanation"].endswith(ACTION)
    # the answer is the library's own rendering with the new strategy
    unmapped = np.array(colour["rgb_unmapped"])
    np.testing.assert_allclose(colour["rgb_linear"], np.clip(unmapped / 2, 0.0, 1.0), rtol=0, atol=1e-12)
    # the request model's schema lists it (the models were built before it was registered)
    assert new_strategy in EvaluateRequest.model_json_schema()["properties"]["gamut"]["enum"]
    # the photo panel's request takes the same vocabulary
    photo = client.post("/api/relight", json={"image": "x", "illuminant": [30.0] * 31, "gamut": "no-such"})
    assert photo.status_code == 422 and new_strategy in photo.json()["error"]


def test_an_unknown_name_gets_a_422_naming_the_accepted_values(client, new_strategy):
    r = _evaluate(client, "no-such-strategy")
    assert r.status_code == 422
    message = r.json()["error"]
    assert message.startswith("gamut: Input should be ")
    for name in GAMUT_STRATEGIES.names():
        assert repr(name) in message
    assert repr(new_strategy) in message


def test_after_cleanup_the_name_is_refused_again(client):
    assert NAME not in GAMUT_STRATEGIES
    r = _evaluate(client, NAME)
    assert r.status_code == 422 and NAME not in r.json()["error"].split("should be", 1)[1]


def test_the_command_line_help_lists_it(new_strategy, capsys):
    with pytest.raises(SystemExit) as done:
        main(["render", "--help"])
    assert done.value.code == 0
    help_text = " ".join(capsys.readouterr().out.split())  # argparse wraps lines
    assert new_strategy in help_text.split("--gamut {", 1)[1].split("}", 1)[0].split(",")
    assert "halve the colour, then clip each channel to [0, 1]" in help_text


def test_the_library_renders_with_it(new_strategy):
    rendering = render([[1.0, 60.0, 5.0]], "sRGB", normalise="per-colour", gamut=new_strategy)
    assert rendering.gamut == new_strategy and not bool(rendering.in_gamut[0])


@pytest.mark.browser
def test_the_page_lists_it(browser, base_url, new_strategy):
    """The page's select is filled from /api/options: the new strategy is an option with its
    label and tooltip, and choosing it shows the server's rendering (it has no local fast path)."""
    from appbrowser import open_page, settle

    with open_page(browser, base_url) as page:
        option = page.locator(f"#gamut option[value='{new_strategy}']")
        assert option.count() == 1
        assert option.inner_text() == LABEL and option.get_attribute("title") == ACTION
        page.select_option("#gamut", new_strategy)
        settle(page)
        assert page.evaluate("() => window.__spectra.server.gamut") == new_strategy


# ---- a kind of light, added in one place -------------------------------------------------------

KIND = "twice-blackbody"
KIND_LABEL = "Planckian radiator at 2T"
KIND_HELP = "a Planckian radiator at twice temperature_K"


def _twice_blackbody(temperature_K, wavelengths_nm):
    """A stand-in kind: the Planckian radiator at twice the temperature given."""
    return blackbody(2.0 * temperature_K, wavelengths_nm)


@pytest.fixture
def new_light_kind():
    """The one place: ``LIGHT_KINDS.add`` (a :class:`LightKind` with its prefix, label template,
    SPD function, reference and range, and the label and help the interfaces show)."""
    LIGHT_KINDS.add(KIND, LightKind(KIND, "blackbody at twice {T:g} K", _twice_blackbody, "this test",
                                    max_K=5.0e5), KIND_HELP, aliases=("tbb",), label=KIND_LABEL)
    try:
        yield KIND
    finally:
        LIGHT_KINDS.remove(KIND)


def test_the_library_resolves_and_uses_the_new_kind(new_light_kind):
    light = sc.resolve_illuminant(f"{new_light_kind}:5000")
    # exact: temperature_K is float("5000"), parsed from the name's text, not computed
    assert (light.name, light.kind, light.label, light.temperature_K) == (
        "twice-blackbody:5000", new_light_kind, "blackbody at twice 5000 K", 5000.0)
    assert sc.resolve_illuminant("TBB : 5000 K") == light  # an alias, any case, with K
    assert light.by_formula and new_light_kind in ILLUMINANT_KINDS
    grid = np.arange(400.0, 701.0, 10.0)
    np.testing.assert_allclose(light.spd(grid).values, sc.illuminant("blackbody:10000", grid).values,
                               rtol=1e-12, atol=0)
    reflectance = sc.Spectrum(grid, np.linspace(0.2, 0.8, grid.size))
    np.testing.assert_allclose(sc.tristimulus(reflectance, illuminant=f"{new_light_kind}:5000"),
                               sc.tristimulus(reflectance, illuminant="blackbody:10000"), rtol=1e-12, atol=0)
    with pytest.raises(sc.ColorimetryError, match="defined for 100–500000 K"):
        sc.resolve_illuminant(f"{new_light_kind}:600000")
    # the messages that list the forms name it
    with pytest.raises(sc.ColorimetryError, match="'twice-blackbody:T'"):
        sc.resolve_illuminant("no-such-kind:5000")


def test_after_cleanup_the_kind_is_unknown_again():
    assert KIND not in LIGHT_KINDS and KIND not in ILLUMINANT_KINDS
    with pytest.raises(sc.ColorimetryError, match="is not a CIE illuminant name"):
        sc.resolve_illuminant(f"{KIND}:5000")


def test_the_new_kind_is_offered_by_api_options(client, new_light_kind):
    options = client.get("/api/options").json()
    assert [new_light_kind, KIND_LABEL, KIND_HELP] in options["choices"]["light_kind"]
    assert {"name": new_light_kind, "label": KIND_LABEL, "help": KIND_HELP, "min_K": 100.0,
            "max_K": 5.0e5} in options["light_kinds"]
    lab_options = client.get("/api/lab/light/options").json()
    assert new_light_kind in [k["name"] for k in lab_options["light_kinds"]]


def test_the_light_lab_accepts_the_new_kind_and_refuses_an_unknown_one(client, new_light_kind):
    r = client.post("/api/lab/light", json={"source": {"kind": "temperature", "light": new_light_kind,
                                                       "temperature_K": 3000}})
    assert r.status_code == 200, r.text
    assert r.json()["label"] == "blackbody at twice 3000 K"
    expected = client.post("/api/lab/light", json={"source": {"kind": "named", "name": "blackbody:6000"}}).json()
    assert r.json()["spd"] == expected["spd"]  # exact: both are the same blackbody, rounded to 6 digits
    named = client.post("/api/lab/light", json={"source": {"kind": "named", "name": "tbb:3000"}})
    assert named.status_code == 200 and named.json()["label"] == "blackbody at twice 3000 K"
    bad = client.post("/api/lab/light", json={"source": {"kind": "temperature", "light": "no-such-kind",
                                                         "temperature_K": 3000}})
    assert bad.status_code == 422
    message = bad.json()["error"]
    assert "light: Input should be " in message
    for name in LIGHT_KINDS.names():
        assert repr(name) in message
    assert repr(new_light_kind) in message


def test_the_command_line_help_names_the_new_kind(new_light_kind, capsys):
    for command, option in ((["xyz", "--help"], "--illuminant"), (["relight", "--help"], "--to")):
        with pytest.raises(SystemExit) as done:
            main(command)
        assert done.value.code == 0
        help_text = "".join(capsys.readouterr().out.split())  # argparse wraps lines (at hyphens too)
        assert "blackbody:T,D:Tortwice-blackbody:T(Tinkelvin)" in help_text.split(f"{option}", 2)[2], command


@pytest.mark.browser
def test_the_light_lab_page_offers_the_new_kind(browser, base_url, new_light_kind):
    """The light lab's select is filled from the lab's options: the new kind is an option with its
    label and help, and choosing it shows the server's answer for it at the page's temperature."""
    from appbrowser import open_lab

    page, errors = open_lab(browser, base_url + "labs/light")
    try:
        option = page.locator(f"#name option[value='{new_light_kind}']")
        assert option.count() == 1
        assert option.inner_text() == f"{KIND_LABEL} (temperature below)"
        assert option.get_attribute("title") == KIND_HELP
        page.select_option("#name", new_light_kind)
        page.wait_for_function(
            "document.querySelector('#numbers').textContent.includes('blackbody at twice 3000 K')")
        assert page.locator("#temperature-box").is_visible()
        assert not errors, errors
    finally:
        page.close()
