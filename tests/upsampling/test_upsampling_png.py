"""The PNG reader: 8/16-bit codes back bit for bit, every scanline filter, damaged files refused.

The files are written here by an independent encoder that applies the filters of the PNG
specification (W3C PNG 3rd ed., section 9.2) in their direct, non-recursive form
``filtered = raw − predictor(raw neighbours) mod 256``, so the decoder's recursive
reconstruction is checked against the definition. Pillow- and write_image-made files check it
against other encoders.
"""

import io
import struct
import zlib

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from PIL import Image

import spectrocolor as sc
from spectrocolor.imagefiles import decode_png
from spectrocolor.pictures import write_image
from spectrocolor.upsampling import read_png

SIGNATURE = b"\x89PNG\r\n\x1a\n"
CHANNELS = {0: 1, 2: 3, 4: 2, 6: 4}


def chunk(kind: bytes, body: bytes) -> bytes:
    return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body))


def filtered_rows(codes: np.ndarray, depth: int, filters) -> bytes:
    """Scanlines of ``codes`` (H, W, C), row r filtered with ``filters[r]`` (0-4)."""
    height, width, channels = codes.shape
    if depth == 16:
        raw = codes.astype(">u2").view(np.uint8).reshape(height, width, 2 * channels)
    else:
        raw = codes.astype(np.uint8)
    x = raw.astype(np.int32)
    a = np.zeros_like(x)
    a[:, 1:] = x[:, :-1]
    b = np.zeros_like(x)
    b[1:] = x[:-1]
    c = np.zeros_like(x)
    c[1:, 1:] = x[:-1, :-1]
    p = a + b - c
    pa, pb, pc = np.abs(p - a), np.abs(p - b), np.abs(p - c)
    paeth = np.where((pa <= pb) & (pa <= pc), a, np.where(pb <= pc, b, c))
    predictors = (np.zeros_like(x), a, b, (a + b) // 2, paeth)
    return b"".join(bytes([f]) + ((x[r] - predictors[f][r]) % 256).astype(np.uint8).tobytes()
                    for r, f in enumerate(filters))


def encode(codes, depth=16, colour_type=2, filters=None, pieces=1, interlace=0, before_idat=b"",
           stream=None):
    height, width = codes.shape[:2]
    filters = [0] * height if filters is None else filters
    data = zlib.compress(filtered_rows(codes, depth, filters)) if stream is None else stream
    cuts = np.linspace(0, len(data), pieces + 1).astype(int)
    header = struct.pack(">IIBBBBB", width, height, depth, colour_type, 0, 0, interlace)
    return (SIGNATURE + chunk(b"IHDR", header) + before_idat
            + b"".join(chunk(b"IDAT", data[i:j]) for i, j in zip(cuts[:-1], cuts[1:], strict=True))
            + chunk(b"IEND", b""))


@st.composite
def images(draw):
    depth = draw(st.sampled_from([8, 16]))
    colour_type = draw(st.sampled_from(sorted(CHANNELS)))
    height, width = draw(st.integers(1, 9)), draw(st.integers(1, 9))
    dtype = np.uint16 if depth == 16 else np.uint8
    values = draw(st.lists(st.integers(0, 2**depth - 1), min_size=height * width * CHANNELS[colour_type],
                           max_size=height * width * CHANNELS[colour_type]))
    codes = np.array(values, dtype=dtype).reshape(height, width, CHANNELS[colour_type])
    filters = draw(st.lists(st.integers(0, 4), min_size=height, max_size=height))
    return codes, depth, colour_type, filters, draw(st.integers(1, 3))


@settings(max_examples=150, deadline=None)
@given(images(), st.booleans())
def test_every_filter_depth_and_colour_type_decodes_to_the_codes(image, compiled):
    codes, depth, colour_type, filters, pieces = image
    data = encode(codes, depth, colour_type, filters, pieces)
    with pytest.MonkeyPatch.context() as patch:
        patch.setenv("SPECTROCOLOR_NUMBA", "1" if compiled else "0")
        back = decode_png(data)
    assert back.dtype == codes.dtype
    # exact: integer codes through an encoder and a decoder: no floating point
    np.testing.assert_array_equal(back, codes)


def test_all_five_filters_in_one_image_with_both_paths(monkeypatch):
    rng = np.random.default_rng(7)
    codes = rng.integers(0, 65536, (23, 31, 3), dtype=np.uint16)
    codes[:, :8] = np.arange(8)[None, :, None] * 9000  # smooth runs as well as noise
    data = encode(codes, filters=[r % 5 for r in range(23)], pieces=4)
    # exact: integer codes through an encoder and a decoder: no floating point
    np.testing.assert_array_equal(decode_png(data), codes)
    monkeypatch.setenv("SPECTROCOLOR_NUMBA", "0")
    # exact: integer codes through an encoder and a decoder: no floating point
    np.testing.assert_array_equal(decode_png(data), codes)


@pytest.mark.parametrize("rows", [1, 2, 4, 10])  # the filters' state carried across blocks of rows
def test_large_images_cross_blocks(rows):
    from spectrocolor.imagefiles import iter_png_rows

    codes = np.random.default_rng(8).integers(0, 65536, (11, 6, 4), dtype=np.uint16)
    data = encode(codes, 16, 6, [4, 3, 2, 1, 0, 4, 4, 3, 3, 2, 4])
    blocks = [block for _, block in iter_png_rows(data, rows_per_block=rows)]
    # exact: integer codes through an encoder and a decoder: no floating point
    np.testing.assert_array_equal(np.concatenate(blocks), codes)


def test_round_trip_with_the_project_writer_keeps_all_16_bits(tmp_path):
    codes = np.random.default_rng(9).integers(0, 65536, (40, 33, 3), dtype=np.uint16)
    codes[0, 0] = (0x0001, 0x0100, 0xFFFE)  # the low byte matters
    back = read_png(write_image(tmp_path / "rgb16.png", codes))
    # exact: integer codes through an encoder and a decoder: no floating point
    np.testing.assert_array_equal(back, codes)
    with Image.open(tmp_path / "rgb16.png") as pillow:  # what the reader exists for
        # exact: integer codes through an encoder and a decoder: no floating point
        assert not np.array_equal(np.asarray(pillow).astype(np.uint16) * 257, codes)


@pytest.mark.parametrize("mode, shape", [("RGB", (30, 41, 3)), ("RGBA", (30, 41, 4)), ("L", (30, 41)),
                                         ("LA", (30, 41, 2))])
def test_pillow_files_with_adaptive_filters(mode, shape):
    y, x = np.mgrid[0:shape[0], 0:shape[1]]
    planes = [(x * 7 + y * 3) % 256, (x * y) % 256, (x ^ y) % 256, (255 - x) % 256][:(shape + (1,))[2]]
    codes = np.stack(planes, axis=-1).astype(np.uint8).reshape(shape)
    buffer = io.BytesIO()
    picture = Image.fromarray(codes)
    assert picture.mode == mode
    picture.save(buffer, format="PNG")
    back = decode_png(buffer.getvalue())
    # exact: integer codes through an encoder and a decoder: no floating point
    np.testing.assert_array_equal(back.reshape(shape), codes)


def test_pillow_16_bit_grey():
    codes = ((np.arange(24 * 17).reshape(24, 17) * 2579) % 65536).astype(np.uint16)
    buffer = io.BytesIO()
    Image.fromarray(codes).save(buffer, format="PNG")
    # exact: integer codes through an encoder and a decoder: no floating point
    np.testing.assert_array_equal(decode_png(buffer.getvalue())[..., 0], codes)


def corrupt_crc(data: bytes, kind: bytes) -> bytes:
    at = data.index(kind) + 4
    return data[:at] + bytes([data[at] ^ 1]) + data[at + 1:]


CODES = np.arange(2 * 3 * 3, dtype=np.uint16).reshape(2, 3, 3) * 3000
GOOD = encode(CODES, filters=[1, 4])
IDAT_AT = GOOD.index(b"IDAT") - 4


@pytest.mark.parametrize("data, message", [
    (b"", "no PNG signature"),
    (GOOD[:7], "no PNG signature"),
    (SIGNATURE, "no IEND"),
    (GOOD[:40], "cut off|ends first"),
    (GOOD[:-12], "no IEND"),
    (corrupt_crc(GOOD, b"IDAT"), "CRC-32"),
    (SIGNATURE + chunk(b"IDAT", b"x") + chunk(b"IEND", b""), "not IHDR"),
    (encode(CODES, stream=b"not zlib at all"), "cannot be decompressed"),
    (encode(CODES, stream=zlib.compress(b"\0" * 5)), "need"),
    (encode(CODES, stream=zlib.compress(b"\x05" + b"\0" * 18 + b"\0" * 19)), "filter type 5"),
    (encode(CODES, interlace=1), "interlaced"),
    (encode(CODES.astype(np.uint8), depth=8, colour_type=3), "palette"),
    (encode(CODES, before_idat=chunk(b"ZZZZ", b"")), "critical chunk"),
    (GOOD[:IDAT_AT] + chunk(b"IDAT", b"") + chunk(b"tEXt", b"a\0b") + GOOD[IDAT_AT:], "not consecutive"),
])
def test_damaged_and_unsupported_files_get_one_clear_error(tmp_path, data, message):
    path = tmp_path / "bad.png"
    path.write_bytes(data)
    with pytest.raises(sc.SpectrumError, match=message) as error:
        read_png(path)
    assert str(path) in str(error.value)


def test_ancillary_chunks_are_skipped_and_a_missing_file_is_one_error(tmp_path):
    text = chunk(b"tEXt", b"Comment\0made here") + chunk(b"gAMA", struct.pack(">I", 45455))
    # exact: integer codes through an encoder and a decoder: no floating point
    np.testing.assert_array_equal(decode_png(encode(CODES, filters=[2, 3], before_idat=text)), CODES)
    with pytest.raises(sc.SpectrumError, match="cannot be read"):
        read_png(tmp_path / "absent.png")
    with pytest.raises(sc.SpectrumError, match="bytes"):
        decode_png("not bytes")


# --- streamed decoding (issue 25): blocks of rows, long chunks in pieces, the budget ---------------


@settings(max_examples=60, deadline=None)
@given(images(), st.integers(1, 10))
def test_blocks_of_rows_join_to_the_whole_image(image, rows):
    from spectrocolor.imagefiles import iter_png_rows

    codes, depth, colour_type, filters, pieces = image
    data = encode(codes, depth, colour_type, filters, pieces)
    blocks = list(iter_png_rows(data, rows_per_block=rows))
    assert [top for top, _ in blocks] == list(range(0, codes.shape[0], rows))
    # exact: integer codes through an encoder and a decoder: no floating point
    np.testing.assert_array_equal(np.concatenate([block for _, block in blocks]), codes)


def test_long_chunks_are_read_in_pieces(monkeypatch):
    from spectrocolor import imagefiles

    monkeypatch.setattr(imagefiles, "_PIECE", 7)  # every IDAT chunk is "long"
    codes = np.random.default_rng(11).integers(0, 65536, (9, 7, 3), dtype=np.uint16)
    data = encode(codes, 16, 2, [4, 3, 2, 1, 0, 4, 4, 3, 1], before_idat=chunk(b"tEXt", b"Comment\0" + b"x" * 40))
    # exact: integer codes through an encoder and a decoder: no floating point
    np.testing.assert_array_equal(decode_png(data), codes)
    # a long chunk's data are inflated as they come, its CRC checked at its end: damage is met
    # by whichever check comes first
    with pytest.raises(sc.SpectrumError, match="CRC-32|cannot be decompressed"):
        decode_png(corrupt_crc(data, b"IDAT"))


def test_a_header_is_read_without_decoding_and_the_whole_image_is_checked_against_the_budget(tmp_path):
    from spectrocolor.imagefiles import png_header

    path = tmp_path / "wide.png"
    path.write_bytes(encode(np.zeros((600, 1000, 3), np.uint16)))  # 3.4 MiB of codes
    header = png_header(path)
    assert (header.width, header.height, header.bit_depth, header.channels) == (1000, 600, 16, 3)
    with pytest.raises(sc.SpectrumError, match="1000 x 600 pixels of 16-bit codes .*memory budget of 1 MiB"):
        read_png(path, memory_budget="1MiB")
    assert read_png(path, memory_budget="8MiB").shape == (600, 1000, 3)
