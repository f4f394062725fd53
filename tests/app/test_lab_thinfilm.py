"""The thin-film lab's numbers are the library's, and they show what the optics says they should."""

from __future__ import annotations

import numpy as np
import pytest

from spectrocolor import Spectrum
from spectrocolor.app import thinfilm_lab as lab
from spectrocolor.thinfilm.colour import film_colours
from spectrocolor.thinfilm.media import bk7, water
from spectrocolor.thinfilm.optics import optical_path_difference, thin_film, two_beam_reflectance

WL = lab.WAVELENGTHS_NM


def test_the_table_is_the_librarys_film_colours():
    table = lab.thinfilm_lab("soap", "airy", 30.0, "D65", max_thickness_nm=600)
    d = np.arange(0.0, 601.0)
    optics = thin_film(d, WL, water(), angle_deg=30.0)
    colours = film_colours(Spectrum(WL, optics.reflectance), illuminant="D65", exposure="global-max",
                           gamut="preserve-luminance")
    # exact: codes of floats that agree to ~1e-13: a code moves only at a half-code tie, which these inputs do not
    # reach
    np.testing.assert_array_equal(table["rgb8"], colours.rgb8)
    np.testing.assert_allclose(table["reflectance"], optics.reflectance, rtol=0, atol=5e-7)  # 6 decimals
    np.testing.assert_allclose(table["XYZ"], colours.XYZ100, rtol=0, atol=5e-7)


def test_two_beam_is_seed_000s_model_for_the_soap_film():
    d, factor = lab.reflectance_table("soap", "two-beam", 0.0, max_thickness_nm=300)
    n = float(np.real(water().refractive_index([560.0])[0]))
    np.testing.assert_allclose(factor, two_beam_reflectance(optical_path_difference(d, n), WL, 0.95), rtol=1e-15)


def test_no_film_is_black_and_airy_equals_matrix_for_a_single_free_film():
    table = lab.thinfilm_lab("soap", "airy", 0.0, max_thickness_nm=50)
    # exact: black and its sentinel chromaticity are set, not computed
    assert table["rgb8"][0] == [0, 0, 0] and table["xy"][0] == [-1.0, -1.0]
    _, airy = lab.reflectance_table("soap", "airy", 20.0, max_thickness_nm=800)
    _, matrix = lab.reflectance_table("soap", "matrix", 20.0, max_thickness_nm=800)
    np.testing.assert_allclose(matrix, airy, rtol=0, atol=1e-12)


def test_a_quarter_wave_mgf2_layer_is_an_anti_reflection_coating():
    """The lesson of a coating: at d = λ/4n (550 nm, n = 1.38) the glass reflects least."""
    d, R = lab.reflectance_table("mgf2", "airy", 0.0, max_thickness_nm=300)
    # exact: whole-nanometre wavelengths: small integers, exact in any arithmetic
    k550 = int(np.flatnonzero(WL == 550.0)[0])
    n_glass = float(np.real(bk7().refractive_index([550.0])[0]))
    bare = ((n_glass - 1) / (n_glass + 1)) ** 2
    quarter = round(550.0 / (4 * 1.38))
    assert R[0, k550] == pytest.approx(bare, rel=1e-9)  # no coating: bare glass
    assert int(np.argmin(R[:200, k550])) == quarter  # the first minimum (the next is 3λ/4n)
    ideal = ((1.0 * n_glass - 1.38**2) / (1.0 * n_glass + 1.38**2)) ** 2  # quarter-wave formula
    assert R[quarter, k550] == pytest.approx(ideal, rel=2e-3)  # within 1 nm of the exact quarter wave
    # the matrix model adds the 1 mm plate's back surface: more light, never less
    _, plate = lab.reflectance_table("mgf2", "matrix", 0.0, max_thickness_nm=300)
    assert np.all(plate >= R - 1e-12) and plate[quarter, k550] > R[quarter, k550] + 0.02


def test_options_come_from_the_registries():
    options = lab.lab_options()
    assert [m["name"] for m in options["models"]] == ["two-beam", "airy", "matrix"]
    assert options["illuminants"][0]["name"] == "blackbody:6504"
    assert {"D65", "A", "FL11"} <= {i["name"] for i in options["illuminants"]}
    assert "sRGB" in [d["name"] for d in options["displays"]]


@pytest.mark.parametrize(("arguments", "message"), [
    ({"film": "gold"}, "film: 'gold' is not a film of the thin-film lab"),
    ({"model": "ray"}, "model: 'ray' is not a thin-film model"),
    ({"angle_deg": 89.5}, "angle_deg"),
    ({"illuminant": "X99"}, "illuminant: 'X99' is not a CIE illuminant name"),
    ({"display": "CMYK"}, "space: 'CMYK' is not a built-in RGB space"),
])
def test_bad_choices_get_one_clear_error(arguments, message):
    with pytest.raises(ValueError, match=message):
        lab.thinfilm_lab(**{"max_thickness_nm": 10, **arguments})


def test_the_route_answers_the_table_and_errors_in_the_servers_shape():
    from fastapi.testclient import TestClient

    from spectrocolor.app.server import create_app

    client = TestClient(create_app(), base_url="http://127.0.0.1")  # the Host a browser sends
    r = client.post("/api/lab/thinfilm", json={"film": "oil", "model": "two-beam", "angle_deg": 10})
    assert r.status_code == 200
    assert len(r.json()["rgb8"]) == 1501
    bad = client.post("/api/lab/thinfilm", json={"film": "gold"})
    assert bad.status_code == 422 and "film: 'gold'" in bad.json()["error"]
    extra = client.post("/api/lab/thinfilm", json={"film": "soap", "colour": "red"})
    assert extra.status_code == 422 and "error" in extra.json()
    page = client.get("/labs/thinfilm")
    assert page.status_code == 200 and "Thin-film lab" in page.text


def test_the_explorer_and_every_lab_link_to_each_other():
    from fastapi.testclient import TestClient

    from spectrocolor.app.server import create_app

    client = TestClient(create_app(), base_url="http://127.0.0.1")
    labs = ["/labs/thinfilm", "/labs/reflectance", "/labs/solid", "/labs/light"]
    for page in ["/", *labs]:
        html = client.get(page).text
        assert all(f'href="{lab}"' in html for lab in labs), page
        # each lab's tab bar links to the explorer's settings 1-5 (issue 28 item 6)
        assert page == "/" or all(f'href="/?s={n}"' in html for n in range(1, 6)), page
