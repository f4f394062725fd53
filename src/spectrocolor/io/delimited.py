"""Delimited text tables (CSV, TSV, ``;`` with decimal commas), in both common layouts.

* **Long** (one spectrum per column): optional ``#`` comment lines, a header whose first column
  is the wavelength (``wavelength_nm``, ``nm``, ``lambda`` …; ``wavelength_um``/``µm`` is
  converted to nm), then one column per spectrum.
* **Wide** (one sample per row, what most instrument software exports): a header in which at
  least three column names are wavelengths (``380``, ``380nm``, ``nm380``, ``R380``,
  ``SPECTRAL_NM380`` …, increasing); the other columns are the sample name (a column whose
  header contains "name", else the first other column) and per-sample fields kept in
  ``metadata["sample_fields"]`` (date, ID, L*a*b* …).
* **Paired** (Agilent Cary WinUV): a row of sample names over a row ``Wavelength (nm),%R,…``
  (or that row alone, two pairs or more), one wavelength/value pair per sample on each line;
  one spectrum per pair, identical grids stacked exactly, differing grids interpolated onto the
  first sample's within the common range (``metadata["resampled"]`` says so). The data end at
  the first line that does not start with a number (Cary's method notes follow).

Lines ending in the delimiter (Excel, LibreOffice, Cary) are read: empty trailing header cells
and the matching empty cells are dropped, a value under an empty header cell is an error.
Wavelengths written from long to short are sorted ascending with their values
(``metadata["wavelength_order"]``).

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
from . import cary
from .text import apply_scale, number, plain_ascii_numbers, wavelength_of

#: Lines after a paired table's data kept in ``metadata["notes_after_data"]`` (Cary's method block).
_MAX_NOTES = 200

#: The start of a number (data rows of a paired table begin with one).
NUMBER_START = re.compile(r"[+-]?\.?[0-9]")

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
        blank = _BLANK.match(text, start)
        assert blank is not None  # the pattern matches the empty string too
        blank_end = blank.end()
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
    header = _trimmed([cell.strip() for cell in _splitter(delimiter, source)(header_line, header_text)])
    return header_line, header, delimiter


def _trimmed(cells: list[str]) -> list[str]:
    """``cells`` without empty trailing cells (a line ending in the delimiter), keeping at least one."""
    end = len(cells)
    while end > 1 and not cells[end - 1].strip():
        end -= 1
    return cells if end == len(cells) else cells[:end]


def _row_splitter(cells_of, width: int, source: str):
    """``cells_of`` whose rows lose cells beyond ``width`` when they are all empty.

    Excel, LibreOffice and Cary end lines with the delimiter: the header's empty trailing cells
    are dropped by :func:`_header`, and here the matching empty cells of each row. A value under
    an empty header cell is an error (the column is dropped only when it is empty throughout).
    """

    def cells(line_number: int, line: str) -> list[str]:
        row = cells_of(line_number, line)
        if len(row) > width:
            extra = next((i for i in range(width, len(row)) if row[i].strip()), None)
            if extra is not None:
                raise SpectrumError(
                    f"{source}, line {line_number}: {len(row)} cells, but the header has {width} (cell {extra + 1} "
                    f"holds {row[extra].strip()[:40]!r} under no column name; name that column in the header)"
                )
            return row[:width]
        return row

    return cells


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
    lines = _Pushback(_content_lines(text))
    header_line, header, delimiter = _header(lines, source)
    decimal_comma = delimiter != ","
    raw_cells = _splitter(delimiter, source)
    cells_of = _row_splitter(raw_cells, len(header), source)
    paired = _paired_header(header, lines, raw_cells, header_line)
    if paired is not None:
        spectrum = _paired(paired, lines, raw_cells, source, decimal_comma)
        declared, how = _declared_percent(paired[1])
        values, note = apply_scale(spectrum.values, declared, percent, source, how)
        kind = {"\t": "TSV", ";": "CSV (; with decimal comma)", ",": "CSV"}[delimiter]
        metadata = {**spectrum.metadata, "format": f"{kind}, paired wavelength/value columns", "value_scale": note}
        metadata.update(cary.recognise(metadata, paired[3] != header_line))
        return Spectrum(spectrum.wavelengths_nm, values, spectrum.names, metadata)
    wavelength_columns = [(c, wavelength_of(cell)) for c, cell in enumerate(header)]
    wavelength_columns = [(c, nm) for c, nm in wavelength_columns if nm is not None]
    if wavelength_of(header[0]) is not None and len(header) >= 2 and wavelength_of(header[1]) is None:
        wavelength_columns = []  # a long table whose first header cell happens to be e.g. "nm"
    rows = (header_line, header, cells_of, lines)
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
    metadata = {}
    if len(data) > 1 and np.all(np.diff(data[:, 0]) < 0):  # a descending scan: sorted ascending
        data = data[::-1]
        metadata["wavelength_order"] = _DESCENDING
    values = data[:, 1:].T
    try:
        return Spectrum(data[:, 0] * unit_scale, values if values.shape[0] > 1 else values[0], names, metadata)
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
    names: list[str] = []
    fields: dict[str, list[str]] = {header[c] or f"column_{c + 1}": [] for c in field_columns}
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
    metadata: dict = {"sample_fields": {key: tuple(column) for key, column in fields.items()}} if fields else {}
    if len(wavelengths) > 1 and np.all(np.diff(wavelengths) < 0):  # columns from long to short: sorted
        wavelengths, values = wavelengths[::-1], values[:, ::-1]
        metadata["wavelength_order"] = _DESCENDING
    try:
        return Spectrum(wavelengths, values if values.shape[0] > 1 else values[0], names, metadata)
    except SpectrumError as exc:
        raise SpectrumError(f"{source}, line {header_line}: wavelength columns: {exc}") from None


#: ``metadata["wavelength_order"]`` of a file written from long to short wavelengths.
_DESCENDING = "descending in the file; sorted ascending (values reordered with them)"


def _declared_percent(kinds) -> tuple[float | None, str]:
    """``(100.0, how)`` when every value column is titled ``%R`` or ``%T`` (Cary's percent
    reflectance or transmittance), else ``(None, "")``: the file does not say."""
    if kinds and all(re.fullmatch(r"%\s*[RT]", kind.strip(), re.IGNORECASE) for kind in kinds):
        return 100.0, f"value columns titled {'/'.join(sorted({kind.strip() for kind in kinds}))}"
    return None, ""


def _is_wavelength_title(cell: str) -> bool:
    """Whether a header cell titles a wavelength column (``Wavelength (nm)``, ``nm``, ``λ``), not a number."""
    return bool(_NANOMETRE.search(cell) or _MICROMETRE.search(cell)) and not re.fullmatch(r"[\d.,\s]+", cell)


def _paired_header(header: list[str], lines, cells_of, header_line: int):
    """The layout of paired wavelength/value columns, or None (then ``lines`` is untouched).

    Recognised: a header of pairs ``Wavelength (nm),%R,Wavelength (nm),%R,…`` (two pairs or
    more), or such a row of pairs (one or more) under a row of sample names, one name over each
    pair (Cary WinUV). Returns ``(names, kinds, unit_scales, header_line)``.
    """
    def pairs(cells):
        if len(cells) < 2 or len(cells) % 2:
            return False
        return (all(_is_wavelength_title(c) for c in cells[0::2])
                and all(c.strip() and not _is_wavelength_title(c) for c in cells[1::2]))

    def scales(cells):
        return [1000.0 if _MICROMETRE.search(c) else 1.0 for c in cells[0::2]]

    if pairs(header) and len(header) >= 4:
        kinds = header[1::2]
        names = [f"{kind} {i + 1}" for i, kind in enumerate(kinds)] if len(set(kinds)) < len(kinds) else kinds
        return names, kinds, scales(header), header_line
    if wavelength_of(header[0]) is not None or _is_wavelength_title(header[0]) or not header[0]:
        return None
    # a row of names over a row of pairs: peek at the next line (put back when it is not that)
    try:
        second_line, second_text = next(lines)
    except StopIteration:
        return None
    second = _trimmed([c.strip() for c in cells_of(second_line, second_text)])
    names_row = header + [""] * (len(second) - len(header))
    if not pairs(second) or len(names_row) != len(second) or not all(names_row[0::2]):
        lines.send_back((second_line, second_text))
        return None
    return names_row[0::2], second[1::2], scales(second), second_line


class _Pushback:
    """An iterator of ``(line number, line)`` into which one line can be sent back."""

    def __init__(self, lines):
        self._lines, self._back = lines, []

    def __iter__(self):
        return self

    def __next__(self):
        return self._back.pop() if self._back else next(self._lines)

    def send_back(self, item) -> None:
        self._back.append(item)


def _paired(layout, lines, cells_of, source: str, decimal_comma: bool) -> Spectrum:
    """One spectrum per wavelength/value pair; grids sorted ascending, stacked or resampled.

    Data rows end at the first row whose first cell is not a number (Cary writes its method and
    collection notes after the data); a sample whose scan is shorter leaves its cells empty.
    """
    names, kinds, unit_scales, header_line = layout
    width = 2 * len(names)
    columns: list[array] = [array("d") for _ in range(width)]
    trailer = 0
    notes: list[str] = []
    for line_number, line in lines:
        cells = cells_of(line_number, line)
        if trailer or NUMBER_START.match(cells[0].strip()) is None:
            trailer += 1
            if len(notes) < _MAX_NOTES:  # Cary's sample names, Collection Time, method: kept, bounded
                notes.append(",".join(c.strip() for c in cells if c.strip())[:200])
            continue
        extra = next((i for i in range(width, len(cells)) if cells[i].strip()), None)
        if extra is not None:
            raise SpectrumError(f"{source}, line {line_number}: cell {extra + 1} holds {cells[extra].strip()[:40]!r}, "
                                f"but the header names {len(names)} wavelength/value pair(s)")
        cells = cells[:width] + [""] * (width - len(cells))
        for p in range(len(names)):
            wl, value = cells[2 * p].strip(), cells[2 * p + 1].strip()
            if not wl and not value:
                continue
            if not wl or not value:
                column = 2 * p + 1 if wl else 2 * p
                raise SpectrumError(f"{source}, line {line_number}: sample {names[p]!r}: cell {column + 1} is "
                                    "empty but its pair is not; each row holds a wavelength and its value")
            where = f"{source}, line {line_number}, sample {names[p]!r}"
            columns[2 * p].append(number(wl, where + " wavelength", decimal_comma) * unit_scales[p])
            columns[2 * p + 1].append(number(value, where, decimal_comma))
    grids, values = [], []
    metadata: dict = {"value_kinds": tuple(kinds)}
    if trailer:
        metadata["lines_after_data"] = trailer
        metadata["notes_after_data"] = tuple(notes)
    for p, name in enumerate(names):
        grid = np.frombuffer(columns[2 * p], dtype=float)
        value = np.frombuffer(columns[2 * p + 1], dtype=float)
        if len(grid) == 0:
            raise SpectrumError(f"{source}: sample {name!r}: its wavelength/value columns are empty")
        if len(grid) > 1 and np.all(np.diff(grid) < 0):
            grid, value = grid[::-1], value[::-1]
            metadata["wavelength_order"] = _DESCENDING
        if len(grid) > 1 and not np.all(np.diff(grid) > 0):
            raise SpectrumError(f"{source}: sample {name!r}: wavelengths must be strictly increasing or strictly "
                                "decreasing")
        grids.append(grid)
        values.append(value)
    target = grids[0]
    if all(len(g) == len(target) and np.array_equal(g, target) for g in grids):
        stacked = np.array(values)
    else:
        low, high = max(g[0] for g in grids), min(g[-1] for g in grids)
        target = target[(target >= low) & (target <= high)]
        if len(target) < 2:
            raise SpectrumError(f"{source}: the samples' wavelength ranges do not overlap; read them separately")
        stacked = np.array([np.interp(target, g, v) for g, v in zip(grids, values, strict=True)])
        metadata["resampled"] = (f"the samples' wavelength grids differ: each was interpolated linearly onto "
                                 f"{names[0]!r}'s wavelengths within the common range {low:g}–{high:g} nm")
    try:
        return Spectrum(target, stacked if len(names) > 1 else stacked[0], names, metadata)
    except SpectrumError as exc:
        raise SpectrumError(f"{source}: {exc}") from None

