"""Transfer functions and integer codes: IEC 61966-2-1, BT.2020, power laws, level tables."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from spectrocolor import ColorimetryError, from_codes, spectra_excitation_table, to_codes
from spectrocolor.display.transfer import (
    BT2020Curve,
    LevelTable,
    PowerLaw,
    SRGBCurve,
    transfer,
    transfer_names,
)

X = np.concatenate([np.linspace(0, 0.01, 101), np.linspace(0.01, 1, 991)])


def test_srgb_matches_the_iec_formula_written_here():
    v = np.where(X <= 0.0031308, 12.92 * X, 1.055 * X ** (1 / 2.4) - 0.055)
    np.testing.assert_allclose(SRGBCurve().encode(X), v, rtol=0, atol=1e-15)
    np.testing.assert_allclose(SRGBCurve().decode(v), X, atol=1e-14)
    assert SRGBCurve().encode(0.0031308) == pytest.approx(0.04045, abs=2e-6)


def test_seed_000_threshold_0_00304_differs_by_1e_5_at_the_break():
    old = SRGBCurve(threshold=0.00304)
    assert old.encode(0.00304) == pytest.approx(12.92 * 0.00304, abs=1e-15)
    power_branch = 1.055 * 0.00304 ** (1 / 2.4) - 0.055
    assert abs(power_branch - 12.92 * 0.00304) < 2e-5
    assert np.abs(old.encode(X) - SRGBCurve().encode(X)).max() < 2e-5


@pytest.mark.parametrize(
    "ours, name",
    [
        (SRGBCurve(), "sRGB"),
        (PowerLaw(563 / 256), "Adobe RGB (1998)"),
    ],
)
def test_encoding_matches_colour_science(ours, name):
    colour = pytest.importorskip("colour")
    ref = colour.RGB_COLOURSPACES[name]
    np.testing.assert_allclose(ours.encode(X), ref.cctf_encoding(X), atol=1e-12)
    np.testing.assert_allclose(ours.decode(ours.encode(X)), X, atol=1e-12)


def test_bt2020_matches_colour_science_with_the_exact_constants():
    # colour-science defaults to the 10-bit rounded constants (1.099, 0.018); ours are the
    # exact ones that make the curve continuous, as BT.2020-2 defines them.
    colour = pytest.importorskip("colour")
    from colour.models.rgb.transfer_functions.itur_bt_2020 import oetf_BT2020

    exact = colour.utilities.Structure(
        alpha=lambda _: 1.09929682680944, beta=lambda _: 0.018053968510807
    )
    np.testing.assert_allclose(BT2020Curve().encode(X), oetf_BT2020(X, constants=exact), atol=1e-12)
    assert np.abs(BT2020Curve().encode(X) - oetf_BT2020(X)).max() < 3e-4


@settings(max_examples=60, deadline=None)
@given(st.floats(0, 1), st.sampled_from(["srgb", "srgb-1996", "gamma 2.2", "adobe rgb", "bt.2020"]))
def test_curves_round_trip_and_are_monotonic(x, name):
    t = transfer(name)
    assert t.decode(t.encode(x)) == pytest.approx(x, abs=1e-12)
    assert t.encode(min(x + 1e-3, 1.0)) >= t.encode(x)


def test_power_law_and_level_table_digit_routine():
    assert PowerLaw(2.2).encode(0.5) == pytest.approx(0.5 ** (1 / 2.2), rel=1e-15)
    table = LevelTable([0.0, 0.1, 0.5, 1.0])
    # nearest level, ties to the lower one (SPECTRA's digit(): "finds the nearest value")
    # exact: integer indices of typed levels
    np.testing.assert_array_equal(
        table.index([0.0, 0.04, 0.06, 0.3, 0.31, 0.74, 0.76, 1.0]), [0, 0, 1, 1, 2, 2, 3, 3]
    )
    assert table.decode(table.encode(0.49)) == 0.5  # exact: a level of the table, looked up, not computed


def test_spectra_table_nearest_level_is_brute_force_nearest():
    table = spectra_excitation_table()
    x = np.linspace(0, 1, 5001)
    brute = np.abs(x[:, None] - table.levels[None, :]).argmin(axis=1)
    # exact: integer indices from elementwise, correctly rounded arithmetic only (no sums)
    np.testing.assert_array_equal(table.index(x), brute)


def test_integer_codes_any_bit_depth():
    assert to_codes(1.0, 8) == 255 and to_codes(1.0, 10) == 1023 and to_codes(1.0, 16) == 65535
    assert to_codes(1.0, 6) == 63
    # exact: integer codes of typed values (0.5 · 255 = 127.5 is exact, and rounds up by the rule)
    np.testing.assert_array_equal(to_codes([0.0, 0.5, 0.2], 8), [0, 128, 51])
    np.testing.assert_allclose(from_codes([0, 255], 8), [0.0, 1.0])


def test_out_of_range_is_refused_not_clipped():
    with pytest.raises(ColorimetryError, match=r"rgb_linear must lie in \[0, 1\]"):
        SRGBCurve().encode([-0.1, 0.5])
    with pytest.raises(ColorimetryError, match="bit_depth"):
        to_codes(0.5, 0)
    with pytest.raises(ColorimetryError, match="NaN"):
        to_codes(np.nan)
    with pytest.raises(ColorimetryError, match="codes must lie"):
        from_codes([256], 8)
    with pytest.raises(ColorimetryError, match="transfer: .hlg. is not a transfer function .* choose one of .srgb."):
        transfer("hlg")
    with pytest.raises(ColorimetryError, match="strictly"):
        LevelTable([0.0, 0.5, 0.4, 1.0])
    with pytest.raises(ColorimetryError, match="gamma"):
        PowerLaw(-1.0)
    assert "spectra c.dat" in transfer_names()
    assert np.isnan(SRGBCurve().encode(np.nan))
