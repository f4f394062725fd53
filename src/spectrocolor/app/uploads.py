"""Uploaded spectral files, parsed in worker processes so that other clients are answered meanwhile.

Parsing a large CSV is pure-Python work: in a thread it holds the interpreter lock and every
other request waits (a 1 MB file took the explorer's answers from milliseconds to seconds).
:class:`UploadParser` hands each file to a :class:`~spectrocolor.app.workers.WorkerPool` (spawned
processes, at most ``workers`` files at a time, one per client address, :class:`Busy` when none
frees up within ``wait_s``; a parse that runs past ``timeout_s`` has its worker killed) and turns
everything a hostile file can make a parser raise into one :class:`SpectrumError`.

The text is written to a private temporary folder that the server creates and removes, so a
worker killed in the middle of a parse leaves nothing behind.
"""

from __future__ import annotations

import csv
import tempfile
from pathlib import Path

import numpy as np

from ..errors import SpectrumError
from .workers import HEAVY_NICENESS, Busy, WorkerDied, WorkerPool, WorkerTimeout

__all__ = ["Busy", "UploadParser"]

_NAME = "\0upload\0"  # stands for the user's file name in messages made in the worker


def _parse(folder: str, content: str | bytes, suffix: str, step_nm: float, method: str, scale: str,
           max_spectra: int, observer: str | None = None) -> dict:
    """Worker side: write the file to the server's temporary ``folder`` and import it.

    Bytes are written as they came, so :func:`spectrocolor.read_spectra` decodes them as it
    decodes any file (BOM, UTF-8, else cp1252 where unambiguous); text is written as UTF-8.
    """
    from . import compute

    path = Path(folder) / f"upload{suffix}"
    if isinstance(content, bytes):
        path.write_bytes(content)
    else:
        path.write_text(content, encoding="utf-8")
    try:
        answer = compute.import_spectra(path, step_nm, method, scale, max_spectra=max_spectra)
        if not np.all(np.isfinite(np.asarray(answer["levels"], dtype=float))):
            raise SpectrumError(f"{_NAME}: its values are too large to scale and resample (they "
                                "go beyond the float range); import values such as 0-1 or 0-100")
        return _with_conditions(answer, observer)
    except (ValueError, csv.Error, RecursionError, UnicodeError, MemoryError) as exc:
        # SpectrumError, and what a reader lets through on a hostile file (a cell over the
        # csv module's field limit, ...): the file's fault, one line, never a 500
        message = (str(exc) or exc.__class__.__name__).replace(str(path), _NAME)
        message = (message.splitlines() or [exc.__class__.__name__])[0][:300]
        if isinstance(exc, MemoryError):
            message = f"{_NAME}: too large to read in the memory available"
        elif not isinstance(exc, SpectrumError):
            message = f"{_NAME}: cannot be read ({message})"
        raise SpectrumError(message) from None


def declared_note(metadata: dict, observer: str | None) -> str:
    """One line on what the file declares and what the page computes under, or ``""``.

    The explorer's light is the one in its illuminant editor and its observer the page's choice,
    so a file's declared illuminant/observer is reported, never silently dropped.

    Examples
    --------
    >>> declared_note({"declared_illuminant": "D50", "declared_observer": "CIE 1931 2°"}, "1964")  # doctest: +ELLIPSIS
    'the file declares D50/2°; the page computes under its own light and the CIE 1964 10° observer, as ...'
    >>> declared_note({}, "1931")
    ''
    """
    from ..io.conditions import declared_conditions
    from ..observers import resolve_observer
    from ..spectrum import Spectrum

    declared = declared_conditions(Spectrum([400.0, 700.0], [0.0, 0.0], metadata=metadata))
    if not declared:
        return ""
    viewer = resolve_observer(observer or "1931").name
    return (f"the file declares {declared.label}; the page computes under its own light and the {viewer} "
            "observer, as chosen on the page")


def _with_conditions(answer: dict, observer: str | None) -> dict:
    """The answer with the file's encoding and declared conditions in ``metadata`` and the note."""
    metadata = dict(answer.get("metadata", {}))
    note = declared_note(metadata, observer)
    if note:
        metadata["conditions_note"] = note
    encoding = metadata.get("encoding")
    said = [answer["note"]]
    if encoding:
        said.append(f"encoding {encoding}")
    if note:
        said.append(note)
    return {**answer, "metadata": metadata, "note": "; ".join(said)}


class UploadParser:
    """At most ``workers`` uploads parsed at once, each in a worker process.

    Parameters
    ----------
    workers : int
        Worker processes, and uploads parsed at the same time.
    wait_s : float
        How long an upload waits for a free worker before :class:`Busy`.
    timeout_s : float
        Longest parse; beyond it the worker is killed and the upload refused.
    per_client : int, default 1
        Uploads of one client address parsed at the same time (its others wait their turn).
    """

    def __init__(self, workers: int, wait_s: float, timeout_s: float, per_client: int = 1):
        self._pool = WorkerPool(workers, wait_s, timeout_s, per_client=per_client,
                                niceness=HEAVY_NICENESS)

    @property
    def pool(self) -> WorkerPool:
        """The worker pool (its processes' ids, for tests and diagnostics)."""
        return self._pool

    def parse(self, filename: str, content: str | bytes, suffix: str, step_nm: float, method: str,
              scale: str, max_spectra: int, client=None, observer: str | None = None) -> dict:
        """The page's import answer for ``content`` (the file's bytes, or text); raises
        SpectrumError or :class:`Busy`.

        ``client`` (the client's address) is the key of the per-client limit; ``observer`` (the
        page's) goes into the note on the file's declared conditions. The answer's
        ``metadata`` holds the encoding used and what the file declares (``declared_*``,
        ``conditions_note``).
        """
        with tempfile.TemporaryDirectory(prefix="spectrocolor-upload-") as folder:
            try:
                return self._pool.run(_parse, folder, content, suffix, step_nm, method, scale,
                                      max_spectra, observer, client=client)
            except SpectrumError as exc:
                raise SpectrumError(str(exc).replace(_NAME, filename)) from None
            except WorkerTimeout:
                raise SpectrumError(f"{filename}: reading it took more than "
                                    f"{self._pool.timeout_s:g} s and was stopped; import a "
                                    "smaller file") from None
            except WorkerDied:
                raise SpectrumError(f"{filename}: the reader stopped on this file (out of "
                                    "memory?); import a smaller file") from None

    def close(self, wait: bool = True) -> None:
        """Stop the worker processes (a later upload starts new ones)."""
        self._pool.close(wait)
