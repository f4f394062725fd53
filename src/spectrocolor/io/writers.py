"""Text writers: spectra and result tables as CSV and CGATS.17, read back by the readers.

* :func:`spectra_to_csv`: ``wavelength_nm`` then one column per spectrum (long layout).
* :func:`spectra_to_cgats`: CGATS.17 with ``SAMPLE_ID``, ``SAMPLE_NAME``, the file's per-sample
  fields and ``SPECTRAL_NM380``-style fields, declaring the 0–1 scale (``SPECTRAL_NORM "1"``,
  Argyll's keyword) so that no reader has to guess; numbers are written with 17 significant digits,
  so a CGATS → CGATS round trip is exact.
* :func:`table_to_cgats`: result rows (``spectrocolor xyz``/``describe``/``report``) as CGATS.17,
  with CGATS's standard field names where one exists (``XYZ_X``, ``LAB_L`` …).

References
----------
ANSI CGATS.17-2009 / ISO 28178:2009 (file structure, standard field names SAMPLE_ID,
SAMPLE_NAME, XYZ_X/Y/Z, XYY_X/Y, LAB_L/A/B).
"""

from __future__ import annotations

import csv
import io
import math
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


def _quoted(text: str) -> str:
    return '"' + str(text).replace('"', "'") + '"'


def _cell(value) -> str:
    if value is None:  # a missing number (records() writes NaN as None)
        return "NaN"
    if isinstance(value, bool):
        return _quoted("true" if value else "false")
    if isinstance(value, (float, np.floating)):
        return "NaN" if math.isnan(value) else f"{float(value):.17g}"
    if isinstance(value, (int, np.integer)):
        return str(int(value))
    return _quoted(value)


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
        if key not in _STANDARD_KEYWORDS:
            lines.append(f"KEYWORD {_quoted(key)}")
        lines.append(f"{key} {_quoted(value)}")
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
        [str(i + 1), _quoted(names[i]), *(_quoted(column[i]) for _, column in extra), *(_cell(v) for v in values[i])]
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
    body = [[str(i + 1), *(_cell(row[c]) for c in columns)] for i, row in enumerate(rows)]
    return _cgats({"ORIGINATOR": "spectrocolor", **dict(keywords or {})}, fields, body)


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
    names = spectrum.names or tuple(f"spectrum_{i + 1}" for i in range(rows.shape[0]))
    buffer = io.StringIO()
    writer = csv.writer(buffer, lineterminator="\n")
    writer.writerow(["wavelength_nm", *names])
    for k, wavelength in enumerate(spectrum.wavelengths_nm):
        writer.writerow([f"{wavelength:.10g}", *(f"{v:.17g}" for v in rows[:, k])])
    return buffer.getvalue()
