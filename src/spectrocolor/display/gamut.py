"""Out-of-gamut strategies for linear RGB: flag, clip, preserve-luminance, desaturate.

All functions take ``rgb_linear`` of shape ``(..., 3)`` (already normalised: 1 = full drive)
and return a new array of the same shape. A colour is *in gamut* when every channel lies in
[-tolerance, 1 + tolerance]; in-gamut colours are returned unchanged except that channels within
the tolerance band are set exactly to 0 or 1.

References
----------
D. Zawischa, How to calculate and render colours -- thin films as an example, eqs. 20-21.
P. Sällström (1999), USIP Report 99-05, STEP 3 ("cannot be reproduced").
"""

from __future__ import annotations

import numpy as np

from ..coordinates import colour_array
from ..registry import Registry

__all__ = [
    "GAMUT_STRATEGIES",
    "DEFAULT_GAMUT",
    "DEFAULT_TOLERANCE",
    "gamut_flags",
    "apply_gamut",
    "flag_black",
    "clip",
    "preserve_luminance",
    "desaturate",
]


#: Channels within this distance of [0, 1] count as in gamut (absorbs round-off such as the
#: 1 + 2e-16 that the white of a space can produce).
DEFAULT_TOLERANCE = 1e-9


def _rgb(rgb_linear) -> np.ndarray:
    return colour_array(rgb_linear, "rgb_linear", 3, "linear R, G, B")


def gamut_flags(rgb_linear, tolerance: float = DEFAULT_TOLERANCE):
    """Per-channel flags ``negative`` and ``over`` (> 1) and per-colour ``in_gamut``.

    Parameters
    ----------
    rgb_linear : array_like, shape (..., 3)
        Normalised linear RGB (1 = full drive).
    tolerance : float, default DEFAULT_TOLERANCE
        Channels within this distance of [0, 1] count as in gamut (and are snapped to 0 or 1).

    Returns
    -------
    in_gamut : ndarray bool (...,)
        Every channel within [-tolerance, 1 + tolerance].
    negative : ndarray bool (..., 3)
        Channels below -tolerance.
    over : ndarray bool (..., 3)
        Channels above 1 + tolerance.

    NaN channels are neither negative nor over; a colour with NaN is not in gamut.

    Examples
    --------
    >>> in_gamut, negative, over = gamut_flags([[0.5, 0.5, 0.5], [0.9, -0.05, -0.02]])
    >>> in_gamut.tolist(), negative[1].tolist()
    ([True, False], [False, True, True])
    """
    rgb = _rgb(rgb_linear)
    negative = rgb < -tolerance
    over = rgb > 1 + tolerance
    in_gamut = ~(negative | over).any(axis=-1) & ~np.isnan(rgb).any(axis=-1)
    return in_gamut, negative, over


def _snap(rgb: np.ndarray, tolerance: float) -> np.ndarray:
    out = rgb.copy()
    out[(out < 0) & (out >= -tolerance)] = 0.0
    out[(out > 1) & (out <= 1 + tolerance)] = 1.0
    return out


def _inside(rgb: np.ndarray) -> np.ndarray:
    return np.asarray(((rgb >= 0) & (rgb <= 1)).all(axis=-1, keepdims=True))


def flag_black(rgb_linear, tolerance: float = DEFAULT_TOLERANCE) -> np.ndarray:
    """SPECTRA's strategy: out-of-gamut colours are shown black (seed 002, STEP 3).

    Parameters
    ----------
    rgb_linear : array_like, shape (..., 3)
        Normalised linear RGB (1 = full drive).
    tolerance : float, default DEFAULT_TOLERANCE
        Channels within this distance of [0, 1] count as in gamut (and are snapped to 0 or 1).

    Returns
    -------
    numpy.ndarray, shape (..., 3)
        In-gamut colours unchanged, the others (0, 0, 0): "cannot be reproduced".

    Examples
    --------
    >>> from spectrocolor import rgb_space
    >>> colours = [[0.5, 0.5, 0.5], [0.9, -0.05, -0.02], [1.2, 0.5, 0.1]]
    >>> flag_black(colours).tolist()
    [[0.5, 0.5, 0.5], [0.0, 0.0, 0.0], [0.0, 0.0, 0.0]]
    """
    rgb = _snap(_rgb(rgb_linear), tolerance)
    in_gamut, _, _ = gamut_flags(rgb, tolerance)
    return np.where(in_gamut[..., None], rgb, 0.0)


def clip(rgb_linear, tolerance: float = DEFAULT_TOLERANCE) -> np.ndarray:
    """Each channel clipped to [0, 1] independently (changes hue, saturation and luminance).

    Parameters
    ----------
    rgb_linear : array_like, shape (..., 3)
        Normalised linear RGB (1 = full drive).
    tolerance : float, default DEFAULT_TOLERANCE
        Channels within this distance of [0, 1] count as in gamut (and are snapped to 0 or 1).

    Returns
    -------
    numpy.ndarray, shape (..., 3)
        Channels in [0, 1].

    Examples
    --------
    >>> from spectrocolor import rgb_space
    >>> colours = [[0.5, 0.5, 0.5], [0.9, -0.05, -0.02], [1.2, 0.5, 0.1]]
    >>> clip(colours).tolist()
    [[0.5, 0.5, 0.5], [0.9, 0.0, 0.0], [1.0, 0.5, 0.1]]
    """
    return np.clip(_snap(_rgb(rgb_linear), tolerance), 0.0, 1.0)


def preserve_luminance(rgb_linear, luminance_row, tolerance: float = DEFAULT_TOLERANCE):
    """Zawischa's eqs. 20-21 for any number of negative channels at once, then clip above 1.

    Negative channels are set to 0 and the remaining channels are multiplied by
    ``Y / (Y - sum_neg Y_c c) = Y / sum_pos Y_c c`` so that the luminance
    ``Y = Y_R R + Y_G G + Y_B B`` is kept exactly. The seed's Fortran applies the correction
    inside its channel loop, after the earlier channels have already been encoded and written,
    so a negative green or blue no longer rescales red (and green): e.g. linear
    (0.9, -0.05, -0.02) in sRGB comes out 24 % too bright there. Here all negative channels
    are handled in one step before anything is encoded. A colour whose luminance is <= 0
    becomes black. Channels that exceed 1 after the correction are clipped to 1; only then is
    Y not kept (reported by the caller through ``over``).

    Parameters
    ----------
    rgb_linear : array_like, shape (..., 3)
        Normalised linear RGB (1 = full drive).
    luminance_row : array_like, shape (3,)
        Y of each primary at full drive (``RGBSpace.luminance_row``); any positive scale.
    tolerance : float, default DEFAULT_TOLERANCE
        Channels within this distance of [0, 1] count as in gamut (and are snapped to 0 or 1).

    Returns
    -------
    numpy.ndarray, shape (..., 3)
        Channels in [0, 1]; Y kept unless a channel had to be clipped above 1.

    References
    ----------
    Seed 000 (Zawischa), eqs. 20–21.

    Examples
    --------
    >>> from spectrocolor import rgb_space
    >>> colours = [[0.5, 0.5, 0.5], [0.9, -0.05, -0.02], [1.2, 0.5, 0.1]]
    >>> row = rgb_space("sRGB").luminance_row
    >>> mapped = preserve_luminance(colours, row)
    >>> mapped.round(4).tolist()
    [[0.5, 0.5, 0.5], [0.725, 0.0, 0.0], [1.0, 0.5, 0.1]]
    >>> (mapped @ row).round(4).tolist()  # Y of the second colour kept (15.4173)
    [50.0, 15.4173, 57.7443]
    """
    rgb = _snap(_rgb(rgb_linear), tolerance)
    y_c = np.asarray(luminance_row, dtype=float)
    contributions = rgb * y_c
    Y = contributions.sum(axis=-1, keepdims=True)
    positive_part = np.where(rgb > 0, contributions, 0.0).sum(axis=-1, keepdims=True)
    with np.errstate(all="ignore"):
        factor = np.where((Y > 0) & (positive_part > 0), Y / positive_part, 0.0)
    out = np.clip(np.where(rgb > 0, rgb * factor, 0.0), 0.0, 1.0)
    return np.where(_inside(rgb), rgb, out)


def desaturate(rgb_linear, luminance_row, tolerance: float = DEFAULT_TOLERANCE):
    """Move toward the white at constant luminance, the least distance that reaches the gamut.

    The result is ``(1 - t) c + t g (1, 1, 1)`` with ``g = Y / Y_white`` (the grey of the same
    luminance) and the smallest ``t`` in [0, 1] that puts every channel in [0, 1]. Because the
    mixture is linear in XYZ, Y is unchanged and the chromaticity moves on the straight line to
    the white point, so the hue angle about the white (in xy, u'v' or any linear opponent
    space) is kept. Exact and closed-form per channel:
    a channel ``c < 0`` needs ``t >= -c / (g - c)``, a channel ``c > 1`` needs
    ``t >= (c - 1) / (c - g)``.

    Colours darker than black (Y <= 0) become black and colours brighter than the white
    (Y > Y_white) become the white: no in-gamut colour has their luminance.

    Parameters
    ----------
    rgb_linear : array_like, shape (..., 3)
        Normalised linear RGB (1 = full drive).
    luminance_row : array_like, shape (3,)
        Y of each primary at full drive (``RGBSpace.luminance_row``); any positive scale.
    tolerance : float, default DEFAULT_TOLERANCE
        Channels within this distance of [0, 1] count as in gamut (and are snapped to 0 or 1).

    Returns
    -------
    numpy.ndarray, shape (..., 3)
        Channels in [0, 1], with the input's luminance and hue (chromaticity on the line to the
        white point).

    Examples
    --------
    >>> from spectrocolor import rgb_space
    >>> colours = [[0.5, 0.5, 0.5], [0.9, -0.05, -0.02], [1.2, 0.5, 0.1]]
    >>> row = rgb_space("sRGB").luminance_row
    >>> mapped = desaturate(colours, row)
    >>> mapped.round(4).tolist()
    [[0.5, 0.5, 0.5], [0.7174, 0.0, 0.0227], [1.0, 0.5414, 0.2793]]
    >>> (mapped @ row).round(4).tolist()  # every Y kept
    [50.0, 15.4173, 61.997]
    """
    rgb = _snap(_rgb(rgb_linear), tolerance)
    y_c = np.asarray(luminance_row, dtype=float)
    g = (rgb @ y_c / y_c.sum())[..., None]
    with np.errstate(all="ignore"):
        t_low = np.where(rgb < 0, -rgb / (g - rgb), 0.0)
        t_high = np.where(rgb > 1, (rgb - 1) / (rgb - g), 0.0)
    t = np.clip(np.maximum(t_low, t_high).max(axis=-1, keepdims=True), 0.0, 1.0)
    out = (1 - t) * rgb + t * g
    out = np.where(g <= 0, 0.0, np.where(g >= 1, 1.0, out))
    # the exact solution lands on the cube's faces; remove round-off beyond them
    return np.where(_inside(rgb), rgb, np.clip(out, 0.0, 1.0))


#: The gamut strategies: name → function (rgb_linear, luminance_row, tolerance) → rgb_linear.
#: Each entry carries everything an interface shows: the description (help texts), the label
#: (the explorer's select box) and ``extra["action"]``, what was done to a colour
#: (:func:`spectrocolor.display.explain.explain`). A new strategy is one ``add`` here.
GAMUT_STRATEGIES = Registry("gamut", "a gamut strategy")
GAMUT_STRATEGIES.add(
    "flag", lambda rgb, row, tol: flag_black(rgb, tol),
    "show colours the display cannot reproduce as black (SPECTRA's 'cannot be reproduced')",
    label="SPECTRA: cannot be reproduced", extra={"action": "shown black"},
)
GAMUT_STRATEGIES.add(
    "clip", lambda rgb, row, tol: clip(rgb, tol), "clip each channel to [0, 1] (hue and luminance may shift)",
    label="clip channels", extra={"action": "each channel clipped to 0-1"},
)
GAMUT_STRATEGIES.add(
    "preserve-luminance", preserve_luminance,
    "set negative channels to 0 and scale the others to keep luminance (Zawischa eqs. 20-21), then clip above 1",
    label="keep luminance", extra={"action": "negative channels set to 0 at constant luminance"},
)
GAMUT_STRATEGIES.add(
    "desaturate", desaturate, "move towards the grey of equal luminance along constant hue: the least change",
    label="desaturate (keep hue and luminance)",
    extra={"action": "desaturated toward the white at constant luminance (hue kept)"},
)


#: The strategy used wherever the caller names none (the command line, the explorer, reports):
#: the least change of a colour a display cannot show, so no demonstration is a bare black
#: patch. SPECTRA's strict ``"flag"`` and seed 000's ``"preserve-luminance"`` are a choice away.
DEFAULT_GAMUT = "desaturate"


def apply_gamut(
    rgb_linear, strategy: str, luminance_row, tolerance: float = DEFAULT_TOLERANCE
) -> np.ndarray:
    """Apply one of :data:`GAMUT_STRATEGIES` to ``(..., 3)`` linear RGB.

    Parameters
    ----------
    rgb_linear : array_like, shape (..., 3)
        Normalised linear RGB (1 = full drive).
    strategy : str
        A name in :data:`GAMUT_STRATEGIES`.
    luminance_row : array_like, shape (3,)
        The Y row of the display's RGB → XYZ matrix (used by the luminance-keeping strategies).
    tolerance : float
        Channels within this distance of [0, 1] count as in gamut.

    Returns
    -------
    numpy.ndarray
        Linear RGB in [0, 1], shape (..., 3).

    Examples
    --------
    >>> apply_gamut([[1.2, 0.5, -0.1]], "clip", [0.2126, 0.7152, 0.0722]).tolist()
    [[1.0, 0.5, 0.0]]
    """
    return GAMUT_STRATEGIES.get(strategy)(rgb_linear, luminance_row, tolerance)
