"""Read 8- and 16-bit PNG images as integer codes, without losing bits.

Pillow opens a 16-bit RGB PNG as 8-bit RGB (it drops the low byte), so a 16-bit photo cannot
reach the upsampling table at full precision through it. This reader decodes the PNG
datastream itself: chunks with their CRC-32, the zlib stream of the IDAT chunks, and the five
scanline filters (None, Sub, Up, Average, Paeth).

The filters are undone with NumPy along anti-diagonals of the image: a byte depends only on
the reconstructed bytes to its left, above and above-left, so every pixel on one anti-diagonal
``row + column = d`` can be reconstructed at once from the previous two diagonals, whatever the
rows' filter types (bands of :data:`BAND` rows, ``BAND + width − 1`` vectorised steps each;
about 1 megapixel of 16-bit RGB per second). With numba installed (extra ``fast``) a compiled
row-by-row loop does the same (:mod:`spectrocolor.upsampling.compiled`).

Accepted: bit depth 8 or 16; colour types 0 (grey), 2 (RGB), 4 (grey + alpha), 6 (RGBA); no
interlacing. Palette images, bit depths 1, 2 and 4 and Adam7-interlaced files are refused with
a message (Pillow reads the first two without loss). Ancillary chunks (gAMA, cHRM, iCCP, sRGB,
sBIT, tRNS, text) are skipped: the codes are returned as stored, and the caller says which RGB
space they are in.

References
----------
W3C, *Portable Network Graphics (PNG) Specification*, 3rd ed. (2025): sections 5 (datastream,
chunks, CRC), 7 and 9 (scanlines and filters, including the Paeth predictor), 11.2 (IHDR).
"""

from __future__ import annotations

import io
import os
import struct
import zlib
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..errors import SpectrumError

__all__ = ["decode_png", "read_png", "png_header", "iter_png_rows", "PNGHeader", "MAX_PIXELS"]

SIGNATURE = b"\x89PNG\r\n\x1a\n"
#: Channels per colour type (PNG specification, table 11.1), for the types read here.
CHANNELS = {0: 1, 2: 3, 4: 2, 6: 4}
#: Largest image decoded, in pixels (a 24-megapixel photo is 2.4e7).
MAX_PIXELS = 2**28
_CRITICAL = (b"IHDR", b"PLTE", b"IDAT", b"IEND")
#: Chunks up to this size are read whole and their CRC checked before their data are used;
#: longer ones are read in pieces of this size (their CRC is checked at their end).
_PIECE = 2**24


@dataclass(frozen=True)
class PNGHeader:
    """The IHDR fields of a PNG this reader accepts.

    Attributes
    ----------
    width, height : int
        Pixels.
    bit_depth : int
        8 or 16.
    colour_type : int
        0 (grey), 2 (RGB), 4 (grey + alpha) or 6 (RGBA).
    channels : int
        1, 3, 2 or 4.
    """

    width: int
    height: int
    bit_depth: int
    colour_type: int
    channels: int

    @property
    def dtype(self) -> np.dtype:
        """uint8 or uint16 (native byte order): the dtype of the codes returned."""
        return np.dtype(np.uint16 if self.bit_depth == 16 else np.uint8)

    @property
    def line_bytes(self) -> int:
        """Bytes of one filtered scanline in the datastream (filter byte included)."""
        return 1 + self.width * self.channels * self.bit_depth // 8


def read_png(path, *, memory_budget=None) -> np.ndarray:
    """The codes of an 8- or 16-bit PNG file, ``(H, W, C)`` uint8 or uint16.

    The file is read chunk by chunk and decoded in blocks of rows (:func:`iter_png_rows`) into
    one array, which is checked against the memory budget before it is made.

    Parameters
    ----------
    path : str or os.PathLike
        The PNG file.
    memory_budget : int or str, keyword-only, optional
        Most bytes the codes may take (e.g. ``"2GiB"``); default the budget in force
        (:func:`spectrocolor.budget.memory_budget`).

    Returns
    -------
    numpy.ndarray, shape (H, W, C), uint8 or uint16
        ``C`` is 1 (grey), 2 (grey, alpha), 3 (RGB) or 4 (RGBA); samples as stored (16-bit
        samples in native byte order).

    Raises
    ------
    SpectrumError
        The file cannot be read, or is not a PNG this reader accepts (see the module
        docstring); the message names the file and what is wrong.
    spectrocolor.errors.BudgetError
        (a ``SpectrumError``) The image is larger than the memory budget: read it in blocks
        with :func:`iter_png_rows`.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> import numpy as np
    >>> from spectrocolor.pictures import write_image
    >>> codes = np.array([[[0, 257, 65535], [1000, 2000, 3000]]], dtype=np.uint16)
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     back = read_png(write_image(pathlib.Path(folder) / "codes16.png", codes))
    >>> back.dtype.name, back.shape, back[0, 0].tolist()
    ('uint16', (1, 2, 3), [0, 257, 65535])
    """
    return _whole(Path(path), str(path), memory_budget)


def decode_png(data: bytes, source: str = "PNG data", *, memory_budget=None) -> np.ndarray:
    """Decode a PNG datastream held in memory (see :func:`read_png`).

    Parameters
    ----------
    data : bytes
        The whole file.
    source : str, default "PNG data"
        What to call it in error messages (e.g. the file name).
    memory_budget : int or str, keyword-only, optional
        As for :func:`read_png`.

    Returns
    -------
    numpy.ndarray, shape (H, W, C), uint8 or uint16
        As :func:`read_png`.

    Raises
    ------
    SpectrumError
        For anything that is not an accepted, intact PNG.

    Examples
    --------
    >>> decode_png(b"GIF89a", "picture.gif")
    Traceback (most recent call last):
    ...
    spectrocolor.errors.SpectrumError: picture.gif: not a PNG file (no PNG signature)
    """
    if not isinstance(data, bytes | bytearray | memoryview):
        raise SpectrumError(f"{source}: expected the file's bytes, got {type(data).__name__}")
    return _whole(bytes(data), source, memory_budget)


def _whole(source, name: str, memory_budget) -> np.ndarray:
    from ..budget import check_bytes

    with _Datastream(source, name) as stream:
        header = stream.header
        check_bytes(header.height * header.width * header.channels * header.dtype.itemsize,
                    f"{stream.name}: {header.width} x {header.height} pixels of {header.bit_depth}-bit "
                    "codes (read it in blocks with iter_png_rows)", budget=memory_budget)
        out = np.empty((header.height, header.width, header.channels), header.dtype)
        for top, block in stream.rows(None, memory_budget):
            out[top:top + len(block)] = block
    return out


def png_header(source, name: str | None = None) -> PNGHeader:
    """The size and sample format of a PNG, from its IHDR chunk (no pixel is decoded).

    Parameters
    ----------
    source : str, os.PathLike or bytes
        A PNG file, or a datastream held in memory.
    name : str, optional
        What to call it in error messages (default: the path, or "PNG data").

    Returns
    -------
    PNGHeader
        Width, height, bit depth, colour type and channels.

    Raises
    ------
    SpectrumError
        Not a PNG, a damaged IHDR, or a format this reader does not take (see the module
        docstring), or more than :data:`MAX_PIXELS` pixels.

    Examples
    --------
    >>> import io
    >>> from PIL import Image
    >>> buffer = io.BytesIO()
    >>> Image.new("RGB", (640, 480)).save(buffer, "PNG")
    >>> header = png_header(buffer.getvalue())
    >>> header.width, header.height, header.bit_depth, header.channels
    (640, 480, 8, 3)
    """
    with _Datastream(source, name) as stream:
        return stream.header


def iter_png_rows(source, *, rows_per_block: int | None = None, memory_budget=None,
                  name: str | None = None) -> Iterator[tuple[int, np.ndarray]]:
    """Decode a PNG in blocks of rows, holding one block (and zlib's window) at a time.

    The chunks are read from the file as they come (every chunk's CRC-32 checked), the image
    data inflated only as far as the next block needs, and each block's scanline filters undone
    from the last row of the block before. Memory: one block, whatever the image's size, so a
    photo of 2^28 pixels, or a few kilobytes of zeros claiming 40 megapixels, is decoded in
    bounded memory.

    Parameters
    ----------
    source : str, os.PathLike or bytes
        A PNG file, or a datastream held in memory.
    rows_per_block : int, optional
        Rows per block; default as many as fit in a block of the memory budget
        (:func:`spectrocolor.budget.block_rows`).
    memory_budget : int or str, optional
        The budget blocks are sized by (see :func:`spectrocolor.budget.memory_budget`).
    name : str, optional
        What to call the source in error messages.

    Yields
    ------
    tuple
        ``(top, codes)``: the first row of the block and its codes, shape ``(rows, W, C)``,
        uint8 or uint16 (native byte order).

    Raises
    ------
    SpectrumError
        As :func:`read_png`, when the damage is met (a block may have been yielded before).

    Examples
    --------
    >>> import io
    >>> import numpy as np
    >>> from PIL import Image
    >>> buffer = io.BytesIO()
    >>> Image.fromarray(np.arange(60, dtype=np.uint8).reshape(5, 4, 3)).save(buffer, "PNG")
    >>> [(top, block.shape) for top, block in iter_png_rows(buffer.getvalue(), rows_per_block=2)]
    [(0, (2, 4, 3)), (2, (2, 4, 3)), (4, (1, 4, 3))]
    """
    with _Datastream(source, name) as stream:
        yield from stream.rows(rows_per_block, memory_budget)


class _Datastream:
    """A PNG datastream read chunk by chunk from a file or from bytes; opened at the IHDR."""

    def __init__(self, source, name: str | None) -> None:
        if isinstance(source, bytes | bytearray | memoryview):
            self.name = name or "PNG data"
            self.handle, self.length = io.BytesIO(bytes(source)), len(source)
        else:
            self.name = name or str(source)
            try:
                self.handle = open(source, "rb")  # noqa: SIM115 (closed by __exit__)
                self.length = os.fstat(self.handle.fileno()).st_size
            except (OSError, TypeError) as exc:
                reason = getattr(exc, "strerror", None) or exc
                raise SpectrumError(f"{self.name}: cannot be read ({reason})") from None
        try:
            self.header = self._open()
        except BaseException:
            self.handle.close()
            raise

    def __enter__(self) -> _Datastream:
        return self

    def __exit__(self, *_exc) -> None:
        self.handle.close()

    def bad(self, what: str) -> SpectrumError:
        return SpectrumError(f"{self.name}: {what}")

    def _read(self, count: int) -> bytes:
        try:
            return self.handle.read(count)
        except OSError as exc:
            raise self.bad(f"cannot be read ({exc.strerror or exc})") from None

    def _open(self) -> PNGHeader:
        if self._read(len(SIGNATURE)) != SIGNATURE:
            raise self.bad("not a PNG file (no PNG signature)")
        self.position = len(SIGNATURE)
        self.ended, self.idat_seen, self.idat_closed = False, False, False
        kind, body = next(self._chunks(whole=True), (None, None))
        if kind is None:
            raise self.bad("no IEND chunk (the file is truncated)")
        if kind != b"IHDR":
            raise self.bad(f"the first chunk is {kind!r}, not IHDR")
        if len(body) != 13:
            raise self.bad("IHDR chunk repeated or not 13 bytes long")
        width, height, depth, colour_type, compression, filtering, interlace = struct.unpack(">IIBBBBB", body)
        if width == 0 or height == 0 or width > 2**31 - 1 or height > 2**31 - 1:
            raise self.bad(f"image size {width} x {height} is not allowed by PNG")
        if colour_type == 3 or depth not in (8, 16) or colour_type not in CHANNELS:
            raise self.bad(f"bit depth {depth}, colour type {colour_type}: this reader takes 8- or "
                           "16-bit grey, grey + alpha, RGB or RGBA (read palette and 1/2/4-bit "
                           "images with Pillow)")
        if compression != 0 or filtering != 0:
            raise self.bad(f"compression method {compression}, filter method {filtering}: PNG "
                           "defines only 0")
        if interlace != 0:
            raise self.bad("Adam7-interlaced PNG is not read; save the image without interlacing")
        if width * height > MAX_PIXELS:
            raise self.bad(f"{width} x {height} pixels; at most {MAX_PIXELS} are read")
        return PNGHeader(width, height, depth, colour_type, CHANNELS[colour_type])

    def _chunks(self, whole: bool = False) -> Iterator[tuple[bytes, bytes]]:
        """(kind, data) of the chunks in order, each chunk's CRC checked; IDAT data in pieces."""
        while not self.ended:
            head = self._read(8)
            if not head:
                raise self.bad("no IEND chunk (the file is truncated)")
            if len(head) < 8:
                raise self.bad(f"a chunk header is cut off at byte {self.position}")
            length, kind = struct.unpack(">I4s", head)
            if length > 2**31 - 1 or self.position + 12 + length > self.length:
                raise self.bad(f"chunk {kind!r} at byte {self.position} claims {length} bytes; the "
                               "file ends first (truncated?)")
            if self.position == len(SIGNATURE) and kind != b"IHDR":
                raise self.bad(f"the first chunk is {kind!r}, not IHDR")
            if kind == b"IHDR" and self.position != len(SIGNATURE):
                raise self.bad("IHDR chunk repeated or not 13 bytes long")
            if self.position != len(SIGNATURE) or not whole:
                self._structure(kind)
            if kind == b"IHDR" and length != 13:
                raise self.bad("IHDR chunk repeated or not 13 bytes long")
            crc, at, left = zlib.crc32(kind), self.position, length
            self.position += 12 + length
            body = b""
            streamed = kind == b"IDAT" and length > _PIECE  # used as it comes, CRC at its end
            while left:
                piece = self._read(min(left, _PIECE))
                if not piece:
                    raise self.bad(f"chunk {kind!r} at byte {at} is cut off (the file changed?)")
                crc = zlib.crc32(piece, crc)
                left -= len(piece)
                if streamed:
                    yield kind, piece
                elif length <= _PIECE or kind == b"IHDR":
                    body += piece
            stored = self._read(4)
            if len(stored) != 4 or struct.unpack(">I", stored)[0] != crc:
                raise self.bad(f"chunk {kind!r} at byte {at} fails its CRC-32 (damaged file)")
            if kind == b"IEND":
                self.ended = True
            if whole or (kind == b"IDAT" and not streamed):
                yield kind, body
            if whole:
                return

    def _structure(self, kind: bytes) -> None:
        """The order rules: consecutive IDAT chunks, no unknown critical chunk."""
        if kind == b"IDAT":
            if self.idat_closed:
                raise self.bad("the IDAT chunks are not consecutive")
            self.idat_seen = True
        elif kind == b"IHDR":
            raise self.bad("IHDR chunk repeated or not 13 bytes long")
        elif kind not in _CRITICAL and kind[0] & 0x20 == 0:
            raise self.bad(f"unknown critical chunk {kind!r}")
        if kind != b"IDAT" and self.idat_seen:
            self.idat_closed = True

    def rows(self, rows_per_block: int | None, memory_budget) -> Iterator[tuple[int, np.ndarray]]:
        """Blocks of decoded rows (see :func:`iter_png_rows`)."""
        from ..budget import block_rows

        header = self.header
        line = header.line_bytes
        if rows_per_block is None:  # the filtered rows, their reconstruction and int16 work
            rows_per_block = block_rows(6 * line, f"{self.name}: {header.width} pixels per row",
                                        budget=memory_budget)
        rows_per_block = max(1, min(int(rows_per_block), header.height))
        inflater = zlib.decompressobj()
        pending = bytearray()
        above = np.zeros(line - 1, np.uint8)
        top = 0
        data = self._chunks()
        while top < header.height:
            want = min(rows_per_block, header.height - top) * line
            while len(pending) < want:
                if inflater.unconsumed_tail:
                    piece = inflater.unconsumed_tail
                else:
                    piece = next((body for kind, body in data if kind == b"IDAT"), None)
                    if piece is None:
                        break
                try:
                    pending += inflater.decompress(piece, want - len(pending) + 1)
                except zlib.error as exc:
                    raise self.bad(f"the image data cannot be decompressed ({exc})") from None
                if inflater.eof:
                    break
            if len(pending) < want:
                if not self.idat_seen:
                    raise self.bad("no image data (IDAT chunk)")
                got = top * line + len(pending)
                raise self.bad(f"the image data holds {got} bytes (complete: {inflater.eof}); "
                               f"{header.width} x {header.height} pixels need {header.height * line}")
            block = np.frombuffer(bytes(pending[:want]), np.uint8).reshape(-1, line)
            del pending[:want]
            yield top, self._decode(block, above, top)
            above = self._last_row
            top += len(block)
        # the rest of the stream: nothing but the end of the zlib data, then IEND
        extra = len(pending)
        try:
            while not inflater.eof:
                piece = inflater.unconsumed_tail or next(
                    (body for kind, body in data if kind == b"IDAT"), None)
                if piece is None:
                    break
                extra += len(inflater.decompress(piece, 1))
                if extra:
                    break
        except zlib.error as exc:
            raise self.bad(f"the image data cannot be decompressed ({exc})") from None
        if extra or not inflater.eof:
            expected = header.height * line
            raise self.bad(f"the image data holds {expected}{'+' if extra else ''} bytes (complete: "
                           f"{inflater.eof}); {header.width} x {header.height} pixels need {expected}")
        for _ in data:  # the chunks after the image data: checked up to IEND
            pass

    def _decode(self, block: np.ndarray, above: np.ndarray, top: int) -> np.ndarray:
        """Codes of a block of filtered scanlines (R, line) below the reconstructed row ``above``."""
        header = self.header
        filters = block[:, 0]
        if filters.max() > 4:
            raise self.bad(f"row {top + int(np.argmax(filters > 4))} has filter type "
                           f"{int(filters.max())}; PNG defines 0-4")
        pixel_bytes = header.channels * header.bit_depth // 8
        # the row above goes first with filter 0 (None): it is reconstructed as itself
        filtered = np.concatenate([above[None, :], block[:, 1:]]).reshape(-1, header.width, pixel_bytes)
        pixels = _unfilter(filtered, np.concatenate([[0], filters]).astype(np.uint8))[1:]
        self._last_row = pixels[-1].reshape(-1).copy()
        if header.bit_depth == 16:
            samples = pixels.reshape(len(block), -1).view(">u2").astype(np.uint16)
        else:
            samples = pixels
        return samples.reshape(len(block), header.width, header.channels)


#: Rows undone together, at most; fewer for wide images, so that a band holds at most
#: BAND_BYTES of image bytes (the two int16 work arrays of a band take about four times that).
BAND = 1024
BAND_BYTES = 2**25


def _unfilter(filtered: np.ndarray, filters: np.ndarray) -> np.ndarray:
    """Undo the scanline filters of ``filtered`` (H, W, B) bytes; row ``r`` used ``filters[r]``.

    Done in bands of at most :data:`BAND` rows and :data:`BAND_BYTES` bytes, each along its
    anti-diagonals (:func:`_unfilter_band`),
    or by the compiled kernel (numba, row by row) where it is available.
    """
    from .compiled import kernels

    compiled = kernels()
    height, width, depth = filtered.shape
    out = np.empty((height, width, depth), dtype=np.uint8)
    if compiled is not None:
        compiled.unfilter_png(np.ascontiguousarray(filtered), np.ascontiguousarray(filters), out)
        return out
    above = np.zeros((width, depth), dtype=np.int16)  # the row above the image is zero
    band = max(1, min(BAND, BAND_BYTES // (width * depth)))
    for top in range(0, height, band):
        rows = slice(top, min(top + band, height))
        out[rows] = _unfilter_band(filtered[rows], filters[rows], above)
        above = out[rows.stop - 1].astype(np.int16)
    return out


def _unfilter_band(filtered: np.ndarray, filters: np.ndarray, above: np.ndarray) -> np.ndarray:
    """One band of rows below the reconstructed row ``above`` (W, B).

    Pixel (r, c) is stored skewed at ``[r + c + 2, r + 1]``: its left neighbour ``a`` (r, c−1)
    is then at ``[i − 1, j]``, the one above ``b`` at ``[i − 1, j − 1]`` and the upper-left
    ``c`` at ``[i − 2, j − 1]``, so each anti-diagonal ``i`` is one contiguous slice computed
    from the two before it. Column ``j = 0`` holds ``above``; cells with ``i = j`` (the
    column left of the image) stay zero.
    """
    rows, width, depth = filtered.shape
    r, c = np.divmod(np.arange(rows * width), width)
    skewed = np.zeros((rows + width + 1, rows + 1, depth), dtype=np.int16)
    skewed[r + c + 2, r + 1] = filtered.reshape(rows * width, depth)
    done = np.zeros_like(skewed)
    done[np.arange(1, width + 1), 0] = above
    kind = np.concatenate([[0], filters]).astype(np.int16)[:, None]
    sub, up, average, paeth = kind == 1, kind == 2, kind == 3, kind == 4
    for i in range(2, rows + width + 1):
        lo, hi = max(1, i - width), min(rows, i - 1) + 1
        a, b, ul = done[i - 1, lo:hi], done[i - 1, lo - 1:hi - 1], done[i - 2, lo - 1:hi - 1]
        pa, pb, pc = np.abs(b - ul), np.abs(a - ul), np.abs(a + b - 2 * ul)
        nearest = np.where((pa <= pb) & (pa <= pc), a, np.where(pb <= pc, b, ul))
        predictor = (a * sub[lo:hi] + b * up[lo:hi] + ((a + b) >> 1) * average[lo:hi]
                     + nearest * paeth[lo:hi])
        done[i, lo:hi] = (skewed[i, lo:hi] + predictor) & 0xFF
    return done[r + c + 2, r + 1].astype(np.uint8).reshape(rows, width, depth)
