"""The default distributions of SPECTRA's five settings, as data.

Source: P. Sällström, *A Computer Program for Visualising the Relation between Colour and
Spectral Energy Distribution*, USIP Report 99-05, section "A short description of the
computer program SPECTRA" (seed 002): the named defaults of setting 1 (keys 1-8, including the
sunset formula), setting 2 (left and right boxes, keys 1-8), setting 3 (keys 1-6),
setting 4 (illuminants on keys 1-4, metameric samples on keys 5-8) and setting 5 (keys 1-8).

The seed names and describes each default but prints no numbers except the sunset formula,
so the levels below were written for this program to have the described shape on SPECTRA's
grid: 31 bins, 400-700 nm at 10 nm, integer levels 0-30 (30 = the full spectrum, or 100 %
reflectance/transmittance). Where a hand-drawn shape did not show what the seed's words
promise on the default display (sRGB and SPECTRA's monitor, E adapted to the display's white,
normalisation A), the levels were retuned by the integer search in ``tools/tune_presets.py``
(objectives and every difference from the seed's words: ``docs/app.md``, "Presets"); the
metameric pairs minimise CIEDE2000 under the stated illuminant (CIE 1931 observer, summation
at the 31 samples). ``tests/app/test_app_demonstrations.py`` and ``tests/app/test_app_api.py`` check
every property claimed here through the app's compute path. CIE D65 and A are not data here:
they are the CIE tables, evaluated on the requested grid by :func:`spectrocolor.illuminant`,
scaled to a peak of 30 and rounded to whole levels (SPECTRA's model has no fractions).
"""

from __future__ import annotations

import numpy as np

FULL_LEVEL = 30
START_NM, STOP_NM, STEP_NM = 400.0, 700.0, 10.0
SUNSET_D = (0.0, 0.15, 0.30, 0.60, 1.0, 1.5, 3.0)  # seed 002, setting 1, key 8


def _c(level: int) -> list[int]:
    return [level] * 31


# --- setting 1 (and the shapes reused below) -----------------------------------------
STRAW = [3, 6, 9, 12, 13, 14, 15, 15, 16, 17, 18, 19, 19, 19, 19, 19,
         19, 19, 19, 19, 20, 21, 22, 23, 23, 23, 23, 23, 24, 25, 26]
LIGHT_BLUE = [28, 27, 26, 26, 26, 26, 25, 24, 23, 22, 21, 20, 20, 20, 20, 20,
              20, 19, 18, 17, 16, 15, 15, 15, 15, 15, 15, 14, 13, 12, 11]
GREY = _c(15)
GREEN = [8, 8, 8, 9, 9, 10, 12, 13, 16, 19, 21, 24, 25, 26, 25, 24,
         21, 19, 16, 13, 12, 10, 9, 9, 8, 8, 8, 8, 8, 8, 8]
# round(30 · 7 / GREEN): a magenta that, as a filter after GREEN, leaves a flat (grey) light
MAGENTA = [26, 26, 26, 23, 23, 21, 18, 16, 13, 11, 10, 9, 8, 8, 8, 9,
           10, 11, 13, 16, 18, 21, 23, 23, 26, 26, 26, 26, 26, 26, 26]
YELLOW = [1, 1, 1, 1, 1, 6, 10, 14, 19, 24, 28, 28, 28, 28, 28, 28,
          28, 28, 28, 28, 28, 28, 28, 28, 28, 28, 28, 28, 28, 28, 28]
BLUE = [23, 27, 28, 27, 23, 19, 14, 10, 6, 4, 3, 2, 2, 2, 2, 2,
        2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2]

# --- setting 2 ----------------------------------------------------------------------
# The intense blue of the right box, key 2: light blue's hue (λd 470 vs 480 nm), much more
# chroma, displayable on sRGB and SPECTRA's monitor (setting 1's blue is violet, λd 453).
DEEP_BLUE = [28, 28, 28, 28, 28, 28, 28, 27, 24, 20, 15, 10, 7, 5, 4, 3,
             3, 3, 3, 3, 3, 3, 3, 3, 3, 3, 3, 3, 3, 3, 3]
# Grey metameric (as a light) with the constant 15: wavy and spiky versions.
GREY_WAVY = [15, 16, 18, 17, 17, 16, 14, 13, 12, 11, 10, 10, 11, 13, 15, 17,
             18, 19, 19, 18, 16, 14, 12, 10, 8, 7, 6, 8, 9, 11, 14]
GREY_SPIKY = [5, 1, 0, 3, 26, 26, 27, 6, 4, 7, 8, 9, 8, 8, 30, 30,
              30, 4, 0, 0, 24, 25, 24, 25, 1, 3, 0, 0, 0, 0, 0]
# A blue built from a few bands, metameric (as a light) with BLUE.
BLUE_BANDS = [16, 13, 30, 30, 13, 12, 13, 30, 15, 0, 0, 0, 0, 0, 0, 0,
              15, 0, 0, 0, 0, 0, 2, 2, 6, 6, 7, 10, 8, 9, 4]
# "Three-band" light: narrow bands near 450, 540-550 and 610 nm (seed note 13: the red band
# at or near 610 nm), with the chromaticity of D65 (rounded to integer levels) on this grid.
THREE_BAND = [0, 0, 2, 2, 16, 30, 16, 3, 1, 1, 2, 1, 1, 9, 30, 30,
              9, 1, 2, 1, 13, 23, 13, 1, 1, 0, 2, 0, 0, 0, 0]

# --- setting 3: complementary pairs ---------------------------------------------------
# Setting 3, default 2 (Fig. 12): a dark neutral (level 2) plus a block around 575 nm. Moving
# FIG12_MOVES to the right (580 and 570 nm fully, 590 and 560 nm partly: (bin, new left
# level)) leaves two metameric yellows (CIEDE2000 0.06), one with no light at 570-580 nm.
# Found by an exhaustive integer search (docs/app.md, "Presets").
ORANGE_YELLOW = [2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 2, 20,
                 26, 27, 27, 30, 22, 11, 2, 2, 2, 2, 2, 2, 2, 2, 2]
FIG12_MOVES = ((18, 0), (17, 0), (19, 16), (16, 23))


def _ideal(inside: int, outside: int, start_nm: float, stop_nm: float) -> list[int]:
    wl = np.arange(START_NM, STOP_NM + 1, STEP_NM)
    return [inside if start_nm <= w <= stop_nm else outside for w in wl]


def _smooth_yellow() -> list[int]:
    """A logistic step from 3 to 27 around 500 nm (40 nm wide): it and its complement are
    both displayable on sRGB and on SPECTRA's monitor."""
    wl = np.arange(START_NM, STOP_NM + 1, STEP_NM)
    return [int(v) for v in np.round(3 + 24 / (1 + np.exp(-(wl - 500) / 40)))]


# --- setting 4: reflectances metameric under D65 (grey, yellow, green, blue) -----------
S4_GREY = (_c(15), [14, 21, 25, 26, 24, 19, 12, 6, 2, 2, 2, 5, 11, 16, 21, 24,
                    23, 21, 17, 11, 8, 7, 8, 12, 17, 22, 25, 27, 25, 20, 14])
S4_YELLOW = ([30, 24, 18, 12, 6, 3, 7, 11, 13, 15, 17, 20, 24, 27, 27, 27,
              27, 27, 27, 27, 27, 27, 27, 27, 27, 27, 27, 27, 27, 27, 27],
             [30, 30, 27, 17, 8, 6, 6, 6, 7, 10, 11, 11, 24, 27, 30, 29,
              30, 28, 30, 30, 30, 27, 23, 19, 15, 18, 20, 22, 24, 26, 28])
S4_GREEN = ([1, 2, 3, 4, 5, 6, 7, 5, 4, 4, 10, 16, 22, 21, 20, 19,
             18, 14, 10, 9, 8, 7, 4, 1, 2, 3, 4, 4, 4, 4, 4],
            [0, 0, 0, 0, 0, 0, 5, 11, 16, 18, 20, 24, 28, 23, 18, 13,
             8, 6, 7, 8, 10, 12, 13, 13, 8, 3, 1, 0, 0, 0, 0])
S4_BLUE = ([11, 14, 17, 20, 22, 23, 23, 23, 19, 14, 10, 8, 6, 5, 4, 3,
            3, 4, 3, 3, 3, 3, 3, 3, 3, 3, 3, 3, 3, 3, 3],
           [9, 14, 19, 24, 29, 28, 22, 16, 11, 6, 0, 2, 3, 5, 8, 11,
            9, 5, 2, 1, 2, 0, 0, 0, 0, 1, 5, 9, 7, 4, 1])

# --- setting 5: filters ---------------------------------------------------------------
TURQUOISE = [2, 4, 6, 9, 15, 21, 25, 27, 27, 27, 27, 27, 25, 21, 15, 9,
             5, 3, 3, 3, 3, 3, 3, 3, 3, 3, 3, 3, 3, 3, 3]
ORANGE = [3, 3, 3, 3, 3, 3, 3, 3, 3, 3, 3, 3, 3, 4, 4, 6,
          9, 13, 18, 22, 25, 27, 27, 28, 28, 28, 28, 28, 28, 28, 28]
# Setting 5, keys 2-4 (found by tools/tune_presets.py s5-yellow, see docs/app.md): a yellow
# filter with a sharper edge near 490 nm than setting 1's yellow, a blue filter that passes
# the blue and part of the green (seed 002: "what shape of distributions will give the best
# green"), and a magenta filter with a deep notch over 470-570 nm, so that the products are a
# green, a dark green and a red.
YELLOW_FILTER = [1, 1, 1, 1, 1, 1, 1, 3, 8, 17, 25, 28, 28, 28, 28, 28,
                 28, 28, 28, 28, 28, 28, 28, 28, 28, 28, 28, 28, 28, 28, 28]
BLUE_FILTER = [30, 30, 30, 30, 29, 27, 25, 23, 21, 18, 15, 15, 15, 14, 11, 8,
               5, 2, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0]
MAGENTA_FILTER = [28, 28, 28, 28, 22, 15, 8, 2, 0, 0, 0, 0, 0, 0, 0, 0,
                  0, 2, 7, 13, 19, 25, 28, 28, 28, 28, 28, 28, 28, 28, 28]
# Dichroic "moss green": a low green pass band and a high deep-red window. One filter looks
# green; two in series leave mostly the red window (seed 002, setting 5, default 7).
MOSS_GREEN = [0, 0, 0, 0, 0, 0, 1, 3, 5, 7, 6, 6, 6, 4, 2, 1,
              0, 0, 0, 0, 0, 0, 0, 1, 5, 14, 23, 28, 29, 29, 29]


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
    ("2", "blue", DEEP_BLUE),
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
     _ideal(7, 23, 500, 570), _ideal(23, 7, 500, 570)),
    ("6", "full spectrum / darkness", _c(30), _c(0)),
]
#: The seed's suggested edits per setting-3 default: (bin index, new level of the left).
SETTING3_MOVES = {"1": ((18, 0), (17, 0)), "2": FIG12_MOVES}
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
    ("2", "yellow and turquoise: green", YELLOW_FILTER, TURQUOISE),
    ("3", "yellow and blue: dark green", YELLOW_FILTER, BLUE_FILTER),
    ("4", "yellow and magenta: red", YELLOW_FILTER, MAGENTA_FILTER),
    ("5", "green and magenta: grey", GREEN, MAGENTA),
    ("6", "two orange filters: a deeper, redder orange", ORANGE, ORANGE),
    ("7", "two moss-green filters: a dark red (dichroism)", MOSS_GREEN, MOSS_GREEN),
    ("8", "two medium grey filters: a darker grey", GREY, GREY),
]


# --- setting 5, two spotlights (issue 28 item 7) ---------------------------------------
# Seed 002, "Serial and parallel composition": two filters, each in front of its own spotlight,
# the beams on one spot: an additive mixture ("an orange-red and a green filter will give yellow
# illumination"); and "Complementarity": filters r and 1 - r in two identical spotlights give
# the colourless light of one spotlight without a filter. The seed prints no levels: these
# bands (a low floor so that each light stays near the sRGB gamut) were written for this program.
def _band(start_nm: float, stop_nm: float, floor: int) -> list[int]:
    """Full (30) from ``start_nm`` to ``stop_nm``, half-way in the bins just outside, ``floor``
    elsewhere (SPECTRA's 10 nm grid)."""
    wl = np.arange(START_NM, STOP_NM + 1, STEP_NM)
    inside = (wl >= start_nm) & (wl <= stop_nm)
    edge = (wl == start_nm - STEP_NM) | (wl == stop_nm + STEP_NM)
    return [FULL_LEVEL if i else 15 if e else floor for i, e in zip(inside, edge, strict=True)]


SPOT_RED = _band(600, 700, 3)
SPOT_GREEN = _band(500, 570, 8)
SPOT_BLUE = _band(400, 470, 4)
#: Setting 5 as two spotlights: (key, name, light 1's filter, light 2's filter).
SETTING5_ADDITIVE = [
    ("1", "orange-red and green: yellow", SPOT_RED, SPOT_GREEN),
    ("2", "green and blue: cyan", SPOT_GREEN, SPOT_BLUE),
    ("3", "red and blue: magenta, a purple", SPOT_RED, SPOT_BLUE),
    ("4", "red and cyan (green + blue): white, the three primaries", SPOT_RED,
     [FULL_LEVEL - v for v in SPOT_RED]),
    ("5", "yellow and blue, complementary: white", _smooth_yellow(),
     [FULL_LEVEL - v for v in _smooth_yellow()]),
    ("6", "green and magenta: nearly white", GREEN, MAGENTA),
    ("7", "yellow and blue filters (in series: dark green): a pale grey-green", YELLOW_FILTER, BLUE_FILTER),
    ("8", "two orange lights: the same colour, twice as bright", ORANGE, ORANGE),
]
