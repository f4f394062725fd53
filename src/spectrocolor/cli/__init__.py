"""The ``spectrocolor`` command line: one sub-command module per capability.

Each module listed in ``COMMAND_MODULES`` defines ``register(subparsers)``, which adds
its sub-commands with ``set_defaults(handler=...)``. A handler returns an exit code.
Errors that are the user's (bad files, bad arguments) are printed as one clear line,
never as a traceback; so is a missing optional extra, with the command that installs it
(:func:`install_command`).
Output piped into a reader that stops early (``| head``) ends the command quietly with the
shell's SIGPIPE status, 141.
"""

from __future__ import annotations

import argparse
import contextlib
import csv
import importlib
import os
import sys

from .._version import __version__
from ..budget import ENVIRONMENT_VARIABLE, parse_size
from ..errors import BudgetError, ColorimetryError, SpectrumError

COMMAND_MODULES: tuple[str, ...] = (
    "colorimetry", "app", "render", "image", "report", "thinfilm", "recover", "relight", "light",
    "upsample",
)


#: Optional packages and the extra that installs each (pyproject.toml ``[project.optional-dependencies]``).
EXTRA_OF_MODULE = {
    "matplotlib": "plot",
    "PIL": "images",
    "tifffile": "images",
    "xarray": "images",
    "dask": "images",
    "distributed": "images",
    "h5netcdf": "images",
    "h5py": "images",
    "tqdm": "images",
    "fastapi": "app",
    "uvicorn": "app",
    "starlette": "app",
}
#: Exit status after the reader of our output went away (128 + SIGPIPE, as a shell reports it).
BROKEN_PIPE_STATUS = 141


class UserError(Exception):
    """An error caused by the command's input, reported without a traceback."""


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="spectrocolor",
        description="Spectra into colour: colorimetry, display, thin films, reflectance recovery.",
    )
    parser.add_argument("--version", action="version", version=f"spectrocolor {__version__}")
    parser.add_argument(
        "--memory-budget", type=_memory_budget, default=None, metavar="SIZE",
        help="most memory one input may make this run hold, e.g. 2GiB or 512MB (default: "
        f"${ENVIRONMENT_VARIABLE} if set, else 1 GiB); files, options and photos beyond it are "
        "refused, or streamed in blocks of a sixteenth of it")
    subparsers = parser.add_subparsers(dest="command", metavar="COMMAND")
    subparsers.required = True
    for name in COMMAND_MODULES:
        importlib.import_module(f".{name}", __name__).register(subparsers)
    return parser


def _memory_budget(text: str) -> int:
    try:
        return parse_size(text, "--memory-budget")
    except BudgetError as exc:
        raise argparse.ArgumentTypeError(str(exc).removeprefix("--memory-budget: ")) from None


_memory_budget.__name__ = "size"


@contextlib.contextmanager
def _budget_for_run(nbytes: int | None):
    """Set the memory budget of this run (and of the processes it starts) through the environment."""
    if nbytes is None:
        yield
        return
    previous = os.environ.get(ENVIRONMENT_VARIABLE)
    os.environ[ENVIRONMENT_VARIABLE] = str(nbytes)
    try:
        yield
    finally:
        if previous is None:
            os.environ.pop(ENVIRONMENT_VARIABLE, None)
        else:
            os.environ[ENVIRONMENT_VARIABLE] = previous


def missing_extra(exc: ImportError) -> str | None:
    """Advice for an optional package that is not installed (:func:`install_command`), else None."""
    top = (exc.name or "").split(".")[0]
    extra = EXTRA_OF_MODULE.get(top)
    if extra is None:
        return None
    package = {"PIL": "Pillow"}.get(top, top)  # the distribution's name where it differs from the module's
    return (f"needs the optional package {package!r} (extra '{extra}'), which is not installed; "
            f"install it with: {install_command(extra, package)}")


def install_command(extra: str, package: str | None = None) -> str:
    """A command that installs the optional ``extra`` into the environment running this program.

    spectrocolor is not on the package index, so ``pip install spectrocolor[x]`` finds nothing.
    Run from a clone installed in place (``make run``, ``make test``, ``pip install -e``), the
    command installs the clone with the extra at the versions of its ``constraints.txt``;
    otherwise it installs the extra's packages as the installed metadata lists them (``package``
    where there is no metadata).

    Parameters
    ----------
    extra : str
        ``plot``, ``images``, ``app``, ``fast``, ...
    package : str, optional
        The missing distribution, for an installation without metadata.

    Returns
    -------
    str
        One shell command, its paths quoted.

    Examples
    --------
    >>> " -m pip install " in install_command("plot")
    True
    """
    import shlex
    from importlib import metadata
    from pathlib import Path

    python = shlex.quote(sys.executable)
    here = Path(__file__).resolve()
    root = here.parents[3]  # <root>/src/spectrocolor/cli/__init__.py
    if (root / "pyproject.toml").is_file() and here.parents[1] == root / "src" / "spectrocolor":
        constraints = root / "constraints.txt"
        pin = f"-c {shlex.quote(str(constraints))} " if constraints.is_file() else ""
        return f"{python} -m pip install {pin}-e {shlex.quote(f'{root}[{extra}]')}"
    try:
        declared = metadata.requires("spectrocolor") or []
    except metadata.PackageNotFoundError:
        declared = []
    marker = f'extra == "{extra}"'
    requirements = [r.split(";")[0].strip() for r in declared if r.split(";", 1)[-1].strip() == marker]
    if not requirements:
        requirements = [package or extra]
    return f"{python} -m pip install {' '.join(shlex.quote(r) for r in requirements)}"


def _quiet_after_broken_pipe() -> int:
    """Point stdout at /dev/null so that the interpreter's final flush cannot fail again."""
    devnull = os.open(os.devnull, os.O_WRONLY)
    os.dup2(devnull, sys.stdout.fileno())
    return BROKEN_PIPE_STATUS


def main(argv: list[str] | None = None) -> int:
    """Run the command line; returns the exit status (0 ok, 2 a user error, 141 output cut short)."""
    parser = build_parser()
    args = parser.parse_args(argv)
    try:
        with _budget_for_run(args.memory_budget):
            status = int(args.handler(args) or 0)
        sys.stdout.flush()
        return status
    except BrokenPipeError:
        return _quiet_after_broken_pipe()
    except ImportError as exc:
        advice = missing_extra(exc)
        if advice is None:
            raise
        print(f"spectrocolor {args.command}: error: {advice}", file=sys.stderr)
        return 2
    except (UserError, SpectrumError, ColorimetryError, OSError) as exc:  # OSError: full disk, ...
        print(f"spectrocolor {args.command}: error: {exc}", file=sys.stderr)
        return 2
    except (csv.Error, RecursionError) as exc:  # only hostile input makes a parser raise these
        reason = str(exc).splitlines()[0][:200] if str(exc) else exc.__class__.__name__
        print(f"spectrocolor {args.command}: error: the input cannot be read ({reason})",
              file=sys.stderr)
        return 2


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
