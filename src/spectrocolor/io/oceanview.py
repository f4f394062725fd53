"""Ocean Optics OceanView and SpectraSuite text exports: spectra at the spectrometer's own pixel wavelengths.

What the software writes ("Save … Tab-delimited" in OceanView; SpectraSuite's "Tab Delimited"
text), as Ocean Optics' manuals and the files describe it: a header of ``Key: value`` lines, then
a marker line, then one ``wavelength<TAB>value`` row per detector pixel::

    Data from AbsoluteIrradiance_11-17-02-611.txt Node      (OceanView; the node that made it)
    Date: Mon Aug 07 11:17:02 CDT 2017
    User: lab
    Spectrometer: FLMS04381
    Integration Time (sec): 7.712000E-2
    Scans to average: 5
    Boxcar width: 0
    XAxis mode: Wavelengths
    Number of Pixels in Spectrum: 2048
    (the marker line) >>>>>Begin Spectral Data<<<<<
    178.179	556.52
    …

SpectraSuite's older layout starts ``SpectraSuite Data File``, says ``Integration Time (usec)``,
``Spectra Averaged``, ``Number of Pixels in Processed Spectrum`` and brackets the rows with
``>>>>>Begin Processed Spectral Data<<<<<`` / ``>>>>>End Processed Spectral Data<<<<<``.

**The grid is the spectrometer's.** Pixel wavelengths come from the instrument's calibration
polynomial: irregular steps (e.g. 0.38 → 0.33 nm across a Flame), kept exactly as written.
``metadata["grid"]`` says so; colorimetry and photometry integrate an irregular grid with
trapezoidal weights (:func:`spectrocolor.sampling.interval_weights_nm`), while CRI and TM-30
need a uniform 1 or 5 nm grid and say so. To get one, read with ``resample_nm=1`` (linear
interpolation within the measured range, recorded in ``metadata["resampled"]``;
:func:`resampled`) or call ``spectrum.resample(...)`` yourself.

**What the values are.** OceanView does not write a unit; the node name on the first line says
what was saved: ``AbsoluteIrradiance`` (spectral irradiance, µW·cm⁻²·nm⁻¹, OceanView's unit for
it), ``Transmission``/``Reflection`` (percent: divided by 100 as that declares), ``Absorbance``
(absorbance units), anything else (``Scope``, ``Relative``, …) counts or relative values, kept as
written. ``metadata["quantity"]`` and ``["unit"]`` say which.

Checked before anything is allocated: the header's pixel count against the file's length (a
row takes at least 4 characters) and the memory budget (:mod:`spectrocolor.budget`); after
reading, the rows must number exactly what the header claims.

References
----------
The layout as public material shows it (read, not copied): the OceanView Flame export among
colour-science's test resources, and Ocean Optics' OceanView and SpectraSuite manuals' account
of tab-delimited saving and processing nodes (absolute irradiance in µW·cm⁻²·nm⁻¹).
"""

from __future__ import annotations

import math
import re
from array import array

import numpy as np

from ..budget import check_bytes, claimed_bytes
from ..errors import SpectrumError
from ..spectrum import Spectrum, wavelength_grid
from .text import apply_scale, number, plain_ascii_numbers

#: Most wavelengths ``resample_nm`` may make (0.001 nm over 200–1100 nm is 900 001).
MAX_RESAMPLED = 1_000_000
#: What an OceanView/SpectraSuite export holds, for messages.
EXPECTED = "'Key: value' header lines, '>>>>>Begin Spectral Data<<<<<', then wavelength<TAB>value rows"

_BEGIN = re.compile(r">>>>>\s*Begin (?P<processed>Processed )?Spectral Data\s*<<<<<")
_END = re.compile(r">>>>>\s*End (?:Processed )?Spectral Data\s*<<<<<")
#: How far into the text the marker is looked for (headers are a few hundred bytes).
_HEAD = 65536
#: Node names on the first line ("Data from <name> Node"), what they hold and the scale declared.
_NODES = (
    ("absoluteirradiance", "spectral irradiance", "µW·cm⁻²·nm⁻¹ (OceanView's unit for absolute irradiance)", None),
    ("transmission", "transmittance", "fraction (the file's percent divided by 100)", 100.0),
    ("reflection", "reflectance", "fraction (the file's percent divided by 100)", 100.0),
    ("reflectance", "reflectance", "fraction (the file's percent divided by 100)", 100.0),
    ("absorbance", "absorbance", "absorbance units", None),
    ("relativeirradiance", "relative spectral irradiance", "relative (as written)", None),
)


def looks_like_oceanview(text: str) -> bool:
    """True if the text holds the OceanView/SpectraSuite data marker in its first 64 KiB.

    Parameters
    ----------
    text : str
        A file's text.

    Returns
    -------
    bool
        Whether ``>>>>>Begin Spectral Data<<<<<`` (or ``… Processed …``) appears near the top.

    Examples
    --------
    >>> looks_like_oceanview("Date: x\\n>>>>>Begin Spectral Data<<<<<\\n400\\t1\\n")
    True
    """
    return ">>>>>" in text[:_HEAD] and _BEGIN.search(text[:_HEAD]) is not None


def _lines(text: str, start: int = 0):
    """``(line number offset, line)`` from ``start`` on, lazily (``\\n`` or ``\\r\\n`` ends)."""
    end, count = len(text), 0
    while start < end:
        stop = text.find("\n", start)
        stop = end if stop < 0 else stop
        yield count, text[start:stop].removesuffix("\r")
        count += 1
        start = stop + 1


def _fail(source: str, what: str, line: int | None, message: str) -> SpectrumError:
    where = f"line {line}: " if line is not None else ""
    return SpectrumError(f"{source}: this is an Ocean Optics {what} export; {where}{message}")


def parse_oceanview(text: str, source: str, percent: bool | None = None) -> Spectrum:
    """One spectrum from an OceanView or SpectraSuite text export (see the module docstring).

    Parameters
    ----------
    text : str
        The file's text.
    source : str
        File name, for messages.
    percent : bool or None, default None
        Transmission/Reflection exports declare percent, other exports nothing; see :term:`percent`.

    Returns
    -------
    Spectrum
        Shape ``(K,)`` at the file's pixel wavelengths, named after the spectrometer, with
        ``metadata``: ``format``, ``instrument``, ``quantity``, ``unit``, ``grid`` (irregular or
        not, and how to resample), ``pixels``, ``integration_time_s``, ``scans_to_average``,
        ``boxcar_width``, ``date``, ``node`` and every header line in ``keywords``.

    Raises
    ------
    SpectrumError
        One line, "this is an Ocean Optics OceanView export; line N: …", for a header that
        claims a pixel count the file cannot hold or the memory budget refuses, an x axis that
        is not wavelengths, a row that is not two numbers, wavelengths that do not increase, or
        a row count other than the header's.

    Examples
    --------
    >>> s = parse_oceanview("XAxis mode: Wavelengths\\nNumber of Pixels in Spectrum: 3\\n"
    ...                     ">>>>>Begin Spectral Data<<<<<\\n400.12\\t10\\n400.51\\t12\\n400.88\\t11\\n", "a.txt")
    >>> s.wavelengths_nm.tolist(), s.values.tolist(), s.metadata["grid"].split(":")[0]
    ([400.12, 400.51, 400.88], [10.0, 12.0, 11.0], 'irregular')
    """
    head = text[:_HEAD]
    marker = _BEGIN.search(head)
    if marker is None:
        raise SpectrumError(f"{source}: not an OceanView export; expected {EXPECTED}")
    what = "SpectraSuite" if marker["processed"] or "SpectraSuite" in head[: marker.start()] else "OceanView"
    keywords: dict[str, str] = {}
    header_lines = head[: marker.start()].splitlines()  # at most 64 KiB
    for line in header_lines:
        key, colon, value = line.partition(":")
        if colon and key.strip():
            keywords.setdefault(key.strip(), value.strip())
    first = header_lines[0].strip() if header_lines else ""
    node = re.fullmatch(r"Data from (.*) Node", first)
    metadata: dict = {"format": f"Ocean Optics {what} text export", "keywords": keywords}
    if node:
        metadata["node"] = node[1]
    axis = keywords.get("XAxis mode")
    if axis is not None and axis.strip().lower() not in ("wavelengths", "wavelength", "nanometers", "nm"):
        raise _fail(source, what, None, f"its x axis is {axis[:40]!r} (XAxis mode), not wavelengths; save the "
                    "spectrum again with the x axis in wavelengths (nm)")
    claimed = _claimed_pixels(keywords, text, source, what)
    first_row = head.count("\n", 0, marker.end()) + 2
    start = text.find("\n", marker.end())
    wavelengths, values, rows = array("d"), array("d"), 0
    for offset, line in _lines(text, len(text) if start < 0 else start + 1):
        stripped = line.strip()
        if not stripped:
            continue
        if stripped.startswith(">>>>>"):
            if _END.fullmatch(stripped):
                break
            raise _fail(source, what, first_row + offset, f"{stripped[:40]!r} is not a data row")
        if claimed is not None and rows >= claimed:
            raise _fail(source, what, first_row + offset, f"more rows than the {claimed} pixels the header "
                        "claims (Number of Pixels …)")
        nm, reading = _row(stripped, source, what, first_row + offset)
        wavelengths.append(nm)
        values.append(reading)
        rows += 1
    if rows == 0:
        raise _fail(source, what, None, "no data rows after the Begin Spectral Data line")
    if claimed is not None and rows != claimed:
        raise _fail(source, what, None, f"the header claims {claimed} pixels (Number of Pixels …) but the "
                    f"data hold {rows} rows; the file is cut short or was edited")
    grid, data = np.frombuffer(wavelengths, dtype=float), np.frombuffer(values, dtype=float)
    steps = np.diff(grid)
    if np.any(steps <= 0):
        bad = int(np.argmax(steps <= 0))
        raise _fail(source, what, first_row, f"pixel wavelengths must increase; row {bad + 2} "
                    f"({grid[bad + 1]:g} nm) follows {grid[bad]:g} nm")
    metadata.update(_quantity(metadata.get("node", ""), data, percent, source, what))
    data = metadata.pop("_values")
    metadata.update(_facts(keywords, rows, grid))
    instrument = keywords.get("Spectrometer") or keywords.get("Spectrometers") or ""
    if instrument:
        metadata["instrument"] = f"Ocean Optics {instrument}"
    try:
        return Spectrum(grid, data, [instrument or metadata.get("node") or "spectrum"], metadata)
    except SpectrumError as exc:
        raise _fail(source, what, None, str(exc)) from None


def _claimed_pixels(keywords: dict, text: str, source: str, what: str) -> int | None:
    """The header's pixel count, checked against the file's length and the memory budget."""
    key = next((k for k in keywords if k.startswith("Number of Pixels")), None)
    if key is None:
        return None
    claim = keywords[key]
    if not re.fullmatch(r"[0-9]{1,12}", claim):
        raise _fail(source, what, None, f"{key}: {claim[:40]!r} is not a whole number of pixels")
    pixels = int(claim)
    if pixels > len(text) // 4 + 1:  # a row is at least 'd<TAB>d' and a line end
        raise _fail(source, what, None, f"{key}: {pixels} pixels, but the file ({len(text)} characters) can hold "
                    f"at most {len(text) // 4 + 1} rows")
    check_bytes(claimed_bytes((pixels, 4), 8, "pixels"), f"{source}: {key} {pixels}")
    return pixels


def _row(line: str, source: str, what: str, line_number: int) -> tuple[float, float]:
    cells = line.split("\t") if "\t" in line else line.split()
    cells = [cell.strip() for cell in cells if cell.strip()]
    if len(cells) != 2:
        raise _fail(source, what, line_number, f"{len(cells)} cells; each data row is a wavelength and a value "
                    "separated by a tab")
    decimal_comma = "," in line and "." not in line  # a German/French Windows export: 400,12<TAB>1,5
    if not decimal_comma and plain_ascii_numbers(cells):
        try:
            nm, value = float(cells[0]), float(cells[1])
            if math.isfinite(nm) and math.isfinite(value):
                return nm, value
        except ValueError:
            pass
    where = f"{source}: this is an Ocean Optics {what} export; line {line_number}"
    return number(cells[0], where + ", wavelength", decimal_comma), number(cells[1], where, decimal_comma)


def _quantity(node: str, values: np.ndarray, percent: bool | None, source: str, what: str) -> dict:
    key = re.sub(r"[^a-z]", "", node.lower())
    for name, quantity, unit, declared in _NODES:
        if name in key:
            if declared is not None:
                scaled, note = apply_scale(values, declared, percent, source, f"{what} {node!r} node: percent")
                return {"quantity": quantity, "unit": unit, "value_scale": note, "_values": scaled}
            scaled, note = _as_written(values, percent, source, quantity)
            return {"quantity": quantity, "unit": unit, "value_scale": note, "_values": scaled}
    scaled, note = _as_written(values, percent, source, "counts or processed values")
    return {"quantity": "counts or processed values (the export does not say which)",
            "unit": "as written (the export states no unit)", "value_scale": note, "_values": scaled}


def _as_written(values: np.ndarray, percent: bool | None, source: str, quantity: str):
    if percent:
        raise SpectrumError(f"percent: {source} holds {quantity}, not a percentage; leave percent unset")
    return values, "as written"


def _facts(keywords: dict, rows: int, grid: np.ndarray) -> dict:
    facts: dict = {"pixels": rows, "grid": grid_note(grid)}
    for key, scale in (("Integration Time (sec)", 1.0), ("Integration Time (usec)", 1e-6)):
        value = keywords.get(key, "").split(" ")[0]
        if re.fullmatch(r"[0-9.eE+-]{1,30}", value or "-"):
            try:
                facts["integration_time_s"] = float(value) * scale
            except ValueError:
                pass
    for key, name in (("Scans to average", "scans_to_average"), ("Spectra Averaged", "scans_to_average"),
                      ("Boxcar width", "boxcar_width"), ("Boxcar Smoothing", "boxcar_width")):
        value = keywords.get(key, "").split(" ")[0]
        if re.fullmatch(r"[0-9]{1,9}", value):
            facts[name] = int(value)
    if "Date" in keywords:
        facts["date"] = keywords["Date"]
    return facts


def grid_note(grid: np.ndarray) -> str:
    """What ``metadata["grid"]`` says about a wavelength grid: uniform, or irregular and how to resample.

    Parameters
    ----------
    grid : numpy.ndarray
        Strictly increasing wavelengths, nm.

    Returns
    -------
    str
        ``"uniform: …"`` or ``"irregular: …"`` with the range, steps and what to do.

    Examples
    --------
    >>> import numpy as np
    >>> grid_note(np.array([400.0, 401.0, 402.0]))
    'uniform: 3 samples, 400–402 nm at 1 nm'
    """
    steps = np.diff(grid)
    if steps.size and np.allclose(steps, steps[0], rtol=1e-9, atol=0):
        return f"uniform: {grid.size} samples, {grid[0]:g}–{grid[-1]:g} nm at {steps[0]:g} nm"
    low, high = (float(steps.min()), float(steps.max())) if steps.size else (0.0, 0.0)
    return (f"irregular: {grid.size} pixel wavelengths {grid[0]:g}–{grid[-1]:g} nm, steps {low:.3g}–{high:.3g} nm, "
            "kept as the spectrometer reported them; XYZ and photometry integrate them with trapezoidal "
            "weights; CRI and TM-30 need a uniform 1 or 5 nm grid: read with resample_nm=1, or call "
            "spectrum.resample(wavelength_grid(380, 780, 1))")


def resampled(spectrum: Spectrum, step_nm, source: str) -> Spectrum:
    """``spectrum`` interpolated linearly onto a uniform ``step_nm`` grid inside its range, saying so.

    The grid runs from the first multiple of ``step_nm`` at or above the first wavelength to the
    last at or below the last one (never extrapolated); ``metadata["resampled"]`` records what
    was done and ``["grid"]`` describes the new grid.

    Parameters
    ----------
    spectrum : Spectrum
        Spectra on any grid (an OceanView export's pixel wavelengths, typically).
    step_nm : float
        The uniform step, nm (positive, e.g. 1 or 5).
    source : str
        File name, for messages.

    Returns
    -------
    Spectrum
        Values on the uniform grid, names kept, metadata extended.

    Raises
    ------
    SpectrumError
        For a step that is not a positive finite number, a grid beyond the sample limit or the
        memory budget, or a range that holds fewer than two grid points.

    Examples
    --------
    >>> s = Spectrum([400.3, 400.9, 401.6, 402.2], [1.0, 2.0, 3.0, 4.0])
    >>> r = resampled(s, 1, "a.txt")
    >>> r.wavelengths_nm.tolist(), r.metadata["resampled"].split(";")[0]
    ([401.0, 402.0], 'interpolated linearly from 4 wavelengths (400.3–402.2 nm) onto a uniform 1 nm grid, 401–402 nm')
    """
    if isinstance(step_nm, bool) or not isinstance(step_nm, (int, float, np.integer, np.floating)) \
            or not math.isfinite(step_nm) or step_nm <= 0:
        raise SpectrumError(f"resample_nm: expected a positive step in nm such as 1 or 5, got {step_nm!r:.40}")
    step = float(step_nm)
    grid = spectrum.wavelengths_nm
    if float(grid[-1] - grid[0]) > MAX_RESAMPLED * step:
        raise SpectrumError(f"resample_nm: {step:g} nm over {grid[0]:g}–{grid[-1]:g} nm makes more than "
                            f"{MAX_RESAMPLED} wavelengths; choose a larger step such as 1 or 5")
    start, stop = math.ceil(grid[0] / step - 1e-9) * step, math.floor(grid[-1] / step + 1e-9) * step
    count = (stop - start) / step + 1 if stop >= start else 0
    if count < 2:
        raise SpectrumError(f"resample_nm: {source} spans {grid[0]:g}–{grid[-1]:g} nm, which holds fewer than two "
                            f"points of a {step:g} nm grid; choose a smaller step")
    rows = int(np.prod(spectrum.batch_shape, dtype=np.int64)) if spectrum.batch_shape else 1
    check_bytes(claimed_bytes((rows, int(count) + 1), 8 * 3, "resampled grid"),
                f"resample_nm={step:g}: {rows} spectra × {int(count)} wavelengths")
    target = wavelength_grid(start, stop, step)
    result = spectrum.resample(target, "linear")
    metadata = dict(result.metadata)
    metadata["resampled"] = (f"interpolated linearly from {grid.size} wavelengths ({grid[0]:g}–{grid[-1]:g} nm) "
                             f"onto a uniform {step:g} nm grid, {start:g}–{stop:g} nm; resample_nm={step:g} asked "
                             "for it")
    metadata["grid"] = grid_note(target)
    return Spectrum(target, result.values, result.names, metadata)
