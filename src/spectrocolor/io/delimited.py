"""Delimited text tables (CSV, TSV, ``;`` with decimal commas), in both common layouts.

* **Long** (one spectrum per column): optional ``#`` comment lines, a header whose first column
  is the wavelength (``wavelength_nm``, ``nm``, ``lambda`` …; ``wavelength_um``/``µm`` is
  converted to nm), then one column per spectrum.
* **Wide** (one sample per row, what most instrument software exports): a header in which at
  least three column names are wavelengths (``380``, ``380nm``, ``nm380``, ``R380``,
  ``SPECTRAL_NM380`` …, increasing); the other columns are the sample name (a column whose
  header contains "name", else the first other column) and per-sample fields kept in
  ``metadata["sample_fields"]`` (date, ID, L*a*b* …).

The delimiter is read from the header line: a tab if it has one, else ``;`` if it has one (then a
comma inside a number is a decimal comma, ``0,123``), else ``,``. Neither layout declares
percent or fraction; :func:`spectrocolor.io.text.apply_scale` applies the caller's ``percent``.
"""

from __future__ import annotations

import csv
import re

import numpy as np

from ..errors import SpectrumError
from ..spectrum import Spectrum
from .text import apply_scale, number_table, wavelength_of

_MICROMETRE = re.compile(r"((^|[^a-z])um($|[^a-z])|µm|μm|micro)", re.IGNORECASE)
_NANOMETRE = re.compile(r"(nm|nanomet|wavelength|lambda|λ|wl)", re.IGNORECASE)

#: What the two layouts look like, for messages.
EXPECTED = (
    "long ('wavelength_nm,sample_1,…', one spectrum per column) or wide ('name,380,390,…' or "
    "'Sample Name,Date,380nm,…', one sample per row), delimited by ',', ';' or tab"
)


def _rows(text: str, source: str) -> tuple[list[tuple[int, list[str]]], str]:
    content = [(n, line) for n, line in enumerate(text.splitlines(), start=1)]
    content = [(n, line) for n, line in content if line.strip() and not line.lstrip().startswith("#")]
    if not content:
        raise SpectrumError(f"{source}: no data (only comments or blank lines)")
    header = content[0][1]
    delimiter = "\t" if "\t" in header else (";" if ";" in header else ",")
    rows = []
    for n, line in content:
        try:
            (cells,) = csv.reader([line], delimiter=delimiter)
        except (csv.Error, ValueError) as exc:  # a cell over csv's field limit, NUL bytes, …
            raise SpectrumError(f"{source}, line {n}: not readable as delimited text ({exc})") from None
        rows.append((n, [cell.strip() for cell in cells]))
    return rows, delimiter


def parse_delimited(text: str, source: str, percent: bool | None = None) -> Spectrum:
    """Spectra from a long or wide delimited table (see the module docstring).

    Parameters
    ----------
    text : str
        The file's text (``,``, ``;`` with decimal commas, or tab separated).
    source : str
        File name, for messages.
    percent : bool or None, default None
        ``None`` keeps the values as written, ``True`` divides by 100, ``False`` keeps fractions.

    Returns
    -------
    Spectrum
        ``(N, K)`` (or ``(K,)``) with names and ``metadata`` (``format``, ``sample_fields``, …).

    Raises
    ------
    SpectrumError
        One line saying where the table is wrong.

    Examples
    --------
    >>> s = parse_delimited("Sample;Date;400nm;500nm;600nm\\ntile;2024-05-01;0,1;0,2;0,3\\n", "x.csv")
    >>> s.names, s.values.tolist(), s.metadata["sample_fields"]["Date"]
    (('tile',), [0.1, 0.2, 0.3], ('2024-05-01',))
    """
    rows, delimiter = _rows(text, source)
    header_line, header = rows[0]
    decimal_comma = delimiter != ","
    wavelength_columns = [(c, wavelength_of(cell)) for c, cell in enumerate(header)]
    wavelength_columns = [(c, nm) for c, nm in wavelength_columns if nm is not None]
    if wavelength_of(header[0]) is not None and len(header) >= 2 and wavelength_of(header[1]) is None:
        wavelength_columns = []  # a long table whose first header cell happens to be e.g. "nm"
    if len(wavelength_columns) >= 3:
        spectrum = _wide(rows, wavelength_columns, source, decimal_comma)
        layout = "wide"
    else:
        spectrum = _long(rows, source, decimal_comma)
        layout = "long"
    values, note = apply_scale(spectrum.values, None, percent, source, "")
    kind = {"\t": "TSV", ";": "CSV (; with decimal comma)", ",": "CSV"}[delimiter]
    metadata = {**spectrum.metadata, "format": f"{kind}, {layout}", "value_scale": note}
    return Spectrum(spectrum.wavelengths_nm, values, spectrum.names, metadata)


def _long(rows, source: str, decimal_comma: bool) -> Spectrum:
    header_line, header = rows[0]
    if wavelength_of(header[0]) is not None and re.fullmatch(r"[\d.,\s]+", header[0]):
        raise SpectrumError(
            f"{source}, line {header_line}: missing header; the first line must name the columns, "
            "e.g. 'wavelength_nm,sample_1,sample_2' (or, one sample per row, 'name,380,390,…')"
        )
    unit_scale = 1.0
    if _MICROMETRE.search(header[0]):
        unit_scale = 1000.0
    elif not _NANOMETRE.search(header[0]):
        raise SpectrumError(
            f"{source}, line {header_line}: not a spectral table: first column {header[0][:40]!r} is not "
            "recognisably a wavelength and fewer than three column names are wavelengths"
        )
    if len(header) < 2:
        raise SpectrumError(
            f"{source}, line {header_line}: header has {len(header)} column(s); need a wavelength column "
            "and at least one spectrum column (delimiters read: tab, ';' or ',')"
        )
    names = header[1:]
    if len(set(names)) != len(names):
        raise SpectrumError(f"{source}, line {header_line}: duplicate column names in {names[:8]}")
    if len(rows) < 2:
        raise SpectrumError(f"{source}: header but no data rows")
    for line_number, row in rows[1:]:
        if len(row) != len(header):
            raise SpectrumError(f"{source}, line {line_number}: {len(row)} cells, but the header has {len(header)}")
    data = number_table(
        [row for _, row in rows[1:]],
        lambda r, c: f"{source}, line {rows[r + 1][0]}, column {header[c]!r}",
        decimal_comma,
    )
    values = data[:, 1:].T
    try:
        return Spectrum(data[:, 0] * unit_scale, values if values.shape[0] > 1 else values[0], names)
    except SpectrumError as exc:
        raise SpectrumError(f"{source}: {exc}") from None


def _wide(rows, wavelength_columns, source: str, decimal_comma: bool) -> Spectrum:
    header_line, header = rows[0]
    columns = [c for c, _ in wavelength_columns]
    wavelengths = np.array([nm for _, nm in wavelength_columns])
    other = [c for c in range(len(header)) if c not in set(columns)]
    named = [c for c in other if "name" in header[c].lower()]
    name_column = named[0] if named else (other[0] if other else None)
    if len(rows) < 2:
        raise SpectrumError(f"{source}: header but no data rows")
    names, fields = [], {header[c] or f"column_{c + 1}": [] for c in other if c != name_column}
    for r, (line_number, row) in enumerate(rows[1:]):
        if len(row) != len(header):
            raise SpectrumError(f"{source}, line {line_number}: {len(row)} cells, but the header has {len(header)}")
        names.append(row[name_column] if name_column is not None else f"sample_{r + 1}")
        for c in other:
            if c != name_column:
                fields[header[c] or f"column_{c + 1}"].append(row[c])
    values = number_table(
        [[row[c] for c in columns] for _, row in rows[1:]],
        lambda r, i: f"{source}, line {rows[r + 1][0]}, column {header[columns[i]]!r}",
        decimal_comma,
    )
    metadata = {"sample_fields": {key: tuple(column) for key, column in fields.items()}} if fields else {}
    try:
        return Spectrum(wavelengths, values if values.shape[0] > 1 else values[0], names, metadata)
    except SpectrumError as exc:
        raise SpectrumError(f"{source}, line {header_line}: wavelength columns: {exc}") from None
