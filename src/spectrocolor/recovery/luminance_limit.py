"""The brightest object colour of a chromaticity: MacAdam's limit read the other way round.

For a chromaticity (x, y) the object colours (0 ≤ ρ ≤ 1) of that chromaticity have luminance
factors 0 < Y ≤ Y_max(x, y). Y_max is the largest ``s`` with ``ρ @ W = s · (x/y, 1, z/y)`` for some
``0 ≤ ρ ≤ 1``: a linear programme, whose optimum is a vertex of the object-colour solid's
boundary (an optimal colour, van Trigt 1990 §5; MacAdam 1935). Outside the spectral locus no
object colour has the chromaticity and Y_max = 0.

References
----------
D. L. MacAdam, "Maximum visual efficiency of colored materials", J. Opt. Soc. Am. 25, 361 (1935).
C. van Trigt, J. Opt. Soc. Am. A 7, 1891–1904 (1990), section 5 (optimal colours).
"""

from __future__ import annotations

import numpy as np

from ..errors import ColorimetryError
from ..illuminants import DEFAULT_ILLUMINANT
from ..observers import DEFAULT_OBSERVER
from .inputs import DEFAULT_WAVELENGTHS, setup_for


def max_luminance_factor(xy, *, illuminant=DEFAULT_ILLUMINANT, observer=DEFAULT_OBSERVER,
                         wavelengths=DEFAULT_WAVELENGTHS) -> np.ndarray:
    """The largest luminance factor Y (%) of an object colour with chromaticity ``xy``.

    Parameters
    ----------
    xy : array_like, shape (..., 2)
        CIE chromaticities (x, y) with y > 0.
    illuminant : str or Spectrum, default "D65"
        The light the limit is computed under; see :term:`illuminant`.
    observer : str or Spectrum, default "1931"
        The observer of the luminance factor Y; see :term:`observer`.
    wavelengths : tuple of float or array_like, default (380.0, 780.0, 5.0)
        The limiting reflectances' samples; see :term:`wavelength grid`.

    Returns
    -------
    numpy.ndarray, shape (...)
        Y_max in percent of the perfect white (0 where no object colour has the chromaticity).

    Raises
    ------
    ColorimetryError
        For chromaticities that are not finite or have y ≤ 0.

    Examples
    --------
    >>> from spectrocolor import wavelength_grid, white_point, xy
    >>> white_xy = xy(white_point("D65", wavelengths_nm=wavelength_grid(380, 780, 5)))
    >>> round(float(max_luminance_factor(white_xy)), 4)       # only the perfect white is that bright
    100.0
    >>> float(max_luminance_factor([0.05, 0.9]))                         # outside the locus
    0.0
    """
    from scipy.optimize import linprog

    points = np.asarray(xy, dtype=float)
    if points.ndim == 0 or points.shape[-1] != 2 or not np.all(np.isfinite(points)) or np.any(points[..., 1] <= 0):
        raise ColorimetryError(f"xy: expected finite chromaticities (x, y) with y > 0, shape (..., 2); got {xy!r:.80}")
    setup, _, _ = setup_for(wavelengths, observer, illuminant)
    W = setup.W
    K = W.shape[0]
    flat = points.reshape(-1, 2)
    result = np.empty(flat.shape[0])
    objective = np.zeros(K + 1)
    objective[-1] = -1.0  # maximise s
    bounds = [(0.0, 1.0)] * K + [(0.0, None)]
    for i, (x, y) in enumerate(flat):
        direction = np.array([x / y, 1.0, (1.0 - x - y) / y])
        equality = np.hstack([W.T, -direction[:, None]])
        solved = linprog(objective, A_eq=equality, b_eq=np.zeros(3), bounds=bounds, method="highs")
        result[i] = max(0.0, float(solved.x[-1])) if solved.status == 0 else 0.0  # never -0.0
    return result.reshape(points.shape[:-1])
