"""The explorer's compiled kernels: compiled in the background, the NumPy path meanwhile.

On a fresh machine numba takes about a minute (longer under load) to compile the library's
kernels (:mod:`spectrocolor.recovery.warmup`, :mod:`spectrocolor.upsampling.warmup`); a
server that compiled them before serving, or in the first request that needs them, would look
hung. Instead ``spectrocolor app`` starts a :class:`BackgroundCompilation`: a child process, at
a lower priority so that requests keep the processor, compiles every kernel into numba's cache
and then creates a *ready file*. The server and its worker processes name that file in
``SPECTROCOLOR_KERNELS_READY_FILE`` (:func:`spectrocolor.numba_support.kernels_ready`) and run the
NumPy path -- the same numbers, to rounding -- until it exists; then they load the kernels from
the cache, in about a second. A later start finds the kernels cached and is ready in a few
seconds.

:class:`KernelStatusHeader` tells the page: each HTTP response carries
``X-Spectrocolor-Kernels: numpy-path`` when its result took the NumPy path because the kernels
were not ready yet, ``warming-up`` while they are being compiled and the response needed none,
and no such header once they are ready (or where none are in use); the page shows a note for
``numpy-path`` and hides it again once the header is gone.
"""

from __future__ import annotations

import glob
import importlib.util
import os
import shutil
import subprocess
import sys
import tempfile
import threading
import time
from collections.abc import Callable

from ..numba_support import READY_FILE_VARIABLE, kernels_ready, noting_numpy_path, numba_enabled

__all__ = ["HEADER", "BackgroundCompilation", "KernelStatusHeader", "compile_every_kernel",
           "uncached_kernels"]

#: The response header that says whether a result used the NumPy path (see the module docstring).
HEADER = "X-Spectrocolor-Kernels"

#: What the child process runs: ``_compile_in_child(ready_file, parent_pid)``.
_CHILD = ("import sys; from spectrocolor.app.kernels import _compile_in_child; "
          "sys.exit(_compile_in_child(sys.argv[1], int(sys.argv[2])))")
#: How often the child checks that the server that started it still runs, s.
_PARENT_CHECK_S = 0.5
#: Temporary folders of compilations: ``<prefix><server's pid>-<random>``.
_FOLDER_PREFIX = "spectrocolor-kernels-"


def compile_every_kernel() -> bool:
    """Compile (or load from numba's cache) every kernel of the library, in this process.

    Returns
    -------
    bool
        Whether the kernels are in use (False without numba or with ``SPECTROCOLOR_NUMBA=0``).
    """
    from ..recovery import warmup as recovery_kernels
    from ..upsampling import warmup as upsampling_kernels

    recovery = recovery_kernels.warm_up()
    upsampling = upsampling_kernels.warm_up()
    return recovery or upsampling


def uncached_kernels() -> list[str]:
    """The kernels that numba compiled without a cache (no writable cache folder), by name.

    Such kernels would be compiled again in the server, on first use: a background compilation
    is no use for them.

    Returns
    -------
    list of str
        ``module.function`` names; empty where every kernel is cached, or without numba.
    """
    try:
        from numba.core.caching import NullCache

        from ..recovery import numba_kernels as recovery_kernels
        from ..upsampling import numba_kernels as upsampling_kernels
    except ImportError:
        return []
    return [f"{module.__name__}.{name}" for module in (recovery_kernels, upsampling_kernels)
            for name, kernel in vars(module).items()
            if isinstance(getattr(kernel, "_cache", None), NullCache)]


def _remove_stale_folders() -> None:
    """Remove the folders of compilations whose server has gone (killed once they were done)."""
    if os.name != "posix":  # os.kill(pid, 0) probes only there
        return
    for path in glob.glob(os.path.join(tempfile.gettempdir(), f"{_FOLDER_PREFIX}*-*")):
        owner = os.path.basename(path)[len(_FOLDER_PREFIX):].split("-", 1)[0]
        if not owner.isdigit():
            continue
        try:
            os.kill(int(owner), 0)
        except ProcessLookupError:
            shutil.rmtree(path, ignore_errors=True)
        except OSError:  # another user's server, still running
            continue


def _stop_with_parent(parent_pid: int, folder: str) -> None:
    """End this process, and remove the parent's ``folder``, as soon as the parent has gone
    (killed without stopping this process)."""
    while os.getppid() == parent_pid:
        time.sleep(_PARENT_CHECK_S)
    shutil.rmtree(folder, ignore_errors=True)
    os._exit(1)


def _compile_in_child(ready_file: str, parent_pid: int) -> int:
    """The child's work: compile every kernel, then create ``ready_file``; the exit status."""
    threading.Thread(target=_stop_with_parent, args=(parent_pid, os.path.dirname(ready_file)),
                     daemon=True).start()
    if hasattr(os, "nice"):
        os.nice(10)  # requests first: the server's own work keeps the processor
    if not compile_every_kernel():
        print("the compiled kernels are not in use (numba missing or SPECTROCOLOR_NUMBA=0)")
        return 3
    uncached = uncached_kernels()
    if uncached:
        print(f"numba found no writable cache folder for {len(uncached)} kernels (e.g. "
              f"{uncached[0]}); set NUMBA_CACHE_DIR to a writable folder")
        return 4
    with open(ready_file, "w", encoding="utf-8") as ready:
        ready.write("every kernel is compiled and cached\n")
    return 0


class BackgroundCompilation:
    """Every kernel compiled in a child process while this one runs the NumPy path.

    Use :meth:`start`; it sets ``SPECTROCOLOR_KERNELS_READY_FILE`` in this process's
    environment, so that worker processes started afterwards wait for the same file.

    Parameters
    ----------
    process : subprocess.Popen
        The child that compiles.
    folder : str
        Temporary folder of the ready file and the child's log.
    report : callable
        Called with one line of text when the kernels are ready or the compilation failed.
    """

    def __init__(self, process: subprocess.Popen, folder: str, report: Callable[[str], None]):
        self.process, self.folder, self.report = process, folder, report
        self.ready_file = os.path.join(folder, "ready")
        self.log_file = os.path.join(folder, "compile.log")
        self._started = time.monotonic()
        self._stopped = False
        self._watcher = threading.Thread(target=self._watch, name="kernel-compilation",
                                         daemon=True)
        self._watcher.start()

    @classmethod
    def start(cls, report: Callable[[str], None] = print) -> BackgroundCompilation | None:
        """Start compiling; None (after one line to ``report``) where no kernels are in use.

        Parameters
        ----------
        report : callable
            Called with one line of text now and when the compilation ends.

        Returns
        -------
        BackgroundCompilation or None
            None with ``SPECTROCOLOR_NUMBA=0`` or without numba (the extra ``fast``).
        """
        if not numba_enabled():
            report("compiled kernels: off (SPECTROCOLOR_NUMBA=0); every result uses the NumPy "
                   "path")
            return None
        if importlib.util.find_spec("numba") is None:
            report("compiled kernels: numba is not installed (extra 'fast'); every result uses "
                   "the NumPy path")
            return None
        _remove_stale_folders()
        folder = tempfile.mkdtemp(prefix=f"{_FOLDER_PREFIX}{os.getpid()}-")
        ready_file = os.path.join(folder, "ready")
        child_env = {k: v for k, v in os.environ.items() if k != READY_FILE_VARIABLE}
        with open(os.path.join(folder, "compile.log"), "wb") as log:
            process = subprocess.Popen([sys.executable, "-c", _CHILD, ready_file, str(os.getpid())],
                                       env=child_env, stdin=subprocess.DEVNULL, stdout=log,
                                       stderr=subprocess.STDOUT)
        os.environ[READY_FILE_VARIABLE] = ready_file
        report("compiling kernels in the background (a minute or two the first time, seconds "
               "after); until then results use the slower NumPy path")
        return cls(process, folder, report)

    @property
    def ready(self) -> bool:
        """Whether every kernel is compiled and cached."""
        return os.path.exists(self.ready_file)

    def wait(self, timeout: float | None = None) -> bool:
        """Wait until the child has ended (at most ``timeout`` s); whether the kernels are ready."""
        self._watcher.join(timeout)
        return self.ready

    def _watch(self) -> None:
        status = self.process.wait()
        if self._stopped:
            return
        seconds = time.monotonic() - self._started
        if status == 0 and self.ready:
            self.report(f"compiled kernels ready after {seconds:.0f} s; results use them from now "
                        "on")
            return
        self.report(f"compiling the kernels failed (exit status {status}); results keep using the "
                    f"NumPy path. {self._log_tail()}")

    def _log_tail(self) -> str:
        try:
            with open(self.log_file, encoding="utf-8", errors="replace") as log:
                lines = [line.strip() for line in log if line.strip()]
        except OSError:
            return ""
        return f"The last line of its log: {lines[-1]}" if lines else ""

    def stop(self) -> None:
        """End the child if it still runs, remove its folder and ``SPECTROCOLOR_KERNELS_READY_FILE``.

        Kernels already compiled stay in numba's cache for the next start.
        """
        self._stopped = True
        if self.process.poll() is None:
            self.process.terminate()
            try:
                self.process.wait(10)
            except subprocess.TimeoutExpired:
                self.process.kill()
                self.process.wait()
        shutil.rmtree(self.folder, ignore_errors=True)
        if os.environ.get(READY_FILE_VARIABLE) == self.ready_file:
            del os.environ[READY_FILE_VARIABLE]


class KernelStatusHeader:
    """ASGI middleware: adds :data:`HEADER` to responses while the kernels are not ready.

    ``numpy-path`` where the request's result took the NumPy path because the kernels were not
    ready, ``warming-up`` where it needed no kernel while they are being compiled; nothing once
    they are ready or where none are in use.

    Parameters
    ----------
    app : ASGI application
        The application it wraps.
    """

    def __init__(self, app):
        self.app = app

    async def __call__(self, scope, receive, send):
        if scope["type"] != "http":
            await self.app(scope, receive, send)
            return
        with noting_numpy_path() as note:
            async def send_with_status(message):
                if message["type"] == "http.response.start":
                    status = "numpy-path" if note.used else None if kernels_ready() else "warming-up"
                    if status is not None:
                        headers = [*message.get("headers", ()),
                                   (HEADER.lower().encode("latin-1"), status.encode("latin-1"))]
                        message = {**message, "headers": headers}
                await send(message)

            await self.app(scope, receive, send_with_status)
