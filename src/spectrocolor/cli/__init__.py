"""The ``spectrocolor`` command line: one sub-command module per capability.

Each module listed in ``COMMAND_MODULES`` defines ``register(subparsers)``, which adds
its sub-commands with ``set_defaults(handler=...)``. A handler returns an exit code.
Errors that are the user's (bad files, bad arguments) are printed as one clear line,
never as a traceback; so is a missing optional extra (``pip install spectrocolor[x]``).
Output piped into a reader that stops early (``| head``) ends the command quietly with the
shell's SIGPIPE status, 141.
"""

from __future__ import annotations

import argparse
import csv
import importlib
import os
import sys

from .. import __version__
from ..errors import ColorimetryError, SpectrumError

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
    subparsers = parser.add_subparsers(dest="command", metavar="COMMAND")
    subparsers.required = True
    for name in COMMAND_MODULES:
        importlib.import_module(f".{name}", __name__).register(subparsers)
    return parser


def missing_extra(exc: ImportError) -> str | None:
    """``pip install spectrocolor[x]`` advice for an optional package that is not installed, else None."""
    top = (exc.name or "").split(".")[0]
    extra = EXTRA_OF_MODULE.get(top)
    if extra is None:
        return None
    package = {"PIL": "Pillow"}.get(top, top)  # the distribution's name where it differs from the module's
    return f"needs the optional package {package!r}, which is not installed: pip install spectrocolor[{extra}]"


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
