"""Classroom mode: one teacher's explorer, joined by a class from phones and tablets (issue 30).

``spectrocolor app --classroom`` serves the explorer on the machine's local-network address.
Students join with a random **join code** (in the join address and its QR code); the teacher is
recognised by a separate **teacher key**, printed only in the teacher's terminal. This module
holds the class's state (:class:`Classroom`), its guard (:class:`ClassroomGuard`, inside
:class:`spectrocolor.app.guards.LocalOnly`, which checks that Host and Origin are the announced
address), and its routes under ``/api/class`` (:data:`router`):

* ``GET /join?code=...`` sets the join cookie and sends the student to the page;
  ``GET /teacher?key=...`` does the same for the teacher;
* ``GET /api/class/whoami``: the role, and for the teacher the join address, its QR code (SVG),
  the number connected and what the class mode exposes;
* ``GET /api/class/events``: the Server-Sent Events stream (``retry:`` field, heartbeats every
  :data:`HEARTBEAT_S`); students receive ``push`` events, the teacher ``count`` and
  ``received`` events; the browser's ``EventSource`` reconnects by itself;
* ``POST /api/class/push`` (teacher): the teacher's URL state to every student;
* ``POST /api/class/send`` (student): a student's URL state to the teacher;
* ``GET /api/class/received`` (teacher): the states received, newest last;
* ``POST /api/class/renew`` (teacher): a new join code; every student is disconnected.

Everything is bounded: students (:data:`MAX_STUDENTS`, :data:`MAX_STREAMS_PER_ADDRESS`),
states kept (:data:`MAX_RECEIVED`), a state's length (:data:`MAX_STATE_CHARS`, checked before
it is kept or sent), events waiting per stream (:data:`STREAM_QUEUE`), and requests per student
address (:class:`RateLimit`). Nothing is written to disk: the class lives in this process's
memory and ends with it.

Why this file is long: the class's state, its guard and its routes share the same secrets, limits
and role rules; kept together, the whole of what class mode exposes can be reviewed in one place.

References
----------
WHATWG HTML Living Standard, section 9.2, *Server-sent events* (the ``text/event-stream``
format, ``retry:``, comments as heartbeats), https://html.spec.whatwg.org/multipage/server-sent-events.html
RFC 6265, section 4.1 (Set-Cookie: HttpOnly, SameSite).
"""

from __future__ import annotations

import asyncio
import collections
import io
import json
import re
import secrets
import socket
import time
from http.cookies import SimpleCookie
from typing import Annotated
from urllib.parse import parse_qs

from fastapi import APIRouter, Request
from fastapi.responses import JSONResponse, Response, StreamingResponse
from pydantic import Field

from .guards import send_error
from .request_models import StrictRequest

__all__ = ["Classroom", "ClassroomGuard", "RateLimit", "router", "lan_address", "join_code",
           "valid_state", "qr_svg", "qr_terminal", "EXPOSURE", "MAX_STUDENTS", "MAX_RECEIVED",
           "MAX_STATE_CHARS", "CLASS_BODY_BYTES", "HEARTBEAT_S", "TEACHER_ADDRESS", "JOIN_COOKIE", "TEACHER_COOKIE",
           "ROLE_COOKIE"]

#: Most students connected at once (open event streams); beyond, 429.
MAX_STUDENTS = 60
#: Most event streams of one address (a student with several tabs).
MAX_STREAMS_PER_ADDRESS = 4
#: Most received states kept for the teacher (the oldest go first).
MAX_RECEIVED = 100
#: Longest URL state, characters (three distributions of 301 bins written as numbers fit).
MAX_STATE_CHARS = 8192
#: Longest name a student may give, characters.
MAX_NAME_CHARS = 40
#: Body limit of the class's POST routes, bytes.
CLASS_BODY_BYTES = 2 * MAX_STATE_CHARS + 1024
#: Seconds between heartbeats on an idle stream, and the reconnection delay sent (``retry:``).
HEARTBEAT_S, RETRY_MS = 15.0, 3000
#: Events waiting for a slow stream; a stream that falls this far behind is closed (it reconnects).
STREAM_QUEUE = 16
#: Requests per second per student address, and the burst allowed above it.
REQUESTS_PER_S, REQUEST_BURST = 20.0, 120.0
#: States a student may send: one per this many seconds, with a burst of SEND_BURST.
SEND_INTERVAL_S, SEND_BURST = 2.0, 3.0
#: The client address that the teacher's requests carry (the worker pools exempt it alone).
TEACHER_ADDRESS = "classroom-teacher"
JOIN_COOKIE, TEACHER_COOKIE = "spectrocolor-class", "spectrocolor-teacher"
#: A cookie without any secret that tells the page's script which role it has (the two above
#: are HttpOnly: the page cannot read them).
ROLE_COOKIE = "spectrocolor-role"
#: The join code's letters: no 0/O, 1/I/L, so that a code read aloud or copied is unambiguous.
CODE_ALPHABET = "23456789ABCDEFGHJKMNPQRSTUVWXYZ"
CODE_LENGTH = 10  # about 50 bits
#: What the class mode exposes, shown on the teacher's page.
EXPOSURE = ("Class mode serves this explorer to the devices of this local network that have the "
            "join code; nothing leaves the local network. No data is stored: the states students "
            "send are kept in this program's memory only (the last 100) and are gone when it "
            "stops. Students see what the teacher pushes; the teacher sees only what students "
            "send. Renewing the code disconnects everyone.")

# A URL state the page made: a path on this server, then its query, then its fragment (where the
# lab pages keep their state). No scheme, no host, no
# "//" at the start (which a browser reads as another host), no backslash, no space.
_STATE_RE = re.compile(r"^/(?![/\\])[A-Za-z0-9/._~%-]*(\?[A-Za-z0-9._~%!$&'()*+,;=:@/?-]*)?"
                       r"(#[A-Za-z0-9._~%!$&'()*+,;=:@/?-]*)?$")
_NAME_RE = re.compile(r"^[^\x00-\x1f\x7f-\x9f\u2028\u2029<>]*$")


def join_code() -> str:
    """A new random join code (:data:`CODE_LENGTH` letters of :data:`CODE_ALPHABET`).

    Examples
    --------
    >>> code = join_code()
    >>> len(code), set(code) <= set(CODE_ALPHABET)
    (10, True)
    """
    return "".join(secrets.choice(CODE_ALPHABET) for _ in range(CODE_LENGTH))


def valid_state(state: str) -> bool:
    """Whether ``state`` is a URL state of this server's pages (a path and query, bounded).

    Examples
    --------
    >>> valid_state("/?s=2&b=10&l0=i0123"), valid_state("/labs/solid#light=D65&sample=9&mismatch=1")
    (True, True)
    >>> valid_state("//evil.example/"), valid_state("javascript:alert(1)"), valid_state("/" * 9000)
    (False, False, False)
    """
    return len(state) <= MAX_STATE_CHARS and _STATE_RE.match(state) is not None


def lan_address() -> str | None:
    """This machine's address on its local network (the one its default route uses), or None.

    No packet is sent: connecting a UDP socket only chooses the route and the source address.

    Examples
    --------
    >>> address = lan_address()
    >>> address is None or address.count(".") == 3
    True
    """
    with socket.socket(socket.AF_INET, socket.SOCK_DGRAM) as probe:
        try:
            probe.connect(("192.0.2.1", 9))  # TEST-NET-1 (RFC 5737): never answered, never sent
            address = probe.getsockname()[0]
        except OSError:
            return None
    return None if address.startswith(("0.", "127.")) else address


def qr_svg(text: str) -> str:
    """The QR code of ``text`` as an SVG document (segno, error correction M).

    Examples
    --------
    >>> qr_svg("http://192.168.1.20:8765/join?code=ABCDEFGH23").startswith("<?xml")
    True
    """
    import segno

    out = io.BytesIO()
    segno.make(text, error="m").save(out, kind="svg", scale=6, border=4, dark="#000",
                                      light="#fff", title="join address")
    return out.getvalue().decode("utf-8")


def qr_terminal(text: str) -> str:
    """The QR code of ``text`` drawn with half-block characters, for a terminal.

    Examples
    --------
    >>> lines = qr_terminal("http://192.168.1.20:8765/join?code=ABCDEFGH23").splitlines()
    >>> len(lines) > 10
    True
    """
    import segno

    out = io.StringIO()
    segno.make(text, error="m").terminal(out=out, compact=True, border=2)
    return out.getvalue()


class RateLimit:
    """Token buckets per key (``rate`` per second, ``burst`` at most), for at most ``max_keys`` keys.

    Examples
    --------
    >>> limit = RateLimit(rate=1.0, burst=2.0)
    >>> [limit.allow("a", now=0.0) for _ in range(3)], limit.allow("a", now=1.0)
    ([True, True, False], True)
    """

    def __init__(self, rate: float, burst: float, max_keys: int = 1024):
        self.rate, self.burst, self.max_keys = rate, burst, max_keys
        self._buckets: collections.OrderedDict = collections.OrderedDict()

    def allow(self, key, now: float | None = None) -> bool:
        """Take one token of ``key``'s bucket; False when it is empty."""
        now = time.monotonic() if now is None else now
        tokens, last = self._buckets.pop(key, (self.burst, now))
        tokens = min(self.burst, tokens + (now - last) * self.rate)
        allowed = tokens >= 1.0
        self._buckets[key] = (tokens - 1.0 if allowed else tokens, now)
        while len(self._buckets) > self.max_keys:  # the least recently used goes
            self._buckets.popitem(last=False)
        return allowed


class _Stream:
    """One open event stream: its queue of encoded events and who holds it."""

    def __init__(self, role: str, address: str | None):
        self.role, self.address = role, address
        self.queue: asyncio.Queue = asyncio.Queue(STREAM_QUEUE)
        self.closed = False

    def offer(self, event: bytes | None) -> None:
        """Queue an event (None closes); a stream too far behind is closed instead."""
        if self.closed:
            return
        try:
            self.queue.put_nowait(event)
        except asyncio.QueueFull:
            self.closed = True
        if event is None:
            self.closed = True


def _event(name: str, data) -> bytes:
    return f"event: {name}\ndata: {json.dumps(data, separators=(',', ':'))}\n\n".encode()


class Classroom:
    """The state of one class: its codes, its open streams and the states students sent.

    Parameters
    ----------
    host : str
        The announced address (the one students reach, as in their Host header).
    port : int
        The bound port.

    Examples
    --------
    >>> c = Classroom("192.168.1.20", 8765)
    >>> c.join_url().startswith("http://192.168.1.20:8765/join?code=")
    True
    >>> c.role_of({"cookie": f"{JOIN_COOKIE}={c.code}"}), c.role_of({})
    ('student', None)
    """

    def __init__(self, host: str, port: int):
        self.host, self.port = host, port
        self.code = join_code()
        self.teacher_key = secrets.token_urlsafe(24)
        self.streams: set[_Stream] = set()
        self.received: collections.deque = collections.deque(maxlen=MAX_RECEIVED)
        self.numbers: collections.OrderedDict = collections.OrderedDict()  # tab token -> number
        self.next_number = 1
        self.last_push: str | None = None
        self.requests = RateLimit(REQUESTS_PER_S, REQUEST_BURST)
        self.sends = RateLimit(1.0 / SEND_INTERVAL_S, SEND_BURST)

    @property
    def origin(self) -> str:
        """``http://host:port``, the one origin the class answers."""
        shown = f"[{self.host}]" if ":" in self.host else self.host
        return f"http://{shown}:{self.port}"

    def join_url(self) -> str:
        """The address students open (it holds the join code)."""
        return f"{self.origin}/join?code={self.code}"

    def teacher_url(self) -> str:
        """The address the teacher opens (it holds the teacher key: keep it private)."""
        return f"{self.origin}/teacher?key={self.teacher_key}"

    def role_of(self, cookies: dict[str, str]) -> str | None:
        """``'teacher'``, ``'student'`` or None, from a request's cookies ``{name: value}``
        (or ``{"cookie": header}``)."""
        if "cookie" in cookies:
            cookies = _cookies(cookies["cookie"])
        if secrets.compare_digest(cookies.get(TEACHER_COOKIE, "").encode(),
                                  self.teacher_key.encode()):
            return "teacher"
        if secrets.compare_digest(cookies.get(JOIN_COOKIE, "").encode(), self.code.encode()):
            return "student"
        return None

    def students(self) -> int:
        """Students connected now (their open streams)."""
        return sum(1 for s in self.streams if s.role == "student" and not s.closed)

    def number_of(self, token: str | None, address: str | None) -> int:
        """The anonymous number of a student's tab (kept for :data:`MAX_RECEIVED` tabs)."""
        key = token or address or "?"
        if key not in self.numbers:
            self.numbers[key] = self.next_number
            self.next_number += 1
            while len(self.numbers) > 4 * MAX_STUDENTS:
                self.numbers.popitem(last=False)
        return self.numbers[key]

    def broadcast(self, role: str, event: bytes | None) -> int:
        """Queue ``event`` on every open stream of ``role``; the number of streams reached."""
        reached = 0
        for stream in list(self.streams):
            if stream.role == role and not stream.closed:
                stream.offer(event)
                reached += 1
        return reached

    def counted(self) -> None:
        """Tell the teacher how many students are connected."""
        self.broadcast("teacher", _event("count", {"students": self.students()}))

    def renew(self) -> str:
        """A new join code; every student's stream is closed and their cookie stops working."""
        self.code = join_code()
        self.last_push = None
        self.broadcast("student", None)
        self.streams = {s for s in self.streams if s.role != "student"}
        self.counted()
        return self.code

    def close(self) -> None:
        """End every stream (the class ends): each answer completes instead of being cut off."""
        for stream in list(self.streams):
            stream.offer(None)
        self.streams.clear()

    def teacher_view(self) -> dict:
        """What the teacher's page shows about the class."""
        url = self.join_url()
        return {"role": "teacher", "join_url": url, "code": self.code, "qr_svg": qr_svg(url),
                "students": self.students(), "exposure": EXPOSURE,
                "max_students": MAX_STUDENTS, "max_received": MAX_RECEIVED}


def _cookies(header: str) -> dict[str, str]:
    jar: SimpleCookie = SimpleCookie()
    try:
        jar.load(header[:4096])
    except Exception:  # a malformed cookie header: no cookies  # noqa: BLE001
        return {}
    return {name: morsel.value for name, morsel in jar.items()}


def _set_cookie(name: str, value: str, http_only: bool = True) -> tuple[bytes, bytes]:
    flags = "; HttpOnly" if http_only else ""
    return (b"set-cookie", f"{name}={value}; Path=/; SameSite=Lax{flags}".encode("latin-1"))


async def _redirect(send, cookies: list[tuple[bytes, bytes]]) -> None:
    await send({"type": "http.response.start", "status": 303,
                "headers": [(b"location", b"/"), (b"content-length", b"0"),
                            (b"cache-control", b"no-store"), *cookies]})
    await send({"type": "http.response.body", "body": b""})


class ClassroomGuard:
    """Answer only the class: the join code (or teacher key) in a cookie, or ``/join?code=``.

    Mounted inside :class:`spectrocolor.app.guards.LocalOnly` (which answers only the announced
    Host and Origin). A request without the current code or key gets 403 and nothing else;
    ``/join`` with the right code (``/teacher`` with the key) sets the cookie and redirects to
    the page. The teacher's requests carry :data:`TEACHER_ADDRESS` as their client address, so
    the worker pools exempt the teacher alone from their per-address cap; each student address
    is rate-limited (:data:`REQUESTS_PER_S`, burst :data:`REQUEST_BURST`; 429 beyond).
    """

    def __init__(self, app, classroom: Classroom):
        self.app, self.classroom = app, classroom

    async def __call__(self, scope, receive, send):
        if scope["type"] != "http":
            return await self.app(scope, receive, send)
        c = self.classroom
        path = scope.get("path", "")
        if path in ("/join", "/teacher") and scope.get("method") == "GET":
            query = parse_qs(scope.get("query_string", b"")[:512].decode("latin-1"))
            given = (query.get("code" if path == "/join" else "key") or [""])[0]
            secret = c.code if path == "/join" else c.teacher_key
            if secrets.compare_digest(given.encode("utf-8", "replace"), secret.encode()):
                joining = "student" if path == "/join" else "teacher"
                cookie = JOIN_COOKIE if path == "/join" else TEACHER_COOKIE
                return await _redirect(send, [_set_cookie(cookie, secret),
                                              _set_cookie(ROLE_COOKIE, joining, http_only=False)])
        headers = {k.lower(): v for k, v in scope.get("headers", ())}
        role = c.role_of(_cookies(headers.get(b"cookie", b"").decode("latin-1")))
        client = scope.get("client")
        address = client[0] if client else None
        if role is None:
            return await send_error(send, 403, "this class needs its join code: open the join "
                                    "address or scan the QR code the teacher shows (a renewed "
                                    "code replaces the old one)")
        if role == "student" and not c.requests.allow(address):
            return await send_error(send, 429, "too many requests from this device; slow down")
        scope = dict(scope)
        scope["spectrocolor.classroom"] = c
        scope["spectrocolor.role"] = role
        if role == "teacher":
            scope["client"] = (TEACHER_ADDRESS, client[1] if client else 0)
        return await self.app(scope, receive, send)


def exempt_teacher_only(pools) -> None:
    """Give the worker pools' per-address exemption to the teacher alone (not to loopback)."""
    for pool in pools:
        pool.unlimited_addresses = frozenset({TEACHER_ADDRESS})


#: The class's routes; :func:`spectrocolor.app.server.create_app` includes them in class mode.
router = APIRouter()


def _class(request: Request) -> tuple[Classroom, str]:
    return request.scope["spectrocolor.classroom"], request.scope["spectrocolor.role"]


def _refuse(status: int, message: str) -> JSONResponse:
    return JSONResponse({"error": message}, status_code=status)


class PushRequest(StrictRequest):
    """The teacher's URL state."""

    state: Annotated[str, Field(min_length=1, max_length=MAX_STATE_CHARS)]


class SendRequest(PushRequest):
    """A student's URL state and the name they chose (empty: anonymous)."""

    name: Annotated[str, Field(max_length=MAX_NAME_CHARS, pattern=_NAME_RE.pattern)] = ""


@router.get("/api/class/whoami")
def whoami(request: Request):
    """The role of this page, and for the teacher the class's address, QR code and figures."""
    c, role = _class(request)
    if role == "teacher":
        return c.teacher_view()
    return {"role": "student", "students": c.students(), "last_push": c.last_push}


@router.get("/api/class/qr.svg")
def qr(request: Request):
    """The QR code of the join address (teacher only)."""
    c, role = _class(request)
    if role != "teacher":
        return _refuse(403, "only the teacher's page shows the join code")
    return Response(qr_svg(c.join_url()), media_type="image/svg+xml",
                    headers={"cache-control": "no-store"})


@router.get("/api/class/events")
async def events(request: Request):
    """The class's Server-Sent Events stream for this page."""
    c, role = _class(request)
    client = request.scope.get("client")
    address = client[0] if client else None
    if role == "student":
        if c.students() >= MAX_STUDENTS:
            return _refuse(429, f"the class is full ({MAX_STUDENTS} connected)")
        mine = sum(1 for s in c.streams if s.address == address and not s.closed)
        if mine >= MAX_STREAMS_PER_ADDRESS:
            return _refuse(429, f"at most {MAX_STREAMS_PER_ADDRESS} pages per device")
    stream = _Stream(role, address)
    c.streams.add(stream)
    c.counted()
    first = {"role": role, "students": c.students()}
    if role == "student" and c.last_push:
        first["last_push"] = c.last_push

    async def body():
        try:
            yield f"retry: {RETRY_MS}\n\n".encode("ascii") + _event("hello", first)
            while not stream.closed or not stream.queue.empty():
                try:
                    event = await asyncio.wait_for(stream.queue.get(), HEARTBEAT_S)
                except TimeoutError:
                    yield b": heartbeat\n\n"
                    continue
                if event is None:
                    break
                yield event
        finally:
            stream.closed = True
            c.streams.discard(stream)
            c.counted()

    return StreamingResponse(body(), media_type="text/event-stream",
                             headers={"cache-control": "no-store", "x-accel-buffering": "no"})


@router.post("/api/class/push")
def push(request: Request, req: PushRequest):
    """The teacher's URL state to every student's page."""
    c, role = _class(request)
    if role != "teacher":
        return _refuse(403, "only the teacher can push to the class")
    if not valid_state(req.state):
        return _refuse(422, "state: not a URL state of this explorer's pages")
    c.last_push = req.state
    reached = c.broadcast("student", _event("push", {"state": req.state, "at": time.time()}))
    return {"students": reached}


@router.post("/api/class/send")
def send_back(request: Request, req: SendRequest):
    """A student's URL state to the teacher's list."""
    c, role = _class(request)
    if role != "student":
        return _refuse(403, "only students send states to the teacher")
    if not valid_state(req.state):
        return _refuse(422, "state: not a URL state of this explorer's pages")
    client = request.scope.get("client")
    address = client[0] if client else None
    if not c.sends.allow(address):
        return _refuse(429, f"one state every {SEND_INTERVAL_S:g} s; try again in a moment")
    token = request.headers.get("x-spectrocolor-client")
    number = c.number_of(token[:64] if token else None, address)
    entry = {"name": req.name.strip() or f"Student {number}", "number": number,
             "state": req.state, "at": time.time()}
    c.received.append(entry)
    c.broadcast("teacher", _event("received", entry))
    return {"ok": True}


@router.get("/api/class/received")
def received(request: Request):
    """The states students sent, oldest first (teacher only)."""
    c, role = _class(request)
    if role != "teacher":
        return _refuse(403, "only the teacher sees the states students sent")
    return {"received": list(c.received)}


@router.post("/api/class/renew")
def renew(request: Request):
    """A new join code (teacher only): every student is disconnected and must join again."""
    c, role = _class(request)
    if role != "teacher":
        return _refuse(403, "only the teacher can renew the join code")
    c.renew()
    return c.teacher_view()
