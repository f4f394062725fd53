"""ASGI guards in front of the explorer: who may ask (Host, Origin) and how much (body size).

Both are pure ASGI middleware, so they see every request before FastAPI parses anything:

* :class:`LocalOnly` answers 403 unless the ``Host`` header names this server (127.0.0.1,
  localhost or [::1], with the bound port), which defeats DNS rebinding (a foreign page whose
  name resolves to 127.0.0.1 sends its own name as Host), and unless an ``Origin`` header, when
  present, is this server's own origin (a foreign page's ``fetch`` is refused);
* :class:`BodyLimit` counts the bytes of the body as they arrive, whatever the transfer encoding
  (``Content-Length`` or ``chunked``), answers 413 as soon as the count passes the limit without
  reading the rest, 408 for a body that does not arrive within a time limit, and 422 for JSON
  nested deeper than a limit before any parser recurses into it. Its nesting scan
  (:class:`JSONDepthScanner`) is linear and runs chunk by chunk as the body arrives, so no body
  can make the event loop work for long.

Every refusal has the API's one error shape, ``{"error": "..."}``.

References
----------
ASGI specification 3.0, *HTTP connection scope* and *Request - receive event*,
https://asgi.readthedocs.io/en/latest/specs/www.html
RFC 9110, sections 7.2 (Host) and RFC 6454, section 7 (the Origin header).
"""

from __future__ import annotations

import asyncio
import json

import numpy as np

from .workers import LOOPBACK_ADDRESSES  # the addresses without a per-address cap

__all__ = ["LOOPBACK_NAMES", "LOOPBACK_ADDRESSES", "LocalOnly", "BodyLimit", "JSONDepthScanner",
           "json_depth", "allowed_hosts", "BODY_TIMEOUT_S", "CLIENT_HEADER", "client_key"]

#: Names that reach this machine only.
LOOPBACK_NAMES = ("127.0.0.1", "localhost", "[::1]")
#: The header in which each explorer tab sends the random token it made (sessionStorage).
CLIENT_HEADER = "X-Spectrocolor-Client"
_TOKEN_CHARACTERS = frozenset("ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789-_")
#: Longest time a request body may take to arrive, s (then 408): a client that trickles its
#: body cannot hold a connection and its memory for ever.
BODY_TIMEOUT_S = 30.0


async def send_error(send, status: int, message: str) -> None:
    """Send a complete JSON response ``{"error": message}`` with ``status``."""
    body = json.dumps({"error": message}).encode("utf-8")
    await send({"type": "http.response.start", "status": status,
                "headers": [(b"content-type", b"application/json"),
                            (b"content-length", str(len(body)).encode("ascii")),
                            (b"connection", b"close")]})
    await send({"type": "http.response.body", "body": body})


def allowed_hosts(port: int | None) -> frozenset[str] | None:
    """The ``Host`` header values a loopback server on ``port`` answers (None: any port).

    Examples
    --------
    >>> sorted(allowed_hosts(8765))
    ['127.0.0.1:8765', '[::1]:8765', 'localhost:8765']
    """
    if port is None:
        return None
    return frozenset(f"{name}:{port}" for name in LOOPBACK_NAMES)


def client_key(scope) -> tuple[str | None, str | None]:
    """The worker pools' client key of a request: ``(address, token)``.

    ``token`` is the value of :data:`CLIENT_HEADER` when it is 8 to 64 letters, digits, ``-``
    or ``_`` (each explorer tab makes one at random), else None: requests without a token share
    one client per address, as all requests of an address did before tokens.

    Parameters
    ----------
    scope : mapping or Request
        The ASGI scope (a Starlette ``Request`` is one).

    Examples
    --------
    >>> client_key({"client": ("127.0.0.1", 5000),
    ...             "headers": [(b"x-spectrocolor-client", b"k3Jd9-aZ01")]})
    ('127.0.0.1', 'k3Jd9-aZ01')
    >>> client_key({"client": None, "headers": [(b"x-spectrocolor-client", b"no spaces")]})
    (None, None)
    """
    client = scope.get("client")
    address = client[0] if client else None
    wanted = CLIENT_HEADER.lower().encode("latin-1")
    token = next((value for name, value in scope.get("headers", ()) if name.lower() == wanted),
                 None)
    if token is not None:
        text = token.decode("latin-1")
        token = text if 8 <= len(text) <= 64 and set(text) <= _TOKEN_CHARACTERS else None
    return address, token


def _host_ok(host: str, allowed: frozenset[str] | None) -> bool:
    host = host.lower()
    if allowed is not None:
        return host in allowed
    name = host[: host.find("]") + 1] if host.startswith("[") else host.split(":", 1)[0]
    return name in LOOPBACK_NAMES


class LocalOnly:
    """Refuse (403) requests whose Host is not this loopback server or whose Origin is foreign.

    Parameters
    ----------
    app : ASGI application
    hosts : frozenset of str or None
        Exact ``Host`` values accepted (from :func:`allowed_hosts`); None accepts the loopback
        names with any port.
    check_host : bool
        False when the user chose to serve other machines (``--allow-remote``): any Host is
        answered, and Origin must still equal ``http://`` + that Host.
    """

    def __init__(self, app, hosts: frozenset[str] | None = None, check_host: bool = True):
        self.app, self.hosts, self.check_host = app, hosts, check_host

    async def __call__(self, scope, receive, send):
        if scope["type"] != "http":
            return await self.app(scope, receive, send)
        headers = {k.lower(): v for k, v in scope.get("headers", ())}
        host = headers.get(b"host", b"").decode("latin-1")
        if self.check_host and not _host_ok(host, self.hosts):
            expected = ", ".join(sorted(self.hosts)) if self.hosts else ", ".join(LOOPBACK_NAMES)
            return await send_error(send, 403, f"Host {host[:80]!r} is not this server (expected "
                                    f"{expected}); requests under other names are refused")
        origin = headers.get(b"origin")
        if origin is not None and origin.decode("latin-1").lower() != f"http://{host.lower()}":
            return await send_error(send, 403, f"Origin {origin.decode('latin-1')[:80]!r} is not "
                                    "this page; the API answers its own page only")
        return await self.app(scope, receive, send)


class JSONDepthScanner:
    """Deepest nesting of arrays/objects in a JSON text fed in pieces, in one linear pass.

    Each piece is scanned once, with NumPy, whatever it holds: the state carried from one piece
    to the next is four numbers (inside a string or not, an odd run of backslashes at the end,
    the current depth, the deepest so far), so a body arriving in chunks is scanned as it
    arrives and no piece is ever looked at twice. (A regular expression that skipped strings
    took quadratic time on an unterminated string of escaped quotes: a 40 kB body froze the
    server for 10 s.)

    The count agrees with a JSON parser on valid JSON. On invalid JSON it is an upper bound of
    the depth a parser reaches before it stops at the first error: up to that error the two
    read the text alike (a backslash outside a string is such an error).

    Examples
    --------
    >>> scanner = JSONDepthScanner()
    >>> scanner.feed(b'{"a": [[1, 2], "[[')
    3
    >>> scanner.feed(b'[[\\"]"]}')  # the string goes on in the second piece
    3
    """

    def __init__(self) -> None:
        self.depth = 0
        self.deepest = 0
        self.in_string = False
        self.odd_backslashes = False

    def feed(self, piece: bytes | memoryview) -> int:
        """Scan the next piece of the text; returns the deepest nesting seen so far."""
        if not piece:
            return self.deepest
        piece = bytes(piece)
        data = np.frombuffer((b"\\" if self.odd_backslashes else b"") + piece, dtype=np.uint8)
        if self.odd_backslashes or b"\\" in piece:
            index = np.arange(data.size, dtype=np.int32)
            # index of the last byte that is not a backslash, at or before each position
            last_other = np.maximum.accumulate(np.where(data == _BACKSLASH, -1, index))
            escaped = np.zeros(data.size, dtype=bool)  # preceded by an odd run of backslashes
            escaped[1:] = ((index[:-1] - last_other[:-1]) & 1).astype(bool)
            delimiters = (data == _QUOTE) & ~escaped
            self.odd_backslashes = bool((data.size - 1 - int(last_other[-1])) & 1)
        else:  # no backslash: every quote delimits a string (the common case, half the work)
            delimiters = data == _QUOTE
        steps = ((data == _OPEN_ARRAY) | (data == _OPEN_OBJECT)).astype(np.int8)
        steps -= (data == _CLOSE_ARRAY) | (data == _CLOSE_OBJECT)
        if self.in_string or b'"' in piece:
            quotes = np.cumsum(delimiters, dtype=np.int32)
            steps[(quotes + self.in_string) & 1 == 1] = 0  # inside a string: not a bracket
            self.in_string = bool((int(quotes[-1]) + self.in_string) & 1)
        levels = np.cumsum(steps, dtype=np.int32)
        self.deepest = max(self.deepest, self.depth + int(levels.max()))
        self.depth += int(levels[-1])
        return self.deepest


_QUOTE, _BACKSLASH = ord('"'), ord("\\")
_OPEN_ARRAY, _CLOSE_ARRAY, _OPEN_OBJECT, _CLOSE_OBJECT = (ord(c) for c in "[]{}")
#: Largest piece scanned at once, bytes: a long text is scanned in pieces so that the scan's
#: temporary arrays stay small (about 20 bytes per byte scanned) and each step is short.
SCAN_PIECE_BYTES = 1 << 14


#: Deepest JSON nesting accepted in a body or an imported file (the API needs 3).
MAX_JSON_DEPTH = 32


def json_depth(data: bytes) -> int:
    """Deepest nesting of arrays/objects in a JSON text (strings skipped), without parsing it.

    Linear in the length of ``data`` (see :class:`JSONDepthScanner`), which it reads in pieces
    of :data:`SCAN_PIECE_BYTES`.

    Examples
    --------
    >>> json_depth(b'{"a": [[1, 2], "[[[["]}')
    3
    >>> json_depth(b'"' + b'\\"' * 5)  # an unterminated string of escaped quotes
    0
    """
    return _scan(JSONDepthScanner(), data)


class BodyLimit:
    """Read at most ``max_bytes`` of any request body (413 beyond) and JSON at most ``max_depth`` deep.

    The body is collected here, counted chunk by chunk as the server receives it, and handed on
    whole to the application; a body over the limit is refused at the first chunk that passes
    it, and the connection is closed without reading the rest. Each chunk's JSON nesting is
    scanned as it arrives (:class:`JSONDepthScanner`, linear), one piece of
    :data:`SCAN_PIECE_BYTES` at a time with other requests served between pieces, so the event
    loop never does work that grows faster than the body, nor more than a few milliseconds
    of it at once; a
    complete body nested deeper than ``max_depth`` is refused (422). A body that takes longer
    than ``timeout_s`` to arrive is refused (408).

    ``path_limits`` gives smaller limits to the routes whose bodies are small (``{path: bytes}``,
    exact paths): FastAPI decodes the JSON of those routes in the event loop, and the limit
    bounds that work to a fraction of a millisecond.
    """

    def __init__(self, app, max_bytes: int, max_depth: int, timeout_s: float = BODY_TIMEOUT_S,
                 path_limits: dict[str, int] | None = None):
        self.app, self.max_bytes, self.max_depth = app, max_bytes, max_depth
        self.timeout_s = timeout_s
        self.path_limits = dict(path_limits or {})

    async def __call__(self, scope, receive, send):
        if scope["type"] != "http":
            return await self.app(scope, receive, send)
        max_bytes = min(self.max_bytes, self.path_limits.get(scope.get("path", ""), self.max_bytes))
        too_large = f"request body larger than {max_bytes} bytes"
        too_deep = f"JSON nested deeper than {self.max_depth} levels"
        headers = {k.lower(): v for k, v in scope.get("headers", ())}
        length = headers.get(b"content-length")
        if length is not None and (not length.isdigit() or int(length) > max_bytes):
            return await send_error(send, 413, too_large)
        chunks, size, scanner = [], 0, JSONDepthScanner()
        deadline = asyncio.get_running_loop().time() + self.timeout_s
        while True:
            try:
                async with asyncio.timeout_at(deadline):
                    message = await receive()
            except TimeoutError:
                return await send_error(send, 408, f"request body not received within "
                                        f"{self.timeout_s:g} s; send it at once")
            if message["type"] == "http.disconnect":
                return
            chunk = message.get("body", b"")
            size += len(chunk)
            if size > max_bytes:
                return await send_error(send, 413, too_large)
            chunks.append(chunk)
            await _scan_yielding(scanner, chunk)
            if not message.get("more_body", False):
                break
        if scanner.deepest > self.max_depth:  # after the whole body: a body too large is a 413
            return await send_error(send, 422, too_deep)
        body = b"".join(chunks)
        delivered = False

        async def replay():
            nonlocal delivered
            if not delivered:
                delivered = True
                return {"type": "http.request", "body": body, "more_body": False}
            return await receive()

        return await self.app(scope, replay, send)


async def _scan_yielding(scanner: JSONDepthScanner, chunk: bytes) -> None:
    """Feed ``chunk`` to ``scanner`` one piece at a time, letting other requests run between."""
    view = memoryview(chunk)
    for start in range(0, len(view), SCAN_PIECE_BYTES):
        if start:
            await asyncio.sleep(0)
        scanner.feed(view[start:start + SCAN_PIECE_BYTES])


def _scan(scanner: JSONDepthScanner, chunk: bytes) -> int:
    """Feed ``chunk`` to ``scanner`` in pieces of at most :data:`SCAN_PIECE_BYTES`."""
    view = memoryview(chunk)
    for start in range(0, len(view), SCAN_PIECE_BYTES):
        scanner.feed(view[start:start + SCAN_PIECE_BYTES])
    return scanner.deepest
