"""Load on the explorer's server, started as a user starts it, on 127.0.0.1 only.

Phases (each bounded by a request count, so the script stops by itself):

1. one client, keep-alive: GET /api/options, POST /api/model, POST /api/evaluate in turn;
2. four clients at once, the same mix;
3. hostile: four clients each streaming a 50 MiB chunked body while a fifth client times
   GET /api/options (the body limit must refuse them early; the fifth must not wait);
4. the largest accepted jobs: a 1 MB CSV import and an evaluation of 4 spectra at 1 nm, and
   parallel imports beyond MAX_PARSERS (answered 429 when the parsers stay busy);
5. malformed HTTP: MALFORMED_ROUNDS requests that are not HTTP/1.1 (garbage request line, bad
   chunk size), each on its own connection; every answer must be a JSON 400;
6. hostile requests of issue 31, each while a second client times GET /api/options: a body of
   ``"`` then ``\\"`` x 20 000 (40 kB) and x 900 000 (1.8 MB), a 1 MB import of blank lines
   (then the workers' CPU over 2 s: a job that outlives its answer would show here), a ``.ti3``
   with ``SPECTRAL_NORM "1e-320"``, single-LED lights to /api/lab/light (status counts);
7. IDLE_CONNECTIONS idle connections (fewer if this process may not open that many), then the
   time a new client waits for an answer and the server's open descriptors;
8. ``kill -9`` of the server: how many of its worker processes are still alive 2 s later;
9. fairness (issue 31): a client's POST /api/model latency at 1 nm with its illuminant changing
   at every request (a dragged slider), alone and then while another client replays 2 MB JSON
   bodies of a million numbers to /api/import and /api/evaluate (``--only fairness`` runs this
   phase alone, on a fresh server);
10. classroom (issue 30, ``--only classroom``: on its own server, ``spectrocolor app
    --classroom --host 127.0.0.2``): CLASS_STUDENTS students, each from its own loopback
    address and holding the class's event stream, edit at human speed for CLASS_SECONDS; four in
    five drag in the explorer (POST /api/evaluate every CLASS_EDIT_S, /api/model every
    CLASS_MODEL_S), one in five works in a lab (/api/lab/light or /api/lab/thinfilm every
    CLASS_LAB_S); the teacher pushes every CLASS_PUSH_S. Students start at random moments within
    one pause and vary their pauses by +-25 % (``CLASS_LOCKSTEP=1``: all at the same instants,
    the worst case; ``CLASS_HOSTILE=1``: a 41st student floods /api/evaluate with the heaviest
    accepted evaluation and 30 000-deep bodies, its answers counted apart). Prints p95 of
    evaluate/model and of the labs, pushes received, and memory before and after;

and prints requests/s, p50/p95/p99 latency (ms), the status counts, and the server's resident
memory (VmRSS) before and after, with its peak (VmHWM).

Run: .venv/bin/python bench/bench_server_load.py [--only fairness | --only classroom]
"""

from __future__ import annotations

import collections
import http.client
import json
import os
import re
import socket
import subprocess
import sys
import threading
import time

import numpy as np

ROUNDS_ONE = 1500
ROUNDS_EACH = 400
CLIENTS = 4
HOSTILE_MIB = 50
PARALLEL_IMPORTS = 6
MALFORMED_ROUNDS = 500
IDLE_CONNECTIONS = 1100
MALFORMED = (b"HELLO\r\n\r\n",
             b"POST /api/evaluate HTTP/1.1\r\nHost: 127.0.0.1\r\nTransfer-Encoding: chunked\r\n\r\nZZ\r\n")


def start_server() -> tuple[subprocess.Popen, int]:
    proc = subprocess.Popen([sys.executable, "-m", "spectrocolor", "app", "--port", "0",
                             "--no-browser"], stdout=subprocess.PIPE, text=True)
    port = int(re.search(r":(\d+)/", proc.stdout.readline()).group(1))
    for _ in range(200):
        try:
            socket.create_connection(("127.0.0.1", port), timeout=1).close()
            break
        except OSError:
            time.sleep(0.05)
    return proc, port


def memory_mib(pid: int) -> dict[str, float]:
    """Resident and peak memory of the server, and of its upload workers, MiB."""
    def status(p):
        with open(f"/proc/{p}/status") as fh:
            fields = dict(line.split(":", 1) for line in fh if ":" in line)
        return {k: int(fields[k].split()[0]) / 1024 for k in ("VmRSS", "VmHWM")}

    result = {k: round(v) for k, v in status(pid).items()}
    workers = []
    for entry in os.listdir("/proc"):
        try:
            with open(f"/proc/{entry}/stat") as fh:
                if entry.isdigit() and int(fh.read().rsplit(")", 1)[1].split()[1]) == pid:
                    workers.append(status(entry))
        except (OSError, ValueError, IndexError):
            continue
    if workers:
        result["workers_RSS"] = round(sum(w["VmRSS"] for w in workers))
        result["workers_HWM"] = round(sum(w["VmHWM"] for w in workers))
    return result


BODIES = {
    "options": ("GET", "/api/options", None),
    "model": ("POST", "/api/model", json.dumps({"step_nm": 10}).encode()),
    "evaluate": ("POST", "/api/evaluate", json.dumps(
        {"spectra": [list(np.linspace(0, 30, 31)), [15.0] * 31], "pairs": [[0, 1]]}).encode()),
}


def timed(conn: http.client.HTTPConnection, method: str, path: str, body) -> tuple[float, int]:
    start = time.perf_counter()
    headers = {"Content-Type": "application/json"} if body is not None else {}
    conn.request(method, path, body=body, headers=headers)
    response = conn.getresponse()
    response.read()
    return time.perf_counter() - start, response.status


def client(port: int, rounds: int, latencies: list, statuses: collections.Counter,
           by_name: dict | None = None) -> None:
    conn = http.client.HTTPConnection("127.0.0.1", port, timeout=60)
    names = list(BODIES)
    for i in range(rounds):
        name = names[i % len(names)]
        seconds, status = timed(conn, *BODIES[name])
        latencies.append(seconds)
        statuses[status] += 1
        if by_name is not None:
            by_name.setdefault(name, []).append(seconds)
    conn.close()


def report(label: str, latencies: list, statuses, wall: float) -> None:
    ms = np.array(latencies) * 1e3
    p50, p95, p99 = np.percentile(ms, [50, 95, 99])
    print(f"{label:<34} {len(ms):>6} req  {len(ms) / wall:8.0f} req/s  p50 {p50:6.2f}  "
          f"p95 {p95:6.2f}  p99 {p99:7.2f} ms  max {ms.max():7.1f} ms  {dict(statuses)}")


def hostile_chunked(port: int, results: list) -> None:
    head = (f"POST /api/evaluate HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\n"
            "Content-Type: application/json\r\nTransfer-Encoding: chunked\r\n\r\n").encode()
    chunk = b"[1," * 21846
    framed = f"{len(chunk):x}\r\n".encode() + chunk + b"\r\n"
    sent = 0
    with socket.create_connection(("127.0.0.1", port), timeout=60) as sock:
        sock.sendall(head)
        try:
            while sent < HOSTILE_MIB * 2**20:
                sock.sendall(framed)
                sent += len(chunk)
        except OSError:
            pass
        try:
            status = int(sock.recv(4096).split()[1])
        except (OSError, IndexError, ValueError):
            status = 0
    results.append((status, sent))


def malformed(port: int, data: bytes) -> tuple[float, int, str]:
    """Send ``data`` raw on a new connection; (seconds, status, content type) of the answer."""
    t0 = time.perf_counter()
    with socket.create_connection(("127.0.0.1", port), timeout=30) as sock:
        sock.sendall(data)
        answer = b""
        while chunk := sock.recv(65536):  # the server closes after a 400
            answer += chunk
    head = answer.split(b"\r\n\r\n", 1)[0].decode("latin-1").lower()
    status = int(head.split()[1]) if head.startswith("http/") else 0
    match = re.search(r"content-type: *([^\r\n;]+)", head)
    return time.perf_counter() - t0, status, match.group(1) if match else "none"


def probe_during(port: int, action) -> tuple[list, collections.Counter, object, float]:
    """GET /api/options on a kept-alive connection while ``action()`` runs in a thread.

    Returns the probe's latencies and statuses, what ``action`` returned and its seconds.
    """
    outcome: list = []

    def run():
        t0 = time.perf_counter()
        outcome.append(action())
        outcome.append(time.perf_counter() - t0)

    thread = threading.Thread(target=run)
    conn = http.client.HTTPConnection("127.0.0.1", port, timeout=120)
    lat, st = [], collections.Counter()
    thread.start()
    while thread.is_alive() and len(lat) < 20000:
        seconds, status = timed(conn, *BODIES["options"])
        lat.append(seconds)
        st[status] += 1
        time.sleep(0.005)
    thread.join()
    conn.close()
    return lat, st, outcome[0], outcome[1]


def raw_request(port: int, method: str, path: str, body: bytes) -> tuple[int, bytes]:
    """One request on a fresh connection (closed after the answer): status and body."""
    with socket.create_connection(("127.0.0.1", port), timeout=300) as sock:
        sock.sendall(f"{method} {path} HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\nContent-Type: "
                     f"application/json\r\nContent-Length: {len(body)}\r\nConnection: close\r\n"
                     "\r\n".encode() + body)
        answer = b""
        while chunk := sock.recv(65536):
            answer += chunk
    head, _, rest = answer.partition(b"\r\n\r\n")
    return (int(head.split()[1]) if head else 0), rest


def worker_pids(pid: int) -> list[int]:
    found = []
    for entry in os.listdir("/proc"):
        try:
            with open(f"/proc/{entry}/stat") as fh:
                parent = int(fh.read().rsplit(")", 1)[1].split()[1])
            with open(f"/proc/{entry}/cmdline", "rb") as fh:
                if parent == pid and b"spawn_main" in fh.read():
                    found.append(int(entry))
        except (OSError, ValueError, IndexError):
            continue
    return found


def cpu_ticks(pids: list[int]) -> int:
    total = 0
    for pid in pids:
        try:
            with open(f"/proc/{pid}/stat") as fh:
                fields = fh.read().rsplit(")", 1)[1].split()
            total += int(fields[11]) + int(fields[12])
        except OSError:
            pass
    return total


def hostile_phases(proc: subprocess.Popen, port: int) -> None:
    """Phase 6: the hostile requests of issue 31, each while a second client is timed."""
    cases = [
        ("40 kB of escaped quotes", "POST", "/api/evaluate", b'"' + b'\\"' * 20_000),
        ("1.8 MB of escaped quotes", "POST", "/api/evaluate", b'"' + b'\\"' * 900_000),
        ("1 MB import of blank lines", "POST", "/api/import",
         json.dumps({"filename": "blank.csv", "content": "\n" * 900_000}).encode()),
        ("SPECTRAL_NORM 1e-320", "POST", "/api/import", json.dumps({"filename": "x.ti3", "content": (
            'CTI3\nSPECTRAL_NORM "1e-320"\nBEGIN_DATA_FORMAT\nSAMPLE_ID SPEC_400 SPEC_500 SPEC_600 '
            'SPEC_700\nEND_DATA_FORMAT\nBEGIN_DATA\n1 10 20 30 40\nEND_DATA\n')}).encode()),
    ]
    for label, method, path, body in cases:
        lat, st, (status, answer), seconds = probe_during(
            port, lambda m=method, p=path, b=body: raw_request(port, m, p, b))
        report(f"options during {label}", lat, st, seconds)
        print(f"  the hostile request: {status} in {seconds * 1e3:.0f} ms: {answer[:80]!r}")
        if "blank" in label:
            pids = worker_pids(proc.pid)
            before = cpu_ticks(pids)
            time.sleep(2.0)
            print(f"  workers' CPU over the next 2 s: {(cpu_ticks(pids) - before) * 10} ms")
    counts: collections.Counter = collections.Counter()
    for peak in range(380, 781, 10):
        for width in (5, 20, 60):
            body = json.dumps({"source": {"kind": "leds", "peaks_nm": [peak], "widths_nm": [width],
                                          "powers": [1.0]}}).encode()
            counts[raw_request(port, "POST", "/api/lab/light", body)[0]] += 1
    print(f"single-LED lights to /api/lab/light (123): {dict(counts)}")


def idle_flood(proc: subprocess.Popen, port: int) -> None:
    """Phase 7: many idle connections, then a new client."""
    import resource

    soft, hard = resource.getrlimit(resource.RLIMIT_NOFILE)
    wanted = IDLE_CONNECTIONS + 64
    if soft < wanted:
        resource.setrlimit(resource.RLIMIT_NOFILE, (min(wanted, hard), hard))
    count = min(IDLE_CONNECTIONS, resource.getrlimit(resource.RLIMIT_NOFILE)[0] - 64)
    idle = []
    try:
        for _ in range(count):
            idle.append(socket.create_connection(("127.0.0.1", port), timeout=30))
        time.sleep(1.0)
        t0 = time.perf_counter()
        status, _ = raw_request(port, "GET", "/api/options", b"")
        waited = time.perf_counter() - t0
        files = len(os.listdir(f"/proc/{proc.pid}/fd"))
        print(f"{count} idle connections: a new client got {status} in {waited * 1e3:.0f} ms; "
              f"the server holds {files} descriptors")
    finally:
        for sock in idle:
            sock.close()


def kill_nine(proc: subprocess.Popen) -> None:
    """Phase 8: kill -9 of the server; its workers must end with it."""
    import signal

    pids = worker_pids(proc.pid)
    os.kill(proc.pid, signal.SIGKILL)
    proc.wait(10)
    time.sleep(2.0)
    alive = [p for p in pids if os.path.exists(f"/proc/{p}")]
    print(f"kill -9 of the server: {len(alive)} of its {len(pids)} worker processes still alive "
          "2 s later")
    for p in alive:  # this script's own leftovers
        os.kill(p, signal.SIGKILL)


FAIRNESS_ROUNDS = 300
#: A 2 MB JSON body of a million small numbers: decoding it takes tens of milliseconds.
HOSTILE_JSON = (b'{"filename": "a.csv", "content": "x", "pad": ['
                + b"0," * 999_960 + b'0]}')


def drag_model(port: int, rounds: int, token: str) -> tuple[list, collections.Counter]:
    """POST /api/model at 1 nm, the illuminant changing each time, as a dragged slider sends."""
    conn = http.client.HTTPConnection("127.0.0.1", port, timeout=60)
    lat, st = [], collections.Counter()
    for i in range(rounds):
        levels = [10.0 + 10.0 * ((i + k) % 7) / 7 for k in range(301)]
        body = json.dumps({"step_nm": 1, "illuminant": levels}).encode()
        start = time.perf_counter()
        conn.request("POST", "/api/model", body=body, headers={
            "Content-Type": "application/json", "X-Spectrocolor-Client": token})
        response = conn.getresponse()
        response.read()
        lat.append(time.perf_counter() - start)
        st[response.status] += 1
    conn.close()
    return lat, st


def fairness(port: int) -> None:
    """Phase 9: /api/model latency alone and under 2 MB hostile bodies (see the docstring)."""
    drag_model(port, 20, "warming-up-0001")  # the workers' caches, the connection
    t0 = time.perf_counter()
    lat, st = drag_model(port, FAIRNESS_ROUNDS, "the-slider-0001")
    report("model at 1 nm, dragged, alone", lat, st, time.perf_counter() - t0)
    stop, hostile_statuses = threading.Event(), collections.Counter()

    def hostile():
        paths = ("/api/import", "/api/evaluate")
        i = 0
        while not stop.is_set():
            try:
                status, _ = raw_request(port, "POST", paths[i % 2], HOSTILE_JSON)
            except OSError:  # a 413 closes the connection while the body is still being sent
                status = "refused, connection closed"
            hostile_statuses[f"{paths[i % 2]} {status}"] += 1
            i += 1

    attacker = threading.Thread(target=hostile)
    attacker.start()
    time.sleep(0.5)
    t0 = time.perf_counter()
    lat, st = drag_model(port, FAIRNESS_ROUNDS, "the-slider-0001")
    wall = time.perf_counter() - t0
    stop.set()
    attacker.join()
    report("model, dragged, under 2 MB bodies", lat, st, wall)
    print(f"  hostile client: {dict(hostile_statuses)}")


CLASS_STUDENTS, CLASS_SECONDS = 40, 45.0
LOCKSTEP = os.environ.get("CLASS_LOCKSTEP") == "1"
HOSTILE = os.environ.get("CLASS_HOSTILE") == "1"
CLASS_EDIT_S, CLASS_MODEL_S, CLASS_LAB_S, CLASS_PUSH_S = 0.5, 5.0, 1.0, 10.0


def classroom() -> None:
    """Phase 10: a class of CLASS_STUDENTS on a class-mode server (see the module docstring)."""
    proc = subprocess.Popen([sys.executable, "-m", "spectrocolor", "app", "--classroom", "--host",
                             "127.0.0.2", "--port", "0", "--no-browser"],
                            stdout=subprocess.PIPE, text=True)
    text = ""
    while "teacher's page" not in text:
        text += proc.stdout.readline()
    port = int(re.search(r"127\.0\.0\.2:(\d+)/", text).group(1))
    code = re.search(r"code=(\w+)", text).group(1)
    key = re.search(r"key=([\w-]+)", text).group(1)
    teacher = {"Cookie": f"spectrocolor-teacher={key}", "Content-Type": "application/json"}

    def request(conn, method, path, body, headers):
        start = time.perf_counter()
        conn.request(method, path, body=body, headers=headers)
        response = conn.getresponse()
        response.read()
        return time.perf_counter() - start, response.status

    warm = http.client.HTTPConnection("127.0.0.2", port, timeout=120)
    while request(warm, "POST", "/api/model", b"{}", teacher)[1] != 200:
        time.sleep(0.5)
    for body in (b'{"source": {"kind": "named", "name": "A"}}', b'{"film": "oil"}'):
        request(warm, "POST", "/api/lab/light" if b"source" in body else "/api/lab/thinfilm",
                body, teacher)
    before = memory_mib(proc.pid)
    latencies: dict[str, list] = collections.defaultdict(list)
    statuses: collections.Counter = collections.Counter()
    pushes = collections.Counter()
    stop = threading.Event()
    rng = np.random.default_rng(30)

    def listen(i: int, address: str) -> None:
        conn = http.client.HTTPConnection("127.0.0.2", port, timeout=60,
                                          source_address=(address, 0))
        conn.request("GET", "/api/class/events",
                     headers={"Cookie": f"spectrocolor-class={code}"})
        response = conn.getresponse()
        while not stop.is_set():
            line = response.fp.readline()
            if not line:
                break
            if line.startswith(b"event: push"):
                pushes[i] += 1
        conn.close()

    def student(i: int) -> None:
        address = f"127.0.0.{10 + i}"
        headers = {"Cookie": f"spectrocolor-class={code}", "Content-Type": "application/json",
                   "X-Spectrocolor-Client": f"student-tab-{i:04d}"}
        conn = http.client.HTTPConnection("127.0.0.2", port, timeout=60,
                                          source_address=(address, 0))
        in_lab = i % 5 == 4
        levels = list(rng.integers(0, 31, 31).astype(float))
        next_model = time.perf_counter()
        # students do not edit in step: each starts at its own moment within one pause and
        # varies its pauses by +-25 % (CLASS_LOCKSTEP=1 keeps the worst case: all at once)
        jitter = np.random.default_rng(1000 + i)
        if not LOCKSTEP:
            stop.wait(jitter.uniform(0.0, CLASS_LAB_S if in_lab else CLASS_EDIT_S))
        while not stop.is_set():
            start = time.perf_counter()
            if in_lab:
                if i % 2:
                    name = ["A", "D65", "FL2", "F11"][int(start) % 4]
                    route, body = "light", {"source": {"kind": "named", "name": name}}
                else:
                    route, body = "thinfilm", {"film": "oil", "angle_deg": int(start) % 60}
                path, pause = f"/api/lab/{route}", CLASS_LAB_S
            elif start >= next_model:
                route, path, body = "model", "/api/model", {"step_nm": 10}
                next_model, pause = start + CLASS_MODEL_S, CLASS_EDIT_S
            else:
                levels[int(start * 7) % 31] = float(int(start * 13) % 31)  # a dragged bar
                route, path = "evaluate", "/api/evaluate"
                body, pause = {"spectra": [levels, [15.0] * 31], "pairs": [[0, 1]]}, CLASS_EDIT_S
            try:
                seconds, status = request(conn, "POST", path, json.dumps(body).encode(), headers)
            except (OSError, http.client.HTTPException):
                seconds, status = time.perf_counter() - start, "error"
                conn = http.client.HTTPConnection("127.0.0.2", port, timeout=60,
                                                  source_address=(address, 0))
            latencies["labs" if in_lab else "evaluate/model"].append(seconds)
            latencies[route].append(seconds)
            statuses[status] += 1
            pause *= 1.0 if LOCKSTEP else jitter.uniform(0.75, 1.25)
            stop.wait(max(0.0, pause - (time.perf_counter() - start)))
        conn.close()

    hostile_statuses: collections.Counter = collections.Counter()

    def hostile() -> None:
        """CLASS_HOSTILE=1: one more student sends, without pause, the heaviest evaluation the
        server accepts (4 spectra at 1 nm) and a body of 30 000 nested brackets, in turn."""
        address = f"127.0.0.{10 + CLASS_STUDENTS}"
        headers = {"Cookie": f"spectrocolor-class={code}", "Content-Type": "application/json",
                   "X-Spectrocolor-Client": "hostile-tab"}
        heavy = json.dumps({"step_nm": 1, "spectra": [[15.0] * 301] * 4,
                            "pairs": [[0, 1], [2, 3]]}).encode()
        nested = b"[" * 30_000 + b"]" * 30_000
        conn = http.client.HTTPConnection("127.0.0.2", port, timeout=60,
                                          source_address=(address, 0))
        k = 0
        while not stop.is_set():
            body, k = (heavy if k % 2 == 0 else nested), k + 1
            try:
                hostile_statuses[request(conn, "POST", "/api/evaluate", body, headers)[1]] += 1
            except (OSError, http.client.HTTPException):
                hostile_statuses["error"] += 1
                conn = http.client.HTTPConnection("127.0.0.2", port, timeout=60,
                                                  source_address=(address, 0))

    threads = [threading.Thread(target=listen, args=(i, f"127.0.0.{10 + i}"), daemon=True)
               for i in range(CLASS_STUDENTS)]
    threads += [threading.Thread(target=student, args=(i,)) for i in range(CLASS_STUDENTS)]
    if HOSTILE:
        threads.append(threading.Thread(target=hostile))
    t0 = time.perf_counter()
    for t in threads:
        t.start()
    pushed, peak = 0, before["VmRSS"]
    try:
        while time.perf_counter() - t0 < CLASS_SECONDS:
            time.sleep(CLASS_PUSH_S)
            state = json.dumps({"state": f"/?s={1 + pushed % 5}&b=10"}).encode()
            push = http.client.HTTPConnection("127.0.0.2", port, timeout=60)  # (idle ones close)
            pushed += request(push, "POST", "/api/class/push", state, teacher)[1] == 200
            push.close()
            peak = max(peak, memory_mib(proc.pid)["VmRSS"])
        stop.set()
        for t in threads[CLASS_STUDENTS:]:
            t.join()
        wall = time.perf_counter() - t0
        print(f"classroom: {CLASS_STUDENTS} students ({CLASS_STUDENTS // 5} in a lab), "
              f"{'in lockstep' if LOCKSTEP else 'each at its own moment'}, for "
              f"{wall:.0f} s; load average {os.getloadavg()[0]:.1f} on {os.cpu_count()} CPUs")
        for name in ("evaluate/model", "labs", "evaluate", "model", "light", "thinfilm"):
            if latencies[name]:
                report(f"  {name}", latencies[name], {}, wall)
        if HOSTILE:
            print(f"  the hostile student's statuses {dict(hostile_statuses)}")
        print(f"  statuses {dict(statuses)}; pushes sent {pushed}, received per student "
              f"min {min(pushes.values(), default=0)} max {max(pushes.values(), default=0)}")
        after = memory_mib(proc.pid)
        print(f"  server RSS before {before['VmRSS']:.0f} MiB, during (max) {peak:.0f} MiB, "
              f"after {after['VmRSS']:.0f} MiB; workers {after.get('workers_RSS', 0)} MiB")
    finally:
        stop.set()
        proc.terminate()
        proc.wait(10)


def main() -> None:
    if sys.argv[1:] == ["--only", "classroom"]:
        classroom()
        return
    proc, port = start_server()
    if sys.argv[1:] == ["--only", "fairness"]:
        try:
            fairness(port)
        finally:
            proc.terminate()
            proc.wait(10)
        return
    try:
        before = memory_mib(proc.pid)
        print(f"server pid {proc.pid} on 127.0.0.1:{port}; RSS before {before['VmRSS']:.0f} MiB; "
              f"load average {os.getloadavg()[0]:.1f} on {os.cpu_count()} CPUs")

        lat, st, by_name = [], collections.Counter(), {}
        t0 = time.perf_counter()
        client(port, ROUNDS_ONE, lat, st, by_name)
        wall = time.perf_counter() - t0
        report("1 client, keep-alive mix", lat, st, wall)
        for name, seconds in by_name.items():  # req/s here: of this endpoint within the mix
            report(f"  of which {name}", seconds, {}, wall)

        lat, st = [], collections.Counter()
        threads = [threading.Thread(target=client, args=(port, ROUNDS_EACH, lat, st))
                   for _ in range(CLIENTS)]
        t0 = time.perf_counter()
        for t in threads:
            t.start()
        for t in threads:
            t.join()
        report(f"{CLIENTS} clients at once", lat, st, time.perf_counter() - t0)

        results: list = []
        attackers = [threading.Thread(target=hostile_chunked, args=(port, results))
                     for _ in range(4)]
        lat, st = [], collections.Counter()
        t0 = time.perf_counter()
        for t in attackers:
            t.start()
        conn = http.client.HTTPConnection("127.0.0.1", port, timeout=60)
        while any(t.is_alive() for t in attackers) and len(lat) < 5000:
            seconds, status = timed(conn, *BODIES["options"])
            lat.append(seconds)
            st[status] += 1
        for t in attackers:
            t.join()
        report("options during 4 x 50 MiB chunked", lat, st, time.perf_counter() - t0)
        for status, sent in results:
            print(f"  attacker: answered {status}, sent {sent / 2**20:.1f} MiB before the refusal")
        print(f"  server memory now {memory_mib(proc.pid)}")

        conn = http.client.HTTPConnection("127.0.0.1", port, timeout=60)
        rows = "".join(f"{w:.3f},{0.5 + 0.4 * np.sin(w / 37):.6f},{0.3:.6f},{0.8:.6f},{0.1:.6f}\n"
                       for w in np.arange(380.0, 780.001, 0.018))  # about 0.99 MB
        csv_text = "wavelength_nm,a,b,c,d\n" + rows
        assert len(csv_text) < 1_000_000, len(csv_text)  # ImportRequest's content limit
        body = json.dumps({"filename": "big.csv", "content": csv_text, "step_nm": 1}).encode()
        seconds, status = timed(conn, "POST", "/api/import", body)
        print(f"largest import ({len(body) / 1e6:.2f} MB body): {status} in {seconds * 1e3:.0f} ms; "
              f"memory {memory_mib(proc.pid)}")
        big = json.dumps({"step_nm": 1, "spectra": [[15.0] * 301] * 4,
                          "pairs": [[0, 1], [2, 3]]}).encode()
        seconds, status = timed(conn, "POST", "/api/evaluate", big)
        print(f"largest evaluate (4 spectra x 301 bins): {status} in {seconds * 1e3:.0f} ms")

        statuses, lat = collections.Counter(), []

        def importer():
            c = http.client.HTTPConnection("127.0.0.1", port, timeout=120)
            seconds, status = timed(c, "POST", "/api/import", body)
            lat.append(seconds)
            statuses[status] += 1

        workers = [threading.Thread(target=importer) for _ in range(PARALLEL_IMPORTS)]
        probe, probe_statuses = [], collections.Counter()
        t0 = time.perf_counter()
        for t in workers:
            t.start()
        while any(t.is_alive() for t in workers) and len(probe) < 5000:
            seconds, status = timed(conn, *BODIES["options"])
            probe.append(seconds)
            probe_statuses[status] += 1
        for t in workers:
            t.join()
        wall = time.perf_counter() - t0
        report(f"{PARALLEL_IMPORTS} parallel 1 MB imports", lat, statuses, wall)
        report("options during those imports", probe, probe_statuses, wall)

        lat, st = [], collections.Counter()
        t0 = time.perf_counter()
        for i in range(MALFORMED_ROUNDS):
            seconds, status, kind = malformed(port, MALFORMED[i % len(MALFORMED)])
            lat.append(seconds)
            st[f"{status} {kind}"] += 1
        report("malformed HTTP, one per connection", lat, st, time.perf_counter() - t0)

        after = memory_mib(proc.pid)
        print(f"RSS before {before['VmRSS']:.0f} MiB, after {after['VmRSS']:.0f} MiB, "
              f"peak {after['VmHWM']:.0f} MiB; upload workers {after.get('workers_RSS', 0)} MiB "
              f"(peak {after.get('workers_HWM', 0)} MiB); load average {os.getloadavg()[0]:.1f}")

        hostile_phases(proc, port)
        fairness(port)
        idle_flood(proc, port)
        kill_nine(proc)
    finally:
        if proc.poll() is None:
            proc.terminate()
            proc.wait(10)


if __name__ == "__main__":
    main()
