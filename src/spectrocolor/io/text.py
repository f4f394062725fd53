"""Shared machinery of the spectral-file readers: bounded text reading, numbers, scale options.

Every reader turns a file's text into a :class:`~spectrocolor.Spectrum`; this module holds what
they share: reading at most :data:`MAX_FILE_BYTES` of text in the encoding the bytes say
(:func:`decode_text`: a byte-order mark, UTF-8, else cp1252 only when unambiguous), parsing numbers (with an
optional decimal comma), wavelength labels such as ``380``, ``380nm``, ``SPECTRAL_NM380``, and
the one rule for percent versus fraction (:func:`apply_scale`).

Numbers follow one grammar, :data:`NUMBER` (the decimal numbers of CGATS.17, CSV and XML
Schema): ASCII digits, an optional sign, point and exponent. Python's ``float`` accepts more --
digit separators (``0_5`` is 5.0), digits of other scripts (``'٣'`` is 3.0), ``inf`` and
``nan`` -- so every text that reaches ``float`` here has been checked first (for whole rows at
once: :func:`plain_ascii_numbers`).
"""

from __future__ import annotations

import codecs
import re
from pathlib import Path
from typing import NamedTuple

import numpy as np

from ..errors import SpectrumError

#: Largest spectral file read, bytes (a 10 000-sample, 401-band table is about 40 MB).
MAX_FILE_BYTES = 256 * 1024 * 1024

#: Column or field names that carry a wavelength: ``380``, ``380nm``, ``380 nm``, ``nm380``,
#: ``R380``, ``SPECTRAL_NM380``, ``SPECTRAL_NM_380``, ``SPECTRAL_380``, ``SPEC_380``,
#: ``SPECTRAL_PCT_380``, ``SPECTRAL_DEC_380`` (case-insensitive; decimals allowed).
WAVELENGTH_LABEL = re.compile(
    r"^(?:(?P<prefix>spectral_(?:nm|pct|dec)?_?|spec_|nm_?|r_?|λ)?)"
    r"(?P<nm>[0-9]{3,4}(?:\.[0-9]+)?)\s*(?:nm)?$",
    re.IGNORECASE,
)

#: A number as the file formats write it: ASCII digits, optional sign, point and exponent
#: (``0.5``, ``-1``, ``.5``, ``5.``, ``1e-3``); no digit separators, no other scripts' digits.
#: Possessive quantifiers: no backtracking, linear in the length of the text.
NUMBER = re.compile(r"[+-]?(?:[0-9]++(?:\.[0-9]*+)?|\.[0-9]++)(?:[eE][+-]?[0-9]++)?")


def plain_ascii_numbers(cells) -> bool:
    """Whether the texts ``cells`` can go to ``float`` without reading more than :data:`NUMBER`.

    For ASCII text without ``_``, ``float`` reads exactly the grammar of :data:`NUMBER` plus
    ``inf``/``nan`` (which the readers refuse as non-finite afterwards), so one check of the
    joined row is enough; anything else is parsed cell by cell with :func:`number`.

    Parameters
    ----------
    cells : iterable of str
        The cells of a row (or a table, flattened).

    Returns
    -------
    bool
        True if no cell holds ``_`` or a non-ASCII character.

    Examples
    --------
    >>> plain_ascii_numbers(["0.5", "1e-3"]), plain_ascii_numbers(["0_5"]), plain_ascii_numbers(["٣"])
    (True, False, False)
    """
    joined = "".join(cells)
    return joined.isascii() and "_" not in joined


#: Bytes that cp1252 leaves undefined: a file holding one is not cp1252 text.
CP1252_UNDEFINED = frozenset(b"\x81\x8d\x8f\x90\x9d")

#: Control bytes a text file does not hold (everything below 0x20 but tab, LF, CR; and DEL).
_CONTROL_BYTES = frozenset(range(0x20)) - frozenset(b"\t\n\r") | {0x7F}

#: Byte-order marks, longest first (UTF-32 LE's mark begins with UTF-16 LE's).
_BOMS = (
    (b"\x00\x00\xfe\xff", "utf-32-be", "UTF-32 BE byte-order mark"),
    (b"\xff\xfe\x00\x00", "utf-32-le", "UTF-32 LE byte-order mark"),
    (b"\xef\xbb\xbf", "utf-8", "UTF-8 byte-order mark"),
    (b"\xff\xfe", "utf-16-le", "UTF-16 LE byte-order mark"),
    (b"\xfe\xff", "utf-16-be", "UTF-16 BE byte-order mark"),
)

#: What ``encoding=`` / ``--encoding`` accepts, for messages.
ENCODINGS_ACCEPTED = ("utf-8, utf-16, utf-16-le, utf-16-be, cp1252, latin-1 or any other text encoding "
                      "Python knows (e.g. mac-roman, shift_jis)")


class Decoded(NamedTuple):
    """A file's text and how its bytes were decoded (see :func:`decode_text`)."""

    text: str
    #: The codec used, as Python names it (``utf-8``, ``utf-16-le``, ``cp1252``, …).
    encoding: str
    #: How it was chosen, for ``metadata["encoding_note"]``.
    note: str


def _byte(data: bytes, at: int) -> str:
    return f"byte {at} (0x{data[at]:02X})"


def codec_name(encoding: str) -> str:
    """The codec named ``encoding`` as Python names it; SpectrumError for an unknown or non-text one.

    Parameters
    ----------
    encoding : str
        A codec name or alias (``latin-1``, ``CP1252``, ``utf16`` …).

    Returns
    -------
    str
        Python's name for it.

    Raises
    ------
    SpectrumError
        For an unknown name, a codec that is not a text encoding (``rot13``, ``zlib``) or a non-str.

    Examples
    --------
    >>> codec_name("Latin-1"), codec_name("CP1252"), codec_name("UTF16")
    ('iso8859-1', 'cp1252', 'utf-16')
    """
    if not isinstance(encoding, str):
        raise SpectrumError(f"encoding: expected a name such as 'cp1252', got {type(encoding).__name__}")
    try:
        info = codecs.lookup(encoding)
    except LookupError:
        raise SpectrumError(f"encoding: unknown encoding {encoding!r:.40}; expected {ENCODINGS_ACCEPTED}") from None
    if not getattr(info, "_is_text_encoding", True):
        raise SpectrumError(f"encoding: {encoding!r:.40} is not a text encoding; expected {ENCODINGS_ACCEPTED}")
    return info.name


def decode_text(data: bytes, source: str, encoding: str | None = None) -> Decoded:
    """A file's bytes as text: the encoding told by the bytes, or the one given; SpectrumError otherwise.

    The detection rule, in this order, never a guess between plausible readings:

    1. A byte-order mark says the encoding: UTF-8, UTF-16 LE/BE or UTF-32 LE/BE (the mark is
       removed).
    2. Bytes holding a NUL (0x00) are not text: UTF-16 without a byte-order mark, or a binary
       file (the error says so).
    3. Bytes that are valid UTF-8 are UTF-8 (ASCII included).
    4. Bytes that are not UTF-8 are cp1252 (Windows Latin-1, a superset of the printable
       ISO-8859-1) only when every byte is a printable cp1252 character: no byte cp1252 leaves
       undefined (0x81, 0x8D, 0x8F, 0x90, 0x9D) and no control byte but tab, LF and CR (binary
       files and workbooks hold them).
    5. Anything else is one SpectrumError naming the first offending byte by its offset and
       value and saying how to give the encoding (``encoding=`` / ``--encoding``).

    Parameters
    ----------
    data : bytes
        The file's bytes.
    source : str
        The file name, for messages.
    encoding : str or None, default None
        ``None`` detects as above; otherwise the bytes are decoded with this codec (any Python
        text codec: ``utf-8``, ``utf-16``, ``cp1252``, ``latin-1``, ``mac-roman`` …), strictly,
        and a leading byte-order mark is removed.

    Returns
    -------
    Decoded
        ``(text, encoding, note)``: the text, the codec used and how it was chosen.

    Raises
    ------
    SpectrumError
        For bytes that the given encoding cannot decode, or that are neither marked, UTF-8 nor
        unambiguously cp1252.

    Examples
    --------
    >>> text, encoding, note = decode_text("Messung 10°".encode("cp1252"), "a.txt")
    >>> text, encoding
    ('Messung 10°', 'cp1252')
    >>> note
    'detected: not UTF-8 (byte 10 (0xB0)); every byte is a printable cp1252 character'
    >>> decode_text(b"\\xff\\xfea\\x00", "a.txt").encoding
    'utf-16-le'
    >>> decode_text(b"PK\\x03\\x04\\xb0", "book.xlsx")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    spectrocolor.errors.SpectrumError: book.xlsx: not text in a known encoding: byte 4 (0xB0) is not valid UTF-8, ...
    """
    if encoding is not None:
        codec = codec_name(encoding)
        try:
            text = data.decode(codec)
        except UnicodeDecodeError as exc:
            raise SpectrumError(
                f"{source}: {_byte(data, exc.start)} is not valid {codec} (encoding={encoding!r:.40}); "
                f"give the file's encoding ({ENCODINGS_ACCEPTED}), or leave encoding unset to detect it"
            ) from None
        return Decoded(text.removeprefix("\ufeff"), codec, f"as given (encoding={encoding!r:.40})")
    for mark, codec, said in _BOMS:
        if data.startswith(mark):
            try:
                return Decoded(data[len(mark):].decode(codec), codec, f"detected: {said}")
            except UnicodeDecodeError as exc:
                raise SpectrumError(
                    f"{source}: starts with a {said} but {_byte(data, exc.start + len(mark))} is not valid "
                    f"{codec}; pass encoding= (--encoding on the command line): {ENCODINGS_ACCEPTED}"
                ) from None
    nul = data.find(b"\x00")
    if nul >= 0:
        raise SpectrumError(
            f"{source}: not text in a known encoding: {_byte(data, nul)} is a NUL byte, which no text file in "
            "UTF-8 or cp1252 holds (UTF-16 without a byte-order mark, or a binary file such as a workbook); "
            f"if it is a text file, pass encoding= (--encoding on the command line): {ENCODINGS_ACCEPTED}; "
            "or save it as UTF-8"
        )
    try:
        return Decoded(data.decode("utf-8"), "utf-8", "detected: valid UTF-8")
    except UnicodeDecodeError as exc:
        not_utf8 = exc.start
    offending = next((at for at, byte in enumerate(data) if byte in CP1252_UNDEFINED or byte in _CONTROL_BYTES),
                     None)
    if offending is None:
        return Decoded(data.decode("cp1252"), "cp1252",
                       f"detected: not UTF-8 ({_byte(data, not_utf8)}); every byte is a printable cp1252 character")
    byte = data[offending]
    why = "undefined in cp1252" if byte in CP1252_UNDEFINED else "a control character"
    raise SpectrumError(
        f"{source}: not text in a known encoding: {_byte(data, not_utf8)} is not valid UTF-8, and "
        f"{_byte(data, offending)} is {why}, so it is not cp1252 either; if it is a text file, pass "
        f"encoding= (--encoding on the command line): {ENCODINGS_ACCEPTED}; or save it as UTF-8"
    )


def read_text(path: Path, encoding: str | None = None) -> str:
    """The file's text (see :func:`read_decoded`).

    Parameters
    ----------
    path : pathlib.Path
        The file.
    encoding : str or None, default None
        As for :func:`decode_text`.

    Returns
    -------
    str
        Its text, without a byte-order mark.

    Raises
    ------
    SpectrumError
        For a file larger than :data:`MAX_FILE_BYTES` or one that cannot be decoded.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     path = pathlib.Path(folder) / "a.csv"
    ...     _ = path.write_bytes(b"\\xef\\xbb\\xbfwavelength_nm,a")
    ...     read_text(path)
    'wavelength_nm,a'
    """
    return read_decoded(path, encoding).text


def read_decoded(path: Path, encoding: str | None = None) -> Decoded:
    """The file's text and encoding (:func:`decode_text`), after checking its size.

    Parameters
    ----------
    path : pathlib.Path
        The file.
    encoding : str or None, default None
        ``None`` detects the encoding; otherwise the codec to decode with.

    Returns
    -------
    Decoded
        ``(text, encoding, note)``.

    Raises
    ------
    SpectrumError
        For a file larger than :data:`MAX_FILE_BYTES` or one that cannot be decoded.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     path = pathlib.Path(folder) / "a.csv"
    ...     _ = path.write_bytes("wavelength_nm,µ".encode("utf-16"))
    ...     read_decoded(path).text
    'wavelength_nm,µ'
    """
    if encoding is not None:
        codec_name(encoding)  # an unknown name is the caller's error, before the file is read
    size = path.stat().st_size
    if size > MAX_FILE_BYTES:
        raise SpectrumError(
            f"{path}: {size} bytes; spectral tables are read up to {MAX_FILE_BYTES} bytes "
            "(split the file, or read a spectral image with read_cube)"
        )
    return decode_text(path.read_bytes(), str(path), encoding)


def wavelength_of(label: str) -> float | None:
    """The wavelength in nm that a column label names (see :data:`WAVELENGTH_LABEL`), or None.

    Parameters
    ----------
    label : str
        A column label such as ``"SPECTRAL_NM_380"``, ``"400nm"`` or ``"400"``.

    Returns
    -------
    float or None
        The wavelength in nm, or None for a label that names none.

    Examples
    --------
    >>> wavelength_of("SPECTRAL_NM_380"), wavelength_of("400nm"), wavelength_of("Sample")
    (380.0, 400.0, None)
    """
    match = WAVELENGTH_LABEL.match(label.strip())
    return float(match["nm"]) if match else None


def number(cell: str, where: str, decimal_comma: bool = False) -> float:
    """``cell`` as a finite float (``0,5`` accepted with ``decimal_comma``), or a SpectrumError.

    Parameters
    ----------
    cell : str
        The text of one cell.
    where : str
        Its place, for the error message (e.g. "file, line 7, column '410'").
    decimal_comma : bool, default False
        Read ``,`` as the decimal separator.

    Returns
    -------
    float
        The finite number.

    Raises
    ------
    SpectrumError
        For text that is not a finite number of the grammar :data:`NUMBER` (``0_5``, ``٣``,
        ``1,5`` without ``decimal_comma``, ``nan``, ``inf``).

    Examples
    --------
    >>> number("0,5", "tiles.csv, line 2", decimal_comma=True)
    0.5
    >>> number("0_5", "tiles.csv, line 2")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    spectrocolor.errors.SpectrumError: tiles.csv, line 2: '0_5' is not a number (expected ASCII digits ...)
    """
    text = cell.strip()
    if decimal_comma:
        text = text.replace(",", ".")
    if NUMBER.fullmatch(text) is None:
        if text.lower().lstrip("+-") in ("nan", "inf", "infinity"):
            raise SpectrumError(f"{where}: {cell.strip()[:40]!r} is not a finite number")
        point = "decimal comma" if decimal_comma else "decimal point"
        raise SpectrumError(f"{where}: {cell.strip()[:40]!r} is not a number (expected ASCII digits "
                            f"with an optional sign, {point} and exponent, e.g. "
                            f"{'0,5' if decimal_comma else '0.5'} or 1e-3)")
    value = float(text)
    if not np.isfinite(value):
        raise SpectrumError(f"{where}: {cell.strip()[:40]!r} is not a finite number")
    return value


def number_table(rows: list[list[str]], locate, decimal_comma: bool = False) -> np.ndarray:
    """Equal-length rows of text cells as a finite float table, (rows, cells).

    NumPy converts the whole table at once; if anything is not a finite number, each cell is
    parsed with :func:`number` so that the error names the first bad one (``locate(r, c)`` gives
    its place, e.g. "file, line 7, column '410'").

    Parameters
    ----------
    rows : list of list of str
        The cells, rows of equal length.
    locate : callable
        ``locate(row, column) -> str``: where a cell is, for error messages.
    decimal_comma : bool, default False
        Read ``,`` as the decimal separator.

    Returns
    -------
    numpy.ndarray, shape (rows, cells)
        Float64 table.

    Raises
    ------
    SpectrumError
        Naming the first cell that is not a finite number.

    Examples
    --------
    >>> number_table([["1", "2"], ["3", "4"]], lambda r, c: f"line {r + 1}").tolist()
    [[1.0, 2.0], [3.0, 4.0]]
    """
    try:
        cells = [[cell.replace(",", ".") for cell in row] for row in rows] if decimal_comma else rows
        if all(plain_ascii_numbers(row) for row in cells):
            table = np.array(cells, dtype=float)
            if table.size == 0 or np.all(np.isfinite(table)):
                return table.reshape(len(rows), -1)
    except ValueError:
        pass
    return np.array(
        [[number(cell, locate(r, c), decimal_comma) for c, cell in enumerate(row)] for r, row in enumerate(rows)]
    )


def apply_scale(values: np.ndarray, declared: float | None, percent: bool | None, source: str, how: str):
    """Values on the file's declared scale turned into fractions, following the one rule.

    Parameters
    ----------
    values : numpy.ndarray
        The numbers as written in the file.
    declared : float or None
        The full-scale value the file declares (100 for percent, 1 for fractions, Argyll's
        ``SPECTRAL_NORM``), or ``None`` where the format does not say.
    percent : bool or None
        The caller's option: ``True`` (the values are percentages), ``False`` (fractions) or
        ``None`` (follow the file; where the file does not say, keep the values as written).
    source, how : str
        File name and what declared the scale, for messages.

    Returns
    -------
    tuple
        ``(values, note)``: the scaled values and a note for ``metadata["value_scale"]``.

    Raises
    ------
    SpectrumError
        When ``percent`` contradicts what the file declares, or when the declared full scale
        is not a finite positive number that keeps every value finite (Argyll's
        ``SPECTRAL_NORM "1e-320"`` made infinities).

    Examples
    --------
    >>> import numpy as np
    >>> apply_scale(np.array([50.0]), 100.0, None, "tiles.cgats", "PCT")
    (array([0.5]), 'divided by 100 as the file declares (PCT)')
    """
    if declared is not None:
        if percent is not None and (declared != 1.0) != percent:
            said = "percent" if declared == 100.0 else f"full scale {declared:g}"
            raise SpectrumError(
                f"percent: {source} declares its values on {said if declared != 1.0 else 'the 0–1 scale'} "
                f"({how}); percent={percent} contradicts it; leave percent unset"
            )
        if not (np.isfinite(declared) and declared > 0):
            raise SpectrumError(f"{source}: the declared full scale ({how}) must be a finite positive "
                                f"number, got {declared!r:.40}")
        with np.errstate(over="ignore", divide="ignore", invalid="ignore"):
            scaled = values / declared
        if not np.all(np.isfinite(scaled)):
            raise SpectrumError(
                f"{source}: the declared full scale {declared:g} ({how}) is too small: dividing the "
                "values by it goes beyond the float range; it must be a full scale such as 1 or 100"
            )
        return scaled, f"divided by {declared:g} as the file declares ({how})"
    if percent is None:
        return values, "as written (the file does not declare percent or fraction; pass percent=True/False)"
    if percent:
        return values / 100.0, "divided by 100 (percent=True)"
    return values, "as written (percent=False)"
