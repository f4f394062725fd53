"""ΔE*ab and CIEDE2000: Sharma, Wu & Dalal (2005) test data and colour-science cross-checks."""

from __future__ import annotations

import colour
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

import spectrocolor as sc
from spectrocolor.errors import ColorimetryError

# G. Sharma, W. Wu, E. N. Dalal, "The CIEDE2000 color-difference formula: implementation notes,
# supplementary test data, and mathematical observations", Color Res. Appl. 30 (2005) 21-30,
# Table 1: L1 a1 b1 L2 a2 b2 ΔE00 (published to 4 decimals).
SHARMA_2005 = np.array(
    [
        [50.0000, 2.6772, -79.7751, 50.0000, 0.0000, -82.7485, 2.0425],
        [50.0000, 3.1571, -77.2803, 50.0000, 0.0000, -82.7485, 2.8615],
        [50.0000, 2.8361, -74.0200, 50.0000, 0.0000, -82.7485, 3.4412],
        [50.0000, -1.3802, -84.2814, 50.0000, 0.0000, -82.7485, 1.0000],
        [50.0000, -1.1848, -84.8006, 50.0000, 0.0000, -82.7485, 1.0000],
        [50.0000, -0.9009, -85.5211, 50.0000, 0.0000, -82.7485, 1.0000],
        [50.0000, 0.0000, 0.0000, 50.0000, -1.0000, 2.0000, 2.3669],
        [50.0000, -1.0000, 2.0000, 50.0000, 0.0000, 0.0000, 2.3669],
        [50.0000, 2.4900, -0.0010, 50.0000, -2.4900, 0.0009, 7.1792],
        [50.0000, 2.4900, -0.0010, 50.0000, -2.4900, 0.0010, 7.1792],
        [50.0000, 2.4900, -0.0010, 50.0000, -2.4900, 0.0011, 7.2195],
        [50.0000, 2.4900, -0.0010, 50.0000, -2.4900, 0.0012, 7.2195],
        [50.0000, -0.0010, 2.4900, 50.0000, 0.0009, -2.4900, 4.8045],
        [50.0000, -0.0010, 2.4900, 50.0000, 0.0010, -2.4900, 4.8045],
        [50.0000, -0.0010, 2.4900, 50.0000, 0.0011, -2.4900, 4.7461],
        [50.0000, 2.5000, 0.0000, 50.0000, 0.0000, -2.5000, 4.3065],
        [50.0000, 2.5000, 0.0000, 73.0000, 25.0000, -18.0000, 27.1492],
        [50.0000, 2.5000, 0.0000, 61.0000, -5.0000, 29.0000, 22.8977],
        [50.0000, 2.5000, 0.0000, 56.0000, -27.0000, -3.0000, 31.9030],
        [50.0000, 2.5000, 0.0000, 58.0000, 24.0000, 15.0000, 19.4535],
        [50.0000, 2.5000, 0.0000, 50.0000, 3.1736, 0.5854, 1.0000],
        [50.0000, 2.5000, 0.0000, 50.0000, 3.2972, 0.0000, 1.0000],
        [50.0000, 2.5000, 0.0000, 50.0000, 1.8634, 0.5757, 1.0000],
        [50.0000, 2.5000, 0.0000, 50.0000, 3.2592, 0.3350, 1.0000],
        [60.2574, -34.0099, 36.2677, 60.4626, -34.1751, 39.4387, 1.2644],
        [63.0109, -31.0961, -5.8663, 62.8187, -29.7946, -4.0864, 1.2630],
        [61.2901, 3.7196, -5.3901, 61.4292, 2.2480, -4.9620, 1.8731],
        [35.0831, -44.1164, 3.7933, 35.0232, -40.0716, 1.5901, 1.8645],
        [22.7233, 20.0904, -46.6940, 23.0331, 14.9730, -42.5619, 2.0373],
        [36.4612, 47.8580, 18.3852, 36.2715, 50.5065, 21.2231, 1.4146],
        [90.8027, -2.0831, 1.4410, 91.1528, -1.6435, 0.0447, 1.4441],
        [90.9257, -0.5406, -0.9208, 88.6381, -0.8985, -0.7239, 1.5381],
        [6.7747, -0.2908, -2.4247, 5.8714, -0.0985, -2.2286, 0.6377],
        [2.0776, 0.0795, -1.1350, 0.9033, -0.0636, -0.5514, 0.9082],
    ]
)

RNG = np.random.default_rng(7)
LAB_A = np.column_stack([RNG.uniform(0, 100, 3000), RNG.uniform(-120, 120, (3000, 2))])
LAB_B = np.column_stack([RNG.uniform(0, 100, 3000), RNG.uniform(-120, 120, (3000, 2))])


def test_ciede2000_reproduces_sharma_table_to_published_digits():
    lab1, lab2, expected = SHARMA_2005[:, :3], SHARMA_2005[:, 3:6], SHARMA_2005[:, 6]
    result = sc.delta_e_2000(lab1, lab2)
    assert result.shape == (34,)
    np.testing.assert_array_less(np.abs(result - expected), 0.5e-4 + 1e-12)


def test_ciede2000_is_symmetric_on_sharma_pairs():
    lab1, lab2 = SHARMA_2005[:, :3], SHARMA_2005[:, 3:6]
    np.testing.assert_allclose(sc.delta_e_2000(lab2, lab1), sc.delta_e_2000(lab1, lab2),
                               rtol=0, atol=1e-12)


def test_ciede2000_matches_colour_on_random_pairs():
    expected = colour.delta_E(LAB_A, LAB_B, method="CIE 2000")
    np.testing.assert_allclose(sc.delta_e_2000(LAB_A, LAB_B), expected, rtol=0, atol=1e-9)


def test_ciede2000_parametric_factors_match_colour():
    expected = colour.difference.delta_E_CIE2000(LAB_A[:200], LAB_B[:200], textiles=True)
    np.testing.assert_allclose(sc.delta_e_2000(LAB_A[:200], LAB_B[:200], k_L=2.0), expected,
                               rtol=0, atol=1e-9)


def test_delta_e_76_matches_colour_and_pythagoras():
    assert sc.delta_e_76([50.0, 0.0, 0.0], [50.0, 3.0, 4.0]) == pytest.approx(5.0, abs=1e-15)
    expected = colour.delta_E(LAB_A, LAB_B, method="CIE 1976")
    np.testing.assert_allclose(sc.delta_e_76(LAB_A, LAB_B), expected, rtol=0, atol=1e-12)


def test_differences_broadcast():
    result = sc.delta_e_2000(LAB_A.reshape(30, 100, 3), LAB_B[0])
    assert result.shape == (30, 100)
    np.testing.assert_allclose(result[1, 2], sc.delta_e_2000(LAB_A[102], LAB_B[0]), rtol=1e-14)


def test_bad_shape_is_a_clear_error():
    with pytest.raises(ColorimetryError, match="lab2 must have shape"):
        sc.delta_e_2000([50.0, 1.0, 1.0], [50.0, 1.0])


lab_values = st.tuples(st.floats(0, 100), st.floats(-128, 128), st.floats(-128, 128))


@settings(max_examples=300, deadline=None)
@given(lab_values, lab_values)
def test_ciede2000_symmetric_nonnegative_zero_on_identity(c1, c2):
    d12 = sc.delta_e_2000(c1, c2)
    assert d12 >= 0
    assert d12 == pytest.approx(sc.delta_e_2000(c2, c1), abs=1e-9)
    # exact: every difference of a colour with itself is exactly 0, and so is the sum
    assert sc.delta_e_2000(c1, c1) == 0.0


@settings(max_examples=100, deadline=None)
@given(arrays(np.float64, (4, 3), elements=st.floats(-100, 100)))
def test_delta_e_76_triangle_inequality(labs):
    a, b, c = labs[0], labs[1], labs[2]
    assert sc.delta_e_76(a, c) <= sc.delta_e_76(a, b) + sc.delta_e_76(b, c) + 1e-9


def test_mismatched_batches_are_a_clear_error():
    with pytest.raises(ColorimetryError, match="do not broadcast"):
        sc.delta_e_2000(np.ones((4, 3)), np.ones((5, 3)))
    with pytest.raises(ColorimetryError, match="do not broadcast"):
        sc.delta_e_76(np.ones((4, 3)), np.ones((5, 3)))


# --- numbers that overflow say so (issue 25) ------------------------------------------------------


@pytest.mark.parametrize(("lab1", "lab2"), [
    ([1e308, 0.0, 0.0], [0.0, 0.0, 0.0]),
    ([50.0, 1e308, 0.0], [50.0, -1e308, 0.0]),
    ([50.0, 1e200, 1e200], [50.0, 0.0, 0.0]),
    ([[50.0, 2.0, 3.0], [50.0, 1e60, 0.0]], [50.0, 0.0, 0.0]),
])
def test_differences_that_overflow_are_an_error_naming_the_arguments(lab1, lab2):
    import warnings

    with warnings.catch_warnings():
        warnings.simplefilter("error")  # and no RuntimeWarning on the way
        for difference, name in ((sc.delta_e_2000, "ΔE00"), (sc.delta_e_76, "ΔE*ab")):
            try:
                value = difference(lab1, lab2)
            except sc.ColorimetryError as error:
                assert str(error).startswith("lab1, lab2: ") and f"{name} overflows" in str(error)
            else:  # only where the true difference is finite and was computed so
                assert np.all(np.isfinite(value)), (difference, value)
    with pytest.raises(sc.ColorimetryError, match="lab1, lab2: .*ΔE00 overflows the float range"):
        sc.delta_e_2000(lab1, lab2)


def test_nan_in_a_difference_stays_per_item_and_is_not_an_overflow():
    value = sc.delta_e_2000([[np.nan, 0.0, 0.0], [50.0, 2.0, 3.0]], [50.0, 0.0, 0.0])
    assert np.isnan(value[0]) and np.isfinite(value[1])
