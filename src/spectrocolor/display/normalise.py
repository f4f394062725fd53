"""Normalisation: the one number that scales colorimetric RGB to display drive (1 = full).

Colour stimuli are normalised arbitrarily (seed 000), the display is not: its channels run from
0 to 1. The choices, all reported in a :class:`~spectrocolor.display.render.Rendering`:

* ``"none"`` -- the XYZ are already on the display's scale (``XYZ100``: Y = 100 is the white
  at full drive); scale 1.
* ``"fixed"`` -- one given scale for every colour (SPECTRA's alternative A). Take it from the
  brightest object colour the display must show (:func:`max_object_rgb`: the seed's
  R_max = 1.58) or from a white (:func:`white_scale`), so lightness relations are kept.
* ``"per-colour"`` -- each colour's largest channel becomes 1 (alternative B, "Optimised!"):
  chromaticity only, lightness relations are lost.
* ``"global-max"`` -- the largest channel over all given colours becomes 1 (Zawischa).

References
----------
P. Sällström (1999), USIP Report 99-05, STEP 2 (alternatives A and B) and note 10.
D. Zawischa, How to calculate and render colours -- thin films as an example, p. 6.
"""

from __future__ import annotations

import numpy as np

from ..arguments import real_array
from ..errors import ColorimetryError
from ..registry import Registry
from .spaces import rgb_space

__all__ = ["NORMALISATIONS", "normalise", "max_object_rgb", "white_scale"]

#: The normalisations of linear RGB before display (seed 002, normalisation alternatives).
NORMALISATIONS = Registry("normalise", "a normalisation")
NORMALISATIONS.add("none", "none", "use linear RGB as computed (1 = full drive)")
NORMALISATIONS.add("fixed", "fixed", "divide every colour by one given scale (the white's or the brightest object's)")
NORMALISATIONS.add("per-colour", "per-colour", "scale each colour so its largest channel is 1 (chromaticity only)")
NORMALISATIONS.add("global-max", "global-max", "scale all colours together so the largest channel of all is 1")


def normalise(rgb_linear, method: str, scale=None):
    """Divide ``(..., 3)`` linear RGB by the scale the method asks for.

    Parameters
    ----------
    rgb_linear : array_like, shape (..., 3)
        Linear RGB before normalisation.
    method : {"none", "fixed", "per-colour", "global-max"}
        A name in :data:`NORMALISATIONS` (see the module docstring).
    scale : float, optional
        Required for ``"fixed"`` (a positive divisor); refused for the other methods.

    Returns
    -------
    rgb_normalised : (..., 3)
    scale : float or ndarray (...,)
        The divisor used: a float, or one per colour for ``"per-colour"``. A colour whose
        largest channel is <= 0 (black, or not displayable by any positive scale) keeps scale 1
        under ``"per-colour"``; an input whose largest channel is <= 0 keeps scale 1 under
        ``"global-max"``.

    Raises
    ------
    ColorimetryError
        For an unknown method, ``"fixed"`` without a positive finite ``scale``, or ``scale``
        with another method.

    References
    ----------
    Seed 002 (Sällström 1999), STEP 2 (alternatives A and B); seed 000 (Zawischa), p. 6.

    Examples
    --------
    >>> rgb, scale = normalise([[0.2, 0.4, 0.8], [1.0, 0.5, 0.0]], "per-colour")
    >>> rgb.tolist(), scale.tolist()
    ([[0.25, 0.5, 1.0], [1.0, 0.5, 0.0]], [0.8, 1.0])
    >>> rgb, scale = normalise([[0.2, 0.4, 0.8]], "fixed", scale=1.58)  # SPECTRA's R_max
    >>> rgb.round(4).tolist(), scale
    ([[0.1266, 0.2532, 0.5063]], 1.58)
    """
    rgb = np.asarray(rgb_linear, dtype=float)
    method = NORMALISATIONS.canonical(method)
    if method == "fixed":
        if (scale is None or isinstance(scale, (str, bytes)) or np.ndim(scale) != 0
                or not np.isfinite(scale) or scale <= 0):
            raise ColorimetryError(
                f'normalise="fixed" needs scale, a positive number (e.g. max_object_rgb(...).max()'
                f" or white_scale(...)); got {scale!r}"
            )
        return rgb / float(scale), float(scale)
    if scale is not None:
        raise ColorimetryError(
            f'scale is used only with normalise="fixed"; normalise={method!r} computes its own'
        )
    if method == "none":
        return rgb.copy(), 1.0
    if method == "per-colour":
        top = rgb.max(axis=-1)
        per = np.where(top > 0, top, 1.0)
        return rgb / per[..., None], per
    top = float(np.nanmax(rgb)) if np.any(np.isfinite(rgb)) else 0.0
    g = top if top > 0 else 1.0
    return rgb / g, g


def max_object_rgb(space, weights) -> np.ndarray:
    """Largest linear R, G, B that any reflectance 0 <= f <= 1 can produce (seed 002, note 10).

    With ``XYZ = f @ weights`` and ``rgb = M @ XYZ``, each channel is ``f @ (weights @ M.T)``;
    over 0 <= f <= 1 its maximum is the sum of the positive entries of that column (take
    f = 1 where the entry is positive, 0 elsewhere: an ideal "optimal" reflectance).

    Parameters
    ----------
    space : RGBSpace or str
        The display (an RGBSpace or a built-in name).
    weights : array_like, shape (K, 3)
        Tristimulus weights on the space's XYZ scale, e.g.
        ``spectrocolor.weights(wavelengths_nm, observer, illuminant)`` (perfect white Y = 100).

    Returns
    -------
    ndarray (3,)
        Maximum R, G, B. Use ``.max()`` as the scale for ``normalise="fixed"`` (SPECTRA's
        alternative A: R_max = 1.58 for its monitor, 400-700 nm at 10 nm, equal energy).

    Raises
    ------
    ColorimetryError
        For weights that are not a finite (K, 3) array, or an unknown space.

    References
    ----------
    Seed 002 (Sällström 1999), STEP 2 and note 10 (alternative A, R_max = 1.58).

    Examples
    --------
    >>> from spectrocolor import wavelength_grid, weights
    >>> W = weights(wavelength_grid(400, 700, 10), illuminant="E")
    >>> max_object_rgb("SPECTRA 7000K", W).round(2).tolist()
    [1.58, 1.02, 0.92]
    """
    w = real_array(weights, "weights", "tristimulus weights (numbers, shape (K, 3))")
    if w.ndim != 2 or w.shape[1] != 3 or not np.all(np.isfinite(w)):
        raise ColorimetryError(f"weights must be a finite (K, 3) array, got shape {w.shape}")
    per_bin = w @ rgb_space(space).matrix_from_XYZ.T
    return np.where(per_bin > 0, per_bin, 0.0).sum(axis=0)


def white_scale(space, white_XYZ) -> float:
    """Scale that puts the largest channel of the given white at 1 (alternative A from a white).

    Parameters
    ----------
    space : RGBSpace or str
        The display (an RGBSpace or a built-in name).
    white_XYZ : array_like, shape (3,)
        XYZ of the white on the space's scale (e.g. ``white_point("A")``, Y = 100).

    Returns
    -------
    float
        The largest linear channel of the white: the divisor for ``normalise="fixed"``.

    Raises
    ------
    ColorimetryError
        For a malformed white or one that drives no channel positively.

    References
    ----------
    Seed 002 (Sällström 1999), STEP 2 (normalisation alternative A).

    Examples
    --------
    >>> from spectrocolor import white_point
    >>> round(white_scale("sRGB", white_point("A")), 4)  # illuminant A's white drives red to 1.85
    1.8454
    """
    w = real_array(white_XYZ, "white_XYZ", "the white's X, Y, Z (three numbers)")
    if w.shape != (3,) or not np.all(np.isfinite(w)):
        raise ColorimetryError(f"white_XYZ must be three finite numbers, got {white_XYZ!r}")
    top = float((rgb_space(space).matrix_from_XYZ @ w).max())
    if top <= 0:
        raise ColorimetryError(f"white_XYZ {w.tolist()} drives no channel positively")
    return top
