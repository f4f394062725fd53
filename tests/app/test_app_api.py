"""The explorer's JSON API: every endpoint, the seed's presets and the validation of requests.

Independent cross-checks use colour-science (test-only) and plain NumPy on the CIE tables."""

from __future__ import annotations

import json

import colour
import numpy as np
import pytest
from fastapi.testclient import TestClient

import spectrocolor as sc
from spectrocolor.app import presets as P
from spectrocolor.app.server import create_app

WL = np.arange(400.0, 701.0, 10.0)


@pytest.fixture(scope="module")
def client():
    return TestClient(create_app(), base_url="http://127.0.0.1")  # the Host a browser sends


def evaluate(client, spectra, **kw):
    body = {"spectra": [list(map(float, s)) for s in spectra], **kw}
    r = client.post("/api/evaluate", json=body)
    assert r.status_code == 200, r.text
    return r.json()


def cie_xyz(levels, illuminant=None):
    """Independent XYZ: CIE 1931 CMFs at the bins, summed; white Y = 100 (E or illuminant)."""
    cmfs = colour.MSDS_CMFS["CIE 1931 2 Degree Standard Observer"]
    xbar = np.array([cmfs[w] for w in WL])
    s = np.ones(31) if illuminant is None else np.asarray(illuminant, float)
    k = 100 / (s @ xbar[:, 1])
    return k * (np.asarray(levels, float) / 30 * s) @ xbar


def test_page_and_assets_are_served_without_external_urls(client):
    page = client.get("/")
    assert page.status_code == 200 and "SPECTRA explorer" in page.text
    import re

    assets = re.findall(r'(?:src|href)="(/static/[^"]+)"', page.text)
    assert any(a.endswith(".js") for a in assets) and any(a.endswith(".css") for a in assets)
    for asset in assets:
        r = client.get(asset)
        assert r.status_code == 200
        assert "http://" not in r.text and "https://" not in r.text
    assert "https://" not in page.text and "http://" not in page.text


def test_options_lists_the_choices(client):
    o = client.get("/api/options").json()
    assert o["displays"][:3] == ["sRGB", "SPECTRA 7000K", "Display P3"]
    assert "flag" in o["gamuts"] and o["full_level"] == 30


def test_evaluate_matches_an_independent_summation_and_srgb(client):
    r = evaluate(client, [P.STRAW], normalise="per-colour", adaptation="none")
    c = r["colours"][0]
    np.testing.assert_allclose(c["XYZ"], cie_xyz(P.STRAW), rtol=1e-10)
    rgb = colour.RGB_COLOURSPACES["sRGB"].matrix_XYZ_to_RGB @ np.array(c["XYZ"])
    np.testing.assert_allclose(c["rgb_unmapped"], rgb / rgb.max(), atol=2e-4)  # IEC vs derived
    assert c["status"] == "Optimised!" and max(c["rgb_linear"]) == pytest.approx(1.0)
    lam, _, _ = colour.dominant_wavelength(np.array(c["xy"]), np.array(r["white_xy"]),
                                           colour.MSDS_CMFS["CIE 1931 2 Degree Standard Observer"])
    assert c["dominant_nm"] == pytest.approx(float(lam), abs=0.5) and not c["complementary"]


def test_full_spectrum_is_the_white_and_has_no_dominant_wavelength(client):
    r = evaluate(client, [[30] * 31])
    c = r["colours"][0]
    assert c["XYZ"][1] == pytest.approx(100.0)
    assert c["dominant_nm"] is None and c["lab"][0] == pytest.approx(100.0)


def test_flag_names_the_negative_channel(client):
    # a single line at 520 nm lies far outside the sRGB gamut: red and blue go negative
    line = [0.0] * 31
    line[12] = 30.0
    c = evaluate(client, [line], gamut="flag")["colours"][0]
    assert not c["in_gamut"] and c["negative"] == ["R", "B"]
    assert c["status"].startswith("cannot be reproduced") and "R, B negative" in c["status"]
    assert c["codes"] == [0, 0, 0]


def test_fixed_scale_is_spectra_r_max_for_its_monitor(client):
    # Seed 002 note 10: R_max = 1.58 for SPECTRA's matrix, 31 bins, equal energy (unadapted)
    m = client.post("/api/model", json={"display": "SPECTRA 7000K", "adaptation": "none"}).json()
    assert m["fixed_scale"] == pytest.approx(1.58, abs=0.005)
    assert m["bit_depth"] == 6 and m["transfer"]["kind"] == "levels"
    assert len(m["weights"]) == 31 and len(m["tints"]) == 31


def test_bar_tints_are_the_library_palette_on_the_canvas_scale(client):
    from spectrocolor.pictures import wavelength_tint

    m = client.post("/api/model", json={}).json()
    expected = wavelength_tint(np.asarray(m["wavelengths_nm"])) / 255.0
    np.testing.assert_allclose(m["tints"], expected, rtol=0, atol=1e-12)
    # 580 nm is yellow (seed 002: the unique yellow), 470 nm blue
    yellow = np.asarray(m["tints"])[np.asarray(m["wavelengths_nm"]) == 580][0]
    assert yellow[0] > 0.5 and yellow[1] > 0.5 and yellow[2] < 0.2


def test_sunset_is_the_seed_formula(client):
    p = client.get("/api/presets", params={"step_nm": 10}).json()
    sunset = p["setting1"][7]
    # exact: the preset table's own decimal constants, through JSON (shortest repr round-trips)
    assert [c["d"] for c in sunset["cycle"]] == [0.0, 0.15, 0.3, 0.6, 1.0, 1.5, 3.0]
    for c in sunset["cycle"]:  # SPECTRA's levels are integers: the formula, rounded
        # exact: whole levels; every value of the formula here lies ≥ 2e-4 from a half-integer, far
        # beyond the few ulps by which two evaluations of exp can differ
        np.testing.assert_array_equal(c["levels"], np.round(30 * np.exp(-((700 / WL) ** 4 - 1)
                                                                         * c["d"])))
    names = [q["name"] for q in p["setting1"]]
    assert names == ["straw", "light blue", "grey", "green", "magenta", "yellow", "blue", "sunset"]
    ys = [evaluate(client, [c["levels"]])["colours"][0]["xy"] for c in sunset["cycle"][1:]]
    assert all(b[0] > a[0] for a, b in zip(ys, ys[1:], strict=False))  # redder as d grows


def test_setting1_presets_have_the_described_hues(client):
    p = client.get("/api/presets").json()["setting1"]
    cs = evaluate(client, [q["levels"] for q in p[:4]])["colours"]
    cs += evaluate(client, [q["levels"] for q in p[4:7]])["colours"]
    straw, light_blue, grey, green, magenta, yellow, blue = cs
    assert 570 < straw["dominant_nm"] < 590 and 570 < yellow["dominant_nm"] < 590
    assert yellow["purity"] > straw["purity"]
    assert 470 < light_blue["dominant_nm"] < 495 and 440 < blue["dominant_nm"] < 480
    assert blue["purity"] > light_blue["purity"]
    assert grey["dominant_nm"] is None
    assert 520 < green["dominant_nm"] < 560 and magenta["complementary"]


def test_setting2_metameric_pairs(client):
    p = client.get("/api/presets").json()["setting2"]
    left = {q["key"]: q for q in p["left"]}
    right = {q["key"]: q for q in p["right"]}
    # 3 left (neutral) and 6 right (grey), and 6 left/6 right, match as lights
    for a, b in ((left["3"], right["6"]), (left["6"], right["6"]), (left["5"], right["5"])):
        de = evaluate(client, [a["levels"], b["levels"]], pairs=[[0, 1]])["delta_e_2000"][0]
        assert de < 0.5, (a["name"], b["name"], de)
    # 7: D65 (the CIE table) and the three-band light have the same chromaticity
    d65 = np.asarray(left["7"]["levels"])
    table = sc.illuminant("D65", WL).values
    # exact: whole levels; 30 S/max lies ≥ 5e-3 from a half-integer at every sample, far beyond rounding
    np.testing.assert_array_equal(d65, np.round(table * 30 / table.max()))
    r = evaluate(client, [d65, right["7"]["levels"]], normalise="per-colour", pairs=[[0, 1]])
    assert r["delta_e_2000"][0] > 5  # different lightness without X ...
    assert r["delta_e_2000_shown"][0] < 0.5  # ... but as shown under B (each patch scaled) they match
    xy0, xy1 = (np.array(c["xy"]) for c in r["colours"])
    assert np.abs(xy0 - xy1).max() < 1e-3  # ... metameric chromaticity (after X)
    assert [c["codes"] for c in r["colours"]][0] == r["colours"][1]["codes"]


def test_delta_e_as_shown_is_the_displayed_lights(client):
    # Independently: the shown light is the normalised linear RGB taken back to XYZ, and
    # CIELAB is relative to the display's white at full drive.
    p = client.get("/api/presets").json()["setting1"]
    a, b = p[0]["levels"], p[2]["levels"]
    r = evaluate(client, [a, b], normalise="per-colour", pairs=[[0, 1]])
    space = sc.rgb_space("sRGB")
    shown = [np.asarray(c["rgb_unmapped"]) @ np.asarray(space.matrix_to_XYZ).T for c in r["colours"]]
    lab = [sc.lab(x, space.white_XYZ) for x in shown]
    assert r["delta_e_2000_shown"][0] == pytest.approx(float(sc.delta_e_2000(lab[0], lab[1])), abs=1e-9)


def test_setting3_pairs_conserve_the_total(client):
    p = client.get("/api/presets").json()["setting3"]
    assert len(p) == 6
    for q in p[2:]:
        np.testing.assert_allclose(np.add(q["left"], q["right"]), 30)
    assert max(np.add(p[0]["left"], p[0]["right"])) <= 30


def test_setting4_metamers_match_under_d65_and_not_under_a(client):
    p = client.get("/api/presets").json()["setting4"]
    ills = {q["name"]: q["levels"] for q in p["illuminants"]}
    assert set(ills) == {"E", "D65", "T65 three-band", "A"}
    for q in p["samples"]:
        de = {}
        for name, s in ills.items():
            r = evaluate(client, [[30] * 31, q["left"], q["right"]], illuminant=s, pairs=[[1, 2]])
            de[name] = r["delta_e_2000"][0]
            np.testing.assert_allclose(r["colours"][1]["XYZ"], cie_xyz(q["left"], s), rtol=1e-9)
        assert de["D65"] < 0.3, (q["name"], de)
        assert de["A"] > 1.5 and de["T65 three-band"] > 1.5, (q["name"], de)


def test_setting5_moss_green_filters_make_a_red(client):
    p = client.get("/api/presets").json()["setting5"]
    assert len(p) == 8
    moss = np.array(p[6]["left"])
    r = evaluate(client, [moss, moss * moss / 30])["colours"]
    assert 495 < r[0]["dominant_nm"] < 560
    assert r[1]["dominant_nm"] > 590 and not r[1]["complementary"]
    assert r[1]["XYZ"][1] < r[0]["XYZ"][1]


def test_fine_grid_presets_are_resampled(client):
    p = client.get("/api/presets", params={"step_nm": 5}).json()
    assert len(p["wavelengths_nm"]) == 61 and len(p["setting1"][0]["levels"]) == 61
    np.testing.assert_allclose(p["setting1"][0]["levels"][::2], P.STRAW)


def test_metamer_has_the_same_colour(client):
    target = P.GREEN
    r = client.post("/api/metamer", json={"target": target})
    assert r.status_code == 200, r.text
    out = r.json()
    np.testing.assert_allclose(out["XYZ_metamer"], out["XYZ_target"], atol=1e-6)
    assert 0 <= min(out["levels"]) and max(out["levels"]) <= 30 + 1e-9
    assert not np.allclose(out["levels"], target, atol=0.5)


def test_import_resamples_explicitly_and_export_round_trips(client):
    wl = np.arange(380, 781, 5)
    csv = "wavelength_nm,a,b\n" + "\n".join(f"{w},{0.5},{w / 1000}" for w in wl)
    r = client.post("/api/import", json={"filename": "m.csv", "content": csv, "scale": "unit"})
    assert r.status_code == 200, r.text
    got = r.json()
    assert got["names"] == ["a", "b"] and "resampled to 31 bins" in got["note"]
    np.testing.assert_allclose(got["levels"][0], 15)
    np.testing.assert_allclose(got["levels"][1], WL / 1000 * 30)
    short = "wavelength_nm,a\n" + "\n".join(f"{w},1" for w in range(450, 701, 10))
    bad = client.post("/api/import", json={"filename": "s.csv", "content": short})
    assert bad.status_code == 422 and "never extrapolates" in bad.json()["error"]
    ex = client.post("/api/export", json={"format": "json", "names": ["a"], "spectra": [P.STRAW]})
    assert ex.status_code == 200 and "attachment" in ex.headers["content-disposition"]
    back = sc.Spectrum.from_dict(json.loads(ex.text))
    np.testing.assert_allclose(back.values, P.STRAW)


@pytest.mark.parametrize(
    ("path", "body", "needle"),
    [
        ("/api/evaluate", {"spectra": [[1] * 30]}, "31"),
        ("/api/evaluate", {"spectra": [[1] * 31], "step_nm": 5}, "needs 61"),
        ("/api/evaluate", {"spectra": [[31] * 31]}, "less than or equal to 30"),
        ("/api/evaluate", {"spectra": [[-1] * 31]}, "greater than or equal to 0"),
        ("/api/evaluate", {"spectra": [[1] * 31] * 5}, "at most 4"),
        ("/api/evaluate", {"spectra": [[1] * 31], "display": "CRT"}, "display"),
        ("/api/evaluate", {"spectra": [[1] * 31], "gamut": "magic"}, "gamut"),
        ("/api/evaluate", {"spectra": [[1] * 31], "pairs": [[0, 3]]}, "not sent"),
        ("/api/evaluate", {"spectra": [[1] * 31], "path": "/etc/passwd"}, "path"),
        ("/api/evaluate", {"spectra": [[1] * 31], "illuminant": [0] * 31}, "dark"),
        ("/api/model", {"observer": "1888"}, "observer"),
        ("/api/metamer", {"target": [0] * 31}, "black"),
        ("/api/import", {"filename": "x.csv", "content": "no header"}, "x.csv"),
        ("/api/import", {"filename": "x.json",
                         "content": '{"wavelengths_nm": [400, 700], "values": [NaN, 1]}'},
         "NaN or infinite"),
        ("/api/import", {"filename": "x.json",
                         "content": '{"wavelengths_nm": [400, 700], "values": [1e400, 1]}'},
         "NaN or infinite"),
        ("/api/export", {"names": ["../x"], "spectra": [[1] * 31]}, "names"),
    ],
)
def test_malformed_requests_get_a_clear_4xx(client, path, body, needle):
    r = client.post(path, json=body)
    assert 400 <= r.status_code < 500
    assert needle in r.json()["error"], r.json()


def test_non_finite_numbers_and_huge_bodies_are_refused(client):
    text = '{"spectra": [[NaN' + ", 1" * 30 + "]]}"
    r = client.post("/api/evaluate", content=text, headers={"content-type": "application/json"})
    assert r.status_code == 422 and "finite" in r.json()["error"]
    big = client.post("/api/evaluate", content=b"[" + b"1," * 1_500_000 + b"1]",
                      headers={"content-type": "application/json"})
    assert big.status_code == 413
    assert client.get("/api/presets", params={"step_nm": "3"}).status_code == 422


def test_cli_registers_app_and_binds_loopback():
    import argparse

    from spectrocolor.cli import COMMAND_MODULES
    from spectrocolor.cli import app as cli_app

    assert "app" in COMMAND_MODULES
    parser = argparse.ArgumentParser()
    cli_app.register(parser.add_subparsers())
    args = parser.parse_args(["app", "--no-browser", "--port", "0"])
    # no --host: `run` binds 127.0.0.1 (class mode, the local-network address); the bound address is
    # checked where the real command starts (tests/cli/test_cli_app.py)
    assert args.host is None and not args.classroom and args.port == 0 and args.no_browser


def test_metamer_of_a_boundary_colour_is_a_true_metamer(client):
    """QA: a single bin at 700 nm is an optimal colour (a vertex of the solid): its only
    metamer is itself, and the answer must reproduce its XYZ (it once missed by 0.125)."""
    target = [0.0] * 30 + [30.0]
    r = client.post("/api/metamer", json={"target": target})
    assert r.status_code == 200, r.text
    out = r.json()
    np.testing.assert_allclose(out["XYZ_metamer"], cie_xyz(target), atol=1e-10)
    np.testing.assert_allclose(out["levels"], target, atol=1e-9)


def test_metamer_under_a_one_band_illuminant_is_a_clear_4xx(client):
    r = client.post("/api/metamer", json={"target": [30.0] * 31, "illuminant": [0] * 30 + [30]})
    assert 400 <= r.status_code < 500
    assert "linearly dependent" in r.json()["error"]


@pytest.mark.parametrize(
    ("body", "needle"),
    [
        ({"filename": "x.json", "content": json.dumps(
            {"wavelengths_nm": [400, 700], "values": [[[1, 2]]]})}, "(N, K)"),
        ({"filename": "x.json", "content": json.dumps(
            {"wavelengths_nm": [400, 700], "values": [[1, 2]] * 65})}, "at most 64"),
        ({"filename": "x.json", "step_nm": True, "content": json.dumps(
            {"wavelengths_nm": [400, 700], "values": [1, 2]})}, "boolean"),
    ],
)
def test_import_refuses_deep_batches_too_many_spectra_and_boolean_step(client, body, needle):
    r = client.post("/api/import", json=body)
    assert 400 <= r.status_code < 500
    assert needle in r.json()["error"], r.json()


def test_import_accepts_as_many_spectra_as_the_page_shows(client):
    doc = json.dumps({"wavelengths_nm": [400, 700], "values": [[1, 2]] * 4})
    r = client.post("/api/import", json={"filename": "x.json", "content": doc})
    assert r.status_code == 200 and len(r.json()["levels"]) == 4


def test_equal_energy_grey_renders_grey_by_default_and_pinkish_unadapted(client):
    # issue 13: the equal-energy grey was (163, 146, 143) on sRGB; adapted to the display's
    # white (Bradford) it is R = G = B. Cross-check: colour-science's Bradford matrix from
    # E to D65 applied to the XYZ, then the IEC sRGB matrix.
    grey = [15.0] * 31
    adapted = evaluate(client, [grey])["colours"][0]
    assert max(adapted["codes"]) - min(adapted["codes"]) <= 1
    raw = evaluate(client, [grey], adaptation="none")["colours"][0]
    assert raw["codes"] == [163, 146, 143]
    XYZ = np.array(adapted["XYZ"])
    d65 = colour.xy_to_XYZ(colour.CCS_ILLUMINANTS["CIE 1931 2 Degree Standard Observer"]["D65"])
    e_white = cie_xyz([30] * 31)
    M = colour.adaptation.matrix_chromatic_adaptation_VonKries(e_white, d65 * e_white[1],
                                                               transform="Bradford")
    np.testing.assert_allclose(adapted["XYZ_displayed"], M @ XYZ, rtol=1e-3)  # 4-digit CAT
    spectra_equ = evaluate(client, [grey], display="SPECTRA equal-energy",
                           adaptation="none")["colours"][0]
    assert len(set(spectra_equ["codes"])) == 1  # matris.equ: E gives R = G = B


def test_spectra_exact_reproduces_the_programs_numbers(client):
    # Seed 002: one k per channel (the full spectrum is X = Y = Z = 100) and R_max = 1.32 x R of
    # the white through matris.d (Appendix, 4 significant figures) -> R = 1/1.32 for the white.
    T = np.array([[0.02994, -0.01313, -0.004606], [-0.01022, 0.01836, 0.0004061],
                  [0.000527, -0.001944, 0.009541]])
    rgb_white = T @ [100, 100, 100]
    c = evaluate(client, [[30] * 31], display="SPECTRA 7000K", normalise="spectra-exact",
                 adaptation="none")["colours"][0]
    np.testing.assert_allclose(c["XYZ_displayed"], [100, 100, 100], rtol=1e-12)
    np.testing.assert_allclose(c["rgb_unmapped"], rgb_white / (1.32 * rgb_white[0]), rtol=2e-3)
    assert c["scale"] == pytest.approx(1.32 * rgb_white[0], rel=2e-3)  # 1.611, not 1.58
    m = client.post("/api/model", json={"display": "SPECTRA 7000K", "adaptation": "none",
                                        "normalise": "spectra-exact"}).json()
    assert m["fixed_scale"] == pytest.approx(c["scale"], rel=1e-12)


def test_model_serves_step4_the_white_point_and_its_cct(client):
    m = client.post("/api/model", json={"display": "SPECTRA 7000K"}).json()
    # seed 002: "the white-point of the screen ... is indicated as 7000 K" (x, y = 0.303, 0.327);
    # Ohno 2013 via colour-science for the same chromaticity
    xy = np.array(m["display_white"]["xy"])
    np.testing.assert_allclose(xy, [0.303, 0.327], atol=6e-4)
    expected = colour.temperature.uv_to_CCT(colour.xy_to_UCS_uv(xy), method="Ohno 2013")[0]
    assert m["display_white"]["cct_K"] == pytest.approx(expected, abs=2.0)
    assert 6900 < m["display_white"]["cct_K"] < 7200
    prim = np.array(m["emission"]["levels_per_drive"]) / 30  # back to 'E at Y = 100 is 1.0'
    np.testing.assert_allclose(cie_xyz(prim * 30), sc.rgb_space("SPECTRA 7000K").matrix_to_XYZ.T,
                               rtol=1e-8, atol=1e-8)
    assert len(m["excitation"]["emission"]) == 64 and len(m["emission"]["ybar"]) == 31


@pytest.mark.parametrize("display", ["sRGB", "SPECTRA 7000K"])
def test_emitted_light_is_a_metamer_of_the_shown_colour(client, display):
    # step 4: C(λ) = Σ γ(code) primary(λ), scaled back by the normalisation, has the XYZ the
    # display was asked to show, up to the quantisation of the codes (half a code step)
    r = evaluate(client, [P.STRAW, P.GREEN], display=display, adaptation="none")
    for c in r["colours"]:
        assert c["in_gamut"]
        np.testing.assert_allclose(cie_xyz(c["emitted_levels"]), c["emitted_XYZ"], rtol=1e-8)
        tol = 0.02 if display == "sRGB" else 0.06  # 8-bit vs 6-bit codes
        np.testing.assert_allclose(c["emitted_XYZ"], c["XYZ"], rtol=tol)
        assert not np.allclose(c["emitted_levels"], P.STRAW if c is r["colours"][0] else P.GREEN,
                               atol=1)  # a different spectrum: a metamer


def test_default_gamut_never_shows_a_bare_black_patch(client):
    line = [0.0] * 31
    line[12] = 30.0  # 520 nm: R and B negative on sRGB
    options = client.get("/api/options").json()
    assert options["gamuts"][0] == options["defaults"]["gamut"] == "desaturate"
    c = evaluate(client, [line])["colours"][0]
    assert not c["in_gamut"] and c["gamut_applied"] == "desaturate"
    assert c["negative"] == ["R", "B"] and max(c["codes"]) > 0
    assert c["explanation"] == c["status"] == (
        "cannot be reproduced (R, B negative): desaturated toward the white at constant "
        "luminance (hue kept)")
    strict = evaluate(client, [line], gamut="flag")["colours"][0]
    assert strict["codes"] == [0, 0, 0] and strict["gamut_applied"] == "flag"


def test_single_line_illuminant_works_in_setting4(client):
    # issue 13: the sodium lamp (all energy at 590 nm) gave a 422; now λd is undefined, not an
    # error, and the colours are computed
    sodium = [0.0] * 31
    sodium[19] = 30.0
    r = evaluate(client, [[30] * 31, P.S4_YELLOW[0], P.S4_BLUE[0]], illuminant=sodium,
                 pairs=[[1, 2]])
    white, yellow, blue = r["colours"]
    assert white["XYZ"][1] == pytest.approx(100.0)
    for c in (white, yellow, blue):
        assert c["dominant_nm"] is None and "undefined" in c["dominant_note"]
    # under one line every sample has the lamp's chromaticity, only its lightness differs
    np.testing.assert_allclose(yellow["xy"], white["xy"], atol=1e-12)
    assert yellow["XYZ"][1] == pytest.approx(100 * P.S4_YELLOW[0][19] / 30)
    assert blue["XYZ"][1] < yellow["XYZ"][1]


def test_a_deep_red_line_illuminant_has_no_cielab_but_still_answers(client):
    # a line at 650 nm: z̄ = 0 there, so the white has Z = 0 and CIELAB (hence ΔE00) is
    # undefined; the colours are still computed and shown (found by tests/test_fuzz_app_colour)
    red = [0.0] * 31
    red[25] = 30.0
    r = evaluate(client, [[30] * 31, [15] * 31], illuminant=red, pairs=[[0, 1]])
    assert r["white_XYZ"][2] == 0 and "undefined" in r["lab_note"]
    assert r["delta_e_2000"] == [None] and r["colours"][0]["lab"] == [None, None, None]
    assert max(r["colours"][1]["codes"]) > 0 and r["colours"][1]["XYZ"][1] == pytest.approx(50)


# --- no 500 and no non-finite JSON (issue 31) ----------------------------------------------------


def test_an_answer_with_nan_is_a_422_naming_where_not_a_500():
    """The net under every route: an answer that would hold NaN or an infinity is refused (422)
    with the place named, in the error shape; before, Starlette's ValueError made a 500."""
    app = create_app()

    @app.get("/api/nan-for-the-test")
    def nan_answer():
        return {"colours": [{"xy": [0.3, float("nan")]}]}

    response = TestClient(app, base_url="http://127.0.0.1", raise_server_exceptions=False).get(
        "/api/nan-for-the-test")
    assert response.status_code == 422
    assert "colours[0].xy[1]" in response.json()["error"]


def test_a_declared_full_scale_that_overflows_is_refused(client):
    ti3 = ('CTI3\nSPECTRAL_NORM "1e-320"\nBEGIN_DATA_FORMAT\nSAMPLE_ID SPEC_400 SPEC_500 SPEC_600 '
           'SPEC_700\nEND_DATA_FORMAT\nBEGIN_DATA\n1 10 20 30 40\nEND_DATA\n')
    r = client.post("/api/import", json={"filename": "x.ti3", "content": ti3})
    assert r.status_code == 422 and "SPECTRAL_NORM" in r.json()["error"]


def test_values_that_overflow_when_scaled_are_refused(client):
    content = "wavelength_nm,a\n400,1e308\n550,1.7e308\n700,1e308\n"
    r = client.post("/api/import", json={"filename": "x.csv", "content": content, "scale": "unit"})
    assert r.status_code == 422, r.text


@pytest.mark.parametrize("peak", [380, 450, 530, 600, 780])
@pytest.mark.parametrize("width", [5, 200])
def test_a_single_led_light_is_measured_not_refused(client, peak, width):
    """94 of 122 single-LED lights got 422 "cannot be adapted": a nearly monochromatic white
    defeats Bradford's sensors. Its samples are now shown unadapted, and the answer says so."""
    r = client.post("/api/lab/light", json={"source": {"kind": "leds", "peaks_nm": [peak],
                                                       "widths_nm": [width], "powers": [1.0]}})
    assert r.status_code == 200, r.text
    samples = r.json()["samples"]
    assert len(samples["under_light"]) == 14
    assert samples["under_light_note"].startswith(("adapted", "not adapted"))


def test_a_light_whose_vector_graphic_has_an_empty_bin_says_why():
    """This two-LED light has a TM-30 hue bin with no sample: its graphic was NaN (a 500)."""
    from spectrocolor.app.light_lab import light_lab

    lab = light_lab({"kind": "leds", "peaks_nm": [718.7993482534919, 380.0],
                     "widths_nm": [148.05013990937218, 5.0], "powers": [0.39249177601258245, 1.0]})
    assert lab["graphic"] is None and "hue bin" in lab["graphic_note"]
    json.dumps(lab, allow_nan=False)


def test_the_labs_compute_in_worker_processes(client):
    """A lab's maths (up to a second for a fresh reflectance) runs in a worker, not in the
    server's threads where it would hold the interpreter lock while other clients wait."""
    import os

    from spectrocolor.app import lab_routes

    r = client.post("/api/lab/solid/section", json={"Y": 42.0})
    assert r.status_code == 200, r.text
    pids = lab_routes._workers.worker_pids()
    assert pids and os.getpid() not in pids
