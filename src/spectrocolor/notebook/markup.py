"""Safe HTML and SVG text: every string is escaped unless it is already :class:`Markup`.

A name such as ``<script>`` or ``$x$`` is shown as the text it is: :func:`escape` turns ``<``,
``>``, ``&`` and quotes into entities and control characters (which XML forbids) into U+FFFD,
and :func:`element` escapes every attribute value and every child that is not markup built
here. The root container of every repr carries the classes MathJax 2 and 3 skip
(``tex2jax_ignore``, ``mathjax_ignore``), so a ``$`` in a name is never typeset.

Examples
--------
>>> str(element("td", "<b>"))
'<td>&lt;b&gt;</td>'
>>> str(element("rect", width=3, fill="#ff0000"))
'<rect width="3" fill="#ff0000"/>'
"""

from __future__ import annotations

import html
import math
import re

__all__ = ["Markup", "escape", "element", "join", "number", "numbers", "scientific"]

_CONTROL = re.compile(r"[\x00-\x08\x0b\x0c\x0e-\x1f\x7f]")
#: Elements written as ``<name .../>`` when they have no children.
_VOID = frozenset({"rect", "line", "circle", "polyline", "polygon", "path", "br", "col"})


class Markup(str):
    """A string of HTML/SVG built here, inserted as it is (everything else is escaped).

    Examples
    --------
    >>> escape(Markup("<b>bold</b>")) == "<b>bold</b>"
    True
    """

    __slots__ = ()


def escape(text) -> Markup:
    """``text`` as safe HTML/SVG character data (Markup passes unchanged).

    Parameters
    ----------
    text : object
        Any object; its ``str`` is escaped.

    Returns
    -------
    Markup
        With ``& < > " '`` as entities and control characters as U+FFFD.

    Examples
    --------
    >>> escape('<script>alert("x")</script>')
    '&lt;script&gt;alert(&quot;x&quot;)&lt;/script&gt;'
    """
    if isinstance(text, Markup):
        return text
    return Markup(_CONTROL.sub("\ufffd", html.escape(str(text), quote=True)))


def _attribute(name: str) -> str:
    return "class" if name == "class_" else name.replace("_", "-")


def element(name: str, *children, **attributes) -> Markup:
    """One element: ``<name attr="value">children</name>``, everything escaped but Markup.

    Parameters
    ----------
    name : str
        The tag name (a constant of this package, never user data).
    *children : object
        Content: :class:`Markup` as it is, anything else escaped; ``None`` is skipped.
    **attributes : object
        Attribute values (escaped); ``class_`` is written ``class`` and other underscores
        become hyphens (``font_size`` → ``font-size``); ``None`` values are left out.

    Returns
    -------
    Markup
        The element.

    Examples
    --------
    >>> str(element("text", "a & b", x=1, font_size=9))
    '<text x="1" font-size="9">a &amp; b</text>'
    """
    attrs = "".join(f' {_attribute(key)}="{escape(value)}"' for key, value in attributes.items()
                    if value is not None)
    content = "".join(escape(child) for child in children if child is not None)
    if not content and name in _VOID:
        return Markup(f"<{name}{attrs}/>")
    return Markup(f"<{name}{attrs}>{content}</{name}>")


def join(parts) -> Markup:
    """Concatenate markup (and escaped text) without a separator.

    Parameters
    ----------
    parts : iterable
        Markup or text.

    Returns
    -------
    Markup
        The concatenation.

    Examples
    --------
    >>> join([element("b", "x"), "<y>"])
    '<b>x</b>&lt;y&gt;'
    """
    return Markup("".join(escape(part) for part in parts))


def number(value, digits: int) -> str:
    """``value`` with ``digits`` decimals; "—" for NaN or missing, no negative zero.

    Parameters
    ----------
    value : float or None
        The number.
    digits : int
        Decimals shown.

    Returns
    -------
    str
        The formatted number.

    Examples
    --------
    >>> number(95.0429, 2), number(float("nan"), 2), number(-0.0001, 3)
    ('95.04', '—', '0.000')
    """
    if value is None:
        return "—"
    value = float(value)
    if not math.isfinite(value):
        return "—"
    text = f"{value:.{digits}f}"
    return text[1:] if text.startswith("-") and float(text) == 0.0 else text


def numbers(values, digits: int, separator: str = "  ") -> str:
    """Several numbers formatted by :func:`number`, separated by ``separator``.

    Parameters
    ----------
    values : iterable of float
        The numbers.
    digits : int
        Decimals shown.
    separator : str, default two spaces
        Between numbers.

    Returns
    -------
    str
        The formatted numbers.

    Examples
    --------
    >>> numbers([95.043, 100.0, 108.88], 2)
    '95.04  100.00  108.88'
    """
    return separator.join(number(v, digits) for v in values)


def scientific(value, digits: int = 2) -> str:
    """``value`` in ``digits`` significant figures (``"1.2e-15"``); "—" for NaN, infinity or missing.

    Parameters
    ----------
    value : float or None
        The number.
    digits : int, default 2
        Significant figures.

    Returns
    -------
    str
        The formatted number.

    Examples
    --------
    >>> scientific(7.105e-15), scientific(0.0144), scientific(float("inf"))
    ('7.1e-15', '0.014', '—')
    """
    if value is None or not math.isfinite(float(value)):
        return "—"
    return f"{float(value):.{digits}g}"
