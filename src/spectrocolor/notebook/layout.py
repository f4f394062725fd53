"""The HTML frame every repr shares: a card with a title line, pictures, a compact table, badges.

Styles are inline (no ``<style>`` block that could leak into the notebook's page, no class the
page must define) and use ``currentColor`` and translucent greys, so a card reads on light and
dark notebook themes alike.

Examples
--------
>>> card("Spectrum", "3 samples", [table(["x"], [["0.3127"]])]).startswith('<div class="spectrocolor-repr')
True
"""

from __future__ import annotations

from .markup import Markup, element, escape

__all__ = ["card", "row", "table", "badge", "swatch", "note", "cells", "WARN_COLOUR"]

#: The explorer's warning colour, darkened to read on light and dark backgrounds.
WARN_COLOUR = "#b86e00"
_ROOT = ("font-family: system-ui, -apple-system, 'Segoe UI', sans-serif; font-size: 12px; line-height: 1.35; "
         "display: inline-block; max-width: 100%; border: 1px solid rgba(128, 128, 128, 0.45); "
         "border-radius: 6px; padding: 6px 10px; margin: 2px 0;")
_CELL = "padding: 1px 6px; text-align: right; font-variant-numeric: tabular-nums; white-space: nowrap;"
_HEAD = "padding: 1px 6px; text-align: right; font-weight: 600; opacity: 0.75; white-space: nowrap;"
_TEXT_CELL = "padding: 1px 6px; text-align: left; white-space: nowrap; max-width: 22em; overflow: hidden;" \
             " text-overflow: ellipsis;"


def card(title, subtitle, parts) -> Markup:
    """The outer frame: a bold title, a muted subtitle and the parts below each other.

    Parameters
    ----------
    title : str
        The record's class name (escaped).
    subtitle : str or Markup
        One line of facts (grid, conditions, counts).
    parts : list of Markup
        Pictures, tables and notes.

    Returns
    -------
    Markup
        A ``<div>`` that MathJax leaves alone (``tex2jax_ignore mathjax_ignore``).

    Examples
    --------
    >>> "mathjax_ignore" in card("CRI", "", [])
    True
    """
    head = element("div", element("b", title), " ", element("span", subtitle, style="opacity: 0.75;"),
                   style="margin-bottom: 4px;")
    return element("div", head, *parts, class_="spectrocolor-repr tex2jax_ignore mathjax_ignore", style=_ROOT)


def row(parts) -> Markup:
    """Parts side by side, wrapping on narrow pages.

    Parameters
    ----------
    parts : list of Markup
        Pictures and tables.

    Returns
    -------
    Markup
        A flex ``<div>``.

    Examples
    --------
    >>> row([Markup("<i>a</i>")])
    '<div style="display: flex; flex-wrap: wrap; gap: 10px; align-items: flex-start;"><i>a</i></div>'
    """
    return element("div", *parts, style="display: flex; flex-wrap: wrap; gap: 10px; align-items: flex-start;")


def table(header, rows, text_columns=(0,)) -> Markup:
    """A compact table; text cells left-aligned, number cells right-aligned.

    Parameters
    ----------
    header : list of str
        Column titles.
    rows : list of list
        Cells: :class:`Markup` as it is, anything else escaped.
    text_columns : tuple of int, default (0,)
        Columns aligned left (names).

    Returns
    -------
    Markup
        A ``<table>`` in a ``<div>`` that scrolls sideways on a narrow page.

    Examples
    --------
    >>> "<th" in table(["name", "Y"], [["a", "50.00"]])
    True
    """
    head = element("tr", *(element("th", h, style=_TEXT_CELL if i in text_columns else _HEAD)
                           for i, h in enumerate(header)))
    body = [element("tr", *(element("td", c, style=_TEXT_CELL if i in text_columns else _CELL)
                            for i, c in enumerate(cells))) for cells in rows]
    return element("div", element("table", element("thead", head), element("tbody", *body),
                                  style="border-collapse: collapse; margin: 2px 0; font-size: 12px;"),
                   style="overflow-x: auto; max-width: 100%;")


def badge(text, title=None) -> Markup:
    """The explorer's gamut badge: which channels left the display and what was done.

    Parameters
    ----------
    text : str
        E.g. ``"R negative, G above 1: desaturated toward the white …"``.
    title : str, optional
        Tooltip (the library's full explanation).

    Returns
    -------
    Markup
        A rounded ``<span>`` in the warning colour.

    Examples
    --------
    >>> "R negative" in badge("R negative: shown black")
    True
    """
    return element("span", text, title=title,
                   style=f"display: inline-block; border: 1px solid {WARN_COLOUR}; color: {WARN_COLOUR}; "
                         "border-radius: 10px; padding: 0 7px; font-size: 11px; white-space: normal; min-width: 13em; "
                         "max-width: 26em; text-align: left;")


def swatch(hex_colour: str, title=None, size: int = 14) -> Markup:
    """A small colour square (HTML) with a thin outline.

    Parameters
    ----------
    hex_colour : str
        ``"#rrggbb"``.
    title : str, optional
        Tooltip.
    size : int, default 14
        Side in CSS pixels.

    Returns
    -------
    Markup
        An inline-block ``<span>``.

    Examples
    --------
    >>> "#ff0000" in swatch("#ff0000")
    True
    """
    return element("span", title=title,
                   style=f"display: inline-block; width: {size}px; height: {size}px; background: {escape(hex_colour)}; "
                         "border: 1px solid rgba(128, 128, 128, 0.6); vertical-align: middle;")


def note(text) -> Markup:
    """A muted line below a table (counts, conditions, what is not shown).

    Parameters
    ----------
    text : str or Markup
        The line.

    Returns
    -------
    Markup
        A ``<div>``.

    Examples
    --------
    >>> note("first 5 of 10 000 shown").endswith("</div>")
    True
    """
    return element("div", text, style="opacity: 0.75; margin-top: 2px;")


def cells(*parts) -> Markup:
    """Several pieces of markup or text in one table cell, separated by a space.

    Parameters
    ----------
    *parts : object
        Markup or text (``None`` skipped).

    Returns
    -------
    Markup
        The joined content.

    Examples
    --------
    >>> cells(Markup("<i>a</i>"), "b")
    '<i>a</i> b'
    """
    return Markup(" ".join(escape(p) for p in parts if p is not None))
