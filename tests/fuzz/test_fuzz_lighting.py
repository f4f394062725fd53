"""Hostile input to the lighting metrics, the report writer and ``spectrocolor light``.

Every call either returns arrays of the batch shape (finite, or NaN where a light has no CCT)
or raises one SpectrumError/ColorimetryError naming the argument; the command exits 0 or 2
with one line on stderr, never a traceback.
"""

from __future__ import annotations

import numpy as np
import pytest

hypothesis = pytest.importorskip("hypothesis")
from hypothesis import HealthCheck, given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402
from hypothesis.extra import numpy as hnp  # noqa: E402

from spectrocolor import Spectrum, wavelength_grid  # noqa: E402
from spectrocolor.cli import main  # noqa: E402
from spectrocolor.errors import ColorimetryError, SpectrumError  # noqa: E402
from spectrocolor.lighting import (  # noqa: E402
    alpha_opic,
    colour_fidelity,
    colour_rendering_index,
    luminous_efficacy_of_radiation,
)

GRID_5NM = wavelength_grid(380, 780, 5)
values_5nm = hnp.arrays(
    np.float64, (2, GRID_5NM.size),
    elements=st.one_of(st.floats(0, 1e6), st.floats(-1e-3, 0), st.just(0.0)),
)


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(values_5nm)
def test_any_nonnegative_ish_spectra_give_arrays_of_the_batch_shape(values):
    spd = Spectrum(GRID_5NM, values)
    cri, fidelity = colour_rendering_index(spd), colour_fidelity(spd)
    assert cri.Ri.shape == (2, 14) and fidelity.Rf_h.shape == (2, 16)
    for i in range(2):
        # references exist from 1000 K (Planck) to 25 000 K (CIE daylight); NaN outside
        if 1000.0 <= cri.cct_K[i] <= 25000.0:
            assert np.isfinite(cri.Ra[i]) and np.all(np.isfinite(cri.Ri[i]))
            if np.any(values[i] < 0) and np.isnan(fidelity.Rf[i]):
                # a negative sample can give a test colour negative XYZ, which CAM02-UCS leaves undefined
                assert "negative samples" in fidelity.reason[i]
            else:
                assert np.isfinite(fidelity.Rf[i]) and fidelity.Rf[i] <= 100.001
        else:
            assert np.isnan(cri.Ra[i]) and np.isnan(fidelity.Rf[i])
            assert cri.reason[i] and fidelity.reason[i]
    assert alpha_opic(spd).der.shape == (2, 5)
    assert luminous_efficacy_of_radiation(spd).shape == (2,)


@settings(max_examples=60, deadline=None)
@given(
    start=st.floats(300, 420), step=st.sampled_from([0.5, 1.0, 2.0, 2.5, 5.0, 10.0]),
    count=st.integers(2, 200), bad=st.sampled_from([None, np.nan, np.inf]),
)
def test_any_grid_is_computed_or_refused_with_one_clear_error(start, step, count, bad):
    grid = start + step * np.arange(count)
    values = np.ones(count)
    if bad is not None:
        values[count // 2] = bad
    spd = Spectrum(grid, values)
    for metric in (colour_rendering_index, colour_fidelity, alpha_opic):
        try:
            metric(spd)
        except SpectrumError as error:
            assert "spd" in str(error)


@settings(max_examples=25, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(text=st.text(max_size=300), numbers=st.lists(st.floats(allow_nan=True, allow_infinity=True), max_size=30))
def test_light_command_on_hostile_files_exits_cleanly(tmp_path, capsys, text, numbers):
    source = tmp_path / "lamp.csv"
    rows = "\n".join(f"{380 + 5 * i},{value}" for i, value in enumerate(numbers))
    source.write_text(f"wavelength_nm,lamp\n{rows}\n{text}", encoding="utf-8")
    code = main(["light", str(source), "--out", str(tmp_path / "r.json"), "--force"])
    captured = capsys.readouterr()
    assert code in (0, 2)
    if code == 2:
        assert captured.err.startswith("spectrocolor light: error:") and "Traceback" not in captured.err


@pytest.mark.parametrize("argument", [np.ones(81), [1.0] * 81, None, "FL2"])
def test_non_spectra_are_refused_by_name(argument):
    for metric in (colour_rendering_index, colour_fidelity, alpha_opic, luminous_efficacy_of_radiation):
        with pytest.raises((SpectrumError, ColorimetryError), match="Spectrum"):
            metric(argument)


@settings(max_examples=20, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(start=st.floats(300, 420), step=st.floats(0.3, 12), count=st.integers(2, 150),
       method=st.sampled_from(["linear", "sprague", "cubic"]), graphic=st.sampled_from(["g.png", "g.svg", "g.gif"]))
def test_light_command_resample_and_graphic_options_on_any_grid(tmp_path, capsys, start, step, count, method, graphic):
    grid = start + step * np.arange(count)
    source = tmp_path / "lamp.csv"
    rows = "\n".join(f"{w:.6f},{1.0 + 0.5 * np.sin(w / 40.0):.6f}" for w in grid)
    source.write_text(f"wavelength_nm,lamp\n{rows}\n", encoding="utf-8")
    code = main(["light", str(source), "--out", str(tmp_path / "r.csv"), "--resample", method,
                 "--graphic", str(tmp_path / graphic), "--force"])
    captured = capsys.readouterr()
    assert code in (0, 2)
    if code == 2:
        assert captured.err.startswith("spectrocolor light: error:") and captured.err.count("\n") == 1
    else:
        assert (tmp_path / "r.csv").exists() and graphic != "g.gif"
