"""``make run`` as a new user meets it: what it installs, what it prints, how fast it serves.

* The Makefile (read with ``make -n``, nothing installed): one line per step, only the explorer's
  extras for ``make run``, everything for ``make test``, stamps that let either go first, and
  ``PORT``/``HOST`` passed on.
* The real server, started as ``make run`` starts it (the console script, here on a free port),
  with numba's cache pointed at an empty folder as on a fresh machine: it serves the first page
  while the kernels are still compiling (the answer says ``warming-up``), answers a smoothest
  metamer and a relit photo on the NumPy path with the NumPy path's numbers, says so in the
  ``X-Spectrocolor-Kernels`` header, and leaves no compiling process behind when stopped or
  killed.
* A busy port ends ``make run`` with advice that make can follow: ``make run PORT=…``.

Nothing here is timed: that the page is served before the kernels are ready is read from the
server's own header, and every wait has a generous bound only so that a hang fails.
"""

from __future__ import annotations

import base64
import io
import json
import os
import re
import shutil
import signal
import socket
import subprocess
import sys
import threading
import time
import urllib.error
import urllib.request
from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("fastapi")
pytest.importorskip("uvicorn")

ROOT = Path(__file__).resolve().parents[2]
SCRIPT = Path(sys.executable).with_name("spectrocolor")
VENV = Path(sys.executable).parent.parent
HEADER = "X-Spectrocolor-Kernels"
#: Longest wait for anything the server should do at once (a hang fails here, not a slow run).
PATIENCE_S = 120.0
needs_make = pytest.mark.skipif(shutil.which("make") is None, reason="make is not installed")
linux_only = pytest.mark.skipif(not Path("/proc/self/stat").exists(), reason="reads /proc")


def make_dry_run(*arguments: str, cwd: Path = ROOT) -> list[str]:
    """The commands ``make -n`` would run, one per line."""
    done = subprocess.run(["make", "--no-print-directory", "-n", *arguments], cwd=cwd,
                          capture_output=True, text=True, timeout=60)
    assert done.returncode == 0, done.stderr
    return done.stdout.splitlines()


def fake_venv(folder: Path, *stamps: str) -> Path:
    """A ``.venv`` that make takes as created, with ``stamps`` newer than the project's files."""
    venv = folder / ".venv"
    (venv / "bin").mkdir(parents=True)
    (venv / "bin" / "python").touch()
    later = time.time() + 3600
    for stamp in stamps:
        (venv / stamp).touch()
        os.utime(venv / stamp, (later, later))
    return venv


@needs_make
def test_make_run_from_a_fresh_clone_says_each_step_and_installs_only_the_explorer(tmp_path):
    lines = make_dry_run("run", f"VENV={tmp_path / '.venv'}")
    said = [line for line in lines if line.startswith("echo ")]
    assert len(said) == 2, lines
    assert "creating the environment" in said[0] and "installing the explorer" in said[1]
    installs = [line for line in lines if " install " in line and "-c constraints.txt" in line]
    assert len(installs) == 1 and '".[app,fast]"' in installs[0], installs
    assert "all,test,docs" not in "\n".join(lines)
    assert re.search(r"spectrocolor app --port 8765 --host 127\.0\.0\.1\s*$", lines[-1]), lines[-1]
    assert "SPECTROCOLOR_MAKE_RUN=1" in lines[-1]


@needs_make
def test_make_test_from_a_fresh_clone_installs_everything(tmp_path):
    lines = make_dry_run("test", f"VENV={tmp_path / '.venv'}")
    installs = [line for line in lines if " install " in line and "-c constraints.txt" in line]
    # (a dry run shows the install again under the recursive `make docs`, whose stamp it did not
    # really create)
    assert installs and all('".[all,test,docs]"' in line for line in installs), installs
    assert any("installing everything" in line for line in lines if line.startswith("echo "))


@needs_make
@pytest.mark.parametrize(("stamps", "target", "installs"), [
    ((".installed-all", ".installed-app"), "run", None),     # after make test: run installs nothing
    ((".installed-app",), "run", None),                      # a second make run
    ((".installed-app",), "test", "all,test,docs"),          # make run first, then make test
    ((".installed-all", ".installed-app"), "test", None),    # make test again
])
def test_either_target_may_go_first_and_nothing_installs_twice(tmp_path, stamps, target, installs):
    venv = fake_venv(tmp_path, *stamps)
    lines = make_dry_run(target, f"VENV={venv}")
    found = [line for line in lines if " install " in line and "-c constraints.txt" in line]
    assert not any("creating the environment" in line for line in lines)
    if installs is None:
        assert not found, found
    else:
        assert found and all(installs in line for line in found), found  # (+ `make docs`'s)
        assert any(line.startswith("touch") and ".installed-app" in line for line in lines), \
            "installing everything must leave the explorer's stamp too"


@needs_make
def test_make_run_passes_port_host_and_allow_remote_on(tmp_path):
    venv = fake_venv(tmp_path, ".installed-app")
    assert make_dry_run("run", f"VENV={venv}", "PORT=8766")[-1].split()[-4:] == \
        ["--port", "8766", "--host", "127.0.0.1"]
    assert make_dry_run("run", f"VENV={venv}", "PORT=0", "HOST=::1")[-1].split()[-4:] == \
        ["--port", "0", "--host", "::1"]
    remote = make_dry_run("run", f"VENV={venv}", "HOST=0.0.0.0", "ALLOW_REMOTE=1")[-1]
    assert remote.split()[-3:] == ["--host", "0.0.0.0", "--allow-remote"]


# --- the busy port -------------------------------------------------------------------------------

@pytest.fixture
def busy_port():
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as taken:
        taken.bind(("127.0.0.1", 0))
        taken.listen()
        yield taken.getsockname()[1]


def needs_script():
    if not SCRIPT.exists():
        pytest.skip(f"the console script is not installed next to {sys.executable}")


@needs_make
@pytest.mark.slow
def test_a_busy_port_ends_make_run_with_a_make_command_that_picks_another(busy_port):
    needs_script()
    # -o: take the explorer's stamp as it is (this test installs nothing, whatever the stamp says)
    done = subprocess.run(["make", "--no-print-directory", "-o", f"{VENV}/.installed-app", "run",
                           f"VENV={VENV}", f"PORT={busy_port}"], cwd=ROOT, capture_output=True,
                          text=True, timeout=PATIENCE_S, stdin=subprocess.DEVNULL)
    assert done.returncode != 0
    assert f"port {busy_port} is busy" in done.stderr, done.stderr
    assert re.search(r"`make run PORT=\d+` \(or PORT=0 for any free port\)", done.stderr), done.stderr
    assert "--port" not in done.stderr and "Traceback" not in done.stderr


@pytest.mark.slow
def test_a_busy_port_without_make_names_the_option(busy_port):
    needs_script()
    env = {k: v for k, v in os.environ.items() if k != "SPECTROCOLOR_MAKE_RUN"}
    done = subprocess.run([str(SCRIPT), "app", "--no-browser", "--port", str(busy_port)],
                          capture_output=True, text=True, timeout=PATIENCE_S, env=env,
                          stdin=subprocess.DEVNULL)
    assert done.returncode == 2
    suggested = re.search(r"`spectrocolor app --port (\d+)` \(or --port 0 for any free port\)",
                          done.stderr)
    assert suggested, done.stderr
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as probe:  # the suggestion is free
        probe.bind(("127.0.0.1", int(suggested.group(1))))


# --- the real server on a fresh machine ----------------------------------------------------------

class RunningServer:
    """``spectrocolor app --no-browser --port 0`` in its own session; its lines kept as they come."""

    def __init__(self, cache: Path):
        env = {**os.environ, "NUMBA_CACHE_DIR": str(cache), "PYTHONUNBUFFERED": "1"}
        env.pop("SPECTROCOLOR_NUMBA", None)
        env.pop("SPECTROCOLOR_KERNELS_READY_FILE", None)
        self.process = subprocess.Popen([str(SCRIPT), "app", "--no-browser", "--port", "0"],
                                        stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                                        stdin=subprocess.DEVNULL, text=True, env=env,
                                        start_new_session=True)
        self.lines: list[str] = []
        self._reader = threading.Thread(target=self._read, daemon=True)
        self._reader.start()
        url = self.wait_for_line(r"http://127\.0\.0\.1:\d+/")
        self.url = re.search(r"http://127\.0\.0\.1:\d+/", url).group(0)

    def _read(self):
        for line in self.process.stdout:
            self.lines.append(line.rstrip("\n"))

    def wait_for_line(self, pattern: str) -> str:
        deadline = time.monotonic() + PATIENCE_S
        while time.monotonic() < deadline:
            for line in self.lines:
                if re.search(pattern, line):
                    return line
            assert self.process.poll() is None, "the server stopped:\n" + "\n".join(self.lines)
            time.sleep(0.05)
        raise AssertionError(f"no line matching {pattern!r} in:\n" + "\n".join(self.lines))

    def request(self, path: str, body: dict | None = None):
        """(status, headers, body) of one request; waits while the server is still starting."""
        data = None if body is None else json.dumps(body).encode()
        deadline = time.monotonic() + PATIENCE_S
        while True:
            request = urllib.request.Request(self.url + path.lstrip("/"), data=data,
                                             headers={"Content-Type": "application/json"})
            try:
                with urllib.request.urlopen(request, timeout=PATIENCE_S) as answer:  # noqa: S310
                    return answer.status, answer.headers, answer.read()
            except urllib.error.HTTPError as error:
                return error.code, error.headers, error.read()
            except OSError:  # the socket is bound before the URL is printed; uvicorn starts after
                assert time.monotonic() < deadline and self.process.poll() is None, self.lines
                time.sleep(0.05)

    def compiling_children(self) -> list[int]:
        """Process ids of this server's children that compile the kernels (Linux: /proc)."""
        found = []
        for entry in Path("/proc").iterdir():
            if not entry.name.isdigit():
                continue
            try:
                stat = (entry / "stat").read_text()
                command = (entry / "cmdline").read_bytes()
            except OSError:
                continue
            parent = int(stat.rsplit(")", 1)[1].split()[1])
            if parent == self.process.pid and b"_compile_in_child" in command:
                found.append(int(entry.name))
        return found

    def stop(self, sig=signal.SIGTERM):
        """Send ``sig`` to the server alone (as a user's Ctrl+C or kill would) and wait for it."""
        if self.process.poll() is None:
            self.process.send_signal(sig)
            try:
                self.process.wait(30)
            except subprocess.TimeoutExpired:
                self.process.kill()
                self.process.wait()

    def clean_up(self):
        """Stop the server and anything it left in its session (a test's failure included)."""
        self.stop()
        try:
            os.killpg(self.process.pid, signal.SIGKILL)
        except (ProcessLookupError, PermissionError):
            pass


def gone(pid: int, within_s: float = 30.0) -> bool:
    """Whether process ``pid`` has ended (or is a zombie) within ``within_s`` seconds."""
    deadline = time.monotonic() + within_s
    while time.monotonic() < deadline:
        try:
            state = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()[0]
        except OSError:
            return True
        if state == "Z":
            return True
        time.sleep(0.1)
    return False


@pytest.fixture(scope="module")
def fresh_server(tmp_path_factory):
    """The explorer as ``make run`` starts it, with an empty kernel cache (a fresh machine)."""
    needs_script()
    pytest.importorskip("numba")
    server = RunningServer(tmp_path_factory.mktemp("empty-numba-cache"))
    try:
        yield server
    finally:
        server.clean_up()


@pytest.mark.slow
def test_the_first_page_is_served_while_the_kernels_still_compile(fresh_server):
    status, headers, page = fresh_server.request("/")
    assert status == 200 and b"SPECTRA" in page
    assert headers[HEADER] == "warming-up", "the first page waited for the kernels"
    assert not any("compiled kernels ready" in line for line in fresh_server.lines)
    serving = fresh_server.wait_for_line("serving at http")
    compiling = fresh_server.wait_for_line("compiling kernels in the background")
    assert fresh_server.lines.index(serving) < fresh_server.lines.index(compiling)
    assert "NumPy path" in compiling


def test_a_metamer_during_the_warm_up_is_the_numpy_paths_and_says_so(fresh_server, monkeypatch):
    from spectrocolor.app import compute

    target = [15.0] * 10 + [25.0] * 21
    status, headers, body = fresh_server.request(
        "/api/metamer", {"step_nm": 10, "observer": "1931", "target": target})
    assert status == 200, body
    assert headers[HEADER] == "numpy-path"
    answer = json.loads(body)
    monkeypatch.setenv("SPECTROCOLOR_NUMBA", "0")
    expected = compute.metamer(10.0, "1931", target, None)
    # the same NumPy computation in two processes; 1e-9 of the full level is far above the
    # rounding of its 31-term sums (~31 · 2⁻⁵³ · 30 ≈ 1e-13) and far below any real difference
    np.testing.assert_allclose(answer["levels"], expected["levels"], rtol=0,
                               atol=1e-9 * compute.FULL_LEVEL)
    np.testing.assert_allclose(answer["XYZ_metamer"], answer["XYZ_target"], rtol=1e-9)


@pytest.mark.slow
def test_a_relit_photo_during_the_warm_up_is_the_numpy_paths_and_says_so(fresh_server, monkeypatch):
    pil = pytest.importorskip("PIL.Image")
    from spectrocolor.app.relight_photo import relight_photo

    codes = np.random.default_rng(5).integers(0, 256, size=(6, 9, 3), dtype=np.uint8)
    buffer = io.BytesIO()
    pil.fromarray(codes, "RGB").save(buffer, "PNG")
    image = base64.b64encode(buffer.getvalue()).decode()
    light = [30.0 * (k + 1) / 31 for k in range(31)]  # a warm ramp: colours really change
    status, headers, body = fresh_server.request(
        "/api/relight", {"image": image, "illuminant": light, "step_nm": 10})
    assert status == 200, body
    assert headers[HEADER] == "numpy-path", "the worker process did not report the NumPy path"
    monkeypatch.setenv("SPECTROCOLOR_NUMBA", "0")
    expected = relight_photo(image, light, 10.0, "1931")

    def pixels(answer):
        return np.asarray(pil.open(io.BytesIO(base64.b64decode(answer["relit_png"]))).convert("RGB"),
                          dtype=int)

    got = json.loads(body)
    # the same NumPy computation in two processes: a code may differ by one where a value
    # rounds at .5 under another BLAS kernel, never more
    assert np.abs(pixels(got) - pixels(expected)).max() <= 1
    assert got["outside_solid"] == expected["outside_solid"]


@linux_only
@pytest.mark.slow
def test_stopping_the_server_stops_the_compilation(tmp_path):
    needs_script()
    pytest.importorskip("numba")
    server = RunningServer(tmp_path / "cache")
    try:
        children = []
        deadline = time.monotonic() + PATIENCE_S
        while not children and time.monotonic() < deadline:
            children = server.compiling_children()
            time.sleep(0.05)
        assert len(children) == 1, server.lines
        server.stop(signal.SIGTERM)
        assert gone(children[0]), "the compiling process outlived the server (SIGTERM)"
    finally:
        server.clean_up()


@linux_only
@pytest.mark.slow
def test_a_killed_server_leaves_no_compilation_behind(tmp_path):
    needs_script()
    pytest.importorskip("numba")
    server = RunningServer(tmp_path / "cache")
    try:
        children = []
        deadline = time.monotonic() + PATIENCE_S
        while not children and time.monotonic() < deadline:
            children = server.compiling_children()
            time.sleep(0.05)
        assert len(children) == 1, server.lines
        server.stop(signal.SIGKILL)  # the server alone: its child must notice by itself
        assert gone(children[0]), "the compiling process outlived a killed server"
    finally:
        server.clean_up()


# --- the gate and the report, in this process ---------------------------------------------------

def test_kernels_wait_for_the_ready_file_and_the_note_says_so(tmp_path, monkeypatch):
    pytest.importorskip("numba")
    from spectrocolor.numba_support import READY_FILE_VARIABLE, noting_numpy_path
    from spectrocolor.recovery import compiled as recovery_kernels
    from spectrocolor.upsampling import compiled as upsampling_kernels

    monkeypatch.delenv("SPECTROCOLOR_NUMBA", raising=False)
    ready = tmp_path / "ready"
    monkeypatch.setenv(READY_FILE_VARIABLE, str(ready))
    with noting_numpy_path() as note:
        assert recovery_kernels.kernels() is None and upsampling_kernels.kernels() is None
    assert note.used
    ready.touch()
    with noting_numpy_path() as note:
        assert recovery_kernels.kernels() is not None and upsampling_kernels.kernels() is not None
    assert not note.used


def test_a_failed_compilation_is_reported_with_its_reason(tmp_path):
    from spectrocolor.app.kernels import BackgroundCompilation

    folder = tmp_path / "compilation"
    folder.mkdir()
    with open(folder / "compile.log", "wb") as log:
        child = subprocess.Popen(
            [sys.executable, "-c", "print('numba found no writable cache folder'); raise SystemExit(4)"],
            stdout=log, stderr=subprocess.STDOUT)
    said: list[str] = []
    compilation = BackgroundCompilation(child, str(folder), said.append)
    try:
        assert not compilation.wait(PATIENCE_S)
        assert len(said) == 1 and "failed (exit status 4)" in said[0]
        assert "NumPy path" in said[0] and "no writable cache folder" in said[0]
    finally:
        compilation.stop()
    assert not folder.exists()
