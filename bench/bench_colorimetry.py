"""Tristimulus throughput on a 512×512×31 cube: spectrocolor vs colour-science vs a bare matmul.

Run: .venv/bin/python bench/bench_colorimetry.py [--repeats 5] [--burst 0.2]
The three are timed alternately in this one process, warm, best of N each; prints the ratios
(goal: ≥ 5× faster than colour-science, within 1.3× of the NumPy limit) and records them in the
results file (bench/results.py).
"""

from __future__ import annotations

import argparse
import warnings
from pathlib import Path

import numpy as np

import spectrocolor as sc
from results import figure, ratio, record
from timing import add_arguments, alternate_best, clock_name

SIZE = 512


def main() -> None:
    import colour

    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    add_arguments(parser)
    args = parser.parse_args()

    grid = sc.wavelength_grid(400, 700, 10)
    cube = np.random.default_rng(0).random((SIZE, SIZE, grid.size))
    W = np.array(sc.weights(grid, observer="1931", illuminant="D65"))  # precomputed: the limit does nothing else
    cmfs = colour.MSDS_CMFS["CIE 1931 2 Degree Standard Observer"]
    illuminant = colour.SDS_ILLUMINANTS["D65"]
    shape = colour.SpectralShape(400, 700, 10)

    def theirs():
        return colour.msds_to_XYZ(cube, cmfs, illuminant, method="Integration", shape=shape)

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        best = alternate_best({
            "ours": lambda: sc.tristimulus(sc.Spectrum(grid, cube), observer="1931", illuminant="D65"),
            "colour-science": theirs,
            "limit": lambda: cube @ W,
        }, repeats=args.repeats, burst=args.burst)
        agreement = np.abs(theirs() - sc.tristimulus(sc.Spectrum(grid, cube), observer="1931",
                                                     illuminant="D65")).max()
    ours, limit, colour_time = best["ours"], best["limit"], best["colour-science"]
    pixels = SIZE * SIZE
    print(f"cube {SIZE}x{SIZE}x31 float64, {pixels} spectra; warm, best of {args.repeats}, timed alternately, "
          f"{clock_name()}")
    print(f"  spectrocolor.tristimulus : {ours * 1e3:8.2f} ms  ({pixels / ours / 1e6:.1f} Mspectra/s)")
    print(f"  bare NumPy cube @ W      : {limit * 1e3:8.2f} ms  (the limit)")
    print(f"  colour.msds_to_XYZ       : {colour_time * 1e3:8.2f} ms")
    print(f"  ratio colour / ours      : {colour_time / ours:8.1f}x   (goal >= 5x)")
    print(f"  ratio ours / limit       : {ours / limit:8.2f}x   (goal <= 1.3x)")
    print(f"  max |ours - colour|      : {agreement:.2e} (XYZ100)")
    record("colorimetry", f"XYZ of a {SIZE} × {SIZE} × 31 float64 cube", [
        figure("ours_ms", ours * 1e3, "ours", "{} ms"),
        ratio("colour_over_ours", colour_time / ours, "colour-science", "{}× slower"),
        figure("colour_ms", colour_time * 1e3, "colour-science", "{} ms"),
        ratio("ours_over_limit", ours / limit, "limit", "ours {}× its time"),
        figure("limit_ms", limit * 1e3, "limit", "{} ms (`cube @ W`)"),
    ], script=Path(__file__).name)


if __name__ == "__main__":
    main()
