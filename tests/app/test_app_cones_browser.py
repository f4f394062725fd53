"""The L M S row of the explorer's sample cards, in a real browser (issue 28, item 3).

Setting 5's first card is the equal-energy light E itself, the reference of settings 1–3 and 5: the
page scales cone responses so that light has L = M = S = 100, which the row and its bars must show.
The other cards must show the library's own ``cone_responses`` (via ``compute.evaluate``), to the
two decimals the row prints. A screenshot goes to the artifacts folder and /tmp/h28b_cones.png."""

from __future__ import annotations

import pytest

from appbrowser import choose, library, settle, state

pytestmark = pytest.mark.browser


@pytest.fixture(scope="module")
def page(browser, base_url):
    context = browser.new_context(viewport={"width": 1280, "height": 800})
    pg = context.new_page()
    errors = []
    pg.on("pageerror", lambda e: errors.append(str(e)))
    pg.goto(base_url)
    settle(pg)
    yield pg
    assert not errors, errors
    context.close()


def shown_lms(page, i):
    return page.locator(f"#numbers .card[data-i='{i}'] td.lms").inner_text().split()


def test_equal_energy_light_reads_l_m_s_100_and_the_others_match_the_library(page, artifacts_dir):
    choose(page, 5)
    header = page.locator("#numbers .card[data-i='0'] th", has_text="L M S")
    assert header.count() == 1 and "cone" in header.get_attribute("title")
    assert shown_lms(page, 0) == ["100.00", "100.00", "100.00"]
    widths = page.locator("#numbers .card[data-i='0'] .lms-bar").evaluate_all(
        "bars => bars.map((b) => b.getBoundingClientRect().width)")
    assert widths == pytest.approx([60.0, 60.0, 60.0], abs=0.5)  # full width = 100
    lib = library(state(page))["colours"]
    for i in range(1, len(lib)):
        assert shown_lms(page, i) == [f"{v:.2f}" for v in lib[i]["LMS"]]
    # a filter passes less than the full light to some cone: some value below 100, none above
    assert min(lib[3]["LMS"]) < 100 and max(lib[3]["LMS"]) <= 100 + 1e-9
    page.locator("#numbers").screenshot(path=str(artifacts_dir / "cones_setting5.png"))
    page.screenshot(path="/tmp/h28b_cones.png", full_page=True)
