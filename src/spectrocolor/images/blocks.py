"""The per-block work of every image conversion, shared by the NumPy, memmap and dask paths.

Each function takes a block of spectra ``(..., K)`` (any leading shape: a row block of a cube,
a dask chunk) and returns ``(..., 3)``. They are plain module-level functions of arrays, so
dask can ship them to workers; the precomputed weights and whites are passed in.

The work is the library's: XYZ is ``values @ W`` with ``W`` from :func:`spectrocolor.weights`
(what :func:`spectrocolor.tristimulus` computes for a Spectrum), CIELAB is
:func:`spectrocolor.lab`, display RGB is :func:`spectrocolor.adapt` then
:func:`spectrocolor.render`.
"""

from __future__ import annotations

import numpy as np

__all__ = ["xyz_block", "lab_block", "rgb_block"]


def xyz_block(values, weights: np.ndarray) -> np.ndarray:
    """Tristimulus values of a block of spectra: ``values @ weights``, returned as float64.

    Summed by :func:`spectrocolor.colorimetry.apply_weights`, as :func:`spectrocolor.tristimulus`
    sums: float32 blocks in float32 (~1e-7 relative rounding), every other dtype (float64,
    integer counts) in float64.

    Parameters
    ----------
    values : array_like, shape (..., K)
        Spectral values (reflectance 0-1 for reflectance weights; any dtype).
    weights : ndarray, shape (K, 3)
        From :func:`spectrocolor.weights`, times the value scale.

    Returns
    -------
    ndarray, shape (..., 3), float64
        XYZ on the weights' scale (XYZ100 for reflectance weights).

    Examples
    --------
    >>> import numpy as np
    >>> from spectrocolor import weights
    >>> W = weights(np.arange(400, 701, 10), illuminant="D65")
    >>> grey = np.full((2, 31), 0.5)
    >>> xyz_block(grey, W)[0].round(3).tolist()
    [47.47, 50.0, 54.355]
    """
    from ..colorimetry import apply_weights

    return apply_weights(values, weights).astype(np.float64, copy=False)


def lab_block(values, weights: np.ndarray, white_XYZ: np.ndarray) -> np.ndarray:
    """CIELAB (L*, a*, b*) of a block of spectra, relative to ``white_XYZ`` (same scale as XYZ).

    Parameters
    ----------
    values : array_like, shape (..., K)
        Spectral values.
    weights : numpy.ndarray, shape (K, 3)
        As for :func:`xyz_block`.
    white_XYZ : numpy.ndarray, shape (3,)
        The reference white on the XYZ scale of the weights.

    Returns
    -------
    numpy.ndarray, shape (..., 3)
        L*, a*, b* (CIE 015:2018 §8.2.1).

    Examples
    --------
    >>> import numpy as np
    >>> from spectrocolor import weights
    >>> W = weights(np.arange(400, 701, 10), illuminant="D65")
    >>> grey = np.full((2, 31), 0.5)
    >>> lab_block(grey, W, W.sum(axis=0))[0].round(3).tolist()
    [76.069, 0.0, 0.0]
    """
    from ..coordinates import lab

    return lab(xyz_block(values, weights), white_XYZ)


def rgb_block(values, weights: np.ndarray, options: dict) -> np.ndarray:
    """Display RGB of a block of spectra.

    Parameters
    ----------
    values : array_like, shape (..., K)
        As for :func:`xyz_block`.
    weights : numpy.ndarray, shape (K, 3)
        As for :func:`xyz_block`.
    options : dict
        ``adapt_from`` (XYZ of the source white or None), ``adapt_method``, ``exposure``
        (XYZ multiplier), ``space``, ``gamut``, ``bit_depth``, ``output`` ("codes",
        "rgb_linear" or "rgb_encoded").

    Returns
    -------
    ndarray, shape (..., 3)
        Integer codes (uint8 or uint16) or float64 linear / encoded RGB. Masked pixels (NaN in
        the values, e.g. an ENVI data ignore value) are black codes (0, 0, 0), or NaN floats.

    Examples
    --------
    >>> import numpy as np
    >>> from spectrocolor import weights
    >>> W = weights(np.arange(400, 701, 10), illuminant="D65")
    >>> grey = np.full((2, 31), 0.5)
    >>> options = dict(adapt_from=None, adapt_method=None, exposure=1.0, space="sRGB", gamut="clip",
    ...                bit_depth=8, output="codes")
    >>> rgb_block(grey, W, options)[0].tolist()
    [187, 188, 187]
    """
    import spectrocolor as sc

    XYZ = xyz_block(values, weights)
    masked = ~np.isfinite(XYZ).all(axis=-1)
    if masked.any():  # render the others; masked pixels stay black codes or NaN
        codes = options["output"] == "codes"
        dtype = (np.uint8 if options["bit_depth"] <= 8 else np.uint16) if codes else np.float64
        result = np.full(XYZ.shape, 0 if codes else np.nan, dtype=dtype)
        if not masked.all():
            result[~masked] = rgb_block(values[~masked], weights, options)
        return result
    if options["adapt_from"] is not None:
        space = sc.rgb_space(options["space"]) if isinstance(options["space"], str) else (
            options["space"]
        )
        XYZ = sc.adapt(XYZ, options["adapt_from"], space.white_XYZ,
                       method=options["adapt_method"])
    if options["exposure"] != 1.0:
        XYZ = XYZ * options["exposure"]
    rendering = sc.render(
        XYZ, space=options["space"], normalise="none", gamut=options["gamut"],
        bit_depth=options["bit_depth"],
    )
    if options["output"] == "codes":
        dtype = np.uint8 if options["bit_depth"] <= 8 else np.uint16
        return np.asarray(rendering.codes).astype(dtype)
    return np.asarray(getattr(rendering, options["output"]), dtype=np.float64)
