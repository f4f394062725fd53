"""Photos and textures read in blocks of rows, for ``relight`` and ``upsample``.

8- and 16-bit PNG (grey, grey + alpha, RGB, RGBA; not interlaced) are decoded block by block
by :func:`spectrocolor.upsampling.png_reader.iter_png_rows`, so a photo of any size allowed
(:data:`MAX_PIXELS`) is read in bounded memory, whatever the few kilobytes of zeros it may be
made of. Other files -- palette or interlaced PNG and JPEG through Pillow, TIFF through
tifffile -- are decoded whole, after their size in memory is checked against the memory budget
(:mod:`spectrocolor.budget`). Either way the caller gets blocks of ``(rows, W, 3)`` codes:
alpha dropped, grey repeated.
"""

from __future__ import annotations

from collections.abc import Callable, Iterator
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..errors import BudgetError
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

    Raises UserError for unreadable files, more than :data:`MAX_PIXELS` pixels, or (for files
    decoded whole) more memory than the budget.
    """
    path = Path(path)
    try:
        with open(path, "rb") as handle:
            head = handle.read(29)
    except OSError as exc:
        raise UserError(f"{path}: cannot be read ({exc.strerror or exc})") from None
    if head[:8] == b"\x89PNG\r\n\x1a\n" and _streamable_png(head):
        return _png(path)
    if path.suffix.lower() in (".tif", ".tiff"):
        return _whole(path, _tiff_codes(path))
    return _whole(path, _pillow_codes(path))


def _streamable_png(head: bytes) -> bool:
    """What the library's streaming reader takes: 8-bit grey/RGB(A) without interlacing, and every
    16-bit PNG (Pillow would cut it to 8 bits, so the reader's refusal is the answer there)."""
    if len(head) < 29:
        return False
    return head[24] == 16 or (head[24] == 8 and head[25] in (0, 2, 4, 6) and head[28] == 0)


def _png(path: Path) -> Photo:
    from ..errors import SpectrumError
    from ..upsampling.png_reader import iter_png_rows, png_header

    try:
        header = png_header(path)
    except SpectrumError as exc:
        raise UserError(f"cannot be read as an image: {exc}") from None
    _check_pixels(path, header.width, header.height)

    def read(rows: int) -> Iterator[np.ndarray]:
        try:
            for _, block in iter_png_rows(path, rows_per_block=rows):
                yield block
        except SpectrumError as exc:
            raise UserError(f"cannot be read as an image: {exc}") from None

    return Photo(path, header.width, header.height, header.bit_depth, read)


def _check_pixels(path: Path, width: int, height: int) -> None:
    if width * height > MAX_PIXELS:
        raise UserError(f"{path}: {width} x {height} pixels; at most {MAX_PIXELS} are read")


def _check_memory(path: Path, width: int, height: int, nbytes: int, how: str) -> None:
    from ..budget import check_bytes

    _check_pixels(path, width, height)
    check_bytes(nbytes, f"{path}: {width} x {height} pixels ({how} is decoded whole; a PNG is "
                "streamed)")


def _pillow_codes(path: Path) -> np.ndarray:
    from PIL import Image

    try:
        with Image.open(path) as image:
            width, height = image.size
            bands = len(image.getbands())
            # the decoded image and its RGB conversion are held together
            _check_memory(path, width, height, width * height * (bands + 3), "a JPEG or palette PNG")
            return np.asarray(image.convert("RGB"))
    except (UserError, BudgetError):
        raise
    except Exception as exc:  # Pillow raises many types for damaged files
        raise UserError(f"{path}: cannot be read as an image ({exc})") from None


def _tiff_codes(path: Path) -> np.ndarray:
    import tifffile

    from ..budget import claimed_bytes

    try:
        with tifffile.TiffFile(path) as tif:
            series = tif.series[0]
            shape = tuple(series.shape)
            if len(shape) not in (2, 3):
                raise UserError(f"{path}: expected an RGB image of 8- or 16-bit codes; got shape {shape}")
            nbytes = claimed_bytes(shape, np.dtype(series.dtype).itemsize, f"{path}: shape")
            _check_memory(path, shape[1], shape[0], nbytes, "a TIFF")
            codes = np.asarray(series.asarray())
    except (UserError, BudgetError):
        raise
    except Exception as exc:  # tifffile raises many types for damaged files
        raise UserError(f"{path}: cannot be read as an image ({exc})") from None
    if codes.ndim not in (2, 3) or (codes.ndim == 3 and codes.shape[-1] not in (1, 2, 3, 4)) \
            or codes.dtype not in (np.uint8, np.uint16):
        raise UserError(f"{path}: expected an RGB image of 8- or 16-bit codes; got {codes.dtype} "
                        f"{codes.shape}")
    return codes


def _whole(path: Path, codes: np.ndarray) -> Photo:
    bits = 16 if codes.dtype == np.uint16 else 8

    def read(rows: int) -> Iterator[np.ndarray]:
        for top in range(0, codes.shape[0], rows):
            yield codes[top:top + rows]

    return Photo(path, int(codes.shape[1]), int(codes.shape[0]), bits, read)
