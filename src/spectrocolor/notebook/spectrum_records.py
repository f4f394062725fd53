"""What a notebook shows for a :class:`~spectrocolor.Spectrum`: curves, swatches, grid, XYZ/xy/λd.

A ``Spectrum`` does not say whether it holds reflectances or lights, so the view says how it
read them (and :func:`spectrum_view` lets you choose):

* **reflectance factors** — when the data say so (``metadata["spectral_quantity"]`` names a
  reflectance or transmittance) or, failing that, when every value lies in 0–1: XYZ100 under
  :data:`~spectrocolor.DEFAULT_ILLUMINANT` (perfect white Y = 100), dominant wavelength and
  excitation purity relative to that white, the swatch Bradford-adapted to the display's white
  (as :func:`spectrocolor.measurement_report` does);
* **lights** — otherwise: XYZ in the light's relative units (``k = 1``), dominant wavelength
  relative to the equal-energy white E (as the explorer's settings 1–3), each swatch as bright as
  the display allows.

A batch shows its first :data:`SHOWN_ROWS` spectra and the count; colours are computed for the
shown rows only, the value range over the whole batch up to :data:`SUMMARY_VALUES` values (over
the shown rows beyond, and said so), so a repr of a million spectra costs what one of eight does.

Examples
--------
>>> import numpy as np
>>> from spectrocolor import Spectrum, wavelength_grid
>>> grid = wavelength_grid(380, 780, 5)
>>> view = spectrum_view(Spectrum(grid, np.where(grid > 600, 0.9, 0.05), names=["red tile"]))
>>> view.reading, view.XYZ.round(2).tolist(), view.swatches.hexes
('reflectance', [[31.26, 16.84, 5.45]], ['#de2139'])
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass

import numpy as np

from ..chromaticity import dominant_wavelength
from ..colorimetry import tristimulus, white_point
from ..coordinates import xy as chromaticity
from ..errors import ColorimetryError, SpectrumError
from ..illuminants import DEFAULT_ILLUMINANT, illuminant_label
from ..observers import DEFAULT_OBSERVER, canonical_observer_name
from ..pictures import wavelength_tint
from ..sampling import resolve_observer
from ..spectrum import Spectrum
from . import layout
from .colours import DISPLAY, Swatches, light_swatches, object_swatches
from .markup import Markup, element, number
from .svg import Axes, Canvas, curve, nice_ticks, spectrum_axes, swatch_row

__all__ = ["SHOWN_ROWS", "SUMMARY_VALUES", "SpectrumView", "spectrum_view", "reading_of", "spectrum_html",
           "spectrum_svg"]

#: Spectra of a batch shown as curves, swatches and table rows; the rest are counted.
SHOWN_ROWS = 8
#: Up to this many values the value range is taken over the whole batch.
SUMMARY_VALUES = 1 << 24
#: Readings of a spectrum.
READINGS = ("reflectance", "light")
_AUTO = "auto"


@dataclass(frozen=True, eq=False)
class SpectrumView:
    """A spectrum as a notebook shows it (the colours of the shown rows only).

    Attributes
    ----------
    spectrum : Spectrum
        The spectrum (any batch shape).
    reading : str
        ``"reflectance"`` or ``"light"``.
    illuminant : str or None
        The illuminant's label (reflectances), None for lights.
    observer : str
        The observer's name.
    rows : list of int
        Flat indices (C order over the batch) of the shown spectra.
    labels : list of str
        Their names (or indices).
    XYZ : ndarray (n, 3)
        XYZ100 (reflectances) or XYZ in the light's units (lights) of the shown spectra.
    xy : ndarray (n, 2)
        Chromaticities.
    dominant_nm, purity : ndarray (n,)
        Dominant (or complementary) wavelength and excitation purity; NaN where undefined.
    complementary : ndarray of bool (n,)
        Where ``dominant_nm`` is a complementary wavelength (purples).
    swatches : Swatches
        Display colours and gamut badges of the shown spectra.
    value_range : tuple of float
        Smallest and largest value (NaN ignored).
    range_over_all : bool
        Whether ``value_range`` covers every value (else the shown rows).
    summed_nm : tuple of float or None
        The part of the grid the colours were summed over when the observer covers less than
        the whole grid (e.g. 360–830 nm of an illuminant tabulated from 300 nm), else None.
    problem : str or None
        Why no colour could be computed (e.g. a grid the observer does not cover), else None.

    Examples
    --------
    >>> from spectrocolor import Spectrum
    >>> spectrum_view(Spectrum([400, 500, 600], [2.0, 3.0, 1.0])).reading
    'light'
    """

    spectrum: Spectrum
    reading: str
    illuminant: str | None
    observer: str
    rows: list
    labels: list
    XYZ: np.ndarray
    xy: np.ndarray
    dominant_nm: np.ndarray
    purity: np.ndarray
    complementary: np.ndarray
    swatches: Swatches
    value_range: tuple
    range_over_all: bool
    summed_nm: tuple | None
    problem: str | None

    @property
    def count(self) -> int:
        """Number of spectra in the batch."""
        return int(math.prod(self.spectrum.batch_shape))

    def _repr_html_(self) -> str:
        return spectrum_html(self)

    def _repr_svg_(self) -> str:
        return spectrum_svg(self)


def reading_of(spectrum: Spectrum, value_range: tuple) -> str:
    """``"reflectance"`` or ``"light"``: what the metadata say, else whether values lie in 0–1.

    Parameters
    ----------
    spectrum : Spectrum
        The spectrum.
    value_range : tuple of float
        Its smallest and largest value.

    Returns
    -------
    str
        The reading.

    Examples
    --------
    >>> from spectrocolor import Spectrum
    >>> reading_of(Spectrum([400, 500], [0.5, 0.7]), (0.5, 0.7))
    'reflectance'
    >>> reading_of(Spectrum([400, 500], [0.5, 0.7], metadata={"spectral_quantity": "relative"}), (0.5, 0.7))
    'light'
    """
    quantity = str(spectrum.metadata.get("spectral_quantity", "")).lower()
    if quantity:
        return "reflectance" if ("reflect" in quantity or "transmit" in quantity) else "light"
    low, high = value_range
    return "reflectance" if low >= 0.0 and high <= 1.0 else "light"


def _value_range(values: np.ndarray) -> tuple[float, float]:
    if values.size == 0:
        return (math.nan, math.nan)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)  # an all-NaN batch has no range
        return (float(np.nanmin(values)), float(np.nanmax(values)))


def _labels(spectrum: Spectrum, rows: list) -> list[str]:
    shape = spectrum.batch_shape
    if not shape:
        return [spectrum.names[0] if spectrum.names else "spectrum"]
    if spectrum.names is not None:
        return [spectrum.names[i] for i in rows]
    if len(shape) == 1:
        return [f"#{i}" for i in rows]
    return [str(tuple(int(k) for k in np.unravel_index(i, shape))) for i in rows]


def spectrum_view(spectrum: Spectrum, *, illuminant=_AUTO, observer=DEFAULT_OBSERVER,
                  rows: int = SHOWN_ROWS) -> SpectrumView:
    """The notebook view of a spectrum: how it was read, and colours of its first ``rows`` spectra.

    ``Spectrum._repr_html_`` shows ``spectrum_view(spectrum)``; call it yourself to choose how
    the spectrum is read (``illuminant=None``: as lights; a name: as reflectances under it).

    Parameters
    ----------
    spectrum : Spectrum
        Any batch shape.
    illuminant : "auto", None, str, float or Spectrum, keyword-only, default "auto"
        ``"auto"``: reflectances under :data:`~spectrocolor.DEFAULT_ILLUMINANT` when the metadata or
        the 0–1 value range say so, else lights; ``None``: lights; any light: reflectances under it;
        see :term:`illuminant`.
    observer : str or Spectrum, keyword-only
        Default CIE 1931 2°.
    rows : int, keyword-only, default SHOWN_ROWS
        How many spectra of a batch to show (1–64).

    Returns
    -------
    SpectrumView
        With ``_repr_html_`` and ``_repr_svg_``.

    Raises
    ------
    SpectrumError
        For something that is not a Spectrum or ``rows`` outside 1–64.

    Examples
    --------
    >>> from spectrocolor import Spectrum, wavelength_grid
    >>> grid = wavelength_grid(400, 700, 10)
    >>> view = spectrum_view(Spectrum.constant(1.0, grid), illuminant=None)
    >>> view.reading, view.illuminant, view.xy.round(4).tolist()
    ('light', None, [[0.3333, 0.3338]])
    """
    if not isinstance(spectrum, Spectrum):
        raise SpectrumError(f"spectrum: expected a spectrocolor.Spectrum, got {type(spectrum).__name__}")
    if isinstance(rows, bool) or not isinstance(rows, int) or not 1 <= rows <= 64:
        raise SpectrumError(f"rows: expected an integer from 1 to 64, got {rows!r:.40}")
    grid = spectrum.wavelengths_nm
    flat = spectrum.values.reshape(-1, grid.size)
    shown = list(range(min(rows, flat.shape[0])))
    values = flat[: len(shown)]
    range_over_all = spectrum.values.size <= SUMMARY_VALUES
    value_range = _value_range(spectrum.values if range_over_all else values)
    if isinstance(illuminant, str) and illuminant == _AUTO:
        reading = reading_of(spectrum, value_range)
        illuminant = DEFAULT_ILLUMINANT if reading == "reflectance" else None
    else:
        reading = "light" if illuminant is None else "reflectance"
    n = len(shown)
    XYZ = np.full((n, 3), np.nan)
    dominant = np.full(n, np.nan)
    purity = np.full(n, np.nan)
    complementary = np.zeros(n, dtype=bool)
    problem = None
    swatches = Swatches([None] * n, [None] * n, ["not computed"] * n, None)
    label = summed = None
    try:
        label = illuminant_label(illuminant) if illuminant is not None else None
        sample = Spectrum(grid, values)
        cmfs = resolve_observer(observer)[1].wavelengths_nm
        low, high = max(grid[0], cmfs[0]), min(grid[-1], cmfs[-1])
        if (low > grid[0] or high < grid[-1]) and np.count_nonzero((grid >= low) & (grid <= high)) > 1:
            sample = sample.restrict(low, high)
            summed = (float(sample.wavelengths_nm[0]), float(sample.wavelengths_nm[-1]))
        grid = sample.wavelengths_nm
        if reading == "reflectance":
            XYZ = np.atleast_2d(tristimulus(sample, observer=observer, illuminant=illuminant))
            white = white_point(illuminant, observer=observer, wavelengths_nm=grid)
            swatches = object_swatches(XYZ, white)
        else:
            XYZ = np.atleast_2d(tristimulus(sample, observer=observer))
            white = tristimulus(Spectrum.constant(1.0, grid), observer=observer)
            swatches = light_swatches(XYZ, white)
        lit = np.all(np.isfinite(XYZ), axis=-1) & (XYZ[:, 1] > 0)
        if lit.any():
            found = dominant_wavelength(chromaticity(XYZ[lit]), chromaticity(white), observer)
            dominant[lit] = found.wavelength_nm
            purity[lit] = found.excitation_purity
            complementary[lit] = found.complementary
    except (ColorimetryError, SpectrumError) as exc:
        problem = str(exc)
    observer_name = canonical_observer_name(observer) if isinstance(observer, str) else "custom observer"
    with np.errstate(invalid="ignore", divide="ignore"):
        xy = chromaticity(XYZ) if np.isfinite(XYZ).any() else np.full((n, 2), np.nan)
    return SpectrumView(spectrum, reading, label, observer_name, shown, _labels(spectrum, shown), XYZ,
                        np.atleast_2d(xy), dominant, purity, complementary, swatches, value_range, range_over_all,
                        summed, problem)


# ----------------------------------------------------------------------------- pictures


def _grid_text(spectrum: Spectrum) -> str:
    grid = spectrum.wavelengths_nm
    step = spectrum.interval_nm
    spacing = f"{step:g} nm" if step is not None else "irregular grid"
    return f"{grid[0]:g}–{grid[-1]:g} nm, {spacing}, K = {grid.size}"


def _count_text(view: SpectrumView) -> str:
    shape = view.spectrum.batch_shape
    if not shape:
        return "one spectrum"
    return f"{view.count:,} spectra (batch shape {shape})"


def _reading_text(view: SpectrumView) -> str:
    summed = "" if view.summed_nm is None else \
        f"; summed over {view.summed_nm[0]:g}–{view.summed_nm[1]:g} nm, the observer's range"
    if view.reading == "reflectance":
        return (f"read as reflectance factors under {view.illuminant}, {view.observer}: XYZ100 (perfect white "
                f"Y = 100), λd and purity relative to that white; swatches on {DISPLAY}, Bradford-adapted{summed}")
    return (f"read as lights, {view.observer}: XYZ in the data's units (k = 1), λd and purity relative to the "
            f"equal-energy white E; swatches on {DISPLAY}, each as bright as it can be shown{summed}")


def _plot(view: SpectrumView, width: int = 300, height: int = 150) -> Canvas:
    spectrum = view.spectrum
    grid = spectrum.wavelengths_nm
    values = spectrum.values.reshape(-1, grid.size)[: len(view.rows)]
    low, high = _value_range(values)
    low = min(0.0, low) if math.isfinite(low) else 0.0
    high = max(high, 1.0) if view.reading == "reflectance" and math.isfinite(high) else high
    if not math.isfinite(high) or high <= low:
        high = low + 1.0
    x_range = (float(grid[0]), float(grid[-1])) if grid.size > 1 else (float(grid[0]) - 1, float(grid[0]) + 1)
    canvas = Canvas(width, height, f"{len(view.rows)} of {view.count} spectra, {_grid_text(spectrum)}")
    axes = Axes(x_range, (low, high), 42, 12, width - 50, height - 48)
    y_label = "reflectance factor" if view.reading == "reflectance" else "relative value"
    canvas.add(*spectrum_axes(axes, nice_ticks(low, high, 3), y_label, tint=wavelength_tint))
    for row, label, colour in zip(values, view.labels, view.swatches.hexes, strict=True):
        canvas.add(curve(axes, grid, row, colour or "#808080", title=label))
    return canvas


def _table(view: SpectrumView) -> Markup:
    header = ["", "name", "X", "Y", "Z", "x", "y", "λd nm", "purity", DISPLAY, ""]
    rows = []
    for i, label in enumerate(view.labels):
        colour, badge = view.swatches.hexes[i], view.swatches.badges[i]
        tip = view.swatches.explanations[i]
        wavelength = number(view.dominant_nm[i], 1)
        if view.complementary[i] and wavelength != "—":
            wavelength = f"λc {wavelength}"
        rows.append([
            layout.swatch(colour, tip) if colour else "—",
            label,
            *(number(v, 2) for v in view.XYZ[i]),
            *(number(v, 4) for v in view.xy[i]),
            wavelength,
            number(view.purity[i], 3),
            colour or "—",
            layout.badge(badge, tip) if badge else "",
        ])
    return layout.table(header, rows, text_columns=(0, 1, 10))


def spectrum_html(view) -> str:
    """HTML of a spectrum (or of its :class:`SpectrumView`): curves, swatches, grid, table.


    Examples
    --------
    >>> from spectrocolor import Spectrum
    >>> "λd nm" in spectrum_html(Spectrum([400, 500, 600], [0.2, 0.5, 0.8]))
    True
    """
    view = view if isinstance(view, SpectrumView) else spectrum_view(view)
    spectrum = view.spectrum
    facts = [_count_text(view), _grid_text(spectrum),
             f"values {number(view.value_range[0], 4)}–{number(view.value_range[1], 4)}"
             + ("" if view.range_over_all else f" (over the first {len(view.rows)})")]
    if "format" in spectrum.metadata:
        facts.append(str(spectrum.metadata["format"]))
    parts = [layout.note(_reading_text(view)),
             layout.row([_plot(view).markup(), _table(view)])]
    if view.problem:
        parts.append(layout.note(f"colours not computed: {view.problem}"))
    if view.count > len(view.rows):
        parts.append(layout.note(f"first {len(view.rows)} of {view.count:,} spectra shown; colours computed for "
                                 "these only"))
    return str(layout.card("Spectrum", " · ".join(facts), parts))


def spectrum_svg(view) -> str:
    """Standalone SVG of a spectrum: its curves above a row of swatches.


    Examples
    --------
    >>> from spectrocolor import Spectrum
    >>> spectrum_svg(Spectrum([400, 500, 600], [0.2, 0.5, 0.8])).count("<rect") > 3
    True
    """
    view = view if isinstance(view, SpectrumView) else spectrum_view(view)
    plot = _plot(view)
    canvas = Canvas(plot.width, plot.height + 26, plot.label)
    canvas.add(*plot.parts)
    canvas.add(*swatch_row(view.swatches.hexes, 42, plot.height + 4, 18,
                           [f"{label}: {line}" for label, line in zip(view.labels, view.swatches.explanations,
                                                                        strict=True)]))
    if view.count > len(view.rows):
        canvas.add(element("text", f"+ {view.count - len(view.rows)} more", x=42 + len(view.rows) * 21 + 4,
                           y=plot.height + 17, fill="currentColor"))
    return str(canvas.markup(standalone=True))
