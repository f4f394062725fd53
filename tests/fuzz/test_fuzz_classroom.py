"""Classroom mode's routes and transport under generated input (issue 30).

Whatever a page sends to the class's routes (bodies, join codes, teacher keys, cookies), the
answer is a 2xx, a 303 (the right code only) or a 4xx in the one error shape, never a 5xx; what
the server keeps stays bounded (received states, their length, rate-limit buckets); and an
event of the Server-Sent Events stream is always one event, whatever text it carries.
"""

from __future__ import annotations

import json
import urllib.parse

import pytest
from fastapi.testclient import TestClient
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from spectrocolor.app import classroom as cm
from spectrocolor.app import lab_routes, relight_routes, server

JSON_VALUES = st.recursive(
    st.none() | st.booleans() | st.integers(-10**6, 10**6) | st.floats(allow_nan=False)
    | st.text(max_size=30) | st.sampled_from(["/", "/?s=2&b=10", "//x", "/?" + "a" * 9000]),
    lambda children: st.lists(children, max_size=6) | st.dictionaries(
        st.sampled_from(["state", "name", "x"]), children, max_size=3),
    max_leaves=20)
#: Header values a client can send (HTTP forbids CR, LF and NUL in them).
HEADER_TEXT = st.text(st.characters(min_codepoint=32, max_codepoint=126), max_size=200)
FUZZ = settings(max_examples=60, deadline=None,
                suppress_health_check=[HealthCheck.function_scoped_fixture])


@pytest.fixture(scope="module")
def room():
    """An app in class mode (in this process), its class, and teacher and student clients."""
    pools = [server._interactive, lab_routes._workers, relight_routes._workers]
    before = [pool.unlimited_addresses for pool in pools]
    c = cm.Classroom("testserver", 8765)
    app = server.create_app(classroom=c)
    c.sends = cm.RateLimit(1e9, 1e9)  # the bounds of what is kept, not the rate, are fuzzed here
    c.requests = cm.RateLimit(1e9, 1e9)
    teacher = TestClient(app, base_url="http://testserver:8765", follow_redirects=False)
    student = TestClient(app, base_url="http://testserver:8765", follow_redirects=False)
    assert teacher.get(c.teacher_url()).status_code == 303
    assert student.get(c.join_url()).status_code == 303
    try:
        yield c, app, teacher, student
    finally:
        for pool, addresses in zip(pools, before, strict=True):
            pool.unlimited_addresses = addresses


def _one_error(answer):
    assert answer.status_code < 500, answer.text
    if answer.status_code >= 400:
        assert set(answer.json()) == {"error"}, answer.text


@FUZZ
@given(route=st.sampled_from(["/api/class/push", "/api/class/send"]), payload=JSON_VALUES,
       as_teacher=st.booleans())
def test_generated_bodies_never_give_a_5xx_and_what_is_kept_is_bounded(room, route, payload,
                                                                     as_teacher):
    c, _app, teacher, student = room
    answer = (teacher if as_teacher else student).post(
        route, content=json.dumps(payload).encode(), headers={"Content-Type": "application/json"})
    _one_error(answer)
    assert len(c.received) <= cm.MAX_RECEIVED
    assert all(cm.valid_state(e["state"]) and len(e["name"]) <= cm.MAX_NAME_CHARS
               for e in c.received)
    assert c.last_push is None or cm.valid_state(c.last_push)


@FUZZ
@given(path=st.sampled_from(["/join", "/teacher"]), value=HEADER_TEXT | st.text(max_size=40))
def test_generated_codes_and_keys_open_nothing(room, path, value):
    c, app, _teacher, _student = room
    stranger = TestClient(app, base_url="http://testserver:8765", follow_redirects=False)
    answer = stranger.get(path, params={"code" if path == "/join" else "key": value})
    if value in (c.code, c.teacher_key):
        assert answer.status_code == 303
    else:
        assert answer.status_code == 403 and set(answer.json()) == {"error"}
        assert stranger.get("/").status_code == 403


@FUZZ
@given(cookie=HEADER_TEXT, path=st.sampled_from(["/", "/api/class/whoami", "/api/class/events",
                                                 "/api/class/received", "/static/style.css"]))
def test_generated_cookies_are_refused_in_the_one_error_shape(room, cookie, path):
    _c, app, _teacher, _student = room
    stranger = TestClient(app, base_url="http://testserver:8765")
    answer = stranger.get(path, headers={"Cookie": cookie})
    assert answer.status_code == 403 and set(answer.json()) == {"error"}


@FUZZ
@given(host=HEADER_TEXT, origin=st.none() | HEADER_TEXT)
def test_a_generated_host_or_origin_other_than_the_class_is_refused(room, host, origin):
    _c, _app, _teacher, student = room
    headers = {"Host": host} | ({"Origin": origin} if origin is not None else {})
    answer = student.get("/api/class/whoami", headers=headers)
    _one_error(answer)
    if host.lower() != "testserver:8765" or (origin is not None
                                             and origin.lower() != "http://testserver:8765"):
        assert answer.status_code == 403


@FUZZ
@given(name=st.text(max_size=40), data=JSON_VALUES)
def test_an_event_is_always_one_event_whatever_text_it_carries(name, data):
    name = "".join(ch for ch in name if ch.isalnum()) or "push"
    text = cm._event(name, data).decode("utf-8")
    assert text.endswith("\n\n") and text.count("\n") == 3  # one event line, one data line
    event, payload = text[:-2].split("\n")
    assert event == f"event: {name}" and json.loads(payload.removeprefix("data: ")) == data


@FUZZ
@given(state=st.text(max_size=300) | st.text(max_size=10).map(lambda t: "//" + t))
def test_valid_state_refuses_anything_but_a_path_of_this_server(state):
    if cm.valid_state(state):
        assert state.startswith("/") and not state.startswith(("//", "/\\"))
        assert len(state) <= cm.MAX_STATE_CHARS and "\n" not in state
        assert ":" not in state.split("?")[0].split("#")[0]  # no scheme, in the path or before it


@FUZZ
@given(path=st.sampled_from(["/", "/labs/solid", "/labs/light", "/?s=2"]),
       fragment=st.text(max_size=200))
def test_a_lab_states_fragment_never_makes_it_another_origin(path, fragment):
    """A lab page keeps its state in the fragment (issue 30: lab pages in the class)."""
    state = f"{path}#{fragment}"
    if cm.valid_state(state):
        parts = urllib.parse.urlsplit(state)
        assert parts.scheme == "" and parts.netloc == "" and parts.path == path.split("?")[0]
        assert not any(ch in fragment for ch in "#<>\"\\ \n\r\t")


@FUZZ
@given(keys=st.lists(st.integers(0, 10**6), max_size=300))
def test_the_rate_limits_keep_a_bounded_number_of_clients(keys):
    limit = cm.RateLimit(rate=1.0, burst=2.0, max_keys=50)
    for key in keys:
        limit.allow(key, now=0.0)
    assert len(limit._buckets) <= 50
