"""Datacolor QTX files: standards and their batches (trials), each a reflectance spectrum.

QTX is plain text in sections. Each standard is a section headed ``[STANDARD_DATA n]``, each of
its batches (trials) a following ``[BATCH_DATA n]`` section (some software writes a word before
the kind, ``[PRODUCT STANDARD_DATA 0]``, or ``TRIAL_DATA``); a section's body is one
``FIELD=VALUE`` per line, the field names starting with the section's prefix (``STD_``,
``STANDARD_``, ``BATCH_``, ``TRIAL_``). The spectrum is given by

* ``<prefix>_REFLLOW``: the first wavelength (nm),
* ``<prefix>_REFLINTERVAL``: the step (nm),
* ``<prefix>_REFLPOINTS``: the number of values,
* ``<prefix>_R``: the reflectance values in percent, separated by commas,

and the sample's name by ``<prefix>_NAME`` (standards' names are unique in a file; a batch
names its standard in ``BATCH_STD_NAME`` where the file says). The prefix of a section is the
one its ``…_R`` field has. The declared point count must equal the number of values (and is
checked against the memory budget before any array is made); all spectra must share one grid.
Values are divided by 100 (QTX reflectance is in percent), so ``percent=False`` contradicts the
file. Every other field of a section is kept, per sample, in ``metadata["sample_fields"]``
under its name without the prefix (``DATETIME``, ``INST_TYPE``, ``VIEWING`` …), with ``kind``
(``standard`` or ``batch``) and ``standard`` (the standard a batch belongs to: its
``…_STD_NAME`` field, else the standard before it).

References
----------
Datacolor, *QTX File Specification* (public description of the sections and the STD_NAME,
STD_DATETIME, STD_REFLPOINTS, STD_REFLINTERVAL, STD_REFLLOW and STD_R fields).
"""

from __future__ import annotations

import re

import numpy as np

from ..budget import check_bytes
from ..errors import SpectrumError
from ..spectrum import Spectrum
from .text import apply_scale, number, number_table

__all__ = ["looks_like_qtx", "parse_qtx", "EXPECTED"]

#: What a QTX file must contain, for messages.
EXPECTED = "[STANDARD_DATA 0] sections with STD_NAME=, STD_REFLLOW=, STD_REFLINTERVAL=, STD_REFLPOINTS=, STD_R="
_BREAKS = "\n\r\x0b\x0c\x1c-\x1e\x85\u2028\u2029"
#: A data-section header at the start of a line (tried only at line starts: linear).
_SECTION = re.compile(rf"(?:\A|(?<=[{_BREAKS}]))[^\S{_BREAKS}]*+\[[^\]{_BREAKS}]*?\b"
                      r"(STANDARD|STD|BATCH|TRIAL)_DATA[ \t]+([0-9]+)[ \t]*\]", re.IGNORECASE)
_HEADER = re.compile(r"\[[^\]]*?\b(STANDARD|STD|BATCH|TRIAL)_DATA[ \t]+([0-9]+)[ \t]*\]", re.IGNORECASE)
_KIND = {"STANDARD": "standard", "STD": "standard", "BATCH": "batch", "TRIAL": "batch"}
_SPECTRAL = ("R", "REFLLOW", "REFLINTERVAL", "REFLPOINTS", "NAME")


def looks_like_qtx(text: str) -> bool:
    """True if a line starts a QTX data section (``[STANDARD_DATA 0]``, ``[BATCH_DATA 3]`` …).

    Parameters
    ----------
    text : str
        A file's text.

    Returns
    -------
    bool
        Whether :func:`parse_qtx` should read it.

    Examples
    --------
    >>> looks_like_qtx("[STANDARD_DATA 0]\\nSTD_NAME=red\\n"), looks_like_qtx("nm,a\\n400,1\\n")
    (True, False)
    """
    return _SECTION.search(text) is not None


def _sections(text: str, source: str):
    """``(line, kind word, index, {field: (line, value)})`` for each data section."""
    sections = []
    current: dict[str, tuple[int, str]] | None = None
    for line_number, raw in enumerate(text.splitlines(), start=1):
        line = raw.strip()
        if not line or line.startswith(";"):
            continue
        if line.startswith("["):
            match = _HEADER.fullmatch(line)
            current = None
            if match is not None:
                current = {}
                sections.append((line_number, match.group(1).upper(), match.group(2), current))
            continue
        if current is None:
            continue  # fields of other sections ([DESCRIPTOR] …) are not the samples'
        if "=" not in line:
            raise SpectrumError(f"{source}, line {line_number}: {line[:40]!r} is not FIELD=VALUE")
        field, value = line.split("=", 1)
        current[field.strip().upper()] = (line_number, value.strip())
    return sections


def _prefix(fields: dict[str, tuple[int, str]], where: str) -> str | None:
    prefixes = [field[:-2] for field in fields if field.endswith("_R") and len(field) > 2]
    if len(prefixes) > 1:
        raise SpectrumError(f"{where}: several reflectance fields ({', '.join(p + '_R' for p in prefixes[:4])}); "
                            "expected one")
    return prefixes[0] if prefixes else None


def _spectrum(fields, prefix: str, where: str) -> tuple[np.ndarray, np.ndarray]:
    def field(suffix: str) -> tuple[int, str]:
        key = f"{prefix}_{suffix}"
        if key not in fields:
            raise SpectrumError(f"{where}: no {key}= field; expected {EXPECTED}")
        return fields[key]

    line, text = field("R")
    tokens = [t.strip() for t in text.split(",")]
    if tokens and not tokens[-1]:
        tokens.pop()  # a trailing comma
    low = number(field("REFLLOW")[1], f"{where}, line {field('REFLLOW')[0]}, {prefix}_REFLLOW")
    step = number(field("REFLINTERVAL")[1], f"{where}, line {field('REFLINTERVAL')[0]}, {prefix}_REFLINTERVAL")
    if not step > 0:
        raise SpectrumError(f"{where}: {prefix}_REFLINTERVAL must be positive, got {step:g}")
    if f"{prefix}_REFLPOINTS" in fields:
        at, said = field("REFLPOINTS")
        points = number(said, f"{where}, line {at}, {prefix}_REFLPOINTS")
        if points != int(points) or points < 1:
            raise SpectrumError(f"{where}, line {at}: {prefix}_REFLPOINTS must be a whole number ≥ 1, "
                                f"got {said[:40]!r}")
        if int(points) != len(tokens):
            raise SpectrumError(f"{where}, line {at}: {prefix}_REFLPOINTS says {int(points)} but {prefix}_R "
                                f"(line {line}) holds {len(tokens)} values")
    check_bytes(16 * len(tokens), f"{where}: {prefix}_R with {len(tokens)} values")
    values = number_table([tokens], lambda r, k: f"{where}, line {line}, {prefix}_R value {k + 1}")[0]
    return low + step * np.arange(len(tokens)), values


def parse_qtx(text: str, source: str, percent: bool | None = None) -> Spectrum:
    """Spectra from a Datacolor QTX file: every standard and batch, in file order.

    Parameters
    ----------
    text : str
        The file's text.
    source : str
        File name, for messages.
    percent : bool or None, default None
        QTX values are percent, so ``False`` contradicts the file; see :term:`percent`.

    Returns
    -------
    Spectrum
        ``(N, K)`` (``(K,)`` for one sample) reflectances on the 0–1 scale, named from
        ``…_NAME``, with ``metadata`` (``format``, ``value_scale``, ``sample_fields`` with
        ``kind`` and ``standard`` per sample, ``instrument`` where ``…_INST_TYPE`` gives one).

    Raises
    ------
    SpectrumError
        One line: a point count that disagrees with the values, a missing field, a value that
        is not a number, spectra on different grids, or no spectrum at all.

    Examples
    --------
    >>> text = ("[STANDARD_DATA 0]\\nSTD_NAME=Red\\nSTD_REFLLOW=400\\nSTD_REFLINTERVAL=100\\n"
    ...         "STD_REFLPOINTS=3\\nSTD_R=10,20,40\\n[BATCH_DATA 0]\\nBATCH_NAME=Red lot 1\\n"
    ...         "BATCH_REFLLOW=400\\nBATCH_REFLINTERVAL=100\\nBATCH_REFLPOINTS=3\\nBATCH_R=11,21,39\\n")
    >>> s = parse_qtx(text, "dyes.qtx")
    >>> s.names, s.values[0].tolist(), s.metadata["sample_fields"]["standard"]
    (('Red', 'Red lot 1'), [0.1, 0.2, 0.4], ('Red', 'Red'))
    """
    names, kinds, standards, grids, rows, others = [], [], [], [], [], []
    standard = ""
    for line, word, index, fields in _sections(text, source):
        where = f"{source}, [{word}_DATA {index}] (line {line})"
        prefix = _prefix(fields, where)
        if prefix is None:
            continue
        wavelengths, values = _spectrum(fields, prefix, where)
        kind = _KIND[word]
        name = fields.get(f"{prefix}_NAME", (0, ""))[1] or f"{kind} {index}"
        if kind == "standard":
            standard = name
        names.append(name)
        kinds.append(kind)
        standards.append(name if kind == "standard" else fields.get(f"{prefix}_STD_NAME", (0, standard))[1])
        grids.append((where, wavelengths))
        rows.append(values)
        others.append({key[len(prefix) + 1:]: value for key, (_, value) in fields.items()
                       if key.startswith(prefix + "_") and key[len(prefix) + 1:] not in _SPECTRAL})
    if not rows:
        raise SpectrumError(f"{source}: QTX file without spectra (no section has a …_R= field); expected {EXPECTED}")
    first_where, grid = grids[0]
    for where, wavelengths in grids[1:]:
        if wavelengths.shape != grid.shape or not np.allclose(wavelengths, grid, rtol=0, atol=1e-9):
            raise SpectrumError(f"{where}: {wavelengths[0]:g}–{wavelengths[-1]:g} nm in {wavelengths.size} values, "
                                f"but {first_where} has {grid[0]:g}–{grid[-1]:g} nm in {grid.size}; the spectra "
                                "must share one grid")
    values, note = apply_scale(np.array(rows), 100.0, percent, source, "QTX reflectance is in percent")
    sample_fields: dict[str, tuple[str, ...]] = {"kind": tuple(kinds), "standard": tuple(standards)}
    for key in sorted({key for fields in others for key in fields}):
        sample_fields[key] = tuple(fields.get(key, "") for fields in others)
    metadata: dict[str, object] = {"format": "Datacolor QTX", "value_scale": note, "sample_fields": sample_fields}
    instruments = {fields.get("INST_TYPE") for fields in others} - {None, ""}
    if len(instruments) == 1:
        metadata["instrument"] = instruments.pop()
    try:
        return Spectrum(grid, values if len(rows) > 1 else values[0], names, metadata)
    except SpectrumError as exc:
        raise SpectrumError(f"{source}: {exc}") from None
