"""Every inverse pair of the colour trunk, through one harness (tests/support/round_trip.py).

Gold values and their sources:
- IEC 61966-2-1:1999 (sRGB): D65 white x = 0.3127, y = 0.3290; the printed RGB → XYZ matrix
  (4 decimals: red column 0.4124, 0.2126, 0.0193); the transfer breakpoints 0.0031308 ↔ 0.04045.
- CIE 015:2018 Table 5 (printed to 4 decimals in CIE 015 §7.3 examples): D65 (1931) u' = 0.1978,
  v' = 0.4683, and the 1960 UCS v = 2v'/3 = 0.3122.
- CIE 015:2018 §8.2.1: the reference white has L* = 100, a* = b* = 0; an 18 % grey (Y/Yn = 0.18)
  has L* = 49.496 (116·0.18^(1/3) − 16, printed to 3 decimals in textbooks).
"""

from __future__ import annotations

import numpy as np
import pytest

import spectrocolor as sc
from round_trip import check_round_trip
from spectrocolor.display.transfer import from_codes, to_codes, transfer

D65_XYZ100 = np.array([95.047, 100.0, 108.883])


def positive_XYZ(rng, n):
    return rng.uniform(0.5, 100.0, size=(n, 3))


def chromaticities(rng, n):
    xy = rng.uniform(0.05, 0.6, size=(n, 2))
    return xy[xy.sum(axis=1) < 0.95]


def test_xyY_and_XYZ():
    check_round_trip(
        sc.xyY, sc.XYZ_from_xyY,
        gold=[([95.05, 100.0, 108.90], [0.3127, 0.3290, 100.0])],  # IEC 61966-2-1's D65, 4 decimals
        sample=positive_XYZ, gold_tol=1e-4, internal_tol=1e-12,
    )


def test_uv_1976_and_xy():
    check_round_trip(
        lambda xy: sc.uv_1976(xy=xy), sc.xy_from_uv_1976,
        gold=[([0.3127, 0.3290], [0.1978, 0.4683])],
        sample=chromaticities, gold_tol=6e-5, internal_tol=1e-12,
    )


def test_uv_1960_and_xy():
    check_round_trip(
        lambda xy: sc.uv_1960(xy=xy), sc.xy_from_uv_1960,
        gold=[([0.3127, 0.3290], [0.1978, 0.3122])],
        sample=chromaticities, gold_tol=6e-5, internal_tol=1e-12,
    )


def test_lab_and_XYZ():
    check_round_trip(
        lambda XYZ: sc.lab(XYZ, D65_XYZ100), lambda lab: sc.XYZ_from_lab(lab, D65_XYZ100),
        gold=[(D65_XYZ100.tolist(), [100.0, 0.0, 0.0]), ((0.18 * D65_XYZ100).tolist(), [49.496, 0.0, 0.0])],
        sample=lambda rng, n: rng.uniform(0.01, 1.0, size=(n, 3)) * D65_XYZ100,
        gold_tol=5e-4, internal_tol=1e-11,
    )


def test_lch_and_lab():
    check_round_trip(
        sc.lch, sc.lab_from_lch,
        gold=[([50.0, 0.0, 10.0], [50.0, 10.0, 90.0]), ([60.0, -3.0, -4.0], [60.0, 5.0, 233.13010235415598])],
        sample=lambda rng, n: rng.uniform([0, -100, -100], [100, 100, 100], size=(n, 3)),
        gold_tol=1e-12, internal_tol=1e-12,
    )


@pytest.mark.parametrize("name", sc.rgb_space_names())
def test_rgb_linear_and_XYZ(name):
    space = sc.rgb_space(name)
    gold = [(space.white_XYZ.tolist(), [1.0, 1.0, 1.0])]
    if name == "sRGB":
        gold.append(([41.24, 21.26, 1.93], [1.0, 0.0, 0.0]))  # IEC 61966-2-1's printed red column × 100
    check_round_trip(
        space.rgb_linear_from_XYZ, space.XYZ_from_rgb_linear, gold=gold,
        sample=lambda rng, n: rng.uniform(-0.2, 1.2, size=(n, 3)),
        # half a unit of the printed 4th decimal, on the XYZ100 scale
        gold_tol=5e-3 if name == "sRGB" else 1e-12, internal_tol=1e-12,
    )


@pytest.mark.parametrize("name", [n for n in sc.transfer_names() if n != "spectra c.dat"])
def test_transfer_encode_and_decode(name):
    curve = transfer(name)
    gold = [([0.0, 0.0, 0.0], [0.0, 0.0, 0.0]), ([1.0, 1.0, 1.0], [1.0, 1.0, 1.0])]
    if name == "srgb":
        gold.append(([0.0031308, 0.0031308, 0.0031308], [0.04045, 0.04045, 0.04045]))  # IEC breakpoint
    check_round_trip(
        curve.encode, curve.decode, gold=gold,
        sample=lambda rng, n: rng.uniform(0.0, 1.0, size=(n, 3)),
        gold_tol=1e-6, internal_tol=1e-12,
    )


@pytest.mark.parametrize("bit_depth", [8, 10, 12, 16])
def test_codes(bit_depth):
    top = 2**bit_depth - 1
    check_round_trip(
        lambda encoded: to_codes(encoded, bit_depth), lambda codes: from_codes(codes, bit_depth),
        gold=[([0.0, 0.5 * top / top, 1.0], [0, round(0.5 * top), top])],
        sample=lambda rng, n: rng.integers(0, top + 1, size=(n, 3)) / top,
        gold_tol=0.5 / top + 1e-12, internal_tol=1e-12,
    )


@pytest.mark.parametrize("method", [m for m in sc.display.adaptation.ADAPTATION_METHODS if m != "display rgb"])
def test_adapt_and_its_inverse(method):
    white_A = sc.white_point("A")
    check_round_trip(
        lambda XYZ: sc.adapt(XYZ, white_A, D65_XYZ100, method=method),
        lambda XYZ: sc.adapt(XYZ, D65_XYZ100, white_A, method=method),
        gold=[(white_A.tolist(), D65_XYZ100.tolist())],
        sample=positive_XYZ, gold_tol=1e-10, internal_tol=1e-12,
    )
