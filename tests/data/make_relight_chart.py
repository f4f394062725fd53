"""Writes relight_chart.png: a synthetic colour-checker "photo" for the explorer's relight tests.

The 24 ColorChecker patches (BabelColor spectra shipped with spectrocolor) under D65, CIE 1931,
rendered to 8-bit sRGB (clipped), 6 x 4 patches of 36 x 36 px on a 4-px dark-grey (code 60)
frame; 244 x 164 px. Patch 19 (row 4, column 1) is the white, 22 the middle grey.
Run: python tests/data/make_relight_chart.py
"""

from pathlib import Path

import numpy as np
from PIL import Image

import spectrocolor as sc
from spectrocolor.io import read_spectra

PATCH, GAP = 36, 4


def chart_codes() -> np.ndarray:
    checker = read_spectra(Path(sc.__file__).parent / "data" / "reflectances_colorchecker_babel.csv")
    XYZ = sc.tristimulus(checker, observer="1931", illuminant="D65")
    codes = sc.render(XYZ, "sRGB", gamut="clip", bit_depth=8).codes.reshape(4, 6, 3)
    image = np.full((4 * (PATCH + GAP) + GAP, 6 * (PATCH + GAP) + GAP, 3), 60, np.uint8)
    for row in range(4):
        for col in range(6):
            y, x = GAP + row * (PATCH + GAP), GAP + col * (PATCH + GAP)
            image[y:y + PATCH, x:x + PATCH] = codes[row, col]
    return image


if __name__ == "__main__":
    out = Path(__file__).with_name("relight_chart.png")
    Image.fromarray(chart_codes(), "RGB").save(out, "PNG")
    print(f"wrote {out}")
