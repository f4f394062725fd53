"""Hostile JSON to the labs' routes: every answer is a 200 or a 422 with the server's one error shape.

Bodies are drawn by hypothesis from the fields each route knows, with values of every JSON kind
(numbers out of range, NaN-like strings, nested lists, huge integers, text) plus unknown keys.
"""

from __future__ import annotations

import base64
from pathlib import Path

import pytest

pytest.importorskip("fastapi")
hypothesis = pytest.importorskip("hypothesis")
from fastapi.testclient import TestClient  # noqa: E402
from hypothesis import HealthCheck, given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402

from spectrocolor.app.server import create_app  # noqa: E402

FINITE = st.floats(allow_nan=False, allow_infinity=False)  # JSON has no NaN or infinity
NAMES = st.sampled_from(["D65", "A", "FL11", "blackbody:3000", "D:5000", "sRGB", "soap", "tio2", "airy", "two-beam",
                         "5", "10", "1931"])
SCALARS = st.one_of(st.none(), st.booleans(), st.integers(-10**20, 10**20), FINITE, st.text(max_size=30), NAMES)
VALUES = st.recursive(SCALARS, lambda inner: st.lists(inner, max_size=5) | st.dictionaries(st.text(max_size=8), inner,
                                                                                          max_size=4), max_leaves=12)
FIELDS = {
    "/api/lab/thinfilm": ["film", "model", "angle_deg", "illuminant", "observer", "display"],
    "/api/lab/reflectance": ["x", "y", "Y", "illuminant", "observer", "step_nm"],
    "/api/lab/light": ["source", "display"],
    "/api/lab/solid/section": ["illuminant", "display", "Y"],
}


@pytest.fixture(scope="module")
def client():
    return TestClient(create_app(), base_url="http://127.0.0.1")


def check(response):
    assert response.status_code in (200, 422), (response.status_code, response.text[:300])
    if response.status_code == 422:
        error = response.json()["error"]
        assert isinstance(error, str) and 0 < len(error) < 2000


@settings(max_examples=80, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(data=st.data())
@pytest.mark.slow
def test_hostile_bodies_get_an_answer_or_one_clear_error(client, data):
    route = data.draw(st.sampled_from(sorted(FIELDS)))
    keys = st.sampled_from(FIELDS[route] + ["extra"])
    body = data.draw(st.dictionaries(keys, VALUES, max_size=len(FIELDS[route]) + 1) | VALUES)
    check(client.post(route, json=body))


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(source=st.fixed_dictionaries({"kind": st.just("leds"),
                                     "peaks_nm": st.lists(st.floats(300, 900), min_size=0, max_size=6),
                                     "widths_nm": st.lists(st.floats(0, 400), min_size=0, max_size=6),
                                     "powers": st.lists(st.floats(-1, 2), min_size=0, max_size=6)}))
def test_led_mixtures_of_any_shape(client, source):
    check(client.post("/api/lab/light", json={"source": source}))


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(x=st.floats(-1, 2), y=st.floats(-1, 2), Y=st.floats(-10, 200))
def test_any_colour_for_the_reflectance_lab(client, x, y, Y):
    check(client.post("/api/lab/reflectance", json={"x": x, "y": y, "Y": Y, "step_nm": "10"}))


@pytest.mark.parametrize("body", [{"sample": 0}, {"sample": 15}, {"sample": "9"}, {"second_illuminant": "X"},
                                  {"illuminant": None}, {"sample": 1.5}, [1, 2], "sample"])
def test_mismatch_refuses_bad_requests_clearly(client, body):
    response = client.post("/api/lab/solid/mismatch", json=body)
    assert response.status_code == 422 and isinstance(response.json()["error"], str)


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(step=st.sampled_from([1, 5, 10, 2, 0, -10, 10.5, "10", None]),
       levels=st.lists(st.floats(-5, 40) | st.integers(-5, 10**30) | st.text(max_size=3) | st.none(),
                       min_size=0, max_size=320)
       | st.sampled_from([31, 61, 301]).flatmap(lambda n: st.lists(st.integers(0, 30), min_size=n, max_size=n)),
       label=st.text(max_size=250) | st.none() | st.integers())
def test_the_explorers_distribution_of_any_shape(client, step, levels, label):
    """The explorer's distribution (kind "explorer", issue 28): a light over 400-700 nm whose
    metrics are None with the library's reasons, or one clear error."""
    body = {"kind": "explorer", "step_nm": step, "levels": levels, **({"label": label} if label is not None else {})}
    response = client.post("/api/lab/light", json={"source": body})
    check(response)
    if response.status_code == 200:
        answer = response.json()
        # exact: the range is two grid wavelengths (380 + 5 k nm), copied, not computed
        assert answer["range_nm"] == [400.0, 700.0] and answer["summary"]["Ra"] is None
        assert all("380" in r["reason"] for r in answer["reasons"]) and len(answer["reasons"]) == 4


# ---- the light lab's uploaded SPD (issue 28 item 6): the upload route and the "spd" source ----------

LAMPS = [(Path(__file__).parents[1] / "data" / "io" / name).read_bytes()
         for name in ("sekonic_c800.csv", "cl500a_memory.csv", "argyll.sp")]


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(values=st.lists(st.floats(-1, 1e6) | st.integers(-5, 10**30) | st.text(max_size=4) | st.none(),
                       min_size=0, max_size=90) | st.lists(st.just(0.0), min_size=81, max_size=81),
       label=st.text(max_size=250) | st.none() | st.integers())
def test_an_spd_light_of_any_shape(client, values, label):
    body = {"kind": "spd", "values": values, **({"label": label} if label is not None else {})}
    response = client.post("/api/lab/light", json={"source": body})
    check(response)
    if response.status_code == 200:
        assert response.json()["label"] == label and len(values) == 81


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(data=st.binary(max_size=3000) | st.sampled_from(LAMPS).flatmap(
           lambda lamp: st.integers(0, len(lamp)).map(lambda n: lamp[:n])),  # cut anywhere
       filename=st.text(min_size=0, max_size=220) | st.sampled_from(["lamp.csv", "lamp.json", "a.sp"]),
       raw=st.none() | st.text(max_size=40) | st.integers(),
       extra=st.dictionaries(st.sampled_from(["content", "step_nm", "scale", "observer", "unknown"]), SCALARS,
                             max_size=2))
def test_hostile_light_uploads_get_a_light_or_one_clear_error(client, data, filename, raw, extra):
    body = {"filename": filename, "content_base64": base64.b64encode(data).decode() if raw is None else raw,
            **extra}
    response = client.post("/api/lab/light/upload", json=body)
    assert response.status_code in (200, 422, 429), response.text[:300]
    answer = response.json()
    if response.status_code == 200:
        # exact: x / max(x) at the maximum is 1.0 (IEEE division of a number by itself), rounded to 6 decimals
        assert len(answer["spd"]) == 81 and max(answer["spd"]) == 1.0 and min(answer["spd"]) >= 0
        assert "\0" not in answer["label"] and answer["label"].startswith(filename)
    else:
        error = answer["error"]
        assert isinstance(error, str) and 0 < len(error) < 2000 and "\n" not in error and "\0light" not in error

# ---- issue 28 item 6: a sample handed over by the explorer (levels 0-30 on 400-700 nm) ----

LEVEL_VALUES = st.one_of(st.floats(-5, 40), st.integers(-5, 40), st.none(), st.text(max_size=4))


@settings(max_examples=25, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(levels=st.lists(LEVEL_VALUES, min_size=0, max_size=320) | VALUES,
       step=st.one_of(st.sampled_from([10, 5, 2, 1, 3, 0, -1, 10.5]), SCALARS))
def test_handed_levels_of_any_shape_get_an_answer_or_one_clear_error(client, levels, step):
    check(client.post("/api/lab/solid/mismatch", json={"levels": levels, "levels_step_nm": step}))


@settings(max_examples=200, deadline=None)
@given(levels=st.lists(st.floats(allow_nan=True, allow_infinity=True, width=32), max_size=320),
       step=st.sampled_from([10.0, 5.0, 2.0, 1.0, 3.0, 0.0, float("nan")]))
def test_explorer_reflectance_is_a_reflectance_or_one_clear_error(levels, step):
    import numpy as np

    from spectrocolor.app import solid_lab
    from spectrocolor.errors import ColorimetryError

    try:
        r = solid_lab.explorer_reflectance(levels, step)
    except ColorimetryError as exc:
        assert str(exc).split(":")[0] in ("levels", "levels_step_nm")
        return
    assert r.shape == (41,) and np.all((r >= 0.0) & (r <= 1.0))


@pytest.mark.parametrize("body", [{"levels": [15.0] * 30}, {"levels": [15.0] * 31, "levels_step_nm": 5},
                                  {"levels": [31.0] * 31}, {"levels": [-1.0] * 31}, {"levels": "15,15"},
                                  {"levels": [15.0] * 302}, {"levels": [15.0] * 31, "levels_step_nm": 3}])
def test_bad_handed_levels_are_refused_clearly(client, body):
    response = client.post("/api/lab/solid/mismatch", json=body)
    assert response.status_code == 422 and "levels" in response.json()["error"]
