"""Photos and textures read in blocks of rows, for ``relight`` and ``upsample``.

Every photo is handed to the caller in blocks of ``(rows, W, 3)`` codes (alpha dropped, grey
repeated) sized by the memory budget (:mod:`spectrocolor.budget`), and no file is ever copied
whole into a NumPy array:

* 8- and 16-bit PNG (grey, grey + alpha, RGB, RGBA; not interlaced) are decoded block by block
  by :func:`spectrocolor.imagefiles.iter_png_rows`, so a photo of any size allowed
  (:data:`MAX_PIXELS`) is read in bounded memory, whatever the few kilobytes of zeros it may be
  made of.
* TIFF (contiguous samples, strips or tiles, any compression tifffile decodes) is decoded one
  band of strips or tiles at a time (``tifffile.TiffPage.segments``); an uncompressed one is read
  straight from the file, rows at a time. Only a TIFF whose samples are stored in separate planes
  is decoded whole (after a budget check).
* JPEG, palette, 1/2/4-bit and interlaced PNG go through Pillow, whose decoders give the whole
  image: it is decoded once into Pillow's own buffer (1 byte per pixel for a palette or grey
  image, 4 for RGB) -- checked against the budget first -- and each block is cut out and
  expanded to RGB as it is asked for, so neither the RGB expansion nor a NumPy copy of the
  whole photo is ever made.
"""

from __future__ import annotations

from collections.abc import Callable, Iterator
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..errors import BudgetError, SpectrumError
from ..imagefiles import image_header, iter_png_rows, read_image
from . import UserError

#: Largest photo read, in pixels (a 24-megapixel photo is 2.4e7).
MAX_PIXELS = 2**28
#: Bytes one pixel takes while it is upsampled and relit (float64 colours, lookups, codes).
PIXEL_WORK_BYTES = 256


@dataclass(frozen=True)
class Photo:
    """A photo opened for reading in blocks.

    Attributes
    ----------
    path : pathlib.Path
        The file.
    width, height : int
        Pixels.
    bits : int
        8 or 16: the codes' depth (uint8 or uint16).
    read : callable
        ``read(rows)`` yields ``(rows, W, C)`` codes top to bottom (C of the file).
    """

    path: Path
    width: int
    height: int
    bits: int
    read: Callable[[int], Iterator[np.ndarray]]

    def blocks(self, rows: int) -> Iterator[np.ndarray]:
        """``(rows, W, 3)`` codes top to bottom (fewer in the last block); alpha dropped, grey repeated."""
        for block in self.read(rows):
            yield _rgb(block)

    def rows_per_block(self, per_pixel: int = PIXEL_WORK_BYTES) -> int:
        """Rows per block so that a block's work fits a block of the memory budget."""
        from ..budget import block_rows

        return block_rows(self.width * per_pixel, f"{self.path}: {self.width} pixels per row")


def _rgb(codes: np.ndarray) -> np.ndarray:
    if codes.ndim == 2:
        codes = codes[..., None]
    if codes.shape[-1] in (1, 2):
        return np.repeat(codes[..., :1], 3, axis=-1)
    return codes[..., :3]


def open_photo(path: Path) -> Photo:
    """Open a photo (.png, .tif/.tiff, .jpg) for reading in blocks; sizes checked first.

    Raises UserError for unreadable files or more than :data:`MAX_PIXELS` pixels, and
    BudgetError where what must be held at once (a Pillow decoder's buffer, a TIFF band or a
    TIFF in separate planes) is beyond the memory budget.
    """
    path = Path(path)
    try:
        header = image_header(path)
    except SpectrumError as exc:
        raise UserError(_unreadable(exc)) from None
    _check_pixels(path, header.width, header.height)
    if header.streamed:  # 8/16-bit PNG, not interlaced: imagefiles.iter_png_rows
        return _png(path, header)
    if header.format == "TIFF":
        if header.dtype not in (np.uint8, np.uint16) or header.channels > 4:
            raise UserError(f"{path}: expected an RGB image of 8- or 16-bit codes; got "
                            f"{header.dtype} with {header.channels} channels")
        return _tiff(path, header)
    return _pillow_photo(path, header)


#: Bytes per pixel of Pillow's own buffer, by mode (Pillow keeps 3-channel modes in 4 bytes).
_PILLOW_PIXEL_BYTES = {"1": 1, "L": 1, "P": 1, "I;16": 2, "I;16B": 2, "I;16L": 2}


def _pillow_photo(path: Path, header) -> Photo:
    """A JPEG, palette/1/2/4-bit/interlaced PNG or GIF: decoded once by Pillow, cut in blocks."""
    from PIL import Image

    try:
        with Image.open(path) as probe:
            mode = probe.mode
    except Exception as exc:  # read a moment ago by image_header; changed since
        raise UserError(f"{path}: cannot be read as an image ({exc})") from None
    held = header.width * header.height * _PILLOW_PIXEL_BYTES.get(mode, 4)
    _check_memory(path, header.width, header.height, held,
                  f"a {header.format} is decoded whole, into {_PILLOW_PIXEL_BYTES.get(mode, 4)} bytes "
                  "per pixel")
    target = "RGB" if mode not in ("L", "I;16", "I;16B", "I;16L") else mode
    bits = 16 if mode.startswith("I;16") else 8

    def read(rows: int) -> Iterator[np.ndarray]:
        try:
            with Image.open(path) as image:
                image.load()
                for top in range(0, header.height, rows):
                    part = image.crop((0, top, header.width, min(header.height, top + rows)))
                    if part.mode != target:
                        part = part.convert(target)
                    codes = np.asarray(part)
                    yield codes.astype(np.uint16) if bits == 16 else codes
        except (SpectrumError, BudgetError):
            raise
        except Exception as exc:  # Pillow raises many types for damaged files
            raise UserError(f"{path}: cannot be read as an image ({exc})") from None

    return Photo(path, header.width, header.height, bits, read)


def _tiff(path: Path, header) -> Photo:
    """A TIFF read one band of strips or tiles at a time (see the module's docstring)."""
    import tifffile

    try:
        with tifffile.TiffFile(path) as tif:
            page = tif.pages.first
            planar = int(page.planarconfig) == 2 and header.channels > 1
            segment_rows = int(page.tilelength if page.is_tiled else min(page.rowsperstrip or
                                                                         header.height, header.height))
            contiguous = page.is_final and not page.is_tiled and not planar  # uncompressed, no predictor
            depth = int(getattr(page, "imagedepth", 1) or 1)
            shaped = tuple(page.shaped)
    except Exception as exc:  # tifffile raises many types for damaged files
        raise UserError(f"{path}: cannot be read as a TIFF ({exc!r:.120})") from None
    row_bytes = header.width * header.channels * header.dtype.itemsize
    if planar or depth != 1 or shaped[0] != 1 or tuple(shaped[2:4]) != (header.height, header.width):
        _check_memory(path, header.width, header.height, header.nbytes,
                      "a TIFF of separate planes or several images is decoded whole")
        try:
            return _whole(path, read_image(path))
        except BudgetError:
            raise
        except SpectrumError as exc:
            raise UserError(_unreadable(exc)) from None
    if not contiguous:
        _check_memory(path, header.width, segment_rows, row_bytes * segment_rows,
                      f"one band of {'tiles' if page.is_tiled else 'strips'} of the TIFF is held at once")

    def read(rows: int) -> Iterator[np.ndarray]:
        try:
            if contiguous:
                yield from _tiff_raw_rows(path, header, rows)
            else:
                yield from _tiff_band_rows(path, header, segment_rows, rows)
        except (UserError, BudgetError):
            raise
        except Exception as exc:  # tifffile raises many types for damaged files
            raise UserError(f"{path}: cannot be read as a TIFF ({exc!r:.120})") from None

    return Photo(path, header.width, header.height, header.dtype.itemsize * 8, read)


def _shape(header, rows: int) -> tuple[int, ...]:
    return (rows, header.width) if header.channels == 1 else (rows, header.width, header.channels)


def _tiff_raw_rows(path: Path, header, rows: int) -> Iterator[np.ndarray]:
    """Rows of an uncompressed, contiguous TIFF, read from the file ``rows`` at a time."""
    import tifffile

    with tifffile.TiffFile(path) as tif:
        page = tif.pages.first
        offset = int(page.dataoffsets[0])
        stored = np.dtype(header.dtype).newbyteorder(tif.byteorder)
    row_bytes = header.width * header.channels * stored.itemsize
    with open(path, "rb") as handle:
        handle.seek(offset)
        for top in range(0, header.height, rows):
            count = min(rows, header.height - top)
            data = handle.read(count * row_bytes)
            if len(data) != count * row_bytes:
                raise UserError(f"{path}: cannot be read as a TIFF (its data end at row {top})")
            yield np.frombuffer(data, stored).astype(header.dtype).reshape(_shape(header, count))


def _tiff_band_rows(path: Path, header, band_rows: int, rows: int) -> Iterator[np.ndarray]:
    """Rows of a strip or tile TIFF: the segments of one band are decoded into one buffer, whose
    rows are handed on in blocks of ``rows`` (a block may span two bands)."""
    import tifffile

    from ..budget import block_bytes

    band = np.zeros((band_rows, header.width, header.channels), header.dtype)
    pending: list[np.ndarray] = []
    waiting = 0
    band_top = 0

    def flush(count: int) -> np.ndarray:
        nonlocal waiting
        block = np.concatenate(pending) if len(pending) > 1 else pending[0]
        out, rest = block[:count], block[count:]
        pending[:] = [rest] if len(rest) else []
        waiting = len(rest)
        return out.reshape(_shape(header, len(out)))

    with tifffile.TiffFile(path) as tif:
        page = tif.pages.first
        for segment, index, _ in page.segments(maxworkers=1, buffersize=block_bytes()):
            top, left = int(index[2]), int(index[3])
            if top != band_top:  # the band above is complete
                valid = min(band_rows, header.height - band_top)
                pending.append(band[:valid].copy())
                waiting += valid
                band[:] = 0
                band_top = top
                while waiting >= rows:
                    yield flush(rows)
            if segment is not None:
                part = np.asarray(segment).reshape(-1, segment.shape[-3], segment.shape[-2], segment.shape[-1])[0]
                height = min(part.shape[0], band_rows)
                width = min(part.shape[1], header.width - left)
                band[:height, left:left + width] = part[:height, :width].reshape(height, width, -1)
        valid = min(band_rows, header.height - band_top)
        pending.append(band[:valid].copy())
        waiting += valid
        while waiting >= rows:
            yield flush(rows)
        if waiting:
            yield flush(waiting)


def _unreadable(exc: SpectrumError) -> str:
    return str(exc) if "cannot be read" in str(exc) else f"cannot be read as an image: {exc}"


def _png(path: Path, header) -> Photo:
    def read(rows: int) -> Iterator[np.ndarray]:
        try:
            for _, block in iter_png_rows(path, rows_per_block=rows):
                yield block
        except SpectrumError as exc:
            raise UserError(f"cannot be read as an image: {exc}") from None

    return Photo(path, header.width, header.height, header.dtype.itemsize * 8, read)


def _check_pixels(path: Path, width: int, height: int) -> None:
    if width * height > MAX_PIXELS:
        raise UserError(f"{path}: {width} x {height} pixels; at most {MAX_PIXELS} are read")


def _check_memory(path: Path, width: int, height: int, nbytes: int, how: str) -> None:
    from ..budget import check_bytes

    check_bytes(nbytes, f"{path}: {width} x {height} pixels ({how}; a PNG or a TIFF in strips or "
                "tiles is streamed)")


def _whole(path: Path, codes: np.ndarray) -> Photo:
    bits = 16 if codes.dtype == np.uint16 else 8

    def read(rows: int) -> Iterator[np.ndarray]:
        for top in range(0, codes.shape[0], rows):
            yield codes[top:top + rows]

    return Photo(path, int(codes.shape[1]), int(codes.shape[0]), bits, read)
