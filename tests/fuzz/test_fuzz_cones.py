"""Hostile input to :func:`spectrocolor.cone_responses`: any grid, values, field and normalisation.

Every call either returns L, M, S of the batch shape or raises one ColorimetryError/SpectrumError
whose message starts with the argument's name; never another exception.
"""

from __future__ import annotations

import numpy as np
import pytest

hypothesis = pytest.importorskip("hypothesis")
from hypothesis import given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402
from hypothesis.extra import numpy as hnp  # noqa: E402

from spectrocolor import Spectrum, cone_responses  # noqa: E402
from spectrocolor.errors import ColorimetryError, SpectrumError  # noqa: E402

ARGUMENTS = ("spectrum", "field", "illuminant", "normalisation", "wavelengths_nm")


@settings(max_examples=80, deadline=None)
@given(
    start=st.floats(200, 900), step=st.sampled_from([0.5, 1.0, 5.0, 10.0, 37.0]), count=st.integers(1, 80),
    data=st.data(),
    field=st.one_of(st.sampled_from([2, 10, "2°", "10°", "2015-10", "1931", 3, "x", None, True, 1e308, np.nan])),
    illuminant=st.sampled_from([None, "E", "D65", "A", "FL11", "LED-B3", "nonsense", 1500.0, -3]),
    normalisation=st.sampled_from([None, "white", "equal-energy", "peak", "bogus", 3]),
)
def test_any_call_answers_or_names_its_argument(start, step, count, data, field, illuminant, normalisation):
    grid = start + step * np.arange(count)
    values = data.draw(hnp.arrays(np.float64, (2, count), elements=st.one_of(
        st.floats(-1e3, 1e6), st.just(0.0), st.just(np.nan), st.just(np.inf))))
    try:
        spectrum = Spectrum(grid, values)
    except SpectrumError:
        return
    try:
        out = cone_responses(spectrum, field=field, illuminant=illuminant, normalisation=normalisation)
    except (ColorimetryError, SpectrumError) as error:
        message = str(error)
        assert message.startswith(ARGUMENTS) or "illuminant" in message.split(":")[0], message
        assert "\n" not in message
        return
    assert out.shape == (2, 3)
    finite_rows = np.all(np.isfinite(values), axis=1)
    assert np.all(np.isfinite(out[finite_rows]))  # finite spectra (|v| ≤ 1e6) give finite responses
