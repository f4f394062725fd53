"""Shared machinery of the spectral-file readers: bounded text reading, numbers, scale options.

Every reader turns a file's text into a :class:`~spectrocolor.Spectrum`; this module holds what
they share: reading at most :data:`MAX_FILE_BYTES` of UTF-8 text, parsing numbers (with an
optional decimal comma), wavelength labels such as ``380``, ``380nm``, ``SPECTRAL_NM380``, and
the one rule for percent versus fraction (:func:`apply_scale`).

Numbers follow one grammar, :data:`NUMBER` (the decimal numbers of CGATS.17, CSV and XML
Schema): ASCII digits, an optional sign, point and exponent. Python's ``float`` accepts more --
digit separators (``0_5`` is 5.0), digits of other scripts (``'٣'`` is 3.0), ``inf`` and
``nan`` -- so every text that reaches ``float`` here has been checked first (for whole rows at
once: :func:`plain_ascii_numbers`).
"""

from __future__ import annotations

import re
from pathlib import Path

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


def read_text(path: Path) -> str:
    """The file's text (UTF-8, optional BOM), after checking its size; SpectrumError otherwise.

    Parameters
    ----------
    path : pathlib.Path
        The file.

    Returns
    -------
    str
        Its text, without a byte-order mark.

    Raises
    ------
    SpectrumError
        For a file larger than :data:`MAX_FILE_BYTES` or one that is not UTF-8.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     path = pathlib.Path(folder) / "a.csv"
    ...     _ = path.write_bytes(b"\\xef\\xbb\\xbfwavelength_nm,a")
    ...     read_text(path)
    'wavelength_nm,a'
    """
    size = path.stat().st_size
    if size > MAX_FILE_BYTES:
        raise SpectrumError(
            f"{path}: {size} bytes; spectral tables are read up to {MAX_FILE_BYTES} bytes "
            "(split the file, or read a spectral image with read_cube)"
        )
    try:
        return path.read_bytes().decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        raise SpectrumError(
            f"{path}: not UTF-8 text (byte {exc.start}); save the file as UTF-8 (CSV, CGATS, XML or JSON)"
        ) from None


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
