"""CGATS.17 text files and their dialects: i1Profiler/X-Rite, Barbieri, ArgyllCMS ``.ti3`` and ``.sp``.

A CGATS file (ANSI CGATS.17, the ISO 28178 exchange format) is a first line naming the file type,
keyword lines (``ORIGINATOR "…"``, ``KEYWORD "NAME"`` declaring a private keyword, then
``NAME "…"``), a field list between ``BEGIN_DATA_FORMAT`` and ``END_DATA_FORMAT``, the number of
rows (``NUMBER_OF_SETS``) and the rows between ``BEGIN_DATA`` and ``END_DATA``; tokens are separated
by white space, strings are in double quotes, ``#`` starts a comment, and line ends may be CRLF.

Spectral fields are recognised by name: ``SPECTRAL_NM380`` (i1Profiler), ``SPECTRAL_NM_380``,
``SPECTRAL_380``, ``SPEC_380`` (ArgyllCMS), ``NM380``/``nm_380`` (Barbieri and others),
``SPECTRAL_PCT_380``/``SPECTRAL_DEC_380`` (percent / decimal). Sample names come from
``SAMPLE_NAME``, else ``SAMPLE_ID`` (or ``SampleID``); every other field (``LAB_L``, ``XYZ_X``, ``RGB_R`` …) is kept as
text in ``metadata["sample_fields"]``, every keyword in ``metadata["keywords"]``. The illuminant,
observer and geometry the keywords declare (``MEASUREMENT_SOURCE "Illumination=D50
ObserverAngle=2°"``, ``WEIGHTING_FUNCTION``, ``MEASUREMENT_GEOMETRY`` …) are read by
:func:`spectrocolor.io.conditions.parse_declaration` into ``declared_*`` entries.

**Percent or fraction**, as the file declares it: Argyll's ``SPECTRAL_NORM`` keyword (values are
divided by it); ``SPECTRAL_PCT_…`` fields (percent) or ``SPECTRAL_DEC_…`` fields (fraction); an
Argyll ``CTI3`` file without ``SPECTRAL_NORM`` holds percentages (Argyll's ``.ti3`` convention:
reflectance and transmittance in 0–100). Otherwise the file does not say and the caller's
``percent`` option decides (see :func:`spectrocolor.io.text.apply_scale`).

References
----------
ANSI CGATS.17-2009, *Graphic technology — Exchange format for colour and process control data
using XML or ASCII text*; ISO 28178:2009 (the same format). ArgyllCMS file formats documentation
(``.ti3``: CTI3; ``.sp``: SPECT; keywords SPECTRAL_BANDS, SPECTRAL_START_NM, SPECTRAL_END_NM,
SPECTRAL_NORM).
"""

from __future__ import annotations

import re

from ..errors import SpectrumError
from ..spectrum import Spectrum
from .conditions import parse_declaration
from .text import apply_scale, number, number_table, wavelength_of

_TOKEN = re.compile(r'"([^"]*)"|(\S+)')
#: Where :meth:`str.splitlines` ends a line (the reader splits lines with it).
_BREAKS = "\n\r\x0b\x0c\x1c-\x1e\x85\u2028\u2029"
#: ``BEGIN_DATA_FORMAT`` as the first token of a line. Tried only at line starts and with
#: spaces that cannot cross a line break, so the search is linear: ``^\s*`` (which crosses
#: line breaks) took quadratic time on a file of blank lines.
_FIELD_LIST = re.compile(rf"(?:\A|(?<=[{_BREAKS}]))[^\S{_BREAKS}]*+BEGIN_DATA_FORMAT\b")
_DIALECTS = {"CTI3": "ArgyllCMS .ti3", "SPECT": "ArgyllCMS .sp", "CTI1": "ArgyllCMS .ti1", "CTI2": "ArgyllCMS .ti2"}
#: Keywords that say where and how the data were measured, under the names kept in metadata.
_FACTS = {
    "instrument": ("INSTRUMENTATION", "TARGET_INSTRUMENT", "INSTRUMENT", "MEASUREMENT_DEVICE"),
    "illuminant": ("ILLUMINANT", "ILLUMINATION_NAME", "MEASUREMENT_SOURCE", "ILLUMINATION"),
    "geometry": ("MEASUREMENT_GEOMETRY", "GEOMETRY"),
    "date": ("CREATED", "MEASUREMENT_DATE", "DATE"),
    "description": ("DESCRIPTOR", "DESCRIPTION"),
    "originator": ("ORIGINATOR",),
}
#: What a CGATS file must contain, for messages.
EXPECTED = "BEGIN_DATA_FORMAT … END_DATA_FORMAT, BEGIN_DATA … END_DATA with SPECTRAL_NM380/SPEC_380 fields"


def looks_like_cgats(text: str) -> bool:
    """True if the text has a CGATS field list (``BEGIN_DATA_FORMAT`` at the start of a line).

    Parameters
    ----------
    text : str
        A file's text.

    Returns
    -------
    bool
        Whether :func:`parse_cgats` should read it.

    Examples
    --------
    >>> looks_like_cgats("CGATS.17\\nBEGIN_DATA_FORMAT\\nSAMPLE_ID\\nEND_DATA_FORMAT\\n"), looks_like_cgats("a,b")
    (True, False)
    """
    return _FIELD_LIST.search(text) is not None


def _tokens(line: str) -> list[str]:
    if '"' not in line:
        return line.split("#", 1)[0].split()  # '#' outside a string starts a comment
    return [m.group(1) if m.group(1) is not None else m.group(2) for m in _TOKEN.finditer(line)]


def _tables(text: str, source: str):
    """Yield (identifier, keywords, fields, rows) per table; rows are (line number, tokens)."""
    lines = text.splitlines()
    first = _tokens(lines[0]) if lines else []
    identifier = first[0] if first else ""
    keywords: dict[str, str] = {}
    fields: list[str] | None = None
    rows: list[tuple[int, list[str]]] = []
    state = "header"
    for number_, raw in enumerate(lines, start=1):
        line = raw.strip()
        if not line or line.startswith("#"):
            continue
        tokens = _tokens(line)
        if not tokens:
            continue
        head = tokens[0]
        if state == "format":
            if head == "END_DATA_FORMAT":
                state = "header"
            else:
                assert fields is not None  # BEGIN_DATA_FORMAT set it
                fields.extend(tokens)
            continue
        if state == "data":
            if head == "END_DATA":
                yield identifier, keywords, fields, rows
                keywords, fields, rows, state = {}, None, [], "after"
            else:
                rows.append((number_, tokens))
            continue
        if head == "BEGIN_DATA_FORMAT":
            fields, state = [], "format"
        elif head == "BEGIN_DATA":
            if fields is None:
                raise SpectrumError(f"{source}, line {number_}: BEGIN_DATA before any BEGIN_DATA_FORMAT field list")
            state = "data"
        elif number_ > 1 and head != "KEYWORD":
            value = " ".join(tokens[1:])
            if head == "WEIGHTING_FUNCTION" and keywords.get(head):  # one line per function (CGATS.17)
                value = f"{keywords[head]}; {value}"
            keywords[head] = value
    if state == "data":
        raise SpectrumError(f"{source}: BEGIN_DATA without END_DATA (the file is cut short)")
    if state == "format":
        raise SpectrumError(f"{source}: BEGIN_DATA_FORMAT without END_DATA_FORMAT")


def _declared_scale(identifier: str, keywords: dict[str, str], spectral_fields: list[str], source: str):
    if "SPECTRAL_NORM" in keywords:
        norm = number(keywords["SPECTRAL_NORM"], f"{source}: keyword SPECTRAL_NORM")
        if norm <= 0:
            raise SpectrumError(f"{source}: keyword SPECTRAL_NORM must be positive, got {norm:g}")
        return norm, "SPECTRAL_NORM"
    upper = [f.upper() for f in spectral_fields]
    if all(f.startswith("SPECTRAL_PCT") for f in upper):
        return 100.0, "SPECTRAL_PCT fields"
    if all(f.startswith("SPECTRAL_DEC") for f in upper):
        return 1.0, "SPECTRAL_DEC fields"
    if identifier == "CTI3":
        return 100.0, "Argyll CTI3 spectral values are percentages"
    return None, ""


def parse_cgats(text: str, source: str, percent: bool | None = None) -> Spectrum:
    """Spectra from the first table of a CGATS text that has spectral fields.

    Parameters
    ----------
    text : str
        The file's text.
    source : str
        File name, for messages.
    percent : bool or None, default None
        ``None`` to follow the file's declaration (module docstring), else the caller's statement.

    Returns
    -------
    Spectrum
        ``(N, K)`` values (``(K,)`` for one row) on the 0–1 scale where the file or ``percent`` says
        so, names from SAMPLE_NAME/SAMPLE_ID; ``metadata`` with ``format``, ``keywords``,
        ``sample_fields``, ``value_scale`` and, where the keywords give them, ``instrument``,
        ``illuminant``, ``geometry``, ``date``, and the conditions the file declares
        (``declared_illuminant``, ``declared_observer``, ``declared_geometry``, ``declared_by``:
        see :mod:`spectrocolor.io.conditions`).

    Examples
    --------
    >>> text = ('CGATS.17\\r\\nNUMBER_OF_FIELDS 4\\r\\nBEGIN_DATA_FORMAT\\r\\n'
    ...         'SAMPLE_NAME SPECTRAL_NM400 SPECTRAL_NM500 SPECTRAL_NM600\\r\\nEND_DATA_FORMAT\\r\\n'
    ...         'NUMBER_OF_SETS 1\\r\\nBEGIN_DATA\\r\\n"A1" 0.1 0.2 0.3\\r\\nEND_DATA\\r\\n')
    >>> s = parse_cgats(text, "x.txt", percent=False)
    >>> s.names, s.wavelengths_nm.tolist()
    (('A1',), [400.0, 500.0, 600.0])
    """
    seen = 0
    for identifier, keywords, fields, rows in _tables(text, source):
        seen += 1
        spectral = [(i, wavelength_of(f)) for i, f in enumerate(fields)]
        spectral = [(i, nm) for i, nm in spectral if nm is not None]
        if len(spectral) < 2:
            continue
        return _table_spectra(identifier, keywords, fields, rows, spectral, source, percent)
    if seen == 0:
        raise SpectrumError(f"{source}: no CGATS data table (BEGIN_DATA_FORMAT … BEGIN_DATA … END_DATA)")
    raise SpectrumError(
        f"{source}: CGATS file without spectral fields (found {seen} table(s); expected fields such as "
        "SPECTRAL_NM380, SPECTRAL_NM_380 or SPEC_380)"
    )


def _table_spectra(identifier, keywords, fields, rows, spectral, source, percent) -> Spectrum:
    if "NUMBER_OF_FIELDS" in keywords:
        declared = number(keywords["NUMBER_OF_FIELDS"], f"{source}: NUMBER_OF_FIELDS")
        if declared != len(fields):
            raise SpectrumError(
                f"{source}: NUMBER_OF_FIELDS says {declared:g} but the data format lists {len(fields)} fields"
            )
    if "NUMBER_OF_SETS" in keywords:
        declared = number(keywords["NUMBER_OF_SETS"], f"{source}: NUMBER_OF_SETS")
        if declared != len(rows):
            raise SpectrumError(f"{source}: NUMBER_OF_SETS says {declared:g} but BEGIN_DATA holds {len(rows)} rows")
    if not rows:
        raise SpectrumError(f"{source}: the spectral table has no rows")
    spectral.sort(key=lambda item: item[1])
    columns = [i for i, _ in spectral]
    for line_number, row in rows:
        if len(row) != len(fields):
            raise SpectrumError(
                f"{source}, line {line_number}: {len(row)} values, but the data format has {len(fields)}"
            )
    values = number_table(
        [[row[i] for i in columns] for _, row in rows],
        lambda r, k: f"{source}, line {rows[r][0]}, field {fields[columns[k]]}",
    )
    upper = [f.upper() for f in fields]
    name_index = next((upper.index(key) for key in ("SAMPLE_NAME", "SAMPLE_ID", "SAMPLEID") if key in upper), None)
    names = [row[name_index] if name_index is not None else f"sample_{r + 1}" for r, (_, row) in enumerate(rows)]
    spectral_columns = set(columns)  # built once: a set per field made long field lists quadratic
    others = [i for i in range(len(fields)) if i not in spectral_columns and i != name_index]
    declared, how = _declared_scale(identifier, keywords, [fields[i] for i in columns], source)
    values, note = apply_scale(values, declared, percent, source, how)
    metadata: dict[str, object] = {
        "format": _DIALECTS.get(identifier, f"CGATS ({identifier or 'no identifier'})"),
        "file_identifier": identifier,
        "keywords": dict(keywords),
        "value_scale": note,
    }
    for fact, keys in _FACTS.items():
        found = next((keywords[k] for k in keys if keywords.get(k)), None)
        if found is not None:
            metadata[fact] = found
    metadata.update(parse_declaration(keywords))
    if others:
        metadata["sample_fields"] = {fields[i]: tuple(row[i] for _, row in rows) for i in others}
    try:
        wavelengths = [nm for _, nm in spectral]
        return Spectrum(wavelengths, values if values.shape[0] > 1 else values[0], names, metadata)
    except SpectrumError as exc:
        raise SpectrumError(f"{source}: spectral fields: {exc}") from None
