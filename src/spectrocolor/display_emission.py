"""What the screen emits: the primaries' emission spectra and the light C(λ) for a code (step 4).

An application of the display layer (it needs spectra and colorimetry, which the colour trunk
under ``display/`` never imports).

SPECTRA's fourth step (seed 002): the integer codes (r, g, b) select excitation levels γ(code)
of the three phosphors, and the screen emits

    C(λ) = γ(r)·r_f(λ) + γ(g)·g_f(λ) + γ(b)·b_f(λ),

a light chromatically equivalent to the distribution shown in the graph: the metamer the
screen makes of every colour. Fig. 9 of the seed shows the emission functions r_f, g_f, b_f of
a typical display with the luminous efficiency ȳ(λ); Fig. 10 the excitation function γ.

**The emission spectra are data where data exist, models elsewhere.** The shape of every
primary is the measured spectral radiance of a typical CRT's P22-type phosphors (Brainard 1997,
``data/display_crt_brainard1997.csv``; chromaticities x, y = 0.619, 0.344 / 0.276, 0.605 /
0.151, 0.061, within 0.007 of SPECTRA's measured monitor). So that C(λ) is an exact metamer on
the grid in use, each measured shape is multiplied by the smooth positive factor
``exp(a + b·t + c·t²)``, ``t = (λ − 550 nm)/100 nm``, whose three coefficients make its CIE 1931
tristimulus values equal the display's primary (a column of ``RGBSpace.matrix_to_XYZ``)
exactly. For SPECTRA's monitor (the same kind of phosphors) the factor varies by at most a
factor 2.3 over 400-700 nm, mostly in the weak tails. sRGB's red is more saturated than this
CRT's: the only such factor rises ninefold towards 700 nm and lifts the phosphor's 705 nm
europium line, cut by the grid's edge, far above its 625 nm peak (a spike at 700 nm on the
page). A reshaped phosphor whose largest value lands on an edge of the grid, with a factor
varying more than threefold, is therefore replaced by a smooth model (sRGB's and Adobe RGB's
red): a band 10 nm beyond the primary's dominant wavelength, a weaker band 25 nm short of it and
a weak 450 nm band, in the non-negative amounts that make its XYZ exact. Where no
such factor exists (Display P3's red is beyond the CRT red phosphor; P3 displays are LCD/LED or
OLED, not CRTs) the shape is a model band, a Gaussian of σ = 10 nm at the primary's dominant
wavelength, reshaped in the same way. P3's red (x + y = 1.000) lies on the edge of the
spectrum locus, which no spectrum with any energy below 650 nm reaches exactly: its model band
misses by about 1.3e-4 in x or y, and :func:`emission_sources` says so, as it says which shape
each primary was made from. These are *model* spectra with the display's chromaticities (exact
except where stated), not measurements of that display.

Scale: a primary's values are relative to the equal-energy spectrum that has Y = 100 on the
grid, i.e. ``primaries.values @ weights(grid, illuminant="E")`` gives the primaries' XYZ on the
space's scale (Y = 100 for the white of sRGB/P3, 106.83 for SPECTRA's measured monitor). On
that scale SPECTRA's distribution ``levels / 30`` and the emitted light are directly comparable.

References
----------
P. Sällström (1999), USIP Report 99-05, STEP 2 (C(λ)), STEP 4, Figs. 9-11, Appendix.
D. H. Brainard (1997), The Psychophysics Toolbox, Spatial Vision 10, 433-436 (phosphor data);
G. M. Machado (2010), A model for simulation of color vision deficiency, UFRGS (tabulation).
"""

from __future__ import annotations

from functools import cache

import numpy as np

from .display.spaces import RGBSpace, rgb_space
from .display.transfer import LevelTable, from_codes
from .errors import ColorimetryError

__all__ = ["MEASURED_PRIMARIES", "measured_primaries", "primary_emission", "emission_sources",
           "emitted_light", "excitation_function"]

#: Name of the measured primaries every model spectrum is shaped from.
MEASURED_PRIMARIES = "typical CRT, P22 phosphors (Brainard 1997)"
_FIT_OBSERVER = "1931"  # display primaries are specified by CIE 1931 chromaticities
_BAND_SIGMA_NM = 10.0  # width of the model band used where no phosphor shape fits
_EXACT_XY = 1e-12  # a reshaped spectrum counts as exact below this chromaticity error
_NEAR_XY = 1e-3  # ... and is refused above this one
_EDGE_FACTOR = 3.0  # a reshaping factor varying more than this may not make a grid edge the peak
# A mixed model primary (where a reshaped phosphor would peak at the grid's edge): a band 10 nm
# beyond the dominant wavelength, a weaker band 25 nm short of it (σ 15 nm) and a weak short-wave
# band (450 nm, σ 15 nm), in the amounts that make its XYZ exact.
_MIX_OFFSETS_NM = (10.0, -25.0)
_SHORT = (450.0, 15.0)


def _grid(wavelengths_nm) -> np.ndarray:
    from .spectrum import wavelength_grid

    if wavelengths_nm is None:
        return wavelength_grid(400.0, 700.0, 10.0)
    wl = np.asarray(wavelengths_nm, dtype=float)
    if wl.ndim != 1 or wl.size < 3 or not np.all(np.isfinite(wl)) or np.any(np.diff(wl) <= 0):
        raise ColorimetryError(
            "wavelengths_nm: expected at least 3 finite wavelengths in increasing order (nm)")
    if wl[0] < 380.0 or wl[-1] > 780.0:
        raise ColorimetryError(
            f"wavelengths_nm: the measured primaries cover 380-780 nm, got {wl[0]:g}-{wl[-1]:g} "
            "nm (no extrapolation)")
    return wl


def measured_primaries(wavelengths_nm=None):
    """The measured CRT phosphor spectra (Brainard 1997) on a grid, as published (relative).

    Parameters
    ----------
    wavelengths_nm : array_like (K,), optional
        Within 380-780 nm (linear interpolation of the 5 nm table); default 400-700 nm at 10 nm.

    Returns
    -------
    Spectrum
        Values (3, K), names ``("red", "green", "blue")``, relative spectral radiance.

    Examples
    --------
    >>> s = measured_primaries([450.0, 530.0, 630.0])
    >>> [int(v) for v in s.values.argmax(axis=1)]   # red peaks at 630, green 530, blue 450
    [2, 1, 0]
    """
    from .data_tables import load_table
    from .spectrum import Spectrum

    wl = _grid(wavelengths_nm)
    _, table = load_table("display_crt_brainard1997.csv")
    values = np.array([np.interp(wl, table[:, 0], table[:, c]) for c in (1, 2, 3)])
    return Spectrum(wl, values, names=["red", "green", "blue"])


def _reshape(base: np.ndarray, W: np.ndarray, basis: np.ndarray, target: np.ndarray):
    """``base · exp(p @ basis)`` with XYZ nearest to target, and its chromaticity error."""
    from scipy.optimize import least_squares

    start = np.array([np.log(target[1] / (base @ W)[1]), 0.0, 0.0])

    def residual(p):
        return ((base * np.exp(p @ basis)) @ W - target) / target[1]

    fit = least_squares(residual, start, xtol=1e-15, ftol=1e-15, gtol=1e-15)
    spectrum = base * np.exp(fit.x @ basis)
    XYZ = spectrum @ W
    return spectrum, float(np.abs(XYZ[:2] / XYZ.sum() - target[:2] / target.sum()).max())


def _edge_spike(spectrum: np.ndarray, factor: np.ndarray) -> bool:
    """True where the reshaping made an edge of the grid the spectrum's peak: the largest value
    lies at the first or last wavelength and the factor varies by more than
    :data:`_EDGE_FACTOR` over the grid. (sRGB's red: the factor rises ninefold towards 700 nm and
    lifts the CRT's 705 nm europium line, cut by the grid's edge, above the 625 nm peak. A factor
    that barely changes the measured shape leaves the phosphor's own edge line as measured.)"""
    peak = int(np.argmax(spectrum))
    if 0 < peak < spectrum.size - 1:
        return False
    finite = factor[np.isfinite(factor) & (factor > 0)]
    return bool(finite.size and finite.max() / finite.min() > _EDGE_FACTOR)


def _band_mixture(dominant: float, wl: np.ndarray, W: np.ndarray, target: np.ndarray):
    """A smooth model primary with XYZ ``target``: a band just beyond the dominant wavelength
    (σ :data:`_BAND_SIGMA_NM`), a weaker one short of it and a weak short-wave band, in the
    non-negative amounts that make its XYZ exact (three shapes, three tristimulus values: one
    linear solve); None where an amount would be negative. It peaks inside the grid and falls
    smoothly to both edges."""
    main, side = (dominant + d for d in _MIX_OFFSETS_NM)
    shapes = np.stack([np.exp(-0.5 * ((wl - p) / s) ** 2)
                       for p, s in ((main, _BAND_SIGMA_NM), (side, 15.0), _SHORT)])
    try:
        amounts = np.linalg.solve((shapes @ W).T, target)
    except np.linalg.LinAlgError:
        return None
    if not np.all(amounts >= 0):
        return None
    return amounts @ shapes


@cache
def _fit(space: RGBSpace, grid: tuple) -> tuple[np.ndarray, tuple[str, ...]]:
    from .chromaticity import dominant_wavelength
    from .colorimetry import weights

    wl = np.asarray(grid)
    W = np.asarray(weights(wl, observer=_FIT_OBSERVER, illuminant="E"))
    measured = measured_primaries(wl).values
    t = (wl - 550.0) / 100.0
    basis = np.stack([np.ones_like(t), t, t * t])
    out = np.empty_like(measured)
    sources = []
    for c in range(3):
        target = space.matrix_to_XYZ[:, c]
        spectrum, error = _reshape(measured[c], W, basis, target)
        source = f"{MEASURED_PRIMARIES}, reshaped"
        spiked = error <= _EXACT_XY and _edge_spike(spectrum, spectrum / measured[c])
        if error > _EXACT_XY or spiked:
            # more saturated than the phosphor can be made, or made so only by raising a line at
            # the grid's edge into the spectrum's peak: a narrow band
            peak = float(dominant_wavelength(target[:2] / target.sum(), space.white_xy,
                                             _FIT_OBSERVER).wavelength_nm)
        mixed = _band_mixture(peak, wl, W, target) if spiked else None
        if mixed is not None:
            XYZ = mixed @ W
            spectrum, error = mixed, float(np.abs(XYZ[:2] / XYZ.sum() - target[:2] / target.sum()).max())
            source = (f"model bands at {peak + _MIX_OFFSETS_NM[0]:.0f}, {peak + _MIX_OFFSETS_NM[1]:.0f} "
                      f"and {_SHORT[0]:g} nm, mixed (the reshaped phosphor peaked at the grid's edge)")
        elif error > _EXACT_XY or spiked:
            band = np.exp(-0.5 * ((wl - peak) / _BAND_SIGMA_NM) ** 2)
            spectrum, error = _reshape(band, W, basis, target)
            source = f"model band at {peak:.0f} nm (σ {_BAND_SIGMA_NM:g} nm), reshaped"
            if error > _EXACT_XY:
                source += f"; chromaticity off by {error:.1e} (the primary is on the locus)"
        if error > _NEAR_XY:
            raise ColorimetryError(
                f"space {space.name!r}: no smooth spectrum on this grid has the chromaticity of "
                f"primary {'RGB'[c]}; its emission cannot be modelled")
        out[c] = spectrum
        sources.append(source)
    out.setflags(write=False)
    return out, tuple(sources)


def primary_emission(space="SPECTRA 7000K", wavelengths_nm=None):
    """Emission spectra of a display's R, G, B at full drive, exact in CIE 1931 XYZ (Fig. 9).

    Parameters
    ----------
    space : str or RGBSpace
        The display (:func:`~spectrocolor.display.spaces.rgb_space`).
    wavelengths_nm : array_like (K,), optional
        The grid (within 380-780 nm); default SPECTRA's 400-700 nm at 10 nm.

    Returns
    -------
    Spectrum
        Values (3, K), rows red, green, blue, on the scale of the module docstring:
        ``values @ weights(grid, illuminant="E")`` equals ``space.matrix_to_XYZ.T`` (CIE 1931).

    Examples
    --------
    >>> import numpy as np
    >>> from spectrocolor import weights
    >>> p = primary_emission("SPECTRA 7000K")
    >>> XYZ = p.values @ weights(p.wavelengths_nm, illuminant="E")
    >>> np.round(XYZ[0], 3).tolist()      # the seed's red phosphor: X, Y, Z = 44.68, 24.81, 2.586
    [44.68, 24.81, 2.586]
    """
    from .spectrum import Spectrum

    sp = rgb_space(space)
    wl = _grid(wavelengths_nm)
    return Spectrum(wl, _fit(sp, tuple(wl.tolist()))[0], names=["red", "green", "blue"])


def emission_sources(space="SPECTRA 7000K", wavelengths_nm=None) -> tuple[str, ...]:
    """Where each primary's spectrum in :func:`primary_emission` comes from (R, G, B).

    Parameters
    ----------
    space : str or RGBSpace, default "SPECTRA 7000K"
        The display.
    wavelengths_nm : array_like, shape (K,), optional
        The grid of the emission spectra, nm (as for :func:`primary_emission`).

    Returns
    -------
    tuple of str
        One description per primary (R, G, B).

    Examples
    --------
    >>> emission_sources("sRGB")[1]
    'typical CRT, P22 phosphors (Brainard 1997), reshaped'
    >>> emission_sources("sRGB")[0]
    "model bands at 621, 586 and 450 nm, mixed (the reshaped phosphor peaked at the grid's edge)"
    """
    sp = rgb_space(space)
    return _fit(sp, tuple(_grid(wavelengths_nm).tolist()))[1]


def excitation_function(space="SPECTRA 7000K", bit_depth: int | None = None):
    """The excitation function γ: fraction of full emission at every code (seed 002, Fig. 10).

    Parameters
    ----------
    space : str or RGBSpace
    bit_depth : int, optional
        Bits per code for curve transfers (default 8); a measured level table (SPECTRA's 64
        levels) uses its own levels.

    Returns
    -------
    codes : ndarray int (N,)
    emission : ndarray (N,)
        γ(code), 0 at code 0 and 1 at the top code.

    Examples
    --------
    >>> codes, g = excitation_function("SPECTRA 7000K")
    >>> len(codes), int(np.abs(g - 0.5).argmin())   # seed 002: 50 % excitation at level 46
    (64, 46)
    """
    sp = rgb_space(space)
    if isinstance(sp.transfer, LevelTable):
        if bit_depth not in (None, int(np.log2(sp.transfer.n_levels))):
            raise ColorimetryError(
                f"bit_depth: space {sp.name!r} has a table of {sp.transfer.n_levels} levels; "
                f"give None, got {bit_depth!r}")
        return np.arange(sp.transfer.n_levels), np.array(sp.transfer.levels)
    depth = 8 if bit_depth is None else bit_depth
    codes = np.arange(2 ** int(depth))
    return codes, np.asarray(sp.transfer.decode(from_codes(codes, depth)), dtype=float)


def emitted_light(codes, space="SPECTRA 7000K", wavelengths_nm=None, bit_depth=None):
    """The light the screen emits for integer codes: C(λ) = Σ γ(code)·primary(λ) (STEP 4).

    Parameters
    ----------
    codes : array_like int (..., 3)
        The r, g, b codes sent to the display (``Rendering.codes``).
    space : str or RGBSpace
    wavelengths_nm : array_like (K,), optional
        Default 400-700 nm at 10 nm.
    bit_depth : int, optional
        As in :func:`excitation_function` (``Rendering.bit_depth``).

    Returns
    -------
    Spectrum
        Values (..., K) on the scale of :func:`primary_emission`.

    Examples
    --------
    Full drive on every channel emits the white: its XYZ is the display's white.

    >>> import numpy as np
    >>> from spectrocolor import weights
    >>> c = emitted_light([63, 63, 63], "SPECTRA 7000K")
    >>> np.round(c.values @ weights(c.wavelengths_nm, illuminant="E"), 2).tolist()
    [98.88, 106.83, 121.11]
    """
    from .spectrum import Spectrum

    _, table = excitation_function(space, bit_depth)
    try:
        c = np.asarray(codes)
        valid = c.ndim >= 1 and c.shape[-1] == 3 and np.issubdtype(c.dtype, np.integer)
    except (TypeError, ValueError):
        valid = False
    if not valid:
        raise ColorimetryError(f"codes: expected integers of shape (..., 3), got {codes!r:.60}")
    if c.min() < 0 or c.max() >= table.size:
        raise ColorimetryError(f"codes: must lie in 0..{table.size - 1}, got {c.min()}..{c.max()}")
    primaries = primary_emission(space, wavelengths_nm)
    return Spectrum(primaries.wavelengths_nm, table[c] @ primaries.values)
