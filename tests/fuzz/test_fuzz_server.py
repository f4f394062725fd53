"""Hostile HTTP against the real server, started as a user starts it (``spectrocolor app``).

Every answer must be a 2xx or a 4xx with the page's one error shape ``{"error": "..."}``; never
a 5xx, never a body larger than the limit parsed, never a foreign Host or Origin answered.
Raw sockets are used where an HTTP library would correct the request (chunked bodies, Host).
"""

from __future__ import annotations

import json
import os
import re
import resource
import select
import signal
import socket
import subprocess
import sys
import threading
import time

import pytest

pytest.importorskip("fastapi")
pytest.importorskip("uvicorn")
hypothesis = pytest.importorskip("hypothesis")
from hypothesis import HealthCheck, given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402

from spectrocolor.app.server import MAX_BODY_BYTES, MAX_JSON_DEPTH, SMALL_BODY_BYTES  # noqa: E402


def _router_routes(module: str) -> list[tuple[str, str]]:
    """The routes of ``module``'s router, whatever they are at the time (other modules own them)."""
    import importlib
    router = importlib.import_module(module).router
    return [(m, r.path) for r in router.routes for m in sorted(getattr(r, "methods", ()))
            if "{" not in r.path]


ROUTES = [("GET", "/"), ("GET", "/api/options"), ("GET", "/api/presets"), ("GET", "/api/demos"),
          ("POST", "/api/model"), ("POST", "/api/evaluate"), ("POST", "/api/metamer"),
          ("POST", "/api/import"), ("POST", "/api/export"), ("POST", "/api/lab/light/upload"),
          *_router_routes("spectrocolor.app.lab_routes"),
          *_router_routes("spectrocolor.app.relight_routes")]


def test_the_route_list_covers_every_route_of_the_app():
    """A route added later is fuzzed too: every API route of the real app is in ROUTES."""
    from spectrocolor.app.server import create_app

    def flat(routes):  # FastAPI keeps an included router as one entry holding the original
        for route in routes:
            inner = getattr(route, "original_router", None)
            yield from flat(inner.routes) if inner is not None else (route,)

    app_routes = {(m, r.path) for r in flat(create_app().routes)
                  for m in getattr(r, "methods", ()) if r.path.startswith("/api/")}
    assert ("POST", "/api/relight") in app_routes and ("POST", "/api/lab/thinfilm") in app_routes
    assert app_routes <= set(ROUTES), sorted(app_routes - set(ROUTES))


@pytest.fixture(scope="module")
def server():
    """``spectrocolor app --port 0 --no-browser`` in a subprocess; yields (port, pid)."""
    env = {**os.environ, "PYTHONUNBUFFERED": "1"}
    proc = subprocess.Popen([sys.executable, "-m", "spectrocolor", "app", "--port", "0",
                             "--no-browser"], stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                            text=True, env=env)
    line = proc.stdout.readline()
    match = re.search(r"http://127\.0\.0\.1:(\d+)/", line)
    assert match, f"no URL printed: {line!r} {proc.stderr.read() if proc.poll() else ''}"
    port = int(match.group(1))
    for _ in range(100):  # the socket is bound before the URL is printed; wait for uvicorn
        try:
            status, _, _ = request(port, "GET", "/api/options")
            if status == 200:
                break
        except OSError:
            time.sleep(0.05)
    yield port, proc.pid
    proc.terminate()
    proc.wait(10)


def _read_response(sock: socket.socket, timeout: float = 30.0) -> tuple[int, dict, bytes]:
    sock.settimeout(timeout)
    data = b""
    while b"\r\n\r\n" not in data:
        chunk = sock.recv(65536)
        if not chunk:
            break
        data += chunk
    head, _, body = data.partition(b"\r\n\r\n")
    lines = head.decode("latin-1").split("\r\n")
    status = int(lines[0].split()[1])
    headers = {k.strip().lower(): v.strip() for k, _, v in (x.partition(":") for x in lines[1:])}
    length = int(headers.get("content-length", "-1"))
    while length >= 0 and len(body) < length:
        chunk = sock.recv(65536)
        if not chunk:
            break
        body += chunk
    if length < 0:  # read to close
        while chunk := sock.recv(65536):
            body += chunk
    return status, headers, body


def request(port, method, path, body: bytes | None = None, headers: dict | None = None,
            host: str | None = None) -> tuple[int, dict, bytes]:
    """One request on a fresh connection, headers exactly as given (no Host added if given)."""
    hdrs = {"Host": host or f"127.0.0.1:{port}", "Connection": "close", **(headers or {})}
    if body is not None and "Transfer-Encoding" not in hdrs:
        hdrs.setdefault("Content-Length", str(len(body)))
        hdrs.setdefault("Content-Type", "application/json")
    head = f"{method} {path} HTTP/1.1\r\n" + "".join(f"{k}: {v}\r\n" for k, v in hdrs.items())
    with socket.create_connection(("127.0.0.1", port), timeout=30) as sock:
        sock.sendall(head.encode("latin-1") + b"\r\n" + (body or b""))
        return _read_response(sock)


def post_json(port, path, payload, **kw):
    return request(port, "POST", path, json.dumps(payload).encode(), **kw)


def strict_json(body: bytes):
    """``body`` parsed as JSON proper: NaN, Infinity and -Infinity are refused."""
    def refuse(constant):
        raise AssertionError(f"non-finite number {constant} in a JSON answer: {body[:200]!r}")
    return json.loads(body, parse_constant=refuse)


def assert_clean(status: int, headers: dict, body: bytes) -> None:
    """A 2xx, or a 4xx whose body is {"error": one line}; never a 5xx, never NaN or infinity."""
    assert status < 500, (status, body[:300])
    if status >= 400:
        assert headers.get("content-type", "").startswith("application/json"), (status, body[:200])
        error = strict_json(body)["error"]
        assert isinstance(error, str) and error and "\n" not in error and "Traceback" not in error
    elif headers.get("content-type", "").startswith("application/json"):
        strict_json(body)


def rss_kib(pid: int) -> int:
    with open(f"/proc/{pid}/status") as fh:
        return next(int(line.split()[1]) for line in fh if line.startswith("VmRSS"))


# --- body limits ---------------------------------------------------------------------------------


def test_chunked_body_over_the_limit_is_refused_early(server):
    port, pid = server
    head = (f"POST /api/evaluate HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\n"
            "Content-Type: application/json\r\nTransfer-Encoding: chunked\r\n\r\n").encode()
    chunk = b"[" * 65536
    framed = f"{len(chunk):x}\r\n".encode() + chunk + b"\r\n"
    sent = 0
    rss_before = rss_kib(pid)
    with socket.create_connection(("127.0.0.1", port), timeout=30) as sock:
        sock.sendall(head)
        answered = False
        while sent < 50 * 2**20:  # a 50 MiB chunked body, unless the server answers first
            if select.select([sock], [], [], 0)[0]:
                answered = True
                break
            try:
                sock.sendall(framed)
            except (BrokenPipeError, ConnectionResetError):
                break
            sent += len(chunk)
        status, headers, body = _read_response(sock)
    assert status == 413 and "larger than" in json.loads(body)["error"]
    # refused after the limit plus what the kernel's socket buffers held (a few MiB), not 50 MiB
    assert sent < MAX_BODY_BYTES + 16 * 2**20, (sent, answered)  # answered, or cut off by it
    assert rss_kib(pid) - rss_before < 64 * 1024  # never the 600 MiB of a parsed 50 MiB body


def test_chunked_body_under_the_limit_is_served(server):
    port, _ = server
    payload = json.dumps({"spectra": [[10.0] * 31]}).encode()
    pieces = [payload[i:i + 7] for i in range(0, len(payload), 7)]
    body = b"".join(f"{len(p):x}\r\n".encode() + p + b"\r\n" for p in pieces) + b"0\r\n\r\n"
    status, headers, answer = request(port, "POST", "/api/evaluate", body,
                                      {"Transfer-Encoding": "chunked",
                                       "Content-Type": "application/json"})
    assert status == 200, answer[:200]
    assert len(json.loads(answer)["colours"]) == 1


@pytest.mark.parametrize("length", [str(MAX_BODY_BYTES + 1), "99999999999999999999"])
def test_content_length_over_the_limit_is_413(server, length):
    port, _ = server
    status, headers, body = request(port, "POST", "/api/evaluate", b"{}",
                                    {"Content-Length": length})
    assert status == 413
    assert_clean(status, headers, body)


# --- Host and Origin -----------------------------------------------------------------------------


@pytest.mark.parametrize("host", ["evil.example", "evil.example:{port}", "127.0.0.1:1",
                                  "localhost.evil.example:{port}", "", "127.0.0.2:{port}"])
def test_foreign_host_is_refused(server, host):
    port, _ = server
    status, headers, body = request(port, "GET", "/api/options", host=host.format(port=port) or " ")
    assert status in (400, 403), status
    if status == 403:
        assert_clean(status, headers, body)
        assert "Host" in json.loads(body)["error"]


@pytest.mark.parametrize("host", ["127.0.0.1:{port}", "localhost:{port}", "[::1]:{port}",
                                  "LOCALHOST:{port}"])
def test_own_names_are_answered(server, host):
    port, _ = server
    status, _, body = request(port, "GET", "/api/options", host=host.format(port=port))
    assert status == 200 and "steps_nm" in json.loads(body)


@pytest.mark.parametrize("origin", ["http://evil.example", "null", "http://127.0.0.1:1",
                                    "https://127.0.0.1:{port}", "http://localhost:{port}"])
def test_foreign_origin_is_refused(server, origin):
    port, _ = server  # localhost is the same machine, but another origin than 127.0.0.1:port
    status, headers, body = post_json(port, "/api/evaluate", {"spectra": [[10.0] * 31]},
                                      headers={"Origin": origin.format(port=port)})
    assert status == 403
    assert_clean(status, headers, body)


def test_own_origin_is_answered(server):
    port, _ = server
    status, _, _ = post_json(port, "/api/evaluate", {"spectra": [[10.0] * 31]},
                             headers={"Origin": f"http://127.0.0.1:{port}"})
    assert status == 200


# --- bodies that broke the parsers ---------------------------------------------------------------


@pytest.mark.parametrize("depth", [MAX_JSON_DEPTH + 1, 100_000])
def test_deeply_nested_json_is_422(server, depth):
    port, _ = server
    body = b"[" * depth + b"]" * depth
    for _, path in filter(lambda r: r[0] == "POST", ROUTES):
        status, headers, answer = request(port, "POST", path, body)
        # a route whose bodies are small refuses a longer one (413) before its nesting matters
        small = path not in ("/api/import", "/api/relight", "/api/lab/light/upload") and len(body) > SMALL_BODY_BYTES
        assert status == (413 if small else 422), (path, status)
        assert_clean(status, headers, answer)
    content = "[" * depth + "]" * depth
    status, headers, answer = post_json(port, "/api/import",
                                        {"filename": "deep.json", "content": content})
    assert status == 422 and "nested" in json.loads(answer)["error"]


@pytest.mark.parametrize("cell", [200_000, 900_000])
def test_very_long_csv_cell_gets_a_clean_answer(server, cell):
    """A plain cell has no length limit but the body's (the reader splits lines itself); a quoted
    one goes through Python's csv module, whose field limit (131 072 characters) gives a 422."""
    port, _ = server
    plain = "wavelength_nm," + "a" * cell + "\n400,1\n700,1\n"
    status, headers, answer = post_json(port, "/api/import", {"filename": "long.csv", "content": plain})
    assert status == 200
    assert_clean(status, headers, answer)
    quoted = 'wavelength_nm,"' + "a" * cell + '"\n400,1\n700,1\n'
    status, headers, answer = post_json(port, "/api/import", {"filename": "long.csv", "content": quoted})
    assert status == 422 and b"not readable as delimited text" in answer
    assert_clean(status, headers, answer)


# --- the one error shape on every route ----------------------------------------------------------


@pytest.mark.parametrize("method,path,status", [
    ("GET", "/nothing-here", 404), ("GET", "/static/missing.js", 404),
    ("GET", "/static/../../etc/passwd", 404), ("GET", "/api/evaluate", 405),
    ("DELETE", "/api/options", 405), ("POST", "/api/evaluate", 422),
    ("GET", "/api/presets?step_nm=3", 422)])
def test_errors_have_one_shape(server, method, path, status):
    port, _ = server
    got, headers, body = request(port, method, path, b"{}" if method == "POST" else None)
    assert got == status
    assert_clean(got, headers, body)


def test_export_neutralises_names_a_spreadsheet_would_run(server):
    port, _ = server
    status, _, body = post_json(port, "/api/export", {
        "format": "csv", "names": ["+cmd", "-2+3", "plain"], "spectra": [[1.0] * 31] * 3})
    assert status == 200
    header = next(line for line in body.decode().splitlines() if not line.startswith("#"))  # after the units
    assert "'+cmd" in header and "'-2+3" in header and ",plain" in header


JSON_VALUES = st.recursive(
    st.none() | st.booleans() | st.floats(allow_nan=False) | st.integers() | st.text(max_size=30),
    lambda children: st.lists(children, max_size=40)
    | st.dictionaries(st.sampled_from(["spectra", "step_nm", "illuminant", "target", "names",
                                       "format", "filename", "content", "observer", "pairs",
                                       "gamut", "normalise", "scale", "method", "x"]), children,
                      max_size=6),
    max_leaves=60)


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(route=st.sampled_from([r for r in ROUTES if r[0] == "POST"]), payload=JSON_VALUES)
@pytest.mark.slow
def test_generated_json_never_gives_a_5xx(server, route, payload):
    port, _ = server
    assert_clean(*post_json(port, route[1], payload))


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(route=st.sampled_from(ROUTES), body=st.binary(max_size=2000))
def test_random_bytes_never_give_a_5xx(server, route, body):
    port, _ = server
    assert_clean(*request(port, route[0], route[1], body if route[0] == "POST" else None))


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(filename=st.sampled_from(["x.csv", "x.json", "x.txt"]),
       content=st.text(alphabet=st.sampled_from(list("0123456789.,;-+eE\n\"[]{}:nNaI wavelngth_m#")),
                       min_size=1, max_size=3000))
def test_generated_uploads_never_give_a_5xx(server, filename, content):
    port, _ = server
    assert_clean(*post_json(port, "/api/import", {"filename": filename, "content": content}))


@pytest.mark.slow
def test_a_remote_host_needs_allow_remote_and_warns():
    refused = subprocess.run([sys.executable, "-m", "spectrocolor", "app", "--host", "0.0.0.0",
                              "--port", "0", "--no-browser"], capture_output=True, text=True,
                             timeout=60)
    assert refused.returncode == 2 and "--allow-remote" in refused.stderr
    assert "Traceback" not in refused.stderr and refused.stdout == ""
    proc = subprocess.Popen([sys.executable, "-m", "spectrocolor", "app", "--host", "0.0.0.0",
                             "--allow-remote", "--port", "0", "--no-browser"],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        assert "warning" in proc.stderr.readline()
        port = int(re.search(r":(\d+)/", proc.stdout.readline()).group(1))
        for _ in range(100):
            try:
                # any Host is answered when serving the network; a foreign Origin still is not
                status, _, _ = request(port, "GET", "/api/options", host="myhost.lan")
                break
            except OSError:
                time.sleep(0.05)
        assert status == 200
        status, _, _ = post_json(port, "/api/model", {}, host="myhost.lan",
                                 headers={"Origin": "http://evil.example"})
        assert status == 403
        status, _, _ = post_json(port, "/api/model", {}, host="myhost.lan",
                                 headers={"Origin": "http://myhost.lan"})
        assert status == 200
    finally:
        proc.terminate()
        proc.wait(10)


def test_the_listening_socket_sends_without_delay():
    """Accepted connections inherit TCP_NODELAY: no 40 ms delayed-ACK stall per kept-alive request."""
    from spectrocolor.cli.app import _bind

    sock = _bind("127.0.0.1", 0)
    try:
        assert sock.getsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY) != 0
    finally:
        sock.close()


def raw(port: int, data: bytes) -> tuple[int, dict, bytes]:
    """Send ``data`` exactly as given on a fresh connection; the answer, read to its end."""
    with socket.create_connection(("127.0.0.1", port), timeout=30) as sock:
        sock.sendall(data)
        return _read_response(sock)


def assert_json_400(status: int, headers: dict, body: bytes) -> None:
    assert status == 400, (status, body[:200])
    assert headers.get("content-type") == "application/json", headers
    assert int(headers["content-length"]) == len(body)
    error = json.loads(body)["error"]
    assert error.startswith("malformed HTTP request") and "\n" not in error


MALFORMED = {
    "garbage request line": b"HELLO\r\n\r\n",
    "request line without version": b"GET /api/options\r\nHost: 127.0.0.1\r\n\r\n",
    "binary noise": bytes(range(1, 32)) + b"\r\n\r\n",
    "two Hosts": b"GET /api/options HTTP/1.1\r\nHost: 127.0.0.1\r\nHost: 127.0.0.1\r\n\r\n",
    "HTTP/1.1 without Host": b"GET /api/options HTTP/1.1\r\nConnection: close\r\n\r\n",
    "header without colon": b"GET /api/options HTTP/1.1\r\nHost 127.0.0.1\r\n\r\n",
    "bad chunk size": (b"POST /api/evaluate HTTP/1.1\r\nHost: 127.0.0.1\r\nContent-Type: application/json"
                       b"\r\nTransfer-Encoding: chunked\r\n\r\nZZ\r\n{}\r\n0\r\n\r\n"),
    "chunk size overflow": (b"POST /api/evaluate HTTP/1.1\r\nHost: 127.0.0.1\r\nTransfer-Encoding: chunked"
                            b"\r\n\r\n" + b"f" * 40 + b"\r\n{}\r\n0\r\n\r\n"),
    "Content-Length not a number": (b"POST /api/evaluate HTTP/1.1\r\nHost: 127.0.0.1\r\n"
                                    b"Content-Length: ten\r\n\r\n{}"),
    "two different Content-Lengths": (b"POST /api/evaluate HTTP/1.1\r\nHost: 127.0.0.1\r\n"
                                      b"Content-Length: 2\r\nContent-Length: 3\r\n\r\n{}"),
}


@pytest.mark.parametrize("name", sorted(MALFORMED))
def test_malformed_http_gets_a_json_400(server, name):
    port, _ = server
    assert_json_400(*raw(port, MALFORMED[name]))


def test_an_empty_host_is_refused_in_the_error_shape(server):
    port, _ = server  # h11 accepts an empty Host; the Host guard refuses it
    status, headers, body = raw(port, b"GET /api/options HTTP/1.1\r\nHost:\r\n\r\n")
    assert status == 403
    assert_clean(status, headers, body)


def test_the_server_still_answers_after_malformed_requests(server):
    port, _ = server
    for data in MALFORMED.values():
        raw(port, data)
    status, headers, body = request(port, "GET", "/api/options")
    assert status == 200 and json.loads(body)


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(line=st.binary(min_size=1, max_size=200).filter(lambda b: b"\n" not in b and b"\r" not in b),
       header=st.binary(max_size=100).filter(lambda b: b"\n" not in b and b"\r" not in b))
def test_generated_request_heads_give_json_or_a_clean_answer(server, line, header):
    """Any bytes as request line and header: a JSON 400, or (when they happen to be valid HTTP)
    a clean answer of the application; never plain text, never a 5xx."""
    port, _ = server
    status, headers, body = raw(port, line + b"\r\n" + header + b"\r\nHost: 127.0.0.1\r\n\r\n")
    assert_clean(status, headers, body)


# --- one client never stalls the others (issue 31) -----------------------------------------------


def _served_while(port: int, seconds: float, hostile) -> int:
    """Requests another client completes in ``seconds`` while ``hostile()`` is sent again and again."""
    stop, done = threading.Event(), []

    def attacker():
        while not stop.is_set():
            hostile()

    thread = threading.Thread(target=attacker)
    thread.start()
    time.sleep(0.2)
    deadline = time.monotonic() + seconds
    try:
        while time.monotonic() < deadline:
            status, _, _ = request(port, "GET", "/api/options")
            done.append(status)
    finally:
        stop.set()
        thread.join(60)
    assert set(done) <= {200}, done
    return len(done)


@pytest.mark.parametrize("pairs", [20_000, 900_000])
@pytest.mark.slow
def test_a_hostile_body_scan_does_not_stall_other_clients(server, pairs):
    """The 40 kB body of ``"`` then ``\\"`` x 20 000 froze every client for 10 s: the nesting
    guard's regular expression was quadratic and ran in the event loop. Now another client is
    served about as often as while an ordinary body of the same size is being sent."""
    port, _ = server
    hostile = b'"' + b'\\"' * pairs
    ordinary = json.dumps({"spectra": [[1.0] * 31], "pad": "x" * (len(hostile) - 60)}).encode()
    answers = []

    def send(body):
        def call():
            # /api/import takes bodies of up to 2 MB (the small routes refuse one over 64 kB)
            status, headers, answer = request(port, "POST", "/api/import", body)
            answers.append(status)
            assert_clean(status, headers, answer)
        return call

    reference = _served_while(port, 2.0, send(ordinary))
    during = _served_while(port, 2.0, send(hostile))
    assert 422 in answers
    assert during >= reference / 4, (during, reference)


def test_a_declared_full_scale_that_overflows_is_a_422(server):
    """Argyll's SPECTRAL_NORM "1e-320" divided the values into infinities: a 500 before."""
    port, _ = server
    ti3 = ('CTI3\nSPECTRAL_NORM "1e-320"\nBEGIN_DATA_FORMAT\nSAMPLE_ID SPEC_400 SPEC_500 SPEC_600 '
           'SPEC_700\nEND_DATA_FORMAT\nBEGIN_DATA\n1 10 20 30 40\nEND_DATA\n')
    status, headers, body = post_json(port, "/api/import", {"filename": "x.ti3", "content": ti3})
    assert status == 422 and "SPECTRAL_NORM" in strict_json(body)["error"], body[:300]
    assert_clean(status, headers, body)


def _busy_ticks(pids: list[int]) -> int:
    """CPU time (clock ticks) used so far by the processes ``pids`` that still exist."""
    total = 0
    for pid in pids:
        try:
            with open(f"/proc/{pid}/stat") as handle:
                fields = handle.read().rsplit(")", 1)[1].split()
            total += int(fields[11]) + int(fields[12])
        except FileNotFoundError:
            pass
    return total


def _workers(pid: int) -> list[int]:
    """The worker processes (multiprocessing's spawned children) of process ``pid``."""
    found = []
    for entry in os.listdir("/proc"):
        if entry.isdigit():
            try:
                with open(f"/proc/{entry}/stat") as handle:
                    parent = int(handle.read().rsplit(")", 1)[1].split()[1])
                with open(f"/proc/{entry}/cmdline", "rb") as handle:
                    spawned = b"spawn_main" in handle.read()
            except (FileNotFoundError, ProcessLookupError):
                continue
            if parent == pid and spawned:
                found.append(int(entry))
    return found


@pytest.mark.parametrize("content", ["\n" * 900_000, " \n" * 450_000, "\r\n" * 450_000,
                                     "# note\n" * 120_000], ids=["newlines", "spaces", "crlf", "comments"])
def test_an_import_of_blank_lines_is_answered_and_leaves_no_worker_busy(server, content):
    """A 1 MB import of blank lines took 60 s and kept its worker at 100 % CPU for 270 s more:
    now it is answered like any other file, and no worker works on after the answer."""
    port, pid = server
    reference_body = {"filename": "ok.csv", "content": "wavelength_nm,a\n" + "".join(
        f"{400 + i * 300 / 50_000:.4f},0.5\n" for i in range(50_001))}  # 1 MB, read at once
    started = time.monotonic()
    status, _, _ = post_json(port, "/api/import", reference_body)
    reference_s = time.monotonic() - started
    assert status == 200
    started = time.monotonic()
    status, headers, body = post_json(port, "/api/import", {"filename": "blank.csv", "content": content})
    took = time.monotonic() - started
    assert status == 422 and "no data" in strict_json(body)["error"]
    assert took <= 10 * reference_s, (took, reference_s)
    workers = _workers(pid)
    before = _busy_ticks(workers)
    time.sleep(1.0)
    assert _busy_ticks(workers) - before <= 20  # at most 0.2 s of CPU in 1 s: nobody is working


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="reads /proc")
@pytest.mark.slow
def test_kill_9_of_the_server_ends_its_workers():
    """``kill -9`` of the server left its 4 worker processes running; they now die with it."""
    proc = subprocess.Popen([sys.executable, "-m", "spectrocolor", "app", "--port", "0",
                             "--no-browser"], stdout=subprocess.PIPE, stderr=subprocess.DEVNULL,
                            text=True)
    try:
        port = int(re.search(r"http://127\.0\.0\.1:(\d+)/", proc.stdout.readline()).group(1))
        for _ in range(200):
            try:
                if request(port, "GET", "/api/options")[0] == 200:
                    break
            except OSError:
                time.sleep(0.05)
        status, _, _ = post_json(port, "/api/import", {"filename": "a.csv",
                                                       "content": "wavelength_nm,a\n400,1\n700,1\n"})
        assert status == 200
        children = _workers(proc.pid)
        assert children, "no worker process was started"
        os.kill(proc.pid, signal.SIGKILL)
        proc.wait(10)
        deadline = time.monotonic() + 10
        while time.monotonic() < deadline and any(os.path.exists(f"/proc/{c}") and not _zombie(c)
                                                  for c in children):
            time.sleep(0.1)
        alive = [c for c in children if os.path.exists(f"/proc/{c}") and not _zombie(c)]
        assert not alive, f"processes {alive} outlived the killed server"
    finally:
        proc.kill()
        proc.wait(10)


def _zombie(pid: int) -> bool:
    try:
        with open(f"/proc/{pid}/stat") as handle:
            return handle.read().rsplit(")", 1)[1].split()[0] in ("Z", "X")
    except FileNotFoundError:
        return True


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="reads /proc")
@pytest.mark.slow
def test_a_flood_of_idle_connections_leaves_the_server_reachable():
    """1 100 idle connections against ``ulimit -n 1024`` made the server unreachable. Here the
    server may open 256 files and 400 connections stay idle: it keeps its descriptors below
    the limit (closing the longest idle) and answers a new client."""
    def limit():
        resource.setrlimit(resource.RLIMIT_NOFILE, (256, 256))

    proc = subprocess.Popen([sys.executable, "-m", "spectrocolor", "app", "--port", "0",
                             "--no-browser"], stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                            text=True, preexec_fn=limit)
    idle = []
    try:
        port = int(re.search(r"http://127\.0\.0\.1:(\d+)/", proc.stdout.readline()).group(1))
        for _ in range(200):
            try:
                if request(port, "GET", "/api/options")[0] == 200:
                    break
            except OSError:
                time.sleep(0.05)
        for _ in range(400):
            idle.append(socket.create_connection(("127.0.0.1", port), timeout=30))
        time.sleep(1.0)
        open_files = len(os.listdir(f"/proc/{proc.pid}/fd"))
        assert open_files < 256 - 16, open_files
        status, headers, body = request(port, "GET", "/api/options")
        assert status == 200 and "steps_nm" in strict_json(body)
    finally:
        for sock in idle:
            sock.close()
        proc.kill()
        proc.wait(10)


LED = st.fixed_dictionaries({
    "kind": st.just("leds"),
    "peaks_nm": st.lists(st.floats(380, 780), min_size=1, max_size=4),
    "widths_nm": st.lists(st.sampled_from([5.0, 10.0, 30.0, 200.0]) | st.floats(5, 200),
                          min_size=1, max_size=4),
    "powers": st.lists(st.sampled_from([0.0, 1.0, 5e-324, 1e-300]) | st.floats(0, 1),
                       min_size=1, max_size=4),
}).filter(lambda s: len(s["peaks_nm"]) == len(s["widths_nm"]) == len(s["powers"]))


@pytest.mark.parametrize("peak", range(380, 781, 25))
def test_a_single_led_gets_its_numbers(server, peak):
    """94 of 122 single-LED lights were refused ("cannot be adapted") and one was a 500."""
    port, _ = server
    for width in (5.0, 40.0, 200.0):
        status, headers, body = post_json(port, "/api/lab/light", {"source": {
            "kind": "leds", "peaks_nm": [peak], "widths_nm": [width], "powers": [1.0]}})
        assert status == 200, body[:300]
        assert_clean(status, headers, body)
        samples = strict_json(body)["samples"]
        assert samples["under_light"] is not None and samples["under_light_note"]


@settings(max_examples=30, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(source=LED)
@pytest.mark.slow
def test_generated_led_lights_give_finite_answers(server, source):
    port, _ = server
    status, headers, body = post_json(port, "/api/lab/light", {"source": source})
    assert_clean(status, headers, body)
    if sum(source["powers"]) > 0:
        assert status == 200, body[:300]
