"""Accessibility of the explorer (issue 13, point 8), in Chromium with the real server.

axe-core (vendored in tests/vendor/axe-core, never fetched) finds no serious or critical WCAG 2.x
A/AA violation in any setting, on a desktop and a phone viewport, nor with the About panel open;
the selected bin is an ARIA slider with a value text; the settings are tabs; the patches have
text alternatives; the bars stand out from the panel with a contrast of at least 3:1."""

from __future__ import annotations

import pytest

from appbrowser import AXE, DESKTOP, PHONE, choose, key, open_page, settle

pytestmark = pytest.mark.browser

RUN_AXE = """async () => {
  const r = await axe.run(document, {runOnly: {type: "tag",
    values: ["wcag2a", "wcag2aa", "wcag21a", "wcag21aa", "wcag22aa"]}});
  return r.violations.filter((v) => v.impact === "serious" || v.impact === "critical")
    .map((v) => ({id: v.id, impact: v.impact, help: v.help,
                  nodes: v.nodes.slice(0, 3).map((n) => n.target.join(" "))}));
}"""


def axe_violations(pg):
    if not pg.evaluate("typeof axe !== 'undefined'"):
        pg.add_script_tag(path=str(AXE))
    return pg.evaluate(RUN_AXE)


@pytest.mark.parametrize("size", [DESKTOP, PHONE], ids=["desktop", "phone"])
def test_axe_finds_nothing_serious_in_any_setting(browser, base_url, size):
    with open_page(browser, base_url, size) as pg:
        found = {}
        for setting in (1, 2, 3, 4, 5):
            choose(pg, setting)
            key(pg, "2")
            found[setting] = axe_violations(pg)
        pg.click("#about-open")
        found["about"] = axe_violations(pg)
        assert not any(found.values()), found
        # a control: axe does report an unlabelled field once there is one
        pg.evaluate("document.querySelector('#about').append(document.createElement('input'))")
        assert "label" in [v["id"] for v in axe_violations(pg)]


def test_the_selected_bin_is_an_aria_slider_with_value_text(browser, base_url):
    with open_page(browser, base_url) as pg:
        choose(pg, 1)
        slider = pg.locator("#editors [role=slider]")
        assert slider.count() == 1
        slider.focus()
        for _ in range(20):
            if slider.get_attribute("aria-valuetext").startswith("550 nm"):
                break
            key(pg, "ArrowRight" if int(slider.get_attribute("aria-valuetext")[:3]) < 550
                else "ArrowLeft")
        level = pg.evaluate("window.__spectra.dists[1][0][15]")
        assert slider.get_attribute("aria-valuetext") == f"550 nm, {level:.0f} of 30"
        assert slider.get_attribute("aria-valuenow") == f"{level:g}"
        assert (slider.get_attribute("aria-valuemin"), slider.get_attribute("aria-valuemax")) == ("0", "30")
        key(pg, "ArrowUp")
        assert slider.get_attribute("aria-valuetext") == f"550 nm, {level + 1:.0f} of 30"
        choose(pg, 4)
        names = [s.get_attribute("aria-label") for s in pg.locator("#editors [role=slider]").all()]
        assert len(names) == 3 and names[0].startswith("illuminant")


def test_settings_are_tabs_and_patches_have_text(browser, base_url):
    with open_page(browser, base_url) as pg:
        tabs = pg.locator("#tabs[role=tablist] [role=tab]")
        assert tabs.count() == 5
        choose(pg, 2)
        selected = [t.get_attribute("aria-selected") for t in tabs.all()]
        assert selected == ["false", "true", "false", "false", "false"]
        assert pg.locator("#stage[role=tabpanel]").get_attribute("aria-labelledby") == "tab-2"
        pg.locator("#tab-2").focus()
        pg.keyboard.press("ArrowRight")  # arrows move between focused tabs
        settle(pg)
        assert pg.evaluate("window.__spectra.setting") == 3
        label = pg.locator("#patches .patchbox[role=img]").first.get_attribute("aria-label")
        names = pg.evaluate("window.__spectra.names[3]")
        assert label.startswith("Colour patch:") and all(n in label for n in names)
        assert "#" in label  # the colour, as hex


def luminance(rgb):
    def lin(c):
        c /= 255
        return c / 12.92 if c <= 0.04045 else ((c + 0.055) / 1.055) ** 2.4
    r, g, b = (lin(float(c)) for c in rgb)
    return 0.2126 * r + 0.7152 * g + 0.0722 * b


def contrast(a, b):
    la, lb = sorted((luminance(a), luminance(b)), reverse=True)
    return (la + 0.05) / (lb + 0.05)


COLUMN = """() => {
  const cv = document.querySelector("#editors .editor[data-e='0'] canvas");
  const g = cv.getContext("2d"), x = Math.round(cv.width * 1.5 / 31);  // the middle of bar 1 (410 nm)
  const px = g.getImageData(x, 0, 1, cv.height).data;
  return Array.from({length: cv.height}, (_, y) => [px[4 * y], px[4 * y + 1], px[4 * y + 2], px[4 * y + 3]]);
}"""


def test_violet_bars_stand_out_from_the_panel(browser, base_url):
    """WCAG 1.4.11: the bar's edge against the panel has a contrast of at least 3:1 (the fill of
    a 400 nm bar alone is about 1:1 on the dark panel; the outline carries the shape)."""
    panel = (0x1E, 0x21, 0x28)
    with open_page(browser, base_url) as pg:
        choose(pg, 1)
        key(pg, "1")  # straw: the 400 nm bar is at level 10, well below the top
        column = pg.evaluate(COLUMN)
        top = len(column) - 17  # the bottom of the bar, just above the wavelength labels
        while column[top - 1][3] == 255:  # up through the opaque bar to its top edge
            top -= 1
        assert top < len(column) * 0.8  # a bar of level 11 of 30, not an empty column
        edge = max(contrast(p[:3], panel) for p in column[top:top + 2])
        assert edge >= 3.0, column[top:top + 3]
        fill = column[(top + len(column)) // 2][:3]
        assert contrast(fill, panel) < 3.0  # the fill alone would not do: the outline is needed
