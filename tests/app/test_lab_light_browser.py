"""The light-source lab in Debian's Chromium: controls drive the numbers, the graphic and the samples."""

from __future__ import annotations

import json

import pytest

from appbrowser import AXE, DESKTOP, PHONE, open_lab
from spectrocolor.app import light_lab as lab

pytestmark = pytest.mark.browser


def shown_numbers(page) -> dict:
    terms = page.eval_on_selector_all("#numbers dt", "es => es.map(e => e.textContent)")
    values = page.eval_on_selector_all("#numbers dd", "es => es.map(e => e.textContent)")
    return dict(zip(terms, values, strict=True))


def test_a_named_light_shows_the_librarys_indices(browser, base_url, artifacts_dir):
    page, errors = open_lab(browser, base_url + "labs/light")
    expected = lab.light_lab({"kind": "named", "name": "FL2"})["summary"]
    numbers = shown_numbers(page)
    assert numbers["Ra (CIE 13.3)"] == f"{expected['Ra']:.1f}"
    assert numbers["Rf (TM-30 / CIE 224)"] == f"{expected['Rf']:.1f}"
    assert numbers["CCT"] == f"{expected['cct_K']:.0f} K"
    page.select_option("#name", "blackbody")
    page.wait_for_function("document.querySelector('#numbers').textContent.includes('blackbody 3000 K')")
    assert shown_numbers(page)["Ra (CIE 13.3)"] == "100.0"  # a Planckian radiator is its own reference
    page.select_option("#name", "FL2")
    page.wait_for_function("document.querySelector('#numbers dd').textContent === 'FL2'")
    page.screenshot(path=str(artifacts_dir / "lab_light.png"), full_page=True)
    assert not errors, errors


def test_led_sliders_change_the_light_and_the_url_reproduces_it(browser, base_url):
    page, errors = open_lab(browser, base_url + "labs/light")
    page.select_option("#kind", "leds")
    page.wait_for_function("document.querySelector('#numbers dd').textContent.startsWith('LED mixture')")
    peak = page.locator("#primaries input[type=range]").nth(6)  # primary 3's peak
    peak.evaluate("e => { e.value = 600; e.dispatchEvent(new Event('input', {bubbles: true}));"
                  " e.dispatchEvent(new Event('change', {bubbles: true})); }")
    page.wait_for_function("document.querySelector('#numbers dd').textContent === 'LED mixture (450, 540, 600 nm)'")
    page.wait_for_function("document.body.dataset.ready === 'true'")
    expected = lab.light_lab({"kind": "leds", "peaks_nm": [450, 540, 600], "widths_nm": [20, 60, 20],
                              "powers": [1.0, 0.7, 0.8]})
    assert shown_numbers(page)["Rf (TM-30 / CIE 224)"] == f"{expected['summary']['Rf']:.1f}"
    url = page.url
    again, more_errors = open_lab(browser, url)
    assert shown_numbers(again)["light"] == "LED mixture (450, 540, 600 nm)"
    again.close()
    page.keyboard.press("Control+z")
    page.wait_for_function("document.querySelector('#numbers dd').textContent === 'LED mixture (450, 540, 620 nm)'")
    assert not errors and not more_errors


def test_no_serious_accessibility_violations(browser, base_url, artifacts_dir):
    for name, size in (("desktop", DESKTOP), ("phone", PHONE)):
        page, errors = open_lab(browser, base_url + "labs/light#kind=leds", size)
        page.add_script_tag(path=str(AXE))
        result = json.loads(page.evaluate("async () => JSON.stringify(await axe.run(document))"))
        violations = [v for v in result["violations"] if v["impact"] in ("serious", "critical")]
        assert not violations, [(v["id"], v["help"], [n["target"] for n in v["nodes"]][:3]) for v in violations]
        if name == "phone":
            page.screenshot(path=str(artifacts_dir / "lab_light_phone.png"), full_page=True)
        page.close()
        assert not errors, errors


# ---- the upload and the TM-30 hue-bin charts (issue 28 item 6) ----------------------------------

DATA = __import__("pathlib").Path(__file__).parents[1] / "data" / "io"


def shown_bins(page) -> list[list[str]]:
    """The bin table's rows: bin, hue range, Rcs,hj (%), Rhs,hj, Rf,hj as the page shows them."""
    return page.eval_on_selector_all("#bin-table tbody tr",
                                     "rows => rows.map(r => [...r.cells].map(c => c.textContent))")


def library_light(path):
    """The library's reading of the file on the lab's grid and the lab's numbers for it (the
    route's answer is tested equal to colour_fidelity in test_lab_light_upload.py)."""
    light = lab.light_from_file(path)
    return light, lab.light_lab({"kind": "spd", "label": light["label"], "values": light["spd"]})


def drop_file(page, name: str, text: str) -> None:
    """Drop a file on the page as a user's drag-and-drop does (a DataTransfer holding a File)."""
    page.evaluate("""([name, text]) => {
      const data = new DataTransfer();
      data.items.add(new File([text], name, { type: "text/csv" }));
      for (const type of ["dragover", "drop"]) {
        document.body.dispatchEvent(new DragEvent(type, { dataTransfer: data, bubbles: true, cancelable: true }));
      }
    }""", [name, text])


def test_an_uploaded_measurement_file_shows_the_librarys_tm30_and_survives_a_reload(browser, base_url, artifacts_dir,
                                                                                       tmp_path):
    page, errors = open_lab(browser, base_url + "labs/light")
    path = DATA / "sekonic_c800.csv"  # a Sekonic C-800 light-meter export of CIE A, 380-780 nm at 1 nm
    light, expected = library_light(path)
    page.set_input_files("#file", str(path))
    page.wait_for_function("document.querySelector('#numbers dd').textContent.startsWith('sekonic_c800.csv')")
    page.wait_for_function("document.body.dataset.ready === 'true'")
    numbers = shown_numbers(page)
    assert numbers["light"] == light["label"] == "sekonic_c800.csv — Lamp A 2°"
    assert numbers["Rf (TM-30 / CIE 224)"] == f"{expected['summary']['Rf']:.1f}"
    assert numbers["Rg (gamut)"] == f"{expected['summary']['Rg']:.1f}"
    assert numbers["CCT"] == f"{expected['summary']['cct_K']:.0f} K"
    assert page.input_value("#kind") == "file" and "kind=file" in page.url
    # a light with a hue-dependent rendering, dropped on the page: CIE FL2 as a plain CSV
    from spectrocolor import illuminant
    spd = illuminant("FL2", lab.WAVELENGTHS_NM).values
    text = "wavelength_nm,FL2\n" + "".join(f"{w:g},{v:.4f}\n" for w, v in zip(lab.WAVELENGTHS_NM, spd, strict=True))
    (tmp_path / "fl2.csv").write_text(text)
    light, expected = library_light(tmp_path / "fl2.csv")
    drop_file(page, "fl2.csv", text)
    page.wait_for_function("document.querySelector('#numbers dd').textContent === 'fl2.csv — FL2'")
    page.wait_for_function("document.body.dataset.ready === 'true'")
    assert shown_numbers(page)["Rf (TM-30 / CIE 224)"] == f"{expected['summary']['Rf']:.1f}"
    rows = shown_bins(page)
    bins = expected["hue_bins"]
    assert len(rows) == 16
    for j in (0, 4, 15):  # bin 1 (red), bin 5 (yellow-green), bin 16
        assert rows[j][2] == f"{bins['Rcs_h'][j] * 100:.1f}", (j, rows[j])
        assert rows[j][3] == f"{bins['Rhs_h'][j]:.3f}", (j, rows[j])
        assert rows[j][4] == f"{bins['Rf_h'][j]:.1f}", (j, rows[j])
    for chart in ("#chart-rcs", "#chart-rhs", "#chart-rf"):  # 16 bars, each in its bin's colour
        fills = page.eval_on_selector_all(f"{chart} rect.bar", "bars => bars.map(b => b.getAttribute('fill'))")
        assert fills == [f"rgb({r}, {g}, {b})" for r, g, b in expected["bin_rgb8"]], chart
    heights = page.eval_on_selector_all("#chart-rcs rect.bar", "bars => bars.map(b => b.getBBox().height)")
    assert max(heights) > 20  # FL2 loses ~10-20 % chroma in the reds: visible bars, not hairlines
    page.screenshot(path=str(artifacts_dir / "lab_light_upload.png"), full_page=True)
    page.keyboard.press("Control+z")  # back to the first upload, then to the named light
    page.wait_for_function("document.querySelector('#numbers dd').textContent.startsWith('sekonic_c800.csv')")
    page.keyboard.press("Control+z")
    page.wait_for_function("document.querySelector('#numbers dd').textContent === 'FL2'")
    assert not page.is_disabled("#kind option[value=file]")  # the latest upload is one choice away
    page.select_option("#kind", "file")
    page.wait_for_function("document.querySelector('#numbers dd').textContent === 'fl2.csv — FL2'")
    page.reload()  # the upload is kept in the tab's sessionStorage
    page.wait_for_selector("body[data-ready=true]")
    assert shown_numbers(page)["light"] == "fl2.csv — FL2"
    elsewhere, more_errors = open_lab(browser, page.url)  # another tab (a new context): not kept, and said so
    assert shown_numbers(elsewhere)["light"] == "FL2"
    assert "upload the file again" in elsewhere.text_content("#file-note")
    elsewhere.close()
    assert not errors and not more_errors, errors + more_errors


def test_a_bad_file_shows_one_message(browser, base_url):
    page, errors = open_lab(browser, base_url + "labs/light")
    page.set_input_files("#file", str(DATA / "argyll.sp"))  # 380-730 nm: TM-30 needs 380-780
    page.wait_for_selector("#error:not([hidden])")
    message = page.text_content("#error-text")
    assert message.startswith("argyll.sp: covers 380-730 nm; the light lab needs 380-780 nm"), message
    assert page.locator("[role=alert]:visible").count() == 1
    assert shown_numbers(page)["light"] == "FL2"  # the light shown is unchanged
    assert page.is_disabled("#kind option[value=file]")
    page.set_input_files("#file", {"name": "notes.txt", "mimeType": "text/plain", "buffer": b"hello\n"})
    page.wait_for_function("document.querySelector('#error-text').textContent.startsWith('notes.txt')")
    assert page.locator("[role=alert]:visible").count() == 1
    assert not errors, errors


def test_the_bin_charts_at_desktop_and_phone_size_are_accessible(browser, base_url, artifacts_dir):
    for name, size in (("desktop", DESKTOP), ("phone", PHONE)):
        page, errors = open_lab(browser, base_url + "labs/light", size)
        page.click(".bin-table-box summary")  # the table open, so that axe checks it too
        for chart in ("#chart-rcs", "#chart-rhs", "#chart-rf"):
            assert page.locator(f"{chart} rect.bar").count() == 16
            assert page.locator(f"{chart} text", has_text="hue bin j").count() == 1
        page.add_script_tag(path=str(AXE))
        result = json.loads(page.evaluate("async () => JSON.stringify(await axe.run(document))"))
        violations = [v for v in result["violations"] if v["impact"] in ("serious", "critical")]
        assert not violations, [(v["id"], v["help"], [n["target"] for n in v["nodes"]][:3]) for v in violations]
        page.locator(".bins").screenshot(path=str(artifacts_dir / f"lab_light_bins_{name}.png"))
        page.screenshot(path=str(artifacts_dir / f"lab_light_{name}_full.png"), full_page=True)
        page.close()
        assert not errors, errors
