"""Tristimulus values: the seeds' worked examples, CIE white points, colour-science, properties."""

from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

import spectrocolor as sc
from spectrocolor import ColorimetryError, Spectrum

DATA = Path(__file__).parent / "data"


def _seed003_tables():
    table = sc.read_spectra(DATA / "seed003_ws_example_20nm.csv")
    return {"wavelength_nm": table.wavelengths_nm, **dict(zip(table.names, table.values, strict=True))}


@pytest.mark.parametrize(
    ("columns", "raw_sums", "XYZ1", "xy"),
    [
        # seed 003, "CIE 1964 at 20 nm": A^T S, XYZ scaled by A^T D65's middle number, xy
        (("x10", "y10", "z10"), (386.796, 381.417, 293.87), (0.663953, 0.654719, 0.504441), (0.364186, 0.359122)),
        # seed 003, "CIE 1931 20 nm"
        (("x2", "y2", "z2"), (356.817, 354.641, 271.109), (0.673539, 0.669432, 0.511754), (0.363148, 0.360933)),
    ],
)
def test_wyszecki_stiles_example_on_the_seeds_own_tables(columns, raw_sums, XYZ1, xy):
    t = _seed003_tables()
    grid = t["wavelength_nm"]
    cmfs = Spectrum(grid, np.array([t[c] for c in columns]))
    light_weights = sc.weights(grid, observer=cmfs)  # Σ x̄ S Δλ with Δλ = 20 nm
    np.testing.assert_allclose((t["beta"] * t["D65"]) @ light_weights / 20.0, raw_sums, rtol=5e-6)
    XYZ100 = sc.tristimulus(Spectrum(grid, t["beta"]), observer=cmfs, illuminant=Spectrum(grid, t["D65"]))
    np.testing.assert_allclose(XYZ100 / 100, XYZ1, rtol=2e-6)
    np.testing.assert_allclose(sc.xy(XYZ100), xy, atol=1e-6)


@pytest.mark.parametrize(
    ("observer", "XYZ1"), [("1964", (0.663953, 0.654719, 0.504441)), ("1931", (0.673539, 0.669432, 0.511754))]
)
def test_wyszecki_stiles_example_on_full_precision_cie_tables(observer, XYZ1):
    t = _seed003_tables()
    XYZ100 = sc.tristimulus(Spectrum(t["wavelength_nm"], t["beta"]), observer=observer, illuminant="D65")
    np.testing.assert_allclose(XYZ100 / 100, XYZ1, rtol=1e-3)  # the 0.1 %


def test_perfect_white_is_Y100_and_the_white_point():
    g = sc.wavelength_grid(380, 780, 5)
    white = sc.tristimulus(Spectrum.constant(1.0, g), observer="1931", illuminant="D65")
    np.testing.assert_allclose(white, sc.white_point("D65", observer="1931"), rtol=1e-14)
    assert white[1] == pytest.approx(100.0, rel=1e-14)


@pytest.mark.parametrize(
    ("illuminant", "observer", "xy"),
    [  # CIE 015:2018 Table 5 (computed by the CIE at 5 nm, 380–780 nm)
        ("A", "1931", (0.44758, 0.40745)),
        ("A", "1964", (0.45117, 0.40594)),
        ("C", "1931", (0.31006, 0.31616)),
        ("C", "1964", (0.31039, 0.31905)),
        ("D50", "1931", (0.34567, 0.35851)),
        ("D50", "1964", (0.34773, 0.35952)),
        ("D65", "1931", (0.31272, 0.32903)),
    ],
)
def test_cie_white_points(illuminant, observer, xy):
    XYZ = sc.white_point(illuminant, observer=observer)
    np.testing.assert_allclose(XYZ[:2] / XYZ.sum(), xy, atol=5e-6)


def test_weights_are_cached_and_read_only():
    g = sc.wavelength_grid(400, 700, 10)
    W = sc.weights(g, observer="1931", illuminant="D65")
    assert W is sc.weights(g.copy(), observer="2deg", illuminant="d65")
    assert W.shape == (31, 3) and not W.flags.writeable


def test_1nm_method_equals_explicit_interpolation():
    g = sc.wavelength_grid(400, 700, 10)
    rng = np.random.default_rng(3)
    refl = Spectrum(g, rng.random((5, g.size)))
    fine = refl.resample(sc.wavelength_grid(400, 700, 1))
    np.testing.assert_allclose(
        sc.tristimulus(refl, observer="1931", illuminant="D65", method="1nm"),
        sc.tristimulus(fine, observer="1931", illuminant="D65"),
        rtol=1e-13
    )


def test_light_absolute_scale():
    g = sc.wavelength_grid(360, 830, 1)
    light = Spectrum.constant(1.0, g)
    relative = sc.tristimulus(light, observer="1931")
    absolute = sc.tristimulus(light, observer="1931", k="absolute")
    np.testing.assert_allclose(absolute, 683.0 * relative)
    np.testing.assert_allclose(relative[1], sc.observer("1931").values[1].sum())


def test_errors_are_clear():
    with pytest.raises(ColorimetryError, match="outside the CIE 1931"):
        sc.weights(sc.wavelength_grid(300, 700, 10), observer="1931", illuminant="D65")
    with pytest.raises(ColorimetryError, match="Spectrum"):
        sc.tristimulus(np.ones(31))
    with pytest.raises(ColorimetryError, match="only for lights"):
        sc.tristimulus(Spectrum.constant(1, sc.wavelength_grid(400, 700, 10)), illuminant="D65", k=2)
    with pytest.raises(ColorimetryError, match="resample"):
        sc.weights(sc.wavelength_grid(400, 700, 10), observer="1931", illuminant=Spectrum([400, 700], [1, 1]))
    with pytest.raises(ColorimetryError, match="summation method"):
        sc.weights(sc.wavelength_grid(400, 700, 10), method="simpson")


@pytest.mark.parametrize("step", [1, 5, 10, 20])
@pytest.mark.parametrize(
    ("observer", "colour_observer"),
    [("1931", "CIE 1931 2 Degree Standard Observer"), ("1964", "CIE 1964 10 Degree Standard Observer")],
)
def test_agrees_with_colour_science_integration(step, observer, colour_observer):
    colour = pytest.importorskip("colour")
    import warnings

    g = sc.wavelength_grid(380, 780, step)
    rng = np.random.default_rng(step)
    values = rng.random((1000, g.size))
    ours = sc.tristimulus(Spectrum(g, values), observer=observer, illuminant="D65")
    shape = colour.SpectralShape(380, 780, step)
    cmfs = colour.MSDS_CMFS[colour_observer]
    illuminant = colour.SDS_ILLUMINANTS["D65"]
    if step == 1:
        illuminant = illuminant.copy().interpolate(
            colour.SpectralShape(300, 780, 1), interpolator=colour.LinearInterpolator
        )
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        theirs = colour.colorimetry.msds_to_XYZ_integration(values, cmfs, illuminant, shape=shape)
    np.testing.assert_allclose(ours, theirs, rtol=1e-9, atol=1e-9)


def test_float32_cube_stays_float32_and_agrees():
    g = sc.wavelength_grid(400, 700, 10)
    cube = np.random.default_rng(4).random((8, 9, g.size)).astype(np.float32)
    XYZ32 = sc.tristimulus(Spectrum(g, cube), observer="1931", illuminant="D65")
    XYZ64 = sc.tristimulus(Spectrum(g, cube.astype(float)), observer="1931", illuminant="D65")
    assert XYZ32.dtype == np.float32 and XYZ32.shape == (8, 9, 3)
    np.testing.assert_allclose(XYZ32, XYZ64, rtol=1e-5)


reflectances = arrays(np.float64, 31, elements=st.floats(0, 1))


@settings(max_examples=60, deadline=None)
@given(reflectances, reflectances, st.floats(-3, 3))
def test_tristimulus_is_linear(a, b, scale):
    g = sc.wavelength_grid(400, 700, 10)
    lhs = sc.tristimulus(Spectrum(g, scale * a + b), observer="1964", illuminant="A")
    rhs = (scale * sc.tristimulus(Spectrum(g, a), observer="1964", illuminant="A")
           + sc.tristimulus(Spectrum(g, b), observer="1964", illuminant="A"))
    np.testing.assert_allclose(lhs, rhs, atol=1e-9)


@settings(max_examples=30, deadline=None)
@given(
    st.sampled_from(["A", "C", "D50", "D65", "E", "FL2", "LED-B3"]),
    st.sampled_from(["1931", "1964"]),
    st.sampled_from([5, 10, 20]),
)
def test_perfect_white_property(illuminant, observer, step):
    g = sc.wavelength_grid(380, 780, step)
    XYZ = sc.tristimulus(Spectrum.constant(1.0, g), observer=observer, illuminant=illuminant)
    assert XYZ[1] == pytest.approx(100.0, rel=1e-12)
    np.testing.assert_allclose(XYZ, sc.weights(g, observer=observer, illuminant=illuminant).sum(axis=0))


def test_one_sample_is_not_a_summation():
    with pytest.raises(ColorimetryError, match="at least two samples"):
        sc.weights([500.0])
