"""Swatches, strips, PPM/PNG files and the wavelength tint palette, checked pixel by pixel."""

from __future__ import annotations

import colorsys

import numpy as np
import pytest

import spectrocolor as sc
from spectrocolor.errors import SpectrumError
from spectrocolor.pictures import save_image, strip_image, swatch_image


def test_swatch_pixels_and_layout():
    colours = np.array([[255, 0, 0], [0, 128, 0], [1, 2, 3]])
    img = swatch_image(colours, size=10, columns=2, gap=2, background=(9, 9, 9))
    assert img.shape == (2 + 2 * 12, 2 + 2 * 12, 3)
    assert img[2, 2].tolist() == [255, 0, 0] and img[11, 11].tolist() == [255, 0, 0]
    assert img[2, 14].tolist() == [0, 128, 0]
    assert img[14, 2].tolist() == [1, 2, 3]
    assert img[0, 0].tolist() == [9, 9, 9] and img[14, 14].tolist() == [9, 9, 9]  # empty cell


def test_crossed_swatches_carry_a_diagonal_in_the_background_colour():
    img = swatch_image([[200, 100, 50]], size=8, gap=0, background=(0, 0, 0), crossed=[True])
    assert img[3, 3].tolist() == [0, 0, 0] and img[0, 7].tolist() == [0, 0, 0]
    assert img[0, 3].tolist() == [200, 100, 50]


def test_strip_with_ticks_as_in_seed_000():
    n = 1000
    colours = np.tile([[10, 20, 30]], (n, 1))
    ticks = np.arange(99, n, 100)  # Zawischa: every 100th column (500 nm of path difference)
    img = strip_image(colours, height=80, ticks=ticks, tick_height=10)
    assert img.shape == (80, n, 3)
    assert (img[:70] == [10, 20, 30]).all()
    band = img[70:, :, 0]
    expected = np.zeros(n, bool)
    for t in ticks:
        expected[max(t - 1, 0) : t + 2] = True
    assert (band[:, expected] == 255).all() and (band[:, ~expected] == 0).all()


def test_ppm_p6_bytes(tmp_path):
    img = np.arange(2 * 3 * 3, dtype=np.uint8).reshape(2, 3, 3)
    path = save_image(img, tmp_path / "a.ppm")
    data = path.read_bytes()
    header = b"P6\n3 2\n255\n"
    assert data.startswith(header)
    assert data[len(header) :] == bytes(range(18))


def test_png_round_trip(tmp_path):
    Image = pytest.importorskip("PIL.Image")
    img = swatch_image([[12, 34, 56], [200, 0, 255]], size=5)
    sc.write_swatches([[12, 34, 56], [200, 0, 255]], tmp_path / "s.png", size=5)
    back = np.asarray(Image.open(tmp_path / "s.png").convert("RGB"))
    np.testing.assert_array_equal(back, img)  # exact: integer codes through an encoder and a decoder: no floating point


def test_wavelength_tint_anchors_at_unique_hues():
    tint = sc.wavelength_tint([470, 500, 540, 580, 600, 650])
    hues = [colorsys.rgb_to_hsv(*(c / 255))[0] * 360 for c in tint]
    assert hues[0] == pytest.approx(240, abs=1)  # unique blue
    assert hues[1] == pytest.approx(180, abs=1)  # as blue as green
    assert hues[2] == pytest.approx(120, abs=1)  # green
    assert hues[3] == pytest.approx(60, abs=1)  # unique yellow
    assert hues[4] == pytest.approx(30, abs=1)  # orange: as yellow as red
    assert hues[5] == pytest.approx(0, abs=1)  # red
    brightness = sc.wavelength_tint(np.arange(400, 701, 5)).max(axis=1)
    assert np.arange(400, 701, 5)[brightness.argmax()] in range(540, 571)
    assert sc.wavelength_tint(np.zeros((2, 4)) + 555).shape == (2, 4, 3)


def test_errors(tmp_path):
    with pytest.raises(sc.SpectrumError, match="360-830"):
        sc.wavelength_tint([300])
    with pytest.raises(sc.ColorimetryError, match="0-255"):
        swatch_image([[0, 0, 300]])
    with pytest.raises(sc.ColorimetryError, match=".png or .ppm"):
        save_image(np.zeros((1, 1, 3), np.uint8), tmp_path / "a.jpg")
    with pytest.raises(sc.ColorimetryError, match="column indices"):
        strip_image([[0, 0, 0]], ticks=[5])


def test_wavelength_tint_rejects_text():
    with pytest.raises(SpectrumError, match="wavelengths_nm"):
        sc.wavelength_tint("a")
