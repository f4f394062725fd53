"""IES TM-27 spectral data XML (TM-27-14 and TM-27-20; ``.xml``, ``.spdx``).

The document element is ``IESTM2714`` (in the TM-27 namespace, whatever its URI; ``version``
says which edition). Its ``Header`` (manufacturer, description, laboratory, report date,
measurement equipment …) and other sections (luminaire, equipment) are kept in ``metadata``; each
``SpectralDistribution`` element holds ``SpectralQuantity``, optional ``BandwidthFWHM``,
``BandwidthCorrected``, ``ReflectionGeometry``/``TransmissionGeometry`` and the samples as
``<SpectralData wavelength="380">0.06</SpectralData>``. Several ``SpectralDistribution`` elements
on one grid become a batch.

The reader uses the element names that TM-27-14 defines, for TM-27-20 documents too: the
TM-27-20 schema is not public and could not be checked (see docs/measurement_data.md); elements
it does not know are kept as text in ``metadata`` under ``Section/Element``. ``BandwidthFWHM`` and
``BandwidthCorrected`` are kept (``bandwidth_fwhm_nm``, ``bandwidth_corrected``) for
:func:`spectrocolor.bandpass.bandpass_correction` to check; nothing is corrected on reading.
Documents with a ``DOCTYPE`` or an entity declaration anywhere are refused, found by expat
itself before the document is parsed (no entity is ever expanded). TM-27 does not declare percent
or fraction for reflectance data; the caller's ``percent`` option decides
(:func:`spectrocolor.io.text.apply_scale`).

References
----------
IES TM-27-14, *IES Standard Format for the Electronic Transfer of Spectral Data*, Illuminating
Engineering Society, 2014; IES TM-27-20 (second edition), 2020.
"""

from __future__ import annotations

import xml.etree.ElementTree as ElementTree
from xml.parsers import expat

import numpy as np

from ..errors import SpectrumError
from ..spectrum import Spectrum
from .text import apply_scale, number

EXPECTED = "<IESTM2714> with <SpectralDistribution><SpectralData wavelength=…>"


def looks_like_tm27(text: str) -> bool:
    """True for XML whose document element is ``IESTM2714`` (any namespace prefix), or with a DTD.

    The document element is found by expat itself, however long the comments and processing
    instructions before it. A document with a ``DOCTYPE`` is not read past it (its DTD could
    declare entities): it is answered True, so that :func:`parse_tm27` refuses it with the
    reason, whatever its document element.

    Parameters
    ----------
    text : str
        A file's text.

    Returns
    -------
    bool
        Whether :func:`parse_tm27` should read it.

    Examples
    --------
    >>> looks_like_tm27('<IESTM2714 version="1.0"></IESTM2714>'), looks_like_tm27("<html></html>")
    (True, False)
    >>> looks_like_tm27("<!--" + " " * 100_000 + '--><tm:IESTM2714 xmlns:tm="x"/>')
    True
    """
    if not text.lstrip().startswith("<"):
        return False
    name = _document_element(text)
    return name is _DOCTYPE or (name is not None and name.rsplit(":", 1)[-1] == "IESTM2714")


class _Found(Exception):
    """Raised by an expat handler to stop parsing: the document element (or DOCTYPE) is known."""


class _Declaration(Exception):
    """Raised by an expat handler: the document declares a DOCTYPE or an entity."""


_DOCTYPE = "<!DOCTYPE>"  # what _document_element answers for a document with a DTD


def _stop_at_name(name, *_):
    raise _Found(name)


def _stop_at_doctype(*_):
    raise _Found(_DOCTYPE)


def _document_element(text: str) -> str | None:
    """The document element's name (prefix included), :data:`_DOCTYPE`, or None (not XML)."""
    parser = expat.ParserCreate()
    parser.StartElementHandler = _stop_at_name
    parser.StartDoctypeDeclHandler = _stop_at_doctype
    try:
        parser.Parse(text, True)
    except _Found as found:
        return found.args[0]
    except (expat.ExpatError, ValueError):
        return None
    return None


def _refuse_declaration(*_):
    raise _Declaration


def refuse_declarations(text: str | bytes, source: str, needs: str = "spectral XML (TM-27, CxF3)") -> None:
    """SpectrumError if the document has a DOCTYPE or declares an entity, wherever it is.

    ``needs`` names the format in the message (CxF3 and SpreadsheetML need no DTD either).

    expat reads the whole document once (linear) with handlers that stop at the first DOCTYPE,
    ENTITY or NOTATION declaration: no prefix of the text is trusted, so a DOCTYPE after 70 kB
    of comment is found too, and no entity is ever expanded.
    """
    parser = expat.ParserCreate()
    parser.StartDoctypeDeclHandler = _refuse_declaration
    parser.EntityDeclHandler = _refuse_declaration
    parser.UnparsedEntityDeclHandler = _refuse_declaration
    parser.NotationDeclHandler = _refuse_declaration
    try:
        parser.Parse(text, True)
    except _Declaration:
        raise SpectrumError(f"{source}: XML with a DOCTYPE or ENTITY declaration is not accepted "
                            f"({needs} needs none)") from None
    except (expat.ExpatError, ValueError) as exc:
        raise SpectrumError(f"{source}: not well-formed XML ({exc})") from None


def _local(tag: str) -> str:
    return tag.rsplit("}", 1)[-1]


#: Deepest header element read, in levels below the document element (TM-27's are 2 or 3 deep).
MAX_DEPTH = 32


def _leaves(element, prefix: str, into: dict[str, object], source: str = "<text>") -> None:
    """The text of every leaf below ``element`` as ``into["Header/Laboratory"] = ...``.

    Iterative, in document order: the depth is the file's, never the interpreter's stack; a
    document nested deeper than :data:`MAX_DEPTH` is refused (each level's name would be
    repeated in every key below it).
    """
    pending = [(prefix, iter(element))]
    while pending:
        name_above, children = pending[-1]
        child = next(children, None)
        if child is None:
            pending.pop()
            continue
        name = f"{name_above}/{_local(child.tag)}" if name_above else _local(child.tag)
        if len(child):
            if len(pending) >= MAX_DEPTH:
                raise SpectrumError(f"{source}: <{name.split('/')[0]}> is nested more than {MAX_DEPTH} "
                                    f"levels deep; TM-27 headers are a few levels deep ({EXPECTED})")
            pending.append((name, iter(child)))
        elif child.text and child.text.strip():
            into[name] = child.text.strip()


def parse_tm27(text: str, source: str, percent: bool | None = None) -> Spectrum:
    """Spectra from an IES TM-27 XML document (see the module docstring).

    Parameters
    ----------
    text : str
        The XML document.
    source : str
        File name, for messages.
    percent : bool or None, default None
        ``True`` divides the values by 100; ``None`` and ``False`` keep them.

    Returns
    -------
    Spectrum
        One spectrum per ``SpectralDistribution``, named from the header's description, with
        ``metadata`` (``format``, ``spectral_quantity``, …).

    Raises
    ------
    SpectrumError
        For XML with DOCTYPE or ENTITY declarations, malformed XML, or missing or
        non-numeric spectral data.

    References
    ----------
    ANSI/IES TM-27-20, *IES Standard Format for the Electronic Transfer of Spectral Data*.

    Examples
    --------
    >>> doc = ('<IESTM2714 xmlns="iesna.org/tm2714" version="1.0"><Header><Description>LED'
    ...        '</Description></Header><SpectralDistribution><SpectralQuantity>relative</SpectralQuantity>'
    ...        '<SpectralData wavelength="400">0.5</SpectralData><SpectralData wavelength="410">1'
    ...        '</SpectralData></SpectralDistribution></IESTM2714>')
    >>> s = parse_tm27(doc, "led.xml")
    >>> s.names, s.values.tolist(), s.metadata["spectral_quantity"]
    (('LED',), [0.5, 1.0], 'relative')
    """
    refuse_declarations(text, source)
    try:
        root = ElementTree.fromstring(text)
    except ElementTree.ParseError as exc:
        raise SpectrumError(f"{source}: not well-formed XML ({exc})") from None
    if _local(root.tag) != "IESTM2714":
        raise SpectrumError(f"{source}: XML document element is <{_local(root.tag)}>, expected {EXPECTED}")
    metadata: dict[str, object] = {"format": f"IES TM-27 XML (version {root.get('version', 'not given')})"}
    for section in root:
        if _local(section.tag) != "SpectralDistribution":
            _leaves(section, _local(section.tag), metadata, source)
    distributions = [e for e in root if _local(e.tag) == "SpectralDistribution"]
    if not distributions:
        raise SpectrumError(f"{source}: no <SpectralDistribution> element; expected {EXPECTED}")
    grids, rows, facts = [], [], []
    for d, distribution in enumerate(distributions, start=1):
        wavelengths, values, info = [], [], {}
        for element in distribution:
            tag = _local(element.tag)
            if tag == "SpectralData":
                where = f"{source}: SpectralDistribution {d}, SpectralData"
                if "wavelength" not in element.attrib:
                    raise SpectrumError(f"{where}: missing the wavelength attribute")
                wavelengths.append(number(element.attrib["wavelength"], f"{where} wavelength"))
                values.append(number(element.text or "", f"{where} at {wavelengths[-1]:g} nm"))
            elif element.text and element.text.strip():
                info[tag] = element.text.strip()
        if len(wavelengths) < 1:
            raise SpectrumError(f"{source}: SpectralDistribution {d} has no <SpectralData wavelength=…> samples")
        order = np.argsort(wavelengths, kind="stable")
        grids.append(np.asarray(wavelengths)[order])
        rows.append(np.asarray(values)[order])
        facts.append(info)
    if any(g.shape != grids[0].shape or not np.array_equal(g, grids[0]) for g in grids):
        raise SpectrumError(f"{source}: the SpectralDistribution elements are on different wavelength grids")
    names = _names(metadata, len(distributions))
    for key, tag in (
        ("spectral_quantity", "SpectralQuantity"),
        ("bandwidth_fwhm_nm", "BandwidthFWHM"),
        ("bandwidth_corrected", "BandwidthCorrected"),
    ):
        found = {info.get(tag) for info in facts} - {None}
        if found:
            metadata[key] = found.pop() if len(found) == 1 else tuple(info.get(tag) for info in facts)
    geometry = [info.get("ReflectionGeometry") or info.get("TransmissionGeometry") for info in facts]
    if any(geometry):
        metadata["geometry"] = geometry[0] if len(set(geometry)) == 1 else tuple(geometry)
        if len(set(geometry)) == 1:  # one geometry for every distribution: the file declares it
            metadata["declared_geometry"] = str(geometry[0])[:80]
    for fact, keys in (
        ("instrument", ("Header/MeasurementEquipment", "Equipment/Model", "Equipment/Name")),
        ("date", ("Header/ReportDate", "Header/DocumentCreationDate")),
    ):
        known = next((metadata[k] for k in keys if k in metadata), None)
        if known is not None:
            metadata[fact] = known
    values, note = apply_scale(np.array(rows), None, percent, source, "")
    metadata["value_scale"] = note
    try:
        return Spectrum(grids[0], values if len(rows) > 1 else values[0], names, metadata)
    except SpectrumError as exc:
        raise SpectrumError(f"{source}: SpectralData: {exc}") from None


def _names(metadata: dict[str, object], count: int) -> list[str]:
    parts = [
        str(metadata[k]) for k in ("Header/Manufacturer", "Header/CatalogNumber", "Header/Description") if k in metadata
    ]
    base = " ".join(" – ".join(parts).split()) if parts else "spectrum"  # XML line breaks: spaces
    return [base] if count == 1 else [f"{base} {i + 1}" for i in range(count)]
