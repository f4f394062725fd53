"""Issue 28, item 2: every guided demonstration, run in Chromium against the real server.

For each demo file the test opens the page the demo belongs to, opens its Demos list, chooses
the demo, checks that the page now holds the demo's state (the explorer's setting, options and
levels, or the lab's controls), presses "Show me" where the demo has a second state, and checks
each of the demo's ``expect`` bounds against the numbers the page *shows* (read from the cards'
text, not from the page's memory). Where a demo claims two patches match or differ, the patches'
painted colours are compared too. Screenshots of some demos go to the artifacts folder (and to
/tmp/h28d/ for a person to look at), and axe checks the Demos panel.

The expected levels of an explorer state are rebuilt here from ``/api/presets`` and the demo's
own ``set`` entries, independently of the page's demos.js.
"""

from __future__ import annotations

import json
import math
import re
import urllib.request
from pathlib import Path

import pytest

from appbrowser import AXE, open_lab, open_page, settle
from spectrocolor.app.demos import DEMO_FOLDER, load_demos

pytestmark = pytest.mark.browser

SIZE = (1440, 900)
DEMOS = load_demos(DEMO_FOLDER)
SHOTS = {"straw-short-waves", "notch-540", "three-line-match", "metamers-under-a",
         "filters-in-series", "soap-film-thinning", "smoothest-reflectance", "colour-rendering-tube",
         "spotlights-red-green"}
# the patch pairs whose ΔE00 the card shows (setting 2 and 3: the split patch; 4: the samples)
PAIR = {2: (0, 1), 3: (0, 1), 4: (1, 2)}
# one 8-bit code step per channel is 1/255; "visibly the same" here means every channel of the
# painted patches within 6 codes (ΔE00 < 1 on these colours), "visibly different" more than that
SAME_CODES = 6


@pytest.fixture(scope="module", autouse=True)
def warm_server(base_url):
    """A cold server on a loaded machine answers the page's first requests 429 (busy), and the
    page then does not start; ask once until the workers answer, as a teacher's reload would."""
    import time
    import urllib.error

    for _ in range(60):
        try:
            with urllib.request.urlopen(base_url + "api/presets?step_nm=10", timeout=30) as r:
                if r.status == 200:
                    return
        except urllib.error.URLError:
            pass
        time.sleep(1)


def expected_levels(base_url, setting, distributions, mode="series"):
    """The levels a demo's explorer state should put on the page (rebuilt from /api/presets)."""
    with urllib.request.urlopen(base_url + "api/presets?step_nm=10") as r:
        P = json.load(r)
    out = []
    for i, spec in enumerate(distributions):
        def find(rows, key=spec.get("preset")):  # noqa: B008 -- this spec's key, bound now
            return next(q for q in rows if q["key"] == key)
        if "preset" in spec:
            if setting == 1:
                q = find(P["setting1"])
                levels = q["cycle"][0]["levels"] if "cycle" in q else q["levels"]
            elif setting == 2:
                q = find(P["setting2"]["left" if i == 0 else "right"])
                levels = q["cycle"][0]["levels"] if "cycle" in q else q["levels"]
            elif setting == 4:
                q = find(P["setting4"]["illuminants"] if i == 0 else P["setting4"]["samples"])
                levels = q["levels"] if i == 0 else q["left" if i == 1 else "right"]
            else:
                q = find(P["setting3" if setting == 3 else
                           "setting5_additive" if mode == "additive" else "setting5"])
                levels = q["left" if i == 0 else "right"]
        elif "levels" in spec:
            levels = spec["levels"]
        else:
            levels = [spec["constant"]] * 31
        levels = list(levels)
        for nm, v in spec.get("set", {}).items():
            levels[(int(nm) - 400) // 10] = v
        out.append(levels)
    return out


# ---------------------------------------------------------------- what the page shows
def number(text):
    """A number as the page writes it; None for its "—" (undefined, e.g. a black patch)."""
    return None if text == "—" else float(text)


def explorer_values(pg, setting):
    """The numbers the explorer's cards show, per patch, and the pair's ΔE00."""
    values = {}
    cards = pg.locator("#numbers .card[data-i]")
    for k in range(cards.count()):
        card = cards.nth(k)
        i = int(card.get_attribute("data-i"))
        dom = card.locator("td.dom").inner_text()
        m = re.match(r"(λd|λc) (-?[\d.]+) nm.*p ([\d.]+)", dom)
        L, a, b = (number(v) for v in card.locator("td.lab").inner_text().split())
        x, y = (number(v) for v in card.locator("td.xy").inner_text().split())
        Y = number(card.locator("td.XYZ").inner_text().split()[1])
        values[i] = {"lambda_d": None if not m else float(m[2]) * (-1 if m[1] == "λc" else 1),
                     "purity": None if not m else float(m[3]), "L": L,
                     "chroma": None if a is None or b is None else math.hypot(a, b),
                     "x": x, "y": y, "Y": Y, "dom_text": dom}
    page = {}
    if pg.locator("#numbers .de-card .de").count():
        text = pg.locator("#numbers .de-card .de").inner_text()
        page["dE00"] = float(text) if re.fullmatch(r"[\d.]+", text) else None
    return values, page


def lab_rows(pg):
    return pg.evaluate("""() => Object.fromEntries([...document.querySelectorAll('#numbers dt')]
        .map((dt) => [dt.textContent, dt.nextElementSibling.textContent]))""")


def lab_values(pg, lab):
    rows = lab_rows(pg)
    if lab == "thinfilm":
        return {"Y": float(rows["Y"].split()[0]), "thickness_nm": float(rows["thickness"].split()[0])}
    if lab == "light":
        return {"Ra": number(rows["Ra (CIE 13.3)"]), "R9": number(rows["R9 (strong red)"]),
                "Rf": number(rows["Rf (TM-30 / CIE 224)"]), "Rg": number(rows["Rg (gamut)"]),
                "cct_K": number(rows["CCT"].split()[0])}
    if lab == "solid":  # the status line: "… fill the purple region, up to ΔE*ab 34.2 from …"
        m = re.search(r"up to ΔE\*ab ([\d.]+)", pg.locator("#status").inner_text())
        return {"mismatch_dEab_max": float(m[1]) if m else None}
    ranges = {}
    for label, key in (("unconstrained", "unconstrained"), ("0 ≤ ρ ≤ 1", "unit")):
        m = re.search(r"ρ from (-?[\d.]+) to (-?[\d.]+)", rows[label])
        ranges[f"{key}_min"], ranges[f"{key}_max"] = (float(m[1]), float(m[2])) if m else (None, None)
    ranges["max_Y"] = float(re.search(r"Y = ([\d.]+)", rows["brightest object colour"])[1])
    return ranges


def patch_rgb(pg, i):
    css = pg.locator(f"#patches .patch[data-i='{i}']").first.evaluate(
        "e => getComputedStyle(e).backgroundColor")
    return [float(v) for v in css[css.index("(") + 1:-1].split(",")[:3]]


# ---------------------------------------------------------------- the page holds the state
def check_explorer_state(pg, base_url, demo, st):
    n = int(demo["where"][-1])
    got = pg.evaluate("() => { const S = window.__spectra; return {setting: S.setting, step: S.step,"
                      " normalise: S.normalise, dists: S.dists[S.setting]}; }")
    assert got["setting"] == n, (demo["id"], got["setting"])
    assert got["step"] == 10, demo["id"]
    if "normalise" in st:
        assert got["normalise"] == st["normalise"], demo["id"]
    # exact: whole levels 0-30, copied, never computed
    assert got["dists"] == expected_levels(base_url, n, st["distributions"], st.get("mode", "series")), demo["id"]
    got_mode = pg.evaluate("() => window.__spectra.mode5")
    if n == 5:
        assert got_mode == st.get("mode", "series"), demo["id"]
    assert f"s={n}" in pg.evaluate("location.search")
    tab = pg.locator(f"#tabs [data-setting='{n}']")
    assert tab.get_attribute("aria-selected") == "true"


def wait_lab_state(pg, lab, st):
    if lab == "thinfilm":
        pg.wait_for_function("(d) => { const dd = [...document.querySelectorAll('#numbers dt')]"
                             ".find((dt) => dt.textContent === 'thickness');"
                             " return dd && dd.nextElementSibling.textContent === `${d} nm`; }", arg=st["d"])
        assert pg.locator("#thickness").input_value() == str(st["d"])
        assert pg.locator("#film").input_value() == st["film"]
    elif lab == "light":
        pg.wait_for_function("(w) => { const dt = [...document.querySelectorAll('#numbers dt')]"
                             ".find((e) => e.textContent === 'light'); return dt &&"
                             " dt.nextElementSibling.textContent === w; }", arg=st["name"])
        assert pg.locator("#name").input_value() == st["name"]
    elif lab == "solid":
        pg.wait_for_function("(s) => { const st = window.__solid && window.__solid.state;"
                             " const r = window.__solid && window.__solid.region; return st && r &&"
                             " st.second === s.second && st.light === s.light && st.sample === s.sample"
                             " && document.querySelector('#status').textContent.includes('ΔE*ab')"
                             " && r.second_illuminant.includes(s.second); }", arg=st, timeout=120_000)
        assert pg.locator("#second").input_value() == st["second"]
        assert pg.locator("#sample").input_value() == str(st["sample"])
    else:
        want = f"x {st['x']:.4f}, y {st['y']:.4f}, Y {st['Y']:.1f} under {st['light']}"
        pg.wait_for_function("(w) => { const dt = [...document.querySelectorAll('#numbers dt')]"
                             ".find((e) => e.textContent === 'colour'); return dt &&"
                             " dt.nextElementSibling.textContent === w; }", arg=want)
        assert float(pg.locator("#x").input_value()) == pytest.approx(st["x"], abs=1e-9)
        assert pg.locator("#light").input_value() == st["light"]


def load_phase(pg, demo, phase, base_url):
    selector = "#demo-show" if phase == "then" else f"#demos-list button[data-demo='{demo['id']}']"
    pg.click(selector)
    pg.wait_for_selector(f"body[data-demo='{demo['id']}:{phase}']")
    st = demo["then"]["state"] if phase == "then" else demo["state"]
    if demo["where"].startswith("setting"):
        settle(pg)
        check_explorer_state(pg, base_url, demo, st)
        assert pg.locator("#error").is_hidden(), pg.locator("#error-text").inner_text()
        return explorer_values(pg, int(demo["where"][-1]))
    wait_lab_state(pg, demo["where"], st)
    assert pg.locator("#error").is_hidden(), pg.locator("#error-text").inner_text()
    return {}, lab_values(pg, demo["where"])


def value_of(shown, e):
    patches, page = shown
    return patches[e["patch"]][e["quantity"]] if "patch" in e else page[e["quantity"]]


def check_expect(demo, shown):
    """Every bound of the demo's ``expect`` against what the page showed."""
    failures = []
    for e in demo["expect"]:
        at = e.get("at", "state")
        v = value_of(shown[at], e)
        of = f" of patch {e['patch']}" if "patch" in e else ""
        where = f"{demo['id']}: {at} {e['quantity']}{of} = {v}"
        if v is None:
            failures.append(f"{where}: the page shows no value")
            continue
        if "min" in e and not v >= e["min"]:
            failures.append(f"{where} < {e['min']}")
        if "max" in e and not v <= e["max"]:
            failures.append(f"{where} > {e['max']}")
        if "min_change" in e or "max_change" in e:
            change = v - value_of(shown["state"], e)
            if "min_change" in e and not change >= e["min_change"]:
                failures.append(f"{where}: changed by {change} < {e['min_change']}")
            if "max_change" in e and not change <= e["max_change"]:
                failures.append(f"{where}: changed by {change} > {e['max_change']}")
    assert not failures, failures


def check_patches_agree_with_delta_e(pg, demo, setting, page):
    """What ΔE00 claims, the painted patches show: within a few codes when it says they match,
    more apart when it says they differ."""
    if setting not in PAIR or page.get("dE00") is None:
        return
    a, b = (patch_rgb(pg, i) for i in PAIR[setting])
    apart = max(abs(u - v) for u, v in zip(a, b, strict=True))
    if page["dE00"] < 1:
        assert apart <= SAME_CODES, (demo["id"], a, b)
    if page["dE00"] > 5:
        assert apart > SAME_CODES, (demo["id"], a, b)


RUN_AXE = """async () => {
  const r = await axe.run({include: [["#demos-panel"], ["#demos-open"]]}, {runOnly: {type: "tag",
    values: ["wcag2a", "wcag2aa", "wcag21a", "wcag21aa", "wcag22aa"]}});
  return r.violations.filter((v) => v.impact === "serious" || v.impact === "critical")
    .map((v) => ({id: v.id, nodes: v.nodes.slice(0, 3).map((n) => n.target.join(" "))}));
}"""


def open_where(browser, base_url, where):
    if where.startswith("setting"):
        return open_page(browser, base_url, SIZE)
    return _lab(browser, base_url + f"labs/{where}")


class _lab:
    def __init__(self, browser, url):
        self.browser, self.url = browser, url

    def __enter__(self):
        self.pg, self.errors = open_lab(self.browser, self.url, SIZE)
        return self.pg

    def __exit__(self, *exc):
        self.pg.close()
        assert not self.errors, self.errors


@pytest.mark.parametrize("demo", DEMOS, ids=[d["id"] for d in DEMOS])
def test_every_demo_reaches_what_it_says(browser, base_url, artifacts_dir, demo):
    shots = Path("/tmp/h28d")
    shots.mkdir(exist_ok=True)
    where = demo["where"]
    with open_where(browser, base_url, where) as pg:
        pg.wait_for_selector("body[data-demos=ready]")
        if where.startswith("setting") and where != "setting1":
            pg.click(f"#tabs [data-setting='{where[-1]}']")  # the list follows the setting
            settle(pg)
        pg.click("#demos-open")
        assert pg.locator("#demos-panel").is_visible()
        assert pg.locator(f"#demos-list button[data-demo='{demo['id']}']").inner_text() == demo["title"]
        shown = {"state": load_phase(pg, demo, "state", base_url)}
        assert pg.locator("#demo-question").inner_text() == demo["question"]
        assert pg.locator("#demo-look").inner_text() == demo["look"]
        assert pg.locator("#demo-answer").is_hidden()
        setting = int(where[-1]) if where.startswith("setting") else None
        check_patches_agree_with_delta_e(pg, demo, setting, shown["state"][1])
        if demo["id"] in SHOTS:
            pg.screenshot(path=str(shots / f"demo_{demo['id']}_start.png"))
        if "then" in demo:
            shown["then"] = load_phase(pg, demo, "then", base_url)
            assert demo["then"]["do"] in pg.locator("#demo-done").inner_text()
            check_patches_agree_with_delta_e(pg, demo, setting, shown["then"][1])
        if "badge" in demo["answer"]:  # the answer points at a card's out-of-gamut badge: it shows
            assert pg.locator("#numbers .card .badge:not([hidden])").count() >= 1, demo["id"]
        pg.click("#demo-reveal")
        assert pg.locator("#demo-answer").is_visible()
        assert demo["answer"] in pg.locator("#demo-answer").inner_text()
        check_expect(demo, shown)
        if demo["id"] in SHOTS:
            pg.screenshot(path=str(shots / f"demo_{demo['id']}_shown.png"))
            pg.screenshot(path=str(artifacts_dir / f"demo_{demo['id']}.png"))


@pytest.mark.parametrize("url", ["", "labs/thinfilm", "labs/reflectance", "labs/light"])
def test_the_demos_panel_passes_axe_and_lists_its_page(browser, base_url, url):
    opener = open_page(browser, base_url, SIZE) if not url else _lab(browser, base_url + url)
    with opener as pg:
        pg.wait_for_selector("body[data-demos=ready]")
        pg.click("#demos-open")
        ids = pg.evaluate("[...document.querySelectorAll('#demos-list button')].map((b) => b.dataset.demo)")
        where = url.split("/")[-1] if url else "setting1"
        assert ids == [d["id"] for d in DEMOS if d["where"] == where]
        pg.click("#demos-list button")
        pg.wait_for_selector("body[data-demo$=':state']")
        pg.add_script_tag(path=str(AXE))
        assert pg.evaluate(RUN_AXE) == []
        pg.click("#demo-reveal")
        assert pg.evaluate(RUN_AXE) == []
        pg.click("#demos-close")
        assert pg.locator("#demos-panel").is_hidden()
