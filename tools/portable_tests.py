"""Run the numerical tests again under other BLAS kernels and SIMD choices (``make test-portable``).

A test suite that passes only on the CPU it was written on is a suite that fails for the next user.
OpenBLAS picks a kernel for the CPU it finds (SkylakeX on AVX-512 machines, Haswell on AVX2, …) and
NumPy dispatches its loops to the widest SIMD the CPU has; each choice changes the order, and so the
rounding, of sums.  This script re-runs the numerical part of the suite under choices that are safe
on any x86-64 machine, each with one BLAS thread, and prints the kernel each run actually used, so a
comparison of two different computations bit for bit fails here instead of on a user's machine.

The configurations:

``prescott``
    ``OPENBLAS_CORETYPE=Prescott``: OpenBLAS's SSE3 kernels, which every x86-64 CPU runs.
``haswell``
    ``OPENBLAS_CORETYPE=Haswell``: the AVX2/FMA kernels; only where the CPU has AVX2 and FMA.
``numpy-baseline``
    ``NPY_DISABLE_CPU_FEATURES`` set to every SIMD target NumPy dispatches to and this CPU has
    (AVX2/AVX-512 loops off), so NumPy runs its baseline loops; only where there is such a target.

What is left out of the repeats, and why: the browser tests (the page computes in JavaScript, which
no BLAS or NumPy switch reaches, and they take a third of the suite's time), the tests that start a
dask cluster (the cluster's workers compute with the same functions that the image tests repeat in
one process), and the fuzz suites (they check that hostile input gets a clear error, not digits).

Examples
--------
>>> [c.name for c in configurations(cpu_flags={"avx2", "fma"}, numpy_dispatch_available=["X86_V3"])]
['prescott', 'haswell', 'numpy-baseline']
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import subprocess
import sys
import time
from dataclasses import dataclass, field
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]

#: pytest selection of the repeat runs (see the module docstring for what is left out and why).
MARKERS = "not browser and not cluster"
IGNORED_GLOBS = ("tests/fuzz/*",)


@dataclass(frozen=True)
class Configuration:
    """One repeat run: a name, the environment it adds and why it differs from the default run."""

    name: str
    environment: dict[str, str] = field(default_factory=dict)
    purpose: str = ""


def cpu_flags() -> set[str]:
    """The CPU's feature flags from ``/proc/cpuinfo`` (empty where there is none, e.g. macOS)."""
    try:
        text = Path("/proc/cpuinfo").read_text(errors="replace")
    except OSError:
        return set()
    for line in text.splitlines():
        if line.startswith("flags"):
            return set(line.split(":", 1)[1].split())
    return set()


def numpy_dispatch_targets_available(python: str) -> list[str]:
    """The SIMD targets NumPy dispatches to that this CPU has, as ``python`` (the venv's) sees them."""
    probe = (
        "import json\n"
        "from numpy._core._multiarray_umath import __cpu_dispatch__, __cpu_features__\n"
        "print(json.dumps([t for t in __cpu_dispatch__ if __cpu_features__.get(t)]))\n"
    )
    result = subprocess.run([python, "-c", probe], capture_output=True, text=True, check=True)
    return json.loads(result.stdout)


def configurations(cpu_flags: set[str], numpy_dispatch_available: list[str]) -> list[Configuration]:
    """The repeat runs this CPU can take (see the module docstring)."""
    single = {"OPENBLAS_NUM_THREADS": "1"}
    runs = [Configuration("prescott", {**single, "OPENBLAS_CORETYPE": "Prescott"}, "OpenBLAS SSE3 kernels")]
    if {"avx2", "fma"} <= cpu_flags:
        runs.append(Configuration("haswell", {**single, "OPENBLAS_CORETYPE": "Haswell"}, "OpenBLAS AVX2/FMA kernels"))
    if numpy_dispatch_available:
        disabled = " ".join(numpy_dispatch_available)
        runs.append(
            Configuration(
                "numpy-baseline",
                {**single, "NPY_DISABLE_CPU_FEATURES": disabled},
                f"NumPy without its {disabled} loops",
            )
        )
    return runs


def blas_kernel(python: str, environment: dict[str, str]) -> str:
    """The BLAS library and kernel the venv's NumPy loads under ``environment`` (via threadpoolctl)."""
    probe = (
        "import numpy, threadpoolctl\n"
        "info = threadpoolctl.threadpool_info()\n"
        "print('; '.join(f\"{i['internal_api']} {i.get('version')} kernel {i.get('architecture')}"
        " threads {i['num_threads']}\" for i in info if i['user_api'] == 'blas'))\n"
    )
    result = subprocess.run(
        [python, "-c", probe], capture_output=True, text=True, env={**os.environ, **environment}, check=True
    )
    return result.stdout.strip()


def pytest_command(python: str, extra: list[str]) -> list[str]:
    """The pytest call of one repeat run: the suite's doctests and tests less what is left out."""
    command = [python, "-m", "pytest", "-q", "-p", "no:cacheprovider", "--doctest-modules", "-m", MARKERS]
    for pattern in IGNORED_GLOBS:
        command += ["--ignore-glob", pattern]
    return command + ["src", "tests", *extra]


def main(argv: list[str] | None = None) -> int:
    """Run every configuration this CPU can take; exit non-zero if any run fails."""
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--python", default=str(REPO / ".venv" / "bin" / "python"), help="the venv's interpreter")
    parser.add_argument("--only", action="append", default=[], help="run only this configuration (repeatable)")
    parser.add_argument("pytest_args", nargs="*", help="extra pytest arguments, after --")
    arguments = parser.parse_args(argv)

    if platform.machine() not in ("x86_64", "AMD64"):
        print(f"portable tests: {platform.machine()} is not x86-64; the kernel names here are x86's, nothing run")
        return 0
    runs = configurations(cpu_flags(), numpy_dispatch_targets_available(arguments.python))
    if arguments.only:
        unknown = set(arguments.only) - {r.name for r in runs}
        if unknown:
            parser.error(f"--only: {sorted(unknown)} not among this CPU's configurations {[r.name for r in runs]}")
        runs = [r for r in runs if r.name in arguments.only]

    print(f"portable tests: default kernel here: {blas_kernel(arguments.python, {})}", flush=True)
    failed = []
    for run in runs:
        settings = " ".join(f"{k}={v}" for k, v in run.environment.items())
        print(f"\n== {run.name}: {run.purpose} ({settings})", flush=True)
        print(f"   kernel: {blas_kernel(arguments.python, run.environment)}", flush=True)
        start = time.monotonic()
        code = subprocess.call(
            pytest_command(arguments.python, arguments.pytest_args), cwd=REPO, env={**os.environ, **run.environment}
        )
        print(f"== {run.name}: exit {code} after {time.monotonic() - start:.0f} s", flush=True)
        if code != 0:
            failed.append(run.name)
    if failed:
        print(f"\nportable tests FAILED under: {', '.join(failed)}")
        return 1
    print(f"\nportable tests passed under: {', '.join(r.name for r in runs)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
