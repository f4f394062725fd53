"""Hostile messages and arguments to ``sc.explore_lab``'s kernel side
(spectrocolor.app.notebook_labs): whatever a lab's page (or anything else on the widget's comm)
sends, the answer is one reply in the widget's shapes, a refusal one line, never a traceback; and
``explore_lab``'s settings are taken or refused with one SpectrumError naming the setting.

Drawn by hypothesis: requests to every lab route with bodies made of the lab request models' fields
(values of every JSON kind), ``state`` messages with addresses of any text, and the labs' settings.
"""

from __future__ import annotations

import json

import pytest

pytest.importorskip("fastapi")
hypothesis = pytest.importorskip("hypothesis")
from hypothesis import given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402

from spectrocolor import SpectrumError  # noqa: E402
from spectrocolor.app import notebook_labs as nl  # noqa: E402

FINITE = st.floats(allow_nan=False, allow_infinity=False)
SCALARS = st.one_of(st.none(), st.booleans(), st.integers(-10**20, 10**20), FINITE, st.text(max_size=30))
VALUES = st.recursive(SCALARS, lambda inner: st.lists(inner, max_size=5) | st.dictionaries(st.text(max_size=8), inner,
                                                                                          max_size=4), max_leaves=12)
PATHS = st.sampled_from([p for _m, p in nl.lab_routes()] + ["/api/lab/", "/api/lab/solid/x", "/api/demos",
                                                            "/labs/thinfilm"]) | st.text(max_size=40)
SOURCES = st.fixed_dictionaries({}, optional={
    "kind": st.sampled_from(["named", "leds", "temperature", "x"]) | VALUES,
    "name": st.sampled_from(["FL2", "D65", "A", "?"]) | VALUES, "light": st.sampled_from(["blackbody", "x"]),
    "temperature_K": st.floats(-1e6, 1e6) | VALUES, "peaks_nm": st.lists(FINITE, max_size=6) | VALUES,
    "widths_nm": st.lists(FINITE, max_size=6) | VALUES, "powers": st.lists(FINITE, max_size=6) | VALUES})
BODY_FIELDS = {"film": st.sampled_from(["soap", "oil", "tar"]) | VALUES,
               "model": st.sampled_from(["airy", "two-beam", "x"]) | VALUES,
               "angle_deg": st.floats(-100, 100) | VALUES,
               "illuminant": st.sampled_from(["D65", "A", "F11", "?"]) | VALUES,
               "observer": st.sampled_from(["1931", "1964", "x"]) | VALUES, "display": st.sampled_from(["sRGB", "?"]),
               "x": st.floats(-1, 2) | VALUES, "y": st.floats(-1, 2) | VALUES, "Y": st.floats(-10, 200) | VALUES,
               "step_nm": st.sampled_from(["5", "10", "1", 5]) | VALUES, "sample": st.integers(-3, 20) | VALUES,
               "second_illuminant": st.sampled_from(["A", "?"]) | VALUES, "source": SOURCES | VALUES,
               "extra": VALUES}
BODIES = st.fixed_dictionaries({}, optional=BODY_FIELDS).map(json.dumps) | st.text(max_size=60) | VALUES


def check(reply):
    assert isinstance(reply, dict) and reply["kind"] in ("response", "error", "state")
    if reply["kind"] == "error":
        assert isinstance(reply["message"], str) and 0 < len(reply["message"]) < 500 and "\n" not in reply["message"]
    elif reply["kind"] == "response":
        assert isinstance(reply["status"], int) and 200 <= reply["status"] < 600
        if reply["status"] >= 400:
            error = json.loads(reply["body"])["error"]
            assert isinstance(error, str) and 0 < len(error) < 2000 and "Traceback" not in error
    else:
        assert isinstance(reply["state"], dict) and all(isinstance(v, str) for v in reply["state"].values())


@settings(max_examples=120, deadline=None)
@given(lab=st.sampled_from(nl.LABS),
       message=st.fixed_dictionaries({"kind": st.just("request"), "id": st.integers(0, 10)},
                                     optional={"method": st.sampled_from(["GET", "POST", "PUT"]) | VALUES,
                                               "path": PATHS | VALUES, "body": BODIES}))
@pytest.mark.slow
def test_hostile_lab_requests_get_an_answer_or_one_clear_error(lab, message):
    check(nl.handle_lab_message(lab, message))


ADDRESSES = st.text(max_size=80) | st.lists(st.tuples(st.text(max_size=12), st.text(max_size=12)), max_size=8).map(
    lambda pairs: "&".join(f"{k}={v}" for k, v in pairs)) | st.text(min_size=1990, max_size=2100) | VALUES


@settings(max_examples=200, deadline=None)
@given(lab=st.sampled_from(nl.LABS),
       message=st.fixed_dictionaries({"kind": st.sampled_from(["state", "request", "edited"]) | VALUES},
                                     optional={"address": ADDRESSES, "id": VALUES}) | VALUES)
def test_hostile_state_messages_and_anything_else_get_one_line(lab, message):
    if isinstance(message, dict) and message.get("kind") == "request":
        message = {**message, "path": "/api/lab/solid/options", "method": "GET"}  # cheap; bodies are fuzzed above
    check(nl.handle_lab_message(lab, message))


@settings(max_examples=200, deadline=None)
@given(lab=st.sampled_from(nl.LABS) | st.text(max_size=12) | VALUES,
       settings_=st.dictionaries(st.sampled_from(sorted({k for ks in nl.ADDRESS_KEYS.values() for k in ks})
                                                 + ["thickness", "spectrum_", "x y"]),
                                 SCALARS | st.floats() | st.text(min_size=190, max_size=220), max_size=5))
def test_explore_lab_settings_are_taken_or_refused_in_one_line(lab, settings_):
    try:
        address = nl.initial_address(lab, **settings_)
    except SpectrumError as exc:
        assert "\n" not in str(exc) and len(str(exc)) < 400
    else:
        state = nl.check_address(address)
        assert set(state) == set(settings_) and set(state) <= set(nl.ADDRESS_KEYS[lab])
