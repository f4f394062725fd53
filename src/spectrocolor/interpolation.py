"""Resampling spectra as linear maps: every method is an (M, K) matrix applied to ``values``.

Because interpolation is linear in the data, each method builds the matrix ``P`` with
``resampled = values @ P.T``. Colorimetric weights on a coarse grid are then exactly
``P.T @ W_fine`` (see :func:`spectrocolor.weights` with ``method="1nm"``).

No method extrapolates: a target wavelength outside the source range is a
:class:`~spectrocolor.errors.SpectrumError`.

References
----------
CIE 167:2005, *Recommended practice for tabulating spectral data for use in colour
computations* (Sprague interpolation, boundary coefficients).
Sprague, T. B. (1880). Explanation of a new formula for interpolation.
*Journal of the Institute of Actuaries* 22, 270–285.
"""

from __future__ import annotations

import numpy as np

from .errors import SpectrumError

METHODS = ("linear", "sprague", "cubic")

#: Most entries of a dense resampling matrix built (2**25 float64 = 256 MiB). Linear resampling
#: of data (:func:`resample_linear`, used by ``Spectrum.resample`` and the colorimetric weights)
#: never builds one, so any grid a spectrum can have is resampled linearly; the Sprague and
#: cubic matrices are dense and beyond this size raise a SpectrumError instead of exhausting
#: the memory.
MAX_MATRIX_ENTRIES = 2**25

# Sprague's fifth-degree polynomial, coefficients of (y[-2], ..., y[3]) for a0..a5, divided by 24.
_SPRAGUE_A = (
    np.array(
        [
            [0, 0, 24, 0, 0, 0],
            [2, -16, 0, 16, -2, 0],
            [-1, 16, -30, 16, -1, 0],
            [-9, 39, -70, 66, -33, 7],
            [13, -64, 126, -124, 61, -12],
            [-5, 25, -50, 50, -25, 5],
        ],
        dtype=float,
    )
    / 24.0
)

# CIE 167:2005 boundary extension: two extra points each side from the first/last six.
_SPRAGUE_START = (
    np.array([[884, -1960, 3033, -2648, 1080, -180], [508, -540, 488, -367, 144, -24]], dtype=float) / 209.0
)
_SPRAGUE_END = np.array([[-24, 144, -367, 488, -540, 508], [-180, 1080, -2648, 3033, -1960, 884]], dtype=float) / 209.0


def _check_inside(source_nm: np.ndarray, target_nm: np.ndarray) -> None:
    tolerance = 1e-9 * max(1.0, abs(source_nm[-1]))
    if target_nm[0] < source_nm[0] - tolerance or target_nm[-1] > source_nm[-1] + tolerance:
        raise SpectrumError(
            f"wavelengths_nm: target range {target_nm[0]:g}–{target_nm[-1]:g} nm reaches outside "
            f"the data's range {source_nm[0]:g}–{source_nm[-1]:g} nm; spectrocolor never "
            "extrapolates — restrict the target grid (Spectrum.restrict) or supply wider data"
        )


def _linear_matrix(source_nm: np.ndarray, target_nm: np.ndarray) -> np.ndarray:
    K = source_nm.size
    matrix = np.zeros((target_nm.size, K))
    index = np.clip(np.searchsorted(source_nm, target_nm, side="right") - 1, 0, max(K - 2, 0))
    if K == 1:
        matrix[:, 0] = 1.0
        return matrix
    left, right = source_nm[index], source_nm[index + 1]
    t = np.clip((target_nm - left) / (right - left), 0.0, 1.0)
    rows = np.arange(target_nm.size)
    matrix[rows, index] = 1.0 - t
    matrix[rows, index + 1] += t
    return matrix


def _uniform_step(source_nm: np.ndarray) -> float:
    steps = np.diff(source_nm)
    if source_nm.size < 6 or not np.allclose(steps, steps[0], rtol=1e-9, atol=0):
        raise SpectrumError(
            "method: 'sprague' needs at least 6 uniformly spaced source wavelengths "
            f"(got {source_nm.size} samples, steps {np.unique(np.round(steps, 9))[:4]} nm); "
            "use method='linear' or 'cubic' for irregular data"
        )
    return float(steps[0])


def _sprague_matrix(source_nm: np.ndarray, target_nm: np.ndarray) -> np.ndarray:
    K = source_nm.size
    step = _uniform_step(source_nm)
    # Extended sample set: y[-2], y[-1], y[0..K-1], y[K], y[K+1], each a combination of y[0..K-1].
    extended = np.zeros((K + 4, K))
    extended[2 : K + 2] = np.eye(K)
    extended[0:2, :6] = _SPRAGUE_START
    extended[K + 2 : K + 4, K - 6 :] = _SPRAGUE_END
    position = (target_nm - source_nm[0]) / step
    interval = np.clip(np.floor(position).astype(int), 0, K - 2)
    X = position - interval
    powers = X[:, None] ** np.arange(6)  # (M, 6)
    # For target m: weights over extended samples interval[m] .. interval[m] + 5.
    local = powers @ _SPRAGUE_A  # (M, 6)
    window = interval[:, None] + np.arange(6)  # indices into extended (offset by 2 already)
    return np.einsum("mj,mjk->mk", local, extended[window])


def _cubic_matrix(source_nm: np.ndarray, target_nm: np.ndarray) -> np.ndarray:
    from scipy.interpolate import CubicSpline

    if source_nm.size < 4:
        raise SpectrumError(f"method: 'cubic' needs at least 4 source wavelengths, got {source_nm.size}")
    spline = CubicSpline(source_nm, np.eye(source_nm.size), axis=0, bc_type="not-a-knot")
    return spline(target_nm)


def resample_linear(source_nm, values, target_nm) -> np.ndarray:
    """``values`` (..., K) on ``source_nm`` linearly interpolated at ``target_nm``: (..., M).

    The same numbers as ``values @ interpolation_matrix(source_nm, target_nm).T``, computed from
    the two neighbours of each target sample (memory of the result only, never M x K), so a
    NaN affects only the targets next to it. Keeps a floating ``values`` dtype.

    Parameters
    ----------
    source_nm : array_like, shape (K,)
        Strictly increasing source wavelengths, nm.
    values : array_like, shape (..., K)
        Values on ``source_nm``.
    target_nm : array_like, shape (M,)
        Target wavelengths, nm, inside the source range.

    Returns
    -------
    numpy.ndarray, shape (..., M)
        Linearly interpolated values (exact at coinciding samples).

    Raises
    ------
    SpectrumError
        For a target outside the source range (never extrapolated).

    Examples
    --------
    >>> resample_linear([400.0, 500.0, 600.0], [[0.0, 1.0, 3.0]], [400.0, 450.0, 575.0])
    array([[0. , 0.5, 2.5]])
    """
    source_nm = np.asarray(source_nm, dtype=float)
    target_nm = np.asarray(target_nm, dtype=float)
    values = np.asarray(values)
    if not np.issubdtype(values.dtype, np.floating):
        values = values.astype(float)
    _check_inside(source_nm, target_nm)
    K = source_nm.size
    if K == 1:
        return np.repeat(values[..., :1], target_nm.size, axis=-1)
    index = np.clip(np.searchsorted(source_nm, target_nm, side="right") - 1, 0, K - 2)
    left, right = source_nm[index], source_nm[index + 1]
    t = np.clip((target_nm - left) / (right - left), 0.0, 1.0).astype(values.dtype)
    result = values[..., index] * (1 - t) + values[..., index + 1] * t
    hit = np.clip(np.searchsorted(source_nm, target_nm), 0, K - 1)
    same = np.isclose(source_nm[hit], target_nm, rtol=0, atol=1e-9)
    result[..., same] = values[..., hit[same]]  # exact at coinciding samples
    return result


def interpolation_matrix(source_nm: np.ndarray, target_nm: np.ndarray, method: str = "linear") -> np.ndarray:
    """Matrix ``P`` (M, K) with ``values_on_target = values_on_source @ P.T``.

    Parameters
    ----------
    source_nm : array_like, shape (K,)
        Strictly increasing source wavelengths, nm.
    target_nm : array_like, shape (M,)
        Strictly increasing target wavelengths, nm, inside ``source_nm``'s range.
    method : str, default "linear"
        ``"linear"``; ``"sprague"`` (CIE 167 recommended for uniformly spaced data, e.g.
        5 nm → 1 nm; at least 6 samples); ``"cubic"`` (not-a-knot cubic spline, any spacing).

    Returns
    -------
    numpy.ndarray
        ``P``, float64, shape ``(M, K)``. Target wavelengths that coincide with source samples
        reproduce them exactly in every method.

    Raises
    ------
    SpectrumError
        For an unknown method, a target outside the source range, a grid the method cannot use,
        or a matrix larger than the built-in memory limit.

    References
    ----------
    CIE 167:2005 (Sprague interpolation); see the module docstring.

    Examples
    --------
    >>> interpolation_matrix([400.0, 500.0, 600.0], [450.0, 500.0]).tolist()
    [[0.5, 0.5, 0.0], [0.0, 1.0, 0.0]]
    """
    source_nm = np.asarray(source_nm, dtype=float)
    target_nm = np.asarray(target_nm, dtype=float)
    if not isinstance(method, str) or method not in METHODS:
        raise SpectrumError(f"method: {method!r:.40} is not a resampling method; choose one of {METHODS}")
    _check_inside(source_nm, target_nm)
    entries = max(target_nm.size, source_nm.size + 4) * source_nm.size
    if entries > MAX_MATRIX_ENTRIES:
        raise SpectrumError(
            f"wavelengths_nm: resampling {source_nm.size} samples to {target_nm.size} with "
            f"method={method!r} needs a dense matrix of {entries * 8 / 2**30:.3g} GiB (at most "
            f"{MAX_MATRIX_ENTRIES * 8 / 2**20:.0f} MiB are built); use method='linear' or "
            "coarser grids")
    if method == "linear":
        matrix = _linear_matrix(source_nm, target_nm)
    elif method == "sprague":
        matrix = _sprague_matrix(source_nm, target_nm)
    else:
        matrix = _cubic_matrix(source_nm, target_nm)
    # Exact reproduction at coinciding samples (removes rounding noise of the polynomial forms).
    hit = np.searchsorted(source_nm, target_nm)
    hit = np.clip(hit, 0, source_nm.size - 1)
    same = np.isclose(source_nm[hit], target_nm, rtol=0, atol=1e-9)
    matrix[same] = 0.0
    matrix[np.nonzero(same)[0], hit[same]] = 1.0
    return matrix
