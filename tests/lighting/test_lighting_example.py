"""The LED mixture design example (docs/examples/led_mixture_design.py) runs, on a small budget."""

from __future__ import annotations

import importlib.util
import sys
from pathlib import Path

import numpy as np
import pytest

from spectrocolor.lighting import colour_fidelity

pytest.importorskip("scipy")


EXAMPLE = Path(__file__).resolve().parents[2] / "docs" / "examples" / "led_mixture_design.py"


def _example():
    spec = importlib.util.spec_from_file_location("led_mixture_design", EXAMPLE)
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module  # dataclasses look their module up there
    try:
        spec.loader.exec_module(module)
    finally:
        del sys.modules[spec.name]
    return module


def test_led_mixture_example_reports_the_metrics_of_the_spectrum_it_returns(tmp_path):
    example = _example()
    best = example.main(["--maxiter", "3", "--seed", "2", "--out", str(tmp_path / "design.png")])
    fidelity = colour_fidelity(best.spectrum)
    assert best.Rf == pytest.approx(float(fidelity.Rf), abs=1e-12)
    assert best.evaluations == 4 * 15 * 8  # initial population + 3 generations, 120 candidates each
    assert all(lo <= peak <= hi for peak, (lo, hi) in zip(best.peaks_nm, example.PEAK_BOUNDS_NM, strict=True))
    assert np.isfinite(best.cct_K) and abs(best.cct_K - 4000) < 1500
    assert (tmp_path / "design.png").stat().st_size > 10_000
