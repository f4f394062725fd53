"""The page's local fast path (static/js/colour.js) against the library, in Chromium.

The page repaints an edit from /api/model's weights and matrix without waiting for the server;
these tests run that JavaScript in the browser for every display, gamut strategy, normalisation
and white adaptation the page offers (and every observer and bin width), under E and under
setting 4's illuminants, and compare each number with ``compute.evaluate`` (the library). Then
they check, end to end, that what the page painted from the fast path while editing equals the
server's answer that replaced it."""

from __future__ import annotations

import itertools

import numpy as np
import pytest

from appbrowser import choose, drag, key, open_page, settle, state
from spectrocolor.app import compute, presets

pytestmark = pytest.mark.browser

# 1e-9: both sides do the same float64 arithmetic in a different order (sums of 31-301 terms)
TOL = 1e-9

LOCAL = """async ([body, gamuts, spectra, illuminant]) => {
  const c = await import("/static/js/colour.js");
  const model = await (await fetch("/api/model", {method: "POST",
    headers: {"Content-Type": "application/json"}, body: JSON.stringify(body)})).json();
  if (model.error) throw new Error(`/api/model: ${model.error}`);
  const lw = c.localWeights(model, body.normalise, illuminant);
  const white = c.whiteOf(lw.W);
  return gamuts.map((gamut) => spectra.map((s) => {
    const col = c.localColour(s, model, {W: lw.W, scale: lw.scale, normalise: body.normalise, gamut});
    return {...col, lab: c.lab(col.XYZ, white), emitted_levels: c.emitted(col, model)};
  }));
}"""


def sample_spectra(step_nm):
    """Distributions that land inside, on and outside each display's gamut, on the grid."""
    wl = compute.grid(step_nm)
    coarse = [presets.STRAW, presets.BLUE, presets.YELLOW, presets.MAGENTA, presets.GREEN,
              [30 if 450 <= w <= 470 else 0 for w in compute.grid(10)],  # a strong blue
              [30 if w >= 680 else 0 for w in compute.grid(10)]]  # a deep red
    out = [np.interp(wl, compute.grid(10), np.array(c, float)).round(1).tolist() for c in coarse]
    return out + [[0.0] * len(wl), [30.0] * len(wl)]


def compare(page, step, observer, display, normalise, gamuts, adaptation, illuminant=None):
    """The page's fast path and the library agree for these choices and each gamut strategy."""
    spectra = sample_spectra(step)
    body = {"step_nm": step, "observer": observer, "display": display, "normalise": normalise,
            "adaptation": adaptation}
    local = page.evaluate(LOCAL, [body, list(gamuts), spectra, illuminant])
    for gamut, mine in zip(gamuts, local, strict=True):
        lib = compute.evaluate(float(step), observer, display, normalise, gamut, spectra,
                               illuminant, (), adaptation=adaptation)["colours"]
        where = f"{body}, gamut {gamut}, illuminant {'given' if illuminant else 'E'}"
        for i, (a, b) in enumerate(zip(mine, lib, strict=True)):
            for name in ("XYZ", "rgb_unmapped", "rgb_linear", "rgb_encoded", "emitted_levels"):
                np.testing.assert_allclose(a[name], b[name], rtol=TOL, atol=TOL,
                                           err_msg=f"{name}, spectrum {i}, {where}")
            if b["XYZ"][1] > 0:
                np.testing.assert_allclose(a["xy"], b["xy"], rtol=TOL, atol=TOL, err_msg=where)
                np.testing.assert_allclose(a["lab"], b["lab"], rtol=TOL, atol=1e-7, err_msg=where)
            assert a["codes"] == b["codes"], (i, where)
            assert a["in_gamut"] == b["in_gamut"] and a["negative"] == b["negative"], (i, where)
            assert a["over"] == b["over"], (i, where)


@pytest.fixture(scope="module")
def page(browser, base_url):
    with open_page(browser, base_url) as pg:
        yield pg


@pytest.fixture(scope="module")
def options():
    return compute.DISPLAYS, compute.GAMUTS, compute.NORMALISATIONS, tuple(compute.ADAPTATIONS)


def test_every_display_gamut_normalisation_and_adaptation(page, options):
    """All combinations at SPECTRA's grid (31 bins) and the 1931 observer, under E."""
    displays, gamuts, normalisations, adaptations = options
    offered = page.evaluate("""() => ({d: [...document.querySelectorAll('#display option')].map(o => o.value),
        g: [...document.querySelectorAll('#gamut option')].map(o => o.value),
        n: [...document.querySelectorAll('#normalise option')].map(o => o.value),
        a: [...document.querySelectorAll('#adaptation option')].map(o => o.value)})""")
    assert (offered["d"], offered["g"], offered["n"], offered["a"]) == (
        list(displays), list(gamuts), list(normalisations), list(adaptations))
    for display, normalise, adaptation in itertools.product(displays, normalisations, adaptations):
        compare(page, 10, "1931", display, normalise, gamuts, adaptation)


@pytest.mark.parametrize("step", [10, 5, 2, 1])
def test_every_observer_and_bin_width(page, options, step):
    displays, gamuts, _, _ = options
    for observer in compute.OBSERVERS:
        compare(page, step, observer, "sRGB", "fixed", gamuts, "bradford")
    for display in displays:  # the SPECTRA monitor's 64 levels too
        compare(page, step, "1964", display, "per-colour", gamuts, "none")


@pytest.mark.parametrize("illuminant", ["D65", "A", "three-band", "sodium"])
def test_setting4_illuminants(page, options, illuminant):
    """Under setting 4's illuminants the page derives the weights itself (and exact A's scale)."""
    displays, gamuts, normalisations, adaptations = options
    wl = compute.grid(10)
    levels = {"D65": compute.resolve("D65", wl), "A": compute.resolve("A", wl),
              "three-band": presets.THREE_BAND,
              "sodium": [30.0 if w == 590 else 0.0 for w in wl]}[illuminant]
    for display, normalise in itertools.product(displays, normalisations):
        compare(page, 10, "1931", display, normalise, gamuts, "bradford", levels)
    for adaptation in adaptations:
        compare(page, 10, "2015-10", "SPECTRA 7000K", "fixed", gamuts, adaptation, levels)


def test_what_the_page_painted_while_editing_equals_the_server(browser, base_url):
    """End to end: after edits in every setting, S.local (painted in the frame of the edit)
    equals the server's answer for the same state."""
    with open_page(browser, base_url) as pg:
        for setting, keys in ((1, "7"), (2, "4"), (3, "3"), (4, "4"), (5, "3")):
            choose(pg, setting)
            for k in keys:
                key(pg, k)
            drag(pg, 0, 0.3, 0.5, 0.6, 0.2)
            for name, value in (("normalise", "spectra-exact"), ("gamut", "preserve-luminance"),
                                ("display", "SPECTRA 7000K")):
                pg.select_option(f"#{name}", value)
                settle(pg)
                st = state(pg)
                assert st[name] == value
                for a, b in zip(st["local"], st["server"]["colours"], strict=True):
                    for field in ("XYZ", "rgb_unmapped", "rgb_linear", "rgb_encoded"):
                        np.testing.assert_allclose(a[field], b[field], rtol=TOL, atol=TOL,
                                                   err_msg=f"setting {setting}, {name} {value}: {field}")
                    assert a["codes"] == b["codes"]
            for name, value in (("normalise", "fixed"), ("gamut", "desaturate"), ("display", "sRGB")):
                pg.select_option(f"#{name}", value)
                settle(pg)
