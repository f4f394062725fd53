"""Issue 30 in the labs, in real Chromium: the class panel on a lab page, a push of a lab's state,
and a student who follows the teacher from the explorer into a lab and back stays in the class.

The real server runs in class mode (``classserver``); the teacher and the student are two browser
contexts (their own cookies, as on two devices). A lab keeps its state in the URL's fragment, so a
pushed lab state is its path and fragment.
"""

from __future__ import annotations

import pytest

from appbrowser import DESKTOP, PHONE, choose, open_page, settle, state
from classserver import class_server

pytestmark = pytest.mark.browser

LAB = "/labs/reflectance#light=D65&step=5&x=0.45&y=0.4&Y=30"


@pytest.fixture(scope="module")
def classroom():
    with class_server() as c:
        yield c


def lab_ready(pg, timeout=120000):
    pg.wait_for_selector("body[data-ready=true]", state="attached", timeout=timeout)


def test_a_student_follows_the_teacher_into_a_lab_and_back(browser, classroom, artifacts_dir):
    origin = classroom["origin"]
    with open_page(browser, classroom["teacher"], DESKTOP) as teacher, \
            open_page(browser, classroom["join"], PHONE, touch=True) as student:
        student.wait_for_selector("#class-live.on")
        teacher.wait_for_function("document.getElementById('class-count').textContent === '1'")

        # the teacher opens a lab: the class panel is there too, and pushes the lab's state
        teacher.goto(origin + LAB)
        lab_ready(teacher)
        teacher.wait_for_selector("#class-qr svg")
        teacher.click("#class-push")
        teacher.wait_for_function("document.getElementById('class-status').textContent.includes('pushed to 1')")
        student.wait_for_url("**/labs/reflectance#*", timeout=30000)
        lab_ready(student)
        assert student.evaluate("location.pathname + location.hash") == LAB
        assert student.input_value("#x") == "0.45" and student.input_value("#y") == "0.4"
        # the student is still in the class on the lab page
        student.wait_for_selector("#class-live.on")
        assert student.locator("#class-follow").is_checked()
        teacher.wait_for_function("document.getElementById('class-count').textContent === '1'")
        teacher.screenshot(path=str(artifacts_dir / "classroom_lab_teacher.png"))
        student.screenshot(path=str(artifacts_dir / "classroom_lab_student_phone.png"))

        # a push within the lab: the student's lab page changes in place (same page, new fragment)
        teacher.fill("#x", "0.3")
        teacher.dispatch_event("#x", "change")
        teacher.wait_for_function("location.hash.includes('x=0.3&')")
        teacher.click("#class-push")
        student.wait_for_function("window.__classPushes === 1")
        student.wait_for_function("document.querySelector('#x').value === '0.3'")
        assert student.evaluate("location.hash") == teacher.evaluate("location.hash")

        # the student sends the lab's state back; the teacher's list has it and opens it
        student.fill("#class-name", "Lin")
        student.click("#class-send")
        student.wait_for_function("document.getElementById('class-status').textContent.startsWith('sent')")
        row = teacher.locator("#class-received li", has_text="Lin")
        row.wait_for()

        # the teacher goes back to the explorer's setting 2 and pushes: the student follows out of
        # the lab, into the explorer, still in the class
        teacher.goto(origin + "/?s=2")
        settle(teacher)
        teacher.wait_for_selector("#class-qr svg")
        teacher.click("#class-push")
        teacher.wait_for_function("document.getElementById('class-status').textContent.includes('pushed to 1')")
        student.wait_for_url(lambda url: "/labs/" not in url, timeout=30000)
        settle(student)
        assert state(student)["setting"] == 2
        student.wait_for_selector("#class-live.on")
        choose(teacher, 3)
        teacher.click("#class-push")
        student.wait_for_function("window.__classPushes === 1")
        settle(student)
        assert state(student)["setting"] == 3


def test_the_lab_class_panel_has_no_serious_accessibility_violations(browser, classroom):
    import json

    from appbrowser import AXE

    for address, size in ((classroom["teacher"], DESKTOP), (classroom["join"], PHONE)):
        context = browser.new_context(viewport={"width": size[0], "height": size[1]})
        page = context.new_page()
        errors = []
        page.on("pageerror", lambda e, errors=errors: errors.append(str(e)))
        page.goto(address)
        page.evaluate("sessionStorage.setItem('spectrocolor-follow', '0')")  # stay on the lab page
        page.goto(classroom["origin"] + LAB)
        lab_ready(page)
        page.wait_for_selector("#classroom:not([hidden]) button")
        page.add_script_tag(path=str(AXE))
        result = json.loads(page.evaluate("async () => JSON.stringify(await axe.run(document))"))
        violations = [v for v in result["violations"] if v["impact"] in ("serious", "critical")]
        assert not violations, [(v["id"], v["help"], [n["target"] for n in v["nodes"]][:3]) for v in violations]
        context.close()
        assert not errors, errors
