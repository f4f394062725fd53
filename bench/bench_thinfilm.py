"""Thin-film benchmarks (run by hand): spectra and thickness-map rendering.

1. Reflectance and transmittance spectra of one film for 81 wavelengths × 1501 thicknesses
   (s and p): spectrocolor's Airy formula and transfer matrices vs colour-science's
   ``thin_film_tmm``, and a plain NumPy limit (the two-beam cosine, no Fresnel work).
2. A 3840 × 2160 thickness map rendered through a thickness → colour lookup table.

Ratios are measured in one run on this machine; best of several repeats.
"""

from __future__ import annotations

import time

import numpy as np

from timing import best_of


def main() -> None:
    from colour.phenomena import thin_film_tmm

    from spectrocolor.thinfilm import maps
    from spectrocolor.thinfilm.films import soap_film
    from spectrocolor.thinfilm.optics import stack_optics, thin_film, two_beam_reflectance

    wl = np.linspace(380.0, 780.0, 81)
    d = np.linspace(0.0, 1500.0, 1501)

    def both(fn):
        return lambda: (fn("s"), fn("p"))

    t_airy = best_of(both(lambda p: thin_film(d, wl, 1.33, substrate=1.5, polarisation=p)))
    t_tmm = best_of(both(lambda p: stack_optics(d[:, None], wl, [1.33], substrate=1.5,
                                             polarisation=p)))
    t_cs = best_of(lambda: thin_film_tmm([1.0, 1.33, 1.5], d, wl), repeats=3)
    t_np = best_of(lambda: two_beam_reflectance(2 * 1.33 * d, wl))
    print("81 wavelengths x 1501 thicknesses, R and T for s and p (best of runs)")
    print(f"  spectrocolor thin_film (Airy)     {t_airy * 1e3:8.1f} ms")
    print(f"  spectrocolor stack_optics (TMM)   {t_tmm * 1e3:8.1f} ms")
    print(f"  colour-science thin_film_tmm      {t_cs * 1e3:8.1f} ms")
    print(f"  NumPy limit (two-beam cosine)     {t_np * 1e3:8.1f} ms")
    print(f"  ratio colour-science / Airy = {t_cs / t_airy:.1f}x, / TMM = {t_cs / t_tmm:.1f}x")

    t0 = time.perf_counter()
    table = maps.colour_table(soap_film, 2000.0, thickness_step_nm=0.5,
                              exposure="perfect-reflector", gain=6.0)
    t_table = time.perf_counter() - t0
    frame = maps.draining_film(3840, 2160, time_s=3000.0, film_height_m=0.02)
    frame = np.minimum(frame, 2000.0)
    t_map = best_of(lambda: maps.render_thickness_map(frame, table), repeats=3)
    print("3840 x 2160 thickness map (draining soap film), float32 thickness")
    print(f"  lookup table (4001 thicknesses, exact optics, colour): {t_table * 1e3:.0f} ms")
    print(f"  render through the table: {t_map * 1e3:.0f} ms per frame")


if __name__ == "__main__":
    main()
