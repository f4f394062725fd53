"""The recovery's grid limit: a grid too fine for the solver's K² memory gets one clear error,
from every entry point, before anything of size K² is allocated (issue 12, bounded resources)."""

from __future__ import annotations

import subprocess
import sys
import tracemalloc

import numpy as np
import pytest

import spectrocolor as sc
from spectrocolor.errors import ColorimetryError
from spectrocolor.recovery.inputs import MAX_SAMPLES, setup_for

TOO_FINE = (360.0, 830.0, 0.01)  # 47 001 samples: the K x K solver matrices alone would be 17.7 GB


def test_the_largest_grid_is_accepted_and_one_more_sample_is_refused():
    start, step = 380.0, 0.2
    setup, _, _ = setup_for((start, start + step * (MAX_SAMPLES - 1), step), "1931", "D65")
    assert setup.W.shape == (MAX_SAMPLES, 3)
    with pytest.raises(ColorimetryError, match=rf"wavelengths: {MAX_SAMPLES + 1} samples .* at most {MAX_SAMPLES}"):
        setup_for((start, start + step * MAX_SAMPLES, step), "1931", "D65")


@pytest.mark.parametrize("call", [
    lambda: sc.smoothest_reflectance([20.0, 21.0, 22.0], wavelengths=TOO_FINE),
    lambda: sc.smoothest_reflectance([[20.0, 21.0, 22.0]] * 4, wavelengths=TOO_FINE, bounds="nonnegative"),
    lambda: sc.optimal_colours(wavelengths=TOO_FINE),
    lambda: sc.macadam_limits(50.0, wavelengths=TOO_FINE),
    lambda: sc.smoothest_reflectance([20.0, 21.0, 22.0], wavelengths=np.arange(360.0, 830.001, 0.1)),
], ids=["unit", "nonnegative", "optimal_colours", "macadam_limits", "array grid"])
def test_every_entry_point_refuses_a_too_fine_grid_cheaply(call):
    tracemalloc.start()
    try:
        with pytest.raises(ColorimetryError, match=r"^wavelengths: \d+ samples .* at most 2001"):
            call()
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert peak < 64 * 2**20  # the refusal comes before any K x K work (47 001² doubles = 17.7 GB)


def test_the_command_line_says_it_in_one_line(tmp_path):
    result = subprocess.run(
        [sys.executable, "-m", "spectrocolor", "recover", "--xyz", "20", "21", "22", "--range",
         "360", "830", "0.01", "--out", str(tmp_path / "r.csv")],
        capture_output=True, text=True, timeout=120)
    assert result.returncode == 2, result.stderr
    assert "Traceback" not in result.stderr and len(result.stderr.strip().splitlines()) == 1
    assert "at most 2001" in result.stderr and not (tmp_path / "r.csv").exists()
