"""Count the exact boundary colours that the smoothest-reflectance solver leaves flagged.

Usage: ``OPENBLAS_NUM_THREADS=1 .venv/bin/python tools/recovery_flagged.py [--sample-1nm]``

The sets are those of issue 10: every reflectance with at most two 0/1 transitions (blocks and
their complements: colours on the boundary of the object-colour solid, many on degenerate
facets) on 380–780 nm at 10 nm under D65 and A and at 5 nm under D65; the single-sample spike
and notch at either end on 380–780/20 nm under E and D65; and, with ``bounds="nonnegative"``
on 380–780/5 nm, every single-wavelength line and every reflectance zero below a cut; with
``--sample-1nm`` also 200 random blocks with an edge at 530–780 nm on 380–780/1 nm under D65
(about 5 more minutes).

The last columns count the colours that only the exact rational solver settled (method
``"boundary face, exact rational arithmetic"``) and the time of each call of that solver
(mean and largest, seconds per colour; calls that gave up included).
"""

from __future__ import annotations

import sys
import time

import numpy as np

import spectrocolor as sc
from spectrocolor.recovery import smoothest
from spectrocolor.recovery.smoothest import EXACT_METHOD, smoothest_reflectance

#: Seconds of each call of the exact solver during one ``count`` (see ``timed``).
CALLS: list[float] = []


def timed(solve):
    """``solve`` (the exact solver that the smoothest module calls) with each call's time noted."""
    def run(*args, **kwargs):
        t = time.perf_counter()
        try:
            return solve(*args, **kwargs)
        finally:
            CALLS.append(time.perf_counter() - t)
    return run


def blocks(K: int) -> np.ndarray:
    """Every 0/1 spectrum with at most two transitions, except black and white."""
    out = []
    for i in range(K):
        for j in range(i, K):
            r = np.zeros(K)
            r[i:j + 1] = 1.0
            out += [r, 1.0 - r]
    out = np.unique(np.array(out), axis=0)
    return out[(out.sum(axis=1) > 0) & (out.sum(axis=1) < K)]


def ends(K: int) -> np.ndarray:
    R = np.zeros((4, K))
    R[0, 0] = R[1, -1] = 1.0
    R[2], R[3] = 1.0 - R[0], 1.0 - R[1]
    return R


def lines_and_cuts(K: int) -> np.ndarray:
    eye = np.eye(K)
    cuts = np.tril(np.ones((K, K)))[1:]  # zero below sample k, one from k on
    return np.concatenate([eye, cuts[:, ::-1]])


def red_edge_sample(K: int, n: int = 200, seed: int = 3) -> np.ndarray:
    """``n`` random blocks (half of them complemented) with their first edge in the last 250
    samples: on 380–780/1 nm, an edge at 530–780 nm (all 160 000 blocks would take hours)."""
    rng = np.random.default_rng(seed)
    out = []
    for _ in range(n):
        i = rng.integers(K - 251, K)
        j = rng.integers(i, K)
        r = np.zeros(K)
        r[i:j + 1] = 1.0
        if rng.random() < 0.5:
            r = 1.0 - r
        if 0 < r.sum() < K:
            out.append(r)
    return np.array(out)


def count(name, grid, illuminant, R, bounds="unit"):
    W = np.asarray(sc.weights(sc.wavelength_grid(*grid), observer="1931", illuminant=illuminant))
    CALLS.clear()
    t = time.perf_counter()
    r = smoothest_reflectance(R @ W, illuminant=illuminant, wavelengths=grid, bounds=bounds)
    seconds = time.perf_counter() - t
    flagged = ~r.certificate.converged
    methods = {str(m): int(np.count_nonzero(flagged & (r.method == m))) for m in np.unique(r.method)}
    calls = f"{np.mean(CALLS):.2f} / {np.max(CALLS):.2f} s" if CALLS else "–"
    print(f"| {name} | {flagged.sum()} of {len(R)} | {np.count_nonzero(~r.feasible)} | "
          f"{ {k: v for k, v in methods.items() if v} } | {seconds:.1f} s | "
          f"{np.count_nonzero(r.method == EXACT_METHOD)} | {len(CALLS)} | {calls} |")
    return r


def main():
    smoothest.exact.exact_solution = timed(smoothest.exact.exact_solution)
    print("| set | flagged | infeasible | flagged by method | time | solved exactly | exact calls "
          "| per call, mean / max |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- |")
    for grid, ill in [((380.0, 780.0, 10.0), "D65"), ((380.0, 780.0, 10.0), "A"),
                      ((400.0, 700.0, 10.0), "E"), ((400.0, 700.0, 10.0), "D65"),
                      ((380.0, 780.0, 5.0), "D65")]:
        K = len(sc.wavelength_grid(*grid))
        count(f"blocks {grid[0]:g}–{grid[1]:g}/{grid[2]:g} {ill}", grid, ill, blocks(K))
    for ill in ("E", "D65"):
        count(f"end spikes/notches 380–780/20 {ill}", (380.0, 780.0, 20.0), ill, ends(21))
    count("lines and cuts 380–780/5 D65, nonnegative", (380.0, 780.0, 5.0), "D65",
          lines_and_cuts(81), bounds="nonnegative")
    if "--sample-1nm" in sys.argv[1:]:
        count("200 red-edge blocks 380–780/1 D65", (380.0, 780.0, 1.0), "D65", red_edge_sample(401))


if __name__ == "__main__":
    main()
