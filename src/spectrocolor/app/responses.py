"""The explorer's JSON answers: never a NaN or an infinity, never a 500 for one.

JSON has no NaN and no infinity; Starlette's ``JSONResponse`` raises ``ValueError`` on them, which
the server would answer with a 500. Every computation of the explorer replaces the non-finite
numbers it can produce by ``null`` with a reason where that is meaningful (a CRI that does not
apply, ...); :class:`FiniteJSONResponse` is the net under all of them: an answer that would
still hold one is refused with one :class:`~spectrocolor.errors.ColorimetryError` naming where,
which the server answers as a 422 in its one error shape.
"""

from __future__ import annotations

import json
import math

from fastapi.responses import JSONResponse

from ..errors import ColorimetryError

__all__ = ["FiniteJSONResponse", "first_non_finite"]


def first_non_finite(content) -> str | None:
    """Where the first NaN or infinity in ``content`` is (``"summary.Ra"``, ``"Ri[3]"``), or None.

    Parameters
    ----------
    content : JSON-ready value
        Dicts, lists, tuples, strings, numbers, booleans and None.

    Returns
    -------
    str or None
        The path to the first non-finite float, ``""`` for the value itself, or None.

    Examples
    --------
    >>> first_non_finite({"a": [1.0, {"b": float("nan")}]})
    'a[1].b'
    >>> first_non_finite({"a": [1.0, None]}) is None
    True
    """
    pending = [("", content)]
    while pending:  # iterative and depth-first, in the order the answer is written
        path, value = pending.pop()
        if isinstance(value, float) and not math.isfinite(value):
            return path
        if isinstance(value, dict):
            pending.extend((f"{path}.{key}" if path else str(key), item)
                           for key, item in reversed(list(value.items())))
        elif isinstance(value, (list, tuple)):
            pending.extend((f"{path}[{i}]", item) for i, item in reversed(list(enumerate(value))))
    return None


class FiniteJSONResponse(JSONResponse):
    """A JSON answer; one that would hold NaN or an infinity raises ColorimetryError instead.

    Examples
    --------
    >>> FiniteJSONResponse({"x": 1.5}).body
    b'{"x":1.5}'
    >>> FiniteJSONResponse({"x": [float("inf")]})  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    spectrocolor.errors.ColorimetryError: the answer has no finite value for x[0] with these inputs ...
    """

    def render(self, content) -> bytes:
        """The UTF-8 JSON text of ``content`` (compact, as Starlette writes it)."""
        try:
            return json.dumps(content, ensure_ascii=False, allow_nan=False, indent=None,
                              separators=(",", ":")).encode("utf-8")
        except ValueError:
            where = first_non_finite(content)
            if where is None:
                raise
            raise ColorimetryError(f"the answer has no finite value for {where or 'the result'} "
                                   "with these inputs (NaN or infinity); choose other settings") from None
