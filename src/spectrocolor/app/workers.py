"""Worker processes for the server's heavy requests (uploaded files, relit photos).

Pure-Python work in a request thread holds the interpreter lock and makes every other client
wait; a hostile input can also exhaust memory, crash a compiled parser or run for minutes.
:class:`WorkerPool` runs such work in at most ``workers`` processes, started with the ``spawn``
method (nothing of the server is copied into them) and kept between jobs, and turns the ways a
job can fail to get an answer into exceptions the caller words for its route:

* :class:`Busy`: no worker freed up within ``wait_s``, or too many jobs already wait;
* :class:`WorkerTimeout`: the job ran longer than ``timeout_s``. Its worker is **killed** at
  once (``SIGKILL``) and a fresh one is started for the next job, so a job that would run for
  minutes costs the pool ``timeout_s`` and no more;
* :class:`WorkerDied`: the worker process stopped (out of memory, a crash in compiled code).

Fairness: jobs wait in one line, first come first served, except that a client (the caller's
``client`` key) never runs more than ``per_client`` jobs at once: its further jobs let other
clients' jobs go first. The server's key is ``(address, token)``: the address the request came
from and the random token its page made (:func:`spectrocolor.app.guards.client_key`), so two
tabs, or a tab and a script on the same machine, are two clients. A token costs nothing to
make, so the jobs of one *address* are capped too (``per_address``), except for the addresses
in ``unlimited_addresses`` (the server gives the loopback ones: a program on the server's own
machine can use that machine's processors in any case, with or without the explorer). At most
``max_waiting`` jobs wait, and at most ``max_waiting_per_client`` of one client or of one
capped address; beyond, :class:`Busy` at once, so a flood of requests from one client cannot
tie up the server's threads nor crowd the others out of the line.

Workers end with the server, however it ends: on Linux each asks the kernel for ``SIGKILL``
when its parent dies (``prctl(PR_SET_PDEATHSIG)``; the kernel ties the signal to the *thread*
that started the process, and request threads come and go, so every worker is started from one
thread that lives as long as the server). Where that is not available (other systems, or
``reaper=True``, or the environment variable :data:`REAPER_VARIABLE` set to ``1``), a *reaper*
does it: a tiny separate process (:data:`_REAPER_SOURCE`, standard library only) that reads the
pids of the workers from a pipe whose other end only the server holds; when the server ends,
however it ends, the system closes that end, the reaper's read returns end-of-file and it kills
every worker still listed. It needs nothing from the workers, so it also ends a worker stuck in
compiled code holding its interpreter lock. On every system a watchdog thread in each worker
also checks twice a second that its parent is still the process that started it (it cannot run
while the worker holds its interpreter lock, hence the two others).

Why this file is long: the pool's admission rules (per client, per address, the waiting line),
its workers' life and the two ways they end with the server are one mechanism; the reaper is
a few lines of it, and each part reads the others' state under one lock.
"""

from __future__ import annotations

import collections
import ctypes
import multiprocessing
import os
import pickle
import queue
import signal
import subprocess
import sys
import threading
import time

__all__ = ["Busy", "WorkerDied", "WorkerPool", "WorkerTimeout", "die_with_parent", "Reaper",
           "REAPER_VARIABLE", "LOOPBACK_ADDRESSES", "HEAVY_NICENESS"]

#: How often a worker's watchdog checks that its parent is alive, s.
WATCHDOG_INTERVAL_S = 0.5
#: How long a worker asked to stop may take before it is killed, s.
STOP_GRACE_S = 2.0
_PR_SET_PDEATHSIG = 1  # <linux/prctl.h>
#: The heavy lanes' workers' niceness (:class:`WorkerPool`'s ``niceness``): under Linux's
#: scheduler a nice-10 process gets about a tenth of a core's time against a nice-0 one, so a
#: class's thin-film tables yield to its dragged sliders instead of sharing the cores evenly.
HEAVY_NICENESS = 10
#: The addresses of the server's own machine (no per-address cap by default).
LOOPBACK_ADDRESSES = ("127.0.0.1", "::1")
#: Set to ``1`` in the server's environment: workers end through a :class:`Reaper` even where the
#: kernel's parent-death signal is available (for tests of the reaper, and for diagnosis).
REAPER_VARIABLE = "SPECTROCOLOR_WORKER_REAPER"


class Busy(Exception):
    """Every worker stayed busy for the whole wait, or too many jobs were already waiting."""


class WorkerTimeout(Exception):
    """The job ran longer than the pool's ``timeout_s``; its worker was killed."""


class WorkerDied(Exception):
    """A worker process stopped during the job (out of memory, a crash in compiled code)."""


def die_with_parent(parent_pid: int, kernel_signal: bool = True) -> None:
    """End this process as soon as the process ``parent_pid`` (its parent) ends, however it ends.

    On Linux the kernel sends ``SIGKILL`` when the parent dies (``PR_SET_PDEATHSIG``); on every
    system a daemon thread checks every :data:`WATCHDOG_INTERVAL_S` that the parent is still
    ``parent_pid`` (an orphan is adopted by another process) and exits at once otherwise. The
    watchdog needs the interpreter lock; the kernel's signal does not, so it also ends a worker
    stuck in a long compiled call.

    Parameters
    ----------
    parent_pid : int
        The parent's process id, as the parent saw it (``os.getpid()`` there).
    kernel_signal : bool
        False where the parent relies on its :class:`Reaper` instead of the kernel's signal.
    """
    if kernel_signal and sys.platform.startswith("linux"):
        try:
            libc = ctypes.CDLL(None, use_errno=True)
            libc.prctl(_PR_SET_PDEATHSIG, int(signal.SIGKILL), 0, 0, 0)
        except (OSError, AttributeError):  # no libc symbol: the watchdog alone
            pass
    if os.getppid() != parent_pid:  # the parent died before the signal was armed
        os._exit(1)
    threading.Thread(target=_watch_parent, args=(parent_pid,), daemon=True,
                     name="spectrocolor-parent-watchdog").start()


def _watch_parent(parent_pid: int) -> None:
    while True:
        time.sleep(WATCHDOG_INTERVAL_S)
        if os.getppid() != parent_pid:
            os._exit(1)


def _serve(connection, parent_pid: int, kernel_signal: bool = True, niceness: int = 0) -> None:
    """A worker's life: run the jobs that arrive on ``connection`` until told to stop."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)  # Ctrl+C is the server's: it closes the pool
    die_with_parent(parent_pid, kernel_signal)
    if niceness > 0 and hasattr(os, "nice"):  # a lower scheduling priority (POSIX only)
        try:
            os.nice(niceness)
        except OSError:
            pass
    while True:
        try:
            message = connection.recv_bytes()
        except (EOFError, OSError):  # the server closed its end
            return
        try:
            job = pickle.loads(message)
            if job is None:
                return
            function, args = job
            answer = (True, function(*args))
        except BaseException as exc:  # noqa: BLE001 - every failure goes back to the caller
            answer = (False, exc)
        try:
            connection.send(answer)
        except Exception as exc:  # noqa: BLE001 - a result or an exception that cannot be pickled
            connection.send((False, RuntimeError(
                f"the worker's answer cannot be sent back ({exc.__class__.__name__})")))


# --- one long-lived thread starts every worker (see the module docstring) ----------------------

_starts: queue.SimpleQueue = queue.SimpleQueue()
_starter_lock = threading.Lock()
_starter: threading.Thread | None = None


def _starter_loop() -> None:
    while True:
        process, done, failure = _starts.get()
        try:
            process.start()
        except BaseException as exc:  # noqa: BLE001 - handed to the thread that asked
            failure.append(exc)
        finally:
            done.set()


def _start_process(process) -> None:
    """Start ``process`` from the starter thread (started on first use), and wait for it."""
    global _starter
    with _starter_lock:
        if _starter is None or not _starter.is_alive():
            _starter = threading.Thread(target=_starter_loop, daemon=True,
                                        name="spectrocolor-worker-starter")
            _starter.start()
    done = threading.Event()
    failure: list[BaseException] = []
    _starts.put((process, done, failure))
    done.wait()
    if failure:
        raise failure[0]


# --- the reaper: workers end with the server without the kernel's parent-death signal --------

#: The reaper's program (standard library only; run with ``python -c``). It keeps the set of
#: worker pids sent as lines ``+pid`` (started) and ``-pid`` (ended) until its standard input
#: reaches end-of-file -- the server's end of the pipe closed, however the server ended -- then
#: kills every pid still in the set.
_REAPER_SOURCE = """
import os, signal, sys
signal.signal(signal.SIGINT, signal.SIG_IGN)
pids = set()
for line in sys.stdin.buffer:
    try:
        pid = int(line[1:])
    except ValueError:
        continue
    (pids.add if line[:1] == b"+" else pids.discard)(pid)
for pid in pids:
    try:
        os.kill(pid, getattr(signal, "SIGKILL", signal.SIGTERM))
    except OSError:
        pass
"""


class Reaper:
    """A separate process that kills the listed workers when the server ends, however it ends.

    The server holds the only write end of the reaper's standard input; the system closes it when
    the server ends (``SIGKILL`` included), and the reaper then kills the workers still listed.
    The reaper is started on first use and again if it has ended.

    Examples
    --------
    >>> reaper = Reaper()
    >>> reaper.add(os.getpid()); reaper.discard(os.getpid())  # listed, then struck off
    >>> reaper.close()  # end-of-file: it kills what is still listed (nothing) and ends
    """

    def __init__(self) -> None:
        self._lock = threading.Lock()
        self._pids: set[int] = set()
        self._process: subprocess.Popen | None = None

    def _send(self, line: bytes) -> None:
        if self._process is None or self._process.poll() is not None:
            self._process = subprocess.Popen(
                [sys.executable, "-c", _REAPER_SOURCE], stdin=subprocess.PIPE,
                stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, start_new_session=True)
            line = b"".join(b"+%d\n" % pid for pid in self._pids) + line
        assert self._process.stdin is not None
        try:
            self._process.stdin.write(line)
            self._process.stdin.flush()
        except OSError:  # the reaper ended meanwhile: the next line starts a new one
            self._process = None

    def add(self, pid: int) -> None:
        """List ``pid``: it is killed when the server ends."""
        with self._lock:
            self._pids.add(pid)
            self._send(b"+%d\n" % pid)

    def discard(self, pid: int) -> None:
        """Strike ``pid`` off (the worker ended), so that a later process with its id is spared."""
        with self._lock:
            if pid in self._pids:
                self._pids.discard(pid)
                self._send(b"-%d\n" % pid)

    @property
    def pid(self) -> int | None:
        """The reaper's process id (None before its first use)."""
        return None if self._process is None else self._process.pid

    def close(self) -> None:
        """End the reaper now (it kills the workers still listed)."""
        with self._lock:
            if self._process is not None:
                if self._process.stdin is not None:
                    self._process.stdin.close()
                self._process.wait(STOP_GRACE_S)
                self._process = None


_reaper_lock = threading.Lock()
_reaper: Reaper | None = None


def _shared_reaper() -> Reaper:
    """The server's one reaper, started on first use."""
    global _reaper
    with _reaper_lock:
        if _reaper is None:
            _reaper = Reaper()
        return _reaper


def _reaper_wanted(reaper: bool | None) -> bool:
    if reaper is not None:
        return reaper
    return os.environ.get(REAPER_VARIABLE) == "1" or not sys.platform.startswith("linux")


class _Worker:
    """One worker process and the server's end of its pipe."""

    def __init__(self, context, reaper: Reaper | None = None, niceness: int = 0) -> None:
        self.connection, child = context.Pipe(duplex=True)
        self.process = context.Process(target=_serve,
                                       args=(child, os.getpid(), reaper is None, niceness),
                                       daemon=True, name="spectrocolor-worker")
        self.reaper = reaper
        try:
            _start_process(self.process)
        finally:
            child.close()
        if reaper is not None and self.process.pid is not None:
            reaper.add(self.process.pid)

    def call(self, function, args: tuple, timeout_s: float):
        """``(True, result)`` or ``(False, exception)``; WorkerTimeout, EOFError or OSError."""
        self.connection.send((function, args))
        if not self.connection.poll(timeout_s):
            raise WorkerTimeout
        return self.connection.recv()

    def kill(self) -> None:
        """End the process now (``SIGKILL``) and reap it."""
        if self.process.is_alive():
            self.process.kill()
        self.process.join(STOP_GRACE_S)
        self.connection.close()
        if self.reaper is not None and self.process.pid is not None and not self.process.is_alive():
            self.reaper.discard(self.process.pid)

    def stop(self) -> None:
        """Ask the process to end; kill it if it does not within :data:`STOP_GRACE_S`."""
        try:
            self.connection.send(None)
        except OSError:
            pass
        self.process.join(STOP_GRACE_S)
        self.kill()


class WorkerPool:
    """At most ``workers`` jobs at once, each in a spawned worker process kept between jobs.

    Parameters
    ----------
    workers : int
        Worker processes, and jobs run at the same time.
    wait_s : float
        How long a job waits for a free worker before :class:`Busy`, s.
    timeout_s : float
        Longest job, s; beyond, its worker is killed and the job ends in :class:`WorkerTimeout`.
    per_client : int, optional
        Most jobs of one client (the ``client`` key of :meth:`run`) running at once; default
        ``workers``.
    max_waiting : int, optional
        Most jobs waiting for a worker; beyond, :class:`Busy` at once. Default ``4 * workers``.
    per_address : int, optional
        Most jobs running at once of all the clients of one address (a client key
        ``(address, token)``; another key is its own address); default ``workers - 1`` (at
        least 1), so that another address always finds a worker.
    max_waiting_per_client : int, optional
        Most jobs waiting of one client, and of one address with a cap; default ``max_waiting``.
    unlimited_addresses : collection, optional
        Addresses without the ``per_address`` cap and the address's share of the waiting line;
        their clients keep their own limits. Default :data:`LOOPBACK_ADDRESSES`: a program on
        the server's own machine can use its processors without the explorer anyway.
    reaper : bool, optional
        Whether a :class:`Reaper` ends the workers with the server (instead of the kernel's
        parent-death signal); default: where that signal is not available, or where the
        environment variable :data:`REAPER_VARIABLE` is ``1``.
    niceness : int, optional
        How much lower than the server's the workers' scheduling priority is (``os.nice``; POSIX
        only, ignored elsewhere). Default 0. The heavy lanes (labs, relit photos, uploads) use
        :data:`HEAVY_NICENESS` so that, on a machine with fewer cores than busy workers, the
        page's interactive requests are scheduled first and a lab's second of work waits.

    Examples
    --------
    >>> pool = WorkerPool(1, wait_s=10.0, timeout_s=60.0)
    >>> pool.run(max, 3, 7)
    7
    >>> pool.close()
    """

    def __init__(self, workers: int, wait_s: float, timeout_s: float, *,
                 per_client: int | None = None, max_waiting: int | None = None,
                 per_address: int | None = None, max_waiting_per_client: int | None = None,
                 unlimited_addresses=None, reaper: bool | None = None, niceness: int = 0):
        self.workers, self.wait_s, self.timeout_s = workers, wait_s, timeout_s
        self.niceness = niceness
        self.per_client = workers if per_client is None else per_client
        self.max_waiting = 4 * workers if max_waiting is None else max_waiting
        self.per_address = max(1, workers - 1) if per_address is None else per_address
        self.max_waiting_per_client = (self.max_waiting if max_waiting_per_client is None
                                       else max_waiting_per_client)
        self.unlimited_addresses = frozenset(LOOPBACK_ADDRESSES if unlimited_addresses is None
                                             else unlimited_addresses)
        self._reaper = _shared_reaper() if _reaper_wanted(reaper) else None
        self._running_by_address: collections.Counter = collections.Counter()
        self._context = multiprocessing.get_context("spawn")
        self._condition = threading.Condition()
        self._idle: list[_Worker] = []
        self._busy: set[_Worker] = set()
        self._waiting: collections.deque[list] = collections.deque()
        self._running_by_client: collections.Counter = collections.Counter()
        self._running = 0
        self._generation = 0  # close() starts a new one: older workers are stopped on return

    # --- admission -----------------------------------------------------------------------

    def _address(self, client):
        """The address whose cap ``client`` counts against, or None (no cap)."""
        address = client[0] if isinstance(client, tuple) and len(client) == 2 else client
        return None if client is _WARMING or address in self.unlimited_addresses else address

    def _startable(self, client) -> bool:
        address = self._address(client)
        return (self._running_by_client[client] < self.per_client
                and (address is None or self._running_by_address[address] < self.per_address))

    def _first_startable(self):
        if self._running >= self.workers:
            return None
        return next((ticket for ticket in self._waiting if self._startable(ticket[0])), None)

    def _line_full(self, client) -> bool:
        """Whether ``client``'s job must be refused at once: the line, or its share, is full."""
        if len(self._waiting) >= self.max_waiting:
            return True
        address = self._address(client)
        mine = sum(1 for ticket in self._waiting if ticket[0] == client)
        ours = 0 if address is None else sum(1 for ticket in self._waiting
                                             if self._address(ticket[0]) == address)
        return max(mine, ours) >= self.max_waiting_per_client

    def _admit(self, client, wait_s: float) -> tuple[_Worker | None, int]:
        with self._condition:
            if self._line_full(client):
                raise Busy
            ticket = [client]
            self._waiting.append(ticket)
            deadline = time.monotonic() + wait_s
            try:
                while self._first_startable() is not ticket:
                    remaining = deadline - time.monotonic()
                    if remaining <= 0:
                        raise Busy
                    self._condition.wait(remaining)
            finally:
                self._waiting.remove(ticket)
                self._condition.notify_all()
            self._running += 1
            self._running_by_client[client] += 1
            self._running_by_address[self._address(client)] += 1
            worker = self._idle.pop() if self._idle else None
            if worker is not None:
                self._busy.add(worker)
            return worker, self._generation

    def _release(self, client, worker: _Worker | None, generation: int) -> None:
        with self._condition:
            self._running -= 1
            self._running_by_client[client] -= 1
            if self._running_by_client[client] <= 0:
                del self._running_by_client[client]
            address = self._address(client)
            self._running_by_address[address] -= 1
            if self._running_by_address[address] <= 0:
                del self._running_by_address[address]
            if worker is not None:
                self._busy.discard(worker)
                if generation == self._generation:
                    self._idle.append(worker)
                    worker = None
            self._condition.notify_all()
        if worker is not None:  # the pool was closed meanwhile
            worker.stop()

    # --- jobs ----------------------------------------------------------------------------

    def run(self, function, *args, client=None):
        """``function(*args)`` in a worker; its exceptions pass through unchanged.

        Parameters
        ----------
        function : callable
            A module-level function (it is pickled to the worker by name).
        *args
            Its arguments (pickled).
        client : hashable, optional, keyword-only
            Who asks, for the per-client limits: the server gives ``(address, token)``
            (:func:`spectrocolor.app.guards.client_key`).

        Raises
        ------
        Busy, WorkerTimeout, WorkerDied
            As described in the module docstring.
        """
        return self._run(function, args, client, self.wait_s)

    def _run(self, function, args: tuple, client, wait_s: float):
        worker, generation = self._admit(client, wait_s)
        try:
            if worker is not None and not worker.process.is_alive():  # died while idle
                with self._condition:
                    self._busy.discard(worker)
                worker.kill()
                worker = None
            if worker is None:
                try:
                    worker = _Worker(self._context, self._reaper, self.niceness)
                except Exception as exc:  # noqa: BLE001 - no descriptors, no memory, ...
                    raise WorkerDied(f"no worker process could be started ({exc.__class__.__name__})") from None
                with self._condition:
                    self._busy.add(worker)
            ok, value = worker.call(function, args, self.timeout_s)
        except WorkerTimeout:
            assert worker is not None  # only worker.call times out
            worker.kill()  # the job is abandoned: nobody else may wait for it
            worker = None
            raise
        except (EOFError, OSError):  # the worker's pipe broke: it died during the job
            if worker is not None:
                worker.kill()
            worker = None
            raise WorkerDied from None
        finally:
            self._release(client, worker, generation)
        if ok:
            return value
        raise value

    def warm(self, function, *args) -> None:
        """Run ``function(*args)`` in a free worker in the background (e.g. to fill its caches).

        Nothing happens if no worker is free at once; failures are ignored.
        """
        def job():
            try:
                self._run(function, args, _WARMING, 0.0)
            except Exception:  # noqa: BLE001 - warming is a courtesy, never an error
                pass

        threading.Thread(target=job, daemon=True, name="spectrocolor-worker-warm").start()

    @property
    def running(self) -> int:
        """How many jobs hold a worker now (at most :attr:`workers`)."""
        with self._condition:
            return self._running

    def worker_pids(self) -> list[int]:
        """Process ids of the live worker processes (idle and busy)."""
        with self._condition:
            workers = [*self._idle, *self._busy]
        return [w.process.pid for w in workers if w.process.pid is not None and w.process.is_alive()]

    def close(self, wait: bool = True) -> None:
        """Stop the worker processes: idle ones are asked to end, busy ones are killed.

        A later job starts new workers. ``wait`` is kept for compatibility: stopping always
        waits at most :data:`STOP_GRACE_S` per worker.
        """
        with self._condition:
            self._generation += 1
            idle, self._idle = self._idle, []
            busy = list(self._busy)
        for worker in idle:
            worker.stop()
        for worker in busy:  # its job ends in WorkerDied, answered to its client
            if worker.process.is_alive():
                worker.process.kill()


_WARMING = object()  # the client key of warm-up jobs: they count against no real client
