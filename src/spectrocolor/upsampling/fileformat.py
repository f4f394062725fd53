"""Save and load upsampling tables: a documented little-endian binary layout (``.scup``).

Layout (version 1; every number little-endian, arrays in C order)::

    offset  size        content
    0       8           magic b"SCUPTBL\\0"
    8       4           uint32  format version (1)
    12      4           uint32  n, nodes per axis (2..129)
    16      4           uint32  K, wavelength samples (2..4096)
    20      4           uint32  J, bytes of the JSON metadata block (a multiple of 8)
    24      8           float64 first wavelength, nm
    32      8           float64 wavelength step, nm
    40      72          float64[3][3] matrix, row-major: XYZ100 = matrix @ (t0, t1, t2)
    112     J           UTF-8 JSON (space, illuminant, observer, node status names), padded
                        with spaces
    112+J   8 n³ K      float64[n][n][n][K] node reflectances (0–1); node (i, j, k) is at
                        table coordinates (i, j, k) / (n − 1)
    …       8 n³ 3      float64[n][n][n][3] node XYZ100 (what each node reproduces)
    …       8 n³        float64[n][n][n]    node roughness, nm⁻¹
    …       8 n³ 3      float64[n][n][n][3] node multipliers μ
    …       8 (n−1)³    float64 cell roughness-excess bound, nm⁻¹ (NaN: cell not exact)
    …       8 (n−1)³    float64 cell roughness excess measured, nm⁻¹
    …       8 K 3       float64[K][3] tristimulus weights W (perfect white Y = 100)
    …       n³          uint8[n][n][n] node status (0 exact, 1 moved toward grey)
    end−4   4           uint32 CRC-32 (zlib/PNG polynomial) of every preceding byte

A renderer needs only the header and the node reflectances: see ``docs/upsampling/reader.py``
and ``docs/upsampling/reader.c`` (and ``docs/upsampling.md`` for the lookup).
"""

from __future__ import annotations

import json
import os
import struct
import zlib
from pathlib import Path

import numpy as np

from ..errors import SpectrumError
from .table import MAX_RESOLUTION, MIN_RESOLUTION, NODE_STATUS, UpsamplingTable

__all__ = ["save_table", "load_table", "MAGIC", "VERSION"]

MAGIC = b"SCUPTBL\0"
VERSION = 1
HEADER = struct.Struct("<8sIIII2d9d")  # 112 bytes
MAX_SAMPLES = 4096
FORMAT_NAME = "spectrocolor spectral upsampling table"


def _sections(n: int, K: int):
    """(attribute, shape, dtype) of the array sections, in file order."""
    nodes, cells = (n, n, n), (n - 1,) * 3
    return (("reflectance", (*nodes, K), "<f8"), ("node_XYZ100", (*nodes, 3), "<f8"),
            ("roughness", nodes, "<f8"), ("multipliers", (*nodes, 3), "<f8"),
            ("cell_excess_bound", cells, "<f8"), ("cell_excess_measured", cells, "<f8"),
            ("weights", (K, 3), "<f8"), ("node_status", nodes, "u1"))


def table_bytes(table: UpsamplingTable) -> bytes:
    """The file's bytes for ``table`` (see the module docstring for the layout).

    Parameters
    ----------
    table : UpsamplingTable
        The table to serialise.

    Returns
    -------
    bytes
        Header, JSON metadata, the arrays, and a CRC-32 checksum.

    Raises
    ------
    SpectrumError
        If an array of the table has an unexpected shape.

    Examples
    --------
    >>> from spectrocolor.upsampling import upsampling_table
    >>> data = table_bytes(upsampling_table("sRGB", resolution=2, measure_excess=False))
    >>> data[:len(MAGIC)] == MAGIC
    True
    """
    n, K = table.resolution, table.wavelengths_nm.size
    meta = {"format": FORMAT_NAME, "space": table.space, "illuminant": table.illuminant,
            "observer": table.observer,
            "node_status": {str(k): v for k, v in NODE_STATUS.items()}}
    text = json.dumps(meta, ensure_ascii=False).encode("utf-8")
    text += b" " * (-len(text) % 8)
    grid = table.wavelengths_nm
    parts = [HEADER.pack(MAGIC, VERSION, n, K, len(text), float(grid[0]),
                         float(grid[1] - grid[0]), *np.asarray(table.matrix, float).ravel()),
             text]
    for name, shape, dtype in _sections(n, K):
        array = np.ascontiguousarray(getattr(table, name), dtype=dtype)
        if array.shape != shape:
            raise SpectrumError(f"table.{name}: shape {array.shape}, expected {shape}")
        parts.append(array.tobytes())
    body = b"".join(parts)
    return body + struct.pack("<I", zlib.crc32(body))


def save_table(table: UpsamplingTable, path) -> Path:
    """Write ``table`` to ``path`` atomically (temporary file beside it, checked, renamed).

    Parameters
    ----------
    table : UpsamplingTable
        The table to save.
    path : str or os.PathLike
        Output file (conventionally ``.scup``).

    Returns
    -------
    pathlib.Path
        ``path``, the table's bytes.

    Raises
    ------
    SpectrumError
        For something other than an UpsamplingTable.
    spectrocolor.safe_write.OutputError
        The table could not be written, or its size on disk differs; see :term:`atomic write`.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> from spectrocolor.upsampling import upsampling_table
    >>> table = upsampling_table("sRGB", resolution=2, measure_excess=False)
    >>> path = save_table(table, pathlib.Path(tempfile.mkdtemp()) / "srgb.scup")
    >>> back = load_table(path)
    >>> bool((back.reflectance == table.reflectance).all()), back.space
    (True, 'sRGB')
    """
    from ..safe_write import verify_size, write_bytes

    if not isinstance(table, UpsamplingTable):
        raise SpectrumError(f"table: expected an UpsamplingTable, got {type(table).__name__}")
    data = table_bytes(table)
    return write_bytes(path, data, verify=lambda p: verify_size(p, len(data)))


def _bad(path, what: str) -> SpectrumError:
    return SpectrumError(f"{path}: not a valid spectrocolor upsampling table: {what}")


def _read_exactly(handle, count: int, path, into=None):
    """``count`` bytes from ``handle`` (into the buffer ``into`` if given); short reads refused."""
    if into is None:
        data = handle.read(count)
        if len(data) != count:
            raise _bad(path, "the file ended early (it changed while being read?)")
        return data
    done = 0
    while done < count:
        got = handle.readinto(into[done:])
        if not got:
            raise _bad(path, "the file ended early (it changed while being read?)")
        done += got
    return into


def load_table(path, *, memory_budget=None) -> UpsamplingTable:
    """Read a table written by :func:`save_table`, checking its size, checksum and values.

    The sizes in the header are checked before anything is read: against the accepted ranges,
    the file's length, the bytes it really stores on disk (a sparse file promising gigabytes of
    holes is refused) and the memory budget (the table is held in memory, about the file's
    size). The sections are read straight into their arrays, the checksum computed on the way.

    Parameters
    ----------
    path : str or os.PathLike
        The table file.
    memory_budget : int or str, keyword-only, optional
        The most bytes the table may take in memory; see :term:`memory budget`.

    Returns
    -------
    UpsamplingTable
        The table, its arrays read-only.

    Raises
    ------
    SpectrumError
        Wrong magic or version, sizes out of range, a length that does not match the header, a
        checksum mismatch, malformed metadata, or values outside their ranges.
    spectrocolor.errors.BudgetError
        (a ``SpectrumError``) A sparse file, or a table larger than the memory budget.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> from spectrocolor.upsampling import upsampling_table
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     path = save_table(upsampling_table("sRGB", resolution=2, measure_excess=False),
    ...                       pathlib.Path(folder) / "srgb.scup")
    ...     load_table(path).resolution
    2
    """
    from ..budget import check_bytes, check_file_claim

    path = Path(path)
    try:
        size = os.stat(path).st_size
        if not path.is_file():
            raise _bad(path, "not a regular file")
        with open(path, "rb") as handle:
            head = handle.read(HEADER.size)
            if len(head) < HEADER.size:
                raise _bad(path, f"{size} bytes, shorter than the {HEADER.size}-byte header")
            magic, version, n, K, J, start, step, *matrix_entries = HEADER.unpack(head)
            if magic != MAGIC:
                raise _bad(path, f"magic {magic!r}, expected {MAGIC!r}")
            if version != VERSION:
                raise _bad(path, f"format version {version}; this reader reads {VERSION}")
            if not MIN_RESOLUTION <= n <= MAX_RESOLUTION or not 2 <= K <= MAX_SAMPLES:
                raise _bad(path, f"n = {n} nodes per axis and K = {K} samples; accepted "
                           f"n in {MIN_RESOLUTION}..{MAX_RESOLUTION}, K in 2..{MAX_SAMPLES}")
            if J % 8 or J > 65536:
                raise _bad(path, f"metadata length {J} (must be a multiple of 8, at most 65536)")
            sections = _sections(n, K)
            expected = HEADER.size + J + sum(
                int(np.prod(s)) * np.dtype(d).itemsize for _, s, d in sections) + 4
            if size != expected:
                raise _bad(path, f"{size} bytes; the header promises {expected}")
            claim = f"the header claims a table of n = {n} nodes per axis and K = {K} samples"
            check_file_claim(path, expected, claim)
            check_bytes(expected, f"{path}: {claim}", budget=memory_budget)
            crc = zlib.crc32(head)
            text = _read_exactly(handle, J, path)
            crc = zlib.crc32(text, crc)
            arrays = {}
            for name, shape, dtype in sections:
                array = np.empty(shape, dtype=dtype)
                buffer = array.reshape(-1).data.cast("B")
                _read_exactly(handle, len(buffer), path, into=buffer)
                crc = zlib.crc32(buffer, crc)
                arrays[name] = array.astype(np.dtype(dtype).newbyteorder("="), copy=False)
            stored_crc = _read_exactly(handle, 4, path)
    except OSError as exc:
        raise SpectrumError(f"{path}: cannot read the table ({exc.strerror or exc})") from None
    if crc != struct.unpack("<I", stored_crc)[0]:
        raise _bad(path, "CRC-32 mismatch (the file is damaged or truncated)")
    try:
        meta = json.loads(text.decode("utf-8"))
        labels = [meta[k] for k in ("space", "illuminant", "observer")]
    except (UnicodeDecodeError, ValueError, KeyError, TypeError, RecursionError):  # RecursionError: nested JSON
        raise _bad(path, "the metadata block is not the expected JSON object") from None
    if not all(isinstance(v, str) for v in labels):
        raise _bad(path, "space, illuminant and observer must be strings")
    if not (np.isfinite(start) and np.isfinite(step) and step > 0):
        raise _bad(path, f"wavelength start {start!r} and step {step!r}")
    rho = arrays["reflectance"]
    if not np.all((rho >= 0.0) & (rho <= 1.0)):
        raise _bad(path, "node reflectances outside [0, 1] (or NaN)")
    if not np.all(np.isin(arrays["node_status"], list(NODE_STATUS))):
        raise _bad(path, f"node status codes other than {sorted(NODE_STATUS)}")
    matrix = np.array(matrix_entries, dtype=float).reshape(3, 3)
    if not (np.all(np.isfinite(matrix)) and np.all(np.isfinite(arrays["weights"]))):
        raise _bad(path, "non-finite colour map or weights")
    grid = start + step * np.arange(K)
    return UpsamplingTable(wavelengths_nm=grid, matrix=matrix, space=labels[0],
                           illuminant=labels[1], observer=labels[2], **arrays)
