"""ASTM E308 route: building the weights, and XYZ of a cube, spectrocolor vs colour-science.

Run: .venv/bin/python bench/bench_astm_e308.py [--repeats 5] [--burst 0.2] [--speed-only]
Prints best-of-N wall times, warm, each comparison timed alternately in this one process:
building one E2022 weight table (ours, uncached, vs colour's
``tristimulus_weighting_factors_ASTME2022`` with its cache off), and XYZ of a 256×256×31 cube by
the same method (ours and a bare matmul with the precomputed weights on the cube;
``colour.msds_to_XYZ(method="ASTM E308")``, which loops over spectra in Python and refuses plain
arrays, on 20 of its spectra, compared per spectrum). Records the figures in the results file
(bench/results.py); then, unless ``--speed-only``, the accuracy and bandpass tables of
docs/astm_e308.md.
"""

from __future__ import annotations

import argparse
import warnings
from pathlib import Path

import numpy as np

import spectrocolor as sc
from results import figure, ratio, record
from spectrocolor.astm_e308 import astm_e308_weights
from timing import BURST, add_arguments, alternate_best, clock_name

COLOUR_SPECTRA = 20  # colour's ASTM E308 route takes 10-30 ms per spectrum


def main(repeats: int = 5, burst: float = BURST) -> None:
    import colour

    colour.utilities.set_caching_enable(False)
    grid = sc.wavelength_grid(400, 700, 10)
    fine = np.arange(360.0, 781.0)
    cm = sc.observer("1931").restrict(360, 780)
    cmfs = colour.MultiSpectralDistributions(cm.values.T, cm.wavelengths_nm)
    spd = colour.SpectralDistribution(sc.illuminant("D65", fine).values, fine)

    tables = alternate_best({
        "ours": lambda: astm_e308_weights(grid, "1931", "D65"),
        "colour-science": lambda: colour.colorimetry.tristimulus_weighting_factors_ASTME2022(
            cmfs, spd, colour.SpectralShape(360, 780, 10)),
    }, repeats=repeats, burst=burst)
    ours_table, theirs_table = tables["ours"], tables["colour-science"]

    cube = np.random.default_rng(0).random((256, 256, grid.size))
    W = np.array(sc.weights(grid, observer="1931", illuminant="D65", method="astm-e308"))
    spectra = sc.Spectrum(grid, cube)
    subset = cube.reshape(-1, grid.size)[:COLOUR_SPECTRA]  # colour loops in Python, one spectrum at a time
    msds = colour.MultiSpectralDistributions(subset.T, grid)
    kwargs = {"method": "ASTM E308", "mi_5nm_omission_method": False, "mi_20nm_interpolation_method": False}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        best = alternate_best({
            "ours": lambda: sc.tristimulus(spectra, observer="1931", illuminant="D65", method="astm-e308"),
            "colour-science": lambda: colour.msds_to_XYZ(msds, cmfs, spd, **kwargs),
            "limit": lambda: cube @ W,
        }, repeats=repeats, burst=burst)
        XYZ_colour = colour.msds_to_XYZ(msds, cmfs, spd, **kwargs)
    ours, limit = best["ours"], best["limit"]
    theirs = best["colour-science"] / COLOUR_SPECTRA
    agreement = np.abs(XYZ_colour - subset @ W).max()

    pixels = cube.shape[0] * cube.shape[1]
    print(f"one E2022 weight table, 400-700 nm at 10 nm, 1931, D65 (uncached); warm, best of {repeats}, alternately, "
          f"{clock_name()}")
    print(f"  spectrocolor.astm_e308_weights                : {ours_table * 1e3:8.2f} ms")
    print(f"  colour tristimulus_weighting_factors_ASTME2022: {theirs_table * 1e3:8.2f} ms")
    print(f"  ratio colour / ours                            : {theirs_table / ours_table:8.1f}x")
    print(f"cube 256x256x31 float64, {pixels} spectra, method ASTM E308")
    print(f"  spectrocolor.tristimulus : {ours * 1e3:8.2f} ms")
    print(f"  bare NumPy cube @ W      : {limit * 1e3:8.2f} ms  (the limit)")
    print(f"  colour.msds_to_XYZ       : {theirs * 1e6:8.1f} us per spectrum ({COLOUR_SPECTRA} spectra)")
    print(f"  ratio colour / ours      : {theirs * pixels / ours:8.0f}x per spectrum")
    print(f"  ratio ours / limit       : {ours / limit:8.2f}x")
    print(f"  max |ours - colour|      : {agreement:.2e} (XYZ100)")
    record("astm_e308", "ASTM E308 weights: one E2022 table; XYZ of a 256² × 31 cube", [
        figure("table_ms", ours_table * 1e3, "ours", "table {} ms"),
        figure("cube_ms", ours * 1e3, "ours", "cube {} ms"),
        ratio("table_colour_over_ours", theirs_table / ours_table, "colour-science", "table {}× slower"),
        ratio("cube_colour_over_ours", theirs * pixels / ours, "colour-science", "cube {}× slower per spectrum"),
        figure("colour_ms_per_spectrum", theirs * 1e3, "colour-science",
               f"{{}} ms per spectrum (timed on {COLOUR_SPECTRA})"),
        ratio("ours_over_limit", ours / limit, "limit", "cube: ours {}× its time"),
        figure("limit_ms", limit * 1e3, "limit", "{} ms (`cube @ W`)"),
    ], script=Path(__file__).name)


def accuracy() -> None:
    """ΔE00 of 10/20 nm methods against 1 nm summation, CIE 13.3 TCS01–14 (Sprague to 1 nm)."""
    from spectrocolor.data_tables import load_table

    header, table = load_table("reflectances_cie_tcs.csv")
    fine = np.arange(360.0, 781.0)
    samples = sc.Spectrum(table[:, 0], table[:, 1:].T.copy()).restrict(360, 780).resample(fine, "sprague")
    print("accuracy: dE00 vs 1 nm summation, TCS01-14 interpolated to 1 nm (Sprague), point sampling")
    for observer, illuminant in (("1931", "D65"), ("1964", "A")):
        white = sc.white_point(illuminant, observer=observer, wavelengths_nm=fine)
        truth = sc.lab(sc.tristimulus(samples, observer=observer, illuminant=illuminant), white)
        for start, stop in ((360, 780), (400, 700)):
            for step in (10, 20):
                sampled = samples.resample(np.arange(start, stop + 1.0, step), "linear")  # exact: a subset
                cells = []
                for method in sc.colorimetry.SUMMATION_METHODS.names():
                    XYZ = sc.tristimulus(sampled, observer=observer, illuminant=illuminant, method=method)
                    dE = sc.delta_e_2000(sc.lab(XYZ, white), truth)
                    cells.append(f"{method} {dE.mean():.3f}/{dE.max():.3f}")
                print(f"  {observer} {illuminant:3s} {start}-{stop} nm at {step:2d} nm (mean/max): " + "  ".join(cells))


def bandpass() -> None:
    """Largest |ΔXYZ100| per sample against 1 nm summation, TCS01–14 measured through a triangular
    bandpass equal to the interval (the instrument E308 Table 6 is for), per summation method."""
    from spectrocolor.astm_e308 import lagrange_matrix
    from spectrocolor.data_tables import load_table

    header, table = load_table("reflectances_cie_tcs.csv")
    fine = np.arange(360.0, 781.0)
    true = table[:, 1:].T @ lagrange_matrix(table[:, 0], fine).T  # E2022 Lagrange from the 5 nm table
    reference = sc.tristimulus(sc.Spectrum(fine, true), observer="1931", illuminant="D65", method="sum")
    print("bandpass: TCS01-14 read through a triangular bandpass = interval; max |dXYZ100| per sample, mean/max")
    for step in (10, 20):
        grid = sc.wavelength_grid(360 + step, 780 - step, step)
        triangle = np.clip(1 - np.abs(fine[None, :] - grid[:, None]) / step, 0, None)
        measured = sc.Spectrum(grid, true @ (triangle / triangle.sum(axis=1, keepdims=True)).T)
        cells = []
        for method in ("sum", "astm-e308", "astm-e308-table6"):
            XYZ = sc.tristimulus(measured, observer="1931", illuminant="D65", method=method)
            error = np.abs(XYZ - reference).max(axis=1)
            cells.append(f"{method} {error.mean():.4f}/{error.max():.4f}")
        print(f"  1931 D65 {grid[0]:.0f}-{grid[-1]:.0f} nm at {step} nm: " + "  ".join(cells))


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    add_arguments(parser)
    parser.add_argument("--speed-only", action="store_true", help="skip the accuracy and bandpass tables")
    args = parser.parse_args()
    main(args.repeats, args.burst)
    if not args.speed_only:
        accuracy()
        bandpass()
