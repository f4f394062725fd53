"""The explorer's HTTP/1.1 protocol: uvicorn's h11 protocol, with its 400 in the API's error shape.

A request that is not HTTP at all -- a garbage request line, a bad chunk size, an empty or
repeated ``Host``, a header without a colon -- is refused by the h11 parser before any ASGI
application sees it, so neither FastAPI nor :mod:`spectrocolor.app.guards` can answer it. uvicorn
answers such requests itself with a plain-text ``400``; this subclass of its h11 protocol sends
the same status with the body every other answer of the explorer has, ``{"error": "..."}``
(``Content-Type: application/json``), then closes the connection as uvicorn does. It is passed
to uvicorn as ``uvicorn.Config(..., http=JSONErrorH11Protocol)`` (uvicorn accepts a protocol
class there).

References
----------
RFC 9112 (HTTP/1.1), sections 3 (request line), 7.1 (chunked coding); RFC 9110, section 15.5.1
(400 Bad Request). uvicorn settings, ``--http``: https://www.uvicorn.org/settings/
"""

from __future__ import annotations

import asyncio
import json

import h11
from uvicorn.protocols.http.h11_impl import H11Protocol

__all__ = ["JSONErrorH11Protocol", "bad_request_body", "connection_cap", "ACCEPT_BACKLOG",
           "HEAD_TIMEOUT_S"]

#: Connections accepted in one turn of the event loop (``uvicorn.Config(backlog=...)``, which
#: asyncio also uses as the listen queue). asyncio accepts that many before any of them is
#: seen by the protocol, so the connection cap can only act between turns: uvicorn's default,
#: 2 048, let one burst pass any descriptor limit, and Python 3.11's accept loop then spins
#: on EMFILE, logging, and answers nobody.
ACCEPT_BACKLOG = 64

#: Longest time a request's head (request line and headers) may take to arrive, counted from
#: the connection's start or the end of the previous answer, s. A client that connects and
#: sends nothing, or trickles its headers, is disconnected after it.
HEAD_TIMEOUT_S = 10.0


def connection_cap(descriptor_limit: int | None = None) -> int:
    """Most connections the server keeps open: about half the process's file-descriptor limit.

    The rest stays for two turns of accepted sockets (:data:`ACCEPT_BACKLOG` each), the
    server's own files and worker pipes, so a flood of idle connections never exhausts the
    descriptors (with ``ulimit -n 1024``, 1 100 idle connections made the server unreachable).
    At most 512, at least 16.

    Parameters
    ----------
    descriptor_limit : int, optional
        The soft limit on open files (``RLIMIT_NOFILE``); read from the process if not given.

    Examples
    --------
    >>> connection_cap(1024), connection_cap(256), connection_cap(1_000_000)
    (448, 64, 512)
    """
    if descriptor_limit is None:
        try:
            import resource

            descriptor_limit = resource.getrlimit(resource.RLIMIT_NOFILE)[0]
        except (ImportError, OSError, ValueError):  # no resource module (Windows)
            descriptor_limit = 1024
        if descriptor_limit < 0:  # RLIM_INFINITY
            descriptor_limit = 1 << 20
    return max(16, min(512, (descriptor_limit - 2 * ACCEPT_BACKLOG) // 2))


def bad_request_body(reason: str) -> bytes:
    """The JSON body of the explorer's answer to a malformed HTTP request.

    Parameters
    ----------
    reason : str
        What the parser found wrong (kept to one line of at most 200 characters).

    Returns
    -------
    bytes
        UTF-8 JSON ``{"error": "malformed HTTP request: ..."}``.

    Examples
    --------
    >>> bad_request_body("illegal request line")
    b'{"error": "malformed HTTP request: illegal request line"}'
    """
    line = " ".join(str(reason).split())[:200] or "not HTTP/1.1"
    return json.dumps({"error": f"malformed HTTP request: {line}"}).encode("utf-8")


class JSONErrorH11Protocol(H11Protocol):
    """uvicorn's h11 protocol whose 400 answer is ``{"error": ...}`` JSON, with bounded connections.

    Besides the JSON 400, it bounds what idle clients can hold:

    * **a head timeout**: a request's head must arrive within :data:`HEAD_TIMEOUT_S` of the
      connection's start (or of the previous answer); otherwise the connection is closed, with
      a JSON 408 if part of a head had arrived (uvicorn itself closes a kept-alive connection
      that stays silent after an answer, but waits for ever for a first request or for the
      rest of a head);
    * **a connection cap** (:data:`max_connections`, :func:`connection_cap`): when a new
      connection would pass it, the connection that has been idle longest (no request in
      progress) is closed to make room, or the new one if every connection is working. So
      idle and half-open connections can never use up the file descriptors, and a client
      that is being answered is never cut off.

    Parameters
    ----------
    *args, **kwargs
        As :class:`uvicorn.protocols.http.h11_impl.H11Protocol` (uvicorn creates it).

    Examples
    --------
    >>> import uvicorn
    >>> config = uvicorn.Config(lambda scope, receive, send: None, http=JSONErrorH11Protocol)
    >>> config.http is JSONErrorH11Protocol
    True
    """

    #: Most open connections (all instances share uvicorn's connection set).
    max_connections = connection_cap()
    #: Head timeout of this server, s (a class attribute, so a test may shorten it).
    head_timeout_s = HEAD_TIMEOUT_S

    def connection_made(self, transport) -> None:  # noqa: D102 - asyncio.Protocol
        super().connection_made(transport)
        self._idle_since = self.loop.time()
        self._head_timer: asyncio.TimerHandle | None = None
        self._arm_head_timer()
        if len(self.connections) > self.max_connections:
            self._make_room()

    def connection_lost(self, exc) -> None:  # noqa: D102 - asyncio.Protocol
        self._cancel_head_timer()
        super().connection_lost(exc)

    def data_received(self, data: bytes) -> None:  # noqa: D102 - asyncio.Protocol
        super().data_received(data)
        if self._working():
            self._cancel_head_timer()  # a whole head arrived: the application has the request

    def on_response_complete(self) -> None:  # noqa: D102 - uvicorn's hook
        super().on_response_complete()
        self._idle_since = self.loop.time()
        if not self.transport.is_closing() and not self._working():
            self._arm_head_timer()

    def _working(self) -> bool:
        """Whether a request of this connection is being answered."""
        return self.cycle is not None and not self.cycle.response_complete

    def _arm_head_timer(self) -> None:
        self._cancel_head_timer()
        self._head_timer = self.loop.call_later(self.head_timeout_s, self._head_timed_out)

    def _cancel_head_timer(self) -> None:
        timer = getattr(self, "_head_timer", None)
        if timer is not None:
            timer.cancel()
            self._head_timer = None

    def _head_timed_out(self) -> None:
        self._head_timer = None
        if self._working() or self.transport.is_closing():
            return
        if self.conn.their_state is h11.SEND_BODY or self.conn.their_state is h11.DONE:
            return  # the head arrived (a pipelined request waits its turn)
        if self.conn.trailing_data[0]:  # part of a head arrived: say why the connection ends
            body = json.dumps({"error": f"request head not received within "
                                        f"{self.head_timeout_s:g} s"}).encode("utf-8")
            self.transport.write(b"HTTP/1.1 408 Request Timeout\r\ncontent-type: application/json"
                                 b"\r\ncontent-length: " + str(len(body)).encode("ascii")
                                 + b"\r\nconnection: close\r\n\r\n" + body)
        self.transport.close()

    def _make_room(self) -> None:
        """Close the connection idle longest (this one if every other is working)."""
        idle = [c for c in self.connections
                if c is not self and isinstance(c, JSONErrorH11Protocol) and not c._working()
                and not c.transport.is_closing()]
        victim = min(idle, key=lambda c: c._idle_since) if idle else self
        victim._cancel_head_timer()
        victim.transport.close()

    def send_400_response(self, msg: str) -> None:
        """Answer 400 with the explorer's JSON error body, then close the connection.

        A body that turns malformed (a bad chunk size) may arrive while the application is
        already answering the request; its answer is then dropped, as uvicorn drops the
        answer to a client that has gone, instead of failing in h11.
        """
        what = "the request line, a header or the chunked framing is not HTTP/1.1"
        body = bad_request_body(f"{msg.rstrip('.')} ({what})")
        headers = [
            (b"content-type", b"application/json"),
            (b"content-length", str(len(body)).encode("ascii")),
            (b"connection", b"close"),
        ]
        cycle = getattr(self, "cycle", None)
        if cycle is not None and not cycle.response_complete:
            cycle.disconnected = True  # the application's own answer, if it comes, is dropped
        try:
            for event in (h11.Response(status_code=400, headers=headers, reason=b"Bad Request"),
                          h11.Data(data=body), h11.EndOfMessage()):
                self.transport.write(self.conn.send(event))
        except h11.LocalProtocolError:  # a response had already begun: nothing more can be sent
            pass
        self.transport.close()
