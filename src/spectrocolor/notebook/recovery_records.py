"""What a notebook shows for a :class:`~spectrocolor.SmoothestResult`: the reflectance and its certificate.

The smoothest reflectance (van Trigt 1990) of each shown colour is drawn in that colour (its
XYZ100 under the result's illuminant on the default display), next to a table of the requested
colour, whether it is feasible, the roughness, how it was solved and the certificate of
optimality (:class:`spectrocolor.recovery.certificate.Certificate`): converged, the colour's
residual, the bound violation and the largest measure over its rounding tolerance (≤ 1 passes).
A batch lists its first :data:`SHOWN_COLOURS` and counts the rest.

Examples
--------
>>> from spectrocolor import smoothest_reflectance
>>> "certified" in smoothest_html(smoothest_reflectance([40.0, 40.0, 40.0], wavelengths=(400, 700, 10)))
True
"""

from __future__ import annotations

import numpy as np

from ..colorimetry import white_point
from ..errors import ColorimetryError, SpectrumError
from ..pictures import wavelength_tint
from . import layout
from .colours import Swatches, object_swatches
from .markup import number, scientific
from .svg import Axes, Canvas, curve, nice_ticks, spectrum_axes

__all__ = ["SHOWN_COLOURS", "smoothest_html", "smoothest_svg", "smoothest_text"]

#: Colours of a batch drawn and listed.
SHOWN_COLOURS = 8


def _count(result) -> tuple[tuple, int]:
    shape = np.shape(result.feasible)
    return shape, int(np.prod(shape, dtype=np.int64))


def _first(values, n: int, width: int | None = None) -> np.ndarray:
    array = np.asarray(values)
    return array.reshape(-1, width)[:n] if width else array.reshape(-1)[:n]


def _swatches(result, n: int) -> tuple[Swatches, str | None]:
    XYZ = _first(result.XYZ100, n, 3).astype(float)
    try:
        white = white_point(result.illuminant, observer=result.observer,
                            wavelengths_nm=result.spectrum.wavelengths_nm)
    except (ColorimetryError, SpectrumError) as exc:
        blank = Swatches([None] * n, [None] * n, ["illuminant not resolved"] * n, None)
        return blank, f"no swatches: {exc}"
    return object_swatches(XYZ, white), None


def _labels(shape: tuple, n: int) -> list[str]:
    if not shape:
        return ["colour"]
    return [f"#{i}" if len(shape) == 1 else str(tuple(int(k) for k in np.unravel_index(i, shape))) for i in range(n)]


def _plot(result, swatches: Swatches, labels: list[str], n: int) -> Canvas:
    grid = result.spectrum.wavelengths_nm
    rho = _first(result.spectrum.values, n, grid.size)
    finite = rho[np.isfinite(rho)]
    low = min(0.0, float(finite.min())) if finite.size else 0.0
    high = max(1.0, float(finite.max())) if finite.size else 1.0
    width, height = 300, 150
    canvas = Canvas(width, height, f"smoothest reflectances of {n} colours")
    axes = Axes((float(grid[0]), float(grid[-1])), (low, high), 42, 12, width - 50, height - 48)
    canvas.add(*spectrum_axes(axes, nice_ticks(low, high, 3), "reflectance factor", tint=wavelength_tint))
    for row, label, colour in zip(rho, labels, swatches.hexes, strict=True):
        canvas.add(curve(axes, grid, row, colour or "#808080", title=label))
    return canvas


def _state(feasible: bool, converged: bool) -> str:
    if not feasible:
        return "infeasible"
    return "certified" if converged else "NOT certified"


def smoothest_text(result) -> str:
    """One line: count, bounds, conditions, how many are feasible and certified.


    Examples
    --------
    >>> from spectrocolor import smoothest_reflectance
    >>> smoothest_text(smoothest_reflectance([40.0, 40.0, 40.0], wavelengths=(400, 700, 10)))
    "SmoothestResult(1 colour, bounds='unit', D65, CIE 1931 2°, K=31: certified, roughness 0.000114 nm⁻¹, \
method 'unconstrained')"
    """
    shape, count = _count(result)
    samples = result.spectrum.wavelengths_nm.size
    conditions = f"bounds={result.bounds!r}, {result.illuminant}, {result.observer}, K={samples}"
    feasible = np.asarray(result.feasible, dtype=bool).reshape(-1)
    converged = np.asarray(result.certificate.converged, dtype=bool).reshape(-1)
    if not shape:
        roughness = float(np.asarray(result.roughness))
        return (f"SmoothestResult(1 colour, {conditions}: {_state(bool(feasible[0]), bool(converged[0]))}, "
                f"roughness {roughness:.4g} nm⁻¹, method {str(np.asarray(result.method))!r})")
    certified = int(np.count_nonzero(feasible & converged))
    return (f"SmoothestResult({count:,} colours, batch shape {shape}, {conditions}: "
            f"{int(np.count_nonzero(feasible)):,} feasible, {certified:,} certified)")


def smoothest_html(result) -> str:
    """HTML: the reflectances drawn in their colours, and the certificate of each.


    Examples
    --------
    >>> from spectrocolor import smoothest_reflectance
    >>> "rounding ratio" in smoothest_html(smoothest_reflectance([40.0, 40.0, 40.0], wavelengths=(400, 700, 10)))
    True
    """
    shape, count = _count(result)
    n = min(count, SHOWN_COLOURS)
    swatches, problem = _swatches(result, n)
    labels = _labels(shape, n)
    XYZ = _first(result.XYZ100, n, 3)
    feasible = _first(result.feasible, n).astype(bool)
    outside = _first(result.distance_outside, n)
    roughness = _first(result.roughness, n)
    method = _first(result.method, n)
    certificate = result.certificate
    converged = _first(certificate.converged, n).astype(bool)
    residual, violation, ratio = (_first(v, n) for v in (certificate.primal_residual, certificate.bound_violation,
                                                         certificate.rounding_ratio))
    rows = []
    for i in range(n):
        colour = swatches.hexes[i]
        state = _state(bool(feasible[i]), bool(converged[i]))
        if not feasible[i]:
            state += f" ({number(outside[i], 3)} outside)"
        rows.append([layout.swatch(colour, swatches.explanations[i]) if colour else "—", labels[i],
                     *(number(v, 2) for v in XYZ[i]), state, scientific(roughness[i], 4), str(method[i]),
                     scientific(residual[i]), scientific(violation[i]), scientific(ratio[i], 3)])
    table = layout.table(["", "", "X", "Y", "Z", "result", "roughness nm⁻¹", "solved by", "colour residual",
                          "bound violation", "rounding ratio"], rows, text_columns=(0, 1, 5, 7))
    parts = [layout.row([_plot(result, swatches, labels, n).markup(), table]),
             layout.note("certificate: bounds held exactly, colour reproduced and KKT conditions met to within "
                         "small multiples of the rounding error (rounding ratio ≤ 1 passes)")]
    if problem:
        parts.append(layout.note(problem))
    if count > n:
        parts.append(layout.note(f"first {n} of {count:,} colours shown"))
    subtitle = (f"{'one colour' if not shape else f'{count:,} colours, batch shape {shape}'} · bounds "
                f"{result.bounds!r} · {result.illuminant}, {result.observer} · "
                f"{result.spectrum.wavelengths_nm[0]:g}–{result.spectrum.wavelengths_nm[-1]:g} nm, "
                f"K = {result.spectrum.wavelengths_nm.size}")
    return str(layout.card("SmoothestResult", subtitle, parts))


def smoothest_svg(result) -> str:
    """Standalone SVG: the reflectances of the first colours, drawn in their colours.


    Examples
    --------
    >>> from spectrocolor import smoothest_reflectance
    >>> smoothest_svg(smoothest_reflectance([40.0, 40.0, 40.0], wavelengths=(400, 700, 10))).startswith("<svg")
    True
    """
    shape, count = _count(result)
    n = min(count, SHOWN_COLOURS)
    swatches, _ = _swatches(result, n)
    return str(_plot(result, swatches, _labels(shape, n), n).markup(standalone=True))
