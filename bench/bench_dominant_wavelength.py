"""Dominant wavelength of 100 000 chromaticities: spectrocolor vs colour-science 0.4.7.

colour-science builds (points x locus-segments) intersection arrays, so it is timed on a
subset and scaled linearly; spectrocolor runs on all points. Also prints peak memory of ours.
Run: .venv/bin/python bench/bench_dominant_wavelength.py
"""

from __future__ import annotations

import tracemalloc

import colour
import numpy as np

import spectrocolor as sc
from timing import best_of

N, SUBSET = 100_000, 2_000
WHITE = np.array([0.3127, 0.3290])


def main() -> None:
    rng = np.random.default_rng(0)
    points = rng.uniform([0.05, 0.05], [0.7, 0.8], (N, 2))
    sc.dominant_wavelength(points[:10], WHITE)  # build the cached locus
    ours = best_of(lambda: sc.dominant_wavelength(points, WHITE))
    cmfs = colour.MSDS_CMFS["CIE 1931 2 Degree Standard Observer"]
    theirs_subset = best_of(lambda: colour.dominant_wavelength(points[:SUBSET], WHITE, cmfs), 1)
    theirs = theirs_subset * N / SUBSET
    tracemalloc.start()
    sc.dominant_wavelength(points, WHITE)
    peak = tracemalloc.get_traced_memory()[1]
    tracemalloc.stop()
    # a plain NumPy floor: one arctan2 + searchsorted over the same points
    angles = np.sort(rng.uniform(-np.pi, np.pi, 340))
    floor = best_of(lambda: np.searchsorted(angles, np.arctan2(points[:, 1], points[:, 0])))
    print(f"points: {N}")
    print(f"spectrocolor      : {ours * 1e3:8.1f} ms  (peak {peak / 2**20:.1f} MiB, "
          f"{peak / N:.0f} B/point)")
    print(f"colour-science    : {theirs * 1e3:8.1f} ms  (measured on {SUBSET}, scaled)")
    print(f"numpy floor       : {floor * 1e3:8.1f} ms  (arctan2 + searchsorted only)")
    print(f"speed-up vs colour: {theirs / ours:8.1f}x")
    print(f"ours / floor      : {ours / floor:8.1f}x")


if __name__ == "__main__":
    main()
