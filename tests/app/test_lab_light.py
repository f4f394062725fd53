"""The light-source lab's numbers are the library's, and its samples show what the metrics say."""

from __future__ import annotations

import numpy as np
import pytest

from spectrocolor import Spectrum, adapt, illuminant, render, rgb_space, weights
from spectrocolor.app import light_lab as lab
from spectrocolor.lighting import colour_fidelity, colour_rendering_index, summary
from spectrocolor.lighting.reference import cri_reference
from spectrocolor.lighting.spectra import tcs_reflectances

WL = lab.WAVELENGTHS_NM


def library_samples(spd: np.ndarray) -> list:
    W = weights(WL, illuminant=Spectrum(WL, spd))
    XYZ = tcs_reflectances(WL) @ W
    return render(adapt(XYZ, W.sum(axis=0), rgb_space("sRGB").white_XYZ), "sRGB", gamut="desaturate").codes.tolist()


def test_a_named_light_gets_the_librarys_metrics_and_samples():
    out = lab.light_lab({"kind": "named", "name": "FL11"})
    spd = illuminant("FL11", WL)
    expected = summary(spd)
    for key in ("cct_K", "duv", "Ra", "R9", "Rf", "Rg", "LER_lm_per_W", "melanopic_DER"):
        assert out["summary"][key] == pytest.approx(expected[key], abs=6e-5), key  # rounded to 4 decimals
    np.testing.assert_allclose(out["Ri"], colour_rendering_index(spd).Ri, atol=6e-5)
    np.testing.assert_allclose(out["hue_bins"]["Rf_h"], colour_fidelity(spd).Rf_h, atol=6e-5)
    values = spd.values / spd.values.max()
    assert out["samples"]["under_light"] == library_samples(values)
    reference = cri_reference(expected["cct_K"], WL)
    assert out["samples"]["under_reference"] == library_samples(np.asarray(reference))


def test_the_samples_differ_where_the_indices_say_so():
    """A daylight renders exactly like its own reference; a narrow-band mixture shifts the red."""
    d65 = lab.light_lab({"kind": "named", "name": "D65"})
    assert d65["summary"]["Ra"] == pytest.approx(100.0, abs=0.05)
    assert d65["samples"]["under_light"] == d65["samples"]["under_reference"]
    leds = lab.light_lab({"kind": "leds", "peaks_nm": [450, 530, 590], "widths_nm": [20, 30, 20],
                          "powers": [1.0, 0.8, 0.9]})
    assert leds["Ri"][8] < 0  # R9: the strong red is rendered badly without red light
    red_light, red_reference = leds["samples"]["under_light"][8], leds["samples"]["under_reference"][8]
    assert red_light != red_reference


def test_the_led_mixture_is_a_sum_of_the_librarys_gaussians():
    spd = lab.led_mixture([450, 620], [20, 30], [1.0, 0.5])
    expected = Spectrum.gaussian(450, 20, WL).values + Spectrum.gaussian(620, 30, WL, peak=0.5).values
    np.testing.assert_allclose(spd, expected / expected.max(), rtol=1e-14)


@pytest.mark.parametrize(("source", "message"), [
    ({"kind": "named", "name": "D99"}, "name: 'D99' is not a CIE illuminant name"),
    ({"kind": "named", "name": None}, "name: the lab takes a named light"),
    ({"kind": "leds", "peaks_nm": [300], "widths_nm": [20], "powers": [1]}, "peaks must be 380-780 nm"),
    ({"kind": "leds", "peaks_nm": [450, 550], "widths_nm": [20], "powers": [1, 1]}, "give 1-4 primaries"),
    ({"kind": "leds", "peaks_nm": [450], "widths_nm": [20], "powers": [0]}, "not all zero"),
    ({"kind": "laser"}, "source: expected"),
])
def test_bad_lights_get_one_clear_error(source, message):
    with pytest.raises(ValueError, match=message):
        lab.light_lab(source)


def test_the_route_validates_and_answers_in_the_servers_shape():
    from fastapi.testclient import TestClient

    from spectrocolor.app.server import create_app

    client = TestClient(create_app(), base_url="http://127.0.0.1")
    ok = client.post("/api/lab/light", json={"source": {"kind": "named", "name": "A"}})
    assert ok.status_code == 200 and ok.json()["summary"]["Ra"] == pytest.approx(100.0, abs=0.05)
    for body in ({"source": {"kind": "leds", "peaks_nm": [450] * 5, "widths_nm": [20] * 5, "powers": [1] * 5}},
                 {"source": {"kind": "named", "name": "FL2", "extra": 1}}, {"source": "FL2"},
                 {"source": {"kind": "leds", "peaks_nm": [450], "widths_nm": [20], "powers": [2]}}):
        bad = client.post("/api/lab/light", json=body)
        assert bad.status_code == 422 and isinstance(bad.json()["error"], str), body
    assert client.get("/labs/light").status_code == 200
