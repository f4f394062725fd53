"""spectrocolor.imagefiles: every format and bit depth round-trips; writes are atomic; sizes are
checked against the memory budget before anything is decoded."""

import io

import numpy as np
import pytest
from PIL import Image

import spectrocolor as sc
from spectrocolor import imagefiles
from spectrocolor.imagefiles import (
    image_header,
    iter_png_rows,
    read_image,
    write_gif,
    write_image,
    write_png_blocks,
    write_tiff_blocks,
)
from spectrocolor.safe_write import OutputError

RNG = np.random.default_rng(24)


def codes(shape, dtype):
    return RNG.integers(0, np.iinfo(dtype).max, shape, endpoint=True, dtype=dtype)


@pytest.mark.parametrize("dtype", [np.uint8, np.uint16])
@pytest.mark.parametrize("shape", [(7, 5), (7, 5, 2), (7, 5, 3), (7, 5, 4)])
def test_png_round_trips_every_depth_and_channel_count_exactly(tmp_path, dtype, shape):
    image = codes(shape, dtype)
    image[0, 0] = 1  # the low byte matters
    path = write_image(tmp_path / "a.png", image)
    header = image_header(path)
    assert (header.format, header.width, header.height, header.dtype) == ("PNG", 5, 7, np.dtype(dtype))
    back = read_image(path)
    assert back.dtype == dtype and back.shape == shape
    # exact: integer codes through an encoder and a decoder: no floating point
    np.testing.assert_array_equal(back, image)


def test_16_bit_rgb_png_keeps_every_bit_where_pillow_would_not(tmp_path):
    image = codes((40, 33, 3), np.uint16)
    image[0, 0] = (0x0001, 0x0100, 0xFFFE)
    path = write_image(tmp_path / "rgb16.png", image)
    # exact: integer codes through an encoder and a decoder: no floating point
    np.testing.assert_array_equal(read_image(path), image)
    with Image.open(path) as pillow:
        assert pillow.mode == "RGB"  # 8 bits: why the module decodes 16-bit PNG itself


@pytest.mark.parametrize("dtype", [np.uint8, np.uint16, np.float32, np.float64])
@pytest.mark.parametrize("shape", [(6, 4), (6, 4, 3), (6, 4, 4)])
def test_tiff_round_trips_exactly_with_metadata(tmp_path, dtype, shape):
    if np.dtype(dtype).kind == "f":
        image = RNG.normal(size=shape).astype(dtype)
    else:
        image = codes(shape, dtype)
    path = write_image(tmp_path / "a.tiff", image, metadata={"quantity": "XYZ100"})
    header = image_header(path)
    assert (header.format, header.width, header.height, header.dtype) == ("TIFF", 4, 6, np.dtype(dtype))
    # exact: the same numbers written and read back (no arithmetic)
    np.testing.assert_array_equal(read_image(path), image)


@pytest.mark.parametrize("shape", [(16, 24), (16, 24, 3)])
def test_jpeg_round_trips_within_its_loss(tmp_path, shape):
    y, x = np.mgrid[0:16, 0:24]
    plane = (x * 8 + y * 4).astype(np.uint8)
    image = plane if len(shape) == 2 else np.stack([plane, 255 - plane, plane // 2], -1)
    path = write_image(tmp_path / "a.jpg", image)
    assert image_header(path).format == "JPEG"
    back = read_image(path)
    assert back.shape == shape and back.dtype == np.uint8
    assert np.abs(back.astype(int) - image).max() <= 12  # JPEG at quality 95 on a smooth ramp


def test_gif_frames_round_trip_and_a_palette_png_is_expanded(tmp_path):
    palette = np.array([[0, 0, 0], [255, 0, 0], [0, 128, 255], [255, 255, 255]], np.uint8)
    frames = [palette[RNG.integers(0, 4, (5, 6))] for _ in range(3)]
    path = write_gif(tmp_path / "a.gif", frames, frame_ms=50)
    header = image_header(path)
    assert (header.format, header.width, header.height, header.frames) == ("GIF", 6, 5, 3)
    # exact: four colours fit a GIF palette: codes come back as written
    np.testing.assert_array_equal(read_image(path), frames[0])
    with Image.open(path) as gif:
        for index, frame in enumerate(frames):
            gif.seek(index)
            # exact: palette indices expanded back to the same codes
            np.testing.assert_array_equal(np.asarray(gif.convert("RGB")), frame)
    buffer = io.BytesIO()
    Image.fromarray(frames[1]).quantize(4).save(buffer, "PNG")
    (tmp_path / "p.png").write_bytes(buffer.getvalue())
    # exact: palette indices expanded back to the same codes
    np.testing.assert_array_equal(read_image(tmp_path / "p.png"), frames[1])


@pytest.mark.parametrize("bit_depth, channels", [(8, 1), (8, 3), (16, 2), (16, 4)])
def test_png_written_in_blocks_reads_back_in_other_blocks(tmp_path, bit_depth, channels):
    dtype = np.uint16 if bit_depth == 16 else np.uint8
    image = codes((13, 9, channels), dtype)
    path = write_png_blocks(tmp_path / "b.png", [image[:5], image[5:6], image[6:]], 13, 9, channels, bit_depth)
    blocks = [block for _, block in iter_png_rows(path, rows_per_block=4)]
    # exact: integer codes through an encoder and a decoder: no floating point
    np.testing.assert_array_equal(np.concatenate(blocks), image)


def test_tiff_written_in_blocks(tmp_path):
    values = RNG.normal(size=(5, 3, 4)).astype(np.float32)
    path = write_tiff_blocks(tmp_path / "b.tif", [values[:2], values[2:4], values[4:]], (5, 3, 4), 2)
    # exact: the same float32 numbers written and read back
    np.testing.assert_array_equal(read_image(path), values)


# --- atomicity --------------------------------------------------------------------------------


def _listing(folder):
    return sorted(p.name for p in folder.iterdir())


@pytest.mark.parametrize("name", ["a.png", "a.tif", "a.jpg", "a.gif"])
def test_a_failing_encoder_leaves_the_previous_file_and_no_partial_one(tmp_path, monkeypatch, name):
    target = tmp_path / name
    target.write_bytes(b"previous")
    image = codes((4, 4, 3), np.uint16 if name == "a.png" else np.uint8)
    if name.endswith(".tif"):
        image = image.astype(np.float32)

    def broken(*_args, **_kwargs):
        raise OSError(28, "No space left on device")

    import imagecodecs
    import tifffile
    from PIL import Image as PillowImage

    monkeypatch.setattr(imagecodecs, "png_encode", broken)
    monkeypatch.setattr(tifffile, "imwrite", broken)
    monkeypatch.setattr(PillowImage.Image, "save", broken)
    with pytest.raises(OutputError):
        write_image(target, image) if name != "a.gif" else write_gif(target, [image])
    assert target.read_bytes() == b"previous"
    assert _listing(tmp_path) == [name]


def test_a_block_writer_stopped_midway_leaves_nothing(tmp_path):
    image = codes((6, 4, 3), np.uint8)
    with pytest.raises(ValueError, match="rows given"):
        write_png_blocks(tmp_path / "c.png", [image[:3]], 6, 4, 3, 8)
    with pytest.raises(ValueError, match="block of shape"):
        write_tiff_blocks(tmp_path / "c.tif", [image[:2].astype(np.float32)], (6, 5, 3), 2)
    assert _listing(tmp_path) == []


def test_a_written_file_that_does_not_read_back_is_not_placed(tmp_path, monkeypatch):
    import imagecodecs

    real = imagecodecs.png_encode
    monkeypatch.setattr(imagecodecs, "png_encode", lambda *a, **k: real(*a, **k)[:-20])  # cut off
    with pytest.raises(OutputError, match="does not read back"):
        write_image(tmp_path / "d.png", codes((4, 4, 3), np.uint16))
    assert _listing(tmp_path) == []


# --- sizes checked before decoding ------------------------------------------------------------


@pytest.mark.parametrize("name", ["big.png", "big16.png", "big.tif", "big.jpg", "big.gif"])
def test_the_header_size_is_checked_against_the_budget_before_decoding(tmp_path, monkeypatch, name):
    dtype = np.uint16 if name in ("big16.png", "big.tif") else np.uint8
    path = write_image(tmp_path / name, np.zeros((700, 800, 3), dtype)) if not name.endswith(".gif") \
        else write_gif(tmp_path / name, [np.zeros((700, 800, 3), np.uint8)])
    import imagecodecs
    import tifffile
    from PIL import ImageFile

    def no_decoding(*_args, **_kwargs):
        raise AssertionError("decoded before the size was checked")

    monkeypatch.setattr(imagecodecs, "png_decode", no_decoding)
    monkeypatch.setattr(tifffile.TiffPageSeries, "asarray", no_decoding)
    monkeypatch.setattr(ImageFile.ImageFile, "load", no_decoding)
    with pytest.raises(sc.BudgetError, match="800 x 700 pixels.*memory budget of 1 MiB"):
        read_image(path, memory_budget="1MiB")


def test_unknown_suffixes_shapes_and_damaged_files_are_one_clear_error(tmp_path):
    with pytest.raises(sc.SpectrumError, match="unknown image format"):
        write_image(tmp_path / "a.bmp", np.zeros((2, 2), np.uint8))
    with pytest.raises(sc.SpectrumError, match="shape"):
        write_image(tmp_path / "a.png", np.zeros((2, 2, 5), np.uint8))
    with pytest.raises(sc.SpectrumError, match="uint8 or uint16"):
        write_image(tmp_path / "a.png", np.zeros((2, 2), np.float32))
    with pytest.raises(sc.SpectrumError, match="TIFF files only"):
        write_image(tmp_path / "a.png", np.zeros((2, 2), np.uint8), metadata={"a": 1})
    (tmp_path / "noise.jpg").write_bytes(b"\xff\xd8\xff" + bytes(40))
    with pytest.raises(sc.SpectrumError, match="noise.jpg"):
        read_image(tmp_path / "noise.jpg")
    with pytest.raises(sc.SpectrumError, match="cannot be read"):
        read_image(tmp_path / "absent.png")
    assert imagefiles.MAX_PIXELS == 2**28


def test_the_thin_film_gif_goes_through_the_atomic_writer(tmp_path, monkeypatch):
    from PIL import Image as PillowImage

    from spectrocolor import colour_table, soap_film
    from spectrocolor.thinfilm.maps import draining_film_gif

    table = colour_table(soap_film, 1200.0, thickness_step_nm=5.0)
    path = draining_film_gif(tmp_path / "film.gif", table, 8, 6, [2.0e4, 4.0e4])
    assert image_header(path).frames == 2 and image_header(path).width == 8
    before = path.read_bytes()

    def broken(*_args, **_kwargs):
        raise OSError(28, "No space left on device")

    monkeypatch.setattr(PillowImage.Image, "save", broken)
    with pytest.raises(OutputError):
        draining_film_gif(path, table, 8, 6, [3.0e4])
    assert path.read_bytes() == before
    assert _listing(tmp_path) == ["film.gif"]
