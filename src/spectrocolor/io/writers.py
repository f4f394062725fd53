"""Text writers: spectra and result tables as CSV and CGATS.17, read back by the readers.

* :func:`spectra_to_csv`: ``wavelength_nm`` then one column per spectrum (long layout).
* :func:`spectra_to_cgats`: CGATS.17 with ``SAMPLE_ID``, ``SAMPLE_NAME``, the file's per-sample
  fields and ``SPECTRAL_NM380``-style fields, declaring the 0–1 scale (``SPECTRAL_NORM "1"``,
  Argyll's keyword) so that no reader has to guess; numbers are written with 17 significant digits,
  so a CGATS → CGATS round trip is exact.
* :func:`table_to_cgats`: result rows (``spectrocolor xyz``/``describe``/``report``) as CGATS.17,
  with CGATS's standard field names where one exists (``XYZ_X``, ``LAB_L`` …).

Every name, keyword and text cell is written on one line: a line break or another control
character in one (:func:`one_line`), or a keyword that is not one CGATS word, is refused with a
SpectrumError naming it, so no name can break a file's structure. A double quote inside a CGATS
string (which has no escape) is written as an apostrophe; CSV quotes as RFC 4180 says.

References
----------
ANSI CGATS.17-2009 / ISO 28178:2009 (file structure, standard field names SAMPLE_ID,
SAMPLE_NAME, XYZ_X/Y/Z, XYY_X/Y, LAB_L/A/B).
"""

from __future__ import annotations

import csv
import io
import math
import re
from collections.abc import Mapping, Sequence

import numpy as np

from ..errors import SpectrumError
from ..spectrum import Spectrum

#: Result columns and their CGATS.17 field names (others are written in upper case).
CGATS_FIELDS = {
    "name": "SAMPLE_NAME",
    "X": "XYZ_X",
    "Y": "XYZ_Y",
    "Z": "XYZ_Z",
    "x": "XYY_X",
    "y": "XYY_Y",
    "L*": "LAB_L",
    "a*": "LAB_A",
    "b*": "LAB_B",
}


#: Characters that end a line for the readers (:meth:`str.splitlines`) and the other control
#: characters: none may appear in a name, keyword or text cell that a writer puts on one line.
_NOT_IN_ONE_LINE = re.compile("[\x00-\x08\x0a-\x1f\x7f\x85\u2028\u2029]")
#: A CGATS keyword: one token, no quote, no comment sign.
_KEYWORD = re.compile(r"[^\s\"#]+")
#: Words that structure a CGATS file: never a keyword of ours.
_RESERVED = {"BEGIN_DATA_FORMAT", "END_DATA_FORMAT", "BEGIN_DATA", "END_DATA", "KEYWORD"}


def one_line(text, what: str) -> str:
    """``text`` as a string, or SpectrumError if it would break a line-based file.

    CGATS and the CSV readers are line based: a name holding a line break (``\\n``, ``\\r``,
    or any other break of :meth:`str.splitlines`) or another control character would end its
    row in the middle and break the file's structure, so writers refuse it, naming it.

    Parameters
    ----------
    text : object
        The name, keyword value or text cell (made a string with ``str``).
    what : str
        What it is, for the message (e.g. ``"names[2]"``).

    Returns
    -------
    str
        The text, unchanged.

    Raises
    ------
    SpectrumError
        If it holds a line break or another control character (a tab is allowed).

    Examples
    --------
    >>> one_line("tile 1", "names[0]")
    'tile 1'
    >>> one_line("tile\\n1", "names[0]")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    spectrocolor.errors.SpectrumError: names[0]: 'tile\\n1' holds a line break or control character ('\\n'); ...
    """
    text = str(text)
    found = _NOT_IN_ONE_LINE.search(text)
    if found is not None:
        raise SpectrumError(f"{what}: {text!r:.60} holds a line break or control character "
                            f"({found.group()!r}); names, keywords and text cells are written on "
                            "one line: remove it")
    return text


def _quoted(text, what: str) -> str:
    return '"' + one_line(text, what).replace('"', "'") + '"'


def _keyword(key, what: str) -> str:
    key = str(key)
    if _KEYWORD.fullmatch(key) is None or key.upper() in _RESERVED:
        raise SpectrumError(f"{what}: {key!r:.60} is not a CGATS keyword (one word without spaces, "
                            f"quotes or '#', and none of {', '.join(sorted(_RESERVED))})")
    return key


def _cell(value, what: str) -> str:
    if value is None:  # a missing number (records() writes NaN as None)
        return "NaN"
    if isinstance(value, bool):
        return _quoted("true" if value else "false", what)
    if isinstance(value, (float, np.floating)):
        return "NaN" if math.isnan(value) else f"{float(value):.17g}"
    if isinstance(value, (int, np.integer)):
        return str(int(value))
    return _quoted(value, what)


#: Keywords CGATS.17 defines (written without a ``KEYWORD`` declaration).
_STANDARD_KEYWORDS = {"ORIGINATOR", "DESCRIPTOR", "FILE_DESCRIPTOR", "CREATED", "INSTRUMENTATION", "MEASUREMENT_SOURCE"}
#: Keywords describing the layout or scale of a table, rewritten by every writer.
_STRUCTURAL_KEYWORDS = {
    "NUMBER_OF_FIELDS",
    "NUMBER_OF_SETS",
    "SPECTRAL_NORM",
    "SPECTRAL_BANDS",
    "SPECTRAL_START_NM",
    "SPECTRAL_END_NM",
}


def _cgats(keywords: Mapping[str, str], fields: Sequence[str], rows: Sequence[Sequence[str]]) -> str:
    lines = ["CGATS.17"]
    for key, value in keywords.items():
        key = _keyword(key, "keywords")
        if key not in _STANDARD_KEYWORDS:
            lines.append(f"KEYWORD {_quoted(key, 'keywords')}")
        lines.append(f"{key} {_quoted(value, f'keywords[{key!r}]')}")
    lines += [
        f"NUMBER_OF_FIELDS {len(fields)}",
        "BEGIN_DATA_FORMAT",
        " ".join(fields),
        "END_DATA_FORMAT",
        f"NUMBER_OF_SETS {len(rows)}",
        "BEGIN_DATA",
        *(" ".join(row) for row in rows),
        "END_DATA",
    ]
    return "\r\n".join(lines) + "\r\n"


def _field_name(label: str) -> str:
    name = "".join(ch if ch.isalnum() else "_" for ch in label.upper()).strip("_")
    return name or "FIELD"


def spectra_to_cgats(spectrum: Spectrum, keywords: Mapping[str, str] | None = None) -> str:
    """CGATS.17 text of an ``(N, K)`` batch (or one spectrum) on the 0–1 scale.

    Parameters
    ----------
    spectrum : Spectrum
        Spectra; names become ``SAMPLE_NAME`` and ``metadata["sample_fields"]`` are written as
        fields of their own.
    keywords : mapping of str to str, optional
        Extra keywords, e.g. ``{"DESCRIPTOR": "tiles", "MEASUREMENT_GEOMETRY": "45/0"}``; the
        keywords a reader kept in ``metadata["keywords"]`` are written too (layout and scale
        keywords are rewritten).

    Returns
    -------
    str
        The CGATS.17 text (CRLF line ends).

    Raises
    ------
    SpectrumError
        For a non-Spectrum or an image cube.

    References
    ----------
    ANSI CGATS.17-2009.

    Examples
    --------
    >>> text = spectra_to_cgats(Spectrum([400, 500], [0.25, 0.5], ["tile"]))
    >>> text.splitlines()[-2]
    '1 "tile" 0.25 0.5'
    """
    if not isinstance(spectrum, Spectrum):
        raise SpectrumError(f"spectrum: expected a Spectrum, got {type(spectrum).__name__}")
    if spectrum.values.ndim > 2:
        raise SpectrumError(f"spectrum: CGATS holds (N, K) batches, got values of shape {spectrum.values.shape}")
    values = np.atleast_2d(spectrum.values)
    names = spectrum.names or tuple(f"spectrum_{i + 1}" for i in range(values.shape[0]))
    sample_fields = dict(spectrum.metadata.get("sample_fields", {}))
    extra = [(_field_name(key), column) for key, column in sample_fields.items() if key.upper() not in ("SAMPLE_ID",)]
    spectral = [f"SPECTRAL_NM{wavelength:g}" for wavelength in spectrum.wavelengths_nm]
    fields = ["SAMPLE_ID", "SAMPLE_NAME", *(name for name, _ in extra), *spectral]
    rows = [
        [
            str(i + 1),
            _quoted(names[i], f"names[{i}]"),
            *(_quoted(column[i], f"sample_fields[{name!r}][{i}]") for name, column in extra),
            *(_cell(v, "values") for v in values[i]),
        ]
        for i in range(values.shape[0])
    ]
    kept = {k: v for k, v in dict(spectrum.metadata.get("keywords", {})).items() if k not in _STRUCTURAL_KEYWORDS}
    header = {"ORIGINATOR": "spectrocolor", **kept, **dict(keywords or {}), "SPECTRAL_NORM": "1"}
    return _cgats(header, fields, rows)


def table_to_cgats(rows: Sequence[Mapping[str, object]], keywords: Mapping[str, str] | None = None) -> str:
    """CGATS.17 text of result rows (dicts with the same keys), numbered ``SAMPLE_ID`` 1…N.

    Parameters
    ----------
    rows : sequence of mapping
        One dict per sample, all with the keys of the first (``X``, ``Y``, ``Z``, ``name`` …
        map to the standard CGATS field names).
    keywords : mapping of str to str, optional
        Extra keywords for the header.

    Returns
    -------
    str
        The CGATS.17 text.

    Raises
    ------
    SpectrumError
        For no rows.

    References
    ----------
    ANSI CGATS.17-2009.

    Examples
    --------
    >>> print(table_to_cgats([{"name": "a", "X": 1.5, "Y": 2.0, "Z": 3.0}]).splitlines()[4])
    SAMPLE_ID SAMPLE_NAME XYZ_X XYZ_Y XYZ_Z
    """
    if not rows:
        raise SpectrumError("rows: nothing to write")
    columns = list(rows[0])
    fields = ["SAMPLE_ID", *(CGATS_FIELDS.get(c, _field_name(c)) for c in columns)]
    body = [[str(i + 1), *(_cell(row[c], f"rows[{i}][{c!r}]") for c in columns)] for i, row in enumerate(rows)]
    return _cgats({"ORIGINATOR": "spectrocolor", **dict(keywords or {})}, fields, body)


def _csv_name(name: str) -> str:
    """A header cell: quoted (RFC 4180) when it holds a delimiter the reader may choose or a quote."""
    if any(c in name for c in ',;\t"'):
        return '"' + name.replace('"', '""') + '"'
    return name


def spectra_to_csv(spectrum: Spectrum) -> str:
    """CSV text: ``wavelength_nm`` then one column per spectrum (batches of shape ``(N, K)``).

    Parameters
    ----------
    spectrum : Spectrum
        One spectrum or an ``(N, K)`` batch; unnamed spectra become ``spectrum_1``, ….

    Returns
    -------
    str
        The CSV text (values with 17 significant digits: they read back exactly).

    Raises
    ------
    SpectrumError
        For an image cube (more than two dimensions).

    Examples
    --------
    >>> spectra_to_csv(Spectrum([400, 500], [0.25, 0.5], ["tile"])).splitlines()
    ['wavelength_nm,tile', '400,0.25', '500,0.5']
    """
    if spectrum.values.ndim > 2:
        raise SpectrumError(f"spectrum: CSV holds (N, K) batches, got values of shape {spectrum.values.shape}")
    rows = np.atleast_2d(spectrum.values)
    names: Sequence[str] = spectrum.names or tuple(f"spectrum_{i + 1}" for i in range(rows.shape[0]))
    names = [one_line(name, f"names[{i}]") for i, name in enumerate(names)]
    buffer = io.StringIO()
    writer = csv.writer(buffer, lineterminator="\n")
    buffer.write(",".join(["wavelength_nm", *map(_csv_name, names)]) + "\n")
    for k, wavelength in enumerate(spectrum.wavelengths_nm):
        writer.writerow([f"{wavelength:.10g}", *(f"{v:.17g}" for v in rows[:, k])])
    return buffer.getvalue()
