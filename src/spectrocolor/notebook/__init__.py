"""Notebook representations: every record shows what a user would look at (presentation layer).

In Jupyter and VS Code a record's ``_repr_html_`` (see :mod:`spectrocolor.notebook_hooks`)
lands here: :func:`html` finds the builder of the record's class in :data:`BUILDERS` and
imports only that module. The HTML is self-contained: inline SVG built as plain strings,
inline styles, no script, no link, no network reference, every name escaped; :func:`svg` gives
a standalone SVG picture as the fallback, :func:`text` a one-line ``__repr__``. Nothing here
imports matplotlib, and a batch shows its first few entries and the count, computing colours
for the shown entries only.

==============================  =============================================================
record                          what it shows
==============================  =============================================================
``Spectrum``                    curves tinted by their colour, swatches with the gamut badge,
                                grid, XYZ/xy/λd/purity (:func:`spectrum_view` to choose how
                                the spectrum is read)
``Rendering``                   swatches, codes, and what the gamut strategy did
``CRI``                         Ra, R9, CCT, Duv and the R1–R14 bars in the samples' colours
``Fidelity``                    Rf, Rg, CCT, Duv and the TM-30 colour vector graphic
``SmoothestResult``             the reflectance with its colour and its certificate
``FilmColours``                 the strip of film colours (``ZawischaStrip``: with its ticks)
``MeasurementReport``           the table of the samples with swatches
``UpsamplingTable``             its coverage: nodes exact or moved, slice by slice
==============================  =============================================================

Examples
--------
>>> from spectrocolor import render
>>> html(render([[20.0, 21.0, 22.0]])).count("#807e7c") >= 1
True
"""

from __future__ import annotations

import importlib

from .spectrum_records import SpectrumView, spectrum_view

__all__ = ["BUILDERS", "html", "svg", "text", "spectrum_view", "SpectrumView"]

#: Record class (module and name) -> (builder module in this package, function prefix): the
#: builder module defines ``<prefix>_html``, ``<prefix>_svg`` and optionally ``<prefix>_text``.
#: Every builder has the same contract, written here once rather than in each builder: it takes
#: one record of its class (as the library function named in the table above returns it) and
#: returns a ``str``: ``_html`` a self-contained HTML ``<div>``, ``_svg`` a standalone SVG
#: document, ``_text`` the one-line ``__repr__``. Each builder's docstring says what it shows and
#: gives an example.
BUILDERS: dict[str, tuple[str, str]] = {
    "spectrocolor.spectrum.Spectrum": ("spectrum_records", "spectrum"),
    "spectrocolor.display.render.Rendering": ("display_records", "rendering"),
    "spectrocolor.lighting.cri.CRI": ("lighting_records", "cri"),
    "spectrocolor.lighting.fidelity.Fidelity": ("lighting_records", "fidelity"),
    "spectrocolor.recovery.smoothest.SmoothestResult": ("recovery_records", "smoothest"),
    "spectrocolor.thinfilm.colour.FilmColours": ("thinfilm_records", "film_colours"),
    "spectrocolor.thinfilm.zawischa.ZawischaStrip": ("thinfilm_records", "zawischa_strip"),
    "spectrocolor.report.MeasurementReport": ("report_records", "measurement_report"),
    "spectrocolor.upsampling.table.UpsamplingTable": ("upsampling_records", "upsampling_table"),
}


def _builder(record, kind: str):
    cls = type(record)
    entry = BUILDERS.get(f"{cls.__module__}.{cls.__qualname__}")
    if entry is None:
        raise TypeError(f"spectrocolor.notebook has no {kind} view of {cls.__qualname__}")
    module, prefix = entry
    return getattr(importlib.import_module(f"{__name__}.{module}"), f"{prefix}_{kind}", None)


def html(record) -> str:
    """Self-contained HTML of a record (inline SVG and a compact table).

    Parameters
    ----------
    record : object
        A record of :data:`BUILDERS`.

    Returns
    -------
    str
        An HTML ``<div>``.

    Raises
    ------
    TypeError
        For an object this package has no view of.

    Examples
    --------
    >>> from spectrocolor import Spectrum
    >>> "Spectrum" in html(Spectrum([400, 500], [0.1, 0.2]))
    True
    """
    return _builder(record, "html")(record)


def svg(record) -> str:
    """A standalone SVG picture of a record (the fallback of :func:`html`).

    Parameters
    ----------
    record : object
        A record of :data:`BUILDERS`.

    Returns
    -------
    str
        An ``<svg>`` document.

    Raises
    ------
    TypeError
        For an object this package has no view of.

    Examples
    --------
    >>> from spectrocolor import render
    >>> svg(render([[20.0, 21.0, 22.0]])).startswith("<svg")
    True
    """
    return _builder(record, "svg")(record)


def text(record) -> str:
    """A concise one-line ``__repr__`` of a record.

    Parameters
    ----------
    record : object
        A record of :data:`BUILDERS` that has a text view.

    Returns
    -------
    str
        One line.

    Raises
    ------
    TypeError
        For an object this package has no text view of.

    Examples
    --------
    >>> from spectrocolor import render
    >>> text(render([[1.0, 60.0, 5.0]], gamut="flag"))
    "Rendering(1 colour, sRGB, 8-bit, normalise='none', gamut='flag', 1 outside the display, hex=['#000000'])"
    """
    builder = _builder(record, "text")
    if builder is None:
        raise TypeError(f"spectrocolor.notebook has no text view of {type(record).__qualname__}")
    return builder(record)
