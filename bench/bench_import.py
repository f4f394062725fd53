"""Cold `import spectrocolor` time, each measured in a fresh interpreter. Goal: under 0.3 s.

Run: .venv/bin/python bench/bench_import.py [--repeats 5]
The three imports (spectrocolor; spectrocolor and the first use of its core; NumPy alone, the
floor) are measured in turn, round after round, best of N each (an import is cold by nature:
each round starts new interpreters). The figures are recorded in the results file
(bench/results.py).
"""

from __future__ import annotations

import argparse
import subprocess
import sys
from pathlib import Path

from results import figure, ratio, record
from timing import alternate_min, clock_choice, clock_name

#: What each fresh interpreter times, between two readings of the clock.
IMPORTS = {
    "import": "import spectrocolor",
    "core": "import spectrocolor as sc; sc.tristimulus; sc.xy; sc.dominant_wavelength; sc.render",
    "numpy": "import numpy",
}


def reported_seconds(statement: str) -> float:
    """The seconds a fresh interpreter takes to run ``statement``, on the bench's clock, as it
    reports them (CPU time by default: see timing.py)."""
    clock = "process_time" if clock_choice() == "cpu" else "perf_counter"
    code = f"import time; t = time.{clock}(); {statement}; print(time.{clock}() - t)"
    return float(subprocess.check_output([sys.executable, "-c", code]))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=5, help="rounds of fresh interpreters, best of them")
    args = parser.parse_args()
    best = alternate_min({name: (lambda statement=statement: reported_seconds(statement))
                          for name, statement in IMPORTS.items()}, repeats=args.repeats)
    ours, core, numpy_only = best["import"], best["core"], best["numpy"]
    print(f"best of {args.repeats} fresh interpreters each, in turn, {clock_name()}")
    print(f"import spectrocolor            : {ours * 1e3:6.1f} ms (public names load lazily)")
    print(f"  + tristimulus, xy, dominant_wavelength, render: {core * 1e3:6.1f} ms (goal < 300 ms)")
    print(f"numpy alone                    : {numpy_only * 1e3:6.1f} ms")
    record("import", "`import spectrocolor` + first use of the core, fresh interpreter", [
        figure("core_ms", core * 1e3, "ours", "{} ms"),
        figure("import_ms", ours * 1e3, "ours", "the import alone {} ms"),
        ratio("core_over_numpy", core / numpy_only, "limit", "{}× the time of `import numpy`"),
        figure("numpy_ms", numpy_only * 1e3, "limit", "`import numpy` {} ms"),
    ], script=Path(__file__).name)


if __name__ == "__main__":
    main()
