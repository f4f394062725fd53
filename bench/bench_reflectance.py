"""Colours per second of the smoothest-reflectance solvers.

Run: OPENBLAS_NUM_THREADS=1 .venv/bin/python bench/bench_reflectance.py [--repeats 3] [--burst 0.2] [--meng 1]

sRGB cube every 5th level (52³ = 140 608 colours), D65, CIE 1931, 380–780 nm at 10 and 5 nm:
unbounded (closed form) and unit-bounded (exact active set), the plain NumPy floor (one matrix
product ``XYZ @ U``), colours at relative depth 1e-9 inside the object-colour solid (random
directions), and at 10 nm the solid's vertices (every 0/1 reflectance with two transitions at grid
points, 1 720 colours) and edges (a band whose next sample is partial, 1 640 colours), each pulled
toward grey by relative depth 1e-9 and 1e-3, timed alternately in this one process, warm, best of
N each; narrow-band colours (Gaussian reflectances, FWHM 5-15 nm) at 1 nm under the 1931 and the
1964 observer, seconds per colour; then colour-science's ``XYZ_to_sd``
(Meng 2015, SLSQP, ρ ≥ 0 only, seconds per colour) alternately with ours on the same cube, on
``--meng`` colours per call (best of two: it takes seconds per colour).

The solvers run compiled where numba is installed (extra ``fast``; one thread) and on the
NumPy path otherwise or with ``SPECTROCOLOR_NUMBA=0``; the first line says which, and with the
kernels the bounded 10 nm case is timed on the NumPy path too (on every 4th colour of the cube).
Run with ``OPENBLAS_NUM_THREADS=1`` so that the NumPy limit is one thread as well. The figures
are recorded in the results file (bench/results.py).
"""

from __future__ import annotations

import argparse
import os
from pathlib import Path

import numpy as np

import spectrocolor as sc
from results import figure, ratio, record
from spectrocolor.recovery import compiled
from spectrocolor.recovery.inputs import setup_for
from timing import add_arguments, alternate_best, clock_name

MENG_COLOURS = (1000, 50000)  # indices into the cube; SLSQP takes 2-7 s per colour


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


def _pulled_in(W, rho, depth):
    """The colours of reflectances ``rho`` moved toward the grey ``W.sum(0) / 2`` by ``depth``."""
    centre = W.sum(axis=0) / 2
    return centre + (rho @ W - centre) * (1 - depth)


def vertex_set(grid, depth):
    """Every 0/1 reflectance with two transitions at grid points (a band and its complement:
    the optimal colours, vertices of the discrete solid), at relative depth ``depth``."""
    W = np.asarray(sc.weights(sc.wavelength_grid(*grid), observer="1931", illuminant="D65"))
    K = len(W)
    i, j = np.triu_indices(K + 1, 1)
    keep = (j - i) < K  # not the white
    k = np.arange(K)
    band = ((k >= i[keep, None]) & (k < j[keep, None])).astype(float)
    return _pulled_in(W, np.concatenate([band, 1 - band]), depth)


def edge_set(grid, depth, seed=0):
    """Points on the solid's edges between two adjacent vertices (a band whose first sample
    past its end takes a value in (0.05, 0.95), and the complement), at relative depth
    ``depth``."""
    W = np.asarray(sc.weights(sc.wavelength_grid(*grid), observer="1931", illuminant="D65"))
    K = len(W)
    i, j = np.triu_indices(K, 1)
    k = np.arange(K)
    band = ((k >= i[:, None]) & (k < j[:, None])).astype(float)
    band[np.arange(len(j)), j] = np.random.default_rng(seed).uniform(0.05, 0.95, len(j))
    return _pulled_in(W, np.concatenate([band, 1 - band]), depth)


PLURAL = {"vertex": "vertices", "edge": "edges"}
#: Narrow-band reflectances (Gaussian): centre nm and full width at half maximum nm.
NARROW_BANDS = ((450.0, 5.0), (520.0, 10.0), (560.0, 5.0), (600.0, 15.0), (650.0, 10.0), (700.0, 5.0))


def narrow_band_seconds(observer: str) -> tuple[float, float]:
    """Worst and median seconds per narrow-band colour at 1 nm (380–780 nm) under ``observer``,
    warm (each colour solved twice, the second timed), and whether all were certified."""
    import time

    grid = (380.0, 780.0, 1.0)
    lam = np.asarray(sc.wavelength_grid(*grid))
    W = np.asarray(sc.weights(lam, observer=observer, illuminant="D65"))
    sc.smoothest_reflectance(0.3 * W.sum(axis=0), wavelengths=grid, observer=observer)
    seconds, certified = [], True
    for centre, fwhm in NARROW_BANDS:
        b = np.exp(-0.5 * ((lam - centre) / (fwhm / 2.3548200450309493)) ** 2) @ W
        best = np.inf
        for _ in range(2):
            start = time.perf_counter()
            r = sc.smoothest_reflectance(b, wavelengths=grid, observer=observer)
            best = min(best, time.perf_counter() - start)
        certified &= bool(r.certificate.converged)
        seconds.append(best)
    print(f"   1 nm  narrow-band (Gaussian, FWHM 5-15 nm), {observer} observer, {len(seconds)} colours: "
          f"worst {max(seconds):.3f} s, median {np.median(seconds):.3f} s per colour, "
          f"{'all' if certified else 'NOT all'} certified")
    return max(seconds), float(np.median(seconds))


def numpy_path(function):
    """``function`` run with the compiled kernels switched off (``SPECTROCOLOR_NUMBA=0``)."""
    def run():
        previous = os.environ.get("SPECTROCOLOR_NUMBA")
        os.environ["SPECTROCOLOR_NUMBA"] = "0"
        try:
            return function()
        finally:
            if previous is None:
                del os.environ["SPECTROCOLOR_NUMBA"]
            else:
                os.environ["SPECTROCOLOR_NUMBA"] = previous
    return run


def cube_for(grid):
    white = np.asarray(sc.weights(sc.wavelength_grid(*grid), observer="1931", illuminant="D65")).sum(axis=0)
    return srgb_cube(white)


def solver_rates(step: float, repeats: int, burst: float, kernels: bool) -> dict[str, float]:
    """Colours/s of each solver on the cube at ``step`` nm, timed alternately; prints them."""
    grid = (380.0, 780.0, step)
    XYZ = cube_for(grid)
    near = near_boundary(grid, 20000, 1e-9)
    U = setup_for(grid, "1931", "D65")[0].problem.unconstrained
    last = {}

    def solve(name, colours, **options):
        def run():
            last[name] = sc.smoothest_reflectance(colours, wavelengths=grid, **options)
        return run

    functions = {"closed form": solve("closed form", XYZ, bounds=None),
                 "unit": solve("unit", XYZ, bounds="unit"),
                 "limit": lambda: XYZ @ U,
                 "near": solve("near", near, bounds="unit")}
    counts = {"closed form": len(XYZ), "unit": len(XYZ), "limit": len(XYZ), "near": len(near)}
    if step == 10.0:
        for name, colours in (("vertex 1e-9", vertex_set(grid, 1e-9)), ("vertex 1e-3", vertex_set(grid, 1e-3)),
                              ("edge 1e-9", edge_set(grid, 1e-9)), ("edge 1e-3", edge_set(grid, 1e-3))):
            functions[name] = solve(name, colours, bounds="unit")
            counts[name] = len(colours)
    if kernels and step == 10.0:
        functions["unit numpy"] = numpy_path(solve("unit numpy", XYZ[::4], bounds="unit"))
        counts["unit numpy"] = len(XYZ[::4])
    best = alternate_best(functions, repeats=repeats, burst=burst)
    rates = {name: counts[name] / best[name] for name in best}
    for name in ("closed form", "unit"):
        r = last[name]
        print(f"{step:>4g} nm  {name:12s} {len(XYZ)} colours: {rates[name]:12,.0f} colours/s  (feasible "
              f"{r.feasible.mean():.4%}, converged {r.certificate.converged[r.feasible].mean():.4%})")
    print(f"{step:>4g} nm  plain NumPy limit (XYZ @ U only): {rates['limit']:,.0f} colours/s; "
          f"certified closed form takes {rates['limit'] / rates['closed form']:.2f}x its time, "
          f"unit-bounded {rates['limit'] / rates['unit']:.1f}x")
    r = last["near"]
    print(f"{step:>4g} nm  unit, {len(near)} colours at relative depth 1e-9: {rates['near']:,.0f} colours/s, "
          f"converged {r.certificate.converged.mean():.4%}, max residual {r.certificate.primal_residual.max():.1e}")
    for name in ("vertex 1e-9", "vertex 1e-3", "edge 1e-9", "edge 1e-3"):
        if name in rates:
            r = last[name]
            methods = dict(zip(*np.unique(r.method, return_counts=True), strict=True))
            kind, depth = name.split()
            print(f"{step:>4g} nm  unit, {counts[name]} colours near the solid's {PLURAL[kind]} at depth {depth}: "
                  f"{rates[name]:,.0f} colours/s ({rates[name] / rates['near']:.2f}x the random-direction set, "
                  f"{rates[name] / 5e4:.2f}x the 5e4/s goal), certified {r.certificate.converged.mean():.4%}; "
                  f"paths {methods}")
    if "unit numpy" in rates:
        print(f"{step:>4g} nm  unit on the NumPy path: {rates['unit numpy']:,.0f} colours/s; the kernels are "
              f"{rates['unit'] / rates['unit numpy']:.1f}x faster")
    return rates


def meng_rates(meng: int, repeats: int) -> dict[str, float]:
    """Colours/s of colour-science's Meng 2015 and of our unit-bounded solver, alternately, 10 nm."""
    import colour

    grid = (380.0, 780.0, 10.0)
    XYZ = cube_for(grid)
    sample = XYZ[list(MENG_COLOURS[:meng])] / 100
    shape = colour.SpectralShape(380, 780, 10)
    best = alternate_best({
        "unit": lambda: sc.smoothest_reflectance(XYZ, wavelengths=grid, bounds="unit"),
        "colour-science": lambda: [colour.XYZ_to_sd(xyz, method="Meng 2015", shape=shape) for xyz in sample],
    }, repeats=repeats)
    rates = {"unit": len(XYZ) / best["unit"], "colour-science": len(sample) / best["colour-science"]}
    print(f"colour-science XYZ_to_sd (Meng 2015, 10 nm, {len(sample)} colours per call): "
          f"{1 / rates['colour-science']:.2f} s/colour = {rates['colour-science']:.2f} colours/s")
    print(f"ratio unit-bounded 10 nm / colour-science: {rates['unit'] / rates['colour-science']:,.0f}x")
    return rates


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    add_arguments(parser, repeats=3)
    parser.add_argument("--meng", type=int, default=1, choices=range(1, len(MENG_COLOURS) + 1),
                        help="colours of the cube that colour-science's Meng 2015 solves per timed call")
    args = parser.parse_args()
    kernels = compiled.kernels() is not None
    path = "compiled kernels (numba, one thread)" if kernels else "NumPy path"
    print(f"solver path: {path}; OPENBLAS_NUM_THREADS={os.environ.get('OPENBLAS_NUM_THREADS', 'unset')}; "
          f"warm, best of {args.repeats}, timed alternately, {clock_name()}")
    rates = {step: solver_rates(step, args.repeats, args.burst, kernels) for step in (10.0, 5.0)}
    narrow = {observer: narrow_band_seconds(observer) for observer in ("1931", "1964")}
    meng = meng_rates(args.meng, repeats=2)
    figures = [
        figure("unit_10nm_per_s", rates[10.0]["unit"], "ours", "{} colours/s at 10 nm"),
        figure("unit_5nm_per_s", rates[5.0]["unit"], "ours", "{} at 5 nm"),
        figure("near_10nm_per_s", rates[10.0]["near"], "ours", "{} colours/s at relative depth 1e-9 (10 nm)"),
    ]
    figures += [figure(f"{name.replace(' ', '_').replace('-', '_')}_10nm_per_s", rates[10.0][name], "ours",
                       f"{{}} colours/s near the solid's {PLURAL[name.split()[0]]} at relative depth "
                       f"{name.split()[1]} (10 nm)")
                for name in ("vertex 1e-9", "vertex 1e-3", "edge 1e-9", "edge 1e-3")]
    figures += [ratio("vertex_1e_9_over_near_10nm", rates[10.0]["vertex 1e-9"] / rates[10.0]["near"], "ours",
                      "vertices at 1e-9 {}× the random-direction set's rate"),
                ratio("edge_1e_9_over_near_10nm", rates[10.0]["edge 1e-9"] / rates[10.0]["near"], "ours",
                      "edges at 1e-9 {}× the random-direction set's rate")]
    figures += [figure(f"narrow_band_1nm_{observer}_worst_s", narrow[observer][0], "ours",
                       f"worst {{}} s per narrow-band colour at 1 nm ({observer} observer)")
                for observer in ("1931", "1964")]
    if kernels:
        figures += [figure("unit_numpy_10nm_per_s", rates[10.0]["unit numpy"], "ours",
                           "NumPy path {} at 10 nm"),
                    ratio("kernels_over_numpy_path", rates[10.0]["unit"] / rates[10.0]["unit numpy"], "ours",
                          "kernels {}× faster than the NumPy path")]
    figures += [
        ratio("unit_over_colour", meng["unit"] / meng["colour-science"], "colour-science",
              "{}× slower (Meng 2015, 10 nm)"),
        figure("colour_per_s", meng["colour-science"], "colour-science",
               "{} colours/s" + (f" (on {args.meng} colours)" if args.meng > 1 else " (on one colour)")),
        ratio("closed_form_over_limit_10nm", rates[10.0]["limit"] / rates[10.0]["closed form"], "limit",
              "certified closed form {}× its time at 10 nm"),
        ratio("closed_form_over_limit_5nm", rates[5.0]["limit"] / rates[5.0]["closed form"], "limit",
              "{}× at 5 nm"),
        figure("limit_10nm_per_s", rates[10.0]["limit"], "limit", "{} colours/s (bare `XYZ @ U`, 10 nm)"),
    ]
    record("reflectance", "smoothest reflectance, 0 ≤ ρ ≤ 1, sRGB cube every 5th level, 140 608 colours, "
           f"every result certified, {path}", figures, script=Path(__file__).name)


if __name__ == "__main__":
    main()
