"""Setting 4 shows how well its illuminant renders colours: the library's lighting metrics."""

from __future__ import annotations

import numpy as np
import pytest

from spectrocolor import Spectrum
from spectrocolor.app import compute
from spectrocolor.lighting import summary


def illuminant_levels(name: str) -> list[float]:
    return next(i["levels"] for i in compute.presets(10.0)["setting4"]["illuminants"] if i["name"].startswith(name))


def test_the_metrics_are_the_librarys_on_the_zero_extended_light():
    levels = illuminant_levels("T65")
    got = compute.light_metrics(compute.grid(10.0), levels)
    fine = np.arange(380.0, 781.0, 5.0)
    values = np.where((fine >= 400) & (fine <= 700), np.interp(fine, compute.grid(10.0), levels), 0.0)
    expected = summary(Spectrum(fine, values))
    for key in ("cct_K", "duv", "Ra", "R9", "Rf", "Rg", "LER_lm_per_W", "melanopic_DER"):
        assert got[key] == pytest.approx(expected[key], rel=1e-12), key
    assert "zero" in got["note"]


def test_a_three_band_lamp_renders_worse_than_daylight_and_evaluate_carries_the_metrics():
    d65 = compute.light_metrics(compute.grid(10.0), illuminant_levels("D65"))
    three_band = compute.light_metrics(compute.grid(10.0), illuminant_levels("T65"))
    assert d65["Ra"] > 95 and three_band["Ra"] < d65["Ra"] - 20 and three_band["Rf"] < d65["Rf"]
    result = compute.evaluate(10.0, "1931", "sRGB", "fixed", "desaturate", [[15] * 31],
                              illuminant_levels=illuminant_levels("A"))
    assert result["light_metrics"]["cct_K"] == pytest.approx(2840, abs=15)  # CIE A, 2856 K on the tabulated grid
    assert compute.evaluate(10.0, "1931", "sRGB", "fixed", "desaturate", [[15] * 31])["light_metrics"] is None


def test_a_dark_or_single_line_light_gives_no_exception():
    assert "no energy" in compute.light_metrics(compute.grid(10.0), [0] * 31)["note"]
    line = [0] * 31
    line[19] = 30  # the sodium-like line at 590 nm: no CCT, metrics undefined, but an answer
    metrics = compute.light_metrics(compute.grid(10.0), line)
    assert metrics["Ra"] is None or np.isfinite(metrics["Ra"])


@pytest.mark.browser
def test_setting4_shows_the_metrics_and_links_to_the_light_lab(browser, base_url):
    from appbrowser import open_page

    with open_page(browser, base_url) as page:
        page.click("#tab-4")
        page.wait_for_function("!document.querySelector('#light-metrics').hidden")
        text = page.text_content("#light-metrics")
        expected = compute.light_metrics(compute.grid(10.0), illuminant_levels("D65"))
        assert f"Ra {expected['Ra']:.1f}" in text and f"Rf {expected['Rf']:.1f}" in text
        assert page.get_attribute("#light-metrics a", "href") == "/labs/light"
        page.click("#tab-1")
        page.wait_for_function("document.querySelector('#light-metrics').hidden")
