"""Numbers and arrays from the caller: real, well-formed, or one clear error naming the argument.

The shared first step of every public function that takes numbers (see ``docs/robustness.md``):
complex values are refused, never made real by dropping the imaginary part; strings, ``None``,
dictionaries, object arrays and ragged lists are refused with the argument's name and what is
accepted, instead of NumPy's ``TypeError`` or ``ValueError`` from deep inside a computation.
"""

from __future__ import annotations

import numpy as np

from .errors import ColorimetryError

__all__ = ["real_array", "real_number"]


def real_array(values, name: str, what: str = "numbers", error: type[ValueError] = ColorimetryError,
               finite: bool = False) -> np.ndarray:
    """``values`` as a float64 array of real numbers, or ``error`` naming ``name``.

    Parameters
    ----------
    values : array_like
        Booleans, integers or floats of any precision (float16 is widened exactly).
    name : str
        The argument's name, as the caller wrote it.
    what : str
        What the numbers are, with units (e.g. "wavelengths in nm").
    error : type
        The exception to raise (a ``ValueError`` subclass from :mod:`spectrocolor.errors`).
    finite : bool
        Also refuse NaN and infinities.

    Returns
    -------
    ndarray of float64

    Examples
    --------
    >>> real_array([1, 2.5], "x")
    array([1. , 2.5])
    >>> real_array([1 + 2j], "x")
    Traceback (most recent call last):
    ...
    spectrocolor.errors.ColorimetryError: x: expected real numbers, got complex values [(1+2j)]
    """
    try:
        array = np.asarray(values)
    except ValueError:  # ragged nested sequences
        raise error(f"{name}: expected {what} in a regular array, got a ragged sequence "
                    f"{values!r:.60}") from None
    if array.dtype.kind == "c":
        raise error(f"{name}: expected real {what}, got complex values {values!r:.60}")
    if array.dtype.kind not in "biuf":
        raise error(f"{name}: expected {what}, got {values!r:.60}")
    array = array.astype(np.float64, copy=False)
    if finite and not np.all(np.isfinite(array)):
        raise error(f"{name}: expected finite {what}, got NaN or infinity")
    return array


def real_number(value, name: str, what: str = "a number", error: type[ValueError] = ColorimetryError,
                positive: bool = False) -> float:
    """``value`` as a finite real float (not a bool, not a string), or ``error`` naming ``name``.

    Parameters
    ----------
    value : object
        The argument's value.
    name : str
        The argument's name, for the message.
    what : str, default "a number"
        What the argument is, for the message.
    error : type, default ColorimetryError
        The ``ValueError`` subclass raised.
    positive : bool, default False
        Require a value > 0.

    Returns
    -------
    float
        The value.

    Raises
    ------
    ValueError
        ``error``, for a bool, a non-number, NaN or infinity (or a value <= 0 with ``positive``).

    Examples
    --------
    >>> real_number(2, "beta")
    2.0
    >>> real_number(float("nan"), "beta", "a factor 0-1")
    Traceback (most recent call last):
    ...
    spectrocolor.errors.ColorimetryError: beta: expected a factor 0-1 (a finite real number), got nan
    """
    ok = isinstance(value, int | float | np.integer | np.floating) and not isinstance(
        value, bool | np.bool_)
    number = float(value) if ok else float("nan")
    if not (ok and np.isfinite(number)) or (positive and not number > 0):
        kind = "a positive, finite real number" if positive else "a finite real number"
        raise error(f"{name}: expected {what} ({kind}), got {value!r:.60}")
    return number
