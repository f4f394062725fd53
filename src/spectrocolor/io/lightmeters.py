"""Exports of spectral light meters: Konica Minolta CL-500A/CL-70F, UPRtek, Sekonic.

Each is a light, read as **spectral irradiance in W·m⁻²·nm⁻¹** (``metadata["quantity"]``,
``["unit"]``; ``["value_scale"]`` says what the file's unit was and how it was converted), with
the meter's own results (illuminance, CCT, Δuv, x, y, CRI …) kept for cross-checking: every
measured item as written in ``metadata["sample_fields"]`` (one text per measurement) and the
common ones as numbers in ``metadata["stated"]`` (``illuminance_lx``, ``cct_K``, ``duv``, ``x``,
``y``; one number per measurement).

The layouts, from the makers' software descriptions and the files they write:

* **UPRtek** (MK350, MK550, CV600, the LI-180 built on them; uSpectrum "save as .xls", which is
  tab-separated text): ``key<TAB>value`` lines (``Model Name``, ``Serial Number``, ``Time``,
  ``Memo``, ``LUX``, ``fc``, ``CCT``, ``Duv``, ``I-Time``, ``X``…, ``LambdaP``, ``CRI``, ``R1``…,
  ``IRR``), then ``380nm<TAB>value`` … ``780nm``. Spectral values in mW·m⁻²·nm⁻¹ (divided by 1000).
* **Sekonic** C-700/C-800/C-7000 (C-800 Utility / SpectroMaster CSV): ``key,value`` lines
  (``Date Saved``, ``Title``, ``Measuring Mode``, ``Tcp [K]``, ``⊿uv``, ``Illuminance [lx]``,
  ``CIE1931 x`` …), then ``Spectral Data 380[nm],value`` rows, usually twice: a 5 nm block and a
  1 nm block. The finest block is read (``metadata["spectral_blocks"]`` lists them). W·m⁻²·nm⁻¹
  unless the label states a unit (``Spectral Data 380nm [mW/m²nm]``).
* **Konica Minolta** CL-500A and CL-70F (the meter's memory CSV, CL-S10w exports): either one
  measurement per row under a header (``Date, Time, Illuminance, x chromaticity, …, Tcp, delta
  uv, …, Spectrum[0] … Spectrum[420]``, where ``Spectrum[i]`` is 360 + i nm, or ``360nm`` …
  column names), or ``key,value`` lines (``Ev``, ``Tcp``, ``Δuv``, …) then ``360nm,value`` rows.
  W·m⁻²·nm⁻¹.

Several measurements side by side (more value columns on each ``key`` line, or more rows in the
header layout) are read as a batch. Recognised by content only (:func:`identify`): a file that
is recognised but malformed gets one line naming the maker's format and the line.

References
----------
The layouts as public material shows them (read, not copied): the UPRtek (CV600) and Sekonic
(C-800) example files of colour-science's test resources and its documented readers
``SpectralDistribution_UPRTek``/``SpectralDistribution_Sekonic`` (which also take the last,
1 nm, Sekonic block); a CL-500A memory CSV published with the LightOcular study
(github.com/mi3nts/LightOcular, ``raw/Minolta``: ``Spectrum[0]`` … ``Spectrum[420]`` for
360–780 nm). The units come from a rough check on those files (683 × the values near 555 nm ×
107 nm, the width of ȳ, against the stated illuminance, which settles the factor of 1000):
mW·m⁻²·nm⁻¹ for UPRtek (about 660 lx for its 695 lx), W·m⁻²·nm⁻¹ for Sekonic (29 for 30.1 lx)
and the CL-500A (8800 for 6385 lx, a bluish daylight). The CL-S10w
key/value layout and the Sekonic ``[mW/m²nm]`` label follow the makers' item names; no such
file was available to check.
"""

from __future__ import annotations

import csv
import math
import re
from array import array

import numpy as np

from ..errors import SpectrumError
from ..spectrum import Spectrum
from .text import NUMBER, number, wavelength_of

#: Makers recognised, with what their files hold (messages).
EXPECTED = {
    "UPRtek": "'LUX<TAB>…' and '380nm<TAB>value' lines",
    "Sekonic": "'Illuminance [lx],…' and 'Spectral Data 380[nm],value' lines",
    "Konica Minolta": "'Tcp' with 'Spectrum[0]…' or '360nm' columns, or 'Tcp,…' and '360nm,value' lines",
}
#: The three in one line, for the list of formats tried.
SUMMARY = ("UPRtek 'LUX'/'380nm' lines, Sekonic 'Spectral Data 380[nm]' lines, Konica Minolta 'Tcp' with "
           "'Spectrum[0]'/'360nm'")
_WHAT = {"UPRtek": "a UPRtek light-meter export", "Sekonic": "a Sekonic C-700/C-800/C-7000 export",
         "Konica Minolta": "a Konica Minolta CL-500A/CL-70F export"}
#: How far into the text the maker is identified (the headers are a few kilobytes).
_HEAD = 65536
#: Most cells one line may hold (a CL-500A row has about 460).
MAX_CELLS = 20000

_SEKONIC_ROW = re.compile(r"^\s*\"?Spectral Data\s*(?P<nm>[0-9]{3,4}(?:\.[0-9]+)?)\s*(?:\[nm\]|nm)?\s*"
                          r"(?:\[(?P<unit>[^\]]{0,40})\])?\s*\"?\s*$", re.IGNORECASE)
_NM_ROW = re.compile(r"^\s*\"?(?P<nm>[0-9]{3,4}(?:\.[0-9]+)?)\s*(?:nm|\[nm\])?\s*\"?\s*$", re.IGNORECASE)
#: A spectral row label as identification requires it: the ``nm`` written (``380nm``, ``360 nm``).
_NM_LABEL = re.compile(r"^[0-9]{3,4}(?:\.[0-9]+)?\s*nm$", re.IGNORECASE)
_SPECTRUM_INDEX = re.compile(r"^\s*Spectrum\s*\[(?P<i>[0-9]{1,4})\]\s*$", re.IGNORECASE)

#: Normalised names of the meters' common results, by the labels the makers use (case-folded,
#: brackets removed); ``x``/``y`` are matched case-sensitively (``X``/``Y`` are tristimulus).
_STATED = {
    "illuminance_lx": ("lux", "illuminance", "ev", "e", "illuminance lx"),
    "cct_k": ("cct", "tcp"),
    "duv": ("duv", "⊿uv", "δuv", "Δuv", "delta uv", "deltauv"),
    "x": ("cie1931 x", "x chromaticity"),
    "y": ("cie1931 y", "y chromaticity"),
}


def identify(text: str) -> str | None:
    """The light-meter maker whose export ``text`` is, from its first 64 KiB, or None.

    Parameters
    ----------
    text : str
        A file's text.

    Returns
    -------
    str or None
        ``"Sekonic"``, ``"UPRtek"``, ``"Konica Minolta"`` or None.

    Examples
    --------
    >>> identify("LUX\\t695.1\\nCCT\\t5198\\n380nm\\t0.03\\n381nm\\t0.03\\n")
    'UPRtek'
    >>> identify("wavelength_nm,a\\n380,1\\n") is None
    True
    """
    head = text[:_HEAD]
    # [ \t]*, not \s*: \s* would cross line ends, and a head of blank lines would take quadratic time
    if re.search(r"^[ \t]{0,20}\"?Spectral Data[ ]?[0-9]{3}", head, re.MULTILINE | re.IGNORECASE):
        return "Sekonic"
    first_cells = {_label(line.split("\t" if "\t" in line else ",")[0])
                   for line in head.splitlines()[:600] if line.strip()}
    lowered = {cell.lower() for cell in first_cells}
    if re.search(r"Spectrum ?\[0\]", head) and re.search(r"\bTcp\b", head):
        return "Konica Minolta"
    has_nm_rows = any(_NM_LABEL.match(cell) for cell in first_cells)
    if has_nm_rows and "lux" in lowered:
        return "UPRtek"
    if re.search(r"\bTcp\b", head) and (has_nm_rows or re.search(r"[,\t] ?\"?360 ?nm\"? ?[,\t]", head)):
        return "Konica Minolta"
    if re.search(r"\bCL-(?:500A|70F|S10w)\b", head) and (has_nm_rows or re.search(r"360 ?nm", head)):
        return "Konica Minolta"
    return None


def _label(cell: str) -> str:
    return cell.strip().strip('"').strip()


def _lines(text: str):
    """``(line number, line)`` for every line, lazily (``\\n`` or ``\\r\\n`` ends)."""
    start, end, number_ = 0, len(text), 1
    while start < end:
        stop = text.find("\n", start)
        stop = end if stop < 0 else stop
        yield number_, text[start:stop].removesuffix("\r")
        number_ += 1
        start = stop + 1


def _cells(line: str, delimiter: str, fail, line_number: int) -> list[str]:
    if line.count(delimiter) > MAX_CELLS:
        raise fail(line_number, f"more than {MAX_CELLS} cells on one line")
    if '"' not in line:
        cells = line.split(delimiter)
    else:
        try:
            (cells,) = csv.reader([line], delimiter=delimiter)
        except (csv.Error, ValueError) as exc:
            raise fail(line_number, f"not readable as delimited text ({exc})") from None
    while len(cells) > 1 and not cells[-1].strip():  # lines ending in the delimiter
        cells.pop()
    return [cell.strip() for cell in cells]


def parse_lightmeter(text: str, source: str, percent: bool | None = None, maker: str | None = None) -> Spectrum:
    """Spectral irradiance from a light meter's export (see the module docstring).

    Parameters
    ----------
    text : str
        The file's text.
    source : str
        File name, for messages.
    percent : bool or None, default None
        Must not be ``True``: a light is not a percentage.
    maker : str or None, default None
        ``"UPRtek"``, ``"Sekonic"`` or ``"Konica Minolta"``; ``None`` identifies it
        (:func:`identify`).

    Returns
    -------
    Spectrum
        ``(K,)`` or ``(N, K)`` spectral irradiance in W·m⁻²·nm⁻¹, with ``metadata``:
        ``format``, ``instrument``, ``quantity``, ``unit``, ``value_scale``, ``sample_fields``
        (the meter's results as written), ``stated`` (illuminance, CCT, Δuv, x, y as numbers).

    Raises
    ------
    SpectrumError
        One line, "this is a … export; line N: …", for a malformed file, or for ``percent=True``.

    Examples
    --------
    >>> s = parse_lightmeter("LUX\\t1000\\nCCT\\t2856\\n380nm\\t10.5\\n381nm\\t11\\n382nm\\t11.5\\n", "m.xls")
    >>> s.values.tolist(), s.metadata["unit"], s.metadata["stated"]["cct_K"]
    ([0.0105, 0.011, 0.0115], 'W·m⁻²·nm⁻¹', (2856.0,))
    """
    maker = maker or identify(text)
    if maker not in _WHAT:
        raise SpectrumError(f"{source}: not a light-meter export; expected one of: "
                            + "; ".join(f"{name}: {what}" for name, what in EXPECTED.items()))
    what = _WHAT[maker]

    def fail(line: int | None, message: str) -> SpectrumError:
        return SpectrumError(f"{source}: this is {what}; {'' if line is None else f'line {line}: '}{message}")

    if percent:
        raise SpectrumError(f"percent: {source} is {what}, a light (spectral irradiance), not a percentage; "
                            "leave percent unset")
    first = next((line for line in text[:_HEAD].splitlines() if line.strip()), "")
    delimiter = "\t" if "\t" in first else ("," if "," in first else ";")
    header_layout = maker == "Konica Minolta" and _header_layout(first, delimiter)
    if header_layout:
        read = _rows_layout(text, delimiter, fail, source)
    else:
        read = _key_value_layout(text, delimiter, maker, fail, source)
    grid, values, names, fields, unit_scale, unit_said, notes = read
    metadata: dict = {
        "format": f"{maker} light-meter export ({'one measurement per row' if header_layout else 'key/value lines'})",
        "instrument": _instrument(maker, fields),
        "quantity": "spectral irradiance",
        "unit": "W·m⁻²·nm⁻¹",
        "value_scale": (f"the file's {unit_said} divided by {1 / unit_scale:g} to W·m⁻²·nm⁻¹"
                        if unit_scale != 1.0 else f"as written ({unit_said})"),
        "sample_fields": {key: tuple(column) for key, column in fields.items()},
        "stated": _stated(fields),
        **notes,
    }
    try:
        return Spectrum(grid, values * unit_scale if values.shape[0] > 1 else values[0] * unit_scale,
                        names, metadata)
    except SpectrumError as exc:
        raise fail(None, str(exc)) from None


def _header_layout(first: str, delimiter: str) -> bool:
    """Whether the first line is a header naming columns (one measurement per row)."""
    cells = [_label(c) for c in first.split(delimiter)]
    spectral = sum(1 for c in cells if _SPECTRUM_INDEX.match(c) or wavelength_of(c) is not None)
    return len(cells) > 3 and spectral >= 3


def _rows_layout(text, delimiter, fail, source):
    """Konica Minolta, one measurement per row under a header of items and spectral columns."""
    lines = ((n, line) for n, line in _lines(text) if line.strip())
    header_line, header_text = next(lines)
    header = [_label(c) for c in _cells(header_text, delimiter, fail, header_line)]
    columns, grid = [], []
    for c, cell in enumerate(header):
        index = _SPECTRUM_INDEX.match(cell)
        nm = 360.0 + int(index["i"]) if index else wavelength_of(cell)
        if nm is not None:
            columns.append(c)
            grid.append(nm)
    spectral = set(columns)
    others = [c for c in range(len(header)) if c not in spectral]
    keys: dict[int, str] = {}
    for c in others:  # a name used twice (or none) gets its column number: one list per column
        key = header[c] or f"column {c + 1}"
        keys[c] = key if key not in keys.values() else f"{key} (column {c + 1})"
    fields: dict[str, list[str]] = {keys[c]: [] for c in others}
    data = array("d")
    rows = 0
    for line_number, line in lines:
        cells = _cells(line, delimiter, fail, line_number)
        if len(cells) != len(header):
            raise fail(line_number, f"{len(cells)} cells, but the header (line {header_line}) names {len(header)}")
        for c in others:
            fields[keys[c]].append(cells[c])
        where = f"{source}: this is {_WHAT['Konica Minolta']}; line {line_number}"
        data.extend(number(cells[c], f"{where}, column {header[c]!r}") for c in columns)
        rows += 1
    if rows == 0:
        raise fail(header_line, "a header but no measurement rows")
    values = np.frombuffer(data, dtype=float).reshape(rows, len(columns))
    names = _names(fields, rows)
    return np.array(grid), values, names, fields, 1.0, "W·m⁻²·nm⁻¹", {}


def _key_value_layout(text, delimiter, maker, fail, source):
    """``key,value…`` lines, then spectral rows (possibly in several blocks)."""
    fields: dict[str, list[str]] = {}
    blocks: list[tuple[list[float], array, int]] = []  # (grid, values, first line)
    width = None
    unit_label = None
    row_pattern = _SEKONIC_ROW if maker == "Sekonic" else _NM_ROW
    for line_number, line in _lines(text):
        if not line.strip():
            continue
        cells = _cells(line, delimiter, fail, line_number)
        label, texts = _label(cells[0]), cells[1:]
        match = row_pattern.match(label)
        if match is None:
            fields.setdefault(label or f"line {line_number}", texts)
            continue
        if unit_label is None and match.groupdict().get("unit"):
            unit_label = match["unit"]
        nm = float(match["nm"])
        if width is None:
            width = len(texts)
            if width == 0:
                raise fail(line_number, f"{label!r} holds no value")
        if len(texts) != width:
            raise fail(line_number, f"{label!r} holds {len(texts)} value(s), but the first spectral row holds "
                       f"{width}; every row needs one value per measurement")
        turned = False
        if blocks:  # a new block where the wavelengths repeat or turn back (Sekonic: 5 nm, then 1 nm)
            previous = blocks[-1][0]
            turned = len(previous) >= 2 and (nm - previous[-1]) * (previous[1] - previous[0]) < 0
        if not blocks or nm == blocks[-1][0][-1] or turned:
            blocks.append(([], array("d"), line_number))
        grid, data, _ = blocks[-1]
        where = f"{source}: this is {_WHAT[maker]}; line {line_number}, {label!r}"
        data.extend(number(text_, where) for text_ in texts)
        grid.append(nm)
    if not blocks or width is None:
        raise fail(None, f"no spectral rows; expected {EXPECTED[maker]}")
    chosen = min(range(len(blocks)), key=lambda b: (_finest_step(blocks[b][0]), -b))
    grid, data, _ = blocks[chosen]
    values = np.frombuffer(data, dtype=float).reshape(len(grid), width)
    notes = {}
    if len(grid) > 1 and grid[1] < grid[0]:  # written from long to short: sorted ascending
        grid, values = grid[::-1], values[::-1]
        notes["wavelength_order"] = "descending in the file; sorted ascending (values reordered with them)"
    if len(blocks) > 1:
        described = [f"{g[0]:g}–{g[-1]:g} nm, {len(g)} rows from line {first}" for g, _, first in blocks]
        notes["spectral_blocks"] = (f"{len(blocks)} spectral blocks ({'; '.join(described)}); the finest, "
                                    f"block {chosen + 1}, was read")
    values = values.T
    unit_scale, unit_said = _unit(maker, unit_label, fail)
    columns = {key: (list(v) + [""] * width)[:width] for key, v in fields.items()}
    names = _names(columns, width)
    return np.array(grid), values, names, columns, unit_scale, unit_said, notes


def _finest_step(grid: list[float]) -> float:
    return float(np.min(np.abs(np.diff(grid)))) if len(grid) > 1 else math.inf


def _unit(maker: str, label: str | None, fail) -> tuple[float, str]:
    """(factor to W·m⁻²·nm⁻¹, the unit as the file has it)."""
    if label is None:
        return (1e-3, "mW·m⁻²·nm⁻¹ (UPRtek's unit)") if maker == "UPRtek" else (1.0, "W·m⁻²·nm⁻¹")
    key = re.sub(r"[\s·*^()/⁻]", "", label.lower()).replace("²", "2").replace("μ", "µ")
    for prefix, area, factor in (("mw", "m2", 1e-3), ("µw", "cm2", 1e-2), ("uw", "cm2", 1e-2), ("w", "m2", 1.0),
                                 ("µw", "m2", 1e-6), ("uw", "m2", 1e-6), ("mw", "cm2", 10.0)):
        if key.startswith(prefix + area):
            return factor, label
    raise fail(None, f"spectral unit {label!r} is not one this reader converts (W/m²nm, mW/m²nm, µW/cm²nm)")


def _names(fields: dict[str, list[str]], count: int) -> list[str]:
    by_key = {key.lower(): column for key, column in fields.items()}
    for key in ("title", "data name", "memo", "sample", "name"):
        column = by_key.get(key)
        if column and all(column) and len(set(column)) == len(column):
            return list(column)
    date, time = by_key.get("date"), by_key.get("time")
    if date and time and len({f"{d} {t}" for d, t in zip(date, time, strict=True)}) == count:
        return [f"{d} {t}" for d, t in zip(date, time, strict=True)]
    if time and all(time) and len(set(time)) == count:
        return list(time)
    return [f"measurement {i + 1}" for i in range(count)]


def _instrument(maker: str, fields: dict[str, list[str]]) -> str:
    for key in ("Model Name", "Model", "Instrument", "Device"):
        if fields.get(key) and fields[key][0]:
            return f"{maker} {fields[key][0]}"
    return {"UPRtek": "UPRtek light meter", "Sekonic": "Sekonic C-700/C-800/C-7000",
            "Konica Minolta": "Konica Minolta CL-500A/CL-70F"}[maker]


def _stated(fields: dict[str, list[str]]) -> dict[str, tuple[float, ...]]:
    stated: dict[str, tuple[float, ...]] = {}
    for key, column in fields.items():
        if re.search(r"\[\s*fc\s*\]|\(\s*fc\s*\)", key, re.IGNORECASE):  # foot-candles, not lux
            continue
        bare = re.sub(r"\[[^\]]*\]|\([^)]*\)", "", key).strip()
        name = "x" if bare == "x" else "y" if bare == "y" else None
        if name is None:
            folded = bare.casefold()
            name = next((n for n, labels in _STATED.items() if folded in {lab.casefold() for lab in labels}), None)
        if name is None:
            continue
        name = "cct_K" if name == "cct_k" else name
        if not column or not all(NUMBER.fullmatch(cell) for cell in column):
            continue
        numbers = tuple(float(cell) for cell in column)
        if name not in stated and all(math.isfinite(v) for v in numbers):
            stated[name] = numbers
    return stated
