"""The ``spectrocolor`` command line: one sub-command module per capability.

Each module listed in ``COMMAND_MODULES`` defines ``register(subparsers)``, which adds
its sub-commands with ``set_defaults(handler=...)``. A handler returns an exit code.
Errors that are the user's (bad files, bad arguments) are printed as one clear line,
never as a traceback.
"""

from __future__ import annotations

import argparse
import importlib
import sys

from ..errors import ColorimetryError, SpectrumError

COMMAND_MODULES: tuple[str, ...] = ("colorimetry", "app", "render", "image", "report", "thinfilm", "recover")


class UserError(Exception):
    """An error caused by the command's input, reported without a traceback."""


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="spectrocolor",
        description="Spectra into colour: colorimetry, display, thin films, reflectance recovery.",
    )
    subparsers = parser.add_subparsers(dest="command", metavar="COMMAND")
    subparsers.required = True
    for name in COMMAND_MODULES:
        importlib.import_module(f".{name}", __name__).register(subparsers)
    return parser


def main(argv: list[str] | None = None) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)
    try:
        return int(args.handler(args) or 0)
    except (UserError, SpectrumError, ColorimetryError, OSError) as exc:  # OSError: full disk, ...
        print(f"spectrocolor {args.command}: error: {exc}", file=sys.stderr)
        return 2


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
