"""What a notebook shows for a :class:`~spectrocolor.MeasurementReport`: its table (seed 001's workflow).

The first :data:`SHOWN_ROWS` samples with their swatch (the report's own sRGB codes), X, Y, Z,
x, y, dominant (λd) or complementary (λc) wavelength, excitation purity, luminance factor and
CIELAB, the gamut badge where the report's colour had to be brought into sRGB, and the curves of
the first samples in their colours; the conditions (illuminant, observer, summation) above.

Examples
--------
>>> import numpy as np
>>> from spectrocolor import Spectrum, measurement_report, wavelength_grid
>>> grid = wavelength_grid(380, 780, 5)
>>> report = measurement_report(Spectrum(grid, np.where(grid > 600, 0.9, 0.05), ["red"]), illuminant="C")
>>> "#de2039" in measurement_report_html(report)
True
"""

from __future__ import annotations

import numpy as np

from ..pictures import wavelength_tint
from . import layout
from .colours import object_swatches
from .markup import number
from .svg import Axes, Canvas, curve, nice_ticks, spectrum_axes

__all__ = ["SHOWN_ROWS", "SHOWN_CURVES", "measurement_report_html", "measurement_report_svg",
           "measurement_report_text"]

#: Samples listed in the table.
SHOWN_ROWS = 20
#: Samples drawn as curves.
SHOWN_CURVES = 8


def _plot(report) -> Canvas:
    spectra = report.spectra
    grid = spectra.wavelengths_nm
    n = min(len(report), SHOWN_CURVES)
    values = np.asarray(spectra.values).reshape(-1, grid.size)[:n]
    high = max(1.0, float(np.nanmax(values))) if values.size else 1.0
    width, height = 300, 150
    canvas = Canvas(width, height, f"reflectances of the first {n} samples")
    axes = Axes((float(grid[0]), float(grid[-1])), (0.0, high), 42, 12, width - 50, height - 48)
    canvas.add(*spectrum_axes(axes, nice_ticks(0.0, high, 3), "reflectance factor", tint=wavelength_tint))
    for row, name, colour in zip(values, report.names, report.srgb_hex, strict=False):
        canvas.add(curve(axes, grid, row, colour, title=name))
    return canvas


def _conditions(report) -> str:
    count = len(report)
    samples = "1 sample" if count == 1 else f"{count:,} samples"
    white = report.white_xy
    return (f"{samples} · illuminant {report.illuminant}, {report.observer}, summation {report.method!r} · white "
            f"x, y = {number(white[0], 4)}, {number(white[1], 4)}")


def measurement_report_text(report) -> str:
    """One line: the number of samples, the conditions and the first samples' swatches.


    Examples
    --------
    >>> import numpy as np
    >>> from spectrocolor import Spectrum, measurement_report, wavelength_grid
    >>> grid = wavelength_grid(380, 780, 5)
    >>> measurement_report_text(measurement_report(Spectrum(grid, np.full(grid.size, 0.5), ["grey"]), illuminant="C"))
    "MeasurementReport(1 sample · illuminant C, CIE 1931 2°, summation 'sum' · white x, y = 0.3101, 0.3162: \
grey #bcbcbc)"
    """
    shown = ", ".join(f"{name} {colour}" for name, colour in zip(report.names[:3], report.srgb_hex[:3],
                                                                 strict=True))
    more = ", …" if len(report) > 3 else ""
    return f"MeasurementReport({_conditions(report)}: {shown}{more})"


def measurement_report_html(report) -> str:
    """HTML: the conditions, the curves of the first samples and the table of the first rows.


    Examples
    --------
    >>> import numpy as np
    >>> from spectrocolor import Spectrum, measurement_report, wavelength_grid
    >>> grid = wavelength_grid(380, 780, 5)
    >>> "λd nm" in measurement_report_html(measurement_report(Spectrum(grid, np.full(grid.size, 0.5))))
    True
    """
    n = min(len(report), SHOWN_ROWS)
    badges = object_swatches(report.XYZ[:n], report.white_XYZ)
    rows = []
    for i in range(n):
        colour = report.srgb_hex[i]
        wavelength = number(report.dominant_wavelength_nm[i], 1)
        if report.complementary[i] and wavelength != "—":
            wavelength = f"λc {wavelength}"
        badge = None if report.in_gamut[i] else badges.badges[i]
        rows.append([layout.swatch(colour, badges.explanations[i]), report.names[i],
                     *(number(v, 2) for v in report.XYZ[i]), *(number(v, 4) for v in report.xy[i]), wavelength,
                     number(100 * report.excitation_purity[i], 1), number(report.luminance_factor[i], 2),
                     *(number(v, 2) for v in report.lab[i]), colour,
                     layout.badge(badge, badges.explanations[i]) if badge else ""])
    table = layout.table(["", "name", "X", "Y", "Z", "x", "y", "λd nm", "purity %", "Y %", "L*", "a*", "b*",
                          "sRGB", ""], rows, text_columns=(0, 1, 14))
    parts = [_plot(report).markup(), table,
             layout.note("seed 001 (Visser): XYZ100 under the illuminant, λd and purity relative to its white, "
                         "swatches Bradford-adapted to sRGB")]
    if len(report) > n:
        parts.append(layout.note(f"first {n} of {len(report):,} samples listed; write_report writes every one"))
    return str(layout.card("MeasurementReport", _conditions(report), parts))


def measurement_report_svg(report) -> str:
    """Standalone SVG: the curves of the first samples in their colours.


    Examples
    --------
    >>> import numpy as np
    >>> from spectrocolor import Spectrum, measurement_report, wavelength_grid
    >>> grid = wavelength_grid(380, 780, 5)
    >>> measurement_report_svg(measurement_report(Spectrum(grid, np.full(grid.size, 0.5)))).startswith("<svg")
    True
    """
    return str(_plot(report).markup(standalone=True))
