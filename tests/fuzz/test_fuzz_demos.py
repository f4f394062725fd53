"""Fuzz: the demo loader (issue 28, item 2). Any bytes in a demo file, any JSON value, and any
small change to a valid demo give a demo or one :class:`DemoError` that names the file, never
another exception."""

from __future__ import annotations

import copy
import json

from hypothesis import HealthCheck, example, given, settings
from hypothesis import strategies as st

from spectrocolor.app import demos as D

GOOD = json.loads((D.DEMO_FOLDER / "notch-540.json").read_text(encoding="utf-8"))
JSON = st.recursive(st.none() | st.booleans() | st.integers(-100, 2000) | st.floats(allow_nan=False)
                    | st.text(max_size=20),
                    lambda inner: st.lists(inner, max_size=5)
                    | st.dictionaries(st.text(max_size=12), inner, max_size=5),
                    max_leaves=30)
SETTINGS = settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])


def _load(tmp_path, raw: bytes):
    path = tmp_path / "notch-540.json"
    path.write_bytes(raw)
    try:
        return D.load_demo(path)
    except D.DemoError as exc:
        assert str(exc).startswith("demo file notch-540.json: ")
        assert "\n" not in str(exc)
        return None


@SETTINGS
@given(raw=st.binary(max_size=400))
def test_any_bytes(tmp_path, raw):
    _load(tmp_path, raw)


@SETTINGS
@given(value=JSON)
def test_any_json_value(tmp_path, value):
    _load(tmp_path, json.dumps(value).encode())


def _paths(value, prefix=()):
    """Every (container, key) inside a parsed demo."""
    if isinstance(value, dict):
        for k, v in value.items():
            yield prefix + (k,)
            yield from _paths(v, prefix + (k,))
    elif isinstance(value, list):
        for i, v in enumerate(value):
            yield prefix + (i,)
            yield from _paths(v, prefix + (i,))


PATHS = list(_paths(GOOD))


@SETTINGS
@given(where=st.sampled_from(PATHS), value=JSON, drop=st.booleans())
# found by the fresh-clone run: a list where a name belongs raised TypeError (unhashable) in the checks
@example(where=("where",), value=[], drop=False)
@example(where=("state", "distributions", 0, "preset"), value=[], drop=False)
def test_a_valid_demo_changed_in_one_place(tmp_path, where, value, drop):
    demo = copy.deepcopy(GOOD)
    box = demo
    for k in where[:-1]:
        box = box[k]
    if drop:
        del box[where[-1]]
    else:
        box[where[-1]] = value
    _load(tmp_path, json.dumps(demo).encode())


@settings(max_examples=40, deadline=None)
@given(query=st.text(max_size=40))
def test_the_route_ignores_any_query(query):
    from fastapi.testclient import TestClient

    from spectrocolor.app.server import create_app

    client = TestClient(create_app(), base_url="http://127.0.0.1")
    r = client.get("/api/demos", params={"q": query})
    assert r.status_code == 200
    assert [d["id"] for d in r.json()["demos"]] == [d["id"] for d in D.load_demos(D.DEMO_FOLDER)]
