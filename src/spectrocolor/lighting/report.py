"""Light source reports: :class:`~spectrocolor.lighting.summary.LightReport` as HTML, CSV or JSON.

:func:`write_light_report` writes a self-contained HTML page (headline table, TM-30 colour
vector graphics as inline SVG, hue-bin and R1–R14 tables), CSV (one row per light) or JSON
(everything, ``null`` where undefined). Compute the report with
:func:`~spectrocolor.lighting.light_report`.

References
----------
CIE 13.3-1995; CIE 224:2017; ANSI/IES TM-30-20; CIE S 026/E:2018.
"""

from __future__ import annotations

import csv
import html
import io
import json
import math
from pathlib import Path

from ..errors import ColorimetryError
from ..safe_write import write_text
from ..spreadsheet import neutralise_cell
from .alpha_opic import ALPHA_OPIC
from .fidelity import HUE_BINS
from .summary import HEADLINE, LightReport

__all__ = ["FORMATS", "report_html", "write_light_report"]

#: Report formats :func:`write_light_report` writes.
FORMATS = ("html", "csv", "json")


# ---------------------------------------------------------------------------- writers
def _number(value: float, digits: int):
    value = float(value)
    return None if not math.isfinite(value) else round(value, digits)


def _records(report: LightReport) -> list[dict]:
    digits = {"cct_K": 1, "duv": 5, "LER_lm_per_W": 2, "melanopic_DER": 4}
    headline = report.headline()
    f, c, a = report.fidelity, report.cri, report.alpha_opic
    reasons = report.reasons()
    records = []
    for i, name in enumerate(report.names):
        record: dict = {"name": name}
        record.update({key: _number(column[i], digits.get(key, 2)) for key, column in headline.items()})
        record["cri_meaningful"] = bool(c.meaningful[i])
        record["R1_R14"] = [_number(v, 2) for v in c.Ri[i]]
        record["Rf_hj"] = [_number(v, 2) for v in f.Rf_h[i]]
        record["Rcs_hj_percent"] = [_number(100 * v, 2) for v in f.Rcs_h[i]]
        record["Rhs_hj"] = [_number(v, 4) for v in f.Rhs_h[i]]
        record["alpha_opic"] = {
            alpha: {
                "irradiance_W_m2": _number(a.irradiance_W_m2[i, k], 9),
                "efficacy_mW_lm": _number(1000 * a.efficacy_W_lm[i, k], 5),
                "edi_lx": _number(a.edi_lx[i, k], 6),
                "der": _number(a.der[i, k], 5),
            }
            for k, alpha in enumerate(ALPHA_OPIC)
        }
        record["illuminance_lx"] = _number(a.illuminance_lx[i], 6)
        record["cri_rounding"] = c.rounding
        record["not_computed"] = str(reasons[i]) or None  # why metrics are null
        records.append(record)
    return records


def _csv(report: LightReport) -> str:
    columns = ["name", *HEADLINE, "cri_meaningful", *(f"R{i}" for i in range(1, 15)),
               *(f"Rf_h{j}" for j in range(1, HUE_BINS + 1)), *(f"Rcs_h{j}_percent" for j in range(1, HUE_BINS + 1)),
               *(f"Rhs_h{j}" for j in range(1, HUE_BINS + 1)), *(f"{alpha}_der" for alpha in ALPHA_OPIC),
               "not_computed"]
    buffer = io.StringIO()
    writer = csv.writer(buffer, lineterminator="\n")
    writer.writerow(columns)
    for record in _records(report):
        row = [neutralise_cell(record["name"]), *(record[key] for key in HEADLINE), record["cri_meaningful"],
               *record["R1_R14"], *record["Rf_hj"], *record["Rcs_hj_percent"], *record["Rhs_hj"],
               *(record["alpha_opic"][alpha]["der"] for alpha in ALPHA_OPIC),
               neutralise_cell(record["not_computed"] or "")]
        writer.writerow(["" if value is None else value for value in row])
    return buffer.getvalue()


def _svg(report: LightReport, index: int) -> str:
    from .vector_graphic import vector_graphic

    buffer = io.StringIO()
    vector_graphic(report.fidelity, index, title=report.names[index]).savefig(buffer, format="svg", bbox_inches="tight")
    text = buffer.getvalue()
    return text[text.index("<svg"):]


#: Decimals shown in the HTML table per headline column (the CSV and JSON keep more).
_HTML_DECIMALS = {"cct_K": 0, "duv": 4, "Ra": 1, "R9": 1, "Rf": 1, "Rg": 1, "LER_lm_per_W": 1, "melanopic_DER": 3}


def _cell(value, decimals: int | None = None) -> str:
    if value is None:
        return "–"
    return html.escape(f"{value:.{decimals}f}" if decimals is not None else str(value))


def report_html(report: LightReport, *, title: str | None = None, pictures: int = 12) -> str:
    """The report as one self-contained HTML page (vector graphics of the first ``pictures`` lights).

    Parameters
    ----------
    report : LightReport
        From :func:`spectrocolor.light_report`.
    title : str, keyword-only, optional
        The page title (default "Light source report").
    pictures : int, keyword-only, default 12
        How many lights get a TM-30 colour vector graphic (needs matplotlib).

    Returns
    -------
    str
        The HTML text.

    Examples
    --------
    >>> from spectrocolor import illuminant, light_report
    >>> page = report_html(light_report(illuminant("FL2")), pictures=0)
    >>> "<title>Light source report</title>" in page
    True
    """
    title = title or "Light source report"
    records = _records(report)
    head = "".join(f"<th title='{html.escape(text)}'>{html.escape(key)}</th>" for key, text in HEADLINE.items())
    rows = "".join(
        "<tr><td>" + html.escape(r["name"]) + "</td>"
        + "".join(f"<td>{_cell(r[key], _HTML_DECIMALS[key])}</td>" for key in HEADLINE)
        + f"<td>{'yes' if r['cri_meaningful'] else 'no'}</td>"
        + f"<td class='note'>{html.escape(r['not_computed'] or '')}</td></tr>"
        for r in records
    )
    try:
        import matplotlib  # noqa: F401
        graphics = []
        for i in range(min(pictures, len(report))):
            r = records[i]
            bins = "".join(
                f"<tr><td>{j + 1}</td><td>{_cell(r['Rf_hj'][j])}</td><td>{_cell(r['Rcs_hj_percent'][j])}</td>"
                f"<td>{_cell(r['Rhs_hj'][j])}</td></tr>" for j in range(HUE_BINS))
            special = "".join(f"<td>{_cell(v)}</td>" for v in r["R1_R14"])
            graphics.append(
                f"<section><h2>{html.escape(r['name'])}</h2><div class='pair'>{_svg(report, i)}"
                "<table><tr><th>hue bin</th><th>Rf,hj</th><th>Rcs,hj %</th><th>Rhs,hj</th></tr>"
                f"{bins}</table></div><table><tr>{''.join(f'<th>R{k}</th>' for k in range(1, 15))}</tr>"
                f"<tr>{special}</tr></table></section>")
        pictures_html = "".join(graphics)
        if len(report) > pictures:
            pictures_html += f"<p>Vector graphics of the first {pictures} of {len(report)} lights.</p>"
    except ImportError:
        pictures_html = "<p>Install matplotlib (the <code>plot</code> extra) for the colour vector graphics.</p>"
    return (
        "<!DOCTYPE html><html><head><meta charset='utf-8'>"
        f"<title>{html.escape(title)}</title><style>"
        "body{font-family:sans-serif;margin:2em}table{border-collapse:collapse;margin:0.5em 0}"
        "td,th{border:1px solid #ccc;padding:2px 6px;text-align:right}td:first-child{text-align:left}"
        ".pair{display:flex;gap:2em;align-items:flex-start}.pair svg{width:360px;height:auto}"
        "td.note{text-align:left;max-width:40em}"
        f"</style></head><body><h1>{html.escape(title)}</h1>"
        "<p>CIE 13.3-1995 (Ra, R9), CIE 224:2017 / ANSI/IES TM-30-20 (Rf, Rg, hue bins), "
        "luminous efficacy of radiation (683 lm/W, CIE 1931 V(λ)), CIE S 026 melanopic DER. "
        "CCT meaningful: CIE 13.3's |Duv| ≤ 5.4 × 10⁻³. "
        f"CIE 13.3 indices: {'rounded as CIE reports them' if report.cri.rounding == 'integer' else 'unrounded'}. "
        "A light with no power, negative power, values that are not finite or a spectrum not "
        "covering 380–780 nm is not computed (–), with the reason.</p>"
        f"<table><tr><th>name</th>{head}<th>CCT meaningful</th><th>not computed because</th></tr>{rows}</table>"
        f"{pictures_html}</body></html>"
    )


def write_light_report(report: LightReport, path, format: str | None = None, *, title: str | None = None) -> Path:
    """Write a light report as HTML, CSV or JSON (default: from the file suffix).

    Written beside ``path`` and renamed over it when complete; CSV names that a spreadsheet
    would execute get a leading apostrophe; JSON has ``null`` where a value is undefined.

    Parameters
    ----------
    report : LightReport
        From :func:`light_report`.
    path : str or os.PathLike
        Output file.
    format : {"html", "csv", "json"}, optional
        Default: from the file suffix (``.htm`` counts as HTML).
    title : str, keyword-only, optional
        HTML title.

    Returns
    -------
    pathlib.Path
        ``path``, the report in ``format``.

    Raises
    ------
    ColorimetryError
        For an unknown format.
    spectrocolor.safe_write.OutputError
        Nothing could be written; any previous report stays as it was (:term:`atomic write`).

    Examples
    --------
    >>> import tempfile, pathlib
    >>> from spectrocolor import illuminant, light_report
    >>> report = light_report(illuminant("FL2"))
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     path = write_light_report(report, pathlib.Path(folder) / "fl2.csv")
    ...     path.read_text().split(",")[:4]
    ['name', 'cct_K', 'duv', 'Ra']
    """
    path = Path(path)
    fmt = (format or path.suffix.lstrip(".")).lower()
    fmt = {"htm": "html"}.get(fmt, fmt)
    if fmt == "html":
        return write_text(path, report_html(report, title=title))
    if fmt == "csv":
        return write_text(path, _csv(report))
    if fmt == "json":
        return write_text(path, json.dumps({"lights": _records(report)}, allow_nan=False, ensure_ascii=False))
    raise ColorimetryError(f"format: {fmt!r} is not a report format; choose one of {FORMATS} (or a file ending in one)")
