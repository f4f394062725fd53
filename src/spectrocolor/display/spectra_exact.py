"""SPECTRA's own normalisation, to reproduce the program's numbers (seed 002, STEP 1-2, note 10).

The exact alternative A (:func:`~spectrocolor.display.normalise.max_object_rgb`) divides by the
largest channel any distribution 0 <= f <= f_max can drive: R_max = 1.58 for SPECTRA's monitor.
The program itself did two things differently:

* **STEP 1, one k per channel.** ``X = k_X Σ f x̄`` with ``k_X = 100 / (f_max Σ x̄)``, and the
  same for Y and Z, so the full spectrum is exactly X = Y = Z = 100 on its 31 bins (the CIE
  uses one k = 100 / Σ ȳ for all three; on 400-700 nm at 10 nm the full spectrum is then
  X = 99.861, Z = 99.709 for the 1931 observer).
* **Note 10, R_max = 1.32 × R_white.** "The value of R for X = Y = Z = 100 (i.e. the white-point)
  is 1.22, hence a strategy that works with an arbitrarily normalised matrix is to put
  R_max = 1.32 * R for the white-point ... This is the way it is done in the program."

References
----------
P. Sällström (1999), USIP Report 99-05, STEP 1 (k), STEP 2 alternative A, note 10, Appendix.
"""

from __future__ import annotations

import numpy as np

from ..errors import ColorimetryError

__all__ = ["SPECTRA_WHITE_HEADROOM", "spectra_channel_factors", "spectra_scale"]

#: Seed 002, note 10: R_max = 1.32 × R of the white point.
SPECTRA_WHITE_HEADROOM = 1.32


def spectra_channel_factors(weights_E) -> np.ndarray:
    """Factors that turn CIE XYZ (one k) into SPECTRA's step-1 XYZ (one k per channel).

    Parameters
    ----------
    weights_E : array_like (K, 3)
        Summation weights of the equal-energy reference on the grid, normalised so the full
        spectrum has Y = 100 (``spectrocolor.weights(grid, illuminant="E")``).

    Returns
    -------
    ndarray (3,)
        ``100 / (X, Y, Z of the full spectrum)``: multiply XYZ by these and the full spectrum
        becomes exactly (100, 100, 100).

    Examples
    --------
    >>> import spectrocolor as sc
    >>> W = sc.weights(sc.wavelength_grid(400, 700, 10), illuminant="E")
    >>> [round(float(v), 5) for v in spectra_channel_factors(W)]
    [1.0014, 1.0, 1.00292]
    """
    w = np.asarray(weights_E, dtype=float)
    if w.ndim != 2 or w.shape[1] != 3 or not np.all(np.isfinite(w)):
        raise ColorimetryError(f"weights_E: expected a finite (K, 3) array, got shape {w.shape}")
    white = w.sum(axis=0)
    if np.any(white <= 0):
        raise ColorimetryError("weights_E: the full spectrum must have X, Y, Z > 0")
    return 100.0 / white


def spectra_scale(matrix_from_XYZ) -> float:
    """SPECTRA's divisor of alternative A: 1.32 × the largest channel of X = Y = Z = 100.

    The seed uses R, which is the largest channel of the white for its matrix (and for sRGB).

    Parameters
    ----------
    matrix_from_XYZ : array_like (3, 3)
        The XYZ -> linear RGB matrix the colours go through (``matris.d`` for SPECTRA).

    Returns
    -------
    float

    Examples
    --------
    The seed's printed ``matris.d`` (Appendix): R_white = 1.2204 ("1.22"), R_max = 1.6109.

    >>> T = [[0.02994, -0.01313, -0.004606], [-0.01022, 0.01836, 0.0004061],
    ...      [0.000527, -0.001944, 0.009541]]
    >>> round(spectra_scale(T), 4)
    1.6109
    """
    m = np.asarray(matrix_from_XYZ, dtype=float)
    if m.shape != (3, 3) or not np.all(np.isfinite(m)):
        raise ColorimetryError(f"matrix_from_XYZ: expected a finite 3 x 3 matrix, got {m.shape}")
    top = float((m @ np.full(3, 100.0)).max())
    if top <= 0:
        raise ColorimetryError("matrix_from_XYZ: the white X = Y = Z = 100 drives no channel")
    return SPECTRA_WHITE_HEADROOM * top
