"""Relighting: an RGB image's colours under another light, through upsampled reflectances.

Each pixel's linear RGB becomes the reflectance of :func:`~spectrocolor.upsampling.upsample`
(exact under the table's illuminant), which is then seen under the new light. The spectra are
never materialised: the node colours under the new light form a 3-channel table
(:func:`~spectrocolor.upsampling.colours_under`), equal to the spectral route to rounding.

The result is shown on the table's display space with one of two viewing assumptions:

* ``adaptation=None``: the viewer stays adapted to the *original* light (the display white is
  that light's perfect white, as for the input): a white surface under a warmer lamp looks
  warm — what a camera with fixed white balance records;
* ``adaptation="bradford"`` (or another method of :func:`spectrocolor.adapt`): the viewer
  adapts to the *new* light (its perfect white becomes the display white); only the colour
  shifts that adaptation cannot undo remain (colour inconstancy).

With the new light equal to the table's illuminant, either way gives back the input colours.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..errors import ColorimetryError
from ..illuminants import illuminant_label, resolve_illuminant
from .apply import colours_under
from .table import UpsamplingTable

__all__ = ["Relit", "relight", "rgb_linear_from_image"]


def rgb_linear_from_image(image, space="sRGB") -> np.ndarray:
    """Linear RGB (0–1 for in-range codes) of an 8-bit (uint8) or 16-bit (uint16) image.

    Codes are divided by 255 or 65535 and decoded with the space's transfer function.
    Floating-point images are not guessed at: pass linear values to
    :func:`~spectrocolor.upsampling.upsample` directly.

    Parameters
    ----------
    image : array_like of uint8 or uint16, shape (..., 3)
        Encoded codes (``rgb8`` or 16-bit).
    space : str or RGBSpace, default "sRGB"
        The space whose transfer function decodes the codes.

    Returns
    -------
    numpy.ndarray, shape (..., 3)
        Linear RGB, 0–1.

    Raises
    ------
    ColorimetryError
        For another dtype or a last axis other than 3, or an unknown space.

    Examples
    --------
    >>> import numpy as np
    >>> rgb_linear_from_image(np.array([[0, 255, 188]], dtype=np.uint8)).round(4).tolist()
    [[0.0, 1.0, 0.5029]]
    """
    from ..display.spaces import rgb_space
    from ..display.transfer import from_codes

    codes = np.asarray(image)
    bits = {np.dtype(np.uint8): 8, np.dtype(np.uint16): 16}.get(codes.dtype)
    if bits is None or codes.ndim == 0 or codes.shape[-1] != 3:
        raise ColorimetryError(
            f"image: expected uint8 or uint16 codes of shape (..., 3), got {codes.dtype} "
            f"{codes.shape}; pass floating-point linear RGB to upsample() directly"
        )
    return np.asarray(rgb_space(space).transfer.decode(from_codes(codes, bits)), dtype=float)


@dataclass(frozen=True)
class Relit:
    """Result of :func:`relight`.

    Attributes
    ----------
    XYZ100 : ndarray (..., 3)
        Colours under the new light, on the display's scale (its white has Y = 100), ready for
        :func:`spectrocolor.render` on ``space``.
    rgb_linear : ndarray (..., 3)
        The same in the display space's linear RGB (may leave [0, 1]).
    exact : ndarray of bool (...)
        The pixel's reflectance reproduced its input colour exactly (see ``upsample``).
    illuminant, adaptation, space : str or None
    """

    XYZ100: np.ndarray
    rgb_linear: np.ndarray
    exact: np.ndarray
    illuminant: str
    adaptation: str | None
    space: str


def relight(table: UpsamplingTable, rgb_linear, illuminant, adaptation: str | None = None,
            space=None, out_of_range: str = "toward-grey") -> Relit:
    """Colours of an image's upsampled reflectances under another light.

    Parameters
    ----------
    table : UpsamplingTable
        Built on an RGB space for the light the image was taken under (e.g. ``"D65"``).
    rgb_linear : array_like (..., 3)
        Linear RGB of the table's space (see :func:`rgb_linear_from_image`).
    illuminant : str, float, Spectrum or Illuminant
        The new light, e.g. ``"A"``, ``"blackbody:3000"``, ``"D:5000"``; see :term:`illuminant`.
    adaptation : str or None
        None (default): viewer adapted to the original light; else a method of
        :func:`spectrocolor.adapt` (e.g. ``"bradford"``) for a viewer adapted to the new light.
    space : str or RGBSpace, optional
        Display space (default: the table's).
    out_of_range : str
        Strategy for colours the table cannot reproduce exactly (see ``upsample``).

    Returns
    -------
    Relit

    Examples
    --------
    >>> from spectrocolor.upsampling import upsampling_table
    >>> table = upsampling_table("sRGB", "D65", resolution=3, measure_excess=False)
    >>> same = relight(table, [[0.2, 0.4, 0.6]], "D65")
    >>> bool(abs(same.rgb_linear - [0.2, 0.4, 0.6]).max() < 1e-9)
    True
    >>> warm = relight(table, [[1.0, 1.0, 1.0]], "A").rgb_linear[0]   # white under A, unadapted
    >>> bool(warm[0] > 1 > warm[2])
    True
    """
    from ..colorimetry import weights
    from ..display.adaptation import adaptation_matrix
    from ..display.spaces import rgb_space

    if table.space == "XYZ" and space is None:
        raise ColorimetryError("space: an 'XYZ' table needs an RGB display space to relight on")
    display = rgb_space(table.space if space is None else space)
    light = resolve_illuminant(illuminant)  # once: the weights and the label take the value
    W_new = np.asarray(weights(table.wavelengths_nm, observer=_observer(table),
                               illuminant=light), dtype=float)
    XYZ, exact = colours_under(table, rgb_linear, W_new, out_of_range)
    seen_white = table.weights.sum(axis=0) if adaptation is None else W_new.sum(axis=0)
    method = "bradford" if adaptation is None else adaptation
    to_display = adaptation_matrix(seen_white, display.white_XYZ, method)
    XYZ_display = XYZ @ to_display.T
    label = illuminant_label(light)
    return Relit(XYZ_display, display.rgb_linear_from_XYZ(XYZ_display), exact, label,
                 adaptation, display.name)


def _observer(table: UpsamplingTable) -> str:
    """The table's observer label as :func:`spectrocolor.weights` accepts it."""
    from ..observers import canonical_observer_name

    try:
        return canonical_observer_name(table.observer)
    except ColorimetryError:
        raise ColorimetryError(
            f"table: its observer {table.observer!r} is not a built-in observer; relighting "
            "needs one"
        ) from None
