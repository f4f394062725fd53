"""Observers, illuminants, Planck and the daylight series against their published definitions."""

import numpy as np
import pytest

import spectrocolor as sc
from spectrocolor import ColorimetryError
from spectrocolor.data_tables import load_table


@pytest.mark.parametrize("alias", ["1931", "2deg", "CIE 1931 2°", "cie_1931_2", "2"])
def test_observer_aliases_1931(alias):
    cmfs = sc.observer(alias)
    assert cmfs.values.shape == (3, 471)
    # CIE 015:2018 Table 1 at 555 nm: ȳ = 1.000000 (the definition of the luminosity function's peak)
    assert cmfs.values[1, cmfs.wavelengths_nm == 555][0] == pytest.approx(1.0, abs=2e-6)


@pytest.mark.parametrize(("alias", "start"), [("1964", 360), ("10deg", 360), ("2015-2", 390), ("2015-10", 390)])
def test_other_observers(alias, start):
    assert sc.observer(alias).wavelengths_nm[0] == start


def test_unknown_observer_lists_choices():
    with pytest.raises(ColorimetryError, match="1964"):
        sc.observer("1976")


def test_observer_data_is_read_only():
    with pytest.raises(ValueError):
        sc.observer("1931").values[0, 0] = 1.0


def test_cmfs_match_colour_science():
    colour = pytest.importorskip("colour")
    for ours, theirs in [
        ("1931", "CIE 1931 2 Degree Standard Observer"),
        ("1964", "CIE 1964 10 Degree Standard Observer"),
        ("2015-2", "CIE 2015 2 Degree Standard Observer"),
    ]:
        cmfs = sc.observer(ours)
        ref = colour.MSDS_CMFS[theirs]
        common = np.intersect1d(cmfs.wavelengths_nm, ref.wavelengths)
        ours_values = cmfs.values[:, np.isin(cmfs.wavelengths_nm, common)].T
        np.testing.assert_allclose(ours_values, ref[common], rtol=0, atol=1e-7)


def test_illuminant_A_formula_reproduces_the_CIE_table():
    header, table = load_table("illuminants/A.csv")
    formula = sc.illuminant("A", table[:, 0]).values
    # the table is printed to 6 significant digits
    np.testing.assert_allclose(formula, table[:, 1], rtol=5e-6)
    assert sc.illuminant("A", [560.0]).values[0] == pytest.approx(100.0, rel=1e-14)


def test_illuminant_A_any_grid():
    a = sc.illuminant("A", np.linspace(380, 780, 801))
    assert a.values.size == 801 and np.all(np.diff(a.values) > 0)


@pytest.mark.parametrize("name", sc.illuminant_names())
def test_every_illuminant_loads(name):
    spd = sc.illuminant(name)
    assert spd.values.ndim == 1 and np.all(spd.values >= 0) and spd.values.max() > 0


@pytest.mark.parametrize(
    ("alias", "canonical"), [("d65", "D65"), ("FL 11", "FL11"), ("F2", "FL2"), ("led_b3", "LED-B3")]
)
def test_illuminant_aliases(alias, canonical):
    assert sc.illuminant(alias).names == (canonical,)


def test_illuminant_never_extrapolates():
    with pytest.raises(ColorimetryError, match="extrapolates"):
        sc.illuminant("FL2", sc.wavelength_grid(360, 830, 5))


def test_daylight_reproduces_D_tables():
    # CIE 015: nominal CCTs of D50/D65/D75 are the old values × 1.4388/1.4380
    for name, nominal in [("D50", 5000), ("D55", 5500), ("D65", 6500), ("D75", 7500)]:
        computed = sc.daylight(nominal * 1.4388 / 1.4380).values
        np.testing.assert_allclose(computed, sc.illuminant(name).values, rtol=0, atol=1.5e-3)


def test_daylight_xy_matches_the_CIE_D65():
    # The daylight-locus formula gives D65's (xD, yD) = (0.3127, 0.3291) to the four decimals the
    # CIE prints for it (the 5-decimal 0.31272, 0.32903 is from integrating the rounded table).
    np.testing.assert_allclose(sc.daylight_xy(6500 * 1.4388 / 1.4380), [0.3127, 0.3291], atol=5e-5)


def test_daylight_range_is_enforced():
    with pytest.raises(ColorimetryError, match="4000–25000"):
        sc.daylight(3000)


def test_blackbody_is_planck():
    # Planck's law with CODATA 2018 constants, written out independently
    h, c, kB = 6.62607015e-34, 299792458.0, 1.380649e-23
    lam = np.array([400e-9, 560e-9, 700e-9])
    radiance = 2 * h * c**2 / lam**5 / np.expm1(h * c / (lam * kB * 6504))
    expected = 100 * radiance / radiance[1]
    # CODATA prints c₂ = hc/k to 10 digits, so agreement is to ~1e-9
    np.testing.assert_allclose(sc.blackbody(6504, [400, 560, 700]).values, expected, rtol=2e-9)


def test_blackbody_rejects_nonsense():
    with pytest.raises(ColorimetryError, match="temperature_K"):
        sc.blackbody(-5)


def test_daylight_temperature_must_be_a_number():
    with pytest.raises(ColorimetryError, match="cct_K"):
        sc.daylight("x")
