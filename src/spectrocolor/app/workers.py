"""Worker processes for the server's heavy requests (uploaded files, relit photos).

Pure-Python work in a request thread holds the interpreter lock and makes every other client
wait; a hostile input can also exhaust memory or crash a compiled parser. :class:`WorkerPool`
runs such work in ``workers`` processes, started on first use with the ``spawn`` method (nothing
of the server is copied into them) and kept between requests, lets at most ``workers`` jobs run
at a time, and turns the three ways a job can fail to get an answer into exceptions the caller
words for its route: :class:`Busy` (no worker freed up within ``wait_s``), :class:`WorkerTimeout`
(the job ran longer than ``timeout_s``) and :class:`WorkerDied` (a worker process stopped; the
pool starts afresh on the next job).
"""

from __future__ import annotations

import concurrent.futures
import multiprocessing
import threading
from concurrent.futures.process import BrokenProcessPool

__all__ = ["Busy", "WorkerDied", "WorkerPool", "WorkerTimeout"]


class Busy(Exception):
    """Every worker stayed busy for the whole wait."""


class WorkerTimeout(Exception):
    """The job ran longer than the pool's ``timeout_s`` (it finishes in the background)."""


class WorkerDied(Exception):
    """A worker process stopped during the job (out of memory, a crash in compiled code)."""


class WorkerPool:
    """At most ``workers`` jobs at once, each in a spawned worker process kept between jobs.

    Parameters
    ----------
    workers : int
        Worker processes, and jobs run at the same time.
    wait_s : float
        How long a job waits for a free worker before :class:`Busy`, s.
    timeout_s : float
        Longest job before :class:`WorkerTimeout`, s.

    Examples
    --------
    >>> pool = WorkerPool(1, wait_s=10.0, timeout_s=60.0)
    >>> pool.run(max, 3, 7)
    7
    >>> pool.close()
    """

    def __init__(self, workers: int, wait_s: float, timeout_s: float):
        self.workers, self.wait_s, self.timeout_s = workers, wait_s, timeout_s
        self._slots = threading.BoundedSemaphore(workers)
        self._lock = threading.Lock()
        self._pool: concurrent.futures.ProcessPoolExecutor | None = None

    def _executor(self) -> concurrent.futures.ProcessPoolExecutor:
        with self._lock:
            if self._pool is None:
                self._pool = concurrent.futures.ProcessPoolExecutor(
                    self.workers, mp_context=multiprocessing.get_context("spawn"))
            return self._pool

    def run(self, function, *args):
        """``function(*args)`` in a worker; its exceptions pass through unchanged.

        Raises
        ------
        Busy, WorkerTimeout, WorkerDied
            As described in the module docstring.
        """
        if not self._slots.acquire(timeout=self.wait_s):
            raise Busy
        try:
            return self._executor().submit(function, *args).result(timeout=self.timeout_s)
        except concurrent.futures.TimeoutError:
            raise WorkerTimeout from None
        except BrokenProcessPool:
            self.close(wait=False)  # start afresh on the next job
            raise WorkerDied from None
        finally:
            self._slots.release()

    def warm(self, function, *args) -> None:
        """Start ``function(*args)`` in a worker now, without waiting (e.g. to fill its caches)."""
        try:
            self._executor().submit(function, *args)
        except BrokenProcessPool:
            self.close(wait=False)

    def close(self, wait: bool = True) -> None:
        """Stop the worker processes (a later job starts new ones)."""
        with self._lock:
            pool, self._pool = self._pool, None
        if pool is not None:
            pool.shutdown(wait=wait, cancel_futures=True)
