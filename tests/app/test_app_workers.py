"""The worker pool: a job past its time limit is ended, workers die with their parent, fairness.

The jobs are standard-library functions (a worker imports nothing of the tests): ``time.sleep``
for a job that waits, a catastrophic regular expression for one that holds the processor inside
compiled code (where no Python-level watchdog can run), ``os._exit`` for a worker that dies.
"""

from __future__ import annotations

import os
import re
import signal
import subprocess
import sys
import textwrap
import threading
import time

import pytest

from spectrocolor.app.workers import HEAVY_NICENESS, Busy, WorkerDied, WorkerPool, WorkerTimeout

#: ``re.match(CATASTROPHIC, "a" * 40)`` backtracks 2**40 times in C: hours, holding the GIL.
CATASTROPHIC = re.compile(r"(a+)+b")


def gone(pid: int, within_s: float = 10.0) -> bool:
    """Whether process ``pid`` has ended (or is a zombie) within ``within_s`` seconds."""
    deadline = time.monotonic() + within_s
    while time.monotonic() < deadline:
        try:
            with open(f"/proc/{pid}/stat") as handle:
                state = handle.read().rsplit(")", 1)[1].split()[0]
        except FileNotFoundError:
            return True
        if state in ("Z", "X"):
            return True
        time.sleep(0.05)
    return False


@pytest.fixture
def pool():
    pool = WorkerPool(2, wait_s=10.0, timeout_s=2.0)
    yield pool
    pool.close()


pytestmark = pytest.mark.skipif(not sys.platform.startswith("linux"), reason="reads /proc")


def test_a_job_past_its_time_limit_is_killed_and_the_worker_replaced(pool):
    first = pool.run(os.getpid)
    with pytest.raises(WorkerTimeout):
        pool.run(CATASTROPHIC.match, "a" * 40)  # stuck in C with the GIL held
    assert gone(first, within_s=5.0), "the timed-out worker is still running"
    assert first not in pool.worker_pids()
    second = pool.run(os.getpid)  # the next job gets a fresh worker at once
    assert second != first


def test_a_timed_out_job_charges_nobody_else(pool):
    """While one client's job runs past its limit, another's runs in the other worker."""
    failures = []

    def hostile():
        try:
            pool.run(time.sleep, 30, client="hostile")
        except WorkerTimeout:
            failures.append("timeout")

    thread = threading.Thread(target=hostile)
    thread.start()
    time.sleep(0.2)
    assert pool.run(max, 3, 7, client="other") == 7
    thread.join(30)
    assert failures == ["timeout"]
    assert pool.run(max, 1, 2, client="other") == 2  # and the pool is whole afterwards


@pytest.mark.slow
def test_one_client_never_fills_the_pool():
    """With one job per client, a client's second job waits and another client's goes first."""
    pool = WorkerPool(2, wait_s=30.0, timeout_s=30.0, per_client=1)
    finished: list[str] = []
    try:
        starters = [threading.Thread(target=pool.run, args=(time.sleep, 0.5), kwargs={"client": c})
                    for c in ("a", "b")]
        for thread in starters:  # start both workers first, so that no job waits for a start
            thread.start()
        for thread in starters:
            thread.join(60)

        def greedy():
            pool.run(time.sleep, 3.0, client="greedy")
            finished.append("greedy")

        threads = [threading.Thread(target=greedy) for _ in range(2)]
        for thread in threads:
            thread.start()
        time.sleep(0.3)  # the greedy client runs one job; its second waits though a worker is free
        assert pool.run(max, 1, 2, client="polite") == 2
        finished.append("polite")
        for thread in threads:
            thread.join(60)
        assert finished[0] == "polite", finished  # before either of the greedy client's jobs
    finally:
        pool.close()


def test_too_many_waiting_jobs_are_refused_at_once():
    pool = WorkerPool(1, wait_s=30.0, timeout_s=10.0, max_waiting=1)
    try:
        running = threading.Thread(target=lambda: pool.run(time.sleep, 1.0))
        running.start()
        time.sleep(0.5)
        waiting = threading.Thread(target=lambda: pool.run(time.sleep, 0.0))
        waiting.start()
        time.sleep(0.2)
        started = time.monotonic()
        with pytest.raises(Busy):
            pool.run(max, 1, 2)
        assert time.monotonic() - started < pool.wait_s / 2  # refused at once, not after the wait
        running.join(30)
        waiting.join(30)
    finally:
        pool.close()


def test_a_worker_that_dies_is_replaced(pool):
    with pytest.raises(WorkerDied):
        pool.run(os._exit, 3)
    assert pool.run(max, 4, 5) == 5


def test_exceptions_pass_through(pool):
    with pytest.raises(ValueError, match="invalid literal"):
        pool.run(int, "x")


PARENT = textwrap.dedent("""
    import os, sys, time
    from spectrocolor.app.workers import WorkerPool
    if __name__ == "__main__":
        import threading
        pool = WorkerPool(2, wait_s=10.0, timeout_s=600.0)
        for _ in range(2):  # both workers busy in a job that would last 10 minutes
            threading.Thread(target=pool.run, args=(time.sleep, 600), daemon=True).start()
        for _ in range(600):
            if len(pool.worker_pids()) == 2:
                break
            time.sleep(0.05)
        time.sleep(0.5)  # the jobs have reached the workers
        print(" ".join(map(str, pool.worker_pids())), flush=True)
        time.sleep(600)
""")


@pytest.mark.parametrize("how", [signal.SIGKILL, signal.SIGTERM])
def test_workers_end_with_their_parent_however_it_ends(tmp_path, how):
    script = tmp_path / "parent.py"
    script.write_text(PARENT)
    parent = subprocess.Popen([sys.executable, str(script)], stdout=subprocess.PIPE, text=True)
    try:
        workers = [int(pid) for pid in parent.stdout.readline().split()]
        assert len(workers) == 2, workers
        os.kill(parent.pid, how)
        parent.wait(10)
        for pid in workers:
            assert gone(pid), f"worker {pid} outlived its parent ({how.name})"
    finally:
        parent.kill()
        parent.wait(10)


# --- client keys: (address, token), with a cap per address (issue 31) -------------------------

def _running_together(pool: WorkerPool, clients: list) -> int:
    """How many of ``clients``' 1 s jobs, all started at once, the pool runs at the same time."""
    threads = [threading.Thread(target=pool.run, args=(time.sleep, 1.0), kwargs={"client": c})
               for c in clients]
    for thread in threads:
        thread.start()
    most = 0
    for _ in range(30):  # 0.6 s: the workers started (first use) and the jobs were admitted
        most = max(most, pool.running)
        time.sleep(0.02)
    for thread in threads:
        thread.join(60)
    return most


@pytest.mark.slow
def test_two_tabs_of_one_machine_are_two_clients():
    """Two tokens from the loopback address run at once; one token's two jobs do not."""
    pool = WorkerPool(2, wait_s=30.0, timeout_s=30.0, per_client=1)
    try:
        pool.run(max, 1, 2, client=("127.0.0.1", "warm-a"))  # start the workers first
        _running_together(pool, [("127.0.0.1", "w1"), ("127.0.0.1", "w2")])
        assert _running_together(pool, [("127.0.0.1", "tab-a"), ("127.0.0.1", "tab-b")]) == 2
        assert _running_together(pool, [("127.0.0.1", "tab-a"), ("127.0.0.1", "tab-a")]) == 1
    finally:
        pool.close()


@pytest.mark.slow
def test_rotating_tokens_from_one_remote_address_cannot_fill_the_pool():
    """A remote address is capped whatever tokens it sends; another address still gets a worker."""
    pool = WorkerPool(2, wait_s=30.0, timeout_s=30.0, per_client=1)
    try:
        _running_together(pool, [("127.0.0.1", "w1"), ("127.0.0.1", "w2")])  # start both workers
        assert _running_together(pool, [("203.0.113.7", f"token-{i}") for i in range(4)]) == 1
        finished: list[str] = []

        def rotating(i):
            pool.run(time.sleep, 1.5, client=("203.0.113.7", f"rotating-{i}"))
            finished.append("rotating")

        threads = [threading.Thread(target=rotating, args=(i,)) for i in range(3)]
        for thread in threads:
            thread.start()
        time.sleep(0.3)
        assert pool.run(max, 1, 2, client=("198.51.100.2", "other")) == 2
        finished.append("other")
        for thread in threads:
            thread.join(60)
        assert finished[0] == "other", finished  # not behind the rotating tokens' jobs
    finally:
        pool.close()


def test_one_client_cannot_fill_the_waiting_line():
    """Past its share of the line a client is refused at once; another client still waits."""
    pool = WorkerPool(1, wait_s=30.0, timeout_s=10.0, max_waiting=8, max_waiting_per_client=2)
    try:
        threads = [threading.Thread(target=pool.run, args=(time.sleep, 0.8),
                                    kwargs={"client": ("127.0.0.1", "greedy")})
                   for _ in range(3)]  # one runs, two wait
        for thread in threads:
            thread.start()
            time.sleep(0.1)
        started = time.monotonic()
        with pytest.raises(Busy):
            pool.run(max, 1, 2, client=("127.0.0.1", "greedy"))
        assert time.monotonic() - started < 1.0  # refused at once
        assert pool.run(max, 1, 2, client=("127.0.0.1", "polite")) == 2  # waited its turn
        for thread in threads:
            thread.join(60)
    finally:
        pool.close()


# --- the reaper: workers end with the server without the kernel's parent-death signal ----------

REAPED_PARENT = textwrap.dedent("""
    import os, re, sys, time, threading
    from spectrocolor.app.workers import WorkerPool
    if __name__ == "__main__":
        pool = WorkerPool(2, wait_s=10.0, timeout_s=600.0, reaper=%s)
        pattern = re.compile(r"(a+)+b")
        for _ in range(2):  # both workers stuck in C, holding their interpreter lock, for hours
            threading.Thread(target=pool.run, args=(pattern.match, "a" * 40), daemon=True).start()
        for _ in range(600):
            if len(pool.worker_pids()) == 2:
                break
            time.sleep(0.05)
        time.sleep(1.0)  # the jobs have reached the workers
        print(" ".join(map(str, pool.worker_pids())), pool._reaper.pid, flush=True)
        time.sleep(600)
""")


def _cpu_ticks(pid: int) -> int:
    with open(f"/proc/{pid}/stat") as handle:
        fields = handle.read().rsplit(")", 1)[1].split()
    return int(fields[11]) + int(fields[12])  # utime + stime (fields 14 and 15 of stat)


@pytest.mark.parametrize("how", ["argument", "environment"])
def test_the_reaper_ends_workers_stuck_in_c_when_the_server_is_killed(tmp_path, how):
    """Forced fallback (no PR_SET_PDEATHSIG): kill -9 of the parent, the workers still go."""
    script = tmp_path / "parent.py"
    script.write_text(REAPED_PARENT % ("True" if how == "argument" else "None"))
    env = {**os.environ}
    if how == "environment":
        env["SPECTROCOLOR_WORKER_REAPER"] = "1"
    parent = subprocess.Popen([sys.executable, str(script)], stdout=subprocess.PIPE, text=True,
                              env=env)
    try:
        *workers, reaper = (int(pid) for pid in parent.stdout.readline().split())
        assert len(workers) == 2, workers
        ticks = [_cpu_ticks(pid) for pid in workers]
        time.sleep(0.5)
        assert all(_cpu_ticks(pid) > t for pid, t in zip(workers, ticks, strict=True)), "not busy in C"
        os.kill(parent.pid, signal.SIGKILL)
        parent.wait(10)
        for pid in workers:
            assert gone(pid, within_s=5.0), f"worker {pid} outlived its killed parent"
        assert gone(reaper, within_s=5.0), "the reaper outlived its work"
    finally:
        parent.kill()
        parent.wait(10)


@pytest.mark.skipif(not hasattr(os, "nice"), reason="os.nice is POSIX only")
def test_heavy_lanes_run_at_a_lower_priority_than_the_server():
    """A pool's ``niceness`` lowers its workers' priority (by exactly that much, capped at 19),
    and the heavy lanes (labs, relit photos, uploads) use it while the interactive lane does not:
    on two cores a class's thin-film tables must yield to dragged sliders."""
    from spectrocolor.app import lab_routes, relight_routes, server
    from spectrocolor.app.uploads import UploadParser

    mine = os.nice(0)
    heavy = WorkerPool(1, wait_s=10.0, timeout_s=60.0, niceness=HEAVY_NICENESS)
    plain = WorkerPool(1, wait_s=10.0, timeout_s=60.0)
    try:
        assert heavy.run(os.nice, 0) == min(19, mine + HEAVY_NICENESS)
        assert plain.run(os.nice, 0) == mine
    finally:
        heavy.close()
        plain.close()
    assert HEAVY_NICENESS > 0
    assert lab_routes._workers.niceness == HEAVY_NICENESS
    assert relight_routes._workers.niceness == HEAVY_NICENESS
    parser = UploadParser(1, wait_s=10.0, timeout_s=60.0)  # (the server builds one per app)
    try:
        assert parser.pool.niceness == HEAVY_NICENESS
    finally:
        parser.close()
    assert server._interactive.niceness == 0
