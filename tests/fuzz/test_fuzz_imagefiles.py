"""Fuzz the readers of spectrocolor.imagefiles: damaged PNG, TIFF, JPEG and GIF files give one
SpectrumError naming the file (or codes of the size the header states), never another exception,
and a header claiming more than the memory budget is refused before anything is decoded."""

import struct
import zlib

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import spectrocolor as sc
from spectrocolor.imagefiles import image_header, read_image, write_gif, write_image

BUDGET = "4MiB"


def _valid(folder, suffix: str) -> bytes:
    codes = (np.arange(5 * 6 * 3).reshape(5, 6, 3) * 977 % 65536).astype(np.uint16)
    if suffix == ".gif":
        return write_gif(folder / "v.gif", [(codes >> 8).astype(np.uint8)] * 2).read_bytes()
    if suffix == ".jpg":
        return write_image(folder / "v.jpg", (codes >> 8).astype(np.uint8)).read_bytes()
    if suffix == ".png8":
        return write_image(folder / "v.png", (codes >> 8).astype(np.uint8)).read_bytes()
    return write_image(folder / f"v{suffix}", codes if suffix == ".png" else codes.astype(np.float32)).read_bytes()


def _read_or_refuse(path):
    try:
        header = image_header(path)
        codes = read_image(path, memory_budget=BUDGET)
    except sc.SpectrumError as exc:
        assert path.name in str(exc)
        return None
    assert codes.shape[:2] == (header.height, header.width)
    return codes


@settings(max_examples=50, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(st.sampled_from([".png", ".png8", ".tif", ".jpg", ".gif"]), st.data())
def test_damaged_image_files_are_refused_with_one_error_or_read(tmp_path, suffix, data):
    raw = bytearray(_valid(tmp_path, suffix))
    for _ in range(data.draw(st.integers(1, 4))):
        at = data.draw(st.integers(0, len(raw) - 1))
        raw[at] = data.draw(st.integers(0, 255))
    if data.draw(st.booleans()):
        raw = raw[:data.draw(st.integers(0, len(raw)))]
    path = tmp_path / f"fuzz{suffix[:4]}"
    path.write_bytes(bytes(raw))
    codes = _read_or_refuse(path)
    if codes is not None and suffix == ".png":  # a CRC-32 guards every chunk of a PNG
        assert bytes(raw) == _valid(tmp_path, suffix)


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(width=st.integers(1, 2**31 - 1), height=st.integers(1, 2**31 - 1),
       depth=st.sampled_from([1, 2, 4, 8, 16]), colour_type=st.sampled_from([0, 2, 3, 4, 6]),
       interlace=st.integers(0, 1))
def test_a_png_header_claiming_any_size_is_checked_before_decoding(tmp_path, width, height, depth,
                                                                   colour_type, interlace):
    def chunk(kind, body):
        return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body))

    header = struct.pack(">IIBBBBB", width, height, depth, colour_type, 0, 0, interlace)
    path = tmp_path / "lying.png"
    path.write_bytes(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header)
                     + chunk(b"IDAT", zlib.compress(bytes(1000))) + chunk(b"IEND", b""))
    codes = _read_or_refuse(path)
    if codes is not None:  # only an image within the budget whose few bytes are all there
        assert codes.nbytes <= 4 * 2**20


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(st.binary(max_size=200), st.sampled_from([b"\x89PNG\r\n\x1a\n", b"II*\x00", b"MM\x00*", b"GIF89a",
                                                 b"\xff\xd8\xff", b""]))
def test_random_bytes_after_a_signature_are_refused(tmp_path, tail, signature):
    path = tmp_path / "noise.img"
    path.write_bytes(signature + tail)
    with pytest.raises(sc.SpectrumError, match="noise.img"):
        read_image(path, memory_budget=BUDGET)
