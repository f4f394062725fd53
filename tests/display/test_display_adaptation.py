"""Chromatic adaptation: against colour-science 0.4.7 and SPECTRA's matris.equ."""

from __future__ import annotations

import numpy as np
import pytest

import spectrocolor as sc

WHITE_A = np.array([109.850, 100.0, 35.585])
WHITE_D65 = np.array([95.047, 100.0, 108.883])


@pytest.mark.parametrize(
    "method, transform",
    [("bradford", "Bradford"), ("von kries", "Von Kries"), ("cat02", "CAT02"), ("cat16", "CAT16"),
     ("xyz scaling", "XYZ Scaling")],
)
def test_matches_colour_science(method, transform):
    colour = pytest.importorskip("colour")
    rng = np.random.default_rng(1)
    XYZ = rng.uniform(0, 100, (20, 3))
    ours = sc.adapt(XYZ, WHITE_A, WHITE_D65, method)
    ref = colour.adaptation.chromatic_adaptation_VonKries(
        XYZ / 100, WHITE_A / 100, WHITE_D65 / 100, transform=transform
    ) * 100
    np.testing.assert_allclose(ours, ref, rtol=1e-10, atol=1e-10)


@pytest.mark.parametrize("method", ["bradford", "von kries", "cat02", "cat16"])
def test_source_white_maps_to_target_white_and_inverse(method):
    np.testing.assert_allclose(sc.adapt(WHITE_A, WHITE_A, WHITE_D65, method), WHITE_D65, atol=1e-11)
    XYZ = np.array([[30.0, 20.0, 10.0], [5.0, 6.0, 7.0]])
    back = sc.adapt(sc.adapt(XYZ, WHITE_A, WHITE_D65, method), WHITE_D65, WHITE_A, method)
    np.testing.assert_allclose(back, XYZ, atol=1e-11)


def test_display_rgb_adaptation_is_spectras_matris_equ():
    # matris.equ shows the equal-energy white as R = G = B; "adapted to the screen" is
    # a von Kries scaling in the display's own primaries
    d70 = sc.rgb_space("SPECTRA 7000K")
    equ = sc.rgb_space("SPECTRA equal-energy")
    E = np.array([100.0, 100.0, 100.0])
    rng = np.random.default_rng(2)
    XYZ = rng.uniform(0, 100, (10, 3))
    adapted = sc.adapt(XYZ, E, d70.white_XYZ, "display rgb", space=d70)
    np.testing.assert_allclose(
        d70.rgb_linear_from_XYZ(adapted), equ.rgb_linear_from_XYZ(XYZ), rtol=1e-12, atol=1e-14
    )


def test_errors():
    with pytest.raises(sc.ColorimetryError, match="needs space"):
        sc.adapt([1, 1, 1], WHITE_A, WHITE_D65, "display rgb")
    with pytest.raises(sc.ColorimetryError, match="method: 'hunt' is not a chromatic adaptation transform"):
        sc.adapt([1, 1, 1], WHITE_A, WHITE_D65, "hunt")
    with pytest.raises(sc.ColorimetryError, match="source_white_XYZ"):
        sc.adapt([1, 1, 1], [1, 0, 1], WHITE_D65)
