"""Colour measurement reports of reflectance samples (the workflow of seed 001, Visser 1986).

For each sample: tristimulus values X, Y, Z under an illuminant, chromaticity x, y, dominant
(or complementary) wavelength and excitation purity relative to the illuminant's white,
luminance factor (Y as a percentage of the perfect white, Visser section 1.8), CIELAB, and an
sRGB swatch. Written as one self-contained HTML file (table, chromaticity diagram and
reflectance curves embedded as base64 PNG), or as CSV or JSON.

Scale: a report of a few samples lists every one; from ``page_rows`` samples on (default 500)
the HTML lists the first ``page_rows`` and summarises every column (min, 5 %, median, 95 %,
max), the diagram becomes a rasterised density and the curves a percentile band with a few
sample curves; the CSV/JSON outputs always hold every sample.

References
----------
R. F. Visser, *Colour measurement*, Council for Mineral Technology, Technical Memorandum
19065 (1986), sections 1.5-1.8 and Appendix A (seed 001). CIE 015:2018 *Colorimetry*,
sections 7 (tristimulus values), 8.2.1 (CIELAB) and 9.1 (dominant wavelength, purity).

Why this file is long: one report: the computation of the measurement record and its three writers
(CSV, JSON, HTML) share the column table and the conditions block, so a change to a column is made
in one file.
"""

from __future__ import annotations

import base64
import csv
import html
import io
import json
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from . import notebook_hooks
from .colorimetry import DEFAULT_METHOD
from .errors import ColorimetryError, SpectrumError
from .illuminants import illuminant_label, resolve_illuminant
from .io.conditions import DECLARED, check_reflectance_scale, choose_conditions
from .observers import resolve_observer
from .plot import plain_text
from .safe_write import write_text
from .spectrum import Spectrum
from .spreadsheet import neutralise_cell

__all__ = ["MeasurementReport", "measurement_report", "write_report", "report_html"]

_COLUMNS = (
    "name", "X", "Y", "Z", "x", "y", "dominant_wavelength_nm", "complementary",
    "excitation_purity_percent", "luminance_factor_percent", "L*", "a*", "b*", "sRGB",
    "in_sRGB_gamut",
)

@dataclass(frozen=True)
class MeasurementReport:
    """Colorimetry of N reflectance samples under one illuminant and observer.

    Attributes
    ----------
    names : tuple of str (N,)
    spectra : Spectrum
        The reflectances (N, K), 0-1.
    illuminant, observer, method : str
    XYZ : ndarray (N, 3)
        XYZ100 (perfect white Y = 100).
    xy : ndarray (N, 2)
    dominant_wavelength_nm : ndarray (N,)
        Dominant wavelength, or the complementary wavelength where ``complementary``; NaN for
        the white itself.
    complementary : ndarray bool (N,)
    excitation_purity : ndarray (N,)
        0-1 (1 on the spectral locus).
    luminance_factor : ndarray (N,)
        Y as a percentage of the perfect white's Y (equals Y on the XYZ100 scale).
    lab : ndarray (N, 3)
        CIELAB relative to the perfect white under the illuminant.
    srgb8 : ndarray (N, 3) int
        sRGB codes of the colour adapted (Bradford) from the illuminant's white to sRGB's white,
        desaturated toward the white at constant Y (hue kept) where out of gamut.
    in_gamut : ndarray bool (N,)
        Whether the adapted colour fits sRGB as it is.
    srgb_hex : tuple of str (N,)
        ``srgb8`` as "#rrggbb".
    white_XYZ : ndarray (3,)
        The perfect white under the illuminant on the samples' grid.
    conditions_note : str
        ``""``, or one line where the caller's illuminant/observer differ from what the spectra's
        file declares ("the file declares D50/2°; computed under D65/10° as asked").

    Examples
    --------
    >>> import numpy as np
    >>> from spectrocolor import Spectrum, wavelength_grid
    >>> grid = wavelength_grid(380, 780, 5)
    >>> tiles = Spectrum(grid, np.stack([np.full(grid.size, 0.5), np.where(grid > 600, 0.9, 0.05)]),
    ...                  ["grey", "red"])
    >>> report = measurement_report(tiles, illuminant="C")  # seed 001's illuminant
    >>> report.XYZ.round(2).tolist(), report.dominant_wavelength_nm.round(1).tolist()
    ([[49.04, 50.0, 59.11], [31.88, 17.0, 5.92]], [nan, 620.2])
    >>> report.srgb_hex
    ('#bcbcbc', '#de2039')
    """

    names: tuple
    spectra: Spectrum
    illuminant: str
    observer: str
    method: str
    XYZ: np.ndarray
    xy: np.ndarray
    dominant_wavelength_nm: np.ndarray
    complementary: np.ndarray
    excitation_purity: np.ndarray
    luminance_factor: np.ndarray
    lab: np.ndarray
    srgb8: np.ndarray
    in_gamut: np.ndarray
    srgb_hex: tuple
    white_XYZ: np.ndarray
    conditions_note: str = ""

    _repr_html_, _repr_svg_, __repr__ = notebook_hooks.html, notebook_hooks.svg, notebook_hooks.text  # notebooks

    def __len__(self) -> int:
        return len(self.names)

    @property
    def white_xy(self) -> np.ndarray:
        """Chromaticity (x, y) of the perfect white under the illuminant, shape (2,)."""
        from .coordinates import xy

        return xy(self.white_XYZ)

    @property
    def hex(self) -> tuple[str, ...]:
        """The sRGB swatches as "#rrggbb" strings (N,)."""
        return self.srgb_hex

    def records(self) -> list[dict]:
        """One dict per sample, keys as in the CSV header; NaN as None.

        Returns
        -------
        list of dict
            One record per sample: ``name``, ``X``, ``Y``, ``Z``, ``x``, ``y``,
            ``dominant_wavelength_nm``, ``complementary``, ``excitation_purity_percent``,
            ``luminance_factor_percent``, ``L*``, ``a*``, ``b*``, ``sRGB``, ``in_sRGB_gamut``
            (numbers rounded as in the CSV).

        Examples
        --------
        >>> import numpy as np
        >>> from spectrocolor import Spectrum, wavelength_grid
        >>> grid = wavelength_grid(380, 780, 5)
        >>> tiles = Spectrum(grid, np.stack([np.full(grid.size, 0.5), np.where(grid > 600, 0.9, 0.05)]),
        ...                  ["grey", "red"])
        >>> record = measurement_report(tiles, illuminant="C").records()[1]
        >>> record["name"], record["luminance_factor_percent"], record["sRGB"]
        ('red', 17.0, '#de2039')
        """
        columns = self._columns()
        return [
            dict(zip(_COLUMNS, row, strict=True))
            for row in zip(*(columns[key] for key in _COLUMNS), strict=True)
        ]

    def _columns(self) -> dict[str, list]:
        def numbers(values, digits):
            rounded = np.round(np.asarray(values, dtype=float), digits) + 0.0  # no -0.0
            return [None if v != v else v for v in rounded.tolist()]  # NaN -> None

        return {
            "name": list(self.names),
            "X": numbers(self.XYZ[:, 0], 4),
            "Y": numbers(self.XYZ[:, 1], 4),
            "Z": numbers(self.XYZ[:, 2], 4),
            "x": numbers(self.xy[:, 0], 5),
            "y": numbers(self.xy[:, 1], 5),
            "dominant_wavelength_nm": numbers(self.dominant_wavelength_nm, 2),
            "complementary": [bool(v) for v in self.complementary],
            "excitation_purity_percent": numbers(100 * self.excitation_purity, 3),
            "luminance_factor_percent": numbers(self.luminance_factor, 4),
            "L*": numbers(self.lab[:, 0], 3),
            "a*": numbers(self.lab[:, 1], 3),
            "b*": numbers(self.lab[:, 2], 3),
            "sRGB": self.srgb_hex,
            "in_sRGB_gamut": [bool(v) for v in self.in_gamut],
        }


def measurement_report(spectra: Spectrum, *, illuminant=DECLARED, observer=DECLARED,
                       method: str = DEFAULT_METHOD) -> MeasurementReport:
    """Colorimetry of reflectance samples for a measurement report.

    Parameters
    ----------
    spectra : Spectrum
        Reflectance factors (0-1) of N samples, values (N, K) or (K,) for one.
    illuminant : str, float, Spectrum or Illuminant, keyword-only
        The light of the report, not ``None`` (seed 001 uses C), or ``"declared"`` (the default):
        the illuminant the spectra's file declares (``metadata["declared_illuminant"]``, see
        :mod:`spectrocolor.io.conditions`), else D65. Its perfect reflector is the white point of
        dominant wavelength and purity (Visser section 1.8). Where a named illuminant or observer
        differs from the file's declaration, ``conditions_note`` says so; see :term:`illuminant`.
    observer : str or Observer, keyword-only
        ``"declared"`` (the default): the file's declared observer, else CIE 1931 2° (seed 001);
        or the observer of the report; see :term:`observer`.
    method : str, keyword-only
        Summation method of :func:`spectrocolor.weights` (default ``"sum"``).

    Returns
    -------
    MeasurementReport
        XYZ100, xy, dominant (or complementary) wavelength, excitation purity, luminance
        factor, CIELAB and an sRGB swatch of every sample, with the conditions used.

    Raises
    ------
    SpectrumError
        For input that is not a Spectrum of (N, K) or (K,) reflectances, or values above 1.5
        (undeclared percentages: read the file with ``percent=True``).
    ColorimetryError
        For ``illuminant=None`` or an unknown illuminant, observer or method.

    References
    ----------
    Seed 001 (Visser 1986), §§1.7–1.8; CIE 015:2018 §§7–9.

    Examples
    --------
    >>> import numpy as np
    >>> from spectrocolor import Spectrum, wavelength_grid
    >>> grid = wavelength_grid(380, 780, 5)
    >>> tiles = Spectrum(grid, np.stack([np.full(grid.size, 0.5), np.where(grid > 600, 0.9, 0.05)]),
    ...                  ["grey", "red"])
    >>> report = measurement_report(tiles, illuminant="C")
    >>> report.names, report.luminance_factor.round(2).tolist()
    (('grey', 'red'), [50.0, 17.0])
    """
    from .chromaticity import dominant_wavelength
    from .colorimetry import tristimulus, white_point
    from .coordinates import lab, xy
    from .display.adaptation import adapt
    from .display.render import render
    from .display.spaces import rgb_space

    if not isinstance(spectra, Spectrum):
        raise SpectrumError(f"spectra must be a Spectrum; got {type(spectra).__name__}")
    values = np.atleast_2d(spectra.values)
    if values.ndim != 2:
        raise SpectrumError(f"spectra must hold (N, K) samples; got shape {values.shape}")
    if not np.all(np.isfinite(values)):
        raise SpectrumError("spectra contain NaN or infinite reflectances")
    check_reflectance_scale(spectra, "spectra")  # the command line's rule: percent is said, not guessed
    illuminant, observer, note = choose_conditions(spectra, illuminant, observer)
    samples = Spectrum(spectra.wavelengths_nm, values, spectra.names)
    names = samples.names or tuple(f"sample {i + 1}" for i in range(values.shape[0]))
    viewer, light = resolve_observer(observer), resolve_illuminant(illuminant)  # once, here
    XYZ = np.atleast_2d(tristimulus(samples, observer=viewer, illuminant=light, method=method))
    white = white_point(light, observer=viewer, wavelengths_nm=samples.wavelengths_nm, method=method)
    chromaticity = xy(XYZ)
    try:
        dominant = dominant_wavelength(chromaticity, xy(white), viewer)
    except ColorimetryError as exc:  # e.g. a very cold blackbody: name this function's argument
        raise ColorimetryError(f"illuminant: {illuminant!r:.40} has a white where {exc}") from None
    purity = np.asarray(dominant.excitation_purity, dtype=float)
    wavelength = np.asarray(dominant.wavelength_nm, dtype=float)  # NaN at the white (no hue)
    complementary = np.asarray(dominant.complementary, dtype=bool)
    srgb = rgb_space("sRGB")
    rendering = render(adapt(XYZ, white, srgb.white_XYZ, method="bradford"), space=srgb,
                       gamut="desaturate", bit_depth=8)
    codes = np.asarray(rendering.codes, dtype=int)
    return MeasurementReport(
        names=tuple(names),
        spectra=samples,
        illuminant=illuminant_label(light),
        observer=viewer.name,
        method=method,
        XYZ=XYZ,
        xy=chromaticity,
        dominant_wavelength_nm=wavelength,
        complementary=complementary,
        excitation_purity=purity,
        luminance_factor=100.0 * XYZ[:, 1] / white[1],
        lab=lab(XYZ, white),
        srgb8=codes,
        in_gamut=np.asarray(rendering.in_gamut, dtype=bool),
        srgb_hex=tuple(str(h) for h in rendering.hex),
        white_XYZ=white,
        conditions_note=note,
    )


# --- output -----------------------------------------------------------------------------------


def write_report(report: MeasurementReport, path, format: str | None = None, *,
                 title: str | None = None, page_rows: int = 500) -> Path:
    """Write a report as HTML (self-contained), CSV or JSON.

    The file is written beside ``path`` and renamed over it once complete
    (``spectrocolor.safe_write.write_text``): a failed write leaves any previous file
    unchanged. CSV names that a spreadsheet would execute (``=``, ``+``, ``-``, ``@``) get a
    leading apostrophe (``spectrocolor.spreadsheet.neutralise_cell``).

    Parameters
    ----------
    report : MeasurementReport
        From :func:`measurement_report`.
    path : str or os.PathLike
        Output file.
    format : {"html", "csv", "json"}, optional
        Default: from the file suffix.
    title : str, keyword-only, optional
        HTML title (default: "Colour measurement report").
    page_rows : int, keyword-only, default 500
        HTML only: list every sample up to this many; beyond, list this many and summarise.

    Returns
    -------
    pathlib.Path
        ``path``, the report (HTML, CSV or JSON).

    Raises
    ------
    ColorimetryError
        For an unknown format.
    spectrocolor.safe_write.OutputError
        The report could not be written in its format (HTML, CSV or JSON); see :term:`atomic write`.

    Examples
    --------
    >>> import numpy as np
    >>> from spectrocolor import Spectrum, wavelength_grid
    >>> grid = wavelength_grid(380, 780, 5)
    >>> tiles = Spectrum(grid, np.stack([np.full(grid.size, 0.5), np.where(grid > 600, 0.9, 0.05)]),
    ...                  ["grey", "red"])
    >>> import tempfile, pathlib
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     path = write_report(measurement_report(tiles, illuminant="C"), pathlib.Path(folder) / "tiles.csv")
    ...     path.read_text().splitlines()[0][:26]
    '# illuminant C, observer C'
    """
    path = Path(path)
    fmt = (format or path.suffix.lstrip(".")).lower()
    if fmt in ("htm", "html"):
        write_text(path, report_html(report, title=title, page_rows=page_rows))
    elif fmt == "csv":
        write_text(path, _csv(report))
    elif fmt == "json":
        write_text(path, json.dumps(_json(report), allow_nan=False))
    else:
        raise ColorimetryError(
            f"report format {fmt!r} is unknown; accepted: html, csv, json (or a file ending in "
            "one of them)"
        )
    return path


def _conditions(report: MeasurementReport) -> dict:
    grid = report.spectra.wavelengths_nm
    return {
        "illuminant": report.illuminant,
        "observer": report.observer,
        "method": report.method,
        "wavelengths_nm": {"start": float(grid[0]), "stop": float(grid[-1]), "count": grid.size},
        "white_XYZ": [round(float(v), 4) for v in report.white_XYZ],
        "white_xy": [round(float(v), 5) for v in report.white_xy],
        "swatch": "sRGB (IEC 61966-2-1), Bradford-adapted from the illuminant's white to D65, "
                  "desaturated toward the white at constant Y where out of gamut",
        **({"conditions_note": report.conditions_note} if report.conditions_note else {}),
    }


def _csv(report: MeasurementReport) -> str:
    buffer = io.StringIO()
    conditions = _conditions(report)
    buffer.write(f"# illuminant {conditions['illuminant']}, observer {conditions['observer']}, "
                 f"method {conditions['method']}, white XYZ {conditions['white_XYZ']}\n")
    if report.conditions_note:
        buffer.write(f"# {report.conditions_note}\n")
    writer = csv.writer(buffer, lineterminator="\n")
    writer.writerow(_COLUMNS)
    columns = report._columns()
    for row in zip(*(columns[key] for key in _COLUMNS), strict=True):
        name, *values = row  # a name a spreadsheet would execute is written as text
        writer.writerow([neutralise_cell(name), *("" if v is None else v for v in values)])
    return buffer.getvalue()


def _json(report: MeasurementReport) -> dict:
    return {**_conditions(report), "samples": report.records()}


def _png_base64(figure) -> str:
    buffer = io.BytesIO()
    figure.savefig(buffer, format="png", dpi=110)
    return base64.b64encode(buffer.getvalue()).decode("ascii")


@plain_text
def _diagram(report: MeasurementReport, dense: bool) -> str:
    from matplotlib.figure import Figure

    from .plot import chromaticity_diagram

    figure = Figure(figsize=(11, 5.4), layout="constrained")
    full, zoom = figure.subplots(1, 2)
    whites = {f"white ({report.illuminant})": report.white_XYZ}
    labels = list(report.names) if len(report) <= 12 else None
    for ax in (full, zoom):
        chromaticity_diagram(observer=report.observer, whites=whites, planckian=False, ax=ax,
                             points=None if dense else report.xy,
                             labels=labels if ax is zoom else None, title="")
        if dense:
            ax.hexbin(report.xy[:, 0], report.xy[:, 1], gridsize=60 if ax is full else 80,
                      mincnt=1, bins="log", cmap="viridis", zorder=5.5, rasterized=True,
                      extent=None if ax is full else _zoom_extent(report))
    full.set_title(f"CIE 1931 xy: {len(report)} samples, illuminant {report.illuminant}")
    x0, x1, y0, y1 = _zoom_extent(report)
    zoom.set_xlim(x0, x1)
    zoom.set_ylim(y0, y1)
    zoom.set_title("zoomed on the samples" + (" (density, log scale)" if dense else ""))
    return _png_base64(figure)


def _zoom_extent(report: MeasurementReport) -> tuple[float, float, float, float]:
    points = np.vstack([report.xy[np.all(np.isfinite(report.xy), axis=1)], report.white_xy])
    low, high = points.min(axis=0), points.max(axis=0)
    half = max(float((high - low).max()) / 2 * 1.25, 0.01)
    centre = (low + high) / 2
    return centre[0] - half, centre[0] + half, centre[1] - half, centre[1] + half


@plain_text
def _curves(report: MeasurementReport, max_curves: int = 20, shown: int = 40) -> str:
    from matplotlib.figure import Figure

    figure = Figure(figsize=(8, 4.2), layout="constrained")
    ax = figure.subplots()
    grid = report.spectra.wavelengths_nm
    values = np.atleast_2d(report.spectra.values)
    if len(report) <= max_curves:
        for i, name in enumerate(report.names):
            ax.plot(grid, values[i], lw=1.4, color=f"C{i % 10}", label=name,
                    ls="-" if i < 10 else "--")
        ax.legend(fontsize=7, ncols=2)
        ax.set_title("Reflectance curves")
    else:
        low, median, high = np.percentile(values, [5, 50, 95], axis=0)
        shown = min(shown, len(report))
        picks = np.random.default_rng(0).choice(len(report), size=shown, replace=False)
        for i in picks:
            ax.plot(grid, values[i], lw=0.5, color=f"C{i % 10}", alpha=0.6, rasterized=True)
        ax.fill_between(grid, low, high, color="0.5", alpha=0.25, label="5-95 % of samples")
        ax.plot(grid, median, color="black", lw=1.6, label="median")
        ax.plot(grid, values.min(axis=0), color="0.3", lw=0.8, ls=":", label="min / max")
        ax.plot(grid, values.max(axis=0), color="0.3", lw=0.8, ls=":")
        ax.legend(fontsize=8)
        ax.set_title(f"Reflectance of {len(report)} samples: median, 5-95 % band and "
                     f"{shown} randomly chosen samples")
    ax.set_xlabel("wavelength (nm)")
    ax.set_ylabel("reflectance factor")
    ax.grid(True, lw=0.3, color="0.85")
    return _png_base64(figure)


def _cell(value, digits: int) -> str:
    return "–" if value is None or not np.isfinite(value) else f"{value:.{digits}f}"


def _table_rows(report: MeasurementReport, count: int) -> str:
    rows = []
    hexes = report.srgb_hex
    for i in range(count):
        dominant = report.dominant_wavelength_nm[i]
        if np.isfinite(dominant):
            dominant_text = f"{dominant:.1f}" + (" c" if report.complementary[i] else "")
        else:
            dominant_text = "–"
        flag = "" if report.in_gamut[i] else ' title="outside sRGB: desaturated at constant Y"'
        mark = "" if report.in_gamut[i] else "*"
        cells = [
            html.escape(report.names[i]),
            *(_cell(v, 3) for v in report.XYZ[i]),
            *(_cell(v, 4) for v in report.xy[i]),
            dominant_text,
            _cell(100 * report.excitation_purity[i], 1),
            _cell(report.luminance_factor[i], 2),
            *(_cell(v, 2) for v in report.lab[i]),
        ]
        swatch = f'<td{flag}><span class="sw" style="background:{hexes[i]}"></span>{mark}</td>'
        rows.append("<tr><td>" + "</td><td>".join(cells) + "</td>" + swatch + "</tr>")
    return "\n".join(rows)


def _summary(report: MeasurementReport) -> str:
    quantities = {
        "X": report.XYZ[:, 0], "Y": report.XYZ[:, 1], "Z": report.XYZ[:, 2],
        "x": report.xy[:, 0], "y": report.xy[:, 1],
        "dominant / complementary λ (nm)": report.dominant_wavelength_nm,
        "excitation purity (%)": 100 * report.excitation_purity,
        "luminance factor (%)": report.luminance_factor,
        "L*": report.lab[:, 0], "a*": report.lab[:, 1], "b*": report.lab[:, 2],
    }
    rows = []
    for name, values in quantities.items():
        finite = values[np.isfinite(values)]
        if finite.size == 0:
            stats = ["–"] * 5
        else:
            stats = [f"{v:.4g}" for v in np.percentile(finite, [0, 5, 50, 95, 100])]
        rows.append(f"<tr><td>{html.escape(name)}</td><td>" + "</td><td>".join(stats)
                    + "</td></tr>")
    return (
        "<table><thead><tr><th>quantity</th><th>min</th><th>5 %</th><th>median</th>"
        "<th>95 %</th><th>max</th></tr></thead><tbody>" + "\n".join(rows) + "</tbody></table>"
        f"<p>{int(report.complementary.sum())} samples have a complementary wavelength; "
        f"{int((~report.in_gamut).sum())} lie outside sRGB.</p>"
    )


_STYLE = """
body{font-family:system-ui,sans-serif;margin:2em;color:#222;max-width:1200px}
table{border-collapse:collapse;font-size:13px;margin:1em 0}
th,td{border:1px solid #ccc;padding:3px 7px;text-align:right}
th{background:#f2f2f2}td:first-child{text-align:left}
.sw{display:inline-block;width:3em;height:1.2em;border:1px solid #888;vertical-align:middle}
img{max-width:100%}dl{display:grid;grid-template-columns:max-content auto;gap:2px 1em}
dt{font-weight:600}
"""


def report_html(report: MeasurementReport, *, title: str | None = None,
                page_rows: int = 500) -> str:
    """The report as one self-contained HTML document (figures embedded as base64 PNG).

    Parameters
    ----------
    report : MeasurementReport
        From :func:`measurement_report`.
    title : str, keyword-only, optional
        The page title (default "Colour measurement report").
    page_rows : int, keyword-only, default 500
        List every sample up to this many; beyond, list this many and summarise.

    Returns
    -------
    str
        The HTML text.

    Examples
    --------
    >>> import numpy as np
    >>> from spectrocolor import Spectrum, measurement_report, wavelength_grid
    >>> grid = wavelength_grid(380, 780, 5)
    >>> tiles = Spectrum(grid, np.stack([np.full(grid.size, 0.5), np.where(grid > 600, 0.9, 0.05)]),
    ...                  ["grey", "red"])
    >>> page = report_html(measurement_report(tiles, illuminant="C"))
    >>> page.startswith("<!DOCTYPE html>"), "<title>Colour measurement report</title>" in page
    (True, True)
    """
    title = title or "Colour measurement report"
    conditions = _conditions(report)
    n = len(report)
    dense = n > 2000
    listed = min(n, page_rows)
    grid = conditions["wavelengths_nm"]
    head = (
        "<tr><th>sample</th><th>X</th><th>Y</th><th>Z</th><th>x</th><th>y</th>"
        "<th>λ<sub>d</sub> / λ<sub>c</sub> (nm)</th><th>purity (%)</th>"
        "<th>luminance factor (%)</th><th>L*</th><th>a*</th><th>b*</th><th>sRGB</th></tr>"
    )
    parts = [
        f"<!DOCTYPE html><html lang='en'><head><meta charset='utf-8'><title>{html.escape(title)}"
        f"</title><style>{_STYLE}</style></head><body>",
        f"<h1>{html.escape(title)}</h1>",
        "<dl>",
        f"<dt>samples</dt><dd>{n}</dd>",
        f"<dt>illuminant</dt><dd>{html.escape(report.illuminant)}</dd>",
        f"<dt>observer</dt><dd>{html.escape(report.observer)}</dd>",
        f"<dt>summation</dt><dd>{html.escape(report.method)} over {grid['count']} wavelengths, "
        f"{grid['start']:g}–{grid['stop']:g} nm</dd>",
        f"<dt>white (perfect reflector)</dt><dd>X = {conditions['white_XYZ'][0]}, Y = 100, "
        f"Z = {conditions['white_XYZ'][2]}; x = {conditions['white_xy'][0]}, "
        f"y = {conditions['white_xy'][1]}</dd>",
        f"<dt>swatch</dt><dd>{conditions['swatch']}; * marks colours outside sRGB</dd>",
        *([f"<dt>conditions</dt><dd class='note'>{html.escape(report.conditions_note)}</dd>"]
          if report.conditions_note else []),
        "</dl>",
        "<p>Dominant wavelength λ<sub>d</sub> and excitation purity are relative to the "
        "illuminant's white; where the colour lies toward the purple line the complementary "
        "wavelength is given, marked c. The luminance factor is Y as a percentage of the perfect "
        "white's Y.</p>",
        "<h2>Chromaticity diagram</h2>",
        f"<img alt='chromaticity diagram' src='data:image/png;base64,{_diagram(report, dense)}'>",
        "<h2>Reflectance</h2>",
        f"<img alt='reflectance curves' src='data:image/png;base64,{_curves(report)}'>",
    ]
    if listed < n:
        parts += ["<h2>Summary of all samples</h2>", _summary(report),
                  f"<h2>First {listed} of {n} samples</h2>",
                  "<p>Every sample is in the CSV and JSON outputs "
                  "(<code>--format csv</code> / <code>--format json</code>).</p>"]
    else:
        parts.append("<h2>Samples</h2>")
    parts += [f"<table><thead>{head}</thead><tbody>", _table_rows(report, listed),
              "</tbody></table></body></html>"]
    return "\n".join(parts)
