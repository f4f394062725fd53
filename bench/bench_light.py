"""Light-source metrics on 10 000 random LED spectra: spectrocolor vs colour-science vs NumPy.

Run: .venv/bin/python bench/bench_light.py [--count 10000] [--sample 10] [--repeats 3] [--burst 0.2]
Prints, measured in this one run: spectra per second for the CIE 13.3 CRI (Ra, R1–R14) and
for CIE 224 / TM-30 (Rf, Rg, 16 hue bins) computed by spectrocolor on the whole batch, by
colour-science one spectrum at a time on a sample, and the NumPy limit of the core matrix
products (the sample colorimetry of the light and of its reference illuminant with
precomputed weights: nothing else). The six are timed alternately in this one process, warm,
best of N each. Goal: ≥ 100× colour-science with the same numbers (the agreement on the sample
is printed too). The figures are recorded in the results file (bench/results.py).
"""

from __future__ import annotations

import argparse
import warnings
from pathlib import Path

import numpy as np

from results import figure, ratio, record
from spectrocolor import Spectrum, wavelength_grid
from spectrocolor.lighting import colour_fidelity, colour_rendering_index
from spectrocolor.lighting.spectra import ces_reflectances, tcs_reflectances
from spectrocolor.sampling import cmfs_on
from timing import add_arguments, alternate_best, clock_name


def led_mixtures(count: int, grid: np.ndarray, seed: int = 0) -> np.ndarray:
    """Mixtures of 3–5 Gaussian LEDs (425–660 nm, 15–40 nm wide) and a broad phosphor band, (count, K)."""
    rng = np.random.default_rng(seed)
    peaks = rng.uniform(425, 660, (count, 5, 1))
    widths = rng.uniform(15, 40, (count, 5, 1)) / 2.3548
    weights = rng.uniform(0.0, 1.0, (count, 5, 1)) * (rng.uniform(size=(count, 5, 1)) < 0.8)
    leds = (weights * np.exp(-0.5 * ((grid - peaks) / widths) ** 2)).sum(axis=1)
    phosphor = rng.uniform(0.0, 1.5, (count, 1)) * np.exp(-0.5 * ((grid - 570.0) / 55.0) ** 2)
    return leds + phosphor + 1e-3


def _limit(S: np.ndarray, reflectances: np.ndarray, observer: str, grid: np.ndarray):
    """The two core products S @ M and R @ M with M = (reflectance × CMF) precomputed, as a function."""
    M = (reflectances[:, :, None] * cmfs_on(grid, observer)[None]).transpose(1, 0, 2).reshape(grid.size, -1)
    R = S[::-1].copy()  # stands for the reference illuminants (same shape)
    return lambda: (S @ M, R @ M)


def main() -> None:
    import colour

    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--count", type=int, default=10_000)
    parser.add_argument("--sample", type=int, default=10)
    add_arguments(parser, repeats=3)
    args = parser.parse_args()

    grid = wavelength_grid(360, 780, 1)
    S = led_mixtures(args.count, grid)
    lights = Spectrum(grid, S)
    lights_380 = lights.restrict(380, 780)
    sample = range(args.sample)
    sds = [colour.SpectralDistribution(S[i], grid) for i in sample]
    sds_380 = [colour.SpectralDistribution(lights_380.values[i], lights_380.wavelengths_nm) for i in sample]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        best = alternate_best({
            "CRI ours": lambda: colour_rendering_index(lights),
            "CRI colour-science": lambda: [colour.colour_rendering_index(sd) for sd in sds],
            "CRI limit": _limit(S, tcs_reflectances(grid), "1931", grid),
            "TM30 ours": lambda: colour_fidelity(lights_380),
            "TM30 colour-science": lambda: [colour.quality.colour_fidelity_index_ANSIIESTM3018(sd, True)
                                            for sd in sds_380],
            "TM30 limit": _limit(lights_380.values, ces_reflectances(lights_380.wavelengths_nm), "1964",
                                 lights_380.wavelengths_nm),
        }, repeats=args.repeats, burst=args.burst)
        Ra = np.array([colour.colour_rendering_index(sd) for sd in sds])
        specs = [colour.quality.colour_fidelity_index_ANSIIESTM3018(sd, True) for sd in sds_380]
    ours_cri, ours_tm30 = best["CRI ours"], best["TM30 ours"]
    limit_cri, limit_tm30 = best["CRI limit"], best["TM30 limit"]
    theirs_cri = best["CRI colour-science"] / args.sample
    theirs_tm30 = best["TM30 colour-science"] / args.sample
    cri = colour_rendering_index(Spectrum(grid, S[: args.sample]))
    tm30 = colour_fidelity(Spectrum(lights_380.wavelengths_nm, lights_380.values[: args.sample]))
    inside = cri.cct_K > 1700  # colour-science's Robertson table starts at 1667 K
    dRa = np.abs(cri.Ra - Ra)[inside].max()
    # we give NaN where the standards define no reference (CCT outside 1000-25 000 K);
    # colour-science extrapolates there with a warning: compare where both are defined
    defined = np.isfinite(tm30.Rf)
    dRf = np.abs(tm30.Rf - [s.R_f for s in specs])[defined].max()
    dRg = np.abs(tm30.Rg - [s.R_g for s in specs])[defined].max()
    undefined = int(np.sum(~np.isfinite(colour_fidelity(lights_380).Rf)))

    n = args.count
    print(f"{n} random LED spectra, 1 nm (CRI 360-780 nm, TM-30 380-780 nm); colour-science on {args.sample}; "
          f"warm, best of {args.repeats}, alternately, {clock_name()}")
    print("                        spectra/s   vs colour-science   ours / NumPy limit")
    print(f"  CRI  spectrocolor   {n / ours_cri:11.0f}   {theirs_cri * n / ours_cri:10.0f}x   "
          f"{ours_cri / limit_cri:10.1f}x")
    print(f"  CRI  colour-science {1 / theirs_cri:11.0f}")
    print(f"  CRI  NumPy limit    {n / limit_cri:11.0f}")
    print(f"  TM30 spectrocolor   {n / ours_tm30:11.0f}   {theirs_tm30 * n / ours_tm30:10.0f}x   "
          f"{ours_tm30 / limit_tm30:10.1f}x")
    print(f"  TM30 colour-science {1 / theirs_tm30:11.0f}")
    print(f"  TM30 NumPy limit    {n / limit_tm30:11.0f}")
    print(f"  agreement on the sample: max |dRa| {dRa:.4f}, |dRf| {dRf:.4f}, |dRg| {dRg:.4f} "
          "(CCT methods differ: Robertson / Ohno table vs exact; 1 nm daylight Sprague vs linear)")
    print(f"  lights without a TM-30 reference (CCT outside 1000-25 000 K): {undefined} of {n} (NaN)")
    record("light", f"CRI / TM-30 of {n:_} random LED spectra at 1 nm".replace("_", " "), [
        figure("cri_per_s", n / ours_cri, "ours", "CRI {} spectra/s"),
        figure("tm30_per_s", n / ours_tm30, "ours", "TM-30 {} spectra/s"),
        ratio("cri_colour_over_ours", theirs_cri * n / ours_cri, "colour-science", "CRI {}× slower"),
        ratio("tm30_colour_over_ours", theirs_tm30 * n / ours_tm30, "colour-science", "TM-30 {}× slower"),
        figure("cri_colour_per_s", 1 / theirs_cri, "colour-science", f"CRI {{}} spectra/s (on {args.sample})"),
        figure("tm30_colour_per_s", 1 / theirs_tm30, "colour-science", f"TM-30 {{}} spectra/s (on {args.sample})"),
        ratio("cri_ours_over_limit", ours_cri / limit_cri, "limit", "CRI: ours {}× its time"),
        ratio("tm30_ours_over_limit", ours_tm30 / limit_tm30, "limit", "TM-30: ours {}× its time"),
    ], script=Path(__file__).name)


if __name__ == "__main__":
    main()
