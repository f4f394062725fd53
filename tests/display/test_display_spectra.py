"""Seed 002 (Sällström, SPECTRA) Appendix and note 10, reproduced from its own tables."""

from __future__ import annotations

import numpy as np
import pytest

import spectrocolor as sc
from spectrocolor.display.spaces import SPECTRA_PHOSPHORS_XYZ

# seed 002, Appendix: "The matrix in matris.d is the inverted matrix" (as printed)
MATRIS_D = [
    ["+0.02994", "-0.01313", "-0.004606"],
    ["-0.01022", "+0.01836", "+0.0004061"],
    ["+0.000527", "-0.001944", "+0.009541"],
]


def _half_unit(text: str) -> float:
    decimals = len(text.split(".")[1])
    return 0.5 * 10.0**-decimals


def test_inverting_the_phosphor_table_reproduces_matris_d_to_printed_digits():
    M = sc.rgb_space("SPECTRA 7000K").matrix_from_XYZ
    for i in range(3):
        for j in range(3):
            printed = MATRIS_D[i][j]
            assert abs(M[i, j] - float(printed)) <= _half_unit(printed), (i, j, M[i, j], printed)


def test_white_point_and_chromaticities_of_the_table():
    s = sc.rgb_space("SPECTRA 7000K")
    # white-point column: 98.88, 106.83, 121.11 (sums of the rows as printed)
    np.testing.assert_allclose(s.white_XYZ, [98.88, 106.83, 121.11], atol=0.005)
    # x, y rows, printed to 3 decimals
    # exact: printed digits of a value known to ~1e-13: it moves only at a tie of the last digit
    np.testing.assert_array_equal(
        np.round(s.primaries_xy, 3), [[0.620, 0.344], [0.283, 0.608], [0.150, 0.066]]
    )
    # exact: printed digits of a value known to ~1e-13: it moves only at a tie of the last digit
    np.testing.assert_array_equal(np.round(s.white_xy, 3), [0.303, 0.327])


def _bins_cmf():
    """CIE 1931 CMFs at 400, 410, ..., 700 nm (31 bins, seed 002's cie.dat)."""
    cmf = sc.observer("1931")
    grid = np.arange(400.0, 701.0, 10.0)
    idx = np.searchsorted(cmf.wavelengths_nm, grid)
    # exact: whole-nanometre wavelengths: small integers, exact in any arithmetic
    assert np.array_equal(cmf.wavelengths_nm[idx], grid)
    return cmf.values[:, idx].T  # (31, 3)


@pytest.mark.parametrize("reading", ["per-channel k", "one k from Y"])
def test_note_10_white_R_is_1_22_and_max_R_is_1_58(reading):
    # STEP 1: X = k sum f x with k = 100 / (f_max sum x), "and likewise for Y and Z".
    # Read per channel, the equal-energy white is exactly X = Y = Z = 100; read as one k (the
    # CIE convention), Y = 100. Both readings reproduce the seed's two-digit numbers.
    cmf = _bins_cmf()
    k = 100 / cmf.sum(axis=0) if reading == "per-channel k" else 100 / cmf[:, 1].sum()
    W = cmf * k
    space = sc.rgb_space("SPECTRA 7000K")
    white_rgb = space.rgb_linear_from_XYZ(W.sum(axis=0))
    # exact: printed digits of a value known to ~1e-13: it moves only at a tie of the last digit
    assert round(float(white_rgb[0]), 2) == 1.22
    max_rgb = sc.max_object_rgb(space, W)
    # exact: printed digits of a value known to ~1e-13: it moves only at a tie of the last digit
    assert round(float(max_rgb[0]), 2) == 1.58
    assert max_rgb.argmax() == 0  # "R is the one that may reach the highest value"
    # brute force over the 2**31 ideal reflectances is what the closed form replaces; check
    # the closed form against the optimal 0/1 reflectance it names
    per_bin = W @ space.matrix_from_XYZ.T
    f = (per_bin[:, 0] > 0).astype(float)
    assert float(f @ per_bin[:, 0]) == pytest.approx(max_rgb[0], rel=1e-14)


def test_max_object_rgb_bounds_random_reflectances():
    rng = np.random.default_rng(3)
    W = _bins_cmf() * 100 / _bins_cmf()[:, 1].sum()
    space = sc.rgb_space("SPECTRA 7000K")
    top = sc.max_object_rgb(space, W)
    f = rng.random((2000, 31)) ** 0.2 * (rng.random((2000, 31)) > 0.5)
    rgb = space.rgb_linear_from_XYZ(f @ W)
    assert np.all(rgb.max(axis=0) <= top + 1e-12)


def test_gamma_2204_puts_half_excitation_at_level_46_of_63():
    table = sc.spectra_excitation_table()
    assert table.n_levels == 64
    # exact: the end levels are 0 ** g and 1 ** g: exactly 0 and 1
    assert table.levels[0] == 0.0 and table.levels[63] == 1.0
    assert int(table.index(0.5)) == 46
    assert abs(table.levels[46] - 0.5) < 1e-3


def test_matris_equ_reproduces_equal_energy_as_R_equal_G_equal_B():
    equ = sc.rgb_space("SPECTRA equal-energy")
    np.testing.assert_allclose(equ.rgb_linear_from_XYZ([100.0, 100.0, 100.0]), 1.0, atol=1e-14)
    # same phosphor chromaticities as matris.d
    np.testing.assert_allclose(
        equ.primaries_xy, sc.rgb_space("SPECTRA 7000K").primaries_xy, atol=1e-14
    )


def test_phosphor_table_is_read_only():
    with pytest.raises(ValueError):
        SPECTRA_PHOSPHORS_XYZ[0, 0] = 1.0
