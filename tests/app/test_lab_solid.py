"""The object-colour solid lab's numbers are the library's and mean what its captions say."""

from __future__ import annotations

import numpy as np
import pytest

import spectrocolor as sc
from spectrocolor.app import solid_lab as lab
from spectrocolor.lighting.spectra import tcs_reflectances
from spectrocolor.recovery.optimal import macadam_limits, object_colour_membership


def test_the_solids_levels_are_macadam_limits_in_cielab():
    solid = lab.solid("A")
    grid = sc.wavelength_grid(*lab.GRID)
    white = sc.white_point("A", wavelengths_nm=grid)
    level = solid["levels"][5]
    limit = macadam_limits(level["Y"], illuminant="A", observer="1931", wavelengths=lab.GRID, samples=lab.HUES)
    expected = sc.lab(limit, white)
    np.testing.assert_allclose(level["lab"], expected, atol=5e-4)  # 3 decimals
    XYZ = sc.XYZ_from_lab(np.array(level["lab"]), white)
    depth = object_colour_membership(XYZ, illuminant="A", observer="1931", wavelengths=lab.GRID).relative_depth
    assert np.all(np.abs(depth) < 1e-4)  # on the boundary (Lab rounded to 3 decimals)


def test_the_display_cube_is_anchored_at_black_and_the_lights_white():
    solid = lab.solid("D65", "sRGB")
    ends = np.array([edge[0] for edge in solid["cube_edges_lab"]] + [edge[-1] for edge in solid["cube_edges_lab"]])
    assert np.min(np.linalg.norm(ends - [0.0, 0.0, 0.0], axis=1)) < 1e-9       # black corner
    assert np.min(np.linalg.norm(ends - [100.0, 0.0, 0.0], axis=1)) < 1e-3     # white corner is the light's white


def test_the_section_is_the_librarys_macadam_limit():
    cut = lab.section(30.0, "D65")
    expected = sc.xy(macadam_limits(30.0, illuminant="D65", observer="1931", wavelengths=lab.GRID, samples=180))
    np.testing.assert_allclose(cut["macadam_xy"], expected, atol=5e-6)


def test_the_mismatch_region_contains_the_sample_itself():
    region = lab.mismatch(9, "D65", "FL11")
    grid = sc.wavelength_grid(*lab.GRID)
    XYZ_second = tcs_reflectances(grid)[8] @ sc.weights(grid, illuminant="FL11")
    np.testing.assert_allclose(region["sample_xy"], sc.xy(XYZ_second), atol=5e-6)
    points = np.array(region["region_xy"])
    assert points.min(axis=0)[0] <= region["sample_xy"][0] <= points.max(axis=0)[0]
    assert points.min(axis=0)[1] <= region["sample_xy"][1] <= points.max(axis=0)[1]
    same = lab.mismatch(9, "FL11", "FL11")  # no change of light: no mismatch
    assert np.ptp(np.array(same["region_lab"]), axis=0).max() < 0.05


@pytest.mark.parametrize(("call", "message"), [
    (lambda: lab.section(0.0), "Y: a section needs 0 < Y < 100"),
    (lambda: lab.mismatch(15), "sample: expected a CIE test-colour sample number 1-14"),
    (lambda: lab.solid("nope"), "illuminant: 'nope' is not a CIE illuminant name"),
    (lambda: lab.mismatch(1, "D65", None), "second_illuminant: the lab takes a named light"),
])
def test_bad_choices_get_one_clear_error(call, message):
    with pytest.raises(ValueError, match=message):
        call()


def test_the_routes_answer_in_the_servers_shape():
    from fastapi.testclient import TestClient

    from spectrocolor.app.server import create_app

    client = TestClient(create_app(), base_url="http://127.0.0.1")
    assert len(client.post("/api/lab/solid", json={}).json()["levels"]) == len(lab.LEVELS_Y)
    assert client.post("/api/lab/solid/section", json={"Y": 20}).status_code == 200
    for body in ({"Y": 100}, {"sample": 0}, {"display": "CMYK"}, {"colour": 1}):
        bad = client.post("/api/lab/solid/section", json=body)
        assert bad.status_code == 422 and isinstance(bad.json()["error"], str), body
    assert client.get("/labs/solid").status_code == 200
