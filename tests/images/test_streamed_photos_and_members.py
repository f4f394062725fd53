"""Photos and ``.npz`` members streamed in blocks (issue 25): what the blocks join to is the file.

The photos' blocks (``spectrocolor.cli.photos``: TIFF by bands of strips or tiles, uncompressed
TIFF rows at a time, JPEG and palette PNG cut out of Pillow's one buffer) must join to what
tifffile and Pillow decode whole, for every block height; a ``.npz`` member beyond the memory
budget is read lazily -- stored members straight from the archive, deflated ones inflated row
by row -- and gives the same values as ``np.load``. Expected values come from the independent
whole-file decoders (tifffile, Pillow, NumPy), never from the code under test.
"""

from __future__ import annotations

import pickle

import numpy as np
import pytest

tifffile = pytest.importorskip("tifffile")
Image = pytest.importorskip("PIL.Image")

from spectrocolor.cli.photos import open_photo  # noqa: E402
from spectrocolor.errors import BudgetError  # noqa: E402
from spectrocolor.images import MappedArray, read_cube  # noqa: E402
from spectrocolor.images.cube import ZipMemberArray  # noqa: E402

WAVELENGTHS = np.arange(400.0, 701.0, 10.0)
ROWS = (1, 5, 16, 33, 500)


def _joined(photo, rows: int) -> np.ndarray:
    return np.concatenate(list(photo.blocks(rows)))


@pytest.mark.parametrize("dtype", [np.uint8, np.uint16])
@pytest.mark.parametrize("layout", [
    {"compression": "zlib", "rowsperstrip": 16},
    {"compression": "zlib", "rowsperstrip": 7, "predictor": True},
    {},  # uncompressed, one strip: read from the file rows at a time
    {"rowsperstrip": 10},  # uncompressed strips
    {"tile": (16, 16)},
    {"tile": (32, 16), "compression": "zlib"},
])
def test_tiff_blocks_join_to_what_tifffile_decodes(tmp_path, dtype, layout):
    top = 255 if dtype == np.uint8 else 65535
    codes = np.random.default_rng(3).integers(0, top, (101, 37, 3), endpoint=True).astype(dtype)
    path = tmp_path / "photo.tif"
    tifffile.imwrite(path, codes, photometric="rgb", **layout)
    expected = tifffile.imread(path)
    photo = open_photo(path)
    assert photo.bits == 8 * np.dtype(dtype).itemsize
    for rows in ROWS:
        # exact: integer codes, copied, never computed
        np.testing.assert_array_equal(_joined(photo, rows), expected)


def test_grey_tiff_is_repeated_into_rgb_and_rgba_drops_alpha(tmp_path):
    grey = np.arange(40 * 9, dtype=np.uint16).reshape(40, 9)
    tifffile.imwrite(tmp_path / "grey.tif", grey, compression="zlib", rowsperstrip=9)
    # exact: integer codes, copied
    np.testing.assert_array_equal(_joined(open_photo(tmp_path / "grey.tif"), 7), np.repeat(grey[..., None], 3, -1))
    rgba = np.arange(40 * 9 * 4, dtype=np.uint8).reshape(40, 9, 4)
    tifffile.imwrite(tmp_path / "rgba.tif", rgba, photometric="rgb", extrasamples=["unassalpha"],
                     rowsperstrip=6, compression="zlib")
    # exact: integer codes, copied
    np.testing.assert_array_equal(_joined(open_photo(tmp_path / "rgba.tif"), 4), rgba[..., :3])


@pytest.mark.parametrize("kind", ["jpeg", "palette", "palette 4-bit", "grey jpeg"])
def test_pillow_photos_blocks_join_to_what_pillow_decodes(tmp_path, kind):
    codes = np.random.default_rng(5).integers(0, 255, (83, 29, 3), endpoint=True).astype(np.uint8)
    if kind == "jpeg":
        path = tmp_path / "p.jpg"
        Image.fromarray(codes).save(path, quality=90)
    elif kind == "grey jpeg":
        path = tmp_path / "g.jpg"
        Image.fromarray(codes[..., 0]).save(path, quality=90)
    elif kind == "palette":
        path = tmp_path / "p.png"
        Image.fromarray(codes).quantize(200).save(path)
    else:
        path = tmp_path / "p4.png"
        Image.fromarray(codes).quantize(16).save(path, bits=4)
    with Image.open(path) as image:
        expected = np.asarray(image.convert("RGB"))
    for rows in ROWS:
        # exact: integer codes, copied out of the same decoder's buffer
        np.testing.assert_array_equal(_joined(open_photo(path), rows), expected)


def test_what_pillow_must_hold_is_checked_against_the_budget(tmp_path, monkeypatch):
    path = tmp_path / "p.jpg"
    Image.fromarray(np.zeros((600, 600, 3), np.uint8)).save(path)
    monkeypatch.setenv("SPECTROCOLOR_MEMORY_BUDGET", "1MiB")  # 600 x 600 x 4 B = 1.37 MiB
    with pytest.raises(BudgetError, match="a JPEG is decoded whole, into 4 bytes per pixel"):
        open_photo(path)


def test_a_tiff_band_beyond_the_budget_is_one_error(tmp_path, monkeypatch):
    path = tmp_path / "one_strip.tif"
    tifffile.imwrite(path, np.zeros((700, 700, 3), np.uint8), photometric="rgb", compression="zlib",
                     rowsperstrip=700)
    monkeypatch.setenv("SPECTROCOLOR_MEMORY_BUDGET", "1MiB")  # the one strip: 1.4 MiB
    with pytest.raises(BudgetError, match="one band of strips of the TIFF is held at once"):
        open_photo(path)


@pytest.mark.parametrize("save", [np.savez, np.savez_compressed])
@pytest.mark.parametrize("fortran", [False, True])
def test_npz_members_beyond_the_budget_are_read_lazily_with_the_same_values(tmp_path, save, fortran):
    values = np.random.default_rng(11).random((300, 120, 31)).astype("<f4")  # 4.3 MiB
    if fortran:
        values = np.asfortranarray(values)
    path = tmp_path / "cube.npz"
    save(path, values=values, wavelengths_nm=WAVELENGTHS)
    if fortran and save is np.savez_compressed:  # inflating in Fortran order needs it all
        with pytest.raises(BudgetError, match="member 'values'.*memory budget of 1 MiB"):
            read_cube(path, memory_budget="1MiB")
        return
    cube = read_cube(path, memory_budget="1MiB")
    assert isinstance(cube.values, MappedArray if save is np.savez else ZipMemberArray)
    assert cube.shape == values.shape
    # exact: stored float32 values, read back, never computed
    np.testing.assert_array_equal(cube.values[40:77], values[40:77])
    # exact: the same stored values, after a read above the last one (the member rewinds)
    np.testing.assert_array_equal(cube.values[0:3], values[0:3])
    # exact: stored values, the last row
    np.testing.assert_array_equal(cube.values[299:300, 5], values[299:300, 5])
    # exact: stored values, read whole by a pickled copy
    np.testing.assert_array_equal(np.asarray(pickle.loads(pickle.dumps(cube.values))), values)
    small = read_cube(path)  # within the default budget: read whole, as before
    assert isinstance(small.values, np.ndarray)


def test_a_deflated_member_converts_block_by_block_to_the_same_image(tmp_path):
    from spectrocolor.cli import main

    values = np.random.default_rng(2).random((200, 64, 31)).astype("<f4")  # 1.5 MiB
    np.savez_compressed(tmp_path / "cube.npz", values=values, wavelengths_nm=WAVELENGTHS)
    np.save(tmp_path / "cube.npy", values)
    common = ["--illuminant", "D65", "--chunks", "16"]
    assert main(["--memory-budget", "1MiB", "image", str(tmp_path / "cube.npz"), *common,
                 "--out", str(tmp_path / "a.png")]) == 0
    assert main(["image", str(tmp_path / "cube.npy"), "--wavelengths", "400:700:10", *common,
                 "--out", str(tmp_path / "b.png")]) == 0
    with Image.open(tmp_path / "a.png") as a, Image.open(tmp_path / "b.png") as b:
        np.testing.assert_array_equal(np.asarray(a), np.asarray(b))  # exact: the same conversion of the same floats
