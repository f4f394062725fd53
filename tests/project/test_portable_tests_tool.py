"""The repeat runs of ``make test-portable``: which configurations a CPU gets and what they run."""

from __future__ import annotations

import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "tools"))
import portable_tests  # noqa: E402


def test_every_x86_cpu_gets_the_prescott_kernel_with_one_thread():
    runs = portable_tests.configurations(cpu_flags=set(), numpy_dispatch_available=[])
    assert [r.name for r in runs] == ["prescott"]
    assert runs[0].environment == {"OPENBLAS_NUM_THREADS": "1", "OPENBLAS_CORETYPE": "Prescott"}


def test_haswell_only_where_the_cpu_has_avx2_and_fma():
    assert "haswell" not in [r.name for r in portable_tests.configurations({"avx2"}, [])]
    assert "haswell" in [r.name for r in portable_tests.configurations({"avx2", "fma"}, [])]


def test_numpy_baseline_turns_off_exactly_the_dispatched_targets_the_cpu_has():
    runs = portable_tests.configurations({"avx2", "fma"}, ["X86_V3", "X86_V4"])
    baseline = {r.name: r for r in runs}["numpy-baseline"]
    assert baseline.environment["NPY_DISABLE_CPU_FEATURES"] == "X86_V3 X86_V4"
    assert baseline.environment["OPENBLAS_NUM_THREADS"] == "1"


def test_the_repeats_leave_out_browser_cluster_and_fuzz_tests_and_keep_the_doctests():
    command = portable_tests.pytest_command("python", ["-x"])
    assert command[command.index(portable_tests.MARKERS) - 1] == "-m"
    assert portable_tests.MARKERS == "not browser and not cluster"
    assert "tests/fuzz/*" in command
    assert "--doctest-modules" in command
    assert command[-3:] == ["src", "tests", "-x"]


@pytest.mark.skipif(
    not {"avx2", "fma"} <= portable_tests.cpu_flags(), reason="compares the Prescott and Haswell kernels"
)
def test_the_kernel_probe_reports_the_kernel_that_was_asked_for():
    prescott = portable_tests.blas_kernel(sys.executable, {"OPENBLAS_CORETYPE": "Prescott"})
    haswell = portable_tests.blas_kernel(sys.executable, {"OPENBLAS_CORETYPE": "Haswell"})
    assert "openblas" in prescott
    assert "kernel Haswell" in haswell
    assert prescott != haswell
