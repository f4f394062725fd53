"""Hostile input to the recovery functions: one clear error naming the argument, never a raw one."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import spectrocolor as sc
from spectrocolor.recovery.optimal import macadam_limits, object_colour_membership, optimal_colours
from spectrocolor.recovery.smoothest import smoothest_reflectance

GRID = (400.0, 700.0, 10.0)
CLEAR = (sc.ColorimetryError, sc.SpectrumError)

anything = st.one_of(
    st.none(), st.booleans(), st.text(max_size=5), st.floats(allow_nan=True, allow_infinity=True),
    st.lists(st.floats(allow_nan=True, allow_infinity=True), max_size=5),
    st.lists(st.lists(st.floats(-1e3, 1e3), min_size=2, max_size=4), max_size=3),
)


@settings(max_examples=60, deadline=None)
@given(XYZ=anything, bounds=st.sampled_from(["unit", "nonnegative", None, "both", 1]))
def test_smoothest_reflectance_hostile_colours(XYZ, bounds):
    try:
        r = smoothest_reflectance(XYZ, wavelengths=GRID, bounds=bounds)
    except CLEAR:
        return
    assert r.spectrum.values.shape[-1] == 31


@settings(max_examples=40, deadline=None)
@given(XYZ=st.lists(st.tuples(*[st.floats(-50.0, 150.0)] * 3), min_size=1, max_size=6),
       bounds=st.sampled_from(["unit", "nonnegative"]))
def test_any_finite_batch_is_answered(XYZ, bounds):
    """A batch of any finite colours never raises: each is solved or flagged."""
    r = smoothest_reflectance(np.array(XYZ), wavelengths=GRID, bounds=bounds)
    assert r.feasible.shape == (len(XYZ),)
    assert np.all(np.isnan(r.spectrum.values[~r.feasible]))
    assert np.all(r.distance_outside[~r.feasible] > 0)


@settings(max_examples=40, deadline=None)
@given(wavelengths=anything, illuminant=st.one_of(st.sampled_from(["D65", "nope", ""]), anything))
def test_bad_grids_and_illuminants(wavelengths, illuminant):
    try:
        smoothest_reflectance([20.0, 20.0, 20.0], illuminant=illuminant, wavelengths=wavelengths)
    except CLEAR:
        pass


@settings(max_examples=40, deadline=None)
@given(Y=anything, samples=st.one_of(st.integers(-3, 10), anything), directions=anything)
def test_optimal_colour_functions(Y, samples, directions):
    for call in (lambda: macadam_limits(Y, wavelengths=GRID, samples=samples),
                 lambda: optimal_colours(wavelengths=GRID, directions=directions),
                 lambda: object_colour_membership(Y, wavelengths=GRID)):
        try:
            call()
        except CLEAR:
            pass


def test_errors_name_the_argument():
    with pytest.raises(sc.ColorimetryError, match="directions"):
        optimal_colours(wavelengths=GRID, directions=[[np.nan, 0.0, 1.0]])
    with pytest.raises(sc.ColorimetryError, match="samples"):
        macadam_limits(20.0, wavelengths=GRID, samples="many")


@settings(max_examples=60, deadline=None)
@given(direction=st.tuples(*[st.floats(-1.0, 2.0)] * 3), exponent=st.integers(-1070, 1020),
       bounds=st.sampled_from(["unit", "nonnegative"]))
def test_any_scale_is_answered(direction, exponent, bounds):
    """Tiny (down to subnormal) and huge colours: feasible ones get a finite spectrum within the
    bounds, infeasible ones NaN and a positive distance; never feasible with a NaN spectrum."""
    XYZ = np.ldexp(np.array(direction), exponent)
    r = smoothest_reflectance(XYZ[None], wavelengths=GRID, bounds=bounds)
    rho = r.spectrum.values[0]
    if r.feasible[0]:
        assert np.all(np.isfinite(rho)) and rho.min() >= 0.0
        assert bounds == "nonnegative" or rho.max() <= 1.0
    else:
        assert np.all(np.isnan(rho)) and r.distance_outside[0] > 0
