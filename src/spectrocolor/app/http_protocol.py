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

import json

import h11
from uvicorn.protocols.http.h11_impl import H11Protocol

__all__ = ["JSONErrorH11Protocol", "bad_request_body"]


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
    """uvicorn's h11 protocol whose 400 answer is ``{"error": ...}`` JSON, not plain text.

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
