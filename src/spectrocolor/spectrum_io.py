"""Read and write spectra as CSV or JSON, with messages that say exactly what is wrong.

CSV layout: optional ``#`` comment lines, then a header whose first column is the
wavelength (``wavelength_nm``, ``wavelength``, ``nm``, ``lambda`` …; a header naming
micrometres — ``um``, ``µm``, ``micrometre`` — is converted to nm and says so in the
docstring), then one column per spectrum. JSON: see :meth:`Spectrum.to_dict`.
"""

from __future__ import annotations

import csv
import io
import json
import re
from pathlib import Path

import numpy as np

from .errors import SpectrumError
from .spectrum import Spectrum

_MICROMETRE = re.compile(r"((^|[^a-z])um($|[^a-z])|µm|μm|micro)", re.IGNORECASE)
_NANOMETRE = re.compile(r"(nm|nanomet|wavelength|lambda|λ|wl)", re.IGNORECASE)


def _is_number(text: str) -> bool:
    try:
        float(text)
    except ValueError:
        return False
    return True


def _parse_csv(text: str, source: str) -> Spectrum:
    lines = [(number, line) for number, line in enumerate(text.splitlines(), start=1)]
    content = [(n, line) for n, line in lines if line.strip() and not line.lstrip().startswith("#")]
    if not content:
        raise SpectrumError(f"{source}: no data (only comments or blank lines)")
    dialect = csv.excel_tab if "\t" in content[0][1] and "," not in content[0][1] else csv.excel
    rows = [(n, row) for n, row in ((n, next(csv.reader([line], dialect))) for n, line in content)]
    header_line, header = rows[0]
    header = [cell.strip() for cell in header]
    if _is_number(header[0]):
        raise SpectrumError(
            f"{source}, line {header_line}: missing header; the first line must name the columns, "
            "e.g. 'wavelength_nm,sample_1,sample_2'"
        )
    if len(header) < 2:
        raise SpectrumError(
            f"{source}, line {header_line}: header has {len(header)} column(s); need a wavelength "
            "column and at least one spectrum column (is the delimiter a comma?)"
        )
    unit_scale = 1.0
    if _MICROMETRE.search(header[0]):
        unit_scale = 1000.0
    elif not _NANOMETRE.search(header[0]):
        raise SpectrumError(
            f"{source}, line {header_line}: first column {header[0]!r} is not recognisably a "
            "wavelength; name it 'wavelength_nm' (or 'wavelength_um' for micrometres)"
        )
    names = header[1:]
    if len(set(names)) != len(names):
        raise SpectrumError(f"{source}, line {header_line}: duplicate column names in {names}")
    data = np.empty((len(rows) - 1, len(header)))
    for r, (line_number, row) in enumerate(rows[1:]):
        if len(row) != len(header):
            raise SpectrumError(f"{source}, line {line_number}: {len(row)} cells, but the header has {len(header)}")
        for c, cell in enumerate(row):
            try:
                data[r, c] = float(cell)
            except ValueError:
                raise SpectrumError(
                    f"{source}, line {line_number}, column {header[c]!r}: {cell.strip()!r} is not a number"
                ) from None
    if data.shape[0] == 0:
        raise SpectrumError(f"{source}: header but no data rows")
    if not np.all(np.isfinite(data)):
        r, c = np.argwhere(~np.isfinite(data))[0]
        raise SpectrumError(f"{source}, line {rows[r + 1][0]}, column {header[c]!r}: not a finite number")
    wavelengths = data[:, 0] * unit_scale
    try:
        values = data[:, 1:].T
        return Spectrum(wavelengths, values if values.shape[0] > 1 else values[0], names)
    except SpectrumError as exc:
        raise SpectrumError(f"{source}: {exc}") from None


def read_spectra(path: str | Path) -> Spectrum:
    """Read spectra from a ``.csv``/``.tsv``/``.txt`` table or a ``.json`` file.

    Returns one :class:`Spectrum` holding every column (shape ``(N, K)``, or ``(K,)`` for a
    single column) with the column names as ``names``. Wavelengths must be strictly
    increasing; a wavelength header in micrometres (``wavelength_um``) is converted to nm.
    """
    if not isinstance(path, (str, Path)):
        raise SpectrumError(f"path: expected a file name (str or Path), got {type(path).__name__}")
    path = Path(path)
    if not path.exists():
        raise FileNotFoundError(f"{path}: no such file")
    if path.is_dir():
        raise SpectrumError(f"{path}: is a folder, not a spectral file (.csv or .json)")
    try:
        text = path.read_text(encoding="utf-8-sig")
    except UnicodeDecodeError as exc:
        raise SpectrumError(
            f"{path}: not UTF-8 text (byte {exc.start}); save the table as UTF-8 CSV or JSON"
        ) from None
    if path.suffix.lower() == ".json":
        try:
            data = json.loads(text)
        except json.JSONDecodeError as exc:
            raise SpectrumError(f"{path}: not valid JSON ({exc})") from None
        try:
            spectrum = Spectrum.from_dict(data)
        except (SpectrumError, ValueError, TypeError) as exc:
            raise SpectrumError(f"{path}: {exc}") from None
        if not np.all(np.isfinite(spectrum.values)):
            raise SpectrumError(f"{path}: values: NaN or infinite numbers; every value must be finite")
        return spectrum
    return _parse_csv(text, str(path))


def spectra_to_csv(spectrum: Spectrum) -> str:
    """CSV text: ``wavelength_nm`` then one column per spectrum (batches of shape ``(N, K)``)."""
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


def write_spectra(spectrum: Spectrum, path: str | Path) -> Path:
    """Write ``spectrum`` to ``path`` as CSV (``.csv``) or JSON (``.json``); returns the path."""
    if not isinstance(spectrum, Spectrum):
        raise SpectrumError(f"spectrum: expected a Spectrum, got {type(spectrum).__name__}")
    path = Path(path)
    if path.suffix.lower() == ".json":
        path.write_text(json.dumps(spectrum.to_dict(), indent=1), encoding="utf-8")
    elif path.suffix.lower() in (".csv", ".txt"):
        path.write_text(spectra_to_csv(spectrum), encoding="utf-8")
    else:
        raise SpectrumError(f"path: unknown spectral file type {path.suffix!r}; use .csv or .json")
    return path
