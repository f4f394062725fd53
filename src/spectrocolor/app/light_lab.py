"""The explorer's light-source lab: a light's colour rendering, every number from the library.

A light is a CIE illuminant, a Planckian radiator or CIE daylight of any temperature, a
mixture of up to four LED-like primaries (Gaussian in wavelength, each with a peak, a full width
at half maximum and a power), a measured SPD from an uploaded file (read by
:func:`spectrocolor.read_spectra`, the explorer's Load reader, in the upload workers:
:func:`read_light_file`), or the explorer's own distribution (levels over 400-700 nm:
:func:`explorer_spd`; the metrics that need 380-780 nm are then not computed, each with the
library's reason). For it the page shows what :mod:`spectrocolor.lighting` computes:
CCT and Duv, CIE 13.3 Ra and R1-R14, CIE 224 / TM-30 Rf and Rg with the 16 hue bins and the colour
vector graphic, the luminous efficacy of radiation and the melanopic daylight efficacy ratio, and
the 14 CIE test-colour samples rendered under the light beside the same samples under the CRI's
reference illuminant (each adapted to the display's white, so the difference is the rendering,
not the white).

Why this file is long: it is the lab's whole server side in one place -- the five kinds of light
the page describes (each checked, with one clear error), the uploaded file's reader, and the
answer for a light over the full range and for one known over part of it -- so that the request
models (``lab_routes``) and the workers call one module.

References
----------
CIE 13.3-1995, CIE 224:2017, ANSI/IES TM-30-20, CIE S 026:2018; see :mod:`spectrocolor.lighting`.
"""

from __future__ import annotations

import csv
from pathlib import Path

import numpy as np

from ..errors import ColorimetryError, SpectrumError
from ..illuminants import resolve_illuminant, temperature_light
from .choices import light_kind_options

WAVELENGTHS_NM = np.arange(380.0, 781.0, 5.0)
MAX_PRIMARIES = 4
#: Longest label of an uploaded light (its file's name and the spectrum's), characters.
MAX_LABEL_CHARS = 200
#: Stands for the uploaded file's name in messages made in a worker (the route puts the name in).
FILE_NAME = "\0light file\0"
TCS_NAMES = ("TCS01 light greyish red", "TCS02 dark greyish yellow", "TCS03 strong yellow green",
             "TCS04 moderate yellowish green", "TCS05 light bluish green", "TCS06 light blue",
             "TCS07 light violet", "TCS08 light reddish purple", "TCS09 strong red", "TCS10 strong yellow",
             "TCS11 strong green", "TCS12 strong blue", "TCS13 light yellowish pink (skin)",
             "TCS14 moderate olive green (leaf)")  # CIE 13.3-1995 Table 1


def led_mixture(peaks_nm, widths_nm, powers) -> np.ndarray:
    """Relative SPD (on :data:`WAVELENGTHS_NM`) of Gaussian primaries (:meth:`Spectrum.gaussian`).

    Parameters
    ----------
    peaks_nm, widths_nm, powers : sequences of 1-4 numbers
        Peak wavelengths (380-780 nm), full widths at half maximum (5-200 nm) and relative peak
        powers (0-1, not all zero).

    Returns
    -------
    numpy.ndarray, shape (K,)
        The mixture, peak 1.

    Examples
    --------
    >>> spd = led_mixture([450, 550, 620], [20, 80, 20], [1.0, 0.6, 0.8])
    >>> float(spd.max()), spd.shape
    (1.0, (81,))
    """
    peaks, widths, powers = (np.asarray(v, dtype=float).reshape(-1) for v in (peaks_nm, widths_nm, powers))
    if not (1 <= peaks.size <= MAX_PRIMARIES and peaks.size == widths.size == powers.size):
        raise ColorimetryError(
            f"leds: give 1-{MAX_PRIMARIES} primaries with a peak, a width and a power each, got "
            f"{peaks.size}, {widths.size} and {powers.size} values"
        )
    if not (np.all((peaks >= 380) & (peaks <= 780)) and np.all((widths >= 5) & (widths <= 200))
            and np.all((powers >= 0) & (powers <= 1)) and powers.sum() > 0):
        raise ColorimetryError("leds: peaks must be 380-780 nm, widths 5-200 nm, powers 0-1 and not all zero")
    from ..spectrum import Spectrum

    primaries = zip(peaks, widths, powers, strict=True)
    spd = np.asarray(sum(Spectrum.gaussian(p, w, WAVELENGTHS_NM, peak=a).values for p, w, a in primaries))
    return spd / spd.max()


def light_spd(source: dict):
    """The light's SPD (peak 1) and its label from the page's description of it.

    ``{"kind": "named", "name": "FL2"}`` (any form of :func:`spectrocolor.canonical_illuminant`
    that names a light: a CIE name, ``"blackbody:T"``, ``"D:T"``), ``{"kind": "temperature",
    "light": "daylight", "temperature_K": 5000}`` (a kind of
    :data:`~spectrocolor.illuminants.LIGHT_KINDS` at a temperature) or ``{"kind": "leds",
    "peaks_nm": […], "widths_nm": […], "powers": […]}``.

    Examples
    --------
    >>> spd, label = light_spd({"kind": "named", "name": "blackbody:2700"})
    >>> label, float(spd.max())
    ('blackbody 2700 K', 1.0)
    >>> light_spd({"kind": "temperature", "light": "daylight", "temperature_K": 5000})[1]
    'CIE daylight 5000 K'
    """
    kind = source.get("kind") if isinstance(source, dict) else None
    if kind in ("named", "temperature"):
        light = (resolve_illuminant(source.get("name"), "name") if kind == "named"
                 else temperature_light(str(source.get("light")), source.get("temperature_K"), "light"))
        if light is None or not light.cacheable:
            raise ColorimetryError("name: the lab takes a named light, e.g. 'FL2', 'blackbody:3000' or 'D:5000'")
        values = light.spd(WAVELENGTHS_NM).values
        return values / values.max(), light.label
    if kind == "spd":
        return measured_spd(source.get("values")), str(source.get("label", "uploaded light"))[:MAX_LABEL_CHARS]
    if kind == "explorer":
        label = str(source.get("label") or "the explorer's distribution")[:MAX_LABEL_CHARS]
        return explorer_spd(source.get("levels"), source.get("step_nm")), label
    if kind == "leds":
        spd = led_mixture(source.get("peaks_nm", ()), source.get("widths_nm", ()), source.get("powers", ()))
        peaks = ", ".join(f"{p:g}" for p in np.asarray(source["peaks_nm"], dtype=float).reshape(-1))
        return spd, f"LED mixture ({peaks} nm)"
    raise ColorimetryError("source: expected {'kind': 'named', 'name': …}, {'kind': 'temperature', 'light': …, "
                           "'temperature_K': …}, {'kind': 'leds', 'peaks_nm': …, …} or {'kind': 'spd', "
                           "'label': …, 'values': […]} or {'kind': 'explorer', 'step_nm': …, 'levels': […]}")


#: The explorer's wavelength range (SPECTRA's 400-700 nm) and its levels' top (the full spectrum).
EXPLORER_RANGE_NM = (400.0, 700.0)
EXPLORER_FULL = 30.0
EXPLORER_STEPS_NM = (1.0, 5.0, 10.0)


def explorer_spd(levels, step_nm) -> np.ndarray:
    """The explorer's distribution on :data:`WAVELENGTHS_NM`: NaN outside 400-700 nm, peak 1.

    The explorer's levels (0-30) cover only 400-700 nm; the lab's grid is 380-780 nm. Inside
    400-700 nm the levels are interpolated linearly onto the 5 nm grid; outside they are NaN: not
    measured, never invented. The metrics that take samples from 380 to 780 nm (CIE 13.3, CIE 224
    / TM-30, photometry, CIE S 026) then give NaN with the library's reason
    (:func:`spectrocolor.lighting.light_report`).

    Parameters
    ----------
    levels : sequence of float
        The explorer's levels at 400, 400 + ``step_nm``, …, 700 nm: finite, 0-30, not all 0.
    step_nm : float
        The explorer's grid step: 1, 5 or 10 nm.

    Returns
    -------
    numpy.ndarray, shape (81,)
        Relative power at 380, 385, …, 780 nm, NaN below 400 and above 700 nm, peak 1.

    Raises
    ------
    ColorimetryError
        For another step, a length other than ``300 / step_nm + 1``, a level outside 0-30 or
        not finite, or levels all 0.

    Examples
    --------
    >>> spd = explorer_spd([30] * 31, 10)  # 380-395 nm and 705-780 nm are not known: 4 + 16 samples
    >>> int(np.isnan(spd).sum()), float(np.nanmax(spd))
    (20, 1.0)
    """
    try:
        step = float(step_nm)
    except (TypeError, ValueError):
        step = float("nan")
    if not any(step == s for s in EXPLORER_STEPS_NM):  # exact: the explorer's steps are whole nm
        raise ColorimetryError(f"step_nm: the explorer's step is 1, 5 or 10 nm, got {str(step_nm)[:20]!r}")
    start, stop = EXPLORER_RANGE_NM
    count = int(round((stop - start) / step)) + 1
    try:
        values = np.asarray(levels, dtype=float)
    except (TypeError, ValueError):
        values = np.empty(0)
    if (values.shape != (count,) or not np.all(np.isfinite(values)) or values.min() < 0
            or values.max() > EXPLORER_FULL or values.max() <= 0):
        raise ColorimetryError(f"levels: give {count} levels (400-700 nm at {step:g} nm), each 0-"
                               f"{EXPLORER_FULL:g}, not all 0")
    grid = np.linspace(start, stop, count)
    inside = (WAVELENGTHS_NM >= start) & (WAVELENGTHS_NM <= stop)
    spd = np.full(WAVELENGTHS_NM.shape, np.nan)
    spd[inside] = np.interp(WAVELENGTHS_NM[inside], grid, values)
    return spd / np.nanmax(spd)


def measured_spd(values) -> np.ndarray:
    """A measured SPD on :data:`WAVELENGTHS_NM` (as :func:`light_from_file` gives it), peak 1.

    Parameters
    ----------
    values : sequence of float, length ``len(WAVELENGTHS_NM)`` (81)
        Relative spectral power at 380, 385, …, 780 nm: finite, not negative, not all zero.

    Returns
    -------
    numpy.ndarray, shape (81,)
        The values scaled to peak 1.

    Raises
    ------
    ColorimetryError
        For another length, a non-finite or negative value, or a light without power.

    Examples
    --------
    >>> spd = measured_spd([2.0] * 81)
    >>> float(spd.min()), float(spd.max())
    (1.0, 1.0)
    """
    try:
        spd = np.asarray(values, dtype=float)
    except (TypeError, ValueError):
        spd = np.empty(0)
    if spd.shape != WAVELENGTHS_NM.shape or not np.all(np.isfinite(spd)) or spd.min() < 0 or spd.max() <= 0:
        raise ColorimetryError(f"values: give {WAVELENGTHS_NM.size} finite, non-negative powers at 380, 385, …, "
                               "780 nm, not all zero")
    return spd / spd.max()


def light_from_file(path, filename: str | None = None, method: str = "linear") -> dict:
    """The light in a measurement file, on :data:`WAVELENGTHS_NM`: what the lab's upload answers.

    The file is read by :func:`spectrocolor.read_spectra` (every format the explorer's Load
    reads: CSV, light-meter exports, spectrometer text, CGATS, TM-27, …). Its first spectrum is
    the light; it must cover 380-780 nm (CIE 224 and TM-30 use those samples; nothing is
    extrapolated) and is resampled there at 5 nm (``method``). Negative samples (a
    spectrometer's dark noise) are set to zero, and the note says how many.

    Parameters
    ----------
    path : str or pathlib.Path
        The file.
    filename : str, optional
        The name shown in the label (default: the path's name).
    method : str, default "linear"
        Interpolation onto the lab's grid (:meth:`spectrocolor.Spectrum.resample`).

    Returns
    -------
    dict
        ``label`` (file name and spectrum name), ``spd`` (81 values, peak 1, 6 decimals) and
        ``note`` (what was read and how it was resampled).

    Raises
    ------
    SpectrumError
        A file that cannot be read, that does not cover 380-780 nm or has no power there.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> folder = pathlib.Path(tempfile.mkdtemp())
    >>> rows = "\\n".join(f"{w},{1 + w / 1000}" for w in range(360, 831, 10))
    >>> _ = (folder / "lamp.csv").write_text("wavelength_nm,lamp\\n" + rows + "\\n")
    >>> light = light_from_file(folder / "lamp.csv")
    >>> light["label"], len(light["spd"]), light["spd"][-1]
    ('lamp.csv — lamp', 81, 1.0)
    """
    from ..io import read_spectra

    path = Path(path)
    name = filename or path.name
    s = read_spectra(path)
    values = np.asarray(s.values, dtype=float)
    count = 1 if values.ndim == 1 else int(np.prod(values.shape[:-1]))
    lo, hi = float(s.wavelengths_nm[0]), float(s.wavelengths_nm[-1])
    if lo > WAVELENGTHS_NM[0] or hi < WAVELENGTHS_NM[-1]:
        raise SpectrumError(f"{name}: covers {lo:g}-{hi:g} nm; the light lab needs 380-780 nm (CIE 224 and "
                            "TM-30 use those samples) and never extrapolates")
    first = s.resample(WAVELENGTHS_NM, method).values.reshape(-1, WAVELENGTHS_NM.size)[0]
    if not np.all(np.isfinite(first)):
        raise SpectrumError(f"{name}: its values are not all finite numbers")
    negative = int(np.count_nonzero(first < 0))
    first = np.clip(first, 0.0, None)
    if first.max() <= 0:
        raise SpectrumError(f"{name}: its light has no power in 380-780 nm")
    spectrum = s.names[0] if s.names else ""
    label = (f"{name} — {spectrum}" if spectrum and spectrum != name else name)[:MAX_LABEL_CHARS]
    said = [f"read {count} spectr{'um' if count == 1 else 'a'} on {lo:g}-{hi:g} nm"
            + (" and took the first" if count > 1 else ""),
            f"resampled to 380-780 nm at 5 nm by {method} interpolation, scaled to peak 1"]
    if negative:
        said.append(f"{negative} negative sample{'s' if negative > 1 else ''} (noise) set to 0")
    return {"label": label, "spd": np.round(first / first.max(), 6).tolist(), "note": "; ".join(said)}


def read_light_file(folder: str, content: str | bytes, suffix: str) -> dict:
    """Upload-worker side: write the file into the server's temporary ``folder`` and read its light.

    Bytes are written as they came, so the reader decodes them as it decodes any file; text as
    UTF-8. Whatever a hostile file makes a reader raise becomes one :class:`~spectrocolor.errors.SpectrumError`
    naming :data:`FILE_NAME` (the route puts the user's file name in), never a traceback.

    Examples
    --------
    >>> import tempfile
    >>> folder = tempfile.mkdtemp()
    >>> try:
    ...     read_light_file(folder, "wavelength_nm,x\\n400,1\\n500,2\\n", ".csv")
    ... except SpectrumError as exc:
    ...     print(str(exc).replace(FILE_NAME, "lamp.csv")[:42])
    lamp.csv: covers 400-500 nm; the light lab
    """
    path = Path(folder) / f"upload{suffix}"
    if isinstance(content, bytes):
        path.write_bytes(content)
    else:
        path.write_text(content, encoding="utf-8")
    try:
        return light_from_file(path, FILE_NAME)
    except (ValueError, csv.Error, RecursionError, UnicodeError, MemoryError) as exc:
        # as the explorer's Load (spectrocolor.app.uploads): the file's fault, one line, never a 500
        message = (str(exc) or exc.__class__.__name__).replace(str(path), FILE_NAME)
        message = (message.splitlines() or [exc.__class__.__name__])[0][:300]
        if isinstance(exc, MemoryError):
            message = f"{FILE_NAME}: too large to read in the memory available"
        elif not message.startswith(FILE_NAME):
            message = f"{FILE_NAME}: cannot be read as a light ({message})"
        raise SpectrumError(message) from None


def _samples_rgb8(spd: np.ndarray, display: str) -> tuple[np.ndarray | None, str]:
    """The 14 TCS under ``spd`` on ``display`` as 8-bit codes, and how they were adapted.

    They are adapted (Bradford) from the light's white to the display's. A nearly
    monochromatic light has a white that Bradford's sensors cannot see positively (a single
    LED: one sensor response is zero or negative); its samples are then shown unadapted, and
    the note says so. A light without luminance gives ``None``.
    """
    from ..colorimetry import weights
    from ..display.adaptation import adapt
    from ..display.render import render
    from ..display.spaces import rgb_space
    from ..lighting.spectra import tcs_reflectances
    from ..spectrum import Spectrum

    try:
        W = weights(WAVELENGTHS_NM, illuminant=Spectrum(WAVELENGTHS_NM, spd))
    except ColorimetryError:
        return None, "not shown: the light has no luminance over 380-780 nm"
    XYZ = tcs_reflectances(WAVELENGTHS_NM) @ W
    space = rgb_space(display)
    try:
        adapted, note = adapt(XYZ, W.sum(axis=0), space.white_XYZ), "adapted to the display's white (Bradford)"
    except ColorimetryError:
        adapted, note = XYZ, ("not adapted: the light's white is too saturated for chromatic "
                              "adaptation (Bradford's sensors do not all see it)")
    codes = render(adapted, space, gamut="desaturate").codes
    return codes, note


def light_lab(source: dict, display: str = "sRGB") -> dict:
    """Everything the light-source lab shows for one light, as JSON-ready values.

    Parameters
    ----------
    source : dict
        See :func:`light_spd`.
    display : str
        A built-in RGB space for the sample swatches.

    Returns
    -------
    dict
        ``label``, ``wavelengths_nm``, ``spd`` (peak 1); ``summary`` (CCT K, Duv, Ra, R9, Rf, Rg,
        LER lm/W, melanopic DER; NaN → None); ``Ri`` (R1-R14); ``hue_bins`` (Rf,hj, Rcs,hj,
        Rhs,hj); ``graphic`` (unit reference circle and test corners of the vector graphic, 16 × 2
        each, or None with the reason in ``graphic_note``) and ``bin_rgb8``; ``samples`` (names,
        rgb8 under the light and under the reference, each None where it cannot be shown, with
        ``under_light_note`` and ``under_reference_note`` saying how they were adapted or why
        they are missing). Every number is finite: what has no value is None.

    Examples
    --------
    >>> lab = light_lab({"kind": "named", "name": "FL2"})   # a cool-white halophosphate lamp
    >>> round(lab["summary"]["Ra"], 1), round(lab["summary"]["Rf"], 1)
    (64.2, 70.1)
    >>> lab["samples"]["under_light"] == lab["samples"]["under_reference"]   # it renders colours differently
    False
    """
    spd, label = light_spd(source)
    return light_lab_of(spd, label, display)


def light_lab_of(spd, label: str, display: str = "sRGB") -> dict:
    """:func:`light_lab` of a light given by its SPD on :data:`WAVELENGTHS_NM` (peak 1) and label.

    The server resolves the light (:func:`light_spd`) in its own process, where every registered
    light kind is known, and has a worker compute this.

    Parameters
    ----------
    spd : array_like, shape (K,)
        Relative SPD on :data:`WAVELENGTHS_NM`.
    label : str
        The light's name as shown.
    display : str
        A built-in RGB space for the sample swatches.

    Returns
    -------
    dict
        As :func:`light_lab`.

    Examples
    --------
    >>> spd, label = light_spd({"kind": "named", "name": "A"})
    >>> round(light_lab_of(spd, label)["summary"]["Ra"], 1)
    100.0
    """
    from ..lighting import colour_fidelity, colour_rendering_index, summary
    from ..lighting.reference import cri_reference
    from ..lighting.vector_graphic import bin_colours_rgb8, normalised_graphic
    from ..spectrum import Spectrum

    spd = np.asarray(spd, dtype=float)
    if not np.all(np.isfinite(spd)):
        return _part_measured(spd, label)
    light = Spectrum(WAVELENGTHS_NM, spd)
    headline = summary(light)
    cri = colour_rendering_index(light)
    fidelity = colour_fidelity(light)

    def plain(values):
        return [None if not np.isfinite(v) else round(float(v), 4) for v in np.asarray(values).reshape(-1)]

    reference_spd = np.asarray(cri_reference(float(cri.cct_K), WAVELENGTHS_NM)) if np.isfinite(cri.cct_K) else None
    circle, test = normalised_graphic(fidelity) if np.isfinite(fidelity.Rf) else (None, None)
    graphic_note = "" if circle is not None else "no colour vector graphic: Rf is not defined for this light"
    if circle is not None and test is not None and not (np.all(np.isfinite(circle)) and np.all(np.isfinite(test))):
        empty = [j + 1 for j in range(len(circle)) if not np.all(np.isfinite([*circle[j], *test[j]]))]
        circle = test = None
        graphic_note = (f"no colour vector graphic: hue bin(s) {', '.join(map(str, empty))} hold no "
                        "sample that this light shows with a hue")
    under_light, light_note = _samples_rgb8(spd, display)
    if reference_spd is None:
        under_reference, reference_note = None, "not shown: the light has no correlated colour temperature"
    else:
        under_reference, reference_note = _samples_rgb8(reference_spd, display)
    return {
        "label": label,
        "wavelengths_nm": WAVELENGTHS_NM.tolist(),
        "spd": np.round(spd, 6).tolist(),
        "summary": {k: (v if isinstance(v, bool) else (None if not np.isfinite(v) else round(v, 4)))
                    for k, v in headline.items()},
        "Ri": plain(cri.Ri),
        "hue_bins": {"Rf_h": plain(fidelity.Rf_h), "Rcs_h": plain(fidelity.Rcs_h), "Rhs_h": plain(fidelity.Rhs_h)},
        "graphic": None if circle is None or test is None else {"reference": np.round(circle, 5).tolist(),
                                                "test": np.round(test, 5).tolist()},
        "graphic_note": graphic_note,
        "bin_rgb8": bin_colours_rgb8().tolist(),
        "samples": {
            "names": list(TCS_NAMES),
            "under_light": None if under_light is None else under_light.tolist(),
            "under_reference": None if under_reference is None else under_reference.tolist(),
            "under_light_note": light_note,
            "under_reference_note": reference_note,
        },
    }


def _part_measured(spd: np.ndarray, label: str) -> dict:
    """:func:`light_lab_of` of a light known over part of 380-780 nm (NaN elsewhere): every metric
    the library refuses is None, and ``reasons`` says, per group of numbers, why (the library's
    own words: :func:`spectrocolor.lighting.light_report` of the light as a batch of one)."""
    from ..lighting.summary import light_report
    from ..spectrum import Spectrum

    report = light_report(Spectrum(WAVELENGTHS_NM, spd[None, :]))
    headline = {key: float(column[0]) for key, column in report.headline().items()}
    nothing = [None] * 16
    known = np.flatnonzero(np.isfinite(spd))
    span = [float(WAVELENGTHS_NM[known[0]]), float(WAVELENGTHS_NM[known[-1]])]
    groups = [("Ra, R9, R1-R14 (CIE 13.3)", report.cri.reason[0]),
              ("CCT, Duv, Rf, Rg, hue bins (CIE 224 / TM-30)", report.fidelity.reason[0]),
              ("LER (photometry)", report.ler_reason[0]),
              ("melanopic DER (CIE S 026)", report.alpha_opic.reason[0])]
    samples_note = (f"not shown: the light is known over {span[0]:g}-{span[1]:g} nm only; the samples' colours "
                    "take 380-780 nm")
    return {
        "label": label,
        "wavelengths_nm": WAVELENGTHS_NM.tolist(),
        "spd": [None if not np.isfinite(v) else round(float(v), 6) for v in spd],
        "range_nm": span,
        "reasons": [{"metrics": metrics, "reason": str(reason)} for metrics, reason in groups if reason],
        "summary": {**{k: (None if not np.isfinite(v) else round(v, 4)) for k, v in headline.items()},
                    "cri_meaningful": bool(report.cri.meaningful[0])},
        "Ri": [None if not np.isfinite(v) else round(float(v), 4) for v in np.asarray(report.cri.Ri).reshape(-1)],
        "hue_bins": {"Rf_h": nothing, "Rcs_h": nothing, "Rhs_h": nothing},
        "graphic": None,
        "graphic_note": "no colour vector graphic: Rf is not defined for this light",
        "bin_rgb8": _bin_rgb8(),
        "samples": {"names": list(TCS_NAMES), "under_light": None, "under_reference": None,
                    "under_light_note": samples_note, "under_reference_note": samples_note},
    }


def _bin_rgb8() -> list:
    from ..lighting.vector_graphic import bin_colours_rgb8

    return bin_colours_rgb8().tolist()


def light_lab_options() -> dict:
    """The named lights, the kinds of light by temperature and the displays the lab offers (from
    the registries, read at every call).

    Examples
    --------
    >>> options = light_lab_options()
    >>> options["lights"][:3], [k["name"] for k in options["light_kinds"]][:2]
    (['A', 'B', 'C'], ['blackbody', 'daylight'])
    """
    from ..display.spaces import RGB_SPACES
    from ..illuminants import ILLUMINANTS

    return {"lights": [n for n in ILLUMINANTS.names() if n != "E"], "light_kinds": light_kind_options(),
            "displays": RGB_SPACES.names(), "max_primaries": MAX_PRIMARIES}
