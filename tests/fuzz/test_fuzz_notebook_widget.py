"""Hostile messages to ``sc.explore``'s kernel side (spectrocolor.app.notebook_widget.handle_message):
whatever a page (or anything else on the widget's comm) sends, the answer is one reply in the
widget's shapes, a refusal being one line, never a traceback.

Messages are drawn by hypothesis from the fields the front end sends, with values of every JSON kind
(huge integers, negative ids, nested lists, text, paths of every route and none), plus unknown keys.
"""

from __future__ import annotations

import json

import pytest

pytest.importorskip("fastapi")
hypothesis = pytest.importorskip("hypothesis")
from hypothesis import given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402

from spectrocolor.app.notebook_widget import handle_message  # noqa: E402

FINITE = st.floats(allow_nan=False, allow_infinity=False)
SCALARS = st.one_of(st.none(), st.booleans(), st.integers(-10**20, 10**20), FINITE, st.text(max_size=30))
VALUES = st.recursive(SCALARS, lambda inner: st.lists(inner, max_size=5) | st.dictionaries(st.text(max_size=8), inner,
                                                                                          max_size=4), max_leaves=12)
PATHS = st.sampled_from(["/api/options", "/api/presets?step_nm=10", "/api/presets?step_nm=x", "/api/model",
                         "/api/evaluate", "/api/metamer", "/api/export", "/api/relight", "/api/relight/options",
                         "/api/import", "/", "/api/evaluate?x=1#y", "//evil", "/api/../etc"]) | st.text(max_size=40)
LEVELS = st.lists(st.one_of(st.integers(-5, 40), FINITE, st.booleans(), st.none()), min_size=0, max_size=70)
BODY_FIELDS = {"step_nm": st.sampled_from([10, 5, 2, 1, 3, 0, "10", True]) | VALUES,
               "spectra": st.lists(LEVELS, max_size=5) | VALUES, "target": LEVELS | VALUES,
               "observer": st.sampled_from(["1931", "1964", "x"]) | VALUES, "pairs": VALUES,
               "display": st.sampled_from(["sRGB", "Display P3", "?"]) | VALUES, "names": VALUES,
               "format": st.sampled_from(["csv", "json", "xlsx"]) | VALUES, "image": VALUES, "extra": VALUES}
BODIES = st.fixed_dictionaries({}, optional=BODY_FIELDS).map(json.dumps) | st.text(max_size=60) | VALUES


def check(reply):
    assert isinstance(reply, dict) and reply["kind"] in ("response", "error", "edited")
    if reply["kind"] == "error":
        assert isinstance(reply["message"], str) and 0 < len(reply["message"]) < 500 and "\n" not in reply["message"]
    elif reply["kind"] == "response":
        assert isinstance(reply["status"], int) and 200 <= reply["status"] < 600
        if reply["status"] >= 400:
            error = json.loads(reply["body"])["error"]
            assert isinstance(error, str) and 0 < len(error) < 2000
            assert "Traceback" not in error
    else:
        assert all(isinstance(v, float) and 0 <= v <= 30 for v in reply["levels"])


@settings(max_examples=150, deadline=None)
@given(message=st.fixed_dictionaries({"kind": st.just("request")},
                                     optional={"id": st.integers(-10, 2**60) | VALUES,
                                               "method": st.sampled_from(["GET", "POST", "PUT"]) | VALUES,
                                               "path": PATHS | VALUES, "body": BODIES}))
@pytest.mark.slow
def test_hostile_requests_get_an_answer_or_one_clear_error(message):
    check(handle_message(message))


@settings(max_examples=150, deadline=None)
@given(message=st.fixed_dictionaries({"kind": st.sampled_from(["edited", "request", "x"]) | VALUES},
                                     optional={"levels": LEVELS | VALUES,
                                               "step_nm": st.sampled_from([10, 5, 2, 1, 7, -1, "10", True, None])
                                               | VALUES, "id": VALUES})
       | VALUES)
def test_hostile_edits_and_anything_else_get_one_line(message):
    check(handle_message(message))
