"""Image files: the package's one reader and writer of PNG, TIFF, JPEG and GIF.

Every picture, swatch, strip, thickness map, band image, photo and converted cube is read or
written here, on maintained codecs:

================  =============================================  ===============================
format            read                                           write
================  =============================================  ===============================
PNG 8-bit         chunks checked here, filters undone by         Pillow
                  ``imagecodecs`` (libpng), in blocks of rows
PNG 16-bit        the same (Pillow would cut 16-bit RGB to 8)    grey: Pillow; with alpha or
                                                                 colour: ``imagecodecs``
PNG palette,      Pillow (expanded to grey, RGB or RGBA)         --
1/2/4-bit,
interlaced
TIFF              ``tifffile``                                   ``tifffile`` (JSON metadata)
JPEG, GIF         Pillow (a GIF's first frame)                   Pillow; :func:`write_gif` for
                                                                 animations
================  =============================================  ===============================

Every writer goes through ``spectrocolor.safe_write.atomic_path``: the file is written
beside the target, read back (``spectrocolor.safe_write.verify_image``,
``verify_tiff``) and only then renamed over it, so a failed write
leaves any previous file unchanged. Every reader reads the header first (Pillow's
``Image.open`` decodes nothing; the PNG ``IHDR``; tifffile's page tags) and checks the size it
claims against the memory budget (:mod:`spectrocolor.budget`) before a pixel is decoded.

Two parts stay streamed, for images larger than the memory budget, because no maintained codec
here streams a PNG (``imagecodecs.png_decode``/``png_encode`` and Pillow take or give the whole
image):

* :func:`iter_png_rows` reads the chunks itself (CRC-32 of every chunk, chunk order, the zlib
  stream inflated only as far as the next block needs) and hands each block of filtered
  scanlines, below the last reconstructed row, to ``imagecodecs.png_decode`` as a small PNG of
  its own (stored, uncompressed deflate): libpng undoes the filters, so the hand-written NumPy
  and numba unfiltering is gone.
* :func:`write_png_blocks` writes the PNG datastream itself (IHDR, Paeth-filtered rows through
  one running ``zlib.compressobj``, IEND), so a conversion holds one block of rows.

Measured (16-bit RGB, blocks of 64 rows, peak of ``tracemalloc``; 2-core x86-64 shared with
other work, load average 11, so the times are relative only):

=================  ===========  ====================  ============  ====================
image              read blocks  ``png_decode`` whole  write blocks  ``png_encode`` whole
=================  ===========  ====================  ============  ====================
1500 x 1000        4 MB         11 MB                 14 MB         21 MB
3000 x 2000        6 MB         44 MB                 27 MB         85 MB
6000 x 4000        15 MB        166 MB                54 MB         330 MB
=================  ===========  ====================  ============  ====================

The streamed paths stay flat while the codec's grow with the image: a 2**28-pixel 16-bit RGB
photo (:data:`MAX_PIXELS`) needs 1.6 GB of codes whole, beyond the 1 GiB default budget.
Times, 1500 x 1000, warm, best of 5: read in blocks 0.28 s, ``imagecodecs.png_decode`` of the
whole file 0.18 s, the hand-written decoder this replaces (numba) 0.27 s; write in blocks
2.0 s, ``imagecodecs.png_encode`` of the whole image 1.7 s.

Why this file is long: it is the package's one image-file module (every read and write of PNG,
TIFF, JPEG and GIF), on purpose; splitting it by format would bring back the several places with
their own header checks and budget rules that it replaced.

References
----------
W3C, *Portable Network Graphics (PNG) Specification*, 3rd ed. (2025): sections 5 (datastream,
chunks, CRC), 7 and 9 (scanlines and filters, the Paeth predictor), 11.2 (IHDR, IDAT, IEND).
TIFF Revision 6.0 (Adobe, 1992), section 3 (strips) and ExtraSamples (unassociated alpha).

Examples
--------
>>> import tempfile, pathlib
>>> import numpy as np
>>> codes = np.array([[[0, 257, 65535], [1000, 2000, 3000]]], dtype=np.uint16)
>>> with tempfile.TemporaryDirectory() as folder:
...     back = read_image(write_image(pathlib.Path(folder) / "codes16.png", codes))
>>> back.dtype.name, back.shape, back[0, 0].tolist()
('uint16', (1, 2, 3), [0, 257, 65535])
"""

from __future__ import annotations

import io
import os
import struct
import zlib
from collections.abc import Iterable, Iterator
from dataclasses import dataclass
from pathlib import Path
from typing import BinaryIO

import numpy as np

from .budget import block_rows, check_bytes, claimed_bytes
from .errors import SpectrumError
from .safe_write import atomic_path, verify_image, verify_png, verify_tiff

__all__ = [
    "ImageHeader",
    "MAX_PIXELS",
    "PNGHeader",
    "decode_png",
    "image_header",
    "iter_png_rows",
    "paeth_filter",
    "png_header",
    "read_image",
    "read_png",
    "write_gif",
    "write_image",
    "write_png_blocks",
    "write_tiff_blocks",
]

SIGNATURE = b"\x89PNG\r\n\x1a\n"
#: Channels per PNG colour type (PNG specification, table 11.1), for the types streamed here.
CHANNELS = {0: 1, 2: 3, 4: 2, 6: 4}
_COLOUR_TYPE = {1: 0, 2: 4, 3: 2, 4: 6}  # channels -> PNG colour type
#: Largest PNG decoded by ``iter_png_rows``, in pixels (a 24-megapixel photo is 2.4e7).
MAX_PIXELS = 2**28
_CRITICAL = (b"IHDR", b"PLTE", b"IDAT", b"IEND")
#: Chunks up to this size are read whole and their CRC checked before their data are used;
#: longer ones are read in pieces of this size (their CRC is checked at their end).
_PIECE = 2**24
_TIFF_SUFFIXES = (".tif", ".tiff")
_SUFFIXES = ".png, .tif/.tiff, .jpg/.jpeg, .gif"
#: Pillow modes -> (mode converted to, channels, dtype) of the codes :func:`read_image` returns.
_PILLOW_MODES = {
    "1": ("L", 1, np.uint8), "L": ("L", 1, np.uint8), "LA": ("LA", 2, np.uint8),
    "RGB": ("RGB", 3, np.uint8), "RGBA": ("RGBA", 4, np.uint8), "I;16": ("I;16", 1, np.uint16),
    "I;16B": ("I;16", 1, np.uint16), "I;16L": ("I;16", 1, np.uint16), "I": ("I", 1, np.int32),
    "F": ("F", 1, np.float32),
}


# --- headers ----------------------------------------------------------------------------------


@dataclass(frozen=True)
class PNGHeader:
    """The IHDR fields of a PNG that ``iter_png_rows`` streams.

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


@dataclass(frozen=True)
class ImageHeader:
    """What :func:`read_image` will return for a file, known before any pixel is decoded.

    Attributes
    ----------
    format : str
        ``"PNG"``, ``"TIFF"``, ``"JPEG"``, ``"GIF"`` or another name Pillow gives.
    width, height : int
        Pixels.
    channels : int
        Samples per pixel as returned (1 grey, 2 grey + alpha, 3 RGB, 4 RGBA; a TIFF's own).
    dtype : numpy.dtype
        The codes' dtype (uint8, uint16; a TIFF's own).
    frames : int
        Frames (pages) in the file; :func:`read_image` returns the first.
    streamed : bool
        True for an 8- or 16-bit, non-interlaced PNG: :func:`iter_png_rows` reads it in blocks
        of rows; other files are decoded whole.
    """

    format: str
    width: int
    height: int
    channels: int
    dtype: np.dtype
    frames: int = 1
    streamed: bool = False

    @property
    def nbytes(self) -> int:
        """Bytes of the codes :func:`read_image` returns, B."""
        return self.width * self.height * self.channels * np.dtype(self.dtype).itemsize


def _streamed_png(head: bytes) -> bool:
    """Whether ``iter_png_rows`` takes a PNG starting with ``head`` (29 bytes): 8- or 16-bit
    grey/RGB with or without alpha, not interlaced, and every 16-bit PNG (its refusal is the
    answer there: Pillow would cut the codes to 8 bits)."""
    if len(head) < 29 or head[:8] != SIGNATURE:
        return False
    return head[24] == 16 or (head[24] == 8 and head[25] in CHANNELS and head[28] == 0)


def _head(path: Path) -> bytes:
    try:
        with open(path, "rb") as handle:
            return handle.read(29)
    except OSError as exc:
        raise SpectrumError(f"{path}: cannot be read ({exc.strerror or exc})") from None


def image_header(path) -> ImageHeader:
    """The size and sample type of an image file, from its header (no pixel is decoded).

    Parameters
    ----------
    path : str or os.PathLike
        A PNG, TIFF, JPEG or GIF file (or another format Pillow reads).

    Returns
    -------
    ImageHeader
        Format, width and height in pixels, channels, dtype and frames.

    Raises
    ------
    SpectrumError
        The file cannot be read or is not an image.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> import numpy as np
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     header = image_header(write_image(pathlib.Path(folder) / "a.png", np.zeros((2, 5), np.uint16)))
    >>> header.format, header.width, header.height, header.channels, header.dtype.name
    ('PNG', 5, 2, 1, 'uint16')
    """
    path = Path(path)
    head = _head(path)
    if _streamed_png(head):
        png = png_header(path)
        return ImageHeader("PNG", png.width, png.height, png.channels, png.dtype, streamed=True)
    if path.suffix.lower() in _TIFF_SUFFIXES or head[:4] in (b"II*\0", b"MM\0*"):
        return _tiff_header(path)
    with _pillow(path) as image:
        return _pillow_header(path, image)


def _tiff_header(path: Path) -> ImageHeader:
    import tifffile

    try:
        with tifffile.TiffFile(path) as tif:
            series = tif.series[0]
            shape, dtype, pages = tuple(series.shape), np.dtype(series.dtype), len(tif.pages)
    except FileNotFoundError as exc:
        raise SpectrumError(f"{path}: cannot be read ({exc.strerror})") from None
    except Exception as exc:  # tifffile raises many types for damaged files (even ZeroDivisionError)
        raise SpectrumError(f"{path}: cannot be read as a TIFF ({exc!r:.120})") from None
    if len(shape) < 2:
        raise SpectrumError(f"{path}: a TIFF of shape {shape} is not an image")
    channels = int(np.prod(shape[2:], dtype=np.int64)) if len(shape) > 2 else 1
    return ImageHeader("TIFF", int(shape[1]), int(shape[0]), channels, dtype, pages)


class _pillow:
    """``Image.open`` (which decodes nothing) with Pillow's many errors turned into one."""

    def __init__(self, path: Path) -> None:
        from PIL import Image

        self.path = path
        try:
            self.image = Image.open(path)
        except FileNotFoundError as exc:
            raise SpectrumError(f"{path}: cannot be read ({exc.strerror})") from None
        except Exception as exc:  # Pillow raises many types for damaged files
            raise SpectrumError(f"{path}: cannot be read as an image ({exc})") from None

    def __enter__(self):
        return self.image

    def __exit__(self, *_exc) -> None:
        self.image.close()


def _pillow_target(image) -> tuple[str, int, np.dtype]:
    if image.mode == "P" or image.mode == "PA":
        rgba = image.mode == "PA" or "transparency" in image.info
        return ("RGBA", 4, np.dtype(np.uint8)) if rgba else ("RGB", 3, np.dtype(np.uint8))
    mode, channels, dtype = _PILLOW_MODES.get(image.mode, ("RGB", 3, np.uint8))
    return mode, channels, np.dtype(dtype)


def _pillow_header(path: Path, image) -> ImageHeader:
    _, channels, dtype = _pillow_target(image)
    return ImageHeader(str(image.format), image.width, image.height, channels, dtype,
                       int(getattr(image, "n_frames", 1)))


# --- readers ----------------------------------------------------------------------------------


def read_image(path, *, memory_budget=None) -> np.ndarray:
    """The codes of an image file: ``(H, W)`` for grey, ``(H, W, C)`` otherwise.

    The header is read first and the size of the codes checked against the memory budget
    before anything is decoded. 8- and 16-bit PNG are read bit for bit (``iter_png_rows``);
    palette images are expanded to RGB (RGBA where a colour is transparent); a GIF gives its
    first frame; a TIFF its first series, as stored.

    Parameters
    ----------
    path : str or os.PathLike
        A PNG, TIFF, JPEG or GIF file (or another format Pillow reads).
    memory_budget : int or str, keyword-only, optional
        The most bytes the image's codes may take; see :term:`memory budget`.

    Returns
    -------
    numpy.ndarray
        uint8 or uint16 codes (a TIFF's own dtype), shape ``(H, W)`` or ``(H, W, C)``, C of 2
        (grey + alpha), 3 (RGB) or 4 (RGBA).

    Raises
    ------
    SpectrumError
        The file cannot be read, or is damaged; the message names the file.
    spectrocolor.errors.BudgetError
        (a ``SpectrumError``) The codes would be larger than the memory budget.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> import numpy as np
    >>> codes = np.arange(12, dtype=np.uint8).reshape(2, 2, 3)
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     back = read_image(write_image(pathlib.Path(folder) / "a.tif", codes))
    >>> back.tolist() == codes.tolist()
    True
    """
    path = Path(path)
    head = _head(path)
    if _streamed_png(head):
        codes = read_png(path, memory_budget=memory_budget)
        return codes[..., 0] if codes.shape[-1] == 1 else codes
    if path.suffix.lower() in _TIFF_SUFFIXES or head[:4] in (b"II*\0", b"MM\0*"):
        return _read_tiff(path, memory_budget)
    with _pillow(path) as image:
        header = _pillow_header(path, image)
        _check(path, header, memory_budget)
        mode = _pillow_target(image)[0]
        try:
            picture = image if image.mode == mode else image.convert(mode)
            codes = np.asarray(picture)
        except Exception as exc:  # Pillow raises many types for damaged files
            raise SpectrumError(f"{path}: cannot be read as an image ({exc})") from None
    return codes.astype(header.dtype, copy=False)


def _check(path: Path, header: ImageHeader, memory_budget) -> None:
    check_bytes(claimed_bytes((header.height, header.width, header.channels), header.dtype.itemsize,
                              f"{path}: shape"),
                f"{path}: {header.width} x {header.height} pixels of {header.channels} x "
                f"{header.dtype.name}", budget=memory_budget)


def _read_tiff(path: Path, memory_budget) -> np.ndarray:
    import tifffile

    header = _tiff_header(path)
    _check(path, header, memory_budget)
    try:
        with tifffile.TiffFile(path) as tif:
            return np.asarray(tif.series[0].asarray())
    except Exception as exc:  # tifffile raises many types for damaged files
        raise SpectrumError(f"{path}: cannot be read as a TIFF ({exc})") from None


def read_png(path, *, memory_budget=None) -> np.ndarray:
    """The codes of an 8- or 16-bit PNG file, ``(H, W, C)`` uint8 or uint16.

    The file is read chunk by chunk and decoded in blocks of rows (``iter_png_rows``) into
    one array, which is checked against the memory budget before it is made.

    Parameters
    ----------
    path : str or os.PathLike
        The PNG file.
    memory_budget : int or str, keyword-only, optional
        The most bytes the decoded codes may take; see :term:`memory budget`.

    Returns
    -------
    numpy.ndarray, shape (H, W, C), uint8 or uint16
        ``C`` is 1 (grey), 2 (grey, alpha), 3 (RGB) or 4 (RGBA); samples as stored (16-bit
        samples in native byte order).

    Raises
    ------
    SpectrumError
        The file cannot be read, or is not an 8/16-bit, non-interlaced, non-palette PNG; the
        message names the file and what is wrong.
    spectrocolor.errors.BudgetError
        (a ``SpectrumError``) The image is larger than the memory budget: read it in blocks
        with ``iter_png_rows``.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> import numpy as np
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
        Not a PNG, a damaged IHDR, a palette, 1/2/4-bit or interlaced PNG (read those with
        :func:`read_image`), or more than :data:`MAX_PIXELS` pixels.

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
    by libpng (``imagecodecs``) below the last row of the block before. Memory: one block,
    whatever the image's size, so a photo of 2^28 pixels, or a few kilobytes of zeros claiming
    40 megapixels, is decoded in bounded memory.

    Parameters
    ----------
    source : str, os.PathLike or bytes
        A PNG file, or a datastream held in memory.
    rows_per_block : int, optional
        Rows per block; default as many as fit in a block of the memory budget
        (``spectrocolor.budget.block_rows``).
    memory_budget : int or str, optional
        The budget the blocks of rows are sized by; see :term:`memory budget`.
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


def _chunk(kind: bytes, data: bytes) -> bytes:
    return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))


class _Datastream:
    """A PNG datastream read chunk by chunk from a file or from bytes; opened at the IHDR."""

    def __init__(self, source, name: str | None) -> None:
        self.handle: BinaryIO
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
        first = next(self._chunks(whole=True), None)
        if first is None:
            raise self.bad("no IEND chunk (the file is truncated)")
        kind, body = first
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
        """Blocks of decoded rows (see ``iter_png_rows``)."""
        header = self.header
        line = header.line_bytes
        if rows_per_block is None:  # the filtered rows, their small PNG and the codes
            rows_per_block = block_rows(6 * line, f"{self.name}: {header.width} pixels per row",
                                        budget=memory_budget)
        rows_per_block = max(1, min(int(rows_per_block), header.height))
        inflater = zlib.decompressobj()
        pending = bytearray()
        above = bytes(line - 1)
        top = 0
        data = self._chunks()
        while top < header.height:
            want = min(rows_per_block, header.height - top) * line
            while len(pending) < want:
                piece: bytes | None
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
            block = bytes(pending[:want])
            del pending[:want]
            codes = self._decode(block, above, top)
            yield top, codes
            above = self._raw_row(codes[-1])
            top += len(codes)
        self._finish(inflater, data, len(pending))

    def _finish(self, inflater, data, extra: int) -> None:
        """The rest of the stream: nothing but the end of the zlib data, then the chunks to IEND."""
        header = self.header
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
            expected = header.height * header.line_bytes
            raise self.bad(f"the image data holds {expected}{'+' if extra else ''} bytes (complete: "
                           f"{inflater.eof}); {header.width} x {header.height} pixels need {expected}")
        for _ in data:  # the chunks after the image data: checked up to IEND
            pass

    def _raw_row(self, codes: np.ndarray) -> bytes:
        """The unfiltered scanline bytes of one decoded row (big-endian samples)."""
        return codes.astype(">u2" if self.header.bit_depth == 16 else np.uint8).tobytes()

    def _decode(self, block: bytes, above: bytes, top: int) -> np.ndarray:
        """Codes of a block of filtered scanlines below the reconstructed row ``above``.

        The block, preceded by ``above`` with filter type 0 (None), is a PNG of its own; libpng
        (``imagecodecs.png_decode``) undoes its filters.
        """
        import imagecodecs

        header = self.header
        line = header.line_bytes
        rows = len(block) // line
        filters = np.frombuffer(block, np.uint8)[::line]
        if filters.max() > 4:
            raise self.bad(f"row {top + int(np.argmax(filters > 4))} has filter type "
                           f"{int(filters.max())}; PNG defines 0-4")
        ihdr = struct.pack(">IIBBBBB", header.width, rows + 1, header.bit_depth, header.colour_type, 0, 0, 0)
        small = (SIGNATURE + _chunk(b"IHDR", ihdr) + _chunk(b"IDAT", zlib.compress(b"\0" + above + block, 0))
                 + _chunk(b"IEND", b""))
        try:
            codes = imagecodecs.png_decode(small)
        except Exception as exc:  # pragma: no cover - a block that passed the checks above decodes
            raise self.bad(f"rows {top}-{top + rows - 1} cannot be decoded ({exc})") from None
        return codes[1:].reshape(rows, header.width, header.channels).astype(header.dtype, copy=False)


# --- writers ----------------------------------------------------------------------------------


def _shape_channels(array: np.ndarray, path: Path) -> int:
    if array.ndim not in (2, 3) or (array.ndim == 3 and not 1 <= array.shape[2] <= 4) or 0 in array.shape:
        raise SpectrumError(f"{path}: an image must have shape (H, W) or (H, W, C) with C of 1-4 and "
                            f"H, W >= 1; got {array.shape}")
    return 1 if array.ndim == 2 else int(array.shape[2])


def write_image(path, image, *, metadata: dict | None = None, quality: int = 95) -> Path:
    """Write an image array to PNG, TIFF, JPEG or GIF (chosen by the suffix), atomically.

    Parameters
    ----------
    path : str or os.PathLike
        Output file: ``.png``, ``.tif``/``.tiff``, ``.jpg``/``.jpeg`` or ``.gif``.
    image : array_like, shape (H, W) or (H, W, C)
        PNG: ``uint8`` or ``uint16`` codes, C of 1 (grey), 2 (grey + alpha), 3 (RGB) or 4
        (RGBA; alpha not premultiplied), every bit kept. TIFF: any numeric dtype, written as it
        is (C of 3 is RGB, 4 RGB plus unassociated alpha). JPEG: ``uint8`` grey or RGB. GIF:
        ``uint8`` grey or RGB, one frame (:func:`write_gif` for animations).
    metadata : dict, keyword-only, optional
        TIFF only: JSON-serialisable facts stored in the image description.
    quality : int, keyword-only, default 95
        JPEG only: Pillow's quality, 1-95.

    Returns
    -------
    pathlib.Path
        ``path``, in the format its suffix names.

    Raises
    ------
    SpectrumError
        An unknown suffix, or a shape or dtype the format cannot hold.
    spectrocolor.safe_write.OutputError
        The file could not be written (full disk, no permission, …); see :term:`atomic write`.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> import numpy as np
    >>> codes = np.array([[[0, 1, 65535, 40000]]], dtype=np.uint16)  # 16-bit RGBA
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     read_image(write_image(pathlib.Path(folder) / "rgba16.png", codes)).tolist()
    [[[0, 1, 65535, 40000]]]
    """
    path = Path(path)
    array = np.asarray(image)
    channels = _shape_channels(array, path)
    suffix = path.suffix.lower()
    if metadata and suffix not in _TIFF_SUFFIXES:
        raise SpectrumError(f"metadata is stored in TIFF files only; {suffix.lstrip('.').upper()} gets none")
    height, width = array.shape[:2]
    if suffix == ".png":
        _write_png(path, array, channels)
    elif suffix in _TIFF_SUFFIXES:
        import tifffile

        photometric = "rgb" if channels in (3, 4) else "minisblack"
        alpha = ["unassalpha"] if channels == 4 else None
        with atomic_path(path, verify=lambda p: verify_tiff(p, array.shape, array.nbytes)) as temporary:
            tifffile.imwrite(temporary, array, photometric=photometric, metadata=metadata or {},
                             extrasamples=alpha)
    elif suffix in (".jpg", ".jpeg", ".gif"):
        if array.dtype != np.uint8 or channels not in (1, 3):
            raise SpectrumError(f"{path}: {suffix.lstrip('.').upper()} holds uint8 grey or RGB codes; got "
                                f"{array.dtype} with {channels} channels")
        if suffix == ".gif":
            return write_gif(path, [array])
        from PIL import Image

        picture = Image.fromarray(np.ascontiguousarray(array.reshape(height, width, -1).squeeze(-1)
                                                       if channels == 1 else array))
        with atomic_path(path, verify=lambda p: verify_image(p, width, height)) as temporary:
            picture.save(temporary, format="JPEG", quality=int(quality))
    else:
        raise SpectrumError(f"{path}: unknown image format {suffix!r}; accepted: {_SUFFIXES}")
    return path


def _write_png(path: Path, array: np.ndarray, channels: int) -> None:
    if array.dtype not in (np.uint8, np.uint16):
        raise SpectrumError(f"{path}: PNG needs uint8 or uint16 codes; got {array.dtype}")
    height, width = array.shape[:2]
    codes = np.ascontiguousarray(array.reshape(height, width) if channels == 1 else array)
    with atomic_path(path, verify=lambda p: verify_png(p, width, height)) as temporary:
        if codes.dtype == np.uint8 or codes.ndim == 2:  # what Pillow writes without loss
            from PIL import Image

            Image.fromarray(codes).save(temporary, format="PNG")
        else:  # 16-bit with colour or alpha: Pillow cannot write it
            import imagecodecs

            # unfiltered rows, zlib level 6: the layout of the writer this replaces
            data = imagecodecs.png_encode(codes, level=6, filter=imagecodecs.PNG.FILTER.NONE)
            with open(temporary, "wb") as handle:
                handle.write(data)


def write_gif(path, frames: Iterable, *, frame_ms: int = 100, loop: int = 0) -> Path:
    """Write an animated GIF of 8-bit frames, atomically (Pillow; each frame gets its palette).

    Parameters
    ----------
    path : str or os.PathLike
        Output ``.gif``.
    frames : iterable of numpy.ndarray, each shape (H, W, 3) or (H, W), uint8
        The frames, all of one size (``rgb8`` codes or grey).
    frame_ms : int, keyword-only, default 100
        Display time of each frame, ms.
    loop : int, keyword-only, default 0
        Times the animation repeats; 0 for ever.

    Returns
    -------
    pathlib.Path
        ``path``, now holding the animation.

    Raises
    ------
    SpectrumError
        No frames, frames of different sizes, or not uint8 codes.
    spectrocolor.safe_write.OutputError
        The GIF could not be written, or did not read back with its size and frame count; see
        :term:`atomic write`.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> import numpy as np
    >>> frames = [np.full((4, 6, 3), level, np.uint8) for level in (0, 128, 255)]
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     image_header(write_gif(pathlib.Path(folder) / "a.gif", frames)).frames
    3
    """
    from PIL import Image

    path = Path(path)
    arrays = [np.asarray(frame) for frame in frames]
    if not arrays:
        raise SpectrumError(f"{path}: a GIF needs at least one frame")
    shapes = {a.shape for a in arrays}
    if len(shapes) != 1 or any(a.dtype != np.uint8 for a in arrays) or _shape_channels(arrays[0], path) not in (1, 3):
        raise SpectrumError(f"{path}: GIF frames must be uint8 grey or RGB codes of one size; got "
                            f"{sorted(map(str, shapes))}")
    height, width = arrays[0].shape[:2]
    pictures = [Image.fromarray(np.ascontiguousarray(a)) for a in arrays]
    with atomic_path(path, verify=lambda p: verify_image(p, width, height, frames=len(pictures))) as temporary:
        pictures[0].save(temporary, format="GIF", save_all=True, append_images=pictures[1:],
                         duration=frame_ms, loop=loop)
    return path


# --- writers of blocks of rows ----------------------------------------------------------------


def paeth_filter(rows: np.ndarray, previous: np.ndarray, bytes_per_pixel: int) -> np.ndarray:
    """PNG filter type 4 (Paeth) of scanlines, with the filter-type byte in front of each.

    Parameters
    ----------
    rows : numpy.ndarray, shape (R, L), uint8
        Raw scanline bytes (big-endian samples for 16-bit images).
    previous : numpy.ndarray, shape (L,), uint8
        The scanline above the first row (zeros above the image's first row).
    bytes_per_pixel : int
        Bytes of one pixel (3 or 4 for 8-bit RGB/RGBA, 6 or 8 for 16-bit).

    Returns
    -------
    numpy.ndarray, shape (R, L + 1), uint8
        Filtered scanlines, each starting with the byte 4.

    References
    ----------
    PNG specification, 3rd edition (W3C, 2025), §9.4 "Filter type 4: Paeth".

    Examples
    --------
    >>> import numpy as np
    >>> paeth_filter(np.array([[10, 20, 30, 40, 50, 60]], np.uint8), np.zeros(6, np.uint8), 3).tolist()
    [[4, 10, 20, 30, 30, 30, 30]]
    """
    x = rows.astype(np.int16)
    up = np.vstack([previous[None, :].astype(np.int16), x[:-1]])
    left = np.zeros_like(x)
    left[:, bytes_per_pixel:] = x[:, :-bytes_per_pixel]
    up_left = np.zeros_like(x)
    up_left[:, bytes_per_pixel:] = up[:, :-bytes_per_pixel]
    estimate = left + up - up_left
    to_left, to_up, to_up_left = np.abs(estimate - left), np.abs(estimate - up), np.abs(estimate - up_left)
    predictor = np.where((to_left <= to_up) & (to_left <= to_up_left), left, np.where(to_up <= to_up_left, up, up_left))
    filtered = np.empty((rows.shape[0], rows.shape[1] + 1), np.uint8)
    filtered[:, 0] = 4
    filtered[:, 1:] = (x - predictor).astype(np.uint8)  # modulo 256, as the specification says
    return filtered


def write_png_blocks(
    path, blocks: Iterable[np.ndarray], height: int, width: int, channels: int, bit_depth: int
) -> Path:
    """Write a PNG from blocks of rows of codes, holding one block at a time.

    Parameters
    ----------
    path : str or os.PathLike
        The PNG file (written atomically, then checked with Pillow).
    blocks : iterable of numpy.ndarray, each shape (rows, width, channels)
        Integer codes (uint8 for 8 bits, uint16 for 16), top to bottom, ``height`` rows in all.
    height, width : int
        Image size in pixels.
    channels : {1, 2, 3, 4}
        Grey, grey + alpha, RGB or RGBA (alpha not premultiplied, as PNG defines it).
    bit_depth : {8, 16}
        Bits per sample.

    Returns
    -------
    pathlib.Path
        ``path``, a PNG of every block.

    Raises
    ------
    ValueError
        Blocks of the wrong shape or dtype, or not ``height`` rows in all (a programming error:
        the target is left unchanged).
    spectrocolor.safe_write.OutputError
        The PNG could not be written, or did not read back at ``width`` × ``height``; see
        :term:`atomic write`.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> import numpy as np
    >>> codes = np.arange(2 * 3 * 3, dtype=np.uint8).reshape(2, 3, 3)
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     path = write_png_blocks(pathlib.Path(folder) / "a.png", [codes[:1], codes[1:]], 2, 3, 3, 8)
    ...     np.array_equal(read_image(path), codes)
    True
    """
    dtype = np.dtype(">u2") if bit_depth == 16 else np.dtype(np.uint8)
    line_bytes = width * channels * dtype.itemsize
    with atomic_path(path, verify=lambda p: verify_png(p, width, height)) as temporary:
        with open(temporary, "wb") as out:
            out.write(SIGNATURE)
            out.write(
                _chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, bit_depth, _COLOUR_TYPE[channels], 0, 0, 0))
            )
            compressor = zlib.compressobj(6)
            previous = np.zeros(line_bytes, np.uint8)
            rows_written = 0
            for block in blocks:
                if block.shape[1:] != (width, channels) or block.dtype.itemsize != dtype.itemsize:
                    raise ValueError(
                        f"block of shape {block.shape}, {block.dtype}; expected "
                        f"(rows, {width}, {channels}) of {bit_depth}-bit codes"
                    )
                rows = np.ascontiguousarray(block, dtype=dtype).view(np.uint8).reshape(len(block), line_bytes)
                data = compressor.compress(paeth_filter(rows, previous, channels * dtype.itemsize).tobytes())
                if data:
                    out.write(_chunk(b"IDAT", data))
                previous = rows[-1].copy()
                rows_written += len(block)
            if rows_written != height:
                raise ValueError(f"{rows_written} rows given for a PNG of height {height}")
            out.write(_chunk(b"IDAT", compressor.flush()))
            out.write(_chunk(b"IEND", b""))
    return Path(path)


def write_tiff_blocks(
    path, blocks: Iterable[np.ndarray], shape: tuple[int, int, int], rows_per_block: int, metadata: dict | None = None
) -> Path:
    """Write a float32 TIFF from blocks of rows, one uncompressed strip per block (tifffile).

    Parameters
    ----------
    path : str or os.PathLike
        The TIFF file (written atomically, then read back with tifffile).
    blocks : iterable of numpy.ndarray, each shape (rows_per_block, W, C)
        Values, top to bottom; every block has ``rows_per_block`` rows except the last. Cast
        to float32.
    shape : tuple of int
        ``(H, W, C)`` with C = 3 (RGB photometric) or 4 (RGB plus unassociated alpha).
    rows_per_block : int
        Rows of every block but the last (the TIFF's RowsPerStrip).
    metadata : dict, optional
        JSON-serialisable facts stored in the image description (as :func:`write_image`
        stores them).

    Returns
    -------
    pathlib.Path
        ``path``, a TIFF of every block.

    Raises
    ------
    ValueError
        Blocks that do not add up to ``shape`` (the target is left unchanged).
    spectrocolor.safe_write.OutputError
        The TIFF could not be written, or did not read back with ``shape``; see
        :term:`atomic write`.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> import numpy as np
    >>> values = np.arange(5 * 2 * 3, dtype=np.float32).reshape(5, 2, 3)
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     path = pathlib.Path(folder) / "a.tif"
    ...     _ = write_tiff_blocks(path, [values[:2], values[2:4], values[4:]], (5, 2, 3), 2)
    ...     np.array_equal(read_image(path), values)
    True
    """
    import tifffile

    height, width, channels = shape

    def strips() -> Iterator[bytes]:
        rows = 0
        for block in blocks:
            expected = min(rows_per_block, height - rows)
            if block.shape != (expected, width, channels):
                raise ValueError(f"block of shape {block.shape}; expected {(expected, width, channels)}")
            rows += expected
            yield np.ascontiguousarray(block, dtype=np.float32).tobytes()

    alpha = ["unassalpha"] if channels == 4 else None
    nbytes = height * width * channels * 4
    with atomic_path(path, verify=lambda p: verify_tiff(p, shape, nbytes)) as temporary:
        tifffile.imwrite(
            temporary,
            data=strips(),
            shape=shape,
            dtype=np.float32,
            photometric="rgb",
            rowsperstrip=rows_per_block,
            metadata=metadata or {},
            extrasamples=alpha,
        )
    return Path(path)
