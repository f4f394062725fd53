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

import struct
import zlib
from pathlib import Path

import numpy as np

from ..errors import SpectrumError

__all__ = ["decode_png", "read_png", "MAX_PIXELS"]

SIGNATURE = b"\x89PNG\r\n\x1a\n"
#: Channels per colour type (PNG specification, table 11.1), for the types read here.
CHANNELS = {0: 1, 2: 3, 4: 2, 6: 4}
#: Largest image decoded, in pixels (a 24-megapixel photo is 2.4e7).
MAX_PIXELS = 2**28
_CRITICAL = (b"IHDR", b"PLTE", b"IDAT", b"IEND")


def read_png(path) -> np.ndarray:
    """The codes of an 8- or 16-bit PNG file, ``(H, W, C)`` uint8 or uint16.

    Parameters
    ----------
    path : str or os.PathLike
        The PNG file.

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
    path = Path(path)
    try:
        data = path.read_bytes()
    except OSError as exc:
        raise SpectrumError(f"{path}: cannot be read ({exc.strerror or exc})") from None
    return decode_png(data, str(path))


def decode_png(data: bytes, source: str = "PNG data") -> np.ndarray:
    """Decode a PNG datastream held in memory (see :func:`read_png`).

    Parameters
    ----------
    data : bytes
        The whole file.
    source : str, default "PNG data"
        What to call it in error messages (e.g. the file name).

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
    data = bytes(data)

    def bad(what: str) -> SpectrumError:
        return SpectrumError(f"{source}: {what}")

    if not data.startswith(SIGNATURE):
        raise bad("not a PNG file (no PNG signature)")
    header, stream = _chunks(data, bad)
    width, height, depth, colour_type, compression, filtering, interlace = header
    if width == 0 or height == 0 or width > 2**31 - 1 or height > 2**31 - 1:
        raise bad(f"image size {width} x {height} is not allowed by PNG")
    if colour_type == 3 or depth not in (8, 16) or colour_type not in CHANNELS:
        raise bad(f"bit depth {depth}, colour type {colour_type}: this reader takes 8- or 16-bit "
                  "grey, grey + alpha, RGB or RGBA (read palette and 1/2/4-bit images with "
                  "Pillow)")
    if compression != 0 or filtering != 0:
        raise bad(f"compression method {compression}, filter method {filtering}: PNG defines "
                  "only 0")
    if interlace != 0:
        raise bad("Adam7-interlaced PNG is not read; save the image without interlacing")
    if width * height > MAX_PIXELS:
        raise bad(f"{width} x {height} pixels; at most {MAX_PIXELS} are read")
    pixel_bytes = CHANNELS[colour_type] * depth // 8
    expected = height * (1 + width * pixel_bytes)
    inflater = zlib.decompressobj()
    try:
        raw = inflater.decompress(stream, expected + 1)
    except zlib.error as exc:
        raise bad(f"the image data cannot be decompressed ({exc})") from None
    if len(raw) != expected or not inflater.eof:
        raise bad(f"the image data holds {len(raw)}{'+' if len(raw) > expected else ''} bytes "
                  f"(complete: {inflater.eof}); {width} x {height} pixels need {expected}")
    rows = np.frombuffer(raw, dtype=np.uint8).reshape(height, 1 + width * pixel_bytes)
    filters = rows[:, 0]
    if filters.max() > 4:
        raise bad(f"row {int(np.argmax(filters > 4))} has filter type {int(filters.max())}; "
                  "PNG defines 0-4")
    pixels = _unfilter(rows[:, 1:].reshape(height, width, pixel_bytes), filters)
    if depth == 16:
        samples = pixels.reshape(height, width * pixel_bytes).view(">u2").astype(np.uint16)
    else:
        samples = pixels
    return samples.reshape(height, width, CHANNELS[colour_type])


def _chunks(data: bytes, bad):
    """The IHDR fields and the concatenated IDAT data, every chunk's CRC checked."""
    position, header, parts, ended = len(SIGNATURE), None, [], False
    idat_closed = False  # a chunk other than IDAT has followed the IDAT chunks
    while position < len(data):
        if position + 8 > len(data):
            raise bad(f"a chunk header is cut off at byte {position}")
        length, kind = struct.unpack(">I4s", data[position:position + 8])
        end = position + 12 + length
        if length > 2**31 - 1 or end > len(data):
            raise bad(f"chunk {kind!r} at byte {position} claims {length} bytes; the file ends "
                      "first (truncated?)")
        body = data[position + 8:end - 4]
        if zlib.crc32(kind + body) != struct.unpack(">I", data[end - 4:end])[0]:
            raise bad(f"chunk {kind!r} at byte {position} fails its CRC-32 (damaged file)")
        if header is None and kind != b"IHDR":
            raise bad(f"the first chunk is {kind!r}, not IHDR")
        if kind == b"IHDR":
            if header is not None or length != 13:
                raise bad("IHDR chunk repeated or not 13 bytes long")
            header = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            if idat_closed:
                raise bad("the IDAT chunks are not consecutive")
            parts.append(body)
        elif kind == b"IEND":
            ended = True
            break
        elif kind[0] & 0x20 == 0 and kind not in _CRITICAL:
            raise bad(f"unknown critical chunk {kind!r}")
        idat_closed = bool(parts) and kind != b"IDAT"
        position = end
    if not ended:
        raise bad("no IEND chunk (the file is truncated)")
    if not parts:
        raise bad("no image data (IDAT chunk)")
    return header, b"".join(parts)


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
