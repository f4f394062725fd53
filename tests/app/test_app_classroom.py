"""Issue 30: classroom mode, with the real server started as a user starts it.

``spectrocolor app --classroom --host 127.0.0.2 --port 0 --no-browser`` runs in its own process;
students are simulated from other loopback addresses (the client socket bound to 127.0.0.3,
127.0.0.4, ...), the teacher by the teacher address the server printed. What is checked is what
the issue asks: join with the code, 403 and nothing served without it or from a foreign Host or
Origin, push received over Server-Sent Events, send-back listed for the teacher, renewal
disconnecting everyone, and the bounds (state length, roles, rate of sends).
"""

from __future__ import annotations

import contextlib
import json
import queue
import re
import threading
import time

import httpx
import pytest

from classserver import HOST, class_server


@pytest.fixture(scope="module")
def classroom():
    """The class's origin, join URL and teacher URL, from the lines the server printed."""
    with class_server(HOST) as c:
        assert any(block in c["output"] for block in "\u2580\u2584\u2588"), "no QR code printed"
        yield c


def client(c, address: str) -> httpx.Client:
    """An HTTP client whose connections come from ``address`` (a loopback address)."""
    return httpx.Client(base_url=c["origin"], timeout=30.0, follow_redirects=False,
                        transport=httpx.HTTPTransport(local_address=address))


@contextlib.contextmanager
def joined(c, address: str, url: str | None = None):
    """A client from ``address`` that opened the join address (or ``url``), with its cookies."""
    with client(c, address) as s:
        r = s.get(url or c["join"])
        assert r.status_code == 303 and r.headers["location"] == "/", r.text
        yield s


def teacher(c):
    return joined(c, "127.0.0.2", c["teacher"])


class Events:
    """An event stream read in a thread: ``(event, data)`` pairs in a queue."""

    def __init__(self, session: httpx.Client):
        self.events: queue.Queue = queue.Queue()
        self.status: int | None = None
        self.ended = threading.Event()
        self.thread = threading.Thread(target=self._read, args=(session,), daemon=True)
        self.thread.start()

    def _read(self, session):
        try:
            with session.stream("GET", "/api/class/events") as r:
                self.status = r.status_code
                name = None
                for line in r.iter_lines():
                    if line.startswith("event: "):
                        name = line[7:]
                    elif line.startswith("data: "):
                        self.events.put((name, json.loads(line[6:])))
                    elif line.startswith("retry: "):
                        self.events.put(("retry", int(line[7:])))
        except httpx.HTTPError:
            pass
        finally:
            self.ended.set()

    def next(self, name: str, timeout: float = 10.0, until=lambda data: True):
        """The next event ``name`` (whose data passes ``until``), within ``timeout`` s."""
        deadline = time.monotonic() + timeout
        while True:
            event, data = self.events.get(timeout=max(0.01, deadline - time.monotonic()))
            if event == name and until(data):
                return data


def test_the_terminal_shows_the_join_address_with_its_code_and_a_qr_code(classroom):
    assert re.fullmatch(r"http://127\.0\.0\.2:\d+/join\?code=[2-9A-HJ-NP-Z]{10}", classroom["join"])
    assert "key=" in classroom["teacher"] and classroom["teacher"].startswith(classroom["origin"])


@pytest.mark.parametrize("path", ["/", "/static/js/main.js", "/api/options", "/api/class/events",
                                  "/api/class/whoami", "/join?code=WRONGCODE2", "/teacher?key=x"])
def test_without_the_code_nothing_is_served(classroom, path):
    with client(classroom, "127.0.0.3") as s:
        r = s.get(path)
    assert r.status_code == 403
    assert set(r.json()) == {"error"} and "join code" in r.json()["error"]


def test_a_student_joins_with_the_code_and_gets_the_page(classroom):
    with joined(classroom, "127.0.0.3") as s:
        assert s.cookies.get("spectrocolor-class") == classroom["join"].split("code=")[1]
        assert s.cookies.get("spectrocolor-role") == "student"
        page = s.get("/")
        assert page.status_code == 200 and "classroom.js" in page.text
        assert s.get("/api/options").status_code == 200
        assert s.post("/api/model", json={"step_nm": 10}).status_code == 200
        assert s.get("/api/class/whoami").json()["role"] == "student"


def test_a_foreign_host_or_origin_is_refused_even_with_the_code(classroom):
    port = classroom["origin"].rsplit(":", 1)[1]
    with joined(classroom, "127.0.0.3") as s:
        for host in (f"evil.example:{port}", f"127.0.0.1:{port}", f"localhost:{port}", HOST):
            r = s.get("/", headers={"Host": host})
            assert r.status_code == 403 and "Host" in r.json()["error"], host
        r = s.post("/api/model", json={}, headers={"Origin": "http://evil.example"})
        assert r.status_code == 403 and "Origin" in r.json()["error"]
        assert s.post("/api/model", json={}, headers={"Origin": classroom["origin"]}).status_code == 200


def test_a_push_reaches_the_students_over_server_sent_events(classroom):
    with teacher(classroom) as t, joined(classroom, "127.0.0.4") as a, \
            joined(classroom, "127.0.0.5") as b:
        counts = Events(t)
        assert counts.next("hello")["role"] == "teacher"
        streams = [Events(a), Events(b)]
        for stream in streams:
            assert stream.next("retry") > 0
            assert stream.next("hello")["role"] == "student"
        counts.next("count", until=lambda data: data["students"] >= 2)  # the teacher is told
        r = t.post("/api/class/push", json={"state": "/?s=3&b=10"})
        assert r.status_code == 200 and r.json()["students"] >= 2
        for stream in streams:
            assert stream.next("push")["state"] == "/?s=3&b=10"
        # a student joining later is told the last push in its first event
        with joined(classroom, "127.0.0.6") as late:
            assert Events(late).next("hello")["last_push"] == "/?s=3&b=10"


def test_a_state_sent_back_is_listed_for_the_teacher(classroom):
    with teacher(classroom) as t, joined(classroom, "127.0.0.7") as s:
        listening = Events(t)
        listening.next("hello")
        r = s.post("/api/class/send", json={"state": "/?s=2&l0=i0123", "name": "Ada"},
                   headers={"X-Spectrocolor-Client": "tab-of-ada-01"})
        assert r.status_code == 200
        pushed = listening.next("received")
        assert pushed["name"] == "Ada" and pushed["state"] == "/?s=2&l0=i0123"
        r = s.post("/api/class/send", json={"state": "/?s=4"},
                   headers={"X-Spectrocolor-Client": "tab-of-ada-01"})
        entry = t.get("/api/class/received").json()["received"][-1]
        assert entry["name"] == f"Student {entry['number']}" and entry["state"] == "/?s=4"


def test_the_roles_and_bounds_are_kept(classroom):
    with teacher(classroom) as t, joined(classroom, "127.0.0.8") as s:
        for path, body in [("/api/class/push", {"state": "/"}), ("/api/class/renew", {})]:
            assert s.post(path, json=body).status_code == 403
        assert s.get("/api/class/received").status_code == 403
        assert s.get("/api/class/qr.svg").status_code == 403
        assert t.post("/api/class/send", json={"state": "/"}).status_code == 403
        for state in ("//evil.example/", "http://evil.example/", "javascript:alert(1)",
                      "/?" + "a" * 9000, "/<script>"):
            r = t.post("/api/class/push", json={"state": state})
            assert r.status_code in (413, 422) and set(r.json()) == {"error"}, state
        assert t.post("/api/class/push", json={"state": "/", "extra": 1}).status_code == 422
        assert s.post("/api/class/send", json={"state": "/", "name": "x" * 41}).status_code == 422
        statuses = [s.post("/api/class/send", json={"state": "/"}).status_code for _ in range(6)]
        assert 429 in statuses, statuses  # one state every 2 s, a burst of 3
        svg = t.get("/api/class/qr.svg")
        assert svg.status_code == 200 and svg.headers["content-type"].startswith("image/svg+xml")


def test_a_class_editing_at_once_is_queued_not_refused(classroom):
    """24 students send an edit at the same instant: every one is answered, none gets 429.

    The interactive lane has two workers; in normal mode its line holds 8 jobs and refuses the
    rest at once, which in a class refused a fifth of the edits (bench_server_load.py --only
    classroom). In class mode the line holds a job of each device.
    """
    students = [f"127.0.0.{20 + i}" for i in range(24)]
    barrier = threading.Barrier(len(students))
    statuses: list[int] = []
    body = {"spectra": [[float(k % 31) for k in range(31)], [15.0] * 31], "pairs": [[0, 1]]}

    def edit(address: str) -> None:
        with joined(classroom, address) as s:
            headers = {"X-Spectrocolor-Client": f"tab-{address.replace('.', '-')}"}
            barrier.wait(30)
            statuses.append(s.post("/api/evaluate", json=body, headers=headers).status_code)

    threads = [threading.Thread(target=edit, args=(a,)) for a in students]
    for t in threads:
        t.start()
    for t in threads:
        t.join(120)
    assert sorted(statuses) == [200] * len(students), statuses


def test_renewing_the_code_disconnects_every_student(classroom):
    with teacher(classroom) as t, joined(classroom, "127.0.0.9") as s:
        stream = Events(s)
        stream.next("hello")
        view = t.post("/api/class/renew").json()
        assert view["join_url"] != classroom["join"] and view["code"] in view["join_url"]
        assert stream.ended.wait(10), "the student's stream was not closed"
        assert s.get("/").status_code == 403  # the old code no longer opens anything
        assert s.get("/api/class/events").status_code == 403
        with joined(classroom, "127.0.0.9", view["join_url"]) as again:
            assert again.get("/").status_code == 200
        assert t.get("/").status_code == 200  # the teacher stays
        classroom["join"] = view["join_url"]
