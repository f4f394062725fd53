"""Seed 000 reproduced: Zawischa's strip of soap-film colours against optical path difference.

The parameters are the seed's: two-beam model with β = 0.95 (eq. 8); a 6504 K blackbody with
``c₂ = hc/k_B = 14388 µm·K`` (the Fortran's ``alf``); CIE 1931 colour-matching functions at 5 nm
from 360 to 830 nm; summation without further weighting (eq. 9); sRGB primaries and D65 white
(eqs. 11-19); luminance-preserving treatment of negative RGB (eqs. 20-21); the largest R, G or
B of the whole series scaled to 1; the sRGB encoding with the seed's threshold 0.00304
(eqs. 22-23); 8-bit codes rounded to integers (eq. 24); 1000 columns at ``s = 5, 10, ...,
5000 nm`` (the Fortran's ``ds = 0.005*ic``, ``ic = 1..1000``) with ticks every 500 nm.

Where the seed's Fortran and its text differ, the text is followed: the Fortran applies the
luminance correction of a later channel to channels it has already gamma-encoded, and it
truncates (``int``) instead of rounding; here all negative channels are corrected in one step
in linear light (:func:`spectrocolor.render`, ``gamut="preserve-luminance"``) and codes are
rounded.

References
----------
D. Zawischa, "How to calculate and render colours – thin films as an example", ITP, Leibniz
University Hannover (seed 000), eqs. (6)-(24) and Appendix A.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .. import notebook_hooks
from ..errors import SpectrumError
from .colour import FilmColours, film_colours
from .optics import two_beam_reflectance

BETA = 0.95
TEMPERATURE_K = 6504.0
C2_M_K = 14.388e-3
COLUMNS = 1000
OPD_STEP_NM = 5.0
#: Memory of one spectral sample of one column (the two-beam factors, their spectrum, the
#: weighting), bytes.
COLUMN_SAMPLE_BYTES = 32
TICK_EVERY_NM = 500.0


@dataclass(frozen=True)
class ZawischaStrip:
    """The strip's data: one entry per column.

    Attributes
    ----------
    opd_nm : numpy.ndarray, shape (columns,)
        Optical path difference of each column, nm.
    colours : FilmColours
        :class:`~spectrocolor.thinfilm.colour.FilmColours` (XYZ relative to a perfect
        reflector under the blackbody with α = 1, xy, the rendering and its 8-bit codes).
    tick_columns : numpy.ndarray of int
        0-based columns at 500, 1000, ..., 5000 nm.

    Examples
    --------
    >>> strip = zawischa_strip(columns=200)
    >>> strip.colours.rgb8.shape, strip.tick_columns.tolist()
    ((200, 3), [99, 199])
    """

    opd_nm: np.ndarray
    colours: FilmColours
    tick_columns: np.ndarray

    _repr_html_, _repr_svg_, __repr__ = notebook_hooks.html, notebook_hooks.svg, notebook_hooks.text  # notebooks


def zawischa_space():
    """sRGB primaries and D65 white of eqs. (11)-(12) with the seed's encoding threshold.

    Returns
    -------
    RGBSpace
        sRGB with the 1996 break point 0.00304 of the encoding (transfer ``"srgb-1996"``).

    References
    ----------
    Seed 000 (Zawischa), eqs. (11)–(12) and (22)–(23).

    Examples
    --------
    >>> space = zawischa_space()
    >>> space.name, space.transfer.threshold
    ('sRGB (seed 000: threshold 0.00304)', 0.00304)
    """
    from ..display.spaces import RGBSpace

    return RGBSpace.from_chromaticities(
        (0.640, 0.330), (0.300, 0.600), (0.150, 0.060), (0.3127, 0.3290),
        transfer="srgb-1996", name="sRGB (seed 000: threshold 0.00304)",
    )


def zawischa_strip(columns: int = COLUMNS, beta: float = BETA) -> ZawischaStrip:
    """Compute seed 000's strip (see the module docstring for every parameter).

    Parameters
    ----------
    columns : int, default 1000
        Number of columns; column ``i`` (0-based) has optical path difference ``5 (i + 1)`` nm.
    beta : float, default 0.95
        Relative amplitude of the second beam (seed 000, eq. 8).

    Returns
    -------
    ZawischaStrip
        The path differences (nm), the films' colours (8-bit sRGB codes in
        ``colours.rgb8``) and the tick columns every 500 nm.

    Raises
    ------
    SpectrumError
        For ``columns`` that is not a positive whole number or β outside [0, 1].
    spectrocolor.errors.BudgetError
        (a ``SpectrumError``) For more columns than fit the memory budget (about 350 000 in
        the default 1 GiB).

    References
    ----------
    Seed 000 (Zawischa), eqs. (6)–(24) and Appendix A.

    Examples
    --------
    >>> strip = zawischa_strip()
    >>> strip.opd_nm[[0, -1]].tolist(), strip.colours.rgb8.shape
    ([5.0, 5000.0], (1000, 3))
    >>> strip.tick_columns.tolist()[:3]
    [99, 199, 299]
    """
    from ..budget import check_bytes
    from ..radiators import blackbody
    from ..spectrum import Spectrum, wavelength_grid

    if isinstance(columns, bool) or not isinstance(columns, (int, np.integer)) or columns < 1:
        raise SpectrumError(f"columns: expected a positive whole number, got {columns!r}")
    wl = wavelength_grid(360.0, 830.0, 5.0)
    check_bytes(int(columns) * wl.size * COLUMN_SAMPLE_BYTES,
                f"columns: {columns} columns of {wl.size} spectral samples")
    opd = OPD_STEP_NM * np.arange(1, columns + 1)
    light = blackbody(TEMPERATURE_K, wl, c2_m_K=C2_M_K)
    factors = Spectrum(wl, two_beam_reflectance(opd, wl, beta=beta))
    colours = film_colours(factors, illuminant=light, observer="1931", exposure="global-max",
                           space=zawischa_space(), gamut="preserve-luminance", bit_depth=8)
    ticks = np.flatnonzero(np.isclose(opd % TICK_EVERY_NM, 0.0))
    return ZawischaStrip(opd, colours, ticks)
