"""The explorer's smoothest-reflectance lab (seed 004, van Trigt): every number from the library.

For a colour given by its chromaticity (x, y) and luminance factor Y under an illuminant, the
page shows the smoothest reflectance three ways — unconstrained (closed form, may go below 0 or
above 1), ρ ≥ 0, and 0 ≤ ρ ≤ 1 (object colours) — with feasibility, the distance outside the
solid when there is none, roughness ∫(dρ/dλ)² dλ and the solver's certificate; the largest Y an
object colour of that chromaticity can have (:func:`~spectrocolor.recovery.luminance_limit.
max_luminance_factor`); and, on the chromaticity diagram, the domain of validity (where the
unconstrained solution is already a reflectance at this Y) and the MacAdam limit at this Y.

References
----------
C. van Trigt, J. Opt. Soc. Am. A 7, 1891–1904 (1990) (seed 004); D. L. MacAdam (1935).
"""

from __future__ import annotations

from functools import lru_cache

import numpy as np

from ..errors import ColorimetryError
from ..illuminants import canonical_illuminant, illuminant_label, resolve_illuminant
from ..registry import Registry

#: The grids the lab offers (380-780 nm): name → step in nm.
STEPS_NM = Registry("step_nm", "a grid step of the reflectance lab")
STEPS_NM.add("5", 5.0, "380-780 nm at 5 nm (81 samples)", label="5 nm (81 samples)")
STEPS_NM.add("10", 10.0, "380-780 nm at 10 nm (41 samples, SPECTRA-like)", label="10 nm (41 samples)")
BOUNDS = (("unconstrained", None), ("nonnegative", "nonnegative"), ("unit", "unit"))
DOMAIN_GRID = 72  # chromaticity cells per side of the domain picture


def _number(value, digits: int):
    """A JSON-ready float, or None where the library answers NaN or infinity."""
    value = float(value)
    return round(value, digits) if np.isfinite(value) else None


def _intervals(wavelengths_nm: np.ndarray, mask: np.ndarray) -> list[list[float]]:
    """[[start, stop], …] nm of the runs where ``mask`` holds."""
    runs, start = [], None
    for k, flag in enumerate(mask):
        if flag and start is None:
            start = k
        if not flag and start is not None:
            runs.append([float(wavelengths_nm[start]), float(wavelengths_nm[k - 1])])
            start = None
    if start is not None:
        runs.append([float(wavelengths_nm[start]), float(wavelengths_nm[-1])])
    return runs


def reflectance_lab(x: float, y: float, Y: float, illuminant="D65", observer: str = "1931",
                    step_nm: str = "5") -> dict:
    """Everything the reflectance lab shows for one colour, as JSON-ready values.

    Parameters
    ----------
    x, y : float
        CIE chromaticity of the colour (y > 0).
    Y : float
        Luminance factor, percent of the perfect white (0 < Y ≤ 100).
    illuminant : str or float
        The lab's light, a name or a temperature (default D65); see :term:`illuminant`.
    observer : str
        Observer name (default CIE 1931 2°).
    step_nm : str
        A name in :data:`STEPS_NM`.

    Returns
    -------
    dict
        ``wavelengths_nm``; ``XYZ``; ``srgb8`` (the colour on sRGB, adapted from the light's white,
        desaturated if outside the display) and ``srgb_in_gamut``; ``solutions`` {unconstrained,
        nonnegative, unit}: each with ``reflectance`` (None if infeasible), ``feasible``,
        ``distance_outside``, ``roughness`` (nm⁻¹), ``converged``, ``method``, ``zero_nm`` and
        ``one_nm`` (intervals where ρ sits on a bound), ``min``/``max``; ``max_Y`` (the brightest object colour of this
        chromaticity), ``valid_up_to_Y`` (the unconstrained solution is a reflectance up to this
        Y; None outside the domain); and for the diagram ``locus_xy``, ``white_xy``,
        ``domain_xy`` (ρ ≥ 0 for every Y) and ``valid_cells`` (grid cells where the unconstrained
        solution is physical at this Y). The MacAdam limit comes from :func:`macadam_xy`.

    Examples
    --------
    >>> lab = reflectance_lab(0.60, 0.33, 20.0)          # a red of luminance factor 20 under D65
    >>> lab["solutions"]["unit"]["feasible"], round(lab["max_Y"], 1)
    (True, 29.2)
    >>> lab["solutions"]["unconstrained"]["min"] < 0 <= lab["solutions"]["unit"]["min"]
    True
    >>> lab["valid_up_to_Y"] is None                      # outside the domain of validity
    True
    """
    from ..chromaticity import spectral_locus
    from ..colorimetry import white_point
    from ..coordinates import XYZ_from_xyY
    from ..coordinates import xy as chromaticity
    from ..display.adaptation import adapt
    from ..display.render import render
    from ..display.spaces import rgb_space
    from ..recovery.luminance_limit import max_luminance_factor
    from ..recovery.smoothest import smoothest_reflectance
    from ..spectrum import wavelength_grid

    values = np.array([x, y, Y], dtype=float)
    if not (np.all(np.isfinite(values)) and y > 0 and x >= 0 and x + y <= 1 and 0 < Y <= 100):
        raise ColorimetryError(f"x, y, Y: expected 0 ≤ x, 0 < y, x + y ≤ 1 and 0 < Y ≤ 100; got {x!r}, {y!r}, {Y!r}")
    light = resolve_illuminant(illuminant)
    if light is None or not light.cacheable:
        raise ColorimetryError(f"illuminant: the lab takes a named light (e.g. 'D65', 'A'), got {illuminant!r:.60}")
    step = STEPS_NM.get(str(step_nm))
    grid = (380.0, 780.0, step)
    wavelengths = wavelength_grid(*grid)
    XYZ = XYZ_from_xyY(values)
    if not np.all(np.isfinite(XYZ)):
        raise ColorimetryError(f"x, y, Y: y = {y!r} is too small: X and Z = Y·x/y, Y·z/y overflow")
    solutions = {}
    for name, bounds in BOUNDS:
        result = smoothest_reflectance(XYZ[None], illuminant=light, observer=observer, wavelengths=grid,
                                       bounds=bounds)
        rho = result.spectrum.values[0]
        # a colour the solver could not turn into a finite reflectance is shown as not feasible
        feasible = bool(result.feasible[0]) and bool(np.all(np.isfinite(rho)))
        solutions[name] = {
            "reflectance": np.round(rho, 6).tolist() if feasible else None,
            "feasible": feasible,
            "distance_outside": _number(result.distance_outside[0], 6),
            "roughness": round(float(result.roughness[0]), 8) if feasible else None,
            "converged": bool(result.certificate.converged[0]),
            "method": str(result.method[0]),
            "zero_nm": _intervals(wavelengths, rho <= 0.0) if feasible and bounds else [],
            "one_nm": _intervals(wavelengths, rho >= 1.0) if feasible and bounds == "unit" else [],
            "min": round(float(np.min(rho)), 6) if feasible else None,
            "max": round(float(np.max(rho)), 6) if feasible else None,
        }
    white = white_point(light, observer=observer, wavelengths_nm=wavelengths)
    srgb = rgb_space("sRGB")
    shown = render(adapt(XYZ, white, srgb.white_XYZ), srgb, gamut="desaturate")
    domain = _domain(light, observer, grid)
    valid = domain.max_luminance_factor(values[:2])
    cells = (np.arange(DOMAIN_GRID) + 0.5) / DOMAIN_GRID
    cx, cy = np.meshgrid(cells * 0.8, cells * 0.9)
    limit = domain.max_luminance_factor(np.stack([cx, cy], axis=-1)) * 100.0
    valid_cells = np.argwhere(np.nan_to_num(limit, nan=-1.0) >= Y)
    return {
        "x": float(x), "y": float(y), "Y": float(Y), "illuminant": illuminant_label(light), "observer": str(observer),
        "wavelengths_nm": wavelengths.tolist(),
        "XYZ": np.round(XYZ, 6).tolist(),
        "solutions": solutions,
        "max_Y": round(float(max_luminance_factor(values[:2], illuminant=light, observer=observer,
                                                  wavelengths=grid)), 4),
        "valid_up_to_Y": None if not np.isfinite(valid) else round(float(valid) * 100.0, 4),
        "locus_xy": np.round(spectral_locus(observer).xy, 5).tolist(),
        "white_xy": np.round(chromaticity(white), 6).tolist(),
        "srgb8": np.asarray(shown.codes).astype(int).tolist(),
        "srgb_in_gamut": bool(shown.in_gamut),
        "domain_xy": np.round(domain.region_xy, 5).tolist(),
        "valid_cells": {"size": DOMAIN_GRID, "x_max": 0.8, "y_max": 0.9,
                        "cells": valid_cells[:, ::-1].tolist()},  # [column (x), row (y)]
    }


@lru_cache(maxsize=16)
def _domain(light, observer: str, grid: tuple):
    from ..recovery.validity import domain_of_validity

    return domain_of_validity(light, observer=observer, wavelengths=grid)


@lru_cache(maxsize=64)
def macadam_xy(Y: float, illuminant="D65", observer: str = "1931", step_nm: str = "5") -> list:
    """The MacAdam limit at luminance factor ``Y`` (%) as 180 chromaticities (the diagram's curve).

    Examples
    --------
    >>> len(macadam_xy(50.0))
    180
    """
    from ..coordinates import xy as chromaticity
    from ..recovery.optimal import macadam_limits

    if not (np.isfinite(Y) and 0 < Y < 100):
        raise ColorimetryError(f"Y: the MacAdam limit needs 0 < Y < 100, got {Y!r}")
    light = canonical_illuminant(illuminant)
    grid = (380.0, 780.0, STEPS_NM.get(str(step_nm)))
    limit = macadam_limits(float(Y), illuminant=light, observer=observer, wavelengths=grid, samples=180)
    return np.round(chromaticity(limit), 5).tolist()


def reflectance_lab_options() -> dict:
    """The lab's lights and grids (from the registries).

    Examples
    --------
    >>> reflectance_lab_options()["steps_nm"]
    ['5', '10']
    """
    from ..illuminants import ILLUMINANTS

    return {"illuminants": ILLUMINANTS.names(), "steps_nm": list(STEPS_NM.names()),
            "steps": [[e.name, e.label] for e in STEPS_NM.entries()]}
