"""Exceptions: every bad input names the argument, what was wrong and what is accepted."""


class SpectrumError(ValueError):
    """A spectrum, wavelength grid or spectral file is malformed or incompatible.

    A ``ValueError``; the message names the argument, what was wrong and what is accepted.

    Examples
    --------
    >>> from spectrocolor import wavelength_grid
    >>> try:
    ...     wavelength_grid(400, 700, 7)
    ... except SpectrumError as error:
    ...     print(error)
    start_nm, stop_nm, step_nm: 7.0 does not divide 400.0–700.0 nm into whole steps
    """


class ColorimetryError(ValueError):
    """A colorimetric argument (observer, illuminant, colour, white) is invalid.

    A ``ValueError``; the message names the argument, what was wrong and what is accepted.

    Examples
    --------
    >>> from spectrocolor import observer
    >>> try:
    ...     observer("1950")
    ... except ColorimetryError as error:
    ...     print(str(error).split(":")[0])  # the message starts with the argument's name
    observer
    >>> issubclass(ColorimetryError, ValueError)
    True
    """


class BudgetError(SpectrumError, ColorimetryError):
    """An input claims more memory (or data) than the budget allows, or than its file holds.

    Raised before anything is allocated: a file header, an option or an argument asks for an
    array beyond the memory budget (:mod:`spectrocolor.budget`), a file claims more bytes than
    it holds or stores, or compressed data claim an expansion no compressor reaches. The message
    names the input, the claimed size and the limit, and how to raise the budget where that
    makes sense. It is both a :class:`SpectrumError` and a :class:`ColorimetryError` (so a
    ``ValueError``), so every handler of bad input catches it.

    Examples
    --------
    >>> from spectrocolor.budget import check_bytes
    >>> try:
    ...     check_bytes(8 * 2**30, "--width 32768 --height 32768", budget="1GiB")
    ... except BudgetError as error:
    ...     print(str(error)[:65])
    --width 32768 --height 32768: needs 8 GiB of memory, more than th
    >>> issubclass(BudgetError, ValueError)
    True
    """
