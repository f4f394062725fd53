"""Colours of thin films: reflectance spectra -> XYZ under an illuminant -> display codes.

All colorimetry and display work is delegated to the library (:func:`spectrocolor.weights`,
:func:`spectrocolor.xy`, :func:`spectrocolor.render`); this module only states the choices that
belong to interference colours: the light (default a 6504 K blackbody, as in seed 000), the
observer and the exposure rule.

Exposure rules (``exposure``):

* ``"global-max"`` (seed 000): the largest linear R, G or B over the whole series becomes full
  drive; relative brightness within the series is kept.
* ``"perfect-reflector"``: XYZ are relative to a perfect reflector under the same light
  (Y = 100), multiplied by ``gain``, and Y = 100 is the display's white. A soap film reflects
  only a few per cent, so a gain of 5-10 is typical for a picture.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .. import notebook_hooks
from ..display.gamut import DEFAULT_GAMUT
from ..display.render import Rendering
from ..errors import ColorimetryError, SpectrumError
from ..illuminants import illuminant_label
from ..observers import DEFAULT_OBSERVER
from .optics import FilmOptics

EXPOSURES = ("global-max", "perfect-reflector")
#: Seed 000 (Zawischa) lights its films with a 6504 K Planckian radiator: the films' default.
SEED_000_ILLUMINANT = "blackbody:6504"


@dataclass(frozen=True)
class FilmColours:
    """Colours of a series of films.

    Returned by :func:`film_colours`.

    Attributes
    ----------
    XYZ100 : numpy.ndarray, shape (..., 3)
        Tristimulus values relative to a perfect reflector under the light (Y = 100), before
        exposure.
    xy : numpy.ndarray, shape (..., 2)
        Chromaticities.
    rendering : Rendering
        The :class:`spectrocolor.Rendering` (linear and encoded RGB, codes, gamut flags).
    illuminant, observer, exposure : str
        What was used (the illuminant as :func:`spectrocolor.illuminant_label` writes it).

    Examples
    --------
    >>> from spectrocolor import soap_film, wavelength_grid
    >>> colours = film_colours(soap_film([100.0, 300.0, 500.0], wavelength_grid(380, 780, 5)))
    >>> colours.rendering.hex.tolist()
    ['#fafdfa', '#c8ffa8', '#6bf862']
    >>> colours.illuminant, colours.exposure, colours.rgb8.shape
    ('blackbody 6504 K', 'global-max', (3, 3))
    """

    XYZ100: np.ndarray
    xy: np.ndarray
    rendering: Rendering
    illuminant: str
    observer: str
    exposure: str

    _repr_html_, _repr_svg_, __repr__ = notebook_hooks.html, notebook_hooks.svg, notebook_hooks.text  # notebooks

    @property
    def rgb8(self) -> np.ndarray:
        """8-bit codes as ``uint8``, shape ``(..., 3)`` (requires ``bit_depth=8``)."""
        if self.rendering.bit_depth != 8:
            raise ColorimetryError("rgb8: this rendering is not 8-bit")
        return self.rendering.codes.astype(np.uint8)


def film_colours(films, *, quantity: str = "reflectance", illuminant=SEED_000_ILLUMINANT,
                 observer=DEFAULT_OBSERVER, exposure: str = "global-max", gain: float = 1.0,
                 space="sRGB", gamut: str = DEFAULT_GAMUT, bit_depth: int = 8,
                 method: str = "sum") -> FilmColours:
    """Colours of films seen in reflection (or transmission) under a light.

    Parameters
    ----------
    films : FilmOptics or Spectrum
        A :class:`~spectrocolor.thinfilm.optics.FilmOptics` or a :class:`spectrocolor.Spectrum`
        of reflectance (or transmittance, or two-beam) factors, shape ``(..., K)``.
    quantity : str, keyword-only, default "reflectance"
        ``"reflectance"`` or ``"transmittance"`` (FilmOptics only).
    illuminant : str, float or Spectrum, keyword-only
        The light the films are seen under (default ``"blackbody:6504"``, seed 000's light), not
        ``None``; a Spectrum must contain every sample of the films' grid; see :term:`illuminant`.
    observer : str or Spectrum, keyword-only
        Any name :func:`spectrocolor.observer` accepts (default CIE 1931 2°).
    exposure : str, keyword-only, default "global-max"
        ``"global-max"`` or ``"perfect-reflector"`` (see the module docstring).
    gain : float, keyword-only, default 1.0
        Multiplier for ``"perfect-reflector"`` exposure (must be 1 for ``"global-max"``).
    space : str or RGBSpace, keyword-only, default "sRGB"
        Passed to :func:`spectrocolor.render`.
    gamut : str, keyword-only, default DEFAULT_GAMUT
        Gamut strategy, passed to :func:`spectrocolor.render` (default ``"desaturate"``; seed
        000's eqs. 20–21 are ``"preserve-luminance"``, as :func:`spectrocolor.zawischa_strip` uses).
    bit_depth : int, keyword-only, default 8
        Passed to :func:`spectrocolor.render`.
    method : str, keyword-only, default "sum"
        Summation method of :func:`spectrocolor.weights`.

    Returns
    -------
    FilmColours
        XYZ100, xy, the rendering and the choices used.

    Raises
    ------
    SpectrumError
        For input that is neither FilmOptics nor Spectrum, or ``quantity`` with a Spectrum.
    ColorimetryError
        For ``illuminant=None``, an unknown exposure, a gain that is not positive or given with
        ``"global-max"``, and as :func:`spectrocolor.weights` and :func:`spectrocolor.render`.

    References
    ----------
    Seed 000 (Zawischa): 6504 K blackbody, eqs. 13–24.

    Examples
    --------
    >>> from spectrocolor import soap_film, wavelength_grid
    >>> bright = film_colours(soap_film([250.0], wavelength_grid(380, 780, 5)),
    ...                       exposure="perfect-reflector", gain=5)
    >>> bright.XYZ100.round(2).tolist()  # relative to a perfect reflector: a few per cent
    [[2.58, 3.08, 8.56]]
    """
    from ..spectrum import Spectrum

    if isinstance(films, FilmOptics):
        spectrum = films.spectrum(quantity)
    elif isinstance(films, Spectrum):
        if quantity != "reflectance":
            raise SpectrumError("quantity: only for FilmOptics; a Spectrum is used as given")
        spectrum = films
    else:
        raise SpectrumError(
            f"films: expected FilmOptics or Spectrum, got {type(films).__name__}"
        )
    W = film_weights(spectrum.wavelengths_nm, illuminant=illuminant, observer=observer,
                     exposure=exposure, gain=gain, method=method)
    return colours_of(spectrum.values @ W, illuminant=illuminant, observer=observer,
                      exposure=exposure, gain=gain, space=space, gamut=gamut, bit_depth=bit_depth)


def film_weights(wavelengths_nm, *, illuminant=SEED_000_ILLUMINANT, observer=DEFAULT_OBSERVER,
                 exposure: str = "global-max", gain: float = 1.0, method: str = "sum",
                 **_ignored) -> np.ndarray:
    """The options of :func:`film_colours` checked, and its weights ``W`` (K, 3) on the grid.

    ``factors @ W`` are the films' XYZ100, for callers that compute the factors in blocks
    (:func:`spectrocolor.thinfilm.maps.colour_table`) and render them together with
    :func:`colours_of`. Other keywords of :func:`film_colours` are ignored.
    """
    from ..colorimetry import weights

    if exposure not in EXPOSURES:
        raise ColorimetryError(f"exposure: expected one of {EXPOSURES}, got {exposure!r}")
    if not (np.isfinite(gain) and gain > 0):
        raise ColorimetryError(f"gain: expected a positive number, got {gain!r}")
    if exposure == "global-max" and gain != 1.0:
        raise ColorimetryError('gain: only with exposure="perfect-reflector"')
    if illuminant is None:
        raise ColorimetryError(
            "illuminant: a film's reflectance needs a light; give a CIE name, 'blackbody:T' or a Spectrum "
            f"(seed 000 uses {SEED_000_ILLUMINANT!r}, the default)"
        )
    return weights(wavelengths_nm, observer=observer, illuminant=illuminant, method=method)


def colours_of(XYZ100, *, illuminant=SEED_000_ILLUMINANT, observer=DEFAULT_OBSERVER,
               exposure: str = "global-max", gain: float = 1.0, space="sRGB",
               gamut: str = DEFAULT_GAMUT, bit_depth: int = 8, **_ignored) -> FilmColours:
    """:class:`FilmColours` of films' XYZ100 (from :func:`film_weights`), as :func:`film_colours` renders them."""
    from ..coordinates import xy as chromaticity
    from ..display.render import render

    rendering = render(
        XYZ100 * gain if exposure == "perfect-reflector" else XYZ100,
        space=space,
        normalise="global-max" if exposure == "global-max" else "none",
        gamut=gamut,
        bit_depth=bit_depth,
    )
    return FilmColours(XYZ100, chromaticity(XYZ100), rendering, illuminant_label(illuminant), str(observer),
                       exposure)
