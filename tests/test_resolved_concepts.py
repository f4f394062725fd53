"""Illuminants and observers resolved once, at a public function's entry, into typed values.

Issue 24, part 1: one resolver per concept (:func:`spectrocolor.resolve_illuminant`,
:func:`spectrocolor.resolve_observer`), frozen :class:`~spectrocolor.Illuminant` and
:class:`~spectrocolor.Observer` values, every argument that names a light accepting every form
the first does, and the resolver's parsing step run once per argument per public call.
"""

import dataclasses
import sys
from collections import Counter

import numpy as np
import pytest

import spectrocolor as sc
from spectrocolor import illuminants, observers, sampling
from spectrocolor.recovery.metamers import (
    metamer_mismatch_region,
    most_different_metamer,
    smoothest_metamer,
)

GRID = (380.0, 780.0, 10.0)
GRID_NM = sc.wavelength_grid(*GRID)
PARSERS = {"_parse_illuminant": "illuminant", "_parse_observer": "observer"}


def _parses(call) -> Counter:
    """How often each resolver's parsing step runs during ``call()`` (``sys.setprofile``)."""
    counts: Counter = Counter()
    files = {illuminants.__file__, observers.__file__}

    def profile(frame, event, arg):
        if event == "call" and frame.f_code.co_name in PARSERS and frame.f_code.co_filename in files:
            counts[PARSERS[frame.f_code.co_name]] += 1

    sys.setprofile(profile)
    try:
        call()
    finally:
        sys.setprofile(None)
    return counts


# --- the values and the resolvers ---------------------------------------------------------------


@pytest.mark.parametrize(("given", "name", "label", "kind", "temperature"), [
    ("d65", "D65", "D65", "cie", None),
    ("FL 11", "FL11", "FL11", "cie", None),
    ("blackbody:3000", "blackbody:3000", "blackbody 3000 K", "blackbody", 3000.0),
    ("planck: 2856 K", "blackbody:2856", "blackbody 2856 K", "blackbody", 2856.0),
    (6504, "blackbody:6504", "blackbody 6504 K", "blackbody", 6504.0),
    ("daylight:5000K", "D:5000", "CIE daylight 5000 K", "daylight", 5000.0),
])
def test_every_named_form_resolves_to_one_value(given, name, label, kind, temperature):
    light = sc.resolve_illuminant(given)
    assert isinstance(light, sc.Illuminant)
    # exact: temperature_K is float() of the canonical name's '%g' text, the same literal as here
    assert (light.name, light.label, light.kind, light.temperature_K) == (name, label, kind, temperature)
    assert light.reference and light.cacheable
    assert sc.resolve_illuminant(light) is light  # an already-resolved value passes through
    assert sc.canonical_illuminant(given) == name  # the old helpers are wrappers over it
    assert sc.illuminant_label(given) == label
    assert hash(light) == hash(sc.resolve_illuminant(name)) and light == sc.resolve_illuminant(name)


def test_a_spectrum_and_none():
    spd = sc.illuminant("FL2", GRID_NM)
    light = sc.resolve_illuminant(spd)
    assert light.kind == "spectrum" and light.spectrum is spd and not light.cacheable
    assert light.label == "FL2" and light.spd() is spd
    assert light == sc.resolve_illuminant(spd)  # the same Spectrum object
    assert light != sc.resolve_illuminant(sc.Spectrum(spd.wavelengths_nm, spd.values.copy()))  # not a copy
    assert sc.canonical_illuminant(spd) is spd
    assert sc.resolve_illuminant(None) is None and sc.canonical_illuminant(None) is None


def test_the_values_are_frozen():
    light, viewer = sc.resolve_illuminant("D65"), sc.resolve_observer("1964")
    with pytest.raises(dataclasses.FrozenInstanceError):
        light.name = "A"
    with pytest.raises(dataclasses.FrozenInstanceError):
        viewer.name = "CIE 1931 2°"


def test_spd_on_demand_is_the_illuminant_function():
    for given in ("D65", "A", "E", "blackbody:3000", "D:5000"):
        light = sc.resolve_illuminant(given)
        expected = sc.illuminant(given, GRID_NM).values
        np.testing.assert_allclose(light.spd(GRID_NM).values, expected, rtol=1e-15, atol=0)
        assert light.spd(GRID_NM) is light.spd(GRID_NM)  # cached
        assert not light.spd(GRID_NM).values.flags.writeable


@pytest.mark.parametrize(("given", "argument", "message"), [
    ("blackbody:3000x", "second_illuminant", "second_illuminant: 'blackbody:3000x' needs a temperature"),
    ("D99", "test", "test: 'D99' is not a CIE illuminant name"),
    ("D:2000", "--to", "--to: 'D:2000'"),
    ([1, 2], "reference", "reference: expected None (no illuminant"),
])
def test_one_error_naming_the_argument(given, argument, message):
    with pytest.raises(sc.ColorimetryError, match="^" + message.replace("(", r"\(")):
        sc.resolve_illuminant(given, argument)


def test_observers():
    ten = sc.resolve_observer("10 degree")
    # exact: field_deg is a constant of the observer table, stored, never computed
    assert (ten.name, ten.label, ten.field_deg, ten.year) == ("CIE 1964 10°", "CIE 1964 10°", 10.0, 1964)
    assert sc.resolve_observer(ten) is ten and ten == sc.resolve_observer("1964") and ten.cacheable
    assert ten.cmfs() is sc.observer("10deg")
    assert observers.canonical_observer_name(ten) == "CIE 1964 10°"
    custom = sc.resolve_observer(sc.observer("1931"))
    assert custom.name == "custom observer" and not custom.cacheable
    assert sampling.resolve_observer("2015-2") == ("CIE 2015 2°", sc.observer("2015-2"))
    with pytest.raises(sc.ColorimetryError, match="^viewer: 'martian' is not a shipped observer"):
        sc.resolve_observer("martian", "viewer")
    with pytest.raises(sc.ColorimetryError, match=r"^observer: a custom observer must be a Spectrum of shape \(3, K\)"):
        sc.resolve_observer(sc.illuminant("D65", GRID_NM))


def test_weights_are_cached_by_the_resolved_values():
    by_name = sc.weights(GRID_NM, observer="2deg", illuminant="d65")
    by_value = sc.weights(GRID_NM, observer=sc.resolve_observer("1931"), illuminant=sc.resolve_illuminant("D65"))
    assert by_name is by_value


# --- every argument that names a light accepts every form -----------------------------------------


def _bb3000_on_grid():
    return sc.illuminant("blackbody:3000", GRID_NM)


def test_mismatch_region_second_illuminant_blackbody():
    XYZ = np.array([20.0, 20.0, 20.0])
    by_name = metamer_mismatch_region(XYZ, second_illuminant="blackbody:3000", wavelengths=GRID, directions=24)
    by_spd = metamer_mismatch_region(XYZ, second_illuminant=_bb3000_on_grid(), wavelengths=GRID, directions=24)
    assert by_name.second_illuminant == "blackbody 3000 K" and by_name.illuminant == "D65"
    np.testing.assert_allclose(by_name.support, by_spd.support, rtol=1e-12, atol=1e-9)
    np.testing.assert_allclose(by_name.boundary_XYZ100, by_spd.boundary_XYZ100, rtol=1e-12, atol=1e-9)
    as_daylight = metamer_mismatch_region(XYZ, second_illuminant="D:5000", wavelengths=GRID, directions=8)
    assert as_daylight.second_illuminant == "CIE daylight 5000 K"


def test_smoothest_metamer_second_illuminant_blackbody():
    rho = 0.3 + 0.2 * np.sin(GRID_NM / 40.0)
    W1 = sc.weights(GRID_NM, illuminant="D65")
    W2 = sc.weights(GRID_NM, illuminant="blackbody:3000")
    by_name = smoothest_metamer(rho @ W1, rho @ W2, second_illuminant="blackbody:3000", wavelengths=GRID)
    by_spd = smoothest_metamer(rho @ W1, rho @ W2, second_illuminant=_bb3000_on_grid(), wavelengths=GRID)
    assert bool(by_name.feasible)
    np.testing.assert_allclose(by_name.spectrum.values, by_spd.spectrum.values, rtol=0, atol=1e-9)
    np.testing.assert_allclose(by_name.spectrum.values @ W2, rho @ W2, rtol=0, atol=1e-6)


def test_most_different_metamer_second_illuminant_blackbody():
    sample = sc.Spectrum(GRID_NM, 0.3 + 0.2 * np.sin(GRID_NM / 40.0))
    by_name = most_different_metamer(sample, 0.5, second_illuminant="blackbody:3000", wavelengths=GRID,
                                     directions=24)
    by_spd = most_different_metamer(sample, 0.5, second_illuminant=_bb3000_on_grid(), wavelengths=GRID,
                                    directions=24)
    assert by_name.region.second_illuminant == "blackbody 3000 K"
    assert by_name.delta_e_2000 == pytest.approx(by_spd.delta_e_2000, rel=1e-9, abs=1e-9)
    np.testing.assert_allclose(by_name.metamer.spectrum.values, by_spd.metamer.spectrum.values,
                               rtol=0, atol=1e-9)


def test_second_illuminant_errors_name_it():
    with pytest.raises(sc.ColorimetryError, match="^second_illuminant: 'blackbody:cold'"):
        metamer_mismatch_region(np.array([20.0, 20.0, 20.0]), second_illuminant="blackbody:cold",
                                wavelengths=GRID)
    with pytest.raises(sc.ColorimetryError, match="^second_illuminant: reflectances need a light"):
        smoothest_metamer(np.array([20.0, 20.0, 20.0]), np.array([20.0, 20.0, 20.0]), second_illuminant=None,
                          wavelengths=GRID)


def test_metamer_conditions_are_keyword_only():
    XYZ = np.array([20.0, 20.0, 20.0])
    with pytest.raises(TypeError):
        smoothest_metamer(XYZ, XYZ, "D65")  # type: ignore[misc]
    with pytest.raises(TypeError):
        most_different_metamer(XYZ, 0.5, "D65")  # type: ignore[misc]


def test_metamerism_index_test_and_reference_take_every_form():
    s1 = sc.Spectrum(GRID_NM, 0.3 + 0.2 * np.sin(GRID_NM / 40.0))
    s2 = sc.Spectrum(GRID_NM, 0.3 + 0.2 * np.sin(GRID_NM / 40.0) + 0.01 * np.cos(GRID_NM / 15.0))
    from spectrocolor.recovery.metamerism import metamerism_index

    by_name = metamerism_index(s1, s2, reference="D:6500", test="blackbody:3000")
    by_spd = metamerism_index(s1, s2, reference=sc.illuminant("D:6500", GRID_NM), test=_bb3000_on_grid())
    assert float(by_name) == pytest.approx(float(by_spd), rel=1e-9, abs=1e-12)


# --- resolved once per argument ---------------------------------------------------------------


def test_metamer_mismatch_region_resolves_each_argument_once():
    call = lambda: metamer_mismatch_region(np.array([20.0, 20.0, 20.0]), second_illuminant="blackbody:3000",  # noqa: E731
                                           wavelengths=GRID, directions=8)
    assert _parses(call) == {"illuminant": 2, "observer": 1}  # illuminant, second_illuminant; observer


GREY_D65 = 0.2 * sc.weights(GRID_NM, illuminant="D65").sum(axis=0)  # a 20 % grey under each light
GREY_A = 0.2 * sc.weights(GRID_NM, illuminant="A").sum(axis=0)


@pytest.mark.parametrize("call", [
    lambda: sc.tristimulus(sc.Spectrum.constant(0.5, GRID_NM), illuminant="D65", observer="1964"),
    lambda: sc.white_point("blackbody:3000", observer="1931"),
    lambda: sc.weights(GRID_NM, illuminant="D:5000", method="astm-e308"),
    lambda: sc.smoothest_metamer(GREY_D65, GREY_A, wavelengths=GRID),
], ids=["tristimulus", "white_point", "weights-astm", "smoothest_metamer"])
def test_public_calls_resolve_each_argument_once(call):
    counts = _parses(call)
    assert counts["observer"] == 1
    assert counts["illuminant"] == (2 if "metamer" in repr(call.__code__.co_names) else 1)
