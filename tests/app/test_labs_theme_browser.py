"""The labs share the explorer's look (issue 28, "one app"), in Chromium with the real server.

The explorer and the four labs link one palette (``static/theme.css``): the page's background and
text colour are the same on all five pages; axe-core (vendored) finds no serious or critical WCAG
violation on any lab at a desktop and a phone size; and every lab's plot draws its axes and labels
in the theme's text colour (a canvas keeps its own pixels, so a plot still inked for a white page
would be dark on the dark panel). Screenshots of each lab at both sizes go to ``/tmp/labs/`` (and
the test artifacts) for a person to look at."""

from __future__ import annotations

import json
import shutil
from pathlib import Path

import pytest

from appbrowser import AXE, DESKTOP, PHONE, open_lab, open_page

pytestmark = pytest.mark.browser

#: each lab and a canvas on it that draws a plot with axes and labels
LABS = {"light": "spd", "reflectance": "spectrum", "solid": "section", "thinfilm": "spectrum"}
SHOTS = Path("/tmp/labs")

#: the page's effective background (the body's, else the root's) and its text colour
LOOK = """() => {
  const bg = (e) => getComputedStyle(e).backgroundColor;
  const transparent = (c) => c === "rgba(0, 0, 0, 0)" || c === "transparent";
  const body = bg(document.body);
  return {background: transparent(body) ? bg(document.documentElement) : body,
          text: getComputedStyle(document.body).color,
          themeText: getComputedStyle(document.documentElement).getPropertyValue("--text").trim()};
}"""

#: how many opaque pixels of a canvas lie within `tol` (per channel) of the theme's text colour
INKED = """([id, tol]) => {
  const c = document.getElementById(id);
  const probe = document.createElement("canvas").getContext("2d");
  probe.fillStyle = getComputedStyle(c).getPropertyValue("--text").trim(); probe.fillRect(0, 0, 1, 1);
  const [r, g, b] = probe.getImageData(0, 0, 1, 1).data;
  const d = c.getContext("2d").getImageData(0, 0, c.width, c.height).data;
  let n = 0;
  for (let k = 0; k < d.length; k += 4)
    if (d[k + 3] > 200 && Math.abs(d[k] - r) <= tol && Math.abs(d[k + 1] - g) <= tol
        && Math.abs(d[k + 2] - b) <= tol) n++;
  return {n, total: d.length / 4, text: [r, g, b]};
}"""

RUN_AXE = """async () => {
  const r = await axe.run(document, {runOnly: {type: "tag",
    values: ["wcag2a", "wcag2aa", "wcag21a", "wcag21aa", "wcag22aa"]}});
  return r.violations.filter((v) => v.impact === "serious" || v.impact === "critical")
    .map((v) => ({id: v.id, impact: v.impact, help: v.help,
                  nodes: v.nodes.slice(0, 3).map((n) => n.target.join(" "))}));
}"""


def _shot(page, name, artifacts_dir):
    SHOTS.mkdir(exist_ok=True)
    path = SHOTS / f"{name}.png"
    page.screenshot(path=str(path), full_page=True)
    shutil.copy(path, artifacts_dir / f"labs_theme_{name}.png")


def test_the_explorer_and_every_lab_have_one_background_and_text_colour(browser, base_url):
    with open_page(browser, base_url) as pg:
        explorer = pg.evaluate(LOOK)
    # the explorer's dark palette (theme.css): background #15171c, text #e6e8ee
    assert explorer["background"] == "rgb(21, 23, 28)", explorer
    assert explorer["text"] == "rgb(230, 232, 238)", explorer
    for lab in LABS:
        page, errors = open_lab(browser, base_url + f"labs/{lab}", timeout_ms=60000)
        try:
            assert page.evaluate(LOOK) == explorer, lab
            assert not errors, errors
        finally:
            page.close()


@pytest.mark.parametrize("size", [DESKTOP, PHONE], ids=["desktop", "phone"])
def test_every_lab_is_legible_and_axe_finds_nothing_serious(browser, base_url, size, artifacts_dir):
    found = {}
    for lab, canvas in LABS.items():
        page, errors = open_lab(browser, base_url + f"labs/{lab}", size, timeout_ms=60000)
        try:
            page.add_script_tag(path=str(AXE))
            found[lab] = page.evaluate(RUN_AXE)
            # the plot's axes, ticks and labels are in the theme's text colour: at least a few
            # hundred pixels of it (a tick label alone is ~30), within 40 of 255 per channel for
            # the antialiased edges of 1–2 px lines
            inked = page.evaluate(INKED, [canvas, 40])
            assert inked["n"] >= 200, (lab, inked)
            _shot(page, f"{lab}_{'desktop' if size == DESKTOP else 'phone'}", artifacts_dir)
            assert not errors, errors
        finally:
            page.close()
    assert not any(found.values()), json.dumps(found, indent=1)


def test_the_colour_patches_are_not_tinted_by_the_theme(browser, base_url):
    """A sample's colour is the computed one: the reflectance lab's patch shows the server's rgb8."""
    page, errors = open_lab(browser, base_url + "labs/reflectance", timeout_ms=60000)
    try:
        shown = page.eval_on_selector("#patch", "e => getComputedStyle(e).backgroundColor")
        label = page.eval_on_selector("#patch", "e => e.getAttribute('aria-label')")
        assert shown.startswith("rgb(") and shown in label, (shown, label)  # the server's srgb8
        assert page.eval_on_selector("#patch", "e => getComputedStyle(e).opacity") == "1"
        assert page.eval_on_selector("#patch", "e => getComputedStyle(e).filter") == "none"
        assert not errors, errors
    finally:
        page.close()
