"""Tristimulus throughput on a 512×512×31 cube: spectrocolor vs colour-science vs a bare matmul.

Run: .venv/bin/python bench/bench_colorimetry.py
Prints best-of-N wall times measured in this one run and the ratios the issue asks for
(goal: ≥ 5× faster than colour-science, within 1.3× of the NumPy limit).
"""

from __future__ import annotations

import warnings

import numpy as np

import spectrocolor as sc
from timing import best_of


def main() -> None:
    import colour

    grid = sc.wavelength_grid(400, 700, 10)
    cube = np.random.default_rng(0).random((512, 512, grid.size))
    spectrum = sc.Spectrum(grid, cube)
    W = np.array(sc.weights(grid, observer="1931", illuminant="D65"))  # precomputed: the limit does nothing else

    ours = best_of(lambda: sc.tristimulus(sc.Spectrum(grid, cube), observer="1931", illuminant="D65"))
    limit = best_of(lambda: cube @ W)
    cmfs = colour.MSDS_CMFS["CIE 1931 2 Degree Standard Observer"]
    illuminant = colour.SDS_ILLUMINANTS["D65"]
    shape = colour.SpectralShape(400, 700, 10)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        theirs = best_of(lambda: colour.msds_to_XYZ(cube, cmfs, illuminant, method="Integration", shape=shape), 3)
        agreement = np.abs(
            colour.msds_to_XYZ(cube, cmfs, illuminant, method="Integration", shape=shape)
            - sc.tristimulus(spectrum, observer="1931", illuminant="D65")
        ).max()
    pixels = cube.shape[0] * cube.shape[1]
    print(f"cube 512x512x31 float64, {pixels} spectra")
    print(f"  spectrocolor.tristimulus : {ours * 1e3:8.2f} ms  ({pixels / ours / 1e6:.1f} Mspectra/s)")
    print(f"  bare NumPy cube @ W      : {limit * 1e3:8.2f} ms  (the limit)")
    print(f"  colour.msds_to_XYZ       : {theirs * 1e3:8.2f} ms")
    print(f"  ratio colour / ours      : {theirs / ours:8.1f}x   (goal >= 5x)")
    print(f"  ratio ours / limit       : {ours / limit:8.2f}x   (goal <= 1.3x)")
    print(f"  max |ours - colour|      : {agreement:.2e} (XYZ100)")


if __name__ == "__main__":
    main()
