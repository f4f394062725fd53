"""The smoothest-reflectance lab's numbers are the library's, and they mean what the page says."""

from __future__ import annotations

import numpy as np
import pytest

import spectrocolor as sc
from spectrocolor.app import reflectance_lab as lab
from spectrocolor.recovery.luminance_limit import max_luminance_factor

GRID = (380.0, 780.0, 5.0)


def test_the_three_solutions_are_the_librarys():
    out = lab.reflectance_lab(0.6, 0.33, 20.0)
    XYZ = sc.XYZ_from_xyY([0.6, 0.33, 20.0])
    for name, bounds in lab.BOUNDS:
        expected = sc.smoothest_reflectance(XYZ[None], illuminant="D65", wavelengths=GRID, bounds=bounds)
        np.testing.assert_allclose(out["solutions"][name]["reflectance"], expected.spectrum.values[0], atol=5e-7)
        assert out["solutions"][name]["converged"] == bool(expected.certificate.converged[0])


def test_inside_the_domain_of_validity_all_three_coincide_and_outside_the_bounds_act():
    inside = lab.reflectance_lab(0.35, 0.35, 30.0)
    assert inside["valid_up_to_Y"] is not None and inside["Y"] <= inside["valid_up_to_Y"]
    free, unit = inside["solutions"]["unconstrained"]["reflectance"], inside["solutions"]["unit"]["reflectance"]
    np.testing.assert_allclose(free, unit, atol=1e-6)
    outside = lab.reflectance_lab(0.6, 0.33, 20.0)
    assert outside["valid_up_to_Y"] is None and outside["solutions"]["unconstrained"]["min"] < 0
    assert outside["solutions"]["unit"]["min"] >= 0 and outside["solutions"]["unit"]["zero_nm"]


def test_a_colour_brighter_than_the_brightest_object_colour_is_infeasible_with_its_distance():
    top = float(max_luminance_factor([0.6, 0.33]))
    assert top == pytest.approx(lab.reflectance_lab(0.6, 0.33, 10.0)["max_Y"], abs=1e-4)
    over = lab.reflectance_lab(0.6, 0.33, min(99.0, top + 5.0))
    unit = over["solutions"]["unit"]
    assert not unit["feasible"] and unit["reflectance"] is None and unit["distance_outside"] > 0
    assert over["solutions"]["unconstrained"]["feasible"]  # the closed form always exists
    below = lab.reflectance_lab(0.6, 0.33, top - 0.5)
    assert below["solutions"]["unit"]["feasible"]


def test_the_brightest_colour_agrees_with_the_macadam_limit():
    """Two independent routes to the solid's boundary: rays at constant Y and a linear programme.

    HiGHS's primal feasibility tolerance (1e-7) on constraints of XYZ100 size bounds the LP's Y
    to about 1e-5.
    """
    xy = sc.xy(sc.macadam_limits(40.0, wavelengths=GRID, samples=12))
    np.testing.assert_allclose(max_luminance_factor(xy), 40.0, rtol=0, atol=1e-5)
    assert len(lab.macadam_xy(40.0)) == 180


@pytest.mark.parametrize(("arguments", "message"), [
    ((0.3, 0.0, 20.0), "x, y, Y"), ((0.3, 0.3, 0.0), "x, y, Y"), ((0.7, 0.5, 10.0), "x, y, Y"),
    ((0.3, 0.3, float("nan")), "x, y, Y"),
])
def test_bad_colours_get_one_clear_error(arguments, message):
    with pytest.raises(ValueError, match=message):
        lab.reflectance_lab(*arguments)


@pytest.mark.slow
def test_the_routes_answer_and_refuse_in_the_servers_shape():
    from fastapi.testclient import TestClient

    from spectrocolor.app.server import create_app

    client = TestClient(create_app(), base_url="http://127.0.0.1")
    ok = client.post("/api/lab/reflectance", json={"x": 0.45, "y": 0.4, "Y": 30, "step_nm": "10"})
    assert ok.status_code == 200 and len(ok.json()["wavelengths_nm"]) == 41
    limit = client.post("/api/lab/reflectance/macadam", json={"x": 0.45, "y": 0.4, "Y": 30})
    assert limit.status_code == 200 and len(limit.json()["xy"]) == 180
    for body in ({"x": 0.45, "y": 0.4, "Y": 130}, {"x": 0.45, "y": 0.4}, {"x": 0.45, "y": 0.4, "Y": 30, "step_nm": "7"},
                 {"x": 0.45, "y": 0.4, "Y": 30, "illuminant": "nope"}):
        bad = client.post("/api/lab/reflectance", json=body)
        assert bad.status_code == 422 and isinstance(bad.json()["error"], str), body
    assert client.get("/labs/reflectance").status_code == 200


@pytest.mark.parametrize("xyY", [(0.0, 0.5, 1e-5), (0.0, 0.5, 3.9e-256), (0.7, 0.29, 50.0), (0.33, 0.33, 100.0)])
def test_edge_colours_give_strict_json(xyY):
    """NaN and infinity are not JSON: an edge colour's answer never contains them."""
    import json

    json.dumps(lab.reflectance_lab(*xyY, step_nm="10"), allow_nan=False)
