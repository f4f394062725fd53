"""The memory budget: one stated limit on what an input may make spectrocolor hold in memory.

Every size that comes from outside -- a file header, a command-line option, an argument, an
upload -- is turned into bytes and checked here *before* anything is allocated or looped over:

* against the **memory budget**: the most bytes one input may make the library hold at once
  (:data:`DEFAULT_MEMORY_BUDGET`, 1 GiB, sized for a machine with 4 GiB of memory: the data, its
  working copies and the interpreter then fit with room for the rest of the machine);
* for sizes a file claims, against the **file's own length** (a header cannot promise more bytes
  than the file holds), against the bytes the file really **stores on disk** (a sparse file
  whose holes read as zeros promises data that is not there) and, for compressed data, against
  the compressed size times :data:`MAX_COMPRESSION_RATIO` (no deflate stream expands more).

Beyond any of them, one :class:`~spectrocolor.errors.BudgetError` (a ``ValueError``) names the
input, the claimed size and the limit, and says how to raise the budget where raising makes
sense. Work that can stream (cube conversion, photos, textures) is done in blocks of
:func:`block_bytes` instead of being refused.

The budget is set, most specific first:

1. per call, with the keyword ``memory_budget=`` of the functions that read files;
2. per process, with the environment variable :data:`ENVIRONMENT_VARIABLE`
   (``SPECTROCOLOR_MEMORY_BUDGET=2GiB``), which the explorer's server and its worker processes
   read too;
3. per command-line run, with ``spectrocolor --memory-budget 2GiB COMMAND ...`` (which sets the
   variable for the run and the processes it starts).

Sizes are written as bytes (``1073741824``) or with a unit: ``kB``/``MB``/``GB``/``TB`` (powers
of 1000) or ``KiB``/``MiB``/``GiB``/``TiB`` (powers of 1024); ``K``, ``M``, ``G``, ``T`` alone are
binary.

Why this file is long: it is the one place where every size from outside is turned into bytes
and checked (the budget, the size grammar, claims against a file's length, its stored blocks
and its compression ratio, the sizes of streamed blocks), with a runnable example for each
check; spreading them out would bring back the readers' own, differing limits it replaced.
"""

from __future__ import annotations

import math
import os
import re

from .errors import BudgetError, SpectrumError

__all__ = ["DEFAULT_MEMORY_BUDGET", "ENVIRONMENT_VARIABLE", "MAX_COMPRESSION_RATIO",
           "MIN_MEMORY_BUDGET", "memory_budget", "parse_size", "format_size", "claimed_bytes",
           "check_bytes", "check_file_claim", "stored_bytes", "block_bytes", "block_rows",
           "npy_claim"]

#: The default memory budget, bytes (1 GiB: sized for a machine with 4 GiB of memory).
DEFAULT_MEMORY_BUDGET = 2**30
#: The smallest budget accepted, bytes (below it nothing useful fits).
MIN_MEMORY_BUDGET = 2**20
#: The environment variable that sets the budget of a process (and of the processes it starts).
ENVIRONMENT_VARIABLE = "SPECTROCOLOR_MEMORY_BUDGET"
#: The largest expansion of compressed data believed: deflate (zlib, gzip, zip, PNG, npz)
#: cannot expand more than 1032:1, so a claim beyond it is a lie, not a compressed file.
MAX_COMPRESSION_RATIO = 1032
#: Claims up to this many bytes are never refused as sparse (small files may be stored inside
#: the file system's own records, with no data blocks).
_SPARSE_ALLOWANCE = 2**16
#: Share of the budget one streamed block may take (the block's working copies take the rest).
_BLOCK_SHARE = 16

_UNITS = {"": 1, "b": 1, "k": 2**10, "kb": 10**3, "kib": 2**10, "m": 2**20, "mb": 10**6,
          "mib": 2**20, "g": 2**30, "gb": 10**9, "gib": 2**30, "t": 2**40, "tb": 10**12,
          "tib": 2**40}
_SIZE = re.compile(r"^\s*([0-9]+(?:\.[0-9]*)?(?:[eE][+-]?[0-9]+)?)\s*([A-Za-z]*)\s*$")
_HOW_TO_RAISE = (f"raise it with memory_budget=... (Python), spectrocolor --memory-budget SIZE or "
                 f"{ENVIRONMENT_VARIABLE}=SIZE if the machine has the memory")


def parse_size(text, name: str = "memory_budget") -> int:
    """A size in bytes from ``"2GiB"``, ``"512 MB"``, ``"1.5G"``, ``"1048576"`` or an int.

    Parameters
    ----------
    text : str or int
        The size: a whole number of bytes, or a number and a unit (``kB``, ``MB``, ``GB``,
        ``TB`` are powers of 1000; ``KiB``, ``MiB``, ``GiB``, ``TiB`` and ``K``, ``M``, ``G``,
        ``T`` are powers of 1024); case is ignored.
    name : str, default "memory_budget"
        What to call the value in the error message (an option or variable name).

    Returns
    -------
    int
        Bytes, at least :data:`MIN_MEMORY_BUDGET`.

    Raises
    ------
    BudgetError
        For anything else, a size below 1 MiB, or one that is not finite.

    Examples
    --------
    >>> parse_size("2GiB"), parse_size("1.5 G"), parse_size("512MB"), parse_size(2**20)
    (2147483648, 1610612736, 512000000, 1048576)
    """
    accepted = ("a size in bytes of at least 1 MiB, e.g. 2GiB, 512MB or 1073741824 "
                "(units kB/MB/GB/TB = 1000^n, KiB/MiB/GiB/TiB or K/M/G/T = 1024^n)")
    if isinstance(text, bool):
        raise BudgetError(f"{name}: expected {accepted}; got {text!r}")
    if isinstance(text, int):
        value = float(text)
    else:
        match = _SIZE.match(str(text)) if isinstance(text, str) else None
        unit = match.group(2).lower() if match else None
        if match is None or unit not in _UNITS:
            raise BudgetError(f"{name}: expected {accepted}; got {str(text)[:40]!r}")
        value = float(match.group(1)) * _UNITS[unit]
    if not math.isfinite(value) or value < MIN_MEMORY_BUDGET or value > 2**62:
        raise BudgetError(f"{name}: expected {accepted}; got {str(text)[:40]!r}")
    return int(value)


def format_size(nbytes) -> str:
    """A byte count for people: ``"4.5 GiB"``, ``"310 GB"`` is written in binary units.

    Parameters
    ----------
    nbytes : int
        Bytes (any size; Python integers do not overflow).

    Returns
    -------
    str
        Three significant digits and a binary unit (B, KiB, MiB, GiB, TiB, PiB, EiB).

    Examples
    --------
    >>> format_size(512), format_size(3 * 2**29), format_size(10**20)
    ('512 B', '1.5 GiB', '86.7 EiB')
    """
    value = float(nbytes)
    for unit in ("B", "KiB", "MiB", "GiB", "TiB", "PiB"):
        if abs(value) < 1024:
            return f"{int(value)} B" if unit == "B" else f"{value:.3g} {unit}"
        value /= 1024
    return f"{value:.3g} EiB"


def memory_budget(budget=None) -> int:
    """The memory budget in force, bytes: ``budget`` if given, else the environment's, else 1 GiB.

    Parameters
    ----------
    budget : int or str, optional
        A budget given for one call (bytes, or a size such as ``"2GiB"``). ``None``: the
        variable :data:`ENVIRONMENT_VARIABLE` if set, else :data:`DEFAULT_MEMORY_BUDGET`.

    Returns
    -------
    int
        Bytes.

    Raises
    ------
    BudgetError
        For a budget (given, or in the environment) that is not a size of at least 1 MiB.

    Examples
    --------
    >>> memory_budget("2GiB")
    2147483648
    >>> import os
    >>> memory_budget() == (parse_size(os.environ[ENVIRONMENT_VARIABLE], ENVIRONMENT_VARIABLE)
    ...                     if ENVIRONMENT_VARIABLE in os.environ else DEFAULT_MEMORY_BUDGET)
    True
    """
    if budget is not None:
        return parse_size(budget)
    text = os.environ.get(ENVIRONMENT_VARIABLE)
    if text is None or not text.strip():
        return DEFAULT_MEMORY_BUDGET
    return parse_size(text, ENVIRONMENT_VARIABLE)


def claimed_bytes(shape, itemsize, what: str) -> int:
    """Bytes of an array of ``shape`` and ``itemsize``, computed exactly, the shape checked first.

    Parameters
    ----------
    shape : sequence of int
        The claimed shape (from a header, an option or an argument).
    itemsize : int
        Bytes per element.
    what : str
        The input, for the error message (e.g. ``"cube.npy: shape"``).

    Returns
    -------
    int
        ``prod(shape) * itemsize`` as a Python integer (no overflow).

    Raises
    ------
    BudgetError
        For a shape with a negative, fractional or non-numeric entry.

    Examples
    --------
    >>> claimed_bytes((1000, 1000, 31), 8, "cube")
    248000000
    >>> claimed_bytes((10, -3), 8, "cube.npy: shape")
    Traceback (most recent call last):
    ...
    spectrocolor.errors.BudgetError: cube.npy: shape (10, -3): every size must be a whole number >= 0
    """
    try:
        sizes = tuple(shape)
        ok = all(not isinstance(s, bool) and int(s) == s and s >= 0 for s in sizes)
    except (TypeError, ValueError, OverflowError):
        ok = False
    if not ok:
        raise BudgetError(f"{what} {shape!r:.80}: every size must be a whole number >= 0")
    return math.prod(int(s) for s in sizes) * int(itemsize)


def check_bytes(nbytes: int, what: str, *, budget=None, raise_hint: str | None = None) -> int:
    """Refuse ``nbytes`` of memory beyond the budget, before it is allocated.

    Parameters
    ----------
    nbytes : int
        Bytes the input would make the library hold at once (data and working copies).
    what : str
        The input and what it claims, for the message, e.g. ``"cube.npz: member 'values'
        (60000, 60000, 31) float64"`` or ``"--width 16384 --height 16384"``.
    budget : int or str, optional
        The budget for this call (see :func:`memory_budget`).
    raise_hint : str, optional
        What to say instead of how to raise the budget (e.g. a smaller option value), where
        raising it is not the answer.

    Returns
    -------
    int
        ``nbytes``.

    Raises
    ------
    BudgetError
        When ``nbytes`` exceeds the budget: one line with the input, the claimed size, the
        budget and how to raise it.

    Examples
    --------
    >>> check_bytes(2**20, "a small cube")
    1048576
    >>> check_bytes(5 * 2**30, "cube.npz: member 'values'", budget="1GiB")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    spectrocolor.errors.BudgetError: cube.npz: member 'values': needs 5 GiB of memory, more than ...
    """
    limit = memory_budget(budget)
    if nbytes > limit:
        hint = _HOW_TO_RAISE if raise_hint is None else raise_hint
        raise BudgetError(f"{what}: needs {format_size(nbytes)} of memory, more than the memory "
                          f"budget of {format_size(limit)}; {hint}")
    return int(nbytes)


def stored_bytes(path) -> int | None:
    """Bytes a file really occupies on disk (its allocated blocks), or None where unknown.

    A sparse file's holes (regions never written) read as zeros but occupy nothing: its length
    may be terabytes while a few kilobytes are stored.

    Parameters
    ----------
    path : str or os.PathLike
        The file.

    Returns
    -------
    int or None
        ``st_blocks * 512`` on POSIX systems; None where the system does not say (Windows,
        whose ``os.stat`` has no ``st_blocks``).

    Notes
    -----
    Where the system does not say (None), :func:`check_file_claim` falls back, so that a missing
    ``st_blocks`` never turns into an error or a crash: a file that the system marks sparse
    (Windows' ``FILE_ATTRIBUTE_SPARSE_FILE`` in ``st_file_attributes``) and that claims more than
    the sparse allowance is refused, since how much of it is holes cannot be known; any other
    file is judged by its length alone (and by the memory budget where it is read whole).

    Examples
    --------
    >>> import tempfile, pathlib
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     sparse = pathlib.Path(folder) / "sparse.raw"
    ...     with open(sparse, "wb") as handle:
    ...         _ = handle.truncate(2**30)    # 1 GiB long, nothing written
    ...     stored, length = stored_bytes(sparse), sparse.stat().st_size
    >>> length, stored is None or stored < 2**20
    (1073741824, True)
    """
    blocks = getattr(os.stat(path), "st_blocks", None)
    return None if blocks is None else int(blocks) * 512


def check_file_claim(path, claimed: int, what: str, *, offset: int = 0,
                     compressed_bytes: int | None = None,
                     max_ratio: float = MAX_COMPRESSION_RATIO) -> int:
    """Refuse a size a file claims for its data that the file cannot hold or does not store.

    Three checks, before anything is read: the claimed bytes (after ``offset``) fit in the
    file's length; they are stored on disk (a sparse file claiming far more than it stores is
    refused: its holes would be read as zeros for hours); and, for compressed data, they are at
    most ``compressed_bytes * max_ratio``. The memory budget is checked separately
    (:func:`check_bytes`), only where the data are held in memory rather than streamed.

    Parameters
    ----------
    path : str or os.PathLike
        The file.
    claimed : int
        Bytes the header claims: raw data for uncompressed files, decompressed data for
        compressed ones.
    what : str
        What claims it, for the message (e.g. ``"the header claims shape (100000, 100000, 31)
        of float32"``).
    offset : int, default 0
        Where the raw data start in the file (uncompressed data only).
    compressed_bytes : int, optional
        For compressed data: the compressed size they come from (then the length check is
        replaced by the ratio check).
    max_ratio : float, default MAX_COMPRESSION_RATIO
        The largest expansion believed for compressed or sparse data.

    Returns
    -------
    int
        ``claimed``.

    Raises
    ------
    BudgetError
        When the file is too short, stores too little on disk, or its compressed data would
        expand beyond ``max_ratio``.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     raw = pathlib.Path(folder) / "cube.raw"
    ...     _ = raw.write_bytes(bytes(800))
    ...     check_file_claim(raw, 800, "the header claims 100 float64")
    800
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     raw = pathlib.Path(folder) / "cube.raw"
    ...     _ = raw.write_bytes(bytes(800))
    ...     check_file_claim(raw, 8000, "the header claims 1000 float64")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    spectrocolor.errors.BudgetError: .../cube.raw: the header claims 1000 float64: 7.81 KiB of data, ...
    """
    claimed = int(claimed)
    if compressed_bytes is not None:
        if claimed > max(int(compressed_bytes), 1) * max_ratio:
            raise BudgetError(
                f"{path}: {what}: {format_size(claimed)} from {format_size(compressed_bytes)}"
                f" of stored (compressed) data, an expansion over {max_ratio:g}:1, which compression does "
                "not reach: the header is wrong (or the file is a decompression bomb)")
        return claimed
    length = os.stat(path).st_size
    if claimed + int(offset) > length:
        raise BudgetError(
            f"{path}: {what}: {format_size(claimed)} of data, but the file holds "
            f"{format_size(max(length - int(offset), 0))} after byte {int(offset)}; the file is "
            "damaged, cut short, or its header is wrong")
    stored = stored_bytes(path)
    if stored is not None and claimed > max(stored, _SPARSE_ALLOWANCE) * max_ratio:
        raise BudgetError(
            f"{path}: {what}: {format_size(claimed)} of data, but the file stores only "
            f"{format_size(stored)} on disk (a sparse file: the rest are holes that read as "
            "zeros); the header is wrong or the data were never written")
    if stored is None and claimed > _SPARSE_ALLOWANCE * max_ratio and _marked_sparse(path):
        raise BudgetError(
            f"{path}: {what}: {format_size(claimed)} of data in a file the system marks sparse "
            "(holes that read as zeros), and this system does not say how much of it is stored; "
            "copy the file to a plain (not sparse) file if its data are really there")
    return claimed


#: Windows' file attribute of a sparse file (``stat.FILE_ATTRIBUTE_SPARSE_FILE``).
_FILE_ATTRIBUTE_SPARSE_FILE = 0x200


def _marked_sparse(path) -> bool:
    """Whether the system marks ``path`` sparse where ``st_blocks`` is missing (Windows'
    ``st_file_attributes``); False where it says nothing either."""
    attributes = getattr(os.stat(path), "st_file_attributes", 0) or 0
    return bool(int(attributes) & _FILE_ATTRIBUTE_SPARSE_FILE)


def block_bytes(budget=None) -> int:
    """Bytes of one streamed block: a sixteenth of the budget (64 MiB of the default 1 GiB).

    The block's working copies (float64 temporaries, the converted result) take several times
    the block itself, so a sixteenth keeps a streamed job well inside the budget.

    Parameters
    ----------
    budget : int or str, optional
        The budget (see :func:`memory_budget`).

    Returns
    -------
    int
        Bytes, at least 64 KiB.

    Examples
    --------
    >>> block_bytes() == max(memory_budget() // 16, 2**16)
    True
    >>> block_bytes("2GiB") // 2**20
    128
    """
    return max(memory_budget(budget) // _BLOCK_SHARE, 2**16)


def block_rows(row_bytes: int, what: str, *, budget=None, block: int | None = None) -> int:
    """Rows per streamed block: as many rows of ``row_bytes`` as fit in one block (at least 1).

    Parameters
    ----------
    row_bytes : int
        Bytes one row takes while it is worked on (data and working copies).
    what : str
        The input, for the message when a single row is beyond the budget.
    budget : int or str, optional
        The budget (see :func:`memory_budget`).
    block : int, optional
        Bytes per block; default :func:`block_bytes`.

    Returns
    -------
    int
        Rows per block, at least 1.

    Raises
    ------
    BudgetError
        When one row alone exceeds the budget (it cannot be streamed by rows).

    Examples
    --------
    >>> block_rows(3 * 1024 * 8, "a 1024-pixel-wide image", block=2**20)
    42
    """
    check_bytes(int(row_bytes), f"{what}: one row", budget=budget)
    size = block_bytes(budget) if block is None else int(block)
    return max(1, size // max(int(row_bytes), 1))


def npy_claim(path, *, held: float | None = 1.0, budget=None):
    """The shape, dtype and data offset a ``.npy`` header claims, checked before any data is read.

    The shape must be whole numbers >= 0, its bytes must be in the file (and stored on disk:
    :func:`check_file_claim`) and, when the array is to be held in memory, ``held`` times its
    bytes must fit the budget.

    Parameters
    ----------
    path : str or os.PathLike
        The ``.npy`` file.
    held : float or None, keyword-only, default 1.0
        How many times the array's bytes the caller will hold (a copy in another dtype, working
        arrays); None when it reads the file lazily (no budget check).
    budget : int or str, keyword-only, optional
        The budget (see :func:`memory_budget`).

    Returns
    -------
    tuple
        ``(shape, dtype, offset, fortran_order)`` as the header says.

    Raises
    ------
    SpectrumError
        Not a ``.npy`` file, an unsupported version or a damaged header.
    BudgetError
        A negative or fractional size, data the file does not hold, or more than the budget.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> import numpy as np
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     np.save(pathlib.Path(folder) / "map.npy", np.zeros((3, 4), np.float32))
    ...     shape, dtype, offset, _ = npy_claim(pathlib.Path(folder) / "map.npy")
    >>> shape, dtype.name, offset
    ((3, 4), 'float32', 128)
    """
    import numpy as np

    with open(path, "rb") as handle:
        try:
            version = np.lib.format.read_magic(handle)
        except ValueError:
            raise SpectrumError(f"{path}: not a NumPy .npy file (no .npy header)") from None
        read_header = {(1, 0): np.lib.format.read_array_header_1_0,
                       (2, 0): np.lib.format.read_array_header_2_0}.get(version)
        if read_header is None:
            raise SpectrumError(f"{path}: .npy format version {version} is not supported")
        try:
            shape, fortran_order, dtype = read_header(handle)
        except ValueError as exc:
            raise SpectrumError(f"{path}: damaged .npy header ({exc})") from None
        offset = handle.tell()
    nbytes = claimed_bytes(shape, dtype.itemsize, f"{path}: the .npy header's shape")
    sizes = tuple(int(n) for n in shape)
    check_file_claim(path, nbytes, f"the header claims shape {sizes} of {dtype.name}", offset=offset)
    if held is not None:
        check_bytes(int(nbytes * held), f"{path}: shape {sizes} of {dtype.name}", budget=budget)
    return sizes, dtype, offset, fortran_order
