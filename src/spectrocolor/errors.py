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
