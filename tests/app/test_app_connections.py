"""Connections are bounded: head and body timeouts and a connection cap (issue 31).

A real uvicorn server runs in a thread of the test with the explorer's protocol class
(:class:`spectrocolor.app.http_protocol.JSONErrorH11Protocol`) and body guard
(:class:`spectrocolor.app.guards.BodyLimit`) around a small echo application, with the limits
made short and small so that each case takes a second: the same classes the real server uses,
only their limits changed.
"""

from __future__ import annotations

import asyncio
import json
import socket
import threading
import time

import pytest

uvicorn = pytest.importorskip("uvicorn")

from spectrocolor.app.guards import BodyLimit  # noqa: E402
from spectrocolor.app.http_protocol import JSONErrorH11Protocol, connection_cap  # noqa: E402

HEAD_TIMEOUT_S = 1.5
BODY_TIMEOUT_S = 0.5
MAX_CONNECTIONS = 8


class ShortLimits(JSONErrorH11Protocol):
    head_timeout_s = HEAD_TIMEOUT_S
    max_connections = MAX_CONNECTIONS


async def echo(scope, receive, send):
    """Answers every request with the length of its body, as JSON."""
    if scope["type"] != "http":
        return
    body, more = b"", True
    while more:
        message = await receive()
        body += message.get("body", b"")
        more = message.get("more_body", False)
    answer = json.dumps({"length": len(body)}).encode()
    await send({"type": "http.response.start", "status": 200,
                "headers": [(b"content-type", b"application/json"),
                            (b"content-length", str(len(answer)).encode())]})
    await send({"type": "http.response.body", "body": answer})


@pytest.fixture(scope="module")
def port():
    sock = socket.socket()
    sock.bind(("127.0.0.1", 0))
    app = BodyLimit(echo, max_bytes=10_000, max_depth=32, timeout_s=BODY_TIMEOUT_S)
    server = uvicorn.Server(uvicorn.Config(app, http=ShortLimits, log_level="error", backlog=16))
    thread = threading.Thread(target=lambda: asyncio.run(server.serve(sockets=[sock])), daemon=True)
    thread.start()
    for _ in range(200):
        if server.started:
            break
        time.sleep(0.02)
    yield sock.getsockname()[1]
    server.should_exit = True
    thread.join(10)


def exchange(port: int, data: bytes, wait_s: float = 5.0) -> bytes:
    """Send ``data`` on a fresh connection; everything the server sends until it closes."""
    with socket.create_connection(("127.0.0.1", port), timeout=wait_s) as sock:
        sock.sendall(data)
        answer = b""
        while chunk := sock.recv(65536):
            answer += chunk
    return answer


def get(port: int) -> bytes:
    return exchange(port, f"GET / HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\nConnection: close\r\n\r\n".encode())


def closed_by_server(sock: socket.socket, within_s: float) -> bool:
    sock.settimeout(within_s)
    try:
        return sock.recv(1) == b""
    except TimeoutError:
        return False
    except ConnectionResetError:
        return True


def closed_now(sock: socket.socket) -> bool:
    """Whether the server has closed ``sock`` already (without waiting)."""
    sock.setblocking(False)
    try:
        return sock.recv(1) == b""
    except BlockingIOError:
        return False
    except ConnectionResetError:
        return True


def test_a_connection_that_sends_nothing_is_closed_after_the_head_timeout(port):
    with socket.create_connection(("127.0.0.1", port)) as sock:
        started = time.monotonic()
        assert closed_by_server(sock, within_s=10 * HEAD_TIMEOUT_S)
        assert time.monotonic() - started >= HEAD_TIMEOUT_S * 0.8


def test_a_trickled_head_gets_a_json_408(port):
    answer = exchange(port, b"GET / HTTP/1.1\r\nHost: 127.0.0.1", wait_s=10 * HEAD_TIMEOUT_S)
    head, _, body = answer.partition(b"\r\n\r\n")
    assert head.startswith(b"HTTP/1.1 408"), answer[:200]
    assert b"application/json" in head and "not received" in json.loads(body)["error"]


def test_a_trickled_body_gets_a_json_408(port):
    head = f"POST / HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\nContent-Length: 100\r\n\r\n".encode()
    answer = exchange(port, head + b"{", wait_s=10 * BODY_TIMEOUT_S)
    status_line, _, rest = answer.partition(b"\r\n")
    assert status_line.startswith(b"HTTP/1.1 408"), answer[:200]
    assert "not received" in json.loads(rest.partition(b"\r\n\r\n")[2])["error"]


def test_a_prompt_request_is_served_and_the_connection_kept_alive(port):
    with socket.create_connection(("127.0.0.1", port), timeout=5) as sock:
        for _ in range(3):  # answers within the head timeout, on one connection
            sock.sendall(f"POST / HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\nContent-Length: 2\r\n\r\n{{}}"
                         .encode())
            answer = b""
            while not answer.endswith(b"}"):
                answer += sock.recv(65536)
            assert answer.startswith(b"HTTP/1.1 200")
            time.sleep(HEAD_TIMEOUT_S / 3)


def test_the_connection_cap_closes_the_longest_idle_first(port):
    idle = [socket.create_connection(("127.0.0.1", port)) for _ in range(3 * MAX_CONNECTIONS)]
    try:
        time.sleep(0.2)
        closed = [closed_now(sock) for sock in idle]
        # the oldest were closed to make room, the newest stay (until their head timeout)
        assert all(closed[:MAX_CONNECTIONS]) and not any(closed[-MAX_CONNECTIONS // 2:]), closed
        assert get(port).startswith(b"HTTP/1.1 200")  # and a new client is answered
    finally:
        for sock in idle:
            sock.close()


def test_the_cap_follows_the_descriptor_limit():
    assert connection_cap(1024) == 448 and connection_cap(256) == 64
    assert connection_cap(10) == 16 and connection_cap(10**6) == 512
