"""The linear display chain of SPECTRA's explorer: XYZ → the XYZ a display is asked to show → RGB.

One set of choices -- a display, a normalisation of the chain (:data:`CHAIN_NORMALISATIONS`) and a
way of showing the reference white (:data:`WHITE_ADAPTATIONS`) -- gives one
:class:`DisplayChain`: SPECTRA's per-channel factors k (``"spectra-exact"``), the adaptation of
the equal-energy white E to the display's white, the effective XYZ → linear RGB matrix and the
divisor of normalisation A. :meth:`DisplayChain.render` then renders colours through it with any
gamut strategy of :data:`~spectrocolor.display.gamut.GAMUT_STRATEGIES`.

The chain takes summation weights (``XYZ = f @ W``), not observers and illuminants: those are
resolved by the caller (:func:`spectrocolor.colorimetry.weights`), so this module needs only the
display modules.

References
----------
P. Sällström (1999), USIP Report 99-05, STEP 1-3, note 10 and "Why not include the effect of
chromatic adaptation?" (matris.equ).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..arguments import real_array
from ..errors import ColorimetryError
from ..registry import Registry
from .adaptation import adaptation_matrix
from .normalise import max_object_rgb
from .render import Rendering, render
from .spaces import RGBSpace, rgb_space
from .spectra_exact import spectra_channel_factors, spectra_scale

__all__ = [
    "CHAIN_NORMALISATIONS",
    "DEFAULT_CHAIN_NORMALISATION",
    "DEFAULT_WHITE_ADAPTATION",
    "WHITE_ADAPTATIONS",
    "DisplayChain",
    "display_chain",
]

#: How the chain scales colours to display drive, the default first: SPECTRA's alternative A
#: exact (the largest channel any object can drive), B per colour ("Optimised!"), and A as the
#: program computed it (one k per channel, 1.32 × R_white; ``display.spectra_exact``). The value is
#: the normalisation :func:`~spectrocolor.display.render.render` applies; ``label`` and
#: ``extra["help"]`` are the explorer's select box and its tooltip.
CHAIN_NORMALISATIONS = Registry("normalise", "a normalisation of the display chain")
CHAIN_NORMALISATIONS.add(
    "fixed", "fixed", "one scale for all colours: the largest channel any reflectance 0-1 can drive",
    label="A · fixed scale",
    extra={"help": "One scale for all colours: the largest channel any distribution can drive "
                   "(lightness relations kept)."},
)
CHAIN_NORMALISATIONS.add(
    "per-colour", "per-colour", "each colour scaled so that its largest channel is 1 (chromaticity only)",
    label="B · per colour (Optimised!)",
    extra={"help": "Every colour as bright as the display allows: only its chromaticity is kept."},
)
CHAIN_NORMALISATIONS.add(
    "spectra-exact", "fixed", "SPECTRA's own numbers: one factor k per channel, 1.32 × the white's largest channel",
    label="A · as SPECTRA computed it",
    extra={"help": "The program's own numbers: 1.32 × the white's largest channel, one factor k per "
                   "channel from its step 1."},
)
#: The normalisation wherever none is named (the explorer's first choice).
DEFAULT_CHAIN_NORMALISATION = "fixed"

#: How the equal-energy white E is shown, the default first: adapted to the display's white by a
#: transform of :data:`~spectrocolor.display.adaptation.ADAPTATION_METHODS` (the value; Bradford, or
#: SPECTRA's matris.equ way: scaling the display's own R, G, B), or as it is (``None``).
WHITE_ADAPTATIONS = Registry("adaptation", "a way of showing the reference white")
WHITE_ADAPTATIONS.add(
    "bradford", "bradford",
    "the equal-energy white E is shown as the display's white; colours adapted by the Bradford "
    "transform, so a neutral looks neutral",
    label="Bradford (E → display white)",
)
WHITE_ADAPTATIONS.add(
    "display rgb", "display rgb",
    "the display's own R, G, B scaled so that E gives R = G = B (seed 002, 'Why not include the "
    "effect of chromatic adaptation?')",
    label="SPECTRA matris.equ",
)
WHITE_ADAPTATIONS.add(
    "none", None,
    "colorimetrically exact for a viewer adapted to E, not to the screen: E looks pinkish on a D65 display",
    label="none (unadapted)",
)
#: The adaptation wherever none is named (the explorer's first choice).
DEFAULT_WHITE_ADAPTATION = "bradford"


@dataclass(frozen=True)
class DisplayChain:
    """The linear part of the display chain for one set of choices (:func:`display_chain`).

    Attributes
    ----------
    weights : numpy.ndarray, shape (K, 3)
        The summation weights the chain was made for (``XYZ = f @ weights``).
    channel_factors : numpy.ndarray, shape (3,)
        SPECTRA's per-channel k relative to CIE's one k (``"spectra-exact"``), else ones.
    adaptation_matrix : numpy.ndarray, shape (3, 3)
        The adaptation of E to the display's white (identity for ``"none"``).
    to_display : numpy.ndarray, shape (3, 3)
        XYZ → the XYZ the display is asked to show: ``adaptation_matrix @ diag(channel_factors)``.
    matrix_from_XYZ : numpy.ndarray, shape (3, 3)
        The effective XYZ → linear RGB: the display's matrix @ ``to_display``.
    scale : float or None
        The divisor of normalisation A; None for ``"per-colour"``.
    space : RGBSpace
        The display.
    normalise : str
        A name in :data:`CHAIN_NORMALISATIONS`.
    adaptation : str
        A name in :data:`WHITE_ADAPTATIONS`.

    Examples
    --------
    >>> W = np.full((31, 3), 100 / 31)
    >>> chain = display_chain("sRGB", W, W, normalise="per-colour", adaptation="none")
    >>> chain.scale is None, chain.to_display.tolist() == np.eye(3).tolist()
    (True, True)
    """

    weights: np.ndarray
    channel_factors: np.ndarray
    adaptation_matrix: np.ndarray
    to_display: np.ndarray
    matrix_from_XYZ: np.ndarray
    scale: float | None
    space: RGBSpace
    normalise: str
    adaptation: str

    def shown_XYZ(self, XYZ) -> np.ndarray:
        """The XYZ the display is asked to show for ``(..., 3)`` XYZ (after k and the adaptation).

        Parameters
        ----------
        XYZ : array_like, shape (..., 3)
            Colours on the weights' scale (``f @ weights``).

        Returns
        -------
        numpy.ndarray, shape (..., 3)

        Examples
        --------
        >>> W = np.full((31, 3), 100 / 31)
        >>> chain = display_chain("sRGB", W, W, adaptation="none")
        >>> chain.shown_XYZ([[10.0, 20.0, 30.0]]).tolist()
        [[10.0, 20.0, 30.0]]
        """
        return np.asarray(XYZ, dtype=float) @ self.to_display.T

    def render(self, XYZ, gamut: str) -> Rendering:
        """Render ``(..., 3)`` XYZ through the chain with one gamut strategy.

        Parameters
        ----------
        XYZ : array_like, shape (..., 3)
            Colours on the weights' scale (``f @ weights``), before the chain.
        gamut : str
            A name in :data:`~spectrocolor.display.gamut.GAMUT_STRATEGIES`.

        Returns
        -------
        Rendering
            As :func:`~spectrocolor.display.render.render` gives it for :meth:`shown_XYZ`,
            normalised as the chain's normalisation asks.

        Examples
        --------
        >>> W = np.full((31, 3), 100 / 31)
        >>> chain = display_chain("sRGB", W, W, normalise="per-colour", adaptation="none")
        >>> chain.render([[1.0, 60.0, 5.0]], "clip").in_gamut.tolist()
        [False]
        """
        method = CHAIN_NORMALISATIONS.get(self.normalise)
        return render(self.shown_XYZ(XYZ), self.space, normalise=method, gamut=gamut, scale=self.scale)


def _white_adaptation(source_white: np.ndarray, space: RGBSpace, adaptation: str) -> np.ndarray:
    method = WHITE_ADAPTATIONS.get(adaptation)
    if method is None:
        return np.eye(3)
    target = space.white_XYZ * (source_white[1] / space.white_XYZ[1])
    return adaptation_matrix(source_white, target, method, space if method == "display rgb" else None)


def display_chain(
    space,
    weights,
    weights_E,
    *,
    normalise: str = DEFAULT_CHAIN_NORMALISATION,
    adaptation: str = DEFAULT_WHITE_ADAPTATION,
) -> DisplayChain:
    """The linear display chain for one display, one set of weights and one set of choices.

    Parameters
    ----------
    space : RGBSpace or str
        The display (a name of :data:`~spectrocolor.display.spaces.RGB_SPACES` or a space).
    weights : array_like, shape (K, 3)
        Summation weights of the reference light the colours are seen under, perfect white
        Y = 100 (``spectrocolor.colorimetry.weights(grid, illuminant=...)``); normalisation A's
        divisor is the largest channel any factor 0 <= f <= 1 drives through them.
    weights_E : array_like, shape (K, 3)
        The same for the equal-energy light E on the same grid: its white is the one adapted to
        the display's white, and it defines SPECTRA's per-channel k.
    normalise : str, keyword-only
        A name in :data:`CHAIN_NORMALISATIONS` (default :data:`DEFAULT_CHAIN_NORMALISATION`).
    adaptation : str, keyword-only
        A name in :data:`WHITE_ADAPTATIONS` (default :data:`DEFAULT_WHITE_ADAPTATION`).

    Returns
    -------
    DisplayChain

    Raises
    ------
    ColorimetryError
        For an unknown name, weights that are not (K, 3) finite numbers or of different shapes,
        or whites the adaptation cannot use.

    Examples
    --------
    >>> W = np.full((31, 3), 100 / 31)      # a flat stand-in: E's white is X = Y = Z = 100
    >>> chain = display_chain("sRGB", W, W, normalise="spectra-exact", adaptation="bradford")
    >>> chain.channel_factors.round(6).tolist()
    [1.0, 1.0, 1.0]
    >>> bool(np.allclose(chain.to_display @ [100.0, 100.0, 100.0], rgb_space("sRGB").white_XYZ))
    True
    """
    normalise = CHAIN_NORMALISATIONS.canonical(normalise)
    adaptation = WHITE_ADAPTATIONS.canonical(adaptation)
    display = rgb_space(space)
    W = real_array(weights, "weights", "summation weights (K, 3)")
    W_E = real_array(weights_E, "weights_E", "summation weights (K, 3)")
    if W.ndim != 2 or W.shape[-1] != 3 or W.shape != W_E.shape:
        raise ColorimetryError(
            f"weights and weights_E must be summation weights of one shape (K, 3), got {W.shape} and {W_E.shape}")
    if not (np.all(np.isfinite(W)) and np.all(np.isfinite(W_E))):
        raise ColorimetryError("weights and weights_E must be finite")
    factors = spectra_channel_factors(W_E) if normalise == "spectra-exact" else np.ones(3)
    source_white = factors * W_E.sum(axis=0)  # E on the weights' scale (Y = 100)
    adapt = _white_adaptation(source_white, display, adaptation)
    to_display = adapt @ np.diag(factors)
    display_matrix = np.asarray(display.matrix_from_XYZ)
    scale: float | None
    if normalise == "fixed":
        scale = float(max_object_rgb(display, W @ to_display.T).max())
    elif normalise == "spectra-exact":
        scale = spectra_scale(display_matrix @ adapt)
    else:
        scale = None
    return DisplayChain(
        weights=W, channel_factors=factors, adaptation_matrix=adapt, to_display=to_display,
        matrix_from_XYZ=display_matrix @ to_display, scale=scale, space=display,
        normalise=normalise, adaptation=adaptation,
    )
