"""Cells a spreadsheet would execute: text written to CSV is neutralised before it is written.

A spreadsheet opening a CSV file treats a cell that begins with ``=``, ``+``, ``-`` or ``@``
(and, in some programs, a tab or carriage return) as a formula, so a sample named
``=HYPERLINK("http://...")`` in a user's file would run when the report is opened. Text cells
(sample names) that start with one of these characters are written with a leading apostrophe,
which spreadsheets show as text and do not evaluate. Numbers are never text cells here, so a
negative number stays a number.

JSON output keeps names verbatim: JSON is data for programs, which do not evaluate it, and a
reader must get back exactly the names it was given.

References
----------
OWASP, *CSV Injection*, https://owasp.org/www-community/attacks/CSV_Injection
"""

from __future__ import annotations

__all__ = ["FORMULA_STARTS", "neutralise_cell"]

#: First characters that make a spreadsheet evaluate a cell.
FORMULA_STARTS = ("=", "+", "-", "@", "\t", "\r")


def neutralise_cell(text: str) -> str:
    """``text`` made safe as a CSV text cell (a leading apostrophe before a formula start).

    Parameters
    ----------
    text : str
        A text cell, e.g. a sample name.

    Returns
    -------
    str
        ``text`` unchanged, or ``"'" + text`` if it starts with one of :data:`FORMULA_STARTS`.

    Examples
    --------
    >>> neutralise_cell('=HYPERLINK("http://example.com")')
    '\\'=HYPERLINK("http://example.com")'
    >>> neutralise_cell("tile 3")
    'tile 3'
    """
    text = str(text)
    return "'" + text if text.startswith(FORMULA_STARTS) else text
