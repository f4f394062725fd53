"""The registries drive every interface: a gamut strategy added in ONE place -- the library's
registry -- is offered by ``/api/options``, accepted by the request validation, listed on the page
and in the command line's ``--help``; an unknown name is refused with a 422 naming the accepted
values. This is the worked example of ``docs/design.md`` ("Adding a gamut strategy").

The new strategy is registered inside the test, after every module was imported (the app's
request models included), and removed again afterwards.
"""

from __future__ import annotations

import numpy as np
import pytest
from fastapi.testclient import TestClient

from spectrocolor.app.server import EvaluateRequest, create_app
from spectrocolor.cli import main
from spectrocolor.display.gamut import GAMUT_STRATEGIES, clip
from spectrocolor.display.render import render

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
