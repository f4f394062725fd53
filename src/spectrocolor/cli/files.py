"""The files of a command: ``--force`` and the checks every writing command makes first.

One helper for every sub-command that writes files, so the policy of
:mod:`spectrocolor.safe_write` is applied the same way everywhere:

* :func:`add_force` adds ``--force`` (replace existing outputs; never the command's inputs);
* :func:`check_files` runs before any computing: inputs must be regular files or folders (not
  a device or a pipe such as ``/dev/zero``, which would be read without end) and at most
  ``max_input_bytes`` large where given; outputs must not be inputs, must not exist unless
  ``--force`` was given, must differ from each other and lie in an existing folder.
"""

from __future__ import annotations

import argparse
import os
import stat
from pathlib import Path

from ..safe_write import check_outputs
from . import UserError

__all__ = ["add_force", "check_files", "MAX_SPECTRAL_FILE_BYTES"]

#: Largest spectral file (CSV/JSON) a command reads: 256 MiB is about 20 million numbers.
MAX_SPECTRAL_FILE_BYTES = 256 * 2**20


def add_force(parser: argparse.ArgumentParser) -> None:
    """Add ``--force`` to a sub-command that writes files."""
    parser.add_argument("--force", action="store_true",
                        help="replace output files that exist (never the command's own input)")


def _option(name: str) -> str:
    return name if name.startswith("<") else "--" + name.replace("_", "-")


def check_files(args: argparse.Namespace, outputs: tuple[str, ...], inputs: tuple[str, ...] = (),
                max_input_bytes: int | None = None) -> None:
    """Check a command's inputs and outputs before it computes anything.

    Parameters
    ----------
    args : argparse.Namespace
        The parsed command line (with ``force`` from :func:`add_force`).
    outputs : tuple of str
        Attribute names of the output options (e.g. ``("out", "csv")``); unset ones are skipped.
    inputs : tuple of str
        Attribute names of the input paths (e.g. ``("file",)``).
    max_input_bytes : int, optional
        Refuse inputs larger than this (spectral files: :data:`MAX_SPECTRAL_FILE_BYTES`).

    Raises
    ------
    UserError
        One line naming the option, the file and what is accepted.

    Examples
    --------
    >>> import argparse, tempfile, pathlib
    >>> folder = pathlib.Path(tempfile.mkdtemp())
    >>> (folder / "in.csv").write_text("wavelength_nm,a\\n400,1\\n") and None
    >>> args = argparse.Namespace(file=str(folder / "in.csv"), out=str(folder / "in.csv"),
    ...                           force=True)
    >>> check_files(args, ("out",), ("file",))
    Traceback (most recent call last):
    ...
    spectrocolor.cli.UserError: --out ...in.csv is the command's input; choose another output file
    """
    paths = []
    for name in inputs:
        value = getattr(args, name, None)
        if value is None:
            continue
        paths.append(value)
        _check_input(Path(str(value)), name, max_input_bytes)
    try:
        check_outputs({_option(name): getattr(args, name, None) for name in outputs}, paths,
                      force=bool(getattr(args, "force", False)))
    except OSError as exc:
        raise UserError(str(exc)) from None


def _check_input(path: Path, name: str, max_bytes: int | None) -> None:
    label = name.upper() if name in ("file", "cube") else _option(name)
    try:
        info = os.stat(path)
    except FileNotFoundError:
        raise UserError(f"{label} {path}: no such file") from None
    except OSError as exc:
        raise UserError(f"{label} {path}: cannot be read ({exc.strerror})") from None
    if stat.S_ISDIR(info.st_mode):
        return  # band folders; readers of single files say so themselves
    if not stat.S_ISREG(info.st_mode):
        raise UserError(f"{label} {path} is not a regular file (a device or a pipe is never "
                        "read: it may not end); give a file")
    if max_bytes is not None and info.st_size > max_bytes:
        raise UserError(f"{label} {path} is {info.st_size / 2**20:.0f} MiB; at most "
                        f"{max_bytes / 2**20:.0f} MiB are read")


#: Suffixes a figure (matplotlib) is written as.
FIGURE_SUFFIXES = (".png", ".svg", ".pdf")


def save_figure(figure, path, option: str = "--out", **options) -> None:
    """Save a matplotlib ``figure`` to ``path`` atomically (PNG, SVG or PDF by the suffix).

    ``options`` go to ``figure.savefig`` (e.g. ``dpi``). The figure is closed afterwards.
    """
    from ..safe_write import atomic_path

    suffix = Path(str(path)).suffix.lower()
    if suffix not in FIGURE_SUFFIXES:
        raise UserError(f"{option} must end in .png, .svg or .pdf, got {str(path)!r}")
    import matplotlib.pyplot as plt

    try:
        with atomic_path(path) as temporary:
            figure.savefig(temporary, format=suffix[1:], **options)
    finally:
        plt.close(figure)
