"""Exceptions: every bad input names the argument, what was wrong and what is accepted."""


class SpectrumError(ValueError):
    """A spectrum, wavelength grid or spectral file is malformed or incompatible."""


class ColorimetryError(ValueError):
    """A colorimetric argument (observer, illuminant, colour, white) is invalid."""
