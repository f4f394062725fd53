"""``render``: CIE XYZ to display drive values, with every decision reported.

The chain (seed 002, STEPS 2-3; seed 000, eqs. 19-24): XYZ -> linear RGB of the space
-> normalisation -> gamut strategy -> transfer (encoding) -> integer codes.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .. import notebook_hooks
from ..coordinates import colour_array
from ..errors import ColorimetryError
from .gamut import DEFAULT_GAMUT, DEFAULT_TOLERANCE, GAMUT_STRATEGIES, apply_gamut, gamut_flags
from .normalise import normalise as _normalise
from .spaces import rgb_space
from .transfer import LevelTable, to_codes

__all__ = ["Rendering", "render"]


@dataclass(frozen=True)
class Rendering:
    """What :func:`render` produced and what it did.

    Attributes
    ----------
    rgb_linear : ndarray (..., 3)
        Linear drive values after normalisation and the gamut strategy, in [0, 1].
    rgb_encoded : ndarray (..., 3)
        After the space's transfer function, in [0, 1].
    codes : ndarray (..., 3) int64
        Integer codes: ``round(rgb_encoded * (2**bit_depth - 1))``, or the level index for a
        measured level table.
    in_gamut : ndarray bool (...,)
        Whether the normalised colour was displayable as it is (every channel in [0, 1]).
    negative, over : ndarray bool (..., 3)
        Which channels were < 0 and > 1 after normalisation (SPECTRA names the negative one).
    rgb_unmapped : ndarray (..., 3)
        Normalised linear RGB before the gamut strategy (may lie outside [0, 1]).
    gamut, normalise : str
        The strategy and normalisation used.
    scale : float or ndarray (...,)
        Divisor applied to the space's linear RGB (one per colour for ``"per-colour"``).
    space : str
        Name of the RGB space.
    bit_depth : int
        Bits per code (6 for SPECTRA's 64-level table).

    Examples
    --------
    >>> r = render([[20.0, 21.0, 22.0], [1.0, 60.0, 5.0]], gamut="clip")
    >>> r.hex.tolist(), r.in_gamut.tolist()
    (['#807e7c', '#00ff00'], [True, False])
    >>> r.negative[1].tolist(), r.gamut, r.normalise, r.space, r.bit_depth
    ([True, False, True], 'clip', 'none', 'sRGB', 8)
    """

    rgb_linear: np.ndarray
    rgb_encoded: np.ndarray
    codes: np.ndarray
    in_gamut: np.ndarray
    negative: np.ndarray
    over: np.ndarray
    rgb_unmapped: np.ndarray
    gamut: str
    normalise: str
    scale: float | np.ndarray
    space: str
    bit_depth: int

    _repr_html_, _repr_svg_, __repr__ = notebook_hooks.html, notebook_hooks.svg, notebook_hooks.text  # notebooks

    def explain(self) -> list[str]:
        """One line per colour: "in gamut" or "cannot be reproduced (…): what was done".

        See :func:`spectrocolor.display.explain.explain` (the one text every interface shows).

        Returns
        -------
        list of str
            One line per colour, in the order of the flattened batch.

        Examples
        --------
        >>> render([[1.0, 60.0, 5.0]], "sRGB", gamut="flag").explain()
        ['cannot be reproduced (R, B negative; G above 1): shown black']
        """
        from .explain import explain

        return explain(self)

    @property
    def hex(self) -> np.ndarray:
        """``"#rrggbb"`` strings (...,) for 8-bit renderings."""
        if self.bit_depth != 8:
            raise ColorimetryError(f"hex needs bit_depth 8, this rendering has {self.bit_depth}")
        c = self.codes.reshape(-1, 3)
        out = np.array([f"#{r:02x}{g:02x}{b:02x}" for r, g, b in c.tolist()], dtype=object)
        return out.reshape(self.codes.shape[:-1])


def render(
    XYZ100,
    space="sRGB",
    normalise: str = "none",
    gamut: str = DEFAULT_GAMUT,
    scale: float | None = None,
    bit_depth: int | None = None,
    tolerance: float = DEFAULT_TOLERANCE,
) -> Rendering:
    """Turn CIE XYZ into display drive values and codes, reporting what was done.

    Parameters
    ----------
    XYZ100 : array_like, shape (..., 3)
        Tristimulus values on the space's scale: for ``normalise="none"``, Y = 100 is the
        display's white at full drive (for measured spaces, the scale of their table).
    space : str or RGBSpace
        See :func:`~spectrocolor.display.spaces.rgb_space`.
    normalise : {"none", "fixed", "per-colour", "global-max"}
        See :mod:`spectrocolor.display.normalise`.
    gamut : {"flag", "clip", "preserve-luminance", "desaturate"}, default DEFAULT_GAMUT
        :data:`~spectrocolor.display.gamut.DEFAULT_GAMUT` is ``"desaturate"``.
        ``"flag"`` shows out-of-gamut colours black (SPECTRA: "cannot be reproduced");
        ``"clip"`` clips each channel; ``"preserve-luminance"`` zeroes negative channels and
        rescales the others to keep Y (Zawischa eqs. 20-21, all negatives at once);
        ``"desaturate"`` moves toward the white at constant Y (hue kept).
    scale : float, optional
        The divisor for ``normalise="fixed"``.
    bit_depth : int, optional
        Bits per integer code. Default: 8 for curve transfers; a measured level table uses its
        own levels (64 levels = 6 bits) and refuses any other depth.
    tolerance : float, default DEFAULT_TOLERANCE
        Channels within this distance of [0, 1] count as in gamut.

    Returns
    -------
    Rendering
        Drive values, encoded values and codes of shape ``(..., 3)``, per-colour flags, and the
        normalisation, scale, gamut strategy, space and bit depth that were used.

    Raises
    ------
    ColorimetryError
        For NaN or infinite XYZ, an unknown space, normalisation or gamut strategy, a missing or
        superfluous ``scale``, or a ``bit_depth`` a measured level table cannot give.

    References
    ----------
    Seed 002 (Sällström 1999), STEPS 2–3 ("cannot be reproduced"); seed 000 (Zawischa),
    eqs. 19–24.

    Examples
    --------
    >>> r = render([[20.0, 21.0, 22.0], [1.0, 60.0, 5.0]], space="sRGB", gamut="flag")
    >>> r.codes.tolist(), r.in_gamut.tolist()
    ([[128, 126, 124], [0, 0, 0]], [True, False])

    The CIE D65 white (95.047, 100, 108.883) is *not* exactly sRGB's white (which is defined by
    x, y = 0.3127, 0.3290): its red channel is 1.00016, out of gamut. Adapt reflectance colours
    to ``space.white_XYZ`` (:func:`~spectrocolor.display.adaptation.adapt`) or use a tolerance.
    """
    sp = rgb_space(space)
    XYZ = colour_array(XYZ100, "XYZ100", 3, "tristimulus values X, Y, Z")
    if not np.all(np.isfinite(XYZ)):
        raise ColorimetryError("XYZ100 contains NaN or infinite values; nothing can be displayed")
    gamut = GAMUT_STRATEGIES.canonical(gamut)
    table = sp.transfer if isinstance(sp.transfer, LevelTable) else None
    if table is not None:
        native = int(np.log2(table.n_levels))
        if 2**native != table.n_levels or bit_depth not in (None, native):
            raise ColorimetryError(
                f"space {sp.name!r} encodes with a table of {table.n_levels} levels; "
                f"bit_depth must be None or {native}, got {bit_depth!r}"
            )
        depth = native
    else:
        depth = 8 if bit_depth is None else bit_depth

    rgb, used_scale = _normalise(sp.rgb_linear_from_XYZ(XYZ), normalise, scale)
    in_gamut, negative, over = gamut_flags(rgb, tolerance)
    mapped = apply_gamut(rgb, gamut, sp.luminance_row, tolerance)
    encoded = sp.transfer.encode(mapped)
    codes = table.index(mapped) if table is not None else to_codes(encoded, depth)
    return Rendering(
        rgb_linear=mapped,
        rgb_encoded=encoded,
        codes=codes.astype(np.int64),
        in_gamut=in_gamut,
        negative=negative,
        over=over,
        rgb_unmapped=rgb,
        gamut=gamut,
        normalise=normalise,
        scale=used_scale,
        space=sp.name,
        bit_depth=depth,
    )
