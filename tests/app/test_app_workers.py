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

from spectrocolor.app.workers import Busy, WorkerDied, WorkerPool, WorkerTimeout

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
