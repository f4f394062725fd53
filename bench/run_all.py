"""Run every bench script that feeds the README's speed table, twice, into one results file.

Run: .venv/bin/python bench/run_all.py [--output bench/results.json] [--passes 2] [--only SCRIPT ...]
(``make bench`` runs this, then ``tools/speed_table.py`` to regenerate the README's table.)

A fresh results file is started (machine, CPU, threads, versions, git commit, date), then pass 1
runs every script in ``SCRIPTS`` one after the other, then pass 2 runs them all again: two
complete passes, so that a figure that does not reproduce shows as such. Each script runs in its
own interpreter with ``SPECTROCOLOR_BENCH_RESULTS`` and ``SPECTROCOLOR_BENCH_RUN`` set, and the
load average before and after it is recorded. ``OPENBLAS_NUM_THREADS`` and ``NUMBA_NUM_THREADS``
are 1 unless set, and the clock is the process's CPU time unless ``SPECTROCOLOR_BENCH_CLOCK=wall``
(see timing.py): the bare-NumPy limits and our code then run on one thread alike, and the figures
depend little on what else the machine runs. ``--only`` re-runs some scripts into the existing
file (both passes), keeping the other scripts' figures.
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import time
from pathlib import Path

import results
from timing import CLOCK_ENV

BENCH = Path(__file__).resolve().parent
#: The scripts of the README's table and the arguments ``make bench`` gives them: sizes that keep
#: two passes within about ten minutes on two shared cores (each script says what it measures).
SCRIPTS: tuple[tuple[str, tuple[str, ...]], ...] = (
    ("bench_colorimetry.py", ()),
    ("bench_images.py", ("--size", "1024", "--no-dask")),
    ("bench_dominant_wavelength.py", ()),
    ("bench_astm_e308.py", ("--speed-only",)),
    ("bench_thinfilm.py", ()),
    ("bench_reflectance.py", ()),
    ("bench_upsampling.py", ("--apply-only",)),
    ("bench_light.py", ()),
    ("bench_import.py", ()),
)


def run_script(script: str, arguments: tuple[str, ...], run: int, output: Path) -> int:
    """Run one bench script in pass ``run``, recording its duration and the load around it."""
    environment = dict(os.environ, **{results.RESULTS_ENV: str(output), results.RUN_ENV: str(run)})
    print(f"== pass {run}: {script} {' '.join(arguments)}", flush=True)
    load_before = results.load_average()
    start = time.perf_counter()
    done = subprocess.run([sys.executable, str(BENCH / script), *arguments], env=environment, cwd=BENCH.parent)
    seconds = time.perf_counter() - start
    results.note_script(script, seconds, done.returncode, load_before, results.load_average(),
                        path=output, run=run)
    return done.returncode


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--output", type=Path, default=results.COMMITTED_PATH)
    parser.add_argument("--passes", type=int, default=2)
    parser.add_argument("--only", nargs="+", choices=[name for name, _ in SCRIPTS], metavar="SCRIPT")
    args = parser.parse_args(argv)
    for variable, value in (("OPENBLAS_NUM_THREADS", "1"), ("NUMBA_NUM_THREADS", "1"), (CLOCK_ENV, "cpu")):
        os.environ.setdefault(variable, value)
    chosen = [(name, arguments) for name, arguments in SCRIPTS if not args.only or name in args.only]
    if not args.only:
        results.start(args.output)
    started = time.perf_counter()
    for run in range(1, args.passes + 1):
        if not args.only:
            results.begin_pass(run, args.output)
        for name, arguments in chosen:
            if run_script(name, arguments, run, args.output) != 0:
                print(f"{name} failed in pass {run}; results so far in {args.output}", file=sys.stderr)
                return 1
    print(f"{args.passes} passes of {len(chosen)} scripts in {time.perf_counter() - started:.0f} s; "
          f"results in {args.output}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
