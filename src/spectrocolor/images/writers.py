"""Write converted images: PNG with 8- or 16-bit codes, TIFF with floating-point values.

* PNG, 8-bit: Pillow.
* PNG, 16-bit RGB: Pillow cannot write 16-bit RGB PNG, so it is encoded here (the PNG format:
  signature, IHDR, one zlib-compressed IDAT of unfiltered rows, IEND; samples big-endian).
  16-bit grey goes through Pillow.
* TIFF, float32 or float64 (e.g. XYZ100, CIELAB, linear RGB): tifffile, with a JSON
  description holding the metadata you pass (quantity, illuminant, ...).

OpenEXR is not written: the maintained ``OpenEXR`` bindings are a compiled extra we do not
need, since float TIFF carries the same data losslessly and every HDR tool reads it.

References
----------
W3C, *Portable Network Graphics (PNG) Specification*, 3rd ed., 2025, sections 5 (datastream
structure) and 11.2 (IHDR, IDAT, IEND).
"""

from __future__ import annotations

import struct
import zlib
from pathlib import Path

import numpy as np

from ..errors import SpectrumError
from ..safe_write import atomic_path, verify_png, verify_tiff, write_bytes

__all__ = ["write_image"]


def write_image(path, image, *, metadata: dict | None = None) -> Path:
    """Write an image array to PNG (integer codes) or TIFF (floating point).

    Parameters
    ----------
    path : str or Path
        Output file; ``.png`` or ``.tif``/``.tiff``.
    image : array_like, shape (H, W, 3) or (H, W)
        For PNG: ``uint8`` codes (8-bit PNG) or ``uint16`` codes (16-bit PNG), e.g. the
        ``codes`` of :func:`spectrocolor.render`. For TIFF: float32 or float64 values, written
        as they are (no scaling, no clipping), e.g. XYZ100 or CIELAB.
    metadata : dict, keyword-only, optional
        TIFF only: JSON-serialisable facts stored in the image description.

    Returns
    -------
    Path
        The path written.

    Raises
    ------
    SpectrumError
        An unsupported suffix, shape or dtype (e.g. floats for PNG: quantise them first).
    spectrocolor.safe_write.OutputError
        The file could not be written completely (full disk, no permission ...); it is written
        beside ``path``, read back and only then renamed over it, so a previous file survives.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> import numpy as np
    >>> from PIL import Image
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     path = write_image(pathlib.Path(folder) / "codes.png", np.zeros((2, 3, 3), np.uint8))
    ...     with Image.open(path) as picture:
    ...         print(picture.size)  # width, height
    (3, 2)
    """
    path = Path(path)
    array = np.asarray(image)
    if array.ndim not in (2, 3) or (array.ndim == 3 and array.shape[2] != 3) or 0 in array.shape:
        raise SpectrumError(f"image must have shape (H, W, 3) or (H, W) with H, W >= 1; got "
                            f"{array.shape}")
    suffix = path.suffix.lower()
    if suffix == ".png":
        if metadata:
            raise SpectrumError("metadata is stored in TIFF files only; PNG gets none")
        height, width = array.shape[:2]
        if array.dtype == np.uint8 or (array.dtype == np.uint16 and array.ndim == 2):
            from PIL import Image

            with atomic_path(path, verify=lambda p: verify_png(p, width, height)) as temporary:
                Image.fromarray(array).save(temporary, format="PNG")
        elif array.dtype == np.uint16:
            write_bytes(path, _png16_rgb(array), verify=lambda p: verify_png(p, width, height))
        else:
            raise SpectrumError(
                f"PNG needs uint8 or uint16 codes; got {array.dtype} (render with bit_depth=8 or"
                " 16, or write floats to .tif)"
            )
    elif suffix in (".tif", ".tiff"):
        if array.dtype not in (np.float32, np.float64):
            raise SpectrumError(
                f"TIFF output is for float32/float64 values; got {array.dtype} (write codes "
                "to .png)"
            )
        import tifffile

        photometric = "rgb" if array.ndim == 3 else "minisblack"
        with atomic_path(path, verify=lambda p: verify_tiff(p, array.shape, array.nbytes)) as temporary:
            tifffile.imwrite(temporary, array, photometric=photometric, metadata=metadata or {})
    else:
        raise SpectrumError(
            f"{path}: unknown image format {suffix!r}; accepted: .png (8/16-bit codes), "
            ".tif/.tiff (float)"
        )
    return path


def _chunk(kind: bytes, data: bytes) -> bytes:
    return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))


def _png16_rgb(codes: np.ndarray) -> bytes:
    """A 16-bit RGB PNG datastream of ``codes`` (H, W, 3) uint16."""
    height, width, _ = codes.shape
    header = struct.pack(">IIBBBBB", width, height, 16, 2, 0, 0, 0)
    rows = codes.astype(">u2").reshape(height, width * 3).view(np.uint8)  # (H, 6 W) bytes
    filtered = np.concatenate([np.zeros((height, 1), np.uint8), rows], axis=1)  # filter 0: none
    return (
        b"\x89PNG\r\n\x1a\n"
        + _chunk(b"IHDR", header)
        + _chunk(b"IDAT", zlib.compress(filtered.tobytes(), 6))
        + _chunk(b"IEND", b"")
    )
