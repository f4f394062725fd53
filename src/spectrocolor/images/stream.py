"""Image files written block by block, so a conversion never holds the whole image.

:func:`spectrocolor.images.write_converted` computes an image in blocks of rows; the writers
here take those blocks as they come:

* **PNG**: this module writes the datastream itself (PNG specification, 3rd edition, W3C
  2025): the ``IHDR`` chunk, then each block's rows filtered with the Paeth filter (filter type
  4, §9.4), compressed by one running :func:`zlib.compressobj` and written as ``IDAT`` chunks
  as soon as zlib hands out bytes, then ``IEND``. Memory: one block of codes and zlib's window.
* **TIFF**: tifffile writes uncompressed strips from an iterator, one strip per block.

Both go through :func:`spectrocolor.safe_write.atomic_path` (temporary file beside the target,
read-back check, rename), like every other writer of the package.
"""

from __future__ import annotations

import struct
import zlib
from collections.abc import Iterable, Iterator
from pathlib import Path

import numpy as np

from ..safe_write import atomic_path, verify_png, verify_tiff

_PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"
_COLOUR_TYPE = {3: 2, 4: 6}  # channels -> PNG colour type: truecolour, truecolour with alpha


def _chunk(kind: bytes, data: bytes) -> bytes:
    return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))


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
    channels : {3, 4}
        RGB or RGBA (alpha not premultiplied, as PNG defines it).
    bit_depth : {8, 16}
        Bits per sample.

    Returns
    -------
    pathlib.Path
        ``path``.

    Raises
    ------
    ValueError
        Blocks of the wrong shape or dtype, or not ``height`` rows in all (a programming error:
        the target is left unchanged).
    spectrocolor.safe_write.OutputError
        The file cannot be written; any previous file is unchanged.

    References
    ----------
    PNG specification, 3rd edition (W3C, 2025): §5 datastream structure, §11.2 IHDR, IDAT, IEND.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> import numpy as np
    >>> from PIL import Image
    >>> codes = np.arange(2 * 3 * 3, dtype=np.uint8).reshape(2, 3, 3)
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     path = write_png_blocks(pathlib.Path(folder) / "a.png", [codes[:1], codes[1:]], 2, 3, 3, 8)
    ...     np.array_equal(np.asarray(Image.open(path)), codes)
    True
    """
    dtype = np.dtype(">u2") if bit_depth == 16 else np.dtype(np.uint8)
    line_bytes = width * channels * dtype.itemsize
    with atomic_path(path, verify=lambda p: verify_png(p, width, height)) as temporary:
        with open(temporary, "wb") as out:
            out.write(_PNG_SIGNATURE)
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
    """Write a float32 TIFF from blocks of rows, one uncompressed strip per block.

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
        JSON-serialisable facts stored in the image description (as
        :func:`spectrocolor.pictures.write_image` stores them).

    Returns
    -------
    pathlib.Path
        ``path``.

    Raises
    ------
    ValueError
        Blocks that do not add up to ``shape`` (the target is left unchanged).
    spectrocolor.safe_write.OutputError
        The file cannot be written; any previous file is unchanged.

    References
    ----------
    TIFF Revision 6.0 (Adobe, 1992), section 3 (strips) and ExtraSamples (unassociated alpha).

    Examples
    --------
    >>> import tempfile, pathlib
    >>> import numpy as np, tifffile
    >>> values = np.arange(5 * 2 * 3, dtype=np.float32).reshape(5, 2, 3)
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     path = pathlib.Path(folder) / "a.tif"
    ...     _ = write_tiff_blocks(path, [values[:2], values[2:4], values[4:]], (5, 2, 3), 2)
    ...     np.array_equal(tifffile.imread(path), values)
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

    extra = {"extrasamples": ["unassalpha"]} if channels == 4 else {}
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
            **extra,
        )
    return Path(path)
