"""Every SPECTRA demonstration shows what the seed's words promise (issue 13, seed 002).

Each preset goes through the app's own path (HTTP API -> compute -> library) with the page's
default choices (normalisation A, E adapted to the display's white, gamut "desaturate"), on
sRGB and on SPECTRA's monitor. What the patch shows is read back from the API's linear drive
values: the shown colour's CIELAB L*, C*ab relative to the display's white, and its dominant
wavelength λd relative to the display's white (negative: complementary, a purple). The ranges
are the seed's words made numbers:

* hue names by λd: blue 440-490 nm, turquoise 485-500, green 500-565, yellow 565-592, orange
  585-605, red >= 600 (or a purple-red beyond the locus' red end); magenta: complementary;
* "grey"/"neutral": C*ab <= 1.5 (the rounding of 8-bit or 6-bit codes gives at most ~1);
* "faint": C*ab <= 25; "strong"/"intense": more chroma than the weak version; "dark": L* < 50
  (darker than a middle grey).
"""

from __future__ import annotations

import numpy as np
import pytest
from fastapi.testclient import TestClient

import spectrocolor as sc
from spectrocolor.app.server import create_app
from spectrocolor.mixing import complementary_edit, subtractive_mix

DISPLAYS = ["sRGB", "SPECTRA 7000K"]
NEUTRAL_C = 1.5


@pytest.fixture(scope="module")
def client():
    return TestClient(create_app(), base_url="http://127.0.0.1")  # the Host a browser sends


@pytest.fixture(scope="module")
def presets(client):
    return client.get("/api/presets", params={"step_nm": 10}).json()


def shown(client, spectra, display, illuminant=None, pairs=()):
    """The API's answer with the default choices, plus what each patch shows."""
    body = {"spectra": [list(map(float, s)) for s in spectra], "display": display,
            "pairs": [list(p) for p in pairs]}
    if illuminant is not None:
        body["illuminant"] = list(map(float, illuminant))
    r = client.post("/api/evaluate", json=body)
    assert r.status_code == 200, r.text
    answer = r.json()
    space = sc.rgb_space(display)
    out = []
    for c in answer["colours"]:
        XYZ = space.XYZ_from_rgb_linear(c["rgb_linear"])
        L, a, b = sc.lab(XYZ, space.white_XYZ)
        lam = None
        if np.hypot(a, b) > NEUTRAL_C:
            d = sc.dominant_wavelength(sc.xy(XYZ), space.white_xy)
            lam = -float(d.wavelength_nm) if d.complementary else float(d.wavelength_nm)
        out.append({"L": float(L), "C": float(np.hypot(a, b)), "lam": lam, "api": c})
    return out, answer


def assert_hue(patch, lo, hi, what):
    assert patch["lam"] is not None and lo <= patch["lam"] <= hi, (what, patch["lam"],
                                                                   patch["C"])


def assert_not_black(patch, what):
    assert patch["L"] > 8 and max(patch["api"]["codes"]) > 0, (what, patch["L"])


def by_key(items):
    return {q["key"]: q for q in items}


def test_every_preset_is_integer_levels_on_spectras_grid(presets):
    levels = []
    for q in presets["setting1"]:
        levels += [c["levels"] for c in q["cycle"]] if "cycle" in q else [q["levels"]]
    for side in ("left", "right"):
        for q in presets["setting2"][side]:
            levels += [c["levels"] for c in q["cycle"]] if "cycle" in q else [q["levels"]]
    for key in ("setting3", "setting5"):
        levels += [q[s] for q in presets[key] for s in ("left", "right")]
    levels += [q["levels"] for q in presets["setting4"]["illuminants"]]
    levels += [q[s] for q in presets["setting4"]["samples"] for s in ("left", "right")]
    a = np.array(levels)
    assert a.shape[1] == 31
    np.testing.assert_array_equal(a, np.round(a))  # exact: whole levels are their own rounding
    assert a.min() >= 0 and a.max() <= 30


# ------------------------------------------------------------------ setting 1
SETTING1 = {  # key: (λd range, C*ab range, L* range) from the seed's description
    "1": ((565, 592), (8, 35), (60, 100)),   # straw: monotonously increasing, yellow-making
    "2": ((465, 495), (8, 35), (60, 100)),   # light blue: decreasing, blue-making
    "4": ((500, 565), (25, 200), (0, 100)),  # green: central parts dominate
    "5": ((-570, -490), (25, 200), (0, 100)),  # magenta: the sides dominate (a purple)
    "6": ((565, 592), (40, 200), (0, 100)),  # yellow: stronger than straw
    "7": ((440, 485), (50, 200), (0, 50)),   # blue: strongly accentuated short-wave side
}


@pytest.mark.parametrize("display", DISPLAYS)
@pytest.mark.parametrize("key", sorted(SETTING1))
def test_setting1_preset_shows_its_name(client, presets, display, key):
    q = by_key(presets["setting1"])[key]
    (p,), _ = shown(client, [q["levels"]], display)
    lam, chroma, lightness = SETTING1[key]
    assert_hue(p, *lam, q["name"])
    assert chroma[0] <= p["C"] <= chroma[1], (q["name"], p["C"])
    assert lightness[0] <= p["L"] <= lightness[1], (q["name"], p["L"])
    assert p["api"]["in_gamut"], (q["name"], p["api"]["explanation"])


@pytest.mark.parametrize("display", DISPLAYS)
def test_setting1_grey_is_neutral_and_the_stronger_colours_are_stronger(client, presets,
                                                                        display):
    s1 = by_key(presets["setting1"])
    patches, _ = shown(client, [s1[k]["levels"] for k in "1362"], display)
    straw, grey, yellow, light_blue = patches
    assert grey["C"] <= NEUTRAL_C and grey["api"]["status"] == "ok"
    if display == "sRGB":  # the equal-energy grey was (163, 146, 143) before adaptation
        assert max(grey["api"]["codes"]) - min(grey["api"]["codes"]) <= 1
    (blue,), _ = shown(client, [s1["7"]["levels"]], display)
    assert yellow["C"] > straw["C"] + 10 and blue["C"] > light_blue["C"] + 10


@pytest.mark.parametrize("display", DISPLAYS)
def test_setting1_sunset_deepens_from_yellow_to_red_and_is_never_black(client, presets,
                                                                       display):
    cycle = by_key(presets["setting1"])["8"]["cycle"]
    patches, _ = shown(client, [c["levels"] for c in cycle[:4]], display)
    more, _ = shown(client, [c["levels"] for c in cycle[4:]], display)
    patches += more
    assert patches[0]["C"] <= NEUTRAL_C  # d = 0: the full spectrum, white
    hues = [p["lam"] for p in patches[1:]]
    assert all(b >= a - 0.5 for a, b in zip(hues, hues[1:], strict=False)), hues
    assert 570 <= hues[0] <= 585 and hues[-1] >= 605, hues  # yellow ... red
    for c, p in zip(cycle, patches, strict=True):
        assert_not_black(p, f"sunset d={c['d']}")
        if not p["api"]["in_gamut"]:  # the badge says what was done and which channel
            assert p["api"]["gamut_applied"] == "desaturate" and p["api"]["negative"]
            assert "negative" in p["api"]["explanation"]


# ------------------------------------------------------------------ setting 2
@pytest.mark.parametrize("display", DISPLAYS)
def test_setting2_intense_versions_share_the_hue(client, presets, display):
    left, right = by_key(presets["setting2"]["left"]), by_key(presets["setting2"]["right"])
    for key in "12":  # straw vs yellow, light blue vs blue: "what makes a colour intense"
        (a, b), _ = shown(client, [left[key]["levels"], right[key]["levels"]], display)
        assert abs(a["lam"] - b["lam"]) <= 12 and b["C"] > a["C"] + 10, (key, a, b)
    for key in "34567":
        patches, _ = shown(client, [left[key]["levels"], right[key]["levels"]], display)
        for p in patches:
            assert_not_black(p, key)


# ------------------------------------------------------------------ setting 3
@pytest.mark.parametrize("display", DISPLAYS)
def test_setting3_default1_the_hue_survives_taking_the_yellow_away(client, presets, display):
    q = by_key(presets["setting3"])["1"]
    left, right = np.array(q["left"], float), np.array(q["right"], float)
    (before,), _ = shown(client, [left], display)
    for k in (17, 18):  # 570 and 580 nm go to the right
        left, right = complementary_edit(left, right, k, 0, full=30)
    (a, b), _ = shown(client, [left, right], display)
    assert_hue(before, 565, 592, "yellow")
    for p in (a, b):  # "they both have the same hue ... as the one you started with"
        assert abs(p["lam"] - before["lam"]) <= 8, (before["lam"], a["lam"], b["lam"])
    assert b["L"] < 50  # the right one is dark: brown


@pytest.mark.parametrize("display", DISPLAYS)
def test_setting3_default2_reaches_the_fig12_metameric_pair(client, presets, display):
    q = by_key(presets["setting3"])["2"]
    left, right = np.array(q["left"], float), np.array(q["right"], float)
    for k, level in q["moves"]:  # 580, 570 fully; 560 and 590 partly
        left, right = complementary_edit(left, right, k, level, full=30)
    assert left[17] == 0 and left[18] == 0  # no photons at 570 and 580 nm on the left
    (a, b), answer = shown(client, [left, right], display, pairs=[(0, 1)])
    assert answer["delta_e_2000"][0] < 1.0, answer["delta_e_2000"]  # metameric
    for p in (a, b):
        assert_hue(p, 565, 595, "yellow/brown")


@pytest.mark.parametrize("display", DISPLAYS)
@pytest.mark.parametrize("key", ["3", "4"])
def test_setting3_yellow_and_blue_complements(client, presets, display, key):
    q = by_key(presets["setting3"])[key]
    np.testing.assert_array_equal(np.add(q["left"], q["right"]), 30)  # exact: sums of whole levels
    (a, b), _ = shown(client, [q["left"], q["right"]], display)
    assert_hue(a, 565, 592, "yellow")
    assert_hue(b, 440, 490, "blue")
    assert_not_black(b, "blue")
    if key == "3":
        assert a["api"]["in_gamut"] and b["api"]["in_gamut"]


@pytest.mark.parametrize("display", DISPLAYS)
def test_setting3_default5_magenta_and_green_with_neutral_can_be_shown(client, presets,
                                                                        display):
    q = by_key(presets["setting3"])["5"]
    (a, b), _ = shown(client, [q["left"], q["right"]], display)
    assert a["api"]["in_gamut"] and b["api"]["in_gamut"]  # "otherwise ... could not be shown"
    assert_hue(a, -570, -490, "magenta")
    assert_hue(b, 500, 565, "green")


# ------------------------------------------------------------------ setting 4
SAMPLE_HUES = {"metameric yellow": (565, 592), "metameric green": (500, 565),
               "metameric blue": (440, 490)}


@pytest.mark.parametrize("display", DISPLAYS)
def test_setting4_illuminants_look_as_the_seed_says(client, presets, display):
    ills = {q["name"]: q["levels"] for q in presets["setting4"]["illuminants"]}
    white = [[30.0] * 31]
    (e,), _ = shown(client, white, display, ills["E"])
    (a,), _ = shown(client, white, display, ills["A"])
    (t65,), _ = shown(client, white, display, ills["T65 three-band"])
    (d65,), _ = shown(client, white, display, ills["D65"])
    assert e["C"] <= NEUTRAL_C  # E is the display's white
    assert_hue(a, 575, 600, "incandescent")  # "looks so strongly coloured"
    assert a["C"] > 30
    assert d65["C"] < 12 and t65["C"] < 12  # daylight and its three-band match: near white
    assert abs(d65["lam"] - t65["lam"]) < 5


@pytest.mark.parametrize("display", DISPLAYS)
@pytest.mark.parametrize("illuminant", ["E", "D65", "T65 three-band", "A"])
def test_setting4_samples_are_shown_under_every_illuminant(client, presets, display,
                                                           illuminant):
    ill = {q["name"]: q["levels"] for q in presets["setting4"]["illuminants"]}[illuminant]
    for q in presets["setting4"]["samples"]:
        patches, answer = shown(client, [q["left"], q["right"]], display, ill, pairs=[(0, 1)])
        for p in patches:
            assert_not_black(p, (q["name"], illuminant))
            assert p["api"]["in_gamut"], (q["name"], illuminant, p["api"]["explanation"])
        if illuminant == "D65":  # the pair is metameric in daylight and has its hue
            assert answer["delta_e_2000"][0] < 0.3, (q["name"], answer["delta_e_2000"])
            if q["name"] in SAMPLE_HUES:
                for p in patches:
                    assert_hue(p, *SAMPLE_HUES[q["name"]], q["name"])
            else:
                assert max(p["C"] for p in patches) < 10  # grey (D65 is bluer than E)
        if illuminant == "E" and q["name"] == "metameric grey":
            assert max(p["C"] for p in patches) < 3


# ------------------------------------------------------------------ setting 5
def product(q):
    return subtractive_mix(q["left"], q["right"], full=30)


@pytest.mark.parametrize("display", DISPLAYS)
def test_setting5_filters_mix_to_the_named_colour(client, presets, display):
    s5 = by_key(presets["setting5"])
    got = {}
    for key, q in s5.items():
        (f1, f2, mix), _ = shown(client, [q["left"], q["right"], product(q)], display)
        got[key] = (f1, f2, mix)
        assert_not_black(mix, q["name"])
    f1, f2, mix = got["1"]  # straw and light blue: a faint green
    assert_hue(mix, 500, 565, "faint green")
    assert mix["C"] <= 25
    assert_hue(f1, 565, 592, "straw")
    assert_hue(f2, 465, 495, "light blue")
    f1, f2, mix = got["2"]  # yellow and turquoise: green
    assert_hue(f1, 565, 592, "yellow")
    assert_hue(f2, 480, 500, "turquoise")
    assert_hue(mix, 505, 565, "green")
    assert mix["C"] >= 25
    f1, f2, mix = got["3"]  # yellow and blue: dark green
    assert_hue(f2, 450, 490, "blue")
    assert_hue(mix, 500, 565, "dark green")
    assert mix["L"] < 50 and mix["C"] >= 15
    f1, f2, mix = got["4"]  # yellow and magenta: red
    assert_hue(f2, -570, -490, "magenta")
    assert_hue(mix, 600, 700, "red")
    assert mix["C"] >= 40
    f1, f2, mix = got["5"]  # green and magenta neutralise each other to grey
    assert_hue(f1, 500, 565, "green")
    assert_hue(f2, -570, -490, "magenta")
    assert mix["C"] <= 3
    f1, f2, mix = got["6"]  # two orange filters: a deeper and redder orange
    assert_hue(f1, 585, 605, "orange")
    assert mix["lam"] > f1["lam"] + 3 and mix["C"] > f1["C"] and mix["L"] < f1["L"]
    f1, f2, mix = got["7"]  # two moss-green filters make a dark red (dichroism)
    assert_hue(f1, 500, 570, "moss green")
    assert_hue(mix, 600, 700, "dark red")
    assert mix["L"] <= 20
    f1, f2, mix = got["8"]  # two medium grey filters give a darker grey
    assert f1["C"] <= NEUTRAL_C and mix["C"] <= NEUTRAL_C and mix["L"] < f1["L"] - 10
