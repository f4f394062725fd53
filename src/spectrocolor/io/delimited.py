"""Delimited text tables (CSV, TSV, ``;`` with decimal commas), in both common layouts.

* **Long** (one spectrum per column): optional ``#`` comment lines, a header whose first column
  is the wavelength (``wavelength_nm``, ``nm``, ``lambda`` …; ``wavelength_um``/``µm`` is
  converted to nm), then one column per spectrum.
* **Wide** (one sample per row, what most instrument software exports): a header in which at
  least three column names are wavelengths (``380``, ``380nm``, ``nm380``, ``R380``,
  ``SPECTRAL_NM380`` …, increasing); the other columns are the sample name (a column whose
  header contains "name", else the first other column) and per-sample fields kept in
  ``metadata["sample_fields"]`` (date, ID, L*a*b* …).

The delimiter is read from the header line, outside its quoted cells: a tab if it has one, else
``;`` if it has one (then a comma inside a number is a decimal comma, ``0,123``), else ``,``. Neither layout declares
percent or fraction; :func:`spectrocolor.io.text.apply_scale` applies the caller's ``percent``.

The table is read as a stream: lines are taken from the text one at a time and each row's numbers
become float64 at once (one growing ``array('d')``); only names and per-sample fields stay
strings. Memory is the text plus 8 bytes per number, where keeping every cell as a Python string
took about 11 times the file's size. Lines are split with ``str.split`` unless they hold a quote,
which Python's :mod:`csv` module then parses.
"""

from __future__ import annotations

import csv
import math
import re
from array import array
from operator import itemgetter

import numpy as np

from ..errors import SpectrumError
from ..spectrum import Spectrum
from .text import apply_scale, number, plain_ascii_numbers, wavelength_of

_MICROMETRE = re.compile(r"((^|[^a-z])um($|[^a-z])|µm|μm|micro)", re.IGNORECASE)
_NANOMETRE = re.compile(r"(nm|nanomet|wavelength|lambda|λ|wl)", re.IGNORECASE)

#: What the two layouts look like, for messages.
EXPECTED = (
    "long ('wavelength_nm,sample_1,…', one spectrum per column) or wide ('name,380,390,…' or "
    "'Sample Name,Date,380nm,…', one sample per row), delimited by ',', ';' or tab"
)


#: One line and its terminator; the terminators are those of :meth:`str.splitlines`.
_LINE = re.compile(r"([^\n\r\x0b\x0c\x1c-\x1e\x85\u2028\u2029]*)(?:\r\n|[\n\r\x0b\x0c\x1c-\x1e\x85\u2028\u2029])?")

#: A quoted cell (RFC 4180: a doubled quote inside), possessive: linear.
_QUOTED = re.compile(r'"(?:[^"]++|"")*+"')

#: Line boundaries of :meth:`str.splitlines` other than ``\n`` and ``\r\n``.
_RARE_BREAKS = "\x0b\x0c\x1c\x1d\x1e\x85\u2028\u2029"


def _lines(text: str):
    """The lines of ``text`` as :meth:`str.splitlines` gives them, one at a time."""
    if text.count("\r") == text.count("\r\n") and not any(c in text for c in _RARE_BREAKS):
        start, end = 0, len(text)  # the common case (\n or \r\n only): str.find is fastest
        while start < end:
            stop = text.find("\n", start)
            stop = end if stop < 0 else stop
            yield text[start:stop].removesuffix("\r")
            start = stop + 1
    else:
        for match in _LINE.finditer(text):
            if match.start() == len(text):  # the empty match at the very end is not a line
                break
            yield match[1]


#: Blank space, line ends included (possessive: no backtracking).
_BLANK = re.compile(r"[ \t\r\n]*+")


def _content_lines(text: str):
    """``(line number, line)`` for every line that is neither blank nor a ``#`` comment, lazily.

    Where lines end with ``\n`` or ``\r\n`` only (the common case), runs of blank lines are
    skipped at the regular-expression engine's speed: a megabyte of blank lines costs
    milliseconds, not a million steps of Python.
    """
    if text.count("\r") != text.count("\r\n") or any(c in text for c in _RARE_BREAKS):
        for line_number, line in enumerate(_lines(text), start=1):
            if line.strip() and not line.lstrip().startswith("#"):
                yield line_number, line
        return
    start, end, line_number = 0, len(text), 1
    while start < end:
        blank_end = _BLANK.match(text, start).end()
        last_break = text.rfind("\n", start, blank_end)
        if last_break >= 0:  # whole blank lines: skip them, counting
            line_number += text.count("\n", start, last_break + 1)
            start = last_break + 1
            if start >= end:
                break
        stop = text.find("\n", start)
        stop = end if stop < 0 else stop
        line = text[start:stop].removesuffix("\r")
        if line.strip() and not line.lstrip().startswith("#"):
            yield line_number, line
        line_number += 1
        start = stop + 1


def _splitter(delimiter: str, source: str):
    """A function ``(line number, line) -> cells``: ``str.split`` unless the line has quotes."""

    def cells(line_number: int, line: str) -> list[str]:
        if '"' not in line:
            return line.split(delimiter)
        try:
            (quoted,) = csv.reader([line], delimiter=delimiter)
        except (csv.Error, ValueError) as exc:  # a quoted cell over csv's field limit, NUL bytes, …
            raise SpectrumError(f"{source}, line {line_number}: not readable as delimited text ({exc})") from None
        return quoted

    return cells


class _Floats:
    """Rows of numbers converted as they are read into one growing ``array('d')``.

    Keeping floats instead of cell strings is what bounds memory: a cell string costs about
    50 bytes, its float 8.
    """

    def __init__(self, source: str, header: list[str], columns: list[int], decimal_comma: bool):
        self.data = array("d")
        self.rows = 0
        self._source, self._header, self._columns = source, header, columns
        self._decimal_comma = decimal_comma
        contiguous = columns == list(range(columns[0], columns[-1] + 1))
        self._pick = (lambda cells: cells[columns[0] : columns[-1] + 1]) if contiguous else itemgetter(*columns)

    def add(self, line_number: int, cells: list[str]) -> None:
        """Append the numeric cells of one row; SpectrumError naming the first bad cell."""
        picked = self._pick(cells)
        if not isinstance(picked, (list, tuple)):  # itemgetter of one column gives the cell itself
            picked = [picked]
        try:  # float reads more than the files' grammar (0_5, other scripts' digits): check first
            texts = [cell.replace(",", ".") for cell in picked] if self._decimal_comma else picked
            row = list(map(float, texts)) if plain_ascii_numbers(texts) else None
        except ValueError:
            row = None
        # One non-finite value makes the sum non-finite; a finite sum means every value is finite.
        if row is None or not math.isfinite(sum(row)):
            row = [self._number(line_number, i, cell) for i, cell in enumerate(picked)]
        self.data.extend(row)
        self.rows += 1

    def _number(self, line_number: int, i: int, cell: str) -> float:
        where = f"{self._source}, line {line_number}, column {self._header[self._columns[i]]!r}"
        return number(cell, where, self._decimal_comma)

    def table(self) -> np.ndarray:
        """The numbers read, shape (rows, columns), sharing the array's memory."""
        return np.frombuffer(self.data, dtype=float).reshape(self.rows, len(self._columns))


def _header(lines, source: str) -> tuple[int, list[str], str]:
    try:
        header_line, header_text = next(lines)
    except StopIteration:
        raise SpectrumError(f"{source}: no data (only comments or blank lines)") from None
    unquoted = _QUOTED.sub("", header_text)  # a ';' or tab inside a quoted name is not a delimiter
    delimiter = "\t" if "\t" in unquoted else (";" if ";" in unquoted else ",")
    header = [cell.strip() for cell in _splitter(delimiter, source)(header_line, header_text)]
    return header_line, header, delimiter


def _check_width(source: str, line_number: int, cells: list[str], header: list[str]) -> None:
    if len(cells) != len(header):
        raise SpectrumError(f"{source}, line {line_number}: {len(cells)} cells, but the header has {len(header)}")


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
    lines = _content_lines(text)
    header_line, header, delimiter = _header(lines, source)
    decimal_comma = delimiter != ","
    wavelength_columns = [(c, wavelength_of(cell)) for c, cell in enumerate(header)]
    wavelength_columns = [(c, nm) for c, nm in wavelength_columns if nm is not None]
    if wavelength_of(header[0]) is not None and len(header) >= 2 and wavelength_of(header[1]) is None:
        wavelength_columns = []  # a long table whose first header cell happens to be e.g. "nm"
    rows = (header_line, header, _splitter(delimiter, source), lines)
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
    header_line, header, cells_of, lines = rows
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
    floats = _Floats(source, header, list(range(len(header))), decimal_comma)
    for line_number, line in lines:
        cells = cells_of(line_number, line)
        _check_width(source, line_number, cells, header)
        floats.add(line_number, cells)
    if floats.rows == 0:
        raise SpectrumError(f"{source}: header but no data rows")
    data = floats.table()
    values = data[:, 1:].T
    try:
        return Spectrum(data[:, 0] * unit_scale, values if values.shape[0] > 1 else values[0], names)
    except SpectrumError as exc:
        raise SpectrumError(f"{source}: {exc}") from None


def _wide(rows, wavelength_columns, source: str, decimal_comma: bool) -> Spectrum:
    header_line, header, cells_of, lines = rows
    columns = [c for c, _ in wavelength_columns]
    wavelengths = np.array([nm for _, nm in wavelength_columns])
    numeric = set(columns)  # built once: a set per column made wide headers quadratic
    other = [c for c in range(len(header)) if c not in numeric]
    named = [c for c in other if "name" in header[c].lower()]
    name_column = named[0] if named else (other[0] if other else None)
    field_columns = [c for c in other if c != name_column]
    names, fields = [], {header[c] or f"column_{c + 1}": [] for c in field_columns}
    floats = _Floats(source, header, columns, decimal_comma)
    for line_number, line in lines:
        cells = cells_of(line_number, line)
        _check_width(source, line_number, cells, header)
        names.append(cells[name_column].strip() if name_column is not None else f"sample_{floats.rows + 1}")
        for c in field_columns:
            fields[header[c] or f"column_{c + 1}"].append(cells[c].strip())
        floats.add(line_number, cells)
    if floats.rows == 0:
        raise SpectrumError(f"{source}: header but no data rows")
    values = floats.table()
    metadata = {"sample_fields": {key: tuple(column) for key, column in fields.items()}} if fields else {}
    try:
        return Spectrum(wavelengths, values if values.shape[0] > 1 else values[0], names, metadata)
    except SpectrumError as exc:
        raise SpectrumError(f"{source}, line {header_line}: wavelength columns: {exc}") from None
