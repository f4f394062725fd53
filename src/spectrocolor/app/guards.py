"""ASGI guards in front of the explorer: who may ask (Host, Origin) and how much (body size).

Both are pure ASGI middleware, so they see every request before FastAPI parses anything:

* :class:`LocalOnly` answers 403 unless the ``Host`` header names this server (127.0.0.1,
  localhost or [::1], with the bound port), which defeats DNS rebinding (a foreign page whose
  name resolves to 127.0.0.1 sends its own name as Host), and unless an ``Origin`` header, when
  present, is this server's own origin (a foreign page's ``fetch`` is refused);
* :class:`BodyLimit` counts the bytes of the body as they arrive, whatever the transfer encoding
  (``Content-Length`` or ``chunked``), answers 413 as soon as the count passes the limit without
  reading the rest, and answers 422 for JSON nested deeper than a limit before any parser
  recurses into it.

Every refusal has the API's one error shape, ``{"error": "..."}``.

References
----------
ASGI specification 3.0, *HTTP connection scope* and *Request - receive event*,
https://asgi.readthedocs.io/en/latest/specs/www.html
RFC 9110, sections 7.2 (Host) and RFC 6454, section 7 (the Origin header).
"""

from __future__ import annotations

import json
import re

import numpy as np

__all__ = ["LOOPBACK_NAMES", "LocalOnly", "BodyLimit", "json_depth", "allowed_hosts"]

#: Names that reach this machine only.
LOOPBACK_NAMES = ("127.0.0.1", "localhost", "[::1]")

_STRING = re.compile(rb'"(?:[^"\\]|\\.)*"', re.DOTALL)


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


def json_depth(data: bytes) -> int:
    """Deepest nesting of arrays/objects in a JSON text (strings skipped), without parsing it.

    Examples
    --------
    >>> json_depth(b'{"a": [[1, 2], "[[[["]}')
    3
    """
    skeleton = np.frombuffer(_STRING.sub(b'""', data), dtype=np.uint8)
    if skeleton.size == 0:
        return 0
    step = (np.isin(skeleton, (ord("["), ord("{"))).astype(np.int64)
            - np.isin(skeleton, (ord("]"), ord("}"))))
    return int(max(np.cumsum(step).max(), 0))


class BodyLimit:
    """Read at most ``max_bytes`` of any request body (413 beyond) and JSON at most ``max_depth`` deep.

    The body is collected here, counted chunk by chunk as the server receives it, and handed on
    whole to the application; a body over the limit is refused at the first chunk that passes
    it, and the connection is closed without reading the rest.
    """

    def __init__(self, app, max_bytes: int, max_depth: int):
        self.app, self.max_bytes, self.max_depth = app, max_bytes, max_depth

    async def __call__(self, scope, receive, send):
        if scope["type"] != "http":
            return await self.app(scope, receive, send)
        too_large = f"request body larger than {self.max_bytes} bytes"
        headers = {k.lower(): v for k, v in scope.get("headers", ())}
        length = headers.get(b"content-length")
        if length is not None and (not length.isdigit() or int(length) > self.max_bytes):
            return await send_error(send, 413, too_large)
        chunks, size = [], 0
        while True:
            message = await receive()
            if message["type"] == "http.disconnect":
                return
            chunk = message.get("body", b"")
            size += len(chunk)
            if size > self.max_bytes:
                return await send_error(send, 413, too_large)
            chunks.append(chunk)
            if not message.get("more_body", False):
                break
        body = b"".join(chunks)
        if body and json_depth(body) > self.max_depth:
            return await send_error(send, 422, f"JSON nested deeper than {self.max_depth} levels")
        delivered = False

        async def replay():
            nonlocal delivered
            if not delivered:
                delivered = True
                return {"type": "http.request", "body": body, "more_body": False}
            return await receive()

        return await self.app(scope, replay, send)
