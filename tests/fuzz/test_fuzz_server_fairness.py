"""The interactive lane and the client token under generated input (issue 31).

Whatever a client sends as its tab token (:data:`spectrocolor.app.guards.CLIENT_HEADER`) and as
the body of a route answered in the interactive lane, the answer is a 2xx or a 4xx in the one
error shape, never a 5xx, and its JSON has no NaN or infinity.
"""

from __future__ import annotations

import json

import pytest
from fastapi.testclient import TestClient
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from spectrocolor.app.guards import CLIENT_HEADER, client_key
from spectrocolor.app.server import create_app

LANE = ["/api/model", "/api/evaluate", "/api/metamer", "/api/export"]
#: Header values a client can send (HTTP forbids CR, LF and NUL in them).
TOKENS = st.text(st.characters(min_codepoint=32, max_codepoint=126), max_size=100)
JSON_VALUES = st.recursive(
    st.none() | st.booleans() | st.integers(-10**6, 10**6) | st.floats(allow_nan=False)
    | st.text(max_size=20),
    lambda children: st.lists(children, max_size=8) | st.dictionaries(
        st.sampled_from(["step_nm", "observer", "display", "illuminant", "spectra", "pairs",
                         "target", "names", "format", "gamut", "normalise", "adaptation", "x"]),
        children, max_size=6),
    max_leaves=40)


@pytest.fixture(scope="module")
def client():
    return TestClient(create_app(), base_url="http://127.0.0.1")


def _strict(body: bytes):
    def refuse(constant):
        raise AssertionError(f"non-finite number {constant} in an answer")
    return json.loads(body, parse_constant=refuse)


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(route=st.sampled_from(LANE), payload=JSON_VALUES, token=TOKENS)
def test_generated_bodies_and_tokens_never_give_a_5xx(client, route, payload, token):
    answer = client.post(route, content=json.dumps(payload).encode(),
                         headers={"Content-Type": "application/json", CLIENT_HEADER: token})
    assert answer.status_code < 500, answer.text
    if answer.headers["content-type"].startswith("application/json"):
        body = _strict(answer.content)
        if answer.status_code >= 400:
            assert set(body) == {"error"}, body


@given(token=TOKENS, address=st.sampled_from(["127.0.0.1", "::1", "203.0.113.7"]))
def test_a_token_is_kept_only_when_it_is_a_token(token, address):
    key = client_key({"client": (address, 1234),
                      "headers": [(CLIENT_HEADER.lower().encode(), token.encode("latin-1"))]})
    assert key[0] == address
    valid = 8 <= len(token) <= 64 and all(c.isascii() and (c.isalnum() or c in "-_") for c in token)
    assert key[1] == (token if valid else None)
