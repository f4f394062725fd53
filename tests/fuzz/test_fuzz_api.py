"""Hostile arguments for the public functions: a result, or one clear error naming the argument.

For each public function a valid call is written out; then every argument in turn is replaced
by hostile values (NaN, infinities, complex numbers, ragged and empty lists, strings, None,
booleans, float16, object arrays, huge and negative numbers). The contract
(``docs/robustness.md``):

* the call returns, or raises :class:`SpectrumError` / :class:`ColorimetryError` whose message
  names the argument replaced (never a raw ``TypeError``, ``IndexError``, ``ZeroDivisionError``
  ..., never a bare ``ValueError``);
* complex input is never silently made real: it raises;
* finite input never gives an all-NaN result (silent garbage such as ``blackbody(10)``).

The long run (more generated arrays): ``SPECTROCOLOR_LONG_FUZZ=1 pytest -m slow tests/fuzz/test_fuzz_api.py``.
"""

from __future__ import annotations

import os
import warnings

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra import numpy as hnp

import spectrocolor as sc
from spectrocolor.errors import ColorimetryError, SpectrumError

LONG = os.environ.get("SPECTROCOLOR_LONG_FUZZ") == "1"

WL = np.arange(380.0, 781.0, 10.0)
REFLECTANCES = sc.Spectrum(WL, np.stack([np.full(WL.size, 0.5), np.linspace(0.1, 0.9, WL.size)]))
LIGHT = sc.blackbody(4000.0, WL)
LAB = [50.0, 10.0, -20.0]
D65 = [95.047, 100.0, 108.883]

#: name -> (function, valid keyword arguments). Arguments are replaced one at a time.
CALLS = {
    "xy": (sc.xy, {"XYZ": [20.0, 30.0, 40.0]}),
    "xyY": (sc.xyY, {"XYZ": [20.0, 30.0, 40.0]}),
    "XYZ_from_xyY": (sc.XYZ_from_xyY, {"xyY": [0.3, 0.3, 20.0]}),
    "uv_1960": (sc.uv_1960, {"XYZ": [20.0, 30.0, 40.0]}),
    "uv_1976": (sc.uv_1976, {"XYZ": [20.0, 30.0, 40.0]}),
    "xy_from_uv_1960": (sc.xy_from_uv_1960, {"uv": [0.2, 0.3]}),
    "xy_from_uv_1976": (sc.xy_from_uv_1976, {"uv": [0.2, 0.45]}),
    "lab": (sc.lab, {"XYZ": [20.0, 30.0, 40.0], "white_XYZ": D65}),
    "XYZ_from_lab": (sc.XYZ_from_lab, {"lab": LAB, "white_XYZ": D65}),
    "lch": (sc.lch, {"lab": LAB}),
    "lab_from_lch": (sc.lab_from_lch, {"lch": [50.0, 20.0, 120.0]}),
    "delta_e_76": (sc.delta_e_76, {"lab1": LAB, "lab2": [55.0, 0.0, 0.0]}),
    "delta_e_2000": (sc.delta_e_2000, {"lab1": LAB, "lab2": [55.0, 0.0, 0.0], "k_L": 1.0,
                                       "k_C": 1.0, "k_H": 1.0}),
    "adapt": (sc.adapt, {"XYZ": [20.0, 30.0, 40.0], "source_white_XYZ": D65,
                         "target_white_XYZ": [96.42, 100.0, 82.52], "method": "bradford"}),
    "blackbody": (sc.blackbody, {"temperature_K": 5000.0, "wavelengths_nm": WL,
                                 "normalise_at_nm": 560.0}),
    "daylight": (sc.daylight, {"cct_K": 6500.0, "wavelengths_nm": WL}),
    "daylight_xy": (sc.daylight_xy, {"cct_K": 6500.0}),
    "xy_from_cct": (sc.xy_from_cct, {"cct_K": 5000.0, "duv": 0.0}),
    "cct": (sc.cct, {"xy": [0.3127, 0.329]}),
    "illuminant": (sc.illuminant, {"name": "D65", "wavelengths_nm": WL, "method": "linear"}),
    "observer": (sc.observer, {"name": "1931"}),
    "rgb_space": (sc.rgb_space, {"name": "sRGB"}),
    "transfer": (sc.transfer, {"spec": "srgb"}),
    "wavelength_grid": (sc.wavelength_grid, {"start_nm": 380.0, "stop_nm": 780.0, "step_nm": 5.0}),
    "wavelength_tint": (sc.wavelength_tint, {"wavelengths_nm": [450.0, 550.0]}),
    "weights": (sc.weights, {"wavelengths_nm": WL, "observer": "1931", "illuminant": "D65"}),
    "white_point": (sc.white_point, {"illuminant": "D65", "observer": "1931",
                                     "wavelengths_nm": WL}),
    "tristimulus": (sc.tristimulus, {"spectrum": REFLECTANCES, "observer": "1931",
                                     "illuminant": "D65", "method": "sum"}),
    "dominant_wavelength": (sc.dominant_wavelength, {"xy": [0.4, 0.4], "white": [0.3127, 0.329]}),
    "colorimetric_purity": (sc.colorimetric_purity, {"xy": [0.4, 0.4],
                                                     "white": [0.3127, 0.329]}),
    "render": (sc.render, {"XYZ100": [20.0, 30.0, 40.0], "space": "sRGB", "gamut": "clip"}),
    "to_codes": (sc.to_codes, {"rgb_encoded": [0.2, 0.5, 1.0], "bit_depth": 8}),
    "from_codes": (sc.from_codes, {"codes": [0, 128, 255], "bit_depth": 8}),
    "two_beam_reflectance": (sc.two_beam_reflectance, {"opd_nm": [100.0, 500.0],
                                                       "wavelengths_nm": WL, "beta": 0.95}),
    "optical_path_difference": (sc.optical_path_difference, {"thickness_nm": [100.0],
                                                             "film_index": 1.33}),
    "soap_film": (sc.soap_film, {"thickness_nm": [100.0, 300.0], "wavelengths_nm": WL}),
    "medium": (sc.medium, {"spec": "water"}),
    "luminous_quantity": (sc.luminous_quantity, {"spd": LIGHT}),
    "fundamental_metamer": (sc.fundamental_metamer, {"spectrum": REFLECTANCES,
                                                     "illuminant": "D65"}),
    "metameric_black": (sc.metameric_black, {"spectrum": REFLECTANCES, "illuminant": "D65"}),
    "measurement_report": (sc.measurement_report, {"spectra": REFLECTANCES, "illuminant": "D65"}),
    "canonical_illuminant": (sc.canonical_illuminant, {"illuminant": "D65"}),
    "spectral_locus": (sc.spectral_locus, {"observer": "1931"}),
    "Spectrum": (sc.Spectrum, {"wavelengths_nm": [400.0, 500.0, 600.0],
                               "values": [0.1, 0.2, 0.3]}),
}

HOSTILE = {
    "nan": float("nan"), "inf": float("inf"), "-inf": float("-inf"), "huge": 1e308,
    "negative": -1.0, "zero": 0.0, "complex": 1 + 2j, "complex list": [1 + 2j, 2.0, 3.0],
    "complex array": np.array([1 + 0j, 2, 3]), "ragged": [[1.0, 2.0, 3.0], [1.0, 2.0]],
    "string": "abc", "None": None, "empty list": [], "True": True,
    "float16": np.float16(0.1), "float16 array": np.array([0.2, 0.3, 0.4], np.float16),
    "object array": np.array([1, "a", None], dtype=object), "dict": {"a": 1},
    "nested": [[[[1.0]]]], "shape (0, 3)": np.zeros((0, 3)), "int": 7,
}
FINITE = {"huge", "negative", "zero", "float16", "float16 array", "int", "True"}
#: Resolvers name the concept their value stands for, the word every caller's argument uses
#: (``render(space=...)`` -> ``rgb_space(name)`` says "space:"); these count as naming it.
ALIASES = {("rgb_space", "name"): "space", ("observer", "name"): "observer",
           ("transfer", "spec"): "gamma", ("medium", "spec"): "medium",
           ("dominant_wavelength", "white"): "illuminant",
           ("colorimetric_purity", "white"): "illuminant"}
#: Where a complex number is a documented value: n + ik of an absorbing medium.
COMPLEX_ALLOWED = {("medium", "spec")}


def call(function, kwargs):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # RuntimeWarnings of NaN arithmetic are not the question
        return function(**kwargs)


def _values(result):
    if isinstance(result, sc.Spectrum):
        return result.values
    if isinstance(result, np.ndarray) and result.dtype.kind in "fc":
        return result
    return None


def check(name: str, argument: str, label: str) -> str | None:
    """Run one hostile call; return a description of a broken contract, or None."""
    function, valid = CALLS[name]
    kwargs = {**valid, argument: HOSTILE[label]}
    try:
        result = call(function, kwargs)
    except (SpectrumError, ColorimetryError) as exc:
        named = argument in str(exc) or ALIASES.get((name, argument), argument) in str(exc)
        return None if named else f"error names no argument: {exc}"
    except RecursionError:
        return "RecursionError"
    except Exception as exc:  # noqa: BLE001 - the point: anything else is a broken contract
        return f"raw {exc.__class__.__name__}: {str(exc)[:120]}"
    if "complex" in label and (name, argument) not in COMPLEX_ALLOWED:
        return "complex input accepted"
    values = _values(result)
    if label in FINITE and values is not None and values.size and np.all(np.isnan(values)):
        return "finite input, all-NaN result"
    return None


CASES = [(name, argument, label) for name, (_, valid) in CALLS.items() for argument in valid
         for label in HOSTILE]


@pytest.mark.parametrize("name", sorted(CALLS))
def test_valid_calls_work(name):
    function, valid = CALLS[name]
    call(function, valid)


@pytest.mark.parametrize("name", sorted(CALLS))
def test_hostile_arguments(name):
    problems = [f"{argument}={label}: {problem}" for n, argument, label in CASES if n == name
                if (problem := check(n, argument, label))]
    assert not problems, "\n".join(problems)


# --- generated arrays for the colour functions ---------------------------------------------------

FLOATS = st.floats(allow_nan=True, allow_infinity=True, width=64)
COLOUR_FUNCTIONS = ["xy", "xyY", "lab", "lch", "delta_e_76", "delta_e_2000", "uv_1976", "render",
                    "adapt", "XYZ_from_xyY", "XYZ_from_lab"]


def _arrays(size):
    return hnp.arrays(np.float64, hnp.array_shapes(min_dims=1, max_dims=3, max_side=4).map(
        lambda s: (*s[:-1], size)), elements=FLOATS)


@settings(max_examples=300 if LONG else 60, deadline=None)
@given(name=st.sampled_from(COLOUR_FUNCTIONS), data=st.data())
def test_generated_colour_arrays(name, data):
    function, valid = CALLS[name]
    argument = next(iter(valid))
    array = data.draw(_arrays(len(valid[argument])))
    try:
        result = call(function, {**valid, argument: array})
    except (SpectrumError, ColorimetryError) as exc:
        assert argument in str(exc) or "XYZ" in str(exc), str(exc)
        return
    values = _values(result) if not hasattr(result, "rgb_linear") else result.rgb_linear
    if np.all(np.isfinite(array)) and values is not None and np.all(np.abs(array) < 1e100):
        # finite, moderate input: one result per colour, whatever the values
        assert values.shape[:array.ndim - 1] == array.shape[:-1]


@pytest.mark.slow
@pytest.mark.skipif(not LONG, reason="long fuzz run: set SPECTROCOLOR_LONG_FUZZ=1")
@settings(max_examples=2000, deadline=None)
@given(name=st.sampled_from(sorted(CALLS)), data=st.data())
def test_generated_scalars_long(name, data):
    function, valid = CALLS[name]
    argument = data.draw(st.sampled_from(sorted(valid)))
    value = data.draw(FLOATS | st.integers(-10**30, 10**30) | st.complex_numbers() | st.text(max_size=8))
    kwargs = {**valid, argument: value}
    try:
        call(function, kwargs)
    except (SpectrumError, ColorimetryError) as exc:
        assert argument in str(exc) or ALIASES.get((name, argument), argument) in str(exc), str(exc)
        return
    complex_ok = (name, argument) in COMPLEX_ALLOWED
    assert complex_ok or not isinstance(value, complex) or value.imag == 0, "complex accepted"
