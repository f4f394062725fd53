"""Setting 5 as two spotlights (issue 28 item 7): the ``additive`` pairs of ``/api/evaluate``, the
spotlight defaults and the demo format's ``mode``.

Golden facts, from seed 002 (Sällström, "Complementarity and circularity" and "Serial and
parallel composition") and Grassmann's additivity, not from this program's output: superimposed
lights add their spectra, so their tristimulus values add, and the mixture's chromaticity is the
centre of gravity of the components' chromaticities with weights X + Y + Z; two complementary
filters (r and 1 - r) in two identical spotlights give the light of one spotlight without a
filter; an orange-red and a green filter give yellow illumination.
"""

from __future__ import annotations

import numpy as np
import pytest
from fastapi.testclient import TestClient

from spectrocolor.app import demos as D
from spectrocolor.app import presets as P
from spectrocolor.app.server import create_app

CLIENT = TestClient(create_app(), base_url="http://127.0.0.1")
E = [30] * 31


def evaluate(spectra, additive, **options):
    r = CLIENT.post("/api/evaluate", json={"spectra": spectra, "additive": additive, **options})
    assert r.status_code == 200, r.text
    return r.json()["colours"]


@pytest.mark.parametrize("key", [row[0] for row in P.SETTING5_ADDITIVE])
def test_the_overlap_is_the_sum_and_lies_between_the_lights(key):
    _, _, a, b = next(row for row in P.SETTING5_ADDITIVE if row[0] == key)
    c = evaluate([E, a, b], [[1, 2]])
    assert len(c) == 4
    X1, X2, X3 = (np.array(c[i]["XYZ"]) for i in (1, 2, 3))
    # tristimulus values are sums over ~31 bins of products: a few ulps of Y = 100 apart
    np.testing.assert_allclose(X3, X1 + X2, rtol=0, atol=1e-12)
    # the centre of gravity, weights X + Y + Z (rounding only: one division of sums)
    s1, s2 = X1.sum(), X2.sum()
    centre = (s1 * np.array(c[1]["xy"]) + s2 * np.array(c[2]["xy"])) / (s1 + s2)
    np.testing.assert_allclose(c[3]["xy"], centre, rtol=0, atol=1e-12)


@pytest.mark.parametrize("key", ["4", "5"])
def test_complementary_filters_give_one_unfiltered_spotlight(key):
    _, _, a, b = next(row for row in P.SETTING5_ADDITIVE if row[0] == key)
    assert [u + v for u, v in zip(a, b, strict=True)] == E  # exact: whole levels, r + (30 - r)
    c = evaluate([E, a, b], [[1, 2]])
    np.testing.assert_allclose(c[3]["XYZ"], c[0]["XYZ"], rtol=0, atol=1e-12)  # same sums, reordered
    assert c[3]["codes"] == c[0]["codes"]


def test_orange_red_and_green_give_yellow():
    c = evaluate([E, P.SPOT_RED, P.SPOT_GREEN], [[1, 2]])
    assert c[1]["dominant_nm"] > 592 and 500 < c[2]["dominant_nm"] < 565
    assert 565 <= c[3]["dominant_nm"] <= 592  # yellow: the bounds docs/demos.md gives
    assert c[3]["XYZ"][1] > max(c[1]["XYZ"][1], c[2]["XYZ"][1])  # brighter than either


def test_the_overlap_may_pass_the_full_level_and_pairs_may_name_it():
    r = CLIENT.post("/api/evaluate", json={"spectra": [E, E], "additive": [[0, 1]], "pairs": [[0, 2]]})
    assert r.status_code == 200, r.text
    c = r.json()["colours"]
    assert c[2]["XYZ"][1] == pytest.approx(200, abs=1e-9)  # two full spotlights: twice Y = 100
    assert len(r.json()["delta_e_2000"]) == 1


@pytest.mark.parametrize("body, words", [
    ({"spectra": [E], "additive": [[0, 1]]}, "additive (0, 1)"),
    ({"spectra": [E, E, E], "additive": [[0, 1], [1, 2]]}, "at most 4"),
    ({"spectra": [E, E], "additive": [[0, 1]], "pairs": [[0, 3]]}, "pair (0, 3)"),
    ({"spectra": [E, E], "additive": [[0, "x"]]}, "additive"),
])
def test_bad_pairs_get_one_clear_422(body, words):
    r = CLIENT.post("/api/evaluate", json=body)
    assert r.status_code == 422 and words in r.json()["error"], r.text


def test_band_shape():
    band = P._band(600, 700, 3)
    assert len(band) == 31 and band[20:] == [30] * 11 and band[19] == 15 and band[:19] == [3] * 19


def test_the_presets_route_serves_the_spotlights_on_every_grid():
    for step in (10, 5):
        p = CLIENT.get(f"/api/presets?step_nm={step}").json()
        rows = p["setting5_additive"]
        assert [q["key"] for q in rows] == [str(k) for k in range(1, 9)]
        assert all(len(q["left"]) == len(p["wavelengths_nm"]) for q in rows)


DEMO = {"id": "x", "title": "t", "where": "setting5", "look": "l", "question": "q?", "answer": "a",
        "state": {"mode": "additive", "distributions": [{"preset": "1"}, {"preset": "1"}]},
        "expect": [{"quantity": "Y", "patch": 3, "min": 1}]}


def test_a_demo_may_set_setting_5s_mode():
    assert D.validate_demo(DEMO, "x")["state"]["mode"] == "additive"


@pytest.mark.parametrize("state, words", [
    ({"mode": "spotlights", "distributions": [{"preset": "1"}, {"preset": "1"}]}, "mode must be one of"),
    ({"mode": ["additive"], "distributions": [{"preset": "1"}, {"preset": "1"}]}, "mode must be one of"),
])
def test_a_bad_mode_is_refused(state, words):
    with pytest.raises(D.DemoError, match=words):
        D.validate_demo({**DEMO, "state": state}, "x")


def test_mode_belongs_to_setting_5_only():
    demo = {**DEMO, "where": "setting3", "state": {"mode": "additive",
                                                   "distributions": [{"preset": "1"}, {"preset": "1"}]}}
    with pytest.raises(D.DemoError, match="unknown keys"):
        D.validate_demo(demo, "x")
