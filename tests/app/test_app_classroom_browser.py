"""Issue 30 in real Chromium: a teacher's desktop page and two students (a phone and a tablet).

The real server runs in class mode on 127.0.0.2 (``spectrocolor app --classroom``, see
``classserver``). The teacher opens the teacher address, the students the join address; each
page is its own browser context (its own cookies, as on separate devices). Checked: the teacher's
page shows the QR code, the join address, the number connected and what class mode exposes; a
push changes the students' pages (the phone follows, the tablet that turned "Follow teacher" off
does not); a state a student sends appears in the teacher's list and opens on the teacher's page;
renewing the code disconnects the students. Screenshots go to the artifacts folder.
"""

from __future__ import annotations

import pytest

from appbrowser import DESKTOP, PHONE, TABLET, choose, open_page, settle, state
from classserver import class_server

pytestmark = pytest.mark.browser


@pytest.fixture(scope="module")
def classroom():
    with class_server() as c:
        yield c


def setting_of(pg) -> int:
    return state(pg)["setting"]


def test_push_and_send_back_between_teacher_phone_and_tablet(browser, classroom, artifacts_dir):
    with open_page(browser, classroom["teacher"], DESKTOP) as teacher, \
            open_page(browser, classroom["join"], PHONE, touch=True) as phone, \
            open_page(browser, classroom["join"], TABLET, touch=True) as tablet:
        teacher.wait_for_selector("#class-qr svg")
        assert teacher.locator("#class-join").inner_text() == classroom["join"]
        assert "nothing leaves the local network" in teacher.locator("#class-exposure").inner_text()
        teacher.wait_for_function("document.getElementById('class-count').textContent === '2'")
        for pg in (phone, tablet):
            pg.wait_for_selector("#class-live.on")
            assert pg.locator("#class-follow").is_checked()
        teacher.screenshot(path=str(artifacts_dir / "classroom_teacher.png"))
        phone.screenshot(path=str(artifacts_dir / "classroom_phone_joined.png"))

        # the teacher pushes setting 3: both students follow (the URL state, whole)
        choose(teacher, 3)
        teacher.click("#class-push")
        teacher.wait_for_function("document.getElementById('class-status').textContent.includes('pushed to 2')")
        for pg in (phone, tablet):
            pg.wait_for_function("window.__classPushes === 1")
            settle(pg)
            assert setting_of(pg) == 3
            assert state(pg)["dists"] == state(teacher)["dists"]  # exact: whole levels
        phone.screenshot(path=str(artifacts_dir / "classroom_phone_followed.png"))
        tablet.screenshot(path=str(artifacts_dir / "classroom_tablet_followed.png"))

        # the tablet goes its own way; the next push reaches it without changing its page
        tablet.locator("#class-follow").uncheck()
        choose(teacher, 2)
        teacher.click("#class-push")
        phone.wait_for_function("window.__classPushes === 2")
        tablet.wait_for_function("window.__classPushes === 2")
        settle(phone)
        settle(tablet)
        assert setting_of(phone) == 2 and setting_of(tablet) == 3
        assert "not followed" in tablet.locator("#class-status").inner_text()

        # the phone sends its state (setting 5) back; the teacher opens it
        choose(phone, 5)
        phone.fill("#class-name", "Ada")
        phone.click("#class-send")
        phone.wait_for_function("document.getElementById('class-status').textContent.startsWith('sent')")
        row = teacher.locator("#class-received li", has_text="Ada")
        row.wait_for()
        teacher.screenshot(path=str(artifacts_dir / "classroom_teacher_received.png"))
        row.get_by_role("button", name="Open").click()
        teacher.wait_for_function("new URLSearchParams(location.search).get('s') === '5'")
        settle(teacher)
        assert setting_of(teacher) == 5
        assert state(teacher)["dists"] == state(phone)["dists"]  # exact: whole levels

        # a new code: the students are disconnected and told so
        teacher.on("dialog", lambda dialog: dialog.accept())
        teacher.click("#class-renew")
        teacher.wait_for_function(f"document.getElementById('class-join').textContent !== {classroom['join']!r}")
        for pg in (phone, tablet):
            pg.wait_for_function("document.getElementById('class-status').textContent.includes('renewed')",
                                 timeout=20000)
        teacher.wait_for_function("document.getElementById('class-count').textContent === '0'")
        phone.screenshot(path=str(artifacts_dir / "classroom_phone_renewed.png"))
