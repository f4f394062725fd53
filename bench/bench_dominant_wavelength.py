"""Dominant wavelength of 100 000 chromaticities: spectrocolor vs colour-science 0.4.7.

colour-science builds (points x locus-segments) intersection arrays, so it is timed on a
subset and scaled linearly; spectrocolor runs on all points. spectrocolor, colour-science and a
plain NumPy floor are timed alternately in this one process, warm, best of N each. Also prints
peak memory of ours, and records the figures in the results file (bench/results.py).
Run: .venv/bin/python bench/bench_dominant_wavelength.py [--repeats 5] [--burst 0.2]
"""

from __future__ import annotations

import argparse
import tracemalloc
from pathlib import Path

import colour
import numpy as np

import spectrocolor as sc
from results import figure, ratio, record
from timing import add_arguments, alternate_best, clock_name

N, SUBSET = 100_000, 2_000
WHITE = np.array([0.3127, 0.3290])


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    add_arguments(parser)
    args = parser.parse_args()

    rng = np.random.default_rng(0)
    points = rng.uniform([0.05, 0.05], [0.7, 0.8], (N, 2))
    cmfs = colour.MSDS_CMFS["CIE 1931 2 Degree Standard Observer"]
    # a plain NumPy floor: one arctan2 + searchsorted over the same points
    angles = np.sort(rng.uniform(-np.pi, np.pi, 340))
    best = alternate_best({
        "ours": lambda: sc.dominant_wavelength(points, WHITE),
        "colour-science": lambda: colour.dominant_wavelength(points[:SUBSET], WHITE, cmfs),
        "limit": lambda: np.searchsorted(angles, np.arctan2(points[:, 1], points[:, 0])),
    }, repeats=args.repeats, burst=args.burst)
    ours, floor = best["ours"], best["limit"]
    theirs = best["colour-science"] * N / SUBSET
    tracemalloc.start()
    sc.dominant_wavelength(points, WHITE)
    peak = tracemalloc.get_traced_memory()[1]
    tracemalloc.stop()
    print(f"points: {N}; warm, best of {args.repeats}, timed alternately, {clock_name()}")
    print(f"spectrocolor      : {ours * 1e3:8.1f} ms  (peak {peak / 2**20:.1f} MiB, "
          f"{peak / N:.0f} B/point)")
    print(f"colour-science    : {theirs * 1e3:8.1f} ms  (measured on {SUBSET}, scaled)")
    print(f"numpy floor       : {floor * 1e3:8.1f} ms  (arctan2 + searchsorted only)")
    print(f"speed-up vs colour: {theirs / ours:8.1f}x")
    print(f"ours / floor      : {ours / floor:8.1f}x")
    record("dominant_wavelength", f"dominant wavelength, {N:_} points".replace("_", " "), [
        figure("ours_ms", ours * 1e3, "ours", "{} ms"),
        figure("peak_mib", peak / 2**20, "ours", "peak {} MiB"),
        ratio("colour_over_ours", theirs / ours, "colour-science", "{}× slower"),
        figure("colour_ms", theirs * 1e3, "colour-science", f"{{}} ms (timed on {SUBSET:_}, scaled)".replace("_", " ")),
        ratio("ours_over_limit", ours / floor, "limit", "ours {}× its time"),
        figure("limit_ms", floor * 1e3, "limit", "{} ms (arctan2 + searchsorted)"),
    ], script=Path(__file__).name)


if __name__ == "__main__":
    main()
