"""X-Rite Color Exchange Format CxF3 (ISO 17972-1): spectra read and written.

A CxF3 document's element ``CxF`` (namespace ``http://colorexchangeformat.com/CxF3-core``,
usually prefixed ``cc:``) holds ``FileInformation`` (``Creator``, ``CreationDate``,
``Description``) and ``Resources``:

* ``ObjectCollection/Object`` (attributes ``ObjectType``, ``Name``, ``Id``), each with
  ``ColorValues`` holding ``ReflectanceSpectrum`` (or ``TransmittanceSpectrum``) elements:
  attributes ``ColorSpecification`` (the ``Id`` of a colour specification) and optional
  ``StartWL`` (nm), the values as text separated by white space, on the 0–1 scale;
* ``ColorSpecificationCollection/ColorSpecification`` (attribute ``Id``) with
  ``TristimulusSpec`` (``Illuminant`` such as ``D50``, ``Observer`` ``2_Degree`` or
  ``10_Degree``, ``Method`` such as ``E308_Table5``) and ``MeasurementSpec``
  (``MeasurementType`` such as ``Spectrum_Reflectance``, ``GeometryChoice`` with
  ``SingleAngle`` (``IlluminationAngle``, ``MeasurementAngle``) or ``SphereGeometry``,
  ``WavelengthRange`` with attributes ``StartWL`` and ``Increment``, ``Device/Model``).

The reader takes every spectrum's start from its own ``StartWL`` (else the specification's) and
the increment from the specification's ``WavelengthRange``; objects that hold only colorimetric
values (``ColorCIELab``) are skipped, and a file with no spectrum at all says what it holds. The
specification's illuminant, observer and geometry go to ``metadata["illuminant"]``,
``["observer"]`` (``"2°"``/``"10°"``, names :func:`spectrocolor.observers.resolve_observer`
accepts; the file's own word in ``["cxf_observer"]``) and ``["geometry"]``, one value when all
samples share it, else one per sample. As for TM-27, a document with a ``DOCTYPE`` or an entity
declaration anywhere is refused before it is parsed, and the number of values is checked
against the memory budget before any array is made.

The writer (:func:`spectra_to_cxf`, ``write_spectra(s, "x.cxf")``) writes one ``Object`` per
sample with its name XML-escaped (``<``, ``&``, quotes and line breaks survive the round trip as
character references; control characters XML 1.0 cannot hold are refused by name), values as
the shortest decimal text that reads back to the same double, the grid as ``StartWL`` and
``Increment`` (a CxF3 spectrum is on a regular grid; an irregular one is refused), and the
illuminant/observer/geometry only where the spectrum's metadata states them.

References
----------
ISO 17972-1:2015, *Graphic technology — Colour data exchange format (CxF/X) — Part 1:
Relationship to CxF3*; X-Rite, *CxF3 core schema* (``CxF3_Core.xsd``,
http://colorexchangeformat.com/CxF3-core).
"""

from __future__ import annotations

import re
import xml.etree.ElementTree as ElementTree
from xml.sax.saxutils import escape, quoteattr

import numpy as np

from ..budget import check_bytes
from ..errors import SpectrumError
from ..spectrum import Spectrum
from .text import apply_scale, number, number_table
from .tm27 import _document_element, refuse_declarations

__all__ = ["looks_like_cxf", "parse_cxf", "spectra_to_cxf", "report_to_cxf", "NAMESPACE", "EXPECTED"]

#: The CxF3 core namespace.
NAMESPACE = "http://colorexchangeformat.com/CxF3-core"
#: What a CxF3 file must contain, for messages.
EXPECTED = ("<cc:CxF> with Resources/ObjectCollection/Object/ColorValues/ReflectanceSpectrum and a "
            "ColorSpecification whose MeasurementSpec/WavelengthRange gives StartWL and Increment")
_KINDS = {"ReflectanceSpectrum": "reflectance", "TransmittanceSpectrum": "transmittance"}
_OBSERVERS = {"2_degree": "2°", "10_degree": "10°"}
#: Characters XML 1.0 cannot hold, even as character references.
_NOT_XML = re.compile("[\x00-\x08\x0b\x0c\x0e-\x1f\ufffe\uffff\ud800-\udfff]")


def looks_like_cxf(text: str) -> bool:
    """True for XML whose document element is ``CxF`` (any prefix).

    Parameters
    ----------
    text : str
        A file's text.

    Returns
    -------
    bool
        Whether :func:`parse_cxf` should read it.

    Examples
    --------
    >>> looks_like_cxf('<cc:CxF xmlns:cc="http://colorexchangeformat.com/CxF3-core"/>'), looks_like_cxf("<a/>")
    (True, False)
    """
    if not text.lstrip().startswith("<"):
        return False
    name = _document_element(text)
    return name is not None and name.rsplit(":", 1)[-1] == "CxF"


def _local(tag: str) -> str:
    return tag.rsplit("}", 1)[-1]


def _child(element, name: str):
    return next((e for e in element if _local(e.tag) == name), None)


def _text_of(element, *path: str) -> str | None:
    for name in path:
        if element is None:
            return None
        element = _child(element, name)
    if element is None or element.text is None or not element.text.strip():
        return None
    return " ".join(element.text.split())


def _geometry(choice) -> str | None:
    """``"45/0 (Annular)"``, ``"sphere (Specular_Excluded)"`` … from a ``GeometryChoice``."""
    if choice is None or not len(choice):
        return None
    kind = choice[0]
    tag = _local(kind.tag)
    leaves = {_local(e.tag): " ".join(e.text.split())
              for e in kind.iter() if e is not kind and e.text and e.text.strip()}
    if tag == "SingleAngle" and "IlluminationAngle" in leaves and "MeasurementAngle" in leaves:
        config = leaves.get("SingleAngleConfiguration")
        text = f"{leaves['IlluminationAngle']}/{leaves['MeasurementAngle']}"
        return f"{text} ({config})" if config else text
    said = kind.text.strip() if kind.text and kind.text.strip() else ", ".join(leaves.values())
    if tag == "UnknownGeometry":  # free text (what spectra_to_cxf writes)
        return said or None
    name = {"SphereGeometry": "sphere"}.get(tag, tag)
    return f"{name} ({said})" if said else name


def _specifications(root, source: str) -> dict[str, dict[str, object]]:
    specs: dict[str, dict[str, object]] = {}
    for spec in root.iter():
        if _local(spec.tag) != "ColorSpecification":
            continue
        ident = spec.get("Id", "")
        where = f"{source}: ColorSpecification {ident!r:.40}"
        info: dict[str, object] = {}
        tristimulus = _child(spec, "TristimulusSpec")
        measurement = _child(spec, "MeasurementSpec")
        for key, value in (("illuminant", _text_of(tristimulus, "Illuminant")),
                           ("cxf_observer", _text_of(tristimulus, "Observer")),
                           ("method", _text_of(tristimulus, "Method")),
                           ("measurement_type", _text_of(measurement, "MeasurementType")),
                           ("instrument", _text_of(measurement, "Device", "Model")),
                           ("geometry", _geometry(None if measurement is None
                                                  else _child(measurement, "GeometryChoice")))):
            if value is not None:
                info[key] = value
        if "cxf_observer" in info:
            info["observer"] = _OBSERVERS.get(str(info["cxf_observer"]).lower(), info["cxf_observer"])
        grid = None if measurement is None else _child(measurement, "WavelengthRange")
        if grid is not None:
            for key in ("StartWL", "Increment"):
                if key in grid.attrib:
                    info[key] = number(grid.get(key, ""), f"{where}, WavelengthRange {key}")
        specs[ident] = info
    return specs


def _samples(root, specs, source: str):
    """``(name, kind, spec id, wavelengths, values)`` for every spectrum in the object collection."""
    objects = [e for e in root.iter() if _local(e.tag) == "Object"]
    found: list[tuple] = []
    held: set[str] = set()
    for o, item in enumerate(objects, start=1):
        name = item.get("Name") or _text_of(item, "Name") or item.get("Id") or f"object_{o}"
        values_of = _child(item, "ColorValues")
        spectra = [e for e in (values_of if values_of is not None else ()) if _local(e.tag) in _KINDS]
        held.update(_local(e.tag) for e in (values_of if values_of is not None else ()))
        for s, element in enumerate(spectra, start=1):
            ident = element.get("ColorSpecification", "")
            where = f"{source}: Object {name!r:.60}, {_local(element.tag)} {s}"
            spec = specs.get(ident)
            if spec is None:
                raise SpectrumError(f"{where}: ColorSpecification {ident!r:.40} is not in the "
                                    "ColorSpecificationCollection")
            if "Increment" not in spec:
                raise SpectrumError(f"{where}: ColorSpecification {ident!r:.40} gives no WavelengthRange Increment")
            start = (number(element.get("StartWL", ""), f"{where}, StartWL") if "StartWL" in element.attrib
                     else spec.get("StartWL"))
            if start is None:
                raise SpectrumError(f"{where}: no StartWL (neither on the spectrum nor in its WavelengthRange)")
            tokens = (element.text or "").split()
            if not tokens:
                raise SpectrumError(f"{where}: no values")
            check_bytes(16 * len(tokens), f"{where}: {len(tokens)} values")
            values = number_table([tokens], lambda r, k, where=where: f"{where}, value {k + 1}")[0]
            increment = float(str(spec["Increment"]))
            if not increment > 0:
                raise SpectrumError(f"{where}: WavelengthRange Increment must be positive, got {increment:g}")
            wavelengths = float(str(start)) + increment * np.arange(len(tokens))
            found.append((name, _KINDS[_local(element.tag)], ident, wavelengths, values, len(spectra)))
    if not found:
        holds = ", ".join(sorted(held)) or "no ColorValues"
        raise SpectrumError(f"{source}: CxF3 file without spectra ({len(objects)} objects holding {holds}); "
                            f"expected {EXPECTED}")
    return found


def parse_cxf(text: str, source: str, percent: bool | None = None) -> Spectrum:
    """Spectra from a CxF3 document (see the module docstring).

    Parameters
    ----------
    text : str
        The XML document.
    source : str
        File name, for messages.
    percent : bool or None, default None
        CxF3 spectra are fractions (0–1), so ``True`` contradicts the format; see :term:`percent`.

    Returns
    -------
    Spectrum
        One spectrum per ``ReflectanceSpectrum`` (named from its object, with the
        specification's ``Id`` in brackets where an object holds several), with ``metadata``
        (``format``, ``illuminant``, ``observer``, ``geometry``, ``measurement_type``,
        ``method``, ``instrument``, ``spectral_quantity``, ``date``, ``originator``,
        ``description``, ``color_specification``) as the file gives them.

    Raises
    ------
    SpectrumError
        For a DOCTYPE or entity declaration, malformed XML, no spectra, a missing or unknown
        colour specification or increment, non-numeric values, or spectra on different grids.

    References
    ----------
    ISO 17972-1:2015; X-Rite CxF3 core schema.

    Examples
    --------
    >>> doc = ('<cc:CxF xmlns:cc="http://colorexchangeformat.com/CxF3-core"><cc:Resources>'
    ...        '<cc:ObjectCollection><cc:Object ObjectType="Standard" Name="Red" Id="1"><cc:ColorValues>'
    ...        '<cc:ReflectanceSpectrum ColorSpecification="cs" StartWL="400">0.1 0.2 0.4'
    ...        '</cc:ReflectanceSpectrum></cc:ColorValues></cc:Object></cc:ObjectCollection>'
    ...        '<cc:ColorSpecificationCollection><cc:ColorSpecification Id="cs"><cc:TristimulusSpec>'
    ...        '<cc:Illuminant>D50</cc:Illuminant><cc:Observer>2_Degree</cc:Observer></cc:TristimulusSpec>'
    ...        '<cc:MeasurementSpec><cc:WavelengthRange StartWL="400" Increment="100"/></cc:MeasurementSpec>'
    ...        '</cc:ColorSpecification></cc:ColorSpecificationCollection></cc:Resources></cc:CxF>')
    >>> s = parse_cxf(doc, "red.cxf")
    >>> s.names, s.wavelengths_nm.tolist(), s.metadata["illuminant"], s.metadata["observer"]
    (('Red',), [400.0, 500.0, 600.0], 'D50', '2°')
    """
    refuse_declarations(text, source, "CxF3")
    # the text, its UTF-8 for expat and the element tree: a few copies of the document at once
    check_bytes(4 * len(text), f"{source}: {len(text)} characters of CxF3 XML parsed as a tree")
    try:
        root = ElementTree.fromstring(text)
    except ElementTree.ParseError as exc:
        raise SpectrumError(f"{source}: not well-formed XML ({exc})") from None
    if _local(root.tag) != "CxF":
        raise SpectrumError(f"{source}: XML document element is <{_local(root.tag)}>, expected {EXPECTED}")
    specs = _specifications(root, source)
    samples = _samples(root, specs, source)
    grid = samples[0][3]
    for name, _, _, wavelengths, _, _ in samples[1:]:
        if wavelengths.shape != grid.shape or not np.allclose(wavelengths, grid, rtol=0, atol=1e-9):
            raise SpectrumError(
                f"{source}: the spectra are on different wavelength grids ({samples[0][0]!r:.40}: {grid[0]:g}–"
                f"{grid[-1]:g} nm, {grid.size} values; {name!r:.40}: {wavelengths[0]:g}–{wavelengths[-1]:g} nm, "
                f"{wavelengths.size} values); read them separately")
    kinds = {kind for _, kind, _, _, _, _ in samples}
    if len(kinds) > 1:
        raise SpectrumError(f"{source}: holds both reflectance and transmittance spectra; read one kind at a time")
    metadata: dict[str, object] = {"format": "X-Rite CxF3 (ISO 17972-1)", "spectral_quantity": kinds.pop()}
    for key in ("illuminant", "observer", "cxf_observer", "geometry", "measurement_type", "method", "instrument"):
        per_sample = [specs[ident].get(key) for _, _, ident, _, _, _ in samples]
        if any(v is not None for v in per_sample):
            metadata[key] = per_sample[0] if len(set(per_sample)) == 1 else tuple(per_sample)
    idents = [ident for _, _, ident, _, _, _ in samples]
    metadata["color_specification"] = idents[0] if len(set(idents)) == 1 else tuple(idents)
    information = _child(root, "FileInformation")
    for key, tag in (("date", "CreationDate"), ("originator", "Creator"), ("description", "Description")):
        value = _text_of(information, tag)
        if value is not None:
            metadata[key] = value
    names = [f"{name} [{ident}]" if count > 1 else name for name, _, ident, _, _, count in samples]
    values, note = apply_scale(np.array([v for _, _, _, _, v, _ in samples]), 1.0, percent, source,
                               "CxF3 spectra are on the 0–1 scale")
    metadata["value_scale"] = note
    try:
        return Spectrum(grid, values if len(samples) > 1 else values[0], names, metadata)
    except SpectrumError as exc:
        raise SpectrumError(f"{source}: {exc}") from None


def _xml_text(text, what: str) -> str:
    text = str(text)
    bad = _NOT_XML.search(text)
    if bad is not None:
        raise SpectrumError(f"{what} {text[:40]!r} holds {bad.group()!r}, a character an XML document "
                            "cannot hold; rename it")
    return text


def _colour_elements(colour, what: str) -> list[str]:
    """``ColorCIEXYZ``/``ColorCIELab`` lines for one sample's ``{"XYZ": (X, Y, Z), "Lab": (L, a, b)}``."""
    lines = []
    for key, tag, parts in (("XYZ", "ColorCIEXYZ", ("X", "Y", "Z")), ("Lab", "ColorCIELab", ("L", "A", "B"))):
        values = colour.get(key)
        if values is None or any(v is None for v in values):
            continue  # not computed (NaN in a report): left out
        numbers = [float(v) for v in values]
        if len(numbers) != 3 or not all(np.isfinite(numbers)):
            raise SpectrumError(f"{what}[{key!r}]: expected three finite numbers, got {values!r:.60}")
        inner = "".join(f"<cc:{p}>{v!r}</cc:{p}>" for p, v in zip(parts, numbers, strict=True))
        lines.append(f'          <cc:{tag} ColorSpecification="cs1">{inner}</cc:{tag}>')
    return lines


def spectra_to_cxf(spectrum: Spectrum, colours=None) -> str:
    """A CxF3 document holding ``spectrum`` as reflectance spectra (see the module docstring).

    Parameters
    ----------
    spectrum : Spectrum
        One spectrum or an ``(N, K)`` batch on a regular wavelength grid (nm), values on the 0–1
        scale. ``metadata`` ``illuminant``, ``observer`` (``"2°"``/``"10°"`` or the CxF3
        words), ``geometry`` and ``instrument`` are written when they are single strings.
    colours : sequence of dict, optional
        One per sample: ``{"XYZ": (X, Y, Z), "Lab": (L*, a*, b*)}`` (either may be missing or
        hold None), written beside the spectrum as ``ColorCIEXYZ``/``ColorCIELab`` under the
        same colour specification (the command line's ``report --out x.cxf``). The reader skips
        them.

    Returns
    -------
    str
        The XML document (UTF-8 declared).

    Raises
    ------
    SpectrumError
        For an irregular grid, or a name with a character XML 1.0 cannot hold.

    Examples
    --------
    >>> s = Spectrum([400, 500, 600], [[0.1, 0.2, 0.4], [0.3, 0.3, 0.3]], ["a<b", "c & d"])
    >>> parse_cxf(spectra_to_cxf(s), "x.cxf") == s
    True
    """
    wavelengths = np.asarray(spectrum.wavelengths_nm, dtype=float)
    values = np.atleast_2d(np.asarray(spectrum.values, dtype=float))
    start = float(wavelengths[0])
    increment = float(wavelengths[1] - wavelengths[0]) if wavelengths.size > 1 else 1.0
    if wavelengths.size > 1 and not np.allclose(start + increment * np.arange(wavelengths.size), wavelengths,
                                                rtol=0, atol=1e-9):
        raise SpectrumError("spectrum: CxF3 holds spectra on a regular wavelength grid (StartWL, Increment); "
                            f"this one runs {start:g}–{wavelengths[-1]:g} nm in unequal steps; resample it first")
    metadata = spectrum.metadata or {}
    facts: dict[str, str] = {key: _xml_text(metadata[key], f"metadata {key!r}")
                             for key in ("illuminant", "observer", "geometry", "instrument")
                             if isinstance(metadata.get(key), str)}
    observer = facts.get("observer")
    if observer is not None:
        words = {"2°": "2_Degree", "10°": "10_Degree", "CIE 1931 2°": "2_Degree", "CIE 1964 10°": "10_Degree"}
        facts["observer"] = words.get(observer, observer)
    names = [_xml_text(name, "spectrum name") for name in spectrum.names] if spectrum.names else [
        f"sample_{i + 1}" for i in range(values.shape[0])]
    if colours is not None and len(colours) != values.shape[0]:
        raise SpectrumError(f"colours: {len(colours)} entries for {values.shape[0]} spectra; give one per sample")
    lines = ['<?xml version="1.0" encoding="UTF-8"?>',
             f'<cc:CxF xmlns:cc="{NAMESPACE}">',
             "  <cc:FileInformation>",
             "    <cc:Creator>spectrocolor</cc:Creator>",
             "  </cc:FileInformation>",
             "  <cc:Resources>",
             "    <cc:ObjectCollection>"]
    for i, (name, row) in enumerate(zip(names, values, strict=True), start=1):
        text = " ".join(repr(float(v)) for v in row)
        lines += [f'      <cc:Object ObjectType="Target" Name={quoteattr(name)} Id="o{i}">',
                  "        <cc:ColorValues>",
                  f'          <cc:ReflectanceSpectrum ColorSpecification="cs1" StartWL="{start!r}">{text}'
                  "</cc:ReflectanceSpectrum>",
                  *([] if colours is None else _colour_elements(colours[i - 1], f"colours[{i - 1}]")),
                  "        </cc:ColorValues>",
                  "      </cc:Object>"]
    lines += ["    </cc:ObjectCollection>",
              "    <cc:ColorSpecificationCollection>",
              '      <cc:ColorSpecification Id="cs1">']
    if "illuminant" in facts or "observer" in facts:
        lines.append("        <cc:TristimulusSpec>")
        lines += [f"          <cc:{tag}>{escape(facts[key])}</cc:{tag}>"
                  for key, tag in (("illuminant", "Illuminant"), ("observer", "Observer")) if key in facts]
        lines.append("        </cc:TristimulusSpec>")
    lines += ["        <cc:MeasurementSpec>",
              "          <cc:MeasurementType>Spectrum_Reflectance</cc:MeasurementType>"]
    if "geometry" in facts:
        lines.append(f"          <cc:GeometryChoice><cc:UnknownGeometry>{escape(facts['geometry'])}"
                     "</cc:UnknownGeometry></cc:GeometryChoice>")
    lines.append(f'          <cc:WavelengthRange StartWL="{start!r}" Increment="{increment!r}"/>')
    if "instrument" in facts:
        lines.append(f"          <cc:Device><cc:Model>{escape(facts['instrument'])}</cc:Model></cc:Device>")
    lines += ["        </cc:MeasurementSpec>",
              "      </cc:ColorSpecification>",
              "    </cc:ColorSpecificationCollection>",
              "  </cc:Resources>",
              "</cc:CxF>",
              ""]
    return "\n".join(lines)


def report_to_cxf(spectra: Spectrum, report) -> str:
    """A CxF3 document of measured spectra with a measurement report's XYZ and L*a*b*.

    Parameters
    ----------
    spectra : Spectrum
        The reflectances the report was computed from.
    report : spectrocolor.report.MeasurementReport
        Its ``illuminant`` and ``observer`` are declared in the colour specification; its
        ``records()`` give each sample's ``X``, ``Y``, ``Z``, ``L*``, ``a*``, ``b*``.

    Returns
    -------
    str
        The document (:func:`spectra_to_cxf`).

    Examples
    --------
    >>> from spectrocolor import measurement_report
    >>> tiles = Spectrum([400, 500, 600, 700], [[0.5, 0.5, 0.5, 0.5]], ["grey"])
    >>> text = report_to_cxf(tiles, measurement_report(tiles, illuminant="D65"))
    >>> "<cc:Illuminant>D65</cc:Illuminant>" in text, "<cc:ColorCIELab" in text
    (True, True)
    """
    metadata = {**(spectra.metadata or {}), "illuminant": str(report.illuminant), "observer": str(report.observer)}
    colours = [{"XYZ": (r["X"], r["Y"], r["Z"]), "Lab": (r["L*"], r["a*"], r["b*"])} for r in report.records()]
    return spectra_to_cxf(Spectrum(spectra.wavelengths_nm, spectra.values, spectra.names, metadata), colours)
