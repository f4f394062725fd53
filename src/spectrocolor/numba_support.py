"""The optional compiled kernels' switch, decorator and thread rule (numba, extra ``fast``).

Two packages ship numba kernels beside a NumPy path that computes the same thing:
:mod:`spectrocolor.upsampling` (table lookups) and :mod:`spectrocolor.recovery` (the
smoothest-reflectance solvers and their certificate). Both follow the rules kept here:

* the environment variable ``SPECTROCOLOR_NUMBA=0`` (or ``no``, ``off``, ``false``) forces the
  NumPy path, as does a missing numba (:func:`numba_enabled`);
* compiled code is cached (``cache=True``) beside the module or, where that folder is not
  writable, in numba's per-user cache folder (or ``NUMBA_CACHE_DIR``); where neither can be
  written, the kernels are compiled in each process without a cache (:func:`jit`);
* every kernel comes as a (serial, parallel) pair: the parallel one runs numba's ``prange`` on
  ``numba.get_num_threads()`` threads (``NUMBA_NUM_THREADS``) and is used from the main thread;
  from any other thread (dask's worker threads already run chunks in parallel, and numba's
  default threading layer must not be entered from two threads at once) the serial one runs
  (:func:`pick`);
* a process that must not wait for numba to compile (the explorer's server: compiling every
  kernel takes about a minute on a fresh machine) names, in the environment variable
  ``SPECTROCOLOR_KERNELS_READY_FILE``, a file that another process creates once it has compiled
  and cached every kernel. Until that file exists, the kernel modules hand out no kernels
  (:func:`use_compiled` is False) and the NumPy path runs; a computation run inside
  :func:`noting_numpy_path` learns whether it took the NumPy path for that reason, so that its
  result can say so. Where the variable is not set, kernels compile on first use as always.

Examples
--------
>>> pick(("serial", "parallel"))
'parallel'
"""

from __future__ import annotations

import contextvars
import os
import threading
from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass

__all__ = ["READY_FILE_VARIABLE", "NumpyPathNote", "call_noting_numpy_path", "jit", "kernels_ready",
           "note_numpy_path", "noting_numpy_path", "numba_enabled", "pick", "use_compiled"]

#: Environment variable naming the file whose existence says that every kernel is compiled and
#: cached; while it is set and the file is missing, the NumPy path runs (:func:`kernels_ready`).
READY_FILE_VARIABLE = "SPECTROCOLOR_KERNELS_READY_FILE"


def numba_enabled() -> bool:
    """False where ``SPECTROCOLOR_NUMBA`` is ``0``, ``no``, ``off`` or ``false``.

    Whether numba is installed is each kernel module's import to find out.

    Returns
    -------
    bool

    Examples
    --------
    >>> isinstance(numba_enabled(), bool)
    True
    """
    return os.environ.get("SPECTROCOLOR_NUMBA", "1").strip().lower() not in ("0", "no", "off",
                                                                             "false")


def kernels_ready() -> bool:
    """False while ``SPECTROCOLOR_KERNELS_READY_FILE`` names a file that does not exist yet.

    Once the file has been seen it is not looked for again: kernels, once compiled and
    cached, stay so for the life of the process.

    Returns
    -------
    bool
        True where the variable is not set (kernels compile on first use), or once its file
        exists.

    Examples
    --------
    >>> import os, tempfile
    >>> ready = os.path.join(tempfile.mkdtemp(), "ready")
    >>> os.environ[READY_FILE_VARIABLE] = ready
    >>> kernels_ready()
    False
    >>> open(ready, "w").close()
    >>> kernels_ready()
    True
    >>> del os.environ[READY_FILE_VARIABLE]
    """
    path = os.environ.get(READY_FILE_VARIABLE)
    if not path or path in _seen_ready_files:
        return True
    if os.path.exists(path):
        _seen_ready_files.add(path)
        return True
    return False


_seen_ready_files: set[str] = set()


@dataclass
class NumpyPathNote:
    """Whether a computation took the NumPy path because the compiled kernels were not ready.

    Attributes
    ----------
    used : bool
        True once any kernel module ran its NumPy path for that reason.
    """

    used: bool = False


_note: contextvars.ContextVar[NumpyPathNote | None] = contextvars.ContextVar(
    "spectrocolor_numpy_path_note", default=None)


@contextmanager
def noting_numpy_path() -> Iterator[NumpyPathNote]:
    """Note whether the code run inside takes the NumPy path while the kernels are not ready.

    The note travels with the context (:mod:`contextvars`): into threads that copy it, as a
    web framework's thread pool does, but not into other processes (see
    :func:`call_noting_numpy_path`).

    Yields
    ------
    NumpyPathNote

    Examples
    --------
    >>> with noting_numpy_path() as note:
    ...     pass
    >>> note.used
    False
    """
    note = NumpyPathNote()
    token = _note.set(note)
    try:
        yield note
    finally:
        _note.reset(token)


def note_numpy_path() -> None:
    """Mark the current :func:`noting_numpy_path` note as used (nothing outside one).

    For a result computed elsewhere, e.g. in a worker process that reported it
    (:func:`call_noting_numpy_path`).

    Examples
    --------
    >>> with noting_numpy_path() as note:
    ...     note_numpy_path()
    >>> note.used
    True
    """
    note = _note.get()
    if note is not None:
        note.used = True


def call_noting_numpy_path(function, *args):
    """``function(*args)`` and whether it took the NumPy path while the kernels were not ready.

    A picklable top-level function, for running work in another process and reporting back.

    Parameters
    ----------
    function : callable
    *args
        Its arguments.

    Returns
    -------
    result : object
        What ``function`` returned.
    used_numpy_path : bool

    Examples
    --------
    >>> call_noting_numpy_path(max, 3, 7)
    (7, False)
    """
    with noting_numpy_path() as note:
        result = function(*args)
    return result, note.used


def use_compiled() -> bool:
    """Whether a kernel module should hand out its compiled kernels now.

    False with ``SPECTROCOLOR_NUMBA=0`` (:func:`numba_enabled`), and while the kernels are not
    ready (:func:`kernels_ready`); in the second case the current :func:`noting_numpy_path`
    note is marked. Whether numba is installed is each kernel module's import to find out.

    Returns
    -------
    bool

    Examples
    --------
    >>> isinstance(use_compiled(), bool)
    True
    """
    if not numba_enabled():
        return False
    if kernels_ready():
        return True
    note_numpy_path()
    return False


def jit(**options):
    """``numba.njit(cache=True, **options)``, without the cache where no cache folder is writable.

    Parameters
    ----------
    **options
        Passed to :func:`numba.njit` (``parallel=True``, ``inline="always"``, ...).

    Returns
    -------
    callable
        A decorator.

    Examples
    --------
    Code typed at a prompt has no file to cache beside, so this compiles without a cache:

    >>> try:
    ...     import numba
    ... except ImportError:  # the extra "fast" is not installed
    ...     numba = None
    >>> numba is None or jit()(lambda x: 2 * x)(21) == 42
    True
    """
    import numba

    def decorate(function):
        try:
            return numba.njit(cache=True, **options)(function)
        except RuntimeError:  # "cannot cache function ...: no locator available for file ..."
            return numba.njit(cache=False, **options)(function)
    return decorate


def pick(pair):
    """The parallel member of a (serial, parallel) pair on the main thread, else the serial one.

    Parameters
    ----------
    pair : tuple
        ``(serial, parallel)`` kernels.

    Returns
    -------
    object
        One member of ``pair``.

    Examples
    --------
    >>> import threading
    >>> found = []
    >>> worker = threading.Thread(target=lambda: found.append(pick(("serial", "parallel"))))
    >>> worker.start(); worker.join()
    >>> found
    ['serial']
    """
    return pair[threading.current_thread() is threading.main_thread()]
