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
  (:func:`pick`).

Examples
--------
>>> pick(("serial", "parallel"))
'parallel'
"""

from __future__ import annotations

import os
import threading

__all__ = ["jit", "numba_enabled", "pick"]


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
