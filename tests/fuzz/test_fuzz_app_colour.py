"""Fuzz the explorer's colour choices (issue 13): every combination of display, white adaptation,
normalisation and gamut strategy, with random SPECTRA levels and random (also one-line)
illuminants, answers 200 with finite numbers, or a clear 422 naming the field."""

from __future__ import annotations

import math

import numpy as np
import pytest
from fastapi.testclient import TestClient
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from spectrocolor.app import compute
from spectrocolor.app.server import create_app

CLIENT = TestClient(create_app(), base_url="http://127.0.0.1")
levels = st.lists(st.integers(0, 30), min_size=31, max_size=31)
illuminants = st.one_of(
    st.none(),
    st.integers(0, 30).map(lambda k: [30 if i == k else 0 for i in range(31)]),  # one line
    levels.filter(lambda v: max(v) > 0),
)


def finite_or_none(value) -> bool:
    if value is None or isinstance(value, (str, bool)):
        return True
    if isinstance(value, (int, float)):
        return math.isfinite(value)
    if isinstance(value, list):
        return all(finite_or_none(v) for v in value)
    if isinstance(value, dict):
        return all(finite_or_none(v) for v in value.values())
    return False


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(spectra=st.lists(levels, min_size=1, max_size=4), illuminant=illuminants,
       display=st.sampled_from(compute.DISPLAYS), adaptation=st.sampled_from(list(
           compute.ADAPTATIONS)), normalise=st.sampled_from(compute.NORMALISATIONS),
       gamut=st.sampled_from(compute.GAMUTS))
@pytest.mark.slow
def test_every_colour_choice_answers_with_finite_numbers(spectra, illuminant, display,
                                                          adaptation, normalise, gamut):
    body = {"spectra": spectra, "display": display, "adaptation": adaptation,
            "normalise": normalise, "gamut": gamut}
    if illuminant is not None:
        body["illuminant"] = illuminant
    r = CLIENT.post("/api/evaluate", json=body)
    assert r.status_code == 200, r.text
    answer = r.json()
    assert finite_or_none(answer)
    top = 63 if display.startswith("SPECTRA") else 255
    for c, s in zip(answer["colours"], spectra, strict=True):
        assert all(0 <= v <= top for v in c["codes"])
        assert min(c["emitted_levels"]) >= 0
        # never a bare black patch unless the light is black or the strict view was chosen; a colour
        # whose luminance on the display is not positive (adapted in display RGB far outside the
        # gamut) leaves black under the luminance-keeping strategies, and the explanation says so
        if c["XYZ"][1] > 1 and gamut != "flag":
            if max(c["codes"]) == 0 and gamut in ("desaturate", "preserve-luminance"):
                assert "luminance on this display is not positive" in c["explanation"], (s, c["explanation"])
            else:
                assert max(c["codes"]) > 0, (s, c["explanation"])
        assert (c["gamut_applied"] is None) == c["in_gamut"]
    m = CLIENT.post("/api/model", json={k: v for k, v in body.items()
                                        if k not in ("spectra", "gamut")})
    assert m.status_code == 200 and finite_or_none(m.json())


@settings(max_examples=40, deadline=None)
@given(field=st.sampled_from(["adaptation", "normalise", "gamut"]),
       value=st.one_of(st.text(max_size=20), st.integers(), st.none(), st.booleans()))
def test_unknown_choices_get_a_clear_422(field, value):
    accepted = {"adaptation": list(compute.ADAPTATIONS), "normalise": compute.NORMALISATIONS,
                "gamut": compute.GAMUTS}[field]
    if value in accepted:
        return
    r = CLIENT.post("/api/evaluate", json={"spectra": [[15] * 31], field: value})
    assert r.status_code == 422 and field in r.json()["error"], r.text


def test_the_fuzzed_grid_matches_the_page():
    assert len(compute.grid(10.0)) == 31 and np.isclose(compute.grid(10.0)[19], 590.0)


# Setting 5's two spotlights (issue 28 item 7): the ``additive`` pairs of /api/evaluate, any
# indices and any number of them: 200 with one colour more per pair (their sum, possibly above the
# full level, still finite), or one 422 line naming ``additive``.
@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(spectra=st.lists(levels, min_size=1, max_size=4),
       additive=st.lists(st.tuples(st.integers(-2, 5), st.integers(-2, 5)), max_size=4),
       gamut=st.sampled_from(compute.GAMUTS), normalise=st.sampled_from(compute.NORMALISATIONS))
def test_additive_pairs_answer_or_name_the_field(spectra, additive, gamut, normalise):
    r = CLIENT.post("/api/evaluate", json={"spectra": spectra, "additive": additive, "gamut": gamut,
                                           "normalise": normalise})
    fits = all(0 <= a < len(spectra) and 0 <= b < len(spectra) for a, b in additive) \
        and len(spectra) + len(additive) <= 4
    if not fits:
        assert r.status_code == 422 and "additive" in r.json()["error"], r.text
        assert "\n" not in r.json()["error"]
        return
    assert r.status_code == 200, r.text
    answer = r.json()
    assert finite_or_none(answer) and len(answer["colours"]) == len(spectra) + len(additive)
