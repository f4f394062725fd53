"""CCT and Duv: round trips through Planck's law, the seeds' whites, colour-science cross-check."""

from __future__ import annotations

import colour
import numpy as np
import pytest
from colour.temperature import uv_to_CCT_Ohno2013, uv_to_CCT_Robertson1968

import spectrocolor as sc
from spectrocolor.errors import ColorimetryError

RNG = np.random.default_rng(6504)


def planck_xy(temperature_K: float, observer: str = "1931") -> np.ndarray:
    """xy of a blackbody via sc.blackbody and sc.tristimulus (an independent code path).

    c2 = 1.4388e-2 m·K as CIE 015:2018 and Ohno use for CCT (sc.blackbody defaults to CODATA
    1.438776877e-2, which shifts temperatures by 1.6e-5 relative).
    """
    cmfs = sc.observer(observer)
    light = sc.blackbody(temperature_K, cmfs.wavelengths_nm, c2_m_K=1.4388e-2)
    return sc.xy(sc.tristimulus(light, observer=observer))


@pytest.mark.parametrize("temperature_K", [1500.0, 2856.0, 6504.0, 7000.0, 25000.0])
def test_blackbody_has_its_own_temperature_and_zero_duv(temperature_K):
    # seed 000: a 6504 K blackbody; seed 002: a 7000 K monitor white
    result = sc.cct(planck_xy(temperature_K))
    assert result.cct_K == pytest.approx(temperature_K, rel=1e-7)
    assert abs(result.duv) < 1e-9
    np.testing.assert_allclose(sc.xy_from_cct(temperature_K), planck_xy(temperature_K), atol=1e-12)


def test_round_trip_over_the_whole_range_is_accurate_to_the_stated_bounds():
    T = np.exp(RNG.uniform(np.log(1001.0), np.log(99_000.0), 5000))
    duv = RNG.uniform(-0.05, 0.05, 5000)
    result = sc.cct(sc.xy_from_cct(T, duv))
    np.testing.assert_allclose(result.cct_K, T, rtol=3e-8)  # 0.003 K at 100 000 K
    np.testing.assert_allclose(result.duv, duv, rtol=0, atol=1e-9)


def test_duv_sign_positive_toward_green():
    above = sc.xy_from_cct(4000.0, 0.01)
    assert above[1] > sc.xy_from_cct(4000.0)[1]
    assert sc.cct(above).duv == pytest.approx(0.01, abs=1e-9)


def test_d65_and_the_spectra_monitor_white_against_colour_science():
    # D65 (CIE 015 xy) is quoted as about 6504 K; seed 002's monitor white (X, Y, Z = 98.88,
    # 106.83, 121.11) was "formally adjusted to a correlated colour temperature of 7000 K"
    d65 = sc.cct([0.31272, 0.32903])
    assert 6500 < d65.cct_K < 6505
    monitor = sc.cct(XYZ=[98.88, 106.83, 121.11])
    for result, xy in ((d65, np.array([0.31272, 0.32903])),
                       (monitor, colour.XYZ_to_xy(np.array([98.88, 106.83, 121.11])))):
        uv = colour.xy_to_UCS_uv(xy)
        ohno = uv_to_CCT_Ohno2013(uv)
        robertson = uv_to_CCT_Robertson1968(uv)
        assert result.cct_K == pytest.approx(ohno[0], abs=1.0)
        assert result.duv == pytest.approx(ohno[1], abs=1e-6)
        assert result.cct_K == pytest.approx(robertson[0], abs=3.0)  # Robertson: ~1-2 K tables
    assert monitor.cct_K == pytest.approx(7099.4, abs=0.1)  # not 7000 K: Duv = +0.0074
    assert monitor.duv == pytest.approx(0.00736, abs=1e-5)


def test_matches_colour_ohno2013_on_random_points():
    T = np.exp(RNG.uniform(np.log(2000.0), np.log(20_000.0), 1000))
    duv = RNG.uniform(-0.02, 0.02, 1000)
    xy = sc.xy_from_cct(T, duv)
    theirs = uv_to_CCT_Ohno2013(colour.xy_to_UCS_uv(xy))
    ours = sc.cct(xy)
    # colour's Ohno 2013 implementation is itself accurate to ~1e-4 relative (its cascade)
    np.testing.assert_allclose(ours.cct_K, theirs[:, 0], rtol=2e-4)
    np.testing.assert_allclose(ours.duv, theirs[:, 1], atol=1e-6)


def test_shapes_nan_and_out_of_range():
    result = sc.cct(np.full((4, 5, 2), 0.33))
    assert result.cct_K.shape == (4, 5) and result.duv.shape == (4, 5)
    odd = sc.cct([[np.nan, 0.3], [0.7, 0.29], [0.2, 0.1]])
    assert np.isnan(odd.cct_K).all() and np.isnan(odd.duv).all()
    assert sc.xy_from_cct(np.full((2, 3), 5000.0), 0.0).shape == (2, 3, 2)


def test_bad_input_is_a_clear_error():
    with pytest.raises(ColorimetryError, match="exactly one"):
        sc.cct()
    with pytest.raises(ColorimetryError, match="between 1000 and 100000 K"):
        sc.xy_from_cct(500.0)
    with pytest.raises(ColorimetryError, match="is not a shipped observer"):
        sc.cct([0.3, 0.3], observer="1900")


def test_1964_observer_locus_differs_and_round_trips():
    xy10 = sc.xy_from_cct(5000.0, observer="1964")
    assert np.abs(xy10 - sc.xy_from_cct(5000.0)).max() > 1e-3
    assert sc.cct(xy10, observer="1964").cct_K == pytest.approx(5000.0, rel=1e-8)
