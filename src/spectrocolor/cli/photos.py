"""Photos and textures read in blocks of rows, for ``relight`` and ``upsample``.

8- and 16-bit PNG (grey, grey + alpha, RGB, RGBA; not interlaced) are decoded block by block
by :func:`spectrocolor.imagefiles.iter_png_rows`, so a photo of any size allowed
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

    Raises UserError for unreadable files, more than :data:`MAX_PIXELS` pixels, or (for files
    decoded whole) more memory than the budget.
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
        _check_memory(path, header.width, header.height, header.nbytes, "a TIFF")
    else:  # the decoded image and its RGB conversion are held together
        _check_memory(path, header.width, header.height, header.width * header.height * (header.channels + 3),
                      "a JPEG or palette PNG")
    try:
        return _whole(path, read_image(path))
    except BudgetError:
        raise
    except SpectrumError as exc:
        raise UserError(_unreadable(exc)) from None


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

    check_bytes(nbytes, f"{path}: {width} x {height} pixels ({how} is decoded whole; a PNG is "
                "streamed)")


def _whole(path: Path, codes: np.ndarray) -> Photo:
    bits = 16 if codes.dtype == np.uint16 else 8

    def read(rows: int) -> Iterator[np.ndarray]:
        for top in range(0, codes.shape[0], rows):
            yield codes[top:top + rows]

    return Photo(path, int(codes.shape[1]), int(codes.shape[0]), bits, read)
