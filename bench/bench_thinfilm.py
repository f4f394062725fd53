"""Thin-film benchmarks: spectra and thickness-map rendering.

Run: .venv/bin/python bench/bench_thinfilm.py [--repeats 5] [--burst 0.2]

1. Reflectance and transmittance spectra of one film for 81 wavelengths × 1501 thicknesses
   (s and p): spectrocolor's Airy formula and transfer matrices vs colour-science's
   ``thin_film_tmm``, and a plain NumPy limit (the two-beam cosine, no Fresnel work), the four
   timed alternately in this one process, warm, best of N each.
2. A 3840 × 2160 thickness map rendered through a thickness → colour lookup table (the table's
   build, and the render, each best of N).

The figures are recorded in the results file (bench/results.py).
"""

from __future__ import annotations

import argparse
from pathlib import Path

import numpy as np

from results import figure, ratio, record
from timing import add_arguments, alternate_best, clock_name

SCRIPT = Path(__file__).name


def spectra(repeats: int, burst: float) -> None:
    from colour.phenomena import thin_film_tmm

    from spectrocolor.thinfilm.optics import stack_optics, thin_film, two_beam_reflectance

    wl = np.linspace(380.0, 780.0, 81)
    d = np.linspace(0.0, 1500.0, 1501)

    def both(fn):
        return lambda: (fn("s"), fn("p"))

    best = alternate_best({
        "airy": both(lambda p: thin_film(d, wl, 1.33, substrate=1.5, polarisation=p)),
        "tmm": both(lambda p: stack_optics(d[:, None], wl, [1.33], substrate=1.5, polarisation=p)),
        "colour-science": lambda: thin_film_tmm([1.0, 1.33, 1.5], d, wl),
        "limit": lambda: two_beam_reflectance(2 * 1.33 * d, wl),
    }, repeats=repeats, burst=burst)
    t_airy, t_tmm, t_cs, t_np = best["airy"], best["tmm"], best["colour-science"], best["limit"]
    print(f"81 wavelengths x 1501 thicknesses, R and T for s and p (warm, best of {repeats}, alternately, "
          f"{clock_name()})")
    print(f"  spectrocolor thin_film (Airy)     {t_airy * 1e3:8.1f} ms")
    print(f"  spectrocolor stack_optics (TMM)   {t_tmm * 1e3:8.1f} ms")
    print(f"  colour-science thin_film_tmm      {t_cs * 1e3:8.1f} ms")
    print(f"  NumPy limit (two-beam cosine)     {t_np * 1e3:8.1f} ms")
    print(f"  ratio colour-science / Airy = {t_cs / t_airy:.1f}x, / TMM = {t_cs / t_tmm:.1f}x")
    record("thinfilm_spectra", "thin film, 81 λ × 1501 thicknesses, R and T, s and p", [
        figure("airy_ms", t_airy * 1e3, "ours", "{} ms (Airy)"),
        figure("tmm_ms", t_tmm * 1e3, "ours", "{} ms (TMM)"),
        ratio("colour_over_airy", t_cs / t_airy, "colour-science", "{}× slower than Airy"),
        ratio("colour_over_tmm", t_cs / t_tmm, "colour-science", "{}× slower than TMM"),
        figure("colour_ms", t_cs * 1e3, "colour-science", "{} ms (`thin_film_tmm`)"),
        ratio("airy_over_limit", t_airy / t_np, "limit", "Airy {}× its time"),
        figure("limit_ms", t_np * 1e3, "limit", "{} ms (two-beam cosine)"),
    ], script=SCRIPT)


def thickness_map(repeats: int, burst: float) -> None:
    from spectrocolor.thinfilm import maps
    from spectrocolor.thinfilm.films import soap_film

    frame = np.minimum(maps.draining_film(3840, 2160, time_s=3000.0, film_height_m=0.02), 2000.0)
    tables = []
    best = alternate_best({
        "table": lambda: tables.append(maps.colour_table(soap_film, 2000.0, thickness_step_nm=0.5,
                                                         exposure="perfect-reflector", gain=6.0)),
        "render": lambda: maps.render_thickness_map(frame, tables[-1]),
    }, repeats=repeats, burst=burst)
    print("3840 x 2160 thickness map (draining soap film), float32 thickness")
    print(f"  lookup table (4001 thicknesses, exact optics, colour): {best['table'] * 1e3:.0f} ms")
    print(f"  render through the table: {best['render'] * 1e3:.0f} ms per frame")
    record("thinfilm_map", "3840 × 2160 soap-film frame through a lookup table", [
        figure("render_ms", best["render"] * 1e3, "ours", "{} ms per frame"),
        figure("table_ms", best["table"] * 1e3, "ours", "+ {} ms to build the table once"),
    ], script=SCRIPT)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    add_arguments(parser)
    args = parser.parse_args()
    spectra(args.repeats, args.burst)
    thickness_map(args.repeats, args.burst)


if __name__ == "__main__":
    main()
