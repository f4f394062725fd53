"""Colours per second of the smoothest-reflectance solvers (run by hand, one run).

sRGB cube every 5th level (52³ = 140 608 colours), D65, CIE 1931, 380–780 nm at 10 and
5 nm: unbounded (closed form) and unit-bounded (exact active set), the plain NumPy floor
(one matrix product), colours at relative depth 1e-9 inside the object-colour solid, vs
colour-science's ``XYZ_to_sd`` (Meng 2015, SLSQP, ρ ≥ 0 only) on a few colours.

The solvers run compiled where numba is installed (extra ``fast``; one thread) and on the
NumPy path otherwise or with ``SPECTROCOLOR_NUMBA=0``; the first line says which, and with the
kernels the bounded 10 nm case is timed on the NumPy path too. Run with
``OPENBLAS_NUM_THREADS=1`` so that the NumPy limit is one thread as well.
"""

import os
import time

import numpy as np

import spectrocolor as sc
from spectrocolor.recovery import compiled
from spectrocolor.recovery.inputs import setup_for


def srgb_cube(white):
    levels = np.arange(0, 256, 5) / 255
    rgb = np.stack(np.meshgrid(levels, levels, levels, indexing="ij"), -1).reshape(-1, 3)
    space = sc.rgb_space("sRGB")
    linear = space.transfer.decode(rgb)
    M = np.asarray(space.matrix_to_XYZ)
    M = M * (white / M.sum(axis=1))[:, None]  # display white -> perfect reflector
    return linear @ M.T


def near_boundary(grid, n, depth):
    """Colours at relative depth ``depth`` inside the solid, towards random vertices."""
    W = np.asarray(sc.weights(sc.wavelength_grid(*grid), observer="1931", illuminant="D65"))
    rho = (np.random.default_rng(0).normal(size=(n, 3)) @ W.T > 0).astype(float)
    centre = W.sum(axis=0) / 2
    return centre + (rho @ W - centre) * (1 - depth)


def main():
    kernels = compiled.kernels() is not None
    print("solver path:", "compiled kernels (numba, one thread)" if kernels else "NumPy")
    rates = {}
    for step in (10.0, 5.0):
        grid = (380.0, 780.0, step)
        white = np.asarray(sc.weights(sc.wavelength_grid(*grid), observer="1931", illuminant="D65")).sum(axis=0)
        XYZ = srgb_cube(white)
        for bounds in (None, "unit"):
            sc.smoothest_reflectance(XYZ[:100], wavelengths=grid, bounds=bounds)  # warm caches
            dt = np.inf
            for _ in range(3):  # best of three: the machine is shared
                t = time.perf_counter()
                r = sc.smoothest_reflectance(XYZ, wavelengths=grid, bounds=bounds)
                dt = min(dt, time.perf_counter() - t)
            rates[(step, bounds)] = len(XYZ) / dt
            print(f"{step:>4g} nm  bounds={bounds!s:5}  {len(XYZ)} colours in {dt:.2f} s = "
                  f"{len(XYZ) / dt:,.0f} colours/s  (feasible {r.feasible.mean():.4%}, converged "
                  f"{r.certificate.converged[r.feasible].mean():.4%})")
        U = setup_for(grid, "1931", "D65")[0].problem.unconstrained
        dt = np.inf
        for _ in range(3):
            t = time.perf_counter()
            XYZ @ U
            dt = min(dt, time.perf_counter() - t)
        print(f"{step:>4g} nm  plain NumPy limit (XYZ @ U only): {len(XYZ) / dt:,.0f} colours/s; "
              f"certified closed form is {len(XYZ) / dt / rates[(step, None)]:.1f}x slower, "
              f"unit-bounded {len(XYZ) / dt / rates[(step, 'unit')]:.1f}x slower")
        near = near_boundary(grid, 20000, 1e-9)
        sc.smoothest_reflectance(near[:100], wavelengths=grid)
        dt = np.inf
        for _ in range(3):
            t = time.perf_counter()
            r = sc.smoothest_reflectance(near, wavelengths=grid)
            dt = min(dt, time.perf_counter() - t)
        print(f"{step:>4g} nm  bounds=unit  {len(near)} colours at relative depth 1e-9: "
              f"{len(near) / dt:,.0f} colours/s, converged {r.certificate.converged.mean():.4%}, "
              f"max residual {r.certificate.primal_residual.max():.1e}")
    if kernels:
        grid = (380.0, 780.0, 10.0)
        white = np.asarray(sc.weights(sc.wavelength_grid(*grid), observer="1931", illuminant="D65")).sum(axis=0)
        XYZ = srgb_cube(white)
        os.environ["SPECTROCOLOR_NUMBA"] = "0"
        t = time.perf_counter()
        sc.smoothest_reflectance(XYZ, wavelengths=grid)
        dt = time.perf_counter() - t
        del os.environ["SPECTROCOLOR_NUMBA"]
        print(f"  10 nm  bounds=unit  NumPy path: {len(XYZ) / dt:,.0f} colours/s; the kernels are "
              f"{rates[(10.0, 'unit')] * dt / len(XYZ):.1f}x faster")
    import colour

    shape = colour.SpectralShape(380, 780, 10)
    W10 = np.asarray(sc.weights(sc.wavelength_grid(380, 780, 10), observer="1931", illuminant="D65"))
    sample = srgb_cube(W10.sum(0))
    sample = sample[[1000, 50000, 90000]] / 100
    t = time.perf_counter()
    for xyz in sample:
        colour.XYZ_to_sd(xyz, method="Meng 2015", shape=shape)
    dt = (time.perf_counter() - t) / len(sample)
    print(f"colour-science XYZ_to_sd (Meng 2015, 10 nm): {dt:.3f} s/colour = {1 / dt:.2f} colours/s")
    print(f"ratio unit-bounded 10 nm / colour-science: {rates[(10.0, 'unit')] * dt:,.0f}x")


if __name__ == "__main__":
    main()
