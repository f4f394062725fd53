"""What a measurement file declares about how its spectra are to be seen, and the one rule for using it.

Instrument software writes the illuminant and observer it computed its own colorimetry under
into the file; a colour computed from the same spectra without naming conditions should use
them, and a colour computed under other conditions should say so.

Declarations read (CGATS.17 / ISO 28178 keywords; the readers call :func:`parse_declaration`):

* ``MEASUREMENT_SOURCE "Illumination=D50 ObserverAngle=2° WhiteBase=Abs Filter=No"`` (X-Rite
  ColorPort and i1Profiler exports);
* ``WEIGHTING_FUNCTION "ILLUMINANT, D50"`` and ``WEIGHTING_FUNCTION "OBSERVER, 2 degree"``
  (CGATS.17's keyword, as in ECI2002/FOGRA characterisation data);
* ``ILLUMINANT``/``ILLUMINATION_NAME`` and ``OBSERVER`` keywords (``"D65"``, ``"10"``, ``"10°"``,
  ``"CIE 1964"``);
* ``MEASUREMENT_GEOMETRY``/``GEOMETRY`` (``"0/45"``, ``"d/8"``), and TM-27's
  ``ReflectionGeometry``/``TransmissionGeometry``.

They land in ``Spectrum.metadata`` as ``declared_illuminant`` (a canonical illuminant name such
as ``"D50"``), ``declared_observer`` (``"CIE 1931 2°"``/``"CIE 1964 10°"``), ``declared_geometry``
(the text) and ``declared_by`` (the keywords that said so). :func:`declared_conditions` reads them
back; :func:`choose_conditions` applies the rule: ``"declared"`` (or nothing named) uses what the
file declares, else the library's defaults (D65, CIE 1931 2°); a condition the caller names is
used as asked, and where it differs from the declaration a one-line note says so ("the file
declares D50/2°; computed under D65/10° as asked"). :func:`check_reflectance_scale` is the
percent-or-fraction rule for values used as reflectance factors.

References
----------
ANSI CGATS.17-2009 / ISO 28178:2009 (keywords ``MEASUREMENT_SOURCE``, ``WEIGHTING_FUNCTION``,
``MEASUREMENT_GEOMETRY``); ISO 13655:2017 (measurement conditions and the D50/2° convention of
graphic arts); ANSI/IES TM-27-20 (``ReflectionGeometry``).
"""

from __future__ import annotations

import re
import warnings
from dataclasses import dataclass

import numpy as np

from ..errors import SpectrumError

__all__ = ["DeclaredConditions", "declared_conditions", "choose_conditions", "parse_declaration",
           "check_reflectance_scale", "DECLARED", "PERCENT_SUSPICION"]

#: The value of ``illuminant``/``observer`` that means "what the spectra's file declares".
DECLARED = "declared"
#: Reflectance factors above this are almost surely percentages (the CLI's rule, and the API's).
PERCENT_SUSPICION = 1.5
#: Defaults where nothing is declared (the library's :data:`~spectrocolor.DEFAULT_ILLUMINANT`,
#: :data:`~spectrocolor.DEFAULT_OBSERVER`).
_DEFAULT_ILLUMINANT, _DEFAULT_OBSERVER = "D65", "CIE 1931 2°"

_ILLUMINATION = re.compile(r"\bIllumination\s*=\s*([^\s,;]+)", re.IGNORECASE)
_OBSERVER_ANGLE = re.compile(r"\bObserver(?:Angle)?\s*=\s*(\d{1,2})", re.IGNORECASE)
#: An observer as written: ``2``, ``10°``, ``2 degree``, ``10deg``, ``CIE 1964``, ``1931``.
_OBSERVER_TEXT = re.compile(r"\b(1931|1964)\b|(?<![\d.])(2|10)\s*(?:°|º|deg(?:ree)?s?\b|$)", re.IGNORECASE)
_GEOMETRY_KEYS = ("MEASUREMENT_GEOMETRY", "GEOMETRY")
_ILLUMINANT_KEYS = ("ILLUMINANT", "ILLUMINATION_NAME", "ILLUMINATION")


def _observer_name(text: str) -> str | None:
    found = _OBSERVER_TEXT.search(text.strip())
    if found is None:
        return None
    year, angle = found.groups()
    return "CIE 1931 2°" if (year == "1931" or angle == "2") else "CIE 1964 10°"


def _illuminant_name(text: str) -> str | None:
    from ..errors import ColorimetryError
    from ..illuminants import canonical_illuminant

    token = text.strip().strip('"').strip()
    if not token or len(token) > 40:
        return None
    try:
        name = canonical_illuminant(token)
    except ColorimetryError:
        return None
    return name if isinstance(name, str) else None


def parse_declaration(keywords: dict[str, str]) -> dict[str, str]:
    """The conditions a file's keywords declare, as ``metadata`` entries.

    Parameters
    ----------
    keywords : dict of str to str
        A CGATS file's keywords and their values (a repeated ``WEIGHTING_FUNCTION`` joined by
        ``"; "``), or a TM-27 file's facts under the same names.

    Returns
    -------
    dict
        Some of ``declared_illuminant`` (canonical name), ``declared_observer`` (canonical
        observer name), ``declared_geometry`` (text) and ``declared_by`` (the keywords read),
        only what the file says; ``declared_unknown`` where a declaration names an illuminant
        spectrocolor does not know (it is then not used).

    Examples
    --------
    >>> found = parse_declaration({"MEASUREMENT_SOURCE": "Illumination=D50 ObserverAngle=2° WhiteBase=Abs"})
    >>> found["declared_illuminant"], found["declared_observer"]
    ('D50', 'CIE 1931 2°')
    >>> found["declared_by"]
    'MEASUREMENT_SOURCE "Illumination=D50 ObserverAngle=2° WhiteBase=Abs"'
    >>> parse_declaration({"WEIGHTING_FUNCTION": "ILLUMINANT, D65; OBSERVER, 10 degree"})["declared_observer"]
    'CIE 1964 10°'
    """
    illuminant = observer = None
    said: list[str] = []
    unknown: list[str] = []

    def note(key: str) -> None:
        text = f'{key} "{keywords[key]}"'
        if text not in said:
            said.append(text)

    source = keywords.get("MEASUREMENT_SOURCE", "")
    if source:
        found = _ILLUMINATION.search(source)
        if found:
            illuminant = _illuminant_name(found.group(1))
            if illuminant is None:
                unknown.append(f"illuminant {found.group(1)!r:.40}")
            note("MEASUREMENT_SOURCE")
        angle = _OBSERVER_ANGLE.search(source)
        if angle and angle.group(1) in ("2", "10"):
            observer = "CIE 1931 2°" if angle.group(1) == "2" else "CIE 1964 10°"
            note("MEASUREMENT_SOURCE")
    for part in keywords.get("WEIGHTING_FUNCTION", "").split(";"):
        kind, _, value = part.partition(",")
        if kind.strip().upper() == "ILLUMINANT" and illuminant is None:
            illuminant = _illuminant_name(value)
            if illuminant is None:
                unknown.append(f"illuminant {value.strip()!r:.40}")
            note("WEIGHTING_FUNCTION")
        elif kind.strip().upper() == "OBSERVER" and observer is None:
            observer = _observer_name(value)
            note("WEIGHTING_FUNCTION")
    if illuminant is None:
        for key in _ILLUMINANT_KEYS:
            if keywords.get(key) and "=" not in keywords[key]:
                illuminant = _illuminant_name(keywords[key])
                if illuminant is None:
                    unknown.append(f"illuminant {keywords[key]!r:.40}")
                note(key)
                break
    if observer is None and keywords.get("OBSERVER"):
        observer = _observer_name(keywords["OBSERVER"])
        note("OBSERVER")
    geometry = next((keywords[k].strip() for k in _GEOMETRY_KEYS if keywords.get(k, "").strip()), None)
    declared: dict[str, str] = {}
    if illuminant is not None:
        declared["declared_illuminant"] = illuminant
    if observer is not None:
        declared["declared_observer"] = observer
    if geometry is not None:
        declared["declared_geometry"] = geometry[:80]
    if said:
        declared["declared_by"] = "; ".join(said)[:300]
    if unknown:
        declared["declared_unknown"] = "; ".join(unknown)
    return declared


def _short_observer(name: str) -> str:
    return {"CIE 1931 2°": "2°", "CIE 1964 10°": "10°"}.get(name, name)


@dataclass(frozen=True)
class DeclaredConditions:
    """The illuminant, observer and geometry a file declares (``None`` where it says nothing).

    Attributes
    ----------
    illuminant : str or None
        Canonical illuminant name (``"D50"``).
    observer : str or None
        Canonical observer name (``"CIE 1931 2°"``).
    geometry : str or None
        The measuring geometry as written (``"45/0"``); reported, not used in computing.
    declared_by : str
        The keywords that declared them, for messages.
    """

    illuminant: str | None = None
    observer: str | None = None
    geometry: str | None = None
    declared_by: str = ""

    @property
    def label(self) -> str:
        """``"D50/2°"``, ``"D65"`` or ``"10°"``: what is declared, short; ``""`` if nothing."""
        parts = [p for p in (self.illuminant, self.observer and _short_observer(self.observer)) if p]
        return "/".join(parts)

    def __bool__(self) -> bool:
        return bool(self.illuminant or self.observer)


def declared_conditions(spectrum) -> DeclaredConditions:
    """The conditions the file of ``spectrum`` declares (read by :func:`spectrocolor.read_spectra`).

    Parameters
    ----------
    spectrum : Spectrum
        Spectra as a reader returned them (``metadata["declared_illuminant"]`` …).

    Returns
    -------
    DeclaredConditions
        Falsy when the file declares neither illuminant nor observer.

    Examples
    --------
    >>> from spectrocolor import Spectrum
    >>> s = Spectrum([400, 700], [0.2, 0.4], metadata={"declared_illuminant": "D50",
    ...                                                 "declared_observer": "CIE 1931 2°"})
    >>> declared_conditions(s).label, bool(declared_conditions(Spectrum([400, 700], [0.2, 0.4])))
    ('D50/2°', False)
    """
    metadata = getattr(spectrum, "metadata", None) or {}

    def text(key: str) -> str | None:
        value = metadata.get(key)
        return value if isinstance(value, str) and value else None

    return DeclaredConditions(text("declared_illuminant"), text("declared_observer"), text("declared_geometry"),
                              text("declared_by") or "")


def _is_declared(value) -> bool:
    return isinstance(value, str) and value.strip().lower() == DECLARED


def choose_conditions(spectrum, illuminant=DECLARED, observer=DECLARED):
    """The illuminant and observer to compute ``spectrum``'s colour under, and a note.

    Parameters
    ----------
    spectrum : Spectrum
        Spectra read from a file (see :func:`declared_conditions`).
    illuminant : str, Spectrum, Illuminant or ``"declared"``, default ``"declared"``
        ``"declared"``: what the file declares, else D65; anything else as given; see :term:`illuminant`.
    observer : str, Spectrum, Observer or ``"declared"``, default ``"declared"``
        ``"declared"``: what the file declares, else CIE 1931 2°.

    Returns
    -------
    tuple
        ``(illuminant, observer, note)``: the values to pass on, and ``""`` or one line such as
        ``"the file declares D50/2°; computed under D65/10° as asked"`` where a condition named
        by the caller differs from the file's declaration.

    Examples
    --------
    >>> from spectrocolor import Spectrum
    >>> s = Spectrum([400, 700], [0.2, 0.4], metadata={"declared_illuminant": "D50",
    ...                                                 "declared_observer": "CIE 1931 2°"})
    >>> choose_conditions(s)
    ('D50', 'CIE 1931 2°', '')
    >>> choose_conditions(s, "D65", "10deg")[2]
    'the file declares D50/2°; computed under D65/10° as asked'
    """
    from ..illuminants import canonical_illuminant, illuminant_label
    from ..observers import resolve_observer

    declared = declared_conditions(spectrum)
    named_illuminant, named_observer = not _is_declared(illuminant), not _is_declared(observer)
    light = illuminant if named_illuminant else (declared.illuminant or _DEFAULT_ILLUMINANT)
    viewer = observer if named_observer else (declared.observer or _DEFAULT_OBSERVER)
    differs = False
    if named_illuminant and declared.illuminant is not None and light is not None:
        differs |= canonical_illuminant(light) != declared.illuminant
    viewer_name = resolve_observer(viewer).name
    if named_observer and declared.observer is not None:
        differs |= viewer_name != declared.observer
    if not differs:
        return light, viewer, ""
    used = "/".join(p for p in (illuminant_label(light) if light is not None else "no illuminant (lights)",
                                _short_observer(viewer_name)))
    return light, viewer, f"the file declares {declared.label}; computed under {used} as asked"


def check_reflectance_scale(spectrum, argument: str = "spectrum", percent_option: str = "percent=True") -> None:
    """Refuse reflectance factors that look like undeclared percentages (values above 1.5).

    The same rule as the command line's: where the file declared its scale (or the caller said
    ``percent``), the reader already divided; otherwise values above
    :data:`PERCENT_SUSPICION` are refused with the hint.

    Parameters
    ----------
    spectrum : Spectrum
        Values to be used as reflectance/transmittance factors (0–1).
    argument : str
        Name of the caller's argument, for the message.
    percent_option : str
        How the caller says "percent" (``"percent=True"``, ``"--percent"``), for the hint.

    Raises
    ------
    SpectrumError
        When the largest value exceeds 1.5.

    Examples
    --------
    >>> from spectrocolor import Spectrum
    >>> try:
    ...     check_reflectance_scale(Spectrum([400, 700], [20.0, 40.0]))
    ... except SpectrumError as error:
    ...     print(str(error)[:50])
    spectrum: reflectance values reach 40; if they are
    """
    values = np.asarray(spectrum.values, dtype=float)
    if values.size and np.nanmax(values) > PERCENT_SUSPICION:
        raise SpectrumError(f"{argument}: reflectance values reach {np.nanmax(values):g}; if they are "
                            f"percentages read the file with {percent_option} (or divide by 100)")


def warn_percent_of_fractions(values: np.ndarray, source: str) -> None:
    """A :class:`UserWarning` when values said to be percentages never exceed 1 (used by readers)."""
    if values.size and np.nanmax(values) <= 1.0:
        warnings.warn(f"{source}: percent was asked, but no value exceeds 1 (largest {np.nanmax(values):g}); "
                      "these look like fractions (0–1), now divided by 100 — leave percent unset if they are",
                      UserWarning, stacklevel=4)
