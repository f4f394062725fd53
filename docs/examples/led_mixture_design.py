"""Design a four-LED mixture for the highest TM-30 fidelity Rf at a target CCT and Duv.

Each candidate light is a sum of four Gaussian LED primaries; the optimiser chooses their peak
wavelengths and powers. SciPy's differential evolution runs with ``vectorized=True``: every
generation's whole population (here 8 parameters × 15 = 120 candidate spectra) is evaluated by
one call of :func:`spectrocolor.lighting.colour_fidelity`, which is what makes a global search
over spectra take seconds instead of hours.

Objective (minimised): −Rf + 20 000 × (distance in the CIE 1960 uv diagram from the target
chromaticity), so a light 0.001 off the target (well above the 0.0054 of CIE 13.3 but visible
to the eye) costs 20 points of Rf; the result reports its CCT and Duv so the trade is visible.

Run: .venv/bin/python docs/examples/led_mixture_design.py [--cct 4000] [--duv 0] [--maxiter 60]
     [--out docs/images/lighting_led_design.png]
"""

from __future__ import annotations

import argparse
from dataclasses import dataclass

import numpy as np
from scipy.optimize import differential_evolution

from spectrocolor import Spectrum, uv_1960, wavelength_grid, xy_from_cct
from spectrocolor.lighting import colour_fidelity, colour_rendering_index, luminous_efficacy_of_radiation

GRID_NM = wavelength_grid(380, 780, 1)
#: Search ranges of the four peak wavelengths (nm) — blue, cyan-green, lime-amber, red.
PEAK_BOUNDS_NM = ((440, 470), (490, 540), (550, 600), (610, 660))
#: Full width at half maximum of each LED primary, nm (typical of direct-emission LEDs).
FWHM_NM = (20.0, 30.0, 30.0, 20.0)
#: uv-distance penalty, Rf points per unit of uv distance.
PENALTY = 2.0e4


@dataclass(frozen=True)
class Design:
    """The best mixture found: primaries, spectrum, its metrics and the spectra evaluated."""

    peaks_nm: np.ndarray
    powers: np.ndarray
    spectrum: Spectrum
    Rf: float
    Rg: float
    Ra: float
    cct_K: float
    duv: float
    ler_lm_per_W: float
    evaluations: int


def mixtures(parameters: np.ndarray) -> np.ndarray:
    """Spectra (S, K) of parameter vectors (S, 8): four peak wavelengths, then four powers."""
    peaks, powers = parameters[:, :4, None], parameters[:, 4:, None]
    sigma = np.array(FWHM_NM)[:, None] / (2.0 * np.sqrt(2.0 * np.log(2.0)))
    return (powers * np.exp(-0.5 * ((GRID_NM - peaks) / sigma) ** 2)).sum(axis=1)


def objective_factory(target_uv: np.ndarray):
    """The batched objective: (8, S) parameters (SciPy's vectorized layout) → (S,) costs."""
    from spectrocolor.sampling import cmfs_on

    W = cmfs_on(GRID_NM, "1931")

    def objective(parameters: np.ndarray) -> np.ndarray:
        spectra = mixtures(np.atleast_2d(parameters.T))
        objective.spectra_evaluated += len(spectra)
        fidelity = colour_fidelity(Spectrum(GRID_NM, spectra))
        distance = np.hypot(*(uv_1960(spectra @ W) - target_uv).T)
        return np.nan_to_num(-fidelity.Rf, nan=0.0) + PENALTY * distance

    objective.spectra_evaluated = 0
    return objective


def design(cct_K: float = 4000.0, duv: float = 0.0, maxiter: int = 60, seed: int = 1) -> Design:
    """Run differential evolution for the four-LED mixture of highest Rf at (cct_K, duv)."""
    target_uv = uv_1960(xy=xy_from_cct(cct_K, duv))
    bounds = [*PEAK_BOUNDS_NM, *[(0.05, 1.0)] * 4]
    objective = objective_factory(target_uv)
    result = differential_evolution(objective, bounds, maxiter=maxiter, popsize=15,
                                     seed=seed, vectorized=True, updating="deferred", polish=False, tol=1e-8)
    spectrum = Spectrum(GRID_NM, mixtures(result.x[None])[0], ("optimised 4-LED mixture",))
    fidelity = colour_fidelity(spectrum)
    return Design(
        peaks_nm=result.x[:4], powers=result.x[4:] / result.x[4:].max(), spectrum=spectrum,
        Rf=float(fidelity.Rf), Rg=float(fidelity.Rg), Ra=float(colour_rendering_index(spectrum).Ra),
        cct_K=float(fidelity.cct_K), duv=float(fidelity.duv),
        ler_lm_per_W=float(luminous_efficacy_of_radiation(spectrum)), evaluations=objective.spectra_evaluated,
    )


def picture(best: Design, path) -> None:
    """Spectrum with its primaries (left) and the TM-30 colour vector graphic (right)."""
    from matplotlib.figure import Figure

    from spectrocolor import wavelength_tint
    from spectrocolor.lighting.vector_graphic import vector_graphic
    from spectrocolor.safe_write import write_bytes

    figure = Figure(figsize=(10, 4.4))
    left, right = figure.add_subplot(1, 2, 1), figure.add_subplot(1, 2, 2)
    parameters = np.concatenate([best.peaks_nm, best.powers])
    spectra = mixtures(parameters[None])[0]
    scale = spectra.max()
    for k in range(4):
        single = parameters.copy()
        single[4:] = 0.0
        single[4 + k] = best.powers[k]
        left.fill_between(GRID_NM, mixtures(single[None])[0] / scale, alpha=0.6,
                          color=wavelength_tint(best.peaks_nm[k]) / 255.0)
    left.plot(GRID_NM, spectra / scale, color="black", lw=1.5)
    left.set_xlabel("wavelength (nm)")
    left.set_ylabel("relative spectral power")
    left.set_title(f"peaks {', '.join(f'{p:.0f}' for p in best.peaks_nm)} nm\n"
                   f"Rf {best.Rf:.1f}, Rg {best.Rg:.1f}, Ra {best.Ra:.1f}, LER {best.ler_lm_per_W:.0f} lm/W",
                   fontsize=10)
    vector_graphic(colour_fidelity(best.spectrum), ax=right, title=f"{best.cct_K:.0f} K, Duv {best.duv:+.4f}")
    figure.tight_layout()
    import io

    buffer = io.BytesIO()
    figure.savefig(buffer, format="png", dpi=110)
    write_bytes(path, buffer.getvalue())


def main(argv: list[str] | None = None) -> Design:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cct", type=float, default=4000.0, help="target CCT, K (default 4000)")
    parser.add_argument("--duv", type=float, default=0.0, help="target Duv (default 0)")
    parser.add_argument("--maxiter", type=int, default=60, help="generations (default 60)")
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--out", default=None, help="write the picture (PNG) here")
    args = parser.parse_args(argv)
    best = design(args.cct, args.duv, args.maxiter, args.seed)
    print(f"{best.evaluations} spectra evaluated; peaks {np.round(best.peaks_nm, 1).tolist()} nm, "
          f"powers {np.round(best.powers, 3).tolist()}")
    print(f"Rf {best.Rf:.1f}  Rg {best.Rg:.1f}  Ra {best.Ra:.1f}  CCT {best.cct_K:.0f} K  Duv {best.duv:+.4f}  "
          f"LER {best.ler_lm_per_W:.0f} lm/W")
    if args.out:
        picture(best, args.out)
        print(f"wrote {args.out}")
    return best


if __name__ == "__main__":
    main()
