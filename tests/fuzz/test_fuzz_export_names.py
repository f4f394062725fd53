"""Fuzz: /api/export's names (issue 28, glitch 8, widened to any one-line text but path
separators, quotes and angle brackets). Any text gives a file or one clear 422 naming ``names``,
never a 5xx; a name the route accepts comes back from /api/import unchanged (CSV's spreadsheet
guard apart: an apostrophe before a formula start)."""

from __future__ import annotations

import pytest
from fastapi.testclient import TestClient
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from spectrocolor.app.server import create_app
from spectrocolor.spreadsheet import FORMULA_STARTS


@pytest.fixture(scope="module")
def client():
    with TestClient(create_app(), base_url="http://127.0.0.1") as c:
        yield c


@settings(max_examples=80, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(name=st.text(max_size=70), fmt=st.sampled_from(["csv", "json"]))
def test_any_name_gives_a_file_or_one_clear_refusal(client, name, fmt):
    r = client.post("/api/export", json={"format": fmt, "names": [name], "spectra": [[3.0] * 31]})
    assert r.status_code in (200, 422), r.text
    if r.status_code == 422:
        assert "names" in r.json()["error"]
        return
    back = client.post("/api/import", json={"filename": f"s.{fmt}", "content": r.text,
                                            "scale": "levels", "step_nm": 10})
    assert back.status_code == 200, back.text
    got = back.json()["names"][0]
    guarded = fmt == "csv" and name.startswith(FORMULA_STARTS)
    assert got == ("'" + name if guarded else name) or got == name.strip(), (name, got)
