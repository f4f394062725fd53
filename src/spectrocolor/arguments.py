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


def refuse_overflow(result, inputs, names: str, what: str,
                    error: type[ValueError] = ColorimetryError) -> np.ndarray:
    """``result``, unless an item computed from finite input came out NaN or infinite.

    The library's NaN policy: data may carry NaN, and it propagates per item; but a result that
    is not finite although its input was (an intermediate overflowed the float range) is never
    returned silently: ``error`` names the arguments and the first such item.

    Parameters
    ----------
    result : array_like, shape (...) or (..., M)
        What was computed, one item per leading index.
    inputs : sequence of array_like, each (..., N)
        The inputs, items along the leading axes (broadcast against the result's), values
        along the last axis.
    names : str
        The arguments, for the message (e.g. ``"lab1, lab2"``).
    what : str
        What overflowed and what is accepted, for the message.
    error : type, default ColorimetryError
        The ``ValueError`` subclass raised.

    Returns
    -------
    numpy.ndarray
        ``result`` as an array.

    Raises
    ------
    ValueError
        ``error``, when some item of finite input has a non-finite result.

    Examples
    --------
    >>> refuse_overflow(np.array([1.0, np.nan]), [np.array([[1.0], [np.nan]])], "x", "x squared")
    array([ 1., nan])
    >>> with np.errstate(over="ignore"):
    ...     squared = np.array([1e200]) ** 2
    >>> refuse_overflow(squared, [np.array([[1e200]])], "x", "x² overflows")
    Traceback (most recent call last):
    ...
    spectrocolor.errors.ColorimetryError: x: item 0: x² overflows (the result is inf although the input is finite)
    """
    result = np.asarray(result)
    finite_in = np.ones((), bool)
    for values in inputs:
        finite_in = finite_in & np.all(np.isfinite(np.asarray(values, dtype=float)), axis=-1)
    finite_out = np.isfinite(result)
    if finite_out.ndim > finite_in.ndim:  # results with their own value axis, e.g. (..., 3)
        finite_out = np.all(finite_out, axis=-1)
    bad = finite_in & ~finite_out
    if np.any(bad):
        index = tuple(int(i) for i in np.argwhere(bad)[0])
        where = f"item {index[0] if len(index) == 1 else index}: " if index else ""
        value = float(np.ravel(result[index])[~np.isfinite(np.ravel(result[index]))][0])
        raise error(f"{names}: {where}{what} (the result is {value!r} although the input is finite)")
    return result
