"""The default distributions of SPECTRA's five settings, as data.

Source: P. Sällström, *A Computer Program for Visualising the Relation between Colour and
Spectral Energy Distribution*, USIP Report 99-05, section "A short description of the
computer program SPECTRA" (seed 002): the named defaults of setting 1 (keys 1-8, including the
sunset formula), setting 2 (left and right boxes, keys 1-8), setting 3 (keys 1-6),
setting 4 (illuminants on keys 1-4, metameric samples on keys 5-8) and setting 5 (keys 1-8).

The seed names and describes each default but prints no numbers except the sunset formula,
so the levels below were written for this program to have the described shape on SPECTRA's
grid: 31 bins, 400-700 nm at 10 nm, integer levels 0-30 (30 = the full spectrum, or 100 %
reflectance/transmittance). The metameric pairs were found by an integer search that
minimises CIEDE2000 under the stated illuminant (CIE 1931 observer, summation at the 31
samples); ``tests/test_app_api.py`` checks every property claimed here with the library.
CIE D65 and A are not data here: they are the CIE tables, evaluated on the requested grid by
:func:`spectrocolor.illuminant` and scaled to a peak of 30.
"""

from __future__ import annotations

import numpy as np

FULL_LEVEL = 30
START_NM, STOP_NM, STEP_NM = 400.0, 700.0, 10.0
SUNSET_D = (0.0, 0.15, 0.30, 0.60, 1.0, 1.5, 3.0)  # seed 002, setting 1, key 8


def _c(level: int) -> list[int]:
    return [level] * 31


# --- setting 1 (and the shapes reused below) -----------------------------------------
STRAW = [10, 11, 11, 12, 12, 13, 13, 14, 14, 15, 15, 16, 16, 17, 17, 18,
         19, 19, 20, 20, 21, 21, 22, 22, 23, 23, 24, 24, 25, 25, 26]
LIGHT_BLUE = [26, 26, 25, 25, 24, 24, 23, 23, 22, 22, 21, 21, 20, 20, 19, 19,
              19, 18, 18, 17, 17, 16, 16, 15, 15, 14, 14, 13, 13, 12, 12]
GREY = _c(15)
GREEN = [8, 8, 8, 9, 9, 10, 12, 13, 16, 19, 21, 24, 25, 26, 25, 24,
         21, 19, 16, 13, 12, 10, 9, 9, 8, 8, 8, 8, 8, 8, 8]
MAGENTA = [26, 26, 25, 25, 24, 23, 22, 21, 19, 16, 14, 12, 9, 8, 6, 6,
           6, 8, 9, 12, 14, 16, 19, 21, 22, 23, 24, 25, 25, 26, 26]
YELLOW = [1, 1, 1, 1, 1, 6, 10, 14, 19, 24, 28, 28, 28, 28, 28, 28,
          28, 28, 28, 28, 28, 28, 28, 28, 28, 28, 28, 28, 28, 28, 28]
BLUE = [23, 27, 28, 27, 23, 19, 14, 10, 6, 4, 3, 2, 2, 2, 2, 2,
        2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2]

# --- setting 2 ----------------------------------------------------------------------
# Grey metameric (as a light) with the constant 15: wavy and spiky versions.
GREY_WAVY = [15, 16, 18, 17, 17, 16, 14, 13, 12, 11, 10, 10, 11, 13, 15, 17,
             18, 19, 19, 18, 16, 14, 12, 10, 8, 7, 6, 8, 9, 11, 14]
GREY_SPIKY = [5, 1, 0, 3, 26, 26, 27, 6, 4, 7, 8, 9, 8, 8, 30, 30,
              30, 4, 0, 0, 24, 25, 24, 25, 1, 3, 0, 0, 0, 0, 0]
# A blue built from a few bands, metameric (as a light) with BLUE.
BLUE_BANDS = [16, 13, 30, 30, 13, 12, 13, 30, 15, 0, 0, 0, 0, 0, 0, 0,
              15, 0, 0, 0, 0, 0, 2, 2, 6, 6, 7, 10, 8, 9, 4]
# "Three-band" light: narrow bands near 450, 540-550 and 610 nm (seed note 13: the red band
# at or near 610 nm), with the same chromaticity as D65 on this grid.
THREE_BAND = [0, 0, 1, 2, 16, 30, 16, 3, 1, 1, 2, 1, 1, 9, 30, 30,
              9, 1, 2, 1, 13, 23, 13, 1, 1, 1, 1, 0, 0, 0, 0]

# --- setting 3: complementary pairs ---------------------------------------------------
ORANGE_YELLOW = [1, 1, 1, 1, 1, 1, 1, 2, 4, 8, 13, 18, 22, 25, 27, 28,
                 28, 28, 28, 28, 28, 28, 28, 28, 28, 28, 28, 28, 28, 28, 28]


def _ideal(inside: int, outside: int, start_nm: float, stop_nm: float) -> list[int]:
    wl = np.arange(START_NM, STOP_NM + 1, STEP_NM)
    return [inside if start_nm <= w <= stop_nm else outside for w in wl]


def _smooth_yellow() -> list[int]:
    wl = np.arange(START_NM, STOP_NM + 1, STEP_NM)
    return [int(v) for v in np.round(FULL_LEVEL / (1 + np.exp(-(wl - 500) / 25)))]


# --- setting 4: reflectances metameric under D65 (grey, yellow, green, blue) -----------
S4_GREY = (_c(15), [14, 21, 25, 26, 24, 19, 12, 6, 2, 2, 2, 5, 11, 16, 21, 24,
                    23, 21, 17, 11, 8, 7, 8, 12, 17, 22, 25, 27, 25, 20, 14])
S4_YELLOW = ([3, 3, 3, 3, 3, 3, 7, 11, 15, 19, 23, 27, 27, 27, 27, 27,
              27, 27, 27, 27, 27, 27, 27, 27, 27, 27, 27, 27, 27, 27, 27],
             [10, 14, 12, 13, 8, 5, 3, 4, 6, 12, 14, 21, 23, 28, 30, 30,
              30, 30, 30, 30, 30, 25, 21, 18, 17, 16, 20, 24, 29, 30, 30])
S4_GREEN = ([4, 4, 4, 4, 5, 6, 7, 9, 11, 15, 18, 21, 23, 24, 23, 21,
             18, 15, 11, 9, 7, 6, 5, 4, 4, 4, 4, 4, 4, 4, 4],
            [1, 0, 0, 0, 0, 0, 7, 15, 22, 27, 28, 29, 29, 26, 20, 15,
             10, 6, 8, 9, 10, 13, 12, 13, 10, 2, 0, 0, 0, 0, 0])
S4_BLUE = ([10, 14, 17, 20, 22, 23, 22, 20, 17, 14, 10, 8, 6, 5, 4, 3,
            3, 3, 3, 3, 3, 3, 3, 3, 3, 3, 3, 3, 3, 3, 3],
           [0, 11, 17, 23, 26, 26, 23, 19, 9, 4, 0, 2, 3, 6, 10, 8,
            8, 5, 2, 0, 0, 0, 0, 0, 3, 7, 10, 12, 6, 0, 3])

# --- setting 5: filters ---------------------------------------------------------------
TURQUOISE = [3, 3, 5, 9, 15, 21, 25, 27, 27, 27, 27, 27, 25, 21, 15, 9,
             5, 3, 3, 3, 3, 3, 3, 3, 3, 3, 3, 3, 3, 3, 3]
ORANGE = [3, 3, 3, 3, 3, 3, 3, 3, 3, 3, 3, 3, 3, 4, 4, 6,
          9, 13, 18, 22, 25, 27, 27, 28, 28, 28, 28, 28, 28, 28, 28]
# Dichroic "moss green": a low green pass band and a high deep-red window. One filter looks
# green; two in series leave mostly the red window (seed 002, setting 5, default 7).
MOSS_GREEN = [0, 0, 0, 0, 0, 1, 2, 4, 6, 9, 10, 9, 6, 4, 2, 1,
              0, 0, 0, 0, 0, 0, 0, 1, 5, 15, 24, 28, 29, 29, 29]


def sunset(d: float, wavelengths_nm: np.ndarray) -> np.ndarray:
    """SPECTRA's sunset, f(λ) = 30·exp(−[(700/λ)⁴ − 1]·d) (seed 002, setting 1, key 8)."""
    wl = np.asarray(wavelengths_nm, dtype=float)
    return FULL_LEVEL * np.exp(-((700.0 / wl) ** 4 - 1.0) * d)


# Each preset: (key, name, values) where values is a list of 31 levels, or one of the
# named generated distributions "D65", "A", "E", "sunset".
SETTING1 = [
    ("1", "straw", STRAW),
    ("2", "light blue", LIGHT_BLUE),
    ("3", "grey", GREY),
    ("4", "green", GREEN),
    ("5", "magenta", MAGENTA),
    ("6", "yellow", YELLOW),
    ("7", "blue", BLUE),
    ("8", "sunset", "sunset"),
]
SETTING2_LEFT = [
    ("1", "straw", STRAW),
    ("2", "light blue", LIGHT_BLUE),
    ("3", "neutral", GREY),
    ("4", "green", GREEN),
    ("5", "blue", BLUE),
    ("6", "grey", GREY_WAVY),
    ("7", "D65", "D65"),
    ("8", "variable level", "level"),
]
SETTING2_RIGHT = [
    ("1", "yellow", YELLOW),
    ("2", "blue", BLUE),
    ("3", "neutral", _c(10)),
    ("4", "magenta", MAGENTA),
    ("5", "blue", BLUE_BANDS),
    ("6", "grey", GREY_SPIKY),
    ("7", "three-band", THREE_BAND),
    ("8", "variable level", "level"),
]
# Setting 3: (key, name, left, right). What is taken from one side is added to the other,
# so left + right is conserved; it is the full constant spectrum in defaults 3-6.
SETTING3 = [
    ("1", "yellow / very dark neutral", YELLOW, _c(2)),
    ("2", "orange-yellow / dark neutral", ORANGE_YELLOW, _c(2)),
    ("3", "yellow / blue", _smooth_yellow(), [FULL_LEVEL - v for v in _smooth_yellow()]),
    ("4", "ideal yellow / ideal blue", _ideal(30, 0, 500, 700), _ideal(0, 30, 500, 700)),
    ("5", "ideal magenta / ideal green, with neutral",
     _ideal(5, 25, 500, 570), _ideal(25, 5, 500, 570)),
    ("6", "full spectrum / darkness", _c(30), _c(0)),
]
SETTING4_ILLUMINANTS = [
    ("1", "E", "E"),
    ("2", "D65", "D65"),
    ("3", "T65 three-band", THREE_BAND),
    ("4", "A", "A"),
]
SETTING4_SAMPLES = [
    ("5", "metameric grey", *S4_GREY),
    ("6", "metameric yellow", *S4_YELLOW),
    ("7", "metameric green", *S4_GREEN),
    ("8", "metameric blue", *S4_BLUE),
]
SETTING5 = [
    ("1", "straw and light blue: a faint green", STRAW, LIGHT_BLUE),
    ("2", "yellow and turquoise: green", YELLOW, TURQUOISE),
    ("3", "yellow and blue: dark green", YELLOW, BLUE),
    ("4", "yellow and magenta: red", YELLOW, MAGENTA),
    ("5", "green and magenta: grey", GREEN, MAGENTA),
    ("6", "two orange filters: a deeper, redder orange", ORANGE, ORANGE),
    ("7", "two moss-green filters: a dark red (dichroism)", MOSS_GREEN, MOSS_GREEN),
    ("8", "two medium grey filters: a darker grey", GREY, GREY),
]
