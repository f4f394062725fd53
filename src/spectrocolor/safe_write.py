"""Files are never lost: atomic writes, and the overwrite policy of the command line.

Every writer of the package (images, strips, reports, spectra written by the CLI, plots) goes
through :func:`atomic_path`: the data are written to a temporary file *beside* the target (same
folder, hence the same file system), flushed to the disk (``fsync``), checked where a checker is
given, and only then renamed over the target (``os.replace``, atomic on POSIX and Windows). If
anything fails -- a full disk, a killed process, an encoder error, a check that does not match --
the previous file is untouched and the temporary file is removed (a ``kill -9`` cannot run any
clean-up; it leaves at most a hidden ``.NAME.*.partial`` file beside the target, never a damaged
target).

Overwrite policy (the command line; library functions replace their target atomically, as
``open(path, "w")`` would, but never leave it half written):

1. An existing output file is replaced only with ``--force``; without it the command stops with
   one line naming the option and the file, before computing anything. An output that was
   absent then is placed with a create-exclusive link (``os.link``, which fails if the name
   exists): if another run created it meanwhile, that file is kept and this run stops with one
   line saying so, so two runs without ``--force`` can never both succeed.
2. A command never writes over one of its own inputs, not even with ``--force`` (paths are
   compared after resolving links, and with :func:`os.path.samefile` for hard links).
3. Two outputs of one command must be different files; an output's folder must exist.

References
----------
POSIX.1-2017, ``rename()``: "If the link named by the *new* argument exists, it shall be removed
and *old* renamed to *new* ... a link named *new* shall remain visible to other threads
throughout the renaming operation and refer either to the file referred to by *new* or *old*."

Why this file is long: it is the one place that decides how a file is written (temporary file,
fsync, rename, read back, the overwrite policy); each writer of the package calls it, and a split
would let the policy drift between them.
"""

from __future__ import annotations

import contextlib
import errno
import os
import stat
import tempfile
import threading
from collections.abc import Callable, Iterable, Iterator
from pathlib import Path

__all__ = ["OutputError", "atomic_path", "write_bytes", "write_text", "verify_size", "verify_png",
           "verify_image", "verify_tiff", "check_outputs"]


class OutputError(OSError):
    """An output cannot be written, or may not be (it exists, or it is an input).

    A subclass of :class:`OSError` so that callers handling file errors handle it; its message
    is one line that names the file and says what to do.

    Examples
    --------
    >>> import errno
    >>> error = OutputError(errno.EEXIST, "out.png exists; give --force to replace it")
    >>> str(error), isinstance(error, OSError)
    ('out.png exists; give --force to replace it', True)
    """

    def __str__(self) -> str:
        return self.strerror or super().__str__()


def _describe(exc: OSError) -> str:
    reason = exc.strerror or exc.__class__.__name__
    return f"{reason} (errno {exc.errno})" if exc.errno else reason


@contextlib.contextmanager
def atomic_path(path, verify: Callable[[Path], None] | None = None) -> Iterator[Path]:
    """Give a temporary path beside ``path``; on success move it over ``path`` atomically.

    The temporary file keeps ``path``'s suffix, so writers that choose the format from the
    suffix (Pillow, tifffile, matplotlib) write the right one. Where ``path`` is a symbolic link
    (to a file, or to a name not yet written), the link is followed to its final target
    (:func:`os.path.realpath`): the temporary file is written beside that target and renamed
    over it, so the link stays a link and shows the new content.

    Parameters
    ----------
    path : str or Path
        The final file.
    verify : callable, optional
        Called with the temporary path after it is written and synced; raises if the file is
        not what was meant to be written (the target is then left unchanged).

    Yields
    ------
    Path
        Where to write.

    Raises
    ------
    OutputError
        The folder does not exist or is not writable, the disk is full, the name is too long, the
        file is too large ...: the previous file at ``path`` is unchanged; see :term:`atomic write`.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> folder = pathlib.Path(tempfile.mkdtemp())
    >>> with atomic_path(folder / "a.txt") as tmp:
    ...     _ = tmp.write_text("new")
    >>> (folder / "a.txt").read_text()
    'new'
    >>> sorted(p.name for p in folder.iterdir())  # no temporary file is left behind
    ['a.txt']
    """
    target = Path(os.path.realpath(path))  # a symbolic link is written through: it stays a link
    folder = target.parent
    if not folder.is_dir():
        what = "does not exist" if not folder.exists() else "is not a folder"
        raise OutputError(errno.ENOENT, f"{target}: cannot write: {folder} {what}")
    try:
        fd, name = tempfile.mkstemp(prefix=f".{target.name[:80]}.", suffix=f".partial{target.suffix}",
                                    dir=folder)
    except OSError as exc:
        raise OutputError(exc.errno, f"{target}: cannot write here: {_describe(exc)}") from None
    os.close(fd)
    temporary = Path(name)
    try:
        yield temporary
        with open(temporary, "rb+") as handle:  # data of writers that closed without syncing
            os.fsync(handle.fileno())
        if verify is not None:
            verify(temporary)
        os.chmod(temporary, _mode_for(target))  # mkstemp made it 0600
        if _claimed_new(target):
            _place_new(temporary, target)
        else:
            os.replace(temporary, target)
    except OSError as exc:
        temporary.unlink(missing_ok=True)
        if isinstance(exc, OutputError):
            raise
        raise OutputError(exc.errno, f"{target}: not written ({_describe(exc)}); any previous "
                          "file there is unchanged") from None
    except BaseException:
        temporary.unlink(missing_ok=True)
        raise
    _sync_folder(folder)


# --- outputs that must not exist: no-clobber placement ------------------------------------------

#: Outputs that :func:`check_outputs` found absent without ``force``: each is placed with a
#: create-exclusive link, so another process that wrote it meanwhile is never replaced. A
#: process-wide registry because the check (command line) and the write (any writer) are far
#: apart; a path leaves it once written.
_NEW_OUTPUTS: set[str] = set()
_NEW_OUTPUTS_LOCK = threading.Lock()


def _claim_new(path: Path) -> None:
    with _NEW_OUTPUTS_LOCK:
        _NEW_OUTPUTS.add(os.path.realpath(path))


def _release_new(path: Path) -> None:
    with _NEW_OUTPUTS_LOCK:
        _NEW_OUTPUTS.discard(os.path.realpath(path))


def _claimed_new(target: Path) -> bool:
    with _NEW_OUTPUTS_LOCK:
        return str(target) in _NEW_OUTPUTS


def _place_new(temporary: Path, target: Path) -> None:
    """Give ``temporary``'s file the name ``target`` only if nothing has that name (atomic).

    ``os.link`` fails with EEXIST if the name exists, whoever created it and when; the file
    appears whole, as with a rename. Where the file system has no hard links, an exclusive
    create (``O_EXCL``) reserves the name and the rename then replaces that empty file.
    """
    try:
        os.link(temporary, target)
    except FileExistsError:
        raise OutputError(errno.EEXIST, f"{target}: not written: it was created by another "
                          "program while this one ran (it was absent when checked); it is "
                          "left as it is; add --force to replace it") from None
    except OSError as exc:
        if exc.errno not in (errno.EPERM, errno.EOPNOTSUPP, errno.ENOTSUP, errno.EMLINK,
                             errno.EXDEV, errno.ENOSYS):
            raise
        try:
            os.close(os.open(target, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o600))
        except FileExistsError:
            raise OutputError(errno.EEXIST, f"{target}: not written: it was created by another "
                              "program while this one ran; add --force to replace it") from None
        os.replace(temporary, target)
    else:
        temporary.unlink()
    _release_new(target)


def _mode_for(target: Path) -> int:
    """Permissions of the file being replaced, or what ``open(target, "w")`` would give."""
    try:
        return stat.S_IMODE(os.stat(target).st_mode)
    except OSError:
        return 0o666 & ~_UMASK


def _current_umask() -> int:
    mask = os.umask(0)  # the only portable way to read it; set back at once, at import time
    os.umask(mask)
    return mask


_UMASK = _current_umask()


def _sync_folder(folder: Path) -> None:
    """Make the rename itself durable (POSIX: fsync the folder); a no-op where unsupported."""
    try:
        fd = os.open(folder, os.O_RDONLY)
    except OSError:
        return
    try:
        os.fsync(fd)
    except OSError:
        pass  # some file systems (and Windows) cannot sync a folder; the rename is still atomic
    finally:
        os.close(fd)


def write_bytes(path, data: bytes, verify: Callable[[Path], None] | None = None) -> Path:
    """Write ``data`` to ``path`` atomically (see :func:`atomic_path`); returns the path.

    Parameters
    ----------
    path : str or os.PathLike
        The final file.
    data : bytes
        The content.
    verify : callable, optional
        Check of the temporary file before it replaces ``path`` (see :func:`atomic_path`).

    Returns
    -------
    pathlib.Path
        ``path``, holding ``data``.

    Raises
    ------
    OutputError
        The bytes could not be written, or ``verify`` refused them; see :term:`atomic write`.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> target = pathlib.Path(tempfile.mkdtemp()) / "b.bin"
    >>> write_bytes(target, b"abc").read_bytes()
    b'abc'
    """
    with atomic_path(path, verify) as temporary:
        with open(temporary, "wb") as handle:
            handle.write(data)
    return Path(path)


def write_text(path, text: str) -> Path:
    """Write ``text`` to ``path`` as UTF-8, atomically, with a size check; returns the path.

    Parameters
    ----------
    path : str or os.PathLike
        The final file.
    text : str
        The content, encoded as UTF-8.

    Returns
    -------
    pathlib.Path
        ``path``, holding ``text``.

    Raises
    ------
    OutputError
        The text could not be written; see :term:`atomic write`.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> target = pathlib.Path(tempfile.mkdtemp()) / "c.csv"
    >>> write_text(target, "x,y\\n1,2\\n").read_text()
    'x,y\\n1,2\\n'
    """
    data = text.encode("utf-8")
    return write_bytes(path, data, verify=lambda p: verify_size(p, len(data)))


def verify_size(path: Path, expected: int) -> None:
    """Raise :class:`OutputError` unless the file at ``path`` holds ``expected`` bytes.

    Parameters
    ----------
    path : pathlib.Path
        The file written.
    expected : int
        Its size in bytes.

    Raises
    ------
    OutputError
        If the size on disk differs.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     path = pathlib.Path(folder) / "a.bin"
    ...     _ = path.write_bytes(b"abc")
    ...     verify_size(path, 3)  # silent when right
    """
    found = os.stat(path).st_size
    if found != expected:
        raise OutputError(errno.EIO, f"{path}: {found} bytes on disk, {expected} written")


def verify_png(path: Path, width: int, height: int) -> None:
    """Raise :class:`OutputError` unless ``path`` is a complete PNG of ``width`` x ``height``.

    Pillow's ``verify`` checks every chunk's CRC, so a truncated or damaged file is caught
    (:func:`verify_image` with the message naming a PNG).

    Parameters
    ----------
    path : pathlib.Path
        The PNG written.
    width, height : int
        Its size in pixels.

    Raises
    ------
    OutputError
        If the file does not read back as a PNG of that size.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> import numpy as np
    >>> from spectrocolor.pictures import save_image
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     path = save_image(np.zeros((2, 3, 3), np.uint8), pathlib.Path(folder) / "a.png")
    ...     verify_png(path, 3, 2)  # silent when right
    """
    verify_image(path, width, height, kind="PNG")


def verify_image(path: Path, width: int, height: int, *, frames: int | None = None,
                 kind: str = "image") -> None:
    """Raise :class:`OutputError` unless Pillow reads ``path`` back as ``width`` x ``height``.

    Pillow's ``verify`` checks the file's structure (every chunk's CRC for a PNG), so a
    truncated or damaged file is caught; the frames of an animation are counted.

    Parameters
    ----------
    path : pathlib.Path
        The picture written (PNG, JPEG, GIF, ...).
    width, height : int
        Its size in pixels.
    frames : int, keyword-only, optional
        Frames written (an animated GIF): between 1 and this many must read back (a GIF writer
        merges identical consecutive frames into one shown longer); not checked when None.
    kind : str, keyword-only, default "image"
        What to call the file in the message.

    Raises
    ------
    OutputError
        If the file does not read back as a picture of that size (and frame count).

    Examples
    --------
    >>> import tempfile, pathlib
    >>> import numpy as np
    >>> from spectrocolor.imagefiles import write_gif
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     path = write_gif(pathlib.Path(folder) / "a.gif", [np.zeros((2, 3, 3), np.uint8),
    ...                                                         np.ones((2, 3, 3), np.uint8)])
    ...     verify_image(path, 3, 2, frames=2)  # silent when right
    """
    from PIL import Image

    try:
        with Image.open(path) as image:
            size, found = image.size, int(getattr(image, "n_frames", 1))
            image.verify()
    except (OSError, SyntaxError, ValueError) as exc:
        raise OutputError(errno.EIO, f"{path}: the {kind} written does not read back ({exc})") from None
    if size != (width, height):
        raise OutputError(errno.EIO, f"{path}: {kind} of {size[0]} x {size[1]} read back, "
                          f"{width} x {height} written")
    if frames is not None and not 1 <= found <= frames:
        raise OutputError(errno.EIO, f"{path}: {kind} of {found} frames read back, {frames} written")


def verify_tiff(path: Path, shape: tuple[int, ...], nbytes: int) -> None:
    """Raise :class:`OutputError` unless ``path`` is a TIFF of ``shape`` holding ``nbytes``.

    Parameters
    ----------
    path : pathlib.Path
        The TIFF written.
    shape : tuple of int
        The array shape written.
    nbytes : int
        The array's size in bytes (the file holds at least this many).

    Raises
    ------
    OutputError
        If the file does not read back as a TIFF of that shape and size.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> import numpy as np
    >>> from spectrocolor.pictures import write_image
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     path = write_image(pathlib.Path(folder) / "a.tif", np.zeros((2, 3, 3)))
    ...     verify_tiff(path, (2, 3, 3), 144)  # silent when right
    """
    import tifffile

    try:
        with tifffile.TiffFile(path) as tif:
            found = tuple(tif.series[0].shape)
    except (OSError, ValueError, IndexError, tifffile.TiffFileError) as exc:
        raise OutputError(errno.EIO, f"{path}: the TIFF written does not read back ({exc})") from None
    if found != tuple(shape) or os.stat(path).st_size < nbytes:
        raise OutputError(errno.EIO, f"{path}: TIFF of shape {found} and "
                          f"{os.stat(path).st_size} bytes read back; {shape}, {nbytes} bytes "
                          "written")


def _same(a: Path, b: Path) -> bool:
    if a.resolve() == b.resolve():
        return True
    try:
        return os.path.samefile(a, b)
    except OSError:
        return False


def check_outputs(outputs: dict[str, object], inputs: Iterable[object] = (), *,
                  force: bool = False) -> None:
    """Apply the overwrite policy (module docstring) before a command writes anything.

    Parameters
    ----------
    outputs : dict
        Option name (e.g. ``"--out"``) -> output path; ``None`` entries are skipped.
    inputs : iterable of paths
        The command's input files (``None`` skipped); never written over.
    force : bool
        Allow replacing existing outputs (never inputs).

    Raises
    ------
    OutputError
        An output is an input, exists without ``force``, is a folder, repeats another output, or
        lies in a folder that does not exist; see :term:`atomic write` (the overwrite policy).

    Notes
    -----
    Without ``force``, each output found absent is remembered: :func:`atomic_path` then places
    it only if it is still absent (a create-exclusive link) and otherwise raises
    :class:`OutputError`, leaving the file another program wrote meanwhile.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> mine = pathlib.Path(tempfile.mkdtemp()) / "mine.csv"
    >>> _ = mine.write_text("wavelength_nm,a\\n400,1\\n")
    >>> check_outputs({"--out": mine}, [mine], force=True)
    Traceback (most recent call last):
    ...
    spectrocolor.safe_write.OutputError: --out ...mine.csv is the command's input; choose another output file
    """
    sources = [Path(str(p)) for p in inputs if p is not None]
    seen: list[tuple[str, Path]] = []
    for option, value in outputs.items():
        if value is None:
            continue
        path = Path(str(value))
        for source in sources:
            if path.exists() and source.exists() and _same(path, source):
                raise OutputError(errno.EEXIST, f"{option} {path} is the command's input; choose "
                                  "another output file")
        for other_option, other in seen:
            if path.resolve() == other.resolve():
                raise OutputError(errno.EEXIST, f"{option} and {other_option} name the same file "
                                  f"{path}; give each output its own file")
        seen.append((option, path))
        if path.is_dir():
            raise OutputError(errno.EISDIR, f"{option} {path} is a folder; give a file name")
        if not path.parent.is_dir():
            what = "does not exist" if not path.parent.exists() else "is not a folder"
            raise OutputError(errno.ENOENT, f"{option} {path}: the folder {path.parent} {what}")
        if path.exists() and not force:
            raise OutputError(errno.EEXIST, f"{option} {path} exists; add --force to replace it")
        if force:
            _release_new(path)
        else:  # absent now: written only if still absent then (another run may write it first)
            _claim_new(path)
