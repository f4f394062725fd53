"""Fuzz cases for the readers streamed in issue 25: damaged TIFF, JPEG and palette PNG photos read
in blocks (``spectrocolor.cli.photos``) and damaged ``.npz`` members read lazily
(``MappedArray`` / ``ZipMemberArray``) end in a result or one clear error, never a raw exception."""

from __future__ import annotations

import io
import tempfile
import zipfile
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

tifffile = pytest.importorskip("tifffile")
Image = pytest.importorskip("PIL.Image")

from spectrocolor.cli import UserError  # noqa: E402
from spectrocolor.cli.photos import open_photo  # noqa: E402
from spectrocolor.errors import SpectrumError  # noqa: E402
from spectrocolor.images import read_cube  # noqa: E402

SETTINGS = settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])
CODES = np.random.default_rng(4).integers(0, 255, (40, 23, 3), endpoint=True).astype(np.uint8)


def _photo_bytes(kind: str) -> bytes:
    buffer = io.BytesIO()
    if kind == "strips":
        tifffile.imwrite(buffer, CODES, photometric="rgb", compression="zlib", rowsperstrip=6)
    elif kind == "tiles":
        tifffile.imwrite(buffer, CODES, photometric="rgb", tile=(16, 16))
    elif kind == "raw":
        tifffile.imwrite(buffer, CODES, photometric="rgb")
    elif kind == "jpeg":
        Image.fromarray(CODES).save(buffer, "JPEG")
    else:
        Image.fromarray(CODES).quantize(8).save(buffer, "PNG")
    return buffer.getvalue()


SUFFIX = {"strips": ".tif", "tiles": ".tif", "raw": ".tif", "jpeg": ".jpg", "palette": ".png"}


def _damage(data: bytes, edits, cut) -> bytes:
    damaged = bytearray(data)
    for where, value in edits:
        damaged[where % len(damaged)] = value
    return bytes(damaged[:max(8, len(damaged) - cut)])


@SETTINGS
@given(kind=st.sampled_from(sorted(SUFFIX)),
       edits=st.lists(st.tuples(st.integers(0, 10**6), st.integers(0, 255)), max_size=6),
       cut=st.integers(0, 400), rows=st.integers(1, 50))
def test_damaged_photos_read_in_blocks_give_a_result_or_one_clear_error(kind, edits, cut, rows):
    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder) / f"photo{SUFFIX[kind]}"
        path.write_bytes(_damage(_photo_bytes(kind), edits, cut))
        try:
            photo = open_photo(path)
            blocks = list(photo.blocks(rows))
        except (UserError, SpectrumError):
            return
        assert sum(len(b) for b in blocks) == photo.height
        assert all(b.shape[1:] == (photo.width, 3) for b in blocks)


@SETTINGS
@given(compressed=st.booleans(),
       edits=st.lists(st.tuples(st.integers(0, 1_300_000), st.integers(0, 255)), max_size=4),
       cut=st.sampled_from([0, 0, 0, 10, 200, 3000]))
def test_damaged_npz_members_beyond_the_budget_give_a_result_or_one_clear_error(compressed, edits, cut):
    values = np.linspace(0.0, 1.0, 100 * 100 * 31, dtype=np.float32).reshape(100, 100, 31)  # 1.18 MiB
    buffer = io.BytesIO()
    (np.savez_compressed if compressed else np.savez)(buffer, values=values,
                                                        wavelengths_nm=np.arange(400.0, 701.0, 10.0))
    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder) / "cube.npz"
        path.write_bytes(_damage(buffer.getvalue(), edits, cut))
        try:
            cube = read_cube(path, memory_budget="1MiB")  # the member is beyond it: read lazily
            for top in range(0, cube.shape[0], 7):
                cube.values[top:top + 7]
        except (SpectrumError, zipfile.BadZipFile, EOFError, OSError) as exc:
            # a damaged archive must be named by the reader, not leak the zip module's error
            assert isinstance(exc, SpectrumError), repr(exc)
