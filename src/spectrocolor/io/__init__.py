"""Spectral measurement files in and out, the format told by the content, never by a guess.

:func:`read_spectra` reads, whatever the file's name:

==========================  =====================================================  ==============
format                      recognised by                                          module
==========================  =====================================================  ==============
Excel ``.xlsx`` workbook    ZIP signature with ``xl/workbook.xml`` (bytes only)    :mod:`.xlsx`
JSON                        first character ``{``                                  here
IES TM-27-14/-20 XML        document element ``<IESTM2714>``                       :mod:`.tm27`
X-Rite CxF3 (ISO 17972-1)   document element ``<cc:CxF>``                          :mod:`.cxf`
Datacolor QTX               a ``[STANDARD_DATA n]`` (``BATCH_``, ``TRIAL_``) line  :mod:`.qtx`
CGATS.17, i1Profiler,       a ``BEGIN_DATA_FORMAT`` line                           :mod:`.cgats`
Argyll ``.ti3``/``.sp``
Ocean Optics OceanView,     a ``>>>>>Begin Spectral Data<<<<<`` line               :mod:`.oceanview`
SpectraSuite ``.txt``
Light meters: UPRtek,       ``LUX``/``380nm`` lines; ``Spectral Data 380[nm]``;    :mod:`.lightmeters`
Sekonic, Konica Minolta     ``Tcp`` with ``Spectrum[0]``/``360nm``
CL-500A/CL-70F
CSV/TSV/``;``, long/wide    anything else, by its header                           :mod:`.delimited`
(Agilent Cary WinUV pairs)
==========================  =====================================================  ==============

Light meters and OceanView give lights (``metadata["quantity"]``, ``["unit"]``; the meter's own
illuminance, CCT … in ``["stated"]``); OceanView keeps its irregular pixel wavelengths unless
``resample_nm=`` asks for a uniform grid.

Bytes are looked at before any text decoding (:mod:`.sniff`): a workbook is read, and a format
recognised by its signature but not read (``.xls``, PDF, images, HDF5/MATLAB, ICC profiles,
other ZIP archives …) gets one line naming it and what to do instead.

No registry package reads these formats to this standard without pulling in a large dependency
(colour-science reads TM-27-14 only; no maintained CGATS reader on PyPI keeps sample names,
keywords and the percent declaration), so the readers are written here on the standard library.
A text file that is none of them gets one short line naming the formats tried.

Writers: :func:`write_spectra` (``.csv``, ``.json``, ``.cgats``, ``.cxf``), and the text writers in
:mod:`.writers` used by the command line.
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np

from ..errors import SpectrumError
from ..spectrum import Spectrum
from . import cgats, cxf, delimited, lightmeters, oceanview, qtx, sniff, tm27, xlsx
from .conditions import DeclaredConditions, check_reflectance_scale, choose_conditions, declared_conditions
from .text import Decoded, apply_scale, decode_text
from .writers import spectra_to_cgats, spectra_to_csv, table_to_cgats

__all__ = ["read_spectra", "parse_spectra", "write_spectra", "spectra_to_csv", "spectra_to_cgats", "table_to_cgats",
           "decode_text", "Decoded", "declared_conditions", "choose_conditions", "DeclaredConditions",
           "check_reflectance_scale"]

#: Formats tried, in order, with what each expects (error messages list them).
FORMATS = (
    ("JSON", '{"wavelengths_nm": […], "spectra": {name: […]}}'),
    ("IES TM-27 XML", tm27.EXPECTED),
    ("X-Rite CxF3", cxf.EXPECTED),
    ("Datacolor QTX", qtx.EXPECTED),
    ("CGATS/Argyll", cgats.EXPECTED),
    ("OceanView/SpectraSuite", "a '>>>>>Begin Spectral Data<<<<<' line"),
    ("light meters", lightmeters.SUMMARY),
    ("CSV/TSV", delimited.EXPECTED),
)


def _parse_json(text: str, source: str, percent: bool | None) -> Spectrum:
    try:
        data = json.loads(text)
    except json.JSONDecodeError as exc:
        raise SpectrumError(f"{source}: not valid JSON ({exc})") from None
    except RecursionError:
        raise SpectrumError(f"{source}: JSON nested too deeply; expected {FORMATS[0][1]}") from None
    if isinstance(data, dict):
        for key in ("wavelengths_nm", "values", "spectra"):
            if key in data:
                _only_numbers(data[key], f"{source}: {key!r} must hold numbers")
    try:
        spectrum = Spectrum.from_dict(data)
    except (SpectrumError, ValueError, TypeError) as exc:
        raise SpectrumError(f"{source}: {exc}") from None
    if not np.all(np.isfinite(spectrum.values)):
        raise SpectrumError(f"{source}: values: NaN or infinite numbers; every value must be finite")
    values, note = apply_scale(spectrum.values, None, percent, source, "")
    return Spectrum(spectrum.wavelengths_nm, values, spectrum.names, {"format": "JSON", "value_scale": note})


def _only_numbers(value, where: str) -> None:
    """SpectrumError unless every leaf of ``value`` (lists, objects' values) is a JSON number.

    JSON has its own number grammar; a string such as ``"0_5"`` or ``"٣"`` is not a number
    (NumPy's conversion would read them as 5.0 and 3.0), nor is ``true``.
    """
    pending = [value]
    while pending:  # iterative: the depth is the file's, not the interpreter's
        item = pending.pop()
        if isinstance(item, list):
            pending.extend(item)
        elif isinstance(item, dict):
            pending.extend(item.values())
        elif isinstance(item, bool) or not isinstance(item, (int, float)):
            raise SpectrumError(f"{where}: {item!r:.40} is not a JSON number (write numbers "
                                "without quotes, e.g. 0.5)")


def parse_spectra(text: str | bytes, source: str = "<text>", percent: bool | None = None, *,
                  encoding: str | None = None, resample_nm: float | None = None) -> Spectrum:
    """Spectra from a file's text, the format detected from the content (see the module docstring).

    Parameters
    ----------
    text : str or bytes
        The whole file as text, or its bytes (decoded as :func:`decode_text` says: a
        byte-order mark, else UTF-8, else cp1252 only where unambiguous; or ``encoding``).
    source : str, default "<text>"
        Name used in messages (normally the file name).
    percent : bool or None, default None
        Whether the values are percentages (``True``), fractions (``False``) or on the scale the
        file declares (``None``: Argyll ``SPECTRAL_NORM``, ``CTI3``,
        ``SPECTRAL_PCT``/``SPECTRAL_DEC``; where the file does not say, as written); see
        :term:`percent`.
    encoding : str or None, keyword-only, default None
        For ``bytes``: the codec to decode them with (``cp1252``, ``latin-1``, ``utf-16`` …)
        instead of detecting it. Text that is already a ``str`` takes none.
    resample_nm : float or None, keyword-only, default None
        ``None`` keeps the file's wavelengths as they are (an OceanView export's irregular
        pixel wavelengths included; ``metadata["grid"]`` says so); a step such as ``1``
        interpolates linearly onto a uniform grid of that step inside the measured range and
        records it in ``metadata["resampled"]`` (:func:`spectrocolor.io.oceanview.resampled`).

    Returns
    -------
    Spectrum
        ``(N, K)`` (or ``(K,)`` for one spectrum) with names and ``metadata`` (``format``,
        ``value_scale``, for bytes ``encoding`` and ``encoding_note``, and whatever the file says:
        ``instrument``, ``illuminant``, ``geometry``,
        ``date``, ``keywords``, ``sample_fields``).

    Raises
    ------
    SpectrumError
        One line: where the file is wrong, or which formats were tried and what they expect.

    Examples
    --------
    >>> s = parse_spectra("Sample,400,500,600\\nred,5,20,60\\n", "tiles.csv", percent=True)
    >>> s.names, s.values.tolist(), s.metadata["format"]
    (('red',), [0.05, 0.2, 0.6], 'CSV, wide')
    >>> parse_spectra("nm;Probe 1°\\n400;0,5\\n".encode("cp1252")).metadata["encoding"]
    'cp1252'
    """
    if percent not in (None, True, False):
        raise SpectrumError(f"percent: expected True, False or None (follow the file), got {percent!r:.40}")
    if isinstance(text, (bytes, bytearray, memoryview)):
        spectrum = _parse_bytes(bytes(text), source, percent, encoding)
    elif encoding is not None:
        raise SpectrumError(f"encoding: applies to bytes; {source} was given as str (already decoded), "
                            "so leave encoding unset or pass the file's bytes")
    else:
        spectrum = _parse_text(text, source, percent)
    return spectrum if resample_nm is None else oceanview.resampled(spectrum, resample_nm, source)


def _parse_bytes(data: bytes, source: str, percent: bool | None, encoding: str | None) -> Spectrum:
    """A file's bytes: a workbook or a named binary format first (:mod:`.sniff`), else text."""
    if sniff.binary_format(data, source) == "xlsx":
        return xlsx.parse_xlsx(data, source, percent)
    decoded = decode_text(data, source, encoding)
    del data  # not held while the text is parsed (read_spectra's peak memory: tests/io/test_io_memory.py)
    return _parse_decoded(decoded, source, percent)


def _parse_decoded(decoded: Decoded, source: str, percent: bool | None) -> Spectrum:
    """The spectra of decoded text, with ``metadata["encoding"]`` and ``["encoding_note"]``."""
    spectrum = _parse_text(decoded.text, source, percent)
    metadata = {**spectrum.metadata, "encoding": decoded.encoding, "encoding_note": decoded.note}
    return Spectrum(spectrum.wavelengths_nm, spectrum.values, spectrum.names, metadata)


def _parse_text(text: str, source: str, percent: bool | None) -> Spectrum:
    """:func:`parse_spectra` of a ``str``."""
    head = text.lstrip()
    if head.startswith("{"):
        return _parse_json(text, source, percent)
    if head.startswith("<"):
        if tm27.looks_like_tm27(text):
            return tm27.parse_tm27(text, source, percent)
        if cxf.looks_like_cxf(text):
            return cxf.parse_cxf(text, source, percent)
        raise SpectrumError(f"{source}: XML, but not IES TM-27 ({tm27.EXPECTED}) nor X-Rite CxF3 (<cc:CxF>)")
    if qtx.looks_like_qtx(text):
        return qtx.parse_qtx(text, source, percent)
    if cgats.looks_like_cgats(text):
        return cgats.parse_cgats(text, source, percent)
    if oceanview.looks_like_oceanview(text):
        return oceanview.parse_oceanview(text, source, percent)
    if (maker := lightmeters.identify(text)) is not None:
        return lightmeters.parse_lightmeter(text, source, percent, maker)
    try:
        return delimited.parse_delimited(text, source, percent)
    except SpectrumError as exc:
        if "not a spectral table" not in str(exc) and "no data" not in str(exc):
            raise
        tried = ", ".join(name for name, _ in FORMATS)
        raise SpectrumError(f"{exc}. Formats tried: {tried}, .xlsx (docs/measurement_data.md)") from None


def read_spectra(path: str | Path, *, percent: bool | None = None, encoding: str | None = None,
                 resample_nm: float | None = None) -> Spectrum:
    """Read the spectra in a measurement file: CSV/TSV (long or wide, ``;`` with decimal commas),
    CGATS.17 (i1Profiler, X-Rite, Barbieri), ArgyllCMS ``.ti3``/``.sp``, IES TM-27 XML, X-Rite
    CxF3, Datacolor QTX, an Excel ``.xlsx`` workbook (its first sheet) or JSON.

    The format is told by the content, not the file name. See :func:`parse_spectra` for
    ``percent`` and what the result holds; wavelengths must be strictly increasing, and a
    ``wavelength_um`` column is converted to nm.

    Parameters
    ----------
    path : str or os.PathLike
        The measurement file.
    percent : bool or None, keyword-only, default None
        As for :func:`parse_spectra`; see :term:`percent`.
    encoding : str or None, keyword-only, default None
        ``None`` detects it: a byte-order mark (UTF-8, UTF-16, UTF-32), else UTF-8, else cp1252
        only when every byte is a printable cp1252 character (see
        :func:`spectrocolor.io.decode_text`); or the codec to use (``"cp1252"``,
        ``"latin-1"``, ``"utf-16"``, ``"mac-roman"`` …).
    resample_nm : float or None, keyword-only, default None
        As for :func:`parse_spectra`: ``None`` keeps the file's wavelengths (irregular ones
        too), a step interpolates onto a uniform grid and says so in ``metadata["resampled"]``.

    Returns
    -------
    Spectrum
        ``(N, K)`` (or ``(K,)``) values on the 0–1 scale for reflectances when the file or
        ``percent`` says so, with names and ``metadata`` (``format``, ``value_scale``,
        ``encoding`` (the codec used), ``encoding_note`` (how it was chosen), …).

    Raises
    ------
    SpectrumError
        For a path that is not a file name, an unreadable or unrecognised file, or malformed
        content (one line saying where).
    FileNotFoundError
        If the file does not exist.

    References
    ----------
    ANSI CGATS.17-2009 (exchange format); ArgyllCMS ``.ti3``/``.sp`` file formats; ANSI/IES
    TM-27-20 (spectral data format).

    Examples
    --------
    >>> from importlib.resources import files
    >>> tcs = read_spectra(files("spectrocolor") / "data" / "reflectances_cie_tcs.csv")
    >>> tcs.values.shape[0], tcs.metadata["format"], tcs.metadata["encoding"]
    (14, 'CSV, long', 'utf-8')
    """
    if not isinstance(path, (str, Path)) and not hasattr(path, "read_bytes"):
        raise SpectrumError(f"path: expected a file name (str or Path), got {type(path).__name__}")
    path = Path(str(path))
    if not path.exists():
        raise FileNotFoundError(f"{path}: no such file")
    if path.is_dir():
        raise SpectrumError(f"{path}: is a folder, not a spectral file (CSV, CGATS, TM-27 XML or JSON)")
    if percent not in (None, True, False):
        raise SpectrumError(f"percent: expected True, False or None (follow the file), got {percent!r:.40}")
    spectrum = _parse_bytes(sniff.read_checked(path, encoding), str(path), percent, encoding)
    return spectrum if resample_nm is None else oceanview.resampled(spectrum, resample_nm, str(path))


def write_spectra(spectrum: Spectrum, path: str | Path) -> Path:
    """Write ``spectrum`` to ``path`` atomically: ``.csv``/``.txt`` (long CSV), ``.json`` or
    ``.cgats`` (CGATS.17, 0–1 scale declared); returns the path.

    Parameters
    ----------
    spectrum : Spectrum
        One spectrum or an ``(N, K)`` batch (wavelengths in nm; values written as they are).
    path : str or os.PathLike
        Output file; the suffix chooses the format.

    Returns
    -------
    pathlib.Path
        ``path``, written as an :term:`atomic write`.

    Raises
    ------
    SpectrumError
        For a non-Spectrum or an unknown suffix.
    spectrocolor.safe_write.OutputError
        The spectra file could not be written; see :term:`atomic write`.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> s = Spectrum([400, 500], [[0.1, 0.2], [0.3, 0.4]], ["a", "b"])
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     read_spectra(write_spectra(s, pathlib.Path(folder) / "s.cgats")) == s
    True
    """
    from ..safe_write import write_text

    if not isinstance(spectrum, Spectrum):
        raise SpectrumError(f"spectrum: expected a Spectrum, got {type(spectrum).__name__}")
    path = Path(path)
    suffix = path.suffix.lower()
    if suffix == ".json":
        text = json.dumps(spectrum.to_dict(), indent=1)
    elif suffix in (".csv", ".txt"):
        text = spectra_to_csv(spectrum)
    elif suffix == ".cgats":
        text = spectra_to_cgats(spectrum)
    elif suffix == ".cxf":
        text = cxf.spectra_to_cxf(spectrum)
    else:
        raise SpectrumError(f"path: unknown spectral file type {path.suffix!r}; use .csv, .json, .cgats or .cxf")
    return write_text(path, text)
