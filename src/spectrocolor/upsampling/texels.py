"""Texel coefficient files (``.sctx``): a texture's node indices and weights for renderers.

:func:`~spectrocolor.upsampling.texel_coefficients` gives each texel four node indices into a
table's ``(n³, K)`` node reflectances and four barycentric weights; a renderer holding the
table (``.scup``) evaluates the texel's reflectance at any wavelength as
``Σ_j weights[j] · ρ_{nodes[j]}(λ)`` without a lookup at render time. This module writes and
reads them in one documented little-endian layout (version 1; arrays in C order, rows from the
top of the image)::

    offset   size      content
    0        8         magic b"SCTEXEL\\0"
    8        4         uint32 format version (1)
    12       4         uint32 W, texels per row (1..65535)
    16       4         uint32 H, rows (1..65535)
    20       4         uint32 n, nodes per axis of the table (2..129)
    24       4         uint32 K, wavelength samples of the table (2..4096)
    28       4         uint32 table fingerprint: CRC-32 of the table's node reflectances as
                       little-endian float64 (the .scup section after the metadata)
    32       16 W H    uint32[H][W][4] node indices (each < n³)
    …        16 W H    float32[H][W][4] weights (≥ 0, summing to 1 within float32 rounding)
    …        W H       uint8[H][W] flags: bit 0 set = the texel's colour is reproduced
                       exactly (see ``upsample``'s ``exact``)
    end−4    4         uint32 CRC-32 (zlib/PNG polynomial) of every preceding byte

The fingerprint ties the file to its table: :func:`load_texel_coefficients` refuses a table
whose node reflectances differ. Reference readers: ``docs/upsampling/reader.py`` and
``docs/upsampling/texels.c``.
"""

from __future__ import annotations

import os
import struct
import zlib
from collections.abc import Iterable
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..errors import ColorimetryError, SpectrumError
from .apply import texel_coefficients
from .table import MAX_RESOLUTION, MIN_RESOLUTION, UpsamplingTable

__all__ = ["TexelCoefficients", "load_texel_coefficients", "save_texel_coefficients",
           "write_texel_blocks", "table_fingerprint"]

MAGIC = b"SCTEXEL\0"
VERSION = 1
HEADER = struct.Struct("<8sIIIIII")  # 32 bytes
MAX_SIDE = 65535
MAX_SAMPLES = 4096


def table_fingerprint(table: UpsamplingTable) -> int:
    """CRC-32 of the table's node reflectances as little-endian float64 (the ``.scup`` bytes).

    Parameters
    ----------
    table : UpsamplingTable
        The table the coefficients index.

    Returns
    -------
    int
        The unsigned 32-bit checksum stored in a texel file's header.

    Examples
    --------
    >>> from spectrocolor.upsampling import upsampling_table
    >>> table = upsampling_table("sRGB", "D65", resolution=2, measure_excess=False)
    >>> 0 <= table_fingerprint(table) < 2**32
    True
    """
    return zlib.crc32(np.ascontiguousarray(table.reflectance, dtype="<f8").tobytes())


@dataclass(frozen=True)
class TexelCoefficients:
    """The contents of a texel coefficient file.

    Attributes
    ----------
    nodes : ndarray (H, W, 4) uint32
        Flat node indices into the table's ``(n³, K)`` reflectances.
    weights : ndarray (H, W, 4) float32
        Barycentric weights.
    exact : ndarray (H, W) bool
        The texel's colour is reproduced exactly.
    resolution, samples : int
        ``n`` and ``K`` of the table.
    fingerprint : int
        :func:`table_fingerprint` of the table.
    """

    nodes: np.ndarray
    weights: np.ndarray
    exact: np.ndarray
    resolution: int
    samples: int
    fingerprint: int

    def reflectance(self, table: UpsamplingTable) -> np.ndarray:
        """The texels' reflectances (H, W, K) from ``table`` (float64 blend of float32 weights).

        Parameters
        ----------
        table : UpsamplingTable
            The table the file was made for (checked by its fingerprint).

        Returns
        -------
        numpy.ndarray, shape (H, W, K)
            ``Σ_j weights[j] · ρ_{nodes[j]}``, clamped to at most 1.

        Raises
        ------
        ColorimetryError
            For another table.

        Examples
        --------
        >>> import numpy as np, tempfile, pathlib
        >>> from spectrocolor.upsampling import upsampling_table
        >>> table = upsampling_table("sRGB", "D65", resolution=3, measure_excess=False)
        >>> with tempfile.TemporaryDirectory() as folder:
        ...     path = save_texel_coefficients(table, np.full((1, 2, 3), 0.5),
        ...                                    pathlib.Path(folder) / "grey.sctx")
        ...     rho = load_texel_coefficients(path, table).reflectance(table)
        >>> rho.shape, bool(abs(rho - 0.5).max() < 1e-6)
        ((1, 2, 81), True)
        """
        _check_table(table, self.resolution, self.samples, self.fingerprint, "table")
        values = table.flat_reflectance
        rho = values[self.nodes[..., 0]] * self.weights[..., 0:1].astype(np.float64)
        for j in range(1, 4):
            rho += values[self.nodes[..., j]] * self.weights[..., j:j + 1].astype(np.float64)
        return np.minimum(rho, 1.0)


def _check_table(table, n: int, K: int, fingerprint: int, where: str) -> None:
    if not isinstance(table, UpsamplingTable):
        raise ColorimetryError(f"table: expected an UpsamplingTable, got {type(table).__name__}")
    if (table.resolution, table.wavelengths_nm.size) != (n, K) or \
            table_fingerprint(table) != fingerprint:
        raise ColorimetryError(
            f"{where}: the coefficients were made for another table (n = {n}, K = {K}, "
            f"fingerprint {fingerprint:08x}; this table: n = {table.resolution}, "
            f"K = {table.wavelengths_nm.size}, fingerprint {table_fingerprint(table):08x})")


def texel_bytes(table: UpsamplingTable, rgb_linear, out_of_range: str = "toward-grey") -> bytes:
    """The ``.sctx`` file's bytes for an image of table coordinates ``(H, W, 3)``.

    Parameters
    ----------
    table : UpsamplingTable
        The table the coefficients index.
    rgb_linear : array_like, shape (H, W, 3)
        Table coordinates of the texels (e.g. from ``rgb_linear_from_image``).
    out_of_range : str, default "toward-grey"
        A key of :data:`~spectrocolor.upsampling.OUT_OF_RANGE_STRATEGIES` other than "nan".

    Returns
    -------
    bytes
        Header, the three arrays and the CRC-32.

    Raises
    ------
    ColorimetryError
        For a wrong table, an image that is not (H, W, 3) with sides up to 65535, or "nan".

    Examples
    --------
    >>> import numpy as np
    >>> from spectrocolor.upsampling import upsampling_table
    >>> table = upsampling_table("sRGB", "D65", resolution=2, measure_excess=False)
    >>> data = texel_bytes(table, np.zeros((2, 3, 3)))
    >>> data[:8], len(data) == 32 + 2 * 3 * (16 + 16 + 1) + 4
    (b'SCTEXEL\\x00', True)
    """
    if not isinstance(table, UpsamplingTable):
        raise ColorimetryError(f"table: expected an UpsamplingTable, got {type(table).__name__}")
    shape = np.shape(rgb_linear)
    if len(shape) != 3 or shape[2] != 3 or not (1 <= shape[0] <= MAX_SIDE and 1 <= shape[1] <= MAX_SIDE):
        raise ColorimetryError(f"rgb_linear: expected an image of shape (H, W, 3) with sides 1 to "
                               f"{MAX_SIDE}, got {shape}")
    from .apply import OUT_OF_RANGE_STRATEGIES

    if OUT_OF_RANGE_STRATEGIES.canonical(out_of_range) == "nan":
        raise ColorimetryError("out_of_range: 'nan' has no coefficients; use 'toward-grey' or 'clip'")
    nodes, weights, exact = texel_coefficients(table, rgb_linear, out_of_range)
    height, width = shape[:2]
    body = b"".join([
        HEADER.pack(MAGIC, VERSION, width, height, table.resolution, table.wavelengths_nm.size,
                    table_fingerprint(table)),
        np.ascontiguousarray(nodes, dtype="<u4").tobytes(),
        np.ascontiguousarray(weights, dtype="<f4").tobytes(),
        exact.astype(np.uint8).tobytes(),
    ])
    return body + struct.pack("<I", zlib.crc32(body))


def save_texel_coefficients(table: UpsamplingTable, rgb_linear, path,
                            out_of_range: str = "toward-grey") -> Path:
    """Compute a texture's texel coefficients and write them to ``path`` atomically.

    Parameters
    ----------
    table : UpsamplingTable
        The table the coefficients index (save it too, with :func:`save_table`).
    rgb_linear : array_like, shape (H, W, 3)
        Table coordinates of the texels.
    path : str or os.PathLike
        Output file (conventionally ``.sctx``); written beside, checked and renamed.
    out_of_range : str, default "toward-grey"
        "toward-grey" or "clip" (see :data:`~spectrocolor.upsampling.OUT_OF_RANGE_STRATEGIES`).

    Returns
    -------
    pathlib.Path
        ``path``, the coefficients' bytes.

    Raises
    ------
    ColorimetryError
        As :func:`texel_bytes`.
    spectrocolor.safe_write.OutputError
        The coefficients could not be written or read back whole; see :term:`atomic write`.

    Examples
    --------
    >>> import numpy as np, tempfile, pathlib
    >>> from spectrocolor.upsampling import upsampling_table
    >>> table = upsampling_table("sRGB", "D65", resolution=3, measure_excess=False)
    >>> texture = np.random.default_rng(0).random((4, 5, 3))
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     path = save_texel_coefficients(table, texture, pathlib.Path(folder) / "t.sctx")
    ...     back = load_texel_coefficients(path, table)
    >>> back.nodes.shape, back.weights.dtype.name, bool(back.exact.all())
    ((4, 5, 4), 'float32', True)
    """
    from ..safe_write import verify_size, write_bytes

    data = texel_bytes(table, rgb_linear, out_of_range)
    return write_bytes(path, data, verify=lambda p: verify_size(p, len(data)))


def write_texel_blocks(path, table: UpsamplingTable, blocks: Iterable[np.ndarray], width: int,
                       height: int, out_of_range: str = "toward-grey") -> tuple[Path, int]:
    """Write a ``.sctx`` file from blocks of rows of table coordinates, one block at a time.

    Each block's node indices, weights and flags are written at their places in the file's
    three sections as soon as they are computed; the CRC-32 is then computed by reading the file
    back in blocks. Memory: one block, whatever the texture's size. The file is written beside
    ``path``, checked and renamed, like every writer.

    Parameters
    ----------
    path : str or os.PathLike
        Output file (conventionally ``.sctx``).
    table : UpsamplingTable
        The table the coefficients index.
    blocks : iterable of numpy.ndarray, each shape (rows, width, 3)
        Table coordinates (e.g. from ``rgb_linear_from_image``), top to bottom, ``height`` rows
        in all.
    width, height : int
        Texels per row and rows (1 to 65535 each).
    out_of_range : str, default "toward-grey"
        "toward-grey" or "clip" (see :data:`~spectrocolor.upsampling.OUT_OF_RANGE_STRATEGIES`).

    Returns
    -------
    tuple
        ``(path, inexact)``: the file written and the number of texels not reproduced exactly.

    Raises
    ------
    ColorimetryError
        As :func:`texel_bytes`, and for blocks that are not ``height`` rows of ``(width, 3)``.
    spectrocolor.safe_write.OutputError
        The file could not be written block by block, or its size on disk differs
        (:term:`atomic write`).

    Examples
    --------
    >>> import numpy as np, tempfile, pathlib
    >>> from spectrocolor.upsampling import upsampling_table
    >>> table = upsampling_table("sRGB", "D65", resolution=3, measure_excess=False)
    >>> texture = np.random.default_rng(0).random((4, 5, 3))
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     path, inexact = write_texel_blocks(pathlib.Path(folder) / "t.sctx", table,
    ...                                        [texture[:3], texture[3:]], 5, 4)
    ...     same = path.read_bytes() == texel_bytes(table, texture)
    >>> same, inexact
    (True, 0)
    """
    from ..budget import block_bytes
    from ..safe_write import atomic_path, verify_size
    from .apply import OUT_OF_RANGE_STRATEGIES

    if not isinstance(table, UpsamplingTable):
        raise ColorimetryError(f"table: expected an UpsamplingTable, got {type(table).__name__}")
    if not (1 <= width <= MAX_SIDE and 1 <= height <= MAX_SIDE):
        raise ColorimetryError(f"width, height: sides 1 to {MAX_SIDE} texels, got {width} x {height}")
    if OUT_OF_RANGE_STRATEGIES.canonical(out_of_range) == "nan":
        raise ColorimetryError("out_of_range: 'nan' has no coefficients; use 'toward-grey' or 'clip'")
    texels = width * height
    size = HEADER.size + 33 * texels + 4
    inexact = 0
    with atomic_path(path, verify=lambda p: verify_size(p, size)) as temporary:
        with open(temporary, "w+b") as out:
            out.write(HEADER.pack(MAGIC, VERSION, width, height, table.resolution,
                                  table.wavelengths_nm.size, table_fingerprint(table)))
            row = 0
            for block in blocks:
                block = np.asarray(block)
                if block.ndim != 3 or block.shape[1:] != (width, 3) or row + len(block) > height:
                    raise ColorimetryError(f"blocks: expected {height} rows of shape ({width}, 3) in "
                                           f"all; got a block of shape {block.shape} after {row} rows")
                nodes, weights, exact = texel_coefficients(table, block, out_of_range)
                first = row * width
                for at, data in ((HEADER.size + 16 * first, np.ascontiguousarray(nodes, "<u4")),
                                 (HEADER.size + 16 * texels + 16 * first, np.ascontiguousarray(weights, "<f4")),
                                 (HEADER.size + 32 * texels + first, exact.astype(np.uint8))):
                    out.seek(at)
                    out.write(data.tobytes())
                inexact += int(np.count_nonzero(~exact))
                row += len(block)
            if row != height:
                raise ColorimetryError(f"blocks: {row} rows given for a texture of height {height}")
            out.seek(0)
            crc, left, piece = 0, size - 4, block_bytes()
            while left:
                data = out.read(min(left, piece))
                crc = zlib.crc32(data, crc)
                left -= len(data)
            out.seek(size - 4)
            out.write(struct.pack("<I", crc))
    return Path(path), inexact


def load_texel_coefficients(path, table: UpsamplingTable | None = None, *,
                            memory_budget=None) -> TexelCoefficients:
    """Read a ``.sctx`` file, checking its size, checksum and values (and its table, if given).

    The header's sizes are checked before anything is read: against the accepted ranges, the
    file's length, the bytes it really stores on disk (a sparse file promising 142 GB of holes is
    refused) and the memory budget (the coefficients are held in memory: 33 bytes per texel).
    Each section is read straight into its array and checked in blocks.

    Parameters
    ----------
    path : str or os.PathLike
        The file.
    table : UpsamplingTable, optional
        The table it should belong to: refused unless ``n``, ``K`` and the fingerprint match.
    memory_budget : int or str, keyword-only, optional
        The most bytes the coefficients may take in memory; see :term:`memory budget`.

    Returns
    -------
    TexelCoefficients
        The arrays and the table's identity.

    Raises
    ------
    SpectrumError
        Not a version-1 texel file, sizes out of range, a length that does not match the header,
        a checksum mismatch, node indices ≥ n³, or weights that are negative, not finite or do
        not sum to 1.
    spectrocolor.errors.BudgetError
        (a ``SpectrumError``) A sparse file, or coefficients larger than the memory budget.
    ColorimetryError
        For a ``table`` other than the file's.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     (pathlib.Path(folder) / "x.sctx").write_bytes(b"SCTEXEL")
    ...     load_texel_coefficients(pathlib.Path(folder) / "x.sctx")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    spectrocolor.errors.SpectrumError: .../x.sctx: not a valid texel coefficient file: 7 bytes, ...
    """
    from ..budget import block_bytes, check_bytes, check_file_claim

    path = Path(path)

    def bad(what: str) -> SpectrumError:
        return SpectrumError(f"{path}: not a valid texel coefficient file: {what}")

    def read_into(handle, array: np.ndarray, crc: int) -> int:
        buffer = array.reshape(-1).data.cast("B")
        done = 0
        while done < len(buffer):
            got = handle.readinto(buffer[done:])
            if not got:
                raise bad("the file ended early (it changed while being read?)")
            done += got
        return zlib.crc32(buffer, crc)

    try:
        size = os.stat(path).st_size
        if not path.is_file():
            raise bad("not a regular file")
        with open(path, "rb") as handle:
            head = handle.read(HEADER.size)
            if len(head) < HEADER.size:
                raise bad(f"{size} bytes, shorter than the {HEADER.size}-byte header")
            magic, version, width, height, n, K, fingerprint = HEADER.unpack(head)
            if magic != MAGIC:
                raise bad(f"magic {magic!r}, expected {MAGIC!r}")
            if version != VERSION:
                raise bad(f"format version {version}; this reader reads {VERSION}")
            if not (1 <= width <= MAX_SIDE and 1 <= height <= MAX_SIDE
                    and MIN_RESOLUTION <= n <= MAX_RESOLUTION and 2 <= K <= MAX_SAMPLES):
                raise bad(f"W = {width}, H = {height}, n = {n}, K = {K}; accepted W, H in "
                          f"1..{MAX_SIDE}, n in {MIN_RESOLUTION}..{MAX_RESOLUTION}, K in "
                          f"2..{MAX_SAMPLES}")
            texels = width * height
            expected = HEADER.size + 33 * texels + 4
            if size != expected:
                raise bad(f"{size} bytes; the header promises {expected}")
            claim = f"the header claims {width} x {height} texels"
            check_file_claim(path, expected, claim)
            check_bytes(expected, f"{path}: {claim}", budget=memory_budget)
            nodes = np.empty((height, width, 4), "<u4")
            weights = np.empty((height, width, 4), "<f4")
            flags = np.empty((height, width), np.uint8)
            crc = zlib.crc32(head)
            for array in (nodes, weights, flags):
                crc = read_into(handle, array, crc)
            stored_crc = handle.read(4)
    except OSError as exc:
        raise SpectrumError(f"{path}: cannot read the file ({exc.strerror or exc})") from None
    if len(stored_crc) != 4 or crc != struct.unpack("<I", stored_crc)[0]:
        raise bad("CRC-32 mismatch (the file is damaged or truncated)")
    nodes, weights = nodes.astype(np.uint32, copy=False), weights.astype(np.float32, copy=False)
    rows = max(1, block_bytes(memory_budget) // (48 * width))  # float64 sums of a block of rows
    for top in range(0, height, rows):
        block = weights[top:top + rows]
        if nodes[top:top + rows].max() >= n**3:
            raise bad(f"node index {int(nodes[top:top + rows].max())} ≥ n³ = {n**3}")
        sums = block.astype(np.float64).sum(axis=-1)
        if not (np.all(np.isfinite(block)) and block.min() >= 0
                and np.all(np.abs(sums - 1.0) <= 1e-6)):
            raise bad("weights negative, not finite, or not summing to 1")
    if flags.max() > 1:
        raise bad("flags other than 0 and 1")
    found = TexelCoefficients(nodes, weights, flags.view(bool), n, K, fingerprint)
    if table is not None:
        _check_table(table, n, K, fingerprint, str(path))
    return found
