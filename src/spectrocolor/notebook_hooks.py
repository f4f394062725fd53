"""The notebook hooks that every record class shares: ``_repr_html_``, ``_repr_svg_``, ``__repr__``.

Jupyter and VS Code show an object through its ``_repr_html_`` (and ``_repr_svg_`` where HTML
is not rendered). The records live in every layer (``Spectrum`` in the spectra trunk,
``Rendering`` in the colour trunk, ``CRI`` in an application), their pictures in the
presentation layer (:mod:`spectrocolor.notebook`). A record class therefore names these hooks
in one line each::

    _repr_html_ = notebook_hooks.html
    _repr_svg_ = notebook_hooks.svg

and the hook looks the builder up when a notebook asks for it. This module is the one place
below the presentation layer that names :mod:`spectrocolor.notebook`, and it names it as data,
resolved at call time (as the package's lazy public-name table does), so importing a record
never imports the presentation layer, and nothing here ever imports matplotlib.
"""

from __future__ import annotations

import importlib

#: The presentation package that builds every record's picture and table.
NOTEBOOK_PACKAGE = "spectrocolor.notebook"


def _notebook():
    return importlib.import_module(NOTEBOOK_PACKAGE)


def html(record) -> str:
    """Self-contained HTML of ``record`` for a notebook (inline SVG, no script, no network).

    Parameters
    ----------
    record : object
        A spectrocolor record (``Spectrum``, ``Rendering``, ``CRI`` …).

    Returns
    -------
    str
        An HTML fragment.

    Examples
    --------
    >>> from spectrocolor import Spectrum
    >>> html(Spectrum([400, 500, 600], [0.2, 0.5, 0.8])).startswith("<div")
    True
    """
    return _notebook().html(record)


def svg(record) -> str:
    """A standalone SVG picture of ``record`` (the fallback where HTML is not shown).

    Parameters
    ----------
    record : object
        A spectrocolor record.

    Returns
    -------
    str
        An ``<svg>`` document.

    Examples
    --------
    >>> from spectrocolor import Spectrum
    >>> svg(Spectrum([400, 500, 600], [0.2, 0.5, 0.8])).startswith("<svg")
    True
    """
    return _notebook().svg(record)


def text(record) -> str:
    """A concise one-line text representation of ``record`` (its ``__repr__``).

    Parameters
    ----------
    record : object
        A spectrocolor record.

    Returns
    -------
    str
        One line: the class name and the numbers a user looks at first.

    Examples
    --------
    >>> from spectrocolor import render
    >>> text(render([[20.0, 21.0, 22.0]]))
    "Rendering(1 colour, sRGB, 8-bit, normalise='none', gamut='desaturate', all in gamut, hex=['#807e7c'])"
    """
    return _notebook().text(record)
