"""ASTM E308 route: building the weights, and XYZ of a cube, spectrocolor vs colour-science.

Run: .venv/bin/python bench/bench_astm_e308.py
Prints best-of-N wall times measured in this one run: building one E2022 weight table (ours,
uncached, vs colour's ``tristimulus_weighting_factors_ASTME2022`` with its cache off), and XYZ of a
256×256×31 cube by the same method (ours and a bare matmul with the precomputed weights on the cube;
``colour.msds_to_XYZ(method="ASTM E308")``, which loops over spectra in Python and refuses plain
arrays, on 200 of its spectra, compared per spectrum).
"""

from __future__ import annotations

import time
import warnings

import numpy as np

import spectrocolor as sc
from spectrocolor.astm_e308 import astm_e308_weights
from timing import best_of

COLOUR_SPECTRA = 200  # colour's ASTM E308 route takes ~10 ms per spectrum


def main() -> None:
    import colour

    colour.utilities.set_caching_enable(False)
    grid = sc.wavelength_grid(400, 700, 10)
    fine = np.arange(360.0, 781.0)
    cm = sc.observer("1931").restrict(360, 780)
    cmfs = colour.MultiSpectralDistributions(cm.values.T, cm.wavelengths_nm)
    spd = colour.SpectralDistribution(sc.illuminant("D65", fine).values, fine)

    ours_table = best_of(lambda: astm_e308_weights(grid, "1931", "D65"))
    theirs_table = best_of(
        lambda: colour.colorimetry.tristimulus_weighting_factors_ASTME2022(
            cmfs, spd, colour.SpectralShape(360, 780, 10)
        )
    )

    cube = np.random.default_rng(0).random((256, 256, grid.size))
    W = np.array(sc.weights(grid, observer="1931", illuminant="D65", method="astm-e308"))
    spectra = sc.Spectrum(grid, cube)
    ours = best_of(lambda: sc.tristimulus(spectra, observer="1931", illuminant="D65", method="astm-e308"))
    limit = best_of(lambda: cube @ W)
    subset = cube.reshape(-1, grid.size)[:COLOUR_SPECTRA]  # colour loops in Python, one spectrum at a time
    msds = colour.MultiSpectralDistributions(subset.T, grid)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        kwargs = {"method": "ASTM E308", "mi_5nm_omission_method": False, "mi_20nm_interpolation_method": False}
        start = time.perf_counter()
        XYZ_colour = colour.msds_to_XYZ(msds, cmfs, spd, **kwargs)
        theirs = (time.perf_counter() - start) / COLOUR_SPECTRA
    agreement = np.abs(XYZ_colour - subset @ W).max()

    pixels = cube.shape[0] * cube.shape[1]
    print("one E2022 weight table, 400-700 nm at 10 nm, 1931, D65 (uncached)")
    print(f"  spectrocolor.astm_e308_weights                : {ours_table * 1e3:8.2f} ms")
    print(f"  colour tristimulus_weighting_factors_ASTME2022: {theirs_table * 1e3:8.2f} ms")
    print(f"  ratio colour / ours                            : {theirs_table / ours_table:8.1f}x")
    print(f"cube 256x256x31 float64, {pixels} spectra, method ASTM E308")
    print(f"  spectrocolor.tristimulus : {ours * 1e3:8.2f} ms")
    print(f"  bare NumPy cube @ W      : {limit * 1e3:8.2f} ms  (the limit)")
    print(f"  colour.msds_to_XYZ       : {theirs * 1e6:8.1f} us per spectrum ({COLOUR_SPECTRA} spectra, one run)")
    print(f"  ratio colour / ours      : {theirs * pixels / ours:8.0f}x per spectrum")
    print(f"  ratio ours / limit       : {ours / limit:8.2f}x")
    print(f"  max |ours - colour|      : {agreement:.2e} (XYZ100)")


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
    main()
    accuracy()
    bandpass()
