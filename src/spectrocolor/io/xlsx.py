"""Excel ``.xlsx`` workbooks (Office Open XML SpreadsheetML) read on the standard library.

A workbook is a ZIP package (ECMA-376 Part 2, Open Packaging Conventions) whose
``xl/workbook.xml`` lists the sheets (``<sheet name=… r:id=…>``, in tab order),
``xl/_rels/workbook.xml.rels`` maps each ``r:id`` to its part (``worksheets/sheet1.xml``), and
``xl/sharedStrings.xml`` holds the text that cells share (``<si><t>…</t></si>``, rich-text runs
``<r><t>…</t></r>`` concatenated, phonetic runs ``<rPh>`` left out). A worksheet's
``<sheetData>`` holds ``<row r="2">`` elements of ``<c r="B2" t="…"><v>…</v></c>`` cells:
``t="s"`` an index into the shared strings, ``t="inlineStr"`` text in ``<is>``, ``t="str"`` a
formula's text result, ``t="b"`` a boolean, ``t="e"`` an error (``#N/A``), and no ``t`` (or
``t="n"``) a number written as decimal text (ECMA-376 Part 1, §18.3.1.4, §18.4).

The chosen sheet (the first in tab order by default) becomes a table, one line per sheet row
(so a message's "line 7" is the sheet's row 7), and goes to the delimited-table reader
(:mod:`.delimited`): long or wide layout, header recognition and the rest are the same as for
CSV. Numbers keep the decimal text the workbook stores (Excel writes 17 significant digits, so a
double survives the round trip exactly); dates stay serial numbers (they land in
``sample_fields``). Columns empty in every row before the table are dropped (a table that
starts at ``B2``).

**Why the standard library and not openpyxl:** openpyxl is not a dependency of the project (nor
in ``constraints.txt``), it would be one more package to trust with hostile ZIP and XML input, and
a table needs only three parts of the package. Here every member's declared size is checked
before it is inflated: against the memory budget (:mod:`spectrocolor.budget`), against
:data:`spectrocolor.budget.MAX_COMPRESSION_RATIO` times its compressed size (a deflate stream
cannot expand more; a claim beyond that is a zip bomb or a damaged file), and the ZIP reader
never reads past the declared size. Every XML part is refused if it has a ``DOCTYPE`` or an
entity declaration (found by expat before parsing, as for TM-27). Legacy ``.xls``, ``.xlsb``
and ``.ods`` are named by :mod:`.sniff` and refused with what to do.

References
----------
ECMA-376, *Office Open XML File Formats*, 5th edition (2021), Part 1 §18 (SpreadsheetML) and
Part 2 (Open Packaging Conventions); ISO/IEC 29500:2016 (the same); PKWARE APPNOTE.TXT (ZIP).
"""

from __future__ import annotations

import io
import posixpath
import re
import xml.etree.ElementTree as ElementTree
import zipfile
import zlib
from xml.parsers import expat

from ..budget import MAX_COMPRESSION_RATIO, check_bytes, format_size
from ..errors import SpectrumError
from ..spectrum import Spectrum
from . import delimited
from .text import MAX_FILE_BYTES
from .tm27 import refuse_declarations

__all__ = ["parse_xlsx", "sheet_names"]

_MAIN = "http://schemas.openxmlformats.org/spreadsheetml/2006/main"
_RELATIONSHIP_ID = "{http://schemas.openxmlformats.org/officeDocument/2006/relationships}id"
_CELL = re.compile(r"([A-Za-z]{1,3})([0-9]{1,7})")
#: Columns a sheet can have (``XFD``), and rows (ECMA-376 Part 1 §18.3.1.73 limits in Excel).
MAX_COLUMNS = 16384
MAX_ROWS = 1048576
#: Line ends and tabs inside a cell would split the table (or change its delimiter): read as spaces.
_SPLITS = re.compile("[\t\n\r\x0b\x0c\x1c-\x1e\x85\u2028\u2029]")
#: Cells the comma-separated table must quote (a delimiter, a quote, a line end, a leading ``#``).
_QUOTE = re.compile('[",;\t\n\r\x0b\x0c\x1c-\x1e\x85\u2028\u2029]|^\\s*#')


def _local(tag: str) -> str:
    return tag.rsplit("}", 1)[-1]


def _member(archive: zipfile.ZipFile, name: str, source: str, budget, required: bool = True) -> bytes | None:
    """A member's bytes, its declared size checked before it is inflated."""
    try:
        info = archive.getinfo(name)
    except KeyError:
        if required:
            raise SpectrumError(f"{source}: the workbook has no {name} part; it is damaged or not an .xlsx") from None
        return None
    where = f"{source}: member {name}"
    if info.flag_bits & 0x1:
        raise SpectrumError(f"{where} is encrypted; save the workbook without a password")
    if info.file_size > MAX_FILE_BYTES:
        raise SpectrumError(f"{where} claims {format_size(info.file_size)}; workbook parts are read up to "
                            f"{format_size(MAX_FILE_BYTES)} (save the sheet as CSV)")
    if info.compress_type == zipfile.ZIP_STORED:
        if info.file_size > info.compress_size:
            raise SpectrumError(f"{where} is stored uncompressed in {format_size(info.compress_size)} but claims "
                                f"{format_size(info.file_size)}; the workbook is damaged")
    elif info.file_size > max(info.compress_size, 1) * MAX_COMPRESSION_RATIO:
        raise SpectrumError(f"{where} claims {format_size(info.file_size)} from {format_size(info.compress_size)} "
                            f"compressed, more than deflate's {MAX_COMPRESSION_RATIO}:1 can expand; the workbook "
                            "is damaged or a zip bomb")
    # the XML text, its parse and the table built from it: a few copies of the member at once
    check_bytes(4 * info.file_size, f"{where} ({format_size(info.file_size)} of XML)", budget=budget)
    try:
        with archive.open(info) as handle:
            data = handle.read(info.file_size + 1)
    except (zipfile.BadZipFile, zlib.error, NotImplementedError, RuntimeError, OSError, EOFError, ValueError) as exc:
        raise SpectrumError(f"{where} cannot be read ({exc}); the workbook is damaged") from None
    if len(data) != info.file_size:
        raise SpectrumError(f"{where} holds {len(data)} bytes but claims {info.file_size}; the workbook is damaged")
    return data


def _xml(data: bytes, where: str):
    refuse_declarations(data, where, "SpreadsheetML")
    try:
        return ElementTree.fromstring(data)
    except ElementTree.ParseError as exc:
        raise SpectrumError(f"{where}: not well-formed XML ({exc})") from None


def _text(element) -> str:
    """The text of a string item (``<si>``, ``<is>``): its ``<t>`` and runs' ``<t>``, no phonetic runs."""
    parts = []
    for child in element:
        tag = _local(child.tag)
        if tag == "t":
            parts.append(child.text or "")
        elif tag == "r":
            parts.extend(t.text or "" for t in child if _local(t.tag) == "t")
    return "".join(parts)


def _open(data: bytes, source: str) -> zipfile.ZipFile:
    try:
        return zipfile.ZipFile(io.BytesIO(data))
    except (zipfile.BadZipFile, zipfile.LargeZipFile, OSError, ValueError, EOFError, KeyError) as exc:
        raise SpectrumError(f"{source}: not a readable .xlsx workbook ({exc})") from None


def _sheets(archive: zipfile.ZipFile, source: str, budget) -> list[tuple[str, str]]:
    """``(name, part)`` for each sheet, in tab order."""
    workbook = _xml(_member(archive, "xl/workbook.xml", source, budget) or b"", f"{source}: xl/workbook.xml")
    targets: dict[str, str] = {}
    rels = _member(archive, "xl/_rels/workbook.xml.rels", source, budget, required=False)
    if rels is not None:
        for relation in _xml(rels, f"{source}: xl/_rels/workbook.xml.rels"):
            target = relation.get("Target", "")
            part = target.lstrip("/") if target.startswith("/") else posixpath.normpath(posixpath.join("xl", target))
            targets[relation.get("Id", "")] = part
    found = []
    for index, sheet in enumerate(e for e in workbook.iter() if _local(e.tag) == "sheet"):
        rid = sheet.get(_RELATIONSHIP_ID, "")
        found.append((sheet.get("name", f"Sheet{index + 1}"), targets.get(rid, f"xl/worksheets/sheet{index + 1}.xml")))
    if not found:
        raise SpectrumError(f"{source}: the workbook lists no sheets (xl/workbook.xml has no <sheet>)")
    return found


def sheet_names(data: bytes, source: str = "<workbook>", *, budget=None) -> list[str]:
    """The names of a workbook's sheets, in tab order.

    Parameters
    ----------
    data : bytes
        The ``.xlsx`` file's bytes.
    source : str, default "<workbook>"
        The file name, for messages.
    budget : int or str, optional
        The memory budget (:func:`spectrocolor.budget.memory_budget`).

    Returns
    -------
    list of str
        Sheet names.

    Raises
    ------
    SpectrumError
        For a file that is not a readable workbook.

    Examples
    --------
    >>> sheet_names(b"PK\\x05\\x06" + bytes(18), "empty.xlsx")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    spectrocolor.errors.SpectrumError: empty.xlsx: the workbook has no xl/workbook.xml part; ...
    """
    with _open(data, source) as archive:
        return [name for name, _ in _sheets(archive, source, budget)]


def _choose(sheets: list[tuple[str, str]], sheet, source: str) -> tuple[str, str]:
    listed = ", ".join(repr(name) for name, _ in sheets[:10])
    if sheet is None:
        return sheets[0]
    if isinstance(sheet, int) and not isinstance(sheet, bool):
        if 0 <= sheet < len(sheets):
            return sheets[sheet]
        raise SpectrumError(f"sheet: {sheet} is not a sheet index of {source} (0 to {len(sheets) - 1}: {listed})")
    if isinstance(sheet, str):
        for name, part in sheets:
            if name == sheet:
                return name, part
        raise SpectrumError(f"sheet: {sheet!r:.60} is not a sheet of {source}; its sheets are {listed}")
    raise SpectrumError(f"sheet: expected a sheet name (str) or index (int), got {type(sheet).__name__}")


def _column(reference: str, where: str) -> tuple[int, int]:
    match = _CELL.fullmatch(reference)
    if match is None:
        raise SpectrumError(f"{where}: cell reference {reference[:20]!r} is not a column letter and row number")
    column = 0
    for letter in match.group(1).upper():
        column = column * 26 + ord(letter) - 64
    row = int(match.group(2))
    if column > MAX_COLUMNS or not 1 <= row <= MAX_ROWS:
        raise SpectrumError(f"{where}: cell reference {reference!r} is beyond a sheet's {MAX_COLUMNS} columns "
                            f"and {MAX_ROWS} rows")
    return column - 1, row


class _Sheet:
    """expat handlers that collect a worksheet's cells as text, element by element.

    A streaming parse (no element tree): a sheet of 240 000 cells is read in about a second, and
    a DOCTYPE or entity declaration stops the parse where it is met.
    """

    def __init__(self, shared: list[str], where: str):
        self.shared, self.where = shared, where
        self.rows: dict[int, dict[int, str]] = {}
        self.cells: dict[int, str] = {}
        self.row_number, self.column = 0, -1
        self.kind, self.reference = "n", ""
        self.parts: list[str] = []
        self.collecting = self.in_inline = self.in_phonetic = False
        self.names: dict[str, str] = {}

    def local(self, name: str) -> str:
        local = self.names.get(name)
        if local is None:
            local = self.names[name] = name.rsplit(":", 1)[-1]
        return local

    def start(self, name: str, attributes: dict[str, str]) -> None:
        tag = self.local(name)
        if tag == "c":
            reference = attributes.get("r")
            self.column = _column(reference, self.where)[0] if reference is not None else self.column + 1
            if self.column >= MAX_COLUMNS:
                raise SpectrumError(f"{self.where}, row {self.row_number}: more than {MAX_COLUMNS} cells")
            self.kind, self.reference, self.parts = attributes.get("t", "n"), reference or "", []
        elif tag == "v":
            self.collecting = True
        elif tag == "t":
            self.collecting = self.in_inline and not self.in_phonetic
        elif tag == "row":
            declared = attributes.get("r")
            self.row_number = _column(f"A{declared}", self.where)[1] if declared is not None else self.row_number + 1
            self.cells = self.rows.setdefault(self.row_number, {})
            self.column = -1
        elif tag == "is":
            self.in_inline = True
        elif tag == "rPh":
            self.in_phonetic = True

    def end(self, name: str) -> None:
        tag = self.local(name)
        if tag in ("v", "t"):
            self.collecting = False
        elif tag == "c":
            text = self.text("".join(self.parts))
            if text.strip():
                self.cells[self.column] = text
        elif tag == "is":
            self.in_inline = False
        elif tag == "rPh":
            self.in_phonetic = False

    def characters(self, data: str) -> None:
        if self.collecting:
            self.parts.append(data)

    def text(self, value: str) -> str:
        if self.kind == "s":
            if not value.strip().isdigit() or int(value) >= len(self.shared):
                raise SpectrumError(f"{self.where}, cell {self.reference or self.column + 1}: shared string "
                                    f"{value[:20]!r} is not one of the workbook's {len(self.shared)} shared "
                                    "strings; the workbook is damaged")
            return self.shared[int(value)]
        if self.kind == "b":
            return {"1": "TRUE", "0": "FALSE"}.get(value.strip(), value)
        return value


class _Declaration(Exception):
    """Raised by an expat handler: the part declares a DOCTYPE or an entity."""


def _refuse(*_):
    raise _Declaration


def _rows(sheet_xml: bytes, shared: list[str], where: str) -> dict[int, dict[int, str]]:
    """``{row number: {column index: text}}`` for the non-empty cells of a worksheet part.

    Cells: ``t="s"`` a shared string, ``t="inlineStr"`` the ``<t>`` text of ``<is>`` (phonetic
    ``<rPh>`` runs left out), ``t="b"`` TRUE/FALSE, anything else the ``<v>`` text as stored.
    """
    sheet = _Sheet(shared, where)
    parser = expat.ParserCreate()
    parser.buffer_text = True
    parser.StartElementHandler = sheet.start
    parser.EndElementHandler = sheet.end
    parser.CharacterDataHandler = sheet.characters
    parser.StartDoctypeDeclHandler = _refuse
    parser.EntityDeclHandler = _refuse
    parser.UnparsedEntityDeclHandler = _refuse
    try:
        parser.Parse(sheet_xml, True)
    except _Declaration:
        raise SpectrumError(f"{where}: XML with a DOCTYPE or ENTITY declaration is not accepted "
                            "(SpreadsheetML needs none)") from None
    except (expat.ExpatError, ValueError) as exc:
        raise SpectrumError(f"{where}: not well-formed XML ({exc})") from None
    return sheet.rows


def _quoted(text: str) -> str:
    if _QUOTE.search(text) is None:
        return text
    text = _SPLITS.sub(" ", text)
    if any(c in text for c in '",;') or text.lstrip().startswith("#"):
        return '"' + text.replace('"', '""') + '"'
    return text


def _table(rows: dict[int, dict[int, str]], where: str, budget) -> str:
    """The rows as comma-separated text, one line per sheet row (blank lines for empty rows).

    Commas, not tabs: a workbook's numbers are written with a decimal point, and the delimited
    reader takes ``;`` and tab tables to use decimal commas. Cells holding ``,``, ``;`` or ``"``,
    or starting with ``#`` (a comment line to the reader), are quoted.
    """
    filled = {number: cells for number, cells in rows.items() if cells}
    if not filled:
        raise SpectrumError(f"{where}: the sheet is empty")
    first = min(min(cells) for cells in filled.values())
    last_row = max(filled)
    width = max(max(cells) for cells in filled.values()) - first + 1
    size = sum(len(text) + 1 for cells in filled.values() for text in cells.values())
    check_bytes(4 * (size + width * len(filled) + last_row),
                f"{where}: {len(filled)} rows × {width} columns as a table", budget=budget)
    lines = []
    for number in range(1, last_row + 1):
        cells = filled.get(number)
        if not cells:
            lines.append("")
            continue
        row = [""] * (max(cells) - first + 1)
        for column, text in cells.items():
            row[column - first] = _quoted(text)
        lines.append(",".join(row))
    return "\n".join(lines) + "\n"


def parse_xlsx(data: bytes, source: str = "<workbook>", percent: bool | None = None, *, sheet=None,
               budget=None) -> Spectrum:
    """Spectra from one sheet of an ``.xlsx`` workbook, read as a delimited table.

    Parameters
    ----------
    data : bytes
        The workbook file's bytes.
    source : str, default "<workbook>"
        The file name, for messages.
    percent : bool or None, default None
        A workbook does not declare its scale: ``True`` divides by 100; see :term:`percent`.
    sheet : str or int or None, keyword-only, default None
        The sheet's name or its 0-based index in tab order; ``None`` for the first sheet.
    budget : int or str, optional
        The memory budget (:func:`spectrocolor.budget.memory_budget`).

    Returns
    -------
    Spectrum
        As the delimited reader returns it, with ``metadata["format"]`` naming the workbook
        layout and ``metadata["sheet"]`` the sheet read.

    Raises
    ------
    SpectrumError
        One line: a damaged or oversized workbook (naming the member), an unknown sheet, or the
        table's own errors located as ``file, sheet 'Name', line <row>, column '<header>'``.

    References
    ----------
    ECMA-376 Part 1 §18 (SpreadsheetML), Part 2 (Open Packaging Conventions).

    Examples
    --------
    >>> import io, zipfile
    >>> buffer = io.BytesIO()
    >>> main = 'xmlns="http://schemas.openxmlformats.org/spreadsheetml/2006/main"'
    >>> with zipfile.ZipFile(buffer, "w") as book:
    ...     book.writestr("xl/workbook.xml", f'<workbook {main}><sheets><sheet name="Data"/></sheets></workbook>')
    ...     book.writestr("xl/worksheets/sheet1.xml", f'<worksheet {main}><sheetData>'
    ...         '<row r="1"><c r="A1" t="inlineStr"><is><t>nm</t></is></c>'
    ...         '<c r="B1" t="inlineStr"><is><t>tile</t></is></c></row>'
    ...         '<row r="2"><c r="A2"><v>400</v></c><c r="B2"><v>0.25</v></c></row>'
    ...         '<row r="3"><c r="A3"><v>500</v></c><c r="B3"><v>0.5</v></c></row></sheetData></worksheet>')
    >>> s = parse_xlsx(buffer.getvalue(), "book.xlsx")
    >>> s.names, s.values.tolist(), s.metadata["format"]
    (('tile',), [0.25, 0.5], "Excel workbook (.xlsx), sheet 'Data', long")
    """
    with _open(data, source) as archive:
        sheets = _sheets(archive, source, budget)
        name, part = _choose(sheets, sheet, source)
        where = f"{source}, sheet {name!r}"
        shared: list[str] = []
        strings = _member(archive, "xl/sharedStrings.xml", source, budget, required=False)
        if strings is not None:
            root = _xml(strings, f"{source}: xl/sharedStrings.xml")
            shared = [_text(item) for item in root if _local(item.tag) == "si"]
        sheet_xml = _member(archive, part, source, budget)
    assert sheet_xml is not None  # required=True
    table = _table(_rows(sheet_xml, shared, where), where, budget)
    try:
        spectrum = delimited.parse_delimited(table, where, percent)
    except SpectrumError as exc:
        others = [n for n, _ in sheets if n != name]
        if others and ("not a spectral table" in str(exc) or "no data" in str(exc)):
            listed = ", ".join(repr(n) for n in others[:10])
            raise SpectrumError(f"{exc}; the workbook's other sheets: {listed} (choose one with sheet=)") from None
        raise
    layout = str(spectrum.metadata.get("format", "")).rsplit(", ", 1)[-1]
    metadata = {**spectrum.metadata, "format": f"Excel workbook (.xlsx), sheet {name!r}, {layout}", "sheet": name}
    return Spectrum(spectrum.wavelengths_nm, spectrum.values, spectrum.names, metadata)
