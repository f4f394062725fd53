"""Uploaded spectral files, parsed in worker processes so that other clients are answered meanwhile.

Parsing a large CSV is pure-Python work: in a thread it holds the interpreter lock and every
other request waits (a 1 MB file took the explorer's answers from milliseconds to seconds).
:class:`UploadParser` hands each file to a :class:`~spectrocolor.app.workers.WorkerPool` (spawned
processes, at most ``workers`` files at a time, :class:`Busy` when none frees up within
``wait_s``) and turns everything a hostile file can make a parser raise into one
:class:`SpectrumError`.
"""

from __future__ import annotations

import csv
import tempfile
from pathlib import Path

from ..errors import SpectrumError
from .workers import Busy, WorkerDied, WorkerPool, WorkerTimeout

__all__ = ["Busy", "UploadParser"]

_NAME = "\0upload\0"  # stands for the user's file name in messages made in the worker


def _parse(content: str, suffix: str, step_nm: float, method: str, scale: str,
           max_spectra: int) -> dict:
    """Worker side: write the text to a private temporary file and import it."""
    from . import compute

    with tempfile.TemporaryDirectory(prefix="spectrocolor-") as folder:
        path = Path(folder) / f"upload{suffix}"
        path.write_text(content, encoding="utf-8")
        try:
            return compute.import_spectra(path, step_nm, method, scale, max_spectra=max_spectra)
        except (ValueError, csv.Error, RecursionError, UnicodeError) as exc:
            # SpectrumError, and what a reader lets through on a hostile file (a cell over the
            # csv module's field limit, ...): the file's fault, one line, never a 500
            message = (str(exc) or exc.__class__.__name__).replace(str(path), _NAME)
            message = message.splitlines()[0][:300]
            if not isinstance(exc, SpectrumError):
                message = f"{_NAME}: cannot be read ({message})"
            raise SpectrumError(message) from None


class UploadParser:
    """At most ``workers`` uploads parsed at once, each in a worker process.

    Parameters
    ----------
    workers : int
        Worker processes, and uploads parsed at the same time.
    wait_s : float
        How long an upload waits for a free worker before :class:`Busy`.
    timeout_s : float
        Longest parse; beyond it the upload is refused (the worker finishes in the background).
    """

    def __init__(self, workers: int, wait_s: float, timeout_s: float):
        self._pool = WorkerPool(workers, wait_s, timeout_s)

    def parse(self, filename: str, content: str, suffix: str, step_nm: float, method: str,
              scale: str, max_spectra: int) -> dict:
        """The page's import answer for ``content``; raises SpectrumError or :class:`Busy`."""
        try:
            return self._pool.run(_parse, content, suffix, step_nm, method, scale, max_spectra)
        except SpectrumError as exc:
            raise SpectrumError(str(exc).replace(_NAME, filename)) from None
        except WorkerTimeout:
            raise SpectrumError(f"{filename}: reading it took more than {self._pool.timeout_s:g} s; "
                                "import a smaller file") from None
        except WorkerDied:
            raise SpectrumError(f"{filename}: the reader stopped on this file (out of memory?); "
                                "import a smaller file") from None

    def close(self, wait: bool = True) -> None:
        """Stop the worker processes (a later upload starts new ones)."""
        self._pool.close(wait)
