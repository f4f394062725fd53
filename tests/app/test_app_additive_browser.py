"""Setting 5 as two spotlights (issue 28 item 7), in Chromium against the real server.

Switch setting 5 to "two spotlights", load the orange-red and green default, and check what the
page shows against the library (:func:`spectrocolor.mixing.additive_mix` of the two lights,
evaluated by :func:`spectrocolor.app.compute.evaluate`); that the overlap's point lies on the
segment joining the two lights (Grassmann: an additive mixture is the centre of gravity of its
components, weights X + Y + Z), read from the numbers the cards show; that the overlap is painted
yellow (seed 002: "an orange-red and a green filter will give yellow illumination"); that undo
takes back the default and then the mode switch; that a reload keeps the mode; axe; screenshots at
desktop and phone size (artifacts/ and /tmp/additive/)."""

from __future__ import annotations

import colorsys
from pathlib import Path

import numpy as np
import pytest

from appbrowser import AXE, DESKTOP, PHONE, check_card, choose, key, library, open_page, patch_rgb, settle, state
from spectrocolor.app import presets as P

pytestmark = pytest.mark.browser
SHOTS = Path("/tmp/additive")

RUN_AXE = """async () => {
  const r = await axe.run(document, {runOnly: {type: "tag",
    values: ["wcag2a", "wcag2aa", "wcag21a", "wcag21aa", "wcag22aa"]}});
  return r.violations.filter((v) => v.impact === "serious" || v.impact === "critical")
    .map((v) => ({id: v.id, nodes: v.nodes.slice(0, 3).map((n) => n.target.join(" "))}));
}"""


def shown_xy(pg, i):
    return np.array([float(v) for v in pg.locator(f"#numbers .card[data-i='{i}'] td.xy").inner_text().split()])


def shown_XYZ(pg, i):
    return np.array([float(v) for v in pg.locator(f"#numbers .card[data-i='{i}'] td.XYZ").inner_text().split()])


def spotlights(pg):
    choose(pg, 5)
    assert pg.locator("#mode5").is_visible()
    pg.check("#mode5 input[value='additive']")
    settle(pg)
    key(pg, "1")  # orange-red and green


def shots(pg, artifacts_dir, name):
    SHOTS.mkdir(exist_ok=True)
    for folder in (artifacts_dir, SHOTS):
        pg.screenshot(path=str(folder / f"{name}.png"), full_page=True)


def test_two_spotlights_add_and_their_overlap_lies_on_the_line(browser, base_url, artifacts_dir):
    with open_page(browser, base_url, DESKTOP) as pg:
        spotlights(pg)
        st = state(pg)
        assert st["mode5"] == "additive" and "m=add" in pg.evaluate("location.search")
        assert st["dists"] == [P.SPOT_RED, P.SPOT_GREEN]  # exact: whole levels, copied
        # every card as the library computes it (the overlap: additive_mix of the two lights)
        lib = library(st)["colours"]
        for i in range(4):
            check_card(pg, i, lib[i])
        # the overlap's xy equals the library's to the page's rounding (4 decimals: 5e-5)
        np.testing.assert_allclose(shown_xy(pg, 3), lib[3]["xy"], rtol=0, atol=5e-5 + 1e-12)
        # collinear, from the shown numbers: the cross product of (p2 - p1) and (p3 - p1); each of
        # the six coordinates is off by at most 5e-5 and enters with a factor below 1, so |cross|
        # is below 6 * 5e-5 at most
        p1, p2, p3 = (shown_xy(pg, i) for i in (1, 2, 3))
        d, e = p2 - p1, p3 - p1
        assert abs(d[0] * e[1] - d[1] * e[0]) < 3e-4
        t = float(d @ e / (d @ d))
        assert 0 < t < 1  # between the two lights, not beyond either
        # the lever rule: t is light 2's share of X + Y + Z (shown to 2 decimals of ~100)
        s1, s2 = shown_XYZ(pg, 1).sum(), shown_XYZ(pg, 2).sum()
        assert t == pytest.approx(s2 / (s1 + s2), abs=2e-3)
        # the dashed mixing line joins the two points on the diagram
        line = pg.evaluate("""() => { const l = document.getElementById('mix-line');
            return {shown: getComputedStyle(l).display !== 'none', x1: +l.getAttribute('x1'),
                    y1: +l.getAttribute('y1'), x2: +l.getAttribute('x2'), y2: +l.getAttribute('y2')}; }""")
        assert line["shown"]
        np.testing.assert_allclose([line["x1"], -line["y1"], line["x2"], -line["y2"]],
                                   [*lib[1]["xy"], *lib[2]["xy"]], rtol=0, atol=1e-9)
        # the overlap is painted yellow: hue of the patch's sRGB between orange and yellow-green
        h, s, v = colorsys.rgb_to_hsv(*(np.array(patch_rgb(pg, 3)) / 255))
        assert 40 <= h * 360 <= 75 and s > 0.3, (h * 360, s)
        shots(pg, artifacts_dir, "additive_desktop")
        # undo: first the default, then the mode switch; redo brings both back
        pg.locator("#editors canvas").first.focus()
        key(pg, "Control+z")
        assert state(pg)["dists"] != [P.SPOT_RED, P.SPOT_GREEN] and state(pg)["mode5"] == "additive"
        key(pg, "Control+z")
        assert state(pg)["mode5"] == "series" and "m=add" not in pg.evaluate("location.search")
        assert pg.is_checked("#mode5 input[value='series']")
        assert pg.evaluate("getComputedStyle(document.getElementById('mix-line')).display") == "none"
        key(pg, "Control+Shift+z")
        key(pg, "Control+Shift+z")
        st = state(pg)
        assert st["mode5"] == "additive" and st["dists"] == [P.SPOT_RED, P.SPOT_GREEN]  # exact: copied
        # a reload keeps the mode and the lights
        pg.reload()
        settle(pg)
        st = state(pg)
        assert st["setting"] == 5 and st["mode5"] == "additive" and st["dists"] == [P.SPOT_RED, P.SPOT_GREEN]
        assert pg.is_checked("#mode5 input[value='additive']")
        # key M switches back to the filters in series (and the product graph)
        key(pg, "m")
        assert state(pg)["mode5"] == "series"
        assert "product" in pg.locator("#editors .editor.readonly").inner_text()


@pytest.mark.parametrize("size", [DESKTOP, PHONE], ids=["desktop", "phone"])
def test_spotlights_axe_and_phone(browser, base_url, artifacts_dir, size, tmp_path):
    with open_page(browser, base_url, size) as pg:
        spotlights(pg)
        assert pg.locator("#mode5").is_visible()
        if size == DESKTOP:  # the picture for a slide names the sum graph and the overlap
            with pg.expect_download() as d:
                pg.click("#save-svg")
            path = tmp_path / d.value.suggested_filename
            d.value.save_as(path)
            text = path.read_text(encoding="utf-8")
            assert "both lights (sum" in text and "both lights (overlap)" in text
        if size == PHONE:
            shots(pg, artifacts_dir, "additive_phone")
            # nothing wider than the phone
            assert pg.evaluate("document.documentElement.scrollWidth") <= size[0]
        pg.add_script_tag(path=str(AXE))
        assert pg.evaluate(RUN_AXE) == []
