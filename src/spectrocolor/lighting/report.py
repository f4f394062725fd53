"""Light source reports: every metric of :mod:`spectrocolor.lighting` for each spectrum.

:func:`summary` gives the headline numbers of one light as plain floats (for the explorer app
and other callers); :func:`light_report` computes everything for a batch at once;
:func:`write_light_report` writes it as a self-contained HTML page (table, TM-30 colour vector
graphics as inline SVG, hue-bin and R1–R14 tables), as CSV (one row per light) or as JSON.

Columns: CCT (K), Duv, Ra, R9 (CIE 13.3), Rf, Rg (CIE 224:2017 / TM-30-20), luminous efficacy
of radiation (lm/W), melanopic DER (CIE S 026), and whether CIE 13.3 considers the CCT
meaningful (|Duv| ≤ 5.4 × 10⁻³).

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
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..errors import ColorimetryError
from ..safe_write import write_text
from ..spectrum import Spectrum
from ..spreadsheet import neutralise_cell
from .alpha_opic import ALPHA_OPIC, AlphaOpic, alpha_opic
from .cri import CRI, colour_rendering_index
from .fidelity import HUE_BINS, Fidelity, colour_fidelity
from .photometry import luminous_efficacy_of_radiation

#: Report formats :func:`write_light_report` writes.
FORMATS = ("html", "csv", "json")
#: The headline columns, in order (name → description with unit).
HEADLINE = {
    "cct_K": "correlated colour temperature, K",
    "duv": "distance from the Planckian locus, CIE 1960 uv",
    "Ra": "CIE 13.3 general colour rendering index",
    "R9": "CIE 13.3 special index of TCS09 (red)",
    "Rf": "CIE 224:2017 / TM-30 fidelity index",
    "Rg": "TM-30 gamut index",
    "LER_lm_per_W": "luminous efficacy of radiation, lm/W",
    "melanopic_DER": "CIE S 026 melanopic daylight (D65) efficacy ratio",
}


@dataclass(frozen=True)
class LightReport:
    """All lighting metrics of N lights (flattened batch), with their names.

    Attributes
    ----------
    names : tuple of str
    cri : CRI
    fidelity : Fidelity
    ler_lm_per_W : ndarray (N,)
    alpha_opic : AlphaOpic
    """

    names: tuple
    cri: CRI
    fidelity: Fidelity
    ler_lm_per_W: np.ndarray
    alpha_opic: AlphaOpic

    def __len__(self) -> int:
        return len(self.names)

    def headline(self) -> dict[str, np.ndarray]:
        """The :data:`HEADLINE` columns as arrays (N,)."""
        return {
            "cct_K": self.fidelity.cct_K,
            "duv": self.fidelity.duv,
            "Ra": self.cri.Ra,
            "R9": self.cri.R9,
            "Rf": self.fidelity.Rf,
            "Rg": self.fidelity.Rg,
            "LER_lm_per_W": self.ler_lm_per_W,
            "melanopic_DER": self.alpha_opic.melanopic_der,
        }


def _flat(spd: Spectrum) -> Spectrum:
    return spd if spd.values.ndim == 2 else Spectrum(spd.wavelengths_nm, spd.values.reshape(-1, spd.values.shape[-1]))


def light_report(spd) -> LightReport:
    """Every lighting metric of lights ``(..., K)`` (flattened to N lights).

    ``spd`` as for :func:`~spectrocolor.lighting.colour_fidelity` (1 or 5 nm, 380–780 nm at
    least); CIE 13.3 uses samples from 360 nm where present.

    Examples
    --------
    >>> from spectrocolor import illuminant
    >>> report = light_report(illuminant("FL2"))
    >>> len(report), round(float(report.fidelity.Rf[0]), 1)
    (1, 70.1)
    """
    from .spectra import light_grid

    light_grid(spd, 380.0, 780.0)  # one clear error before any work
    flat = _flat(spd)
    names = spd.names if spd.names and len(spd.names) == len(flat.values) else tuple(
        f"spectrum {i + 1}" for i in range(len(flat.values)))
    return LightReport(
        names=tuple(names),
        cri=colour_rendering_index(flat),
        fidelity=colour_fidelity(flat),
        ler_lm_per_W=luminous_efficacy_of_radiation(flat),
        alpha_opic=alpha_opic(flat),
    )


def summary(spd) -> dict[str, float | bool]:
    """Headline numbers of one light as plain Python floats: CCT, Duv, Ra, R9, Rf, Rg, LER, DER.

    For the explorer app and other callers that want JSON-ready values; NaN where a metric is
    undefined (no CCT). ``cri_meaningful`` is CIE 13.3's |Duv| ≤ 5.4 × 10⁻³.

    Examples
    --------
    >>> from spectrocolor import illuminant
    >>> values = summary(illuminant("FL2"))
    >>> {key: round(values[key], 1) for key in ("cct_K", "Ra", "Rf", "Rg")}
    {'cct_K': 4224.5, 'Ra': 64.2, 'Rf': 70.1, 'Rg': 86.4}
    """
    if not isinstance(spd, Spectrum) or spd.batch_shape not in ((), (1,)):
        shape = spd.batch_shape if isinstance(spd, Spectrum) else type(spd).__name__
        raise ColorimetryError(f"spd: summary takes one light (a Spectrum of shape (K,)), got {shape}")
    report = light_report(spd)
    values: dict[str, float | bool] = {key: float(column[0]) for key, column in report.headline().items()}
    values["cri_meaningful"] = bool(report.cri.meaningful[0])
    return values


# ---------------------------------------------------------------------------- writers
def _number(value: float, digits: int):
    value = float(value)
    return None if not math.isfinite(value) else round(value, digits)


def _records(report: LightReport) -> list[dict]:
    digits = {"cct_K": 1, "duv": 5, "LER_lm_per_W": 2, "melanopic_DER": 4}
    headline = report.headline()
    f, c, a = report.fidelity, report.cri, report.alpha_opic
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
        records.append(record)
    return records


def _csv(report: LightReport) -> str:
    columns = ["name", *HEADLINE, "cri_meaningful", *(f"R{i}" for i in range(1, 15)),
               *(f"Rf_h{j}" for j in range(1, HUE_BINS + 1)), *(f"Rcs_h{j}_percent" for j in range(1, HUE_BINS + 1)),
               *(f"Rhs_h{j}" for j in range(1, HUE_BINS + 1)), *(f"{alpha}_der" for alpha in ALPHA_OPIC)]
    buffer = io.StringIO()
    writer = csv.writer(buffer, lineterminator="\n")
    writer.writerow(columns)
    for record in _records(report):
        row = [neutralise_cell(record["name"]), *(record[key] for key in HEADLINE), record["cri_meaningful"],
               *record["R1_R14"], *record["Rf_hj"], *record["Rcs_hj_percent"], *record["Rhs_hj"],
               *(record["alpha_opic"][alpha]["der"] for alpha in ALPHA_OPIC)]
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
    """The report as one self-contained HTML page (vector graphics of the first ``pictures`` lights)."""
    title = title or "Light source report"
    records = _records(report)
    head = "".join(f"<th title='{html.escape(text)}'>{html.escape(key)}</th>" for key, text in HEADLINE.items())
    rows = "".join(
        "<tr><td>" + html.escape(r["name"]) + "</td>"
        + "".join(f"<td>{_cell(r[key], _HTML_DECIMALS[key])}</td>" for key in HEADLINE)
        + f"<td>{'yes' if r['cri_meaningful'] else 'no'}</td></tr>"
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
        f"</style></head><body><h1>{html.escape(title)}</h1>"
        "<p>CIE 13.3-1995 (Ra, R9), CIE 224:2017 / ANSI/IES TM-30-20 (Rf, Rg, hue bins), "
        "luminous efficacy of radiation (683 lm/W, CIE 1931 V(λ)), CIE S 026 melanopic DER. "
        "CCT meaningful: CIE 13.3's |Duv| ≤ 5.4 × 10⁻³.</p>"
        f"<table><tr><th>name</th>{head}<th>CCT meaningful</th></tr>{rows}</table>"
        f"{pictures_html}</body></html>"
    )


def write_light_report(report: LightReport, path, format: str | None = None, *, title: str | None = None) -> Path:
    """Write a light report as HTML, CSV or JSON (default: from the file suffix).

    Written beside ``path`` and renamed over it when complete; CSV names that a spreadsheet
    would execute get a leading apostrophe; JSON has ``null`` where a value is undefined.
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
