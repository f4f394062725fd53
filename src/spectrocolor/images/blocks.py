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
        "rgb_linear" or "rgb_encoded"), and optionally ``masked`` (as checked by
        :func:`spectrocolor.images.convert.masked_fill`).

    Returns
    -------
    ndarray, shape (..., 3), or (..., 4) with ``masked="transparent"``
        Integer codes (uint8 or uint16) or float64 linear / encoded RGB. Masked pixels (NaN in
        the values, e.g. an ENVI data ignore value) are black codes (0, 0, 0), or NaN floats,
        unless ``masked`` gives their colour or makes them transparent (alpha 0, colour 0;
        the other pixels get full alpha).

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
    XYZ = xyz_block(values, weights)
    masked = ~np.isfinite(XYZ).all(axis=-1)
    codes = options["output"] == "codes"
    dtype = (np.uint8 if options["bit_depth"] <= 8 else np.uint16) if codes else np.float64
    if not masked.any():
        rgb = _render(XYZ, options, dtype)
    else:  # render the others; masked pixels are black codes or NaN unless ``masked`` says
        rgb = np.full(XYZ.shape, 0 if codes else np.nan, dtype=dtype)
        if not masked.all():
            rgb[~masked] = _render(XYZ[~masked], options, dtype)
    fill = options.get("masked")
    if fill is None:
        return rgb
    if isinstance(fill, str):  # "transparent": RGBA, alpha 0 and colour 0 where masked
        rgba = np.zeros((*rgb.shape[:-1], 4), dtype)
        rgba[~masked, :3] = rgb[~masked]
        rgba[~masked, 3] = np.iinfo(rgba.dtype).max if codes else 1.0
        return rgba
    rgb[masked] = fill
    return rgb


def _render(XYZ: np.ndarray, options: dict, dtype) -> np.ndarray:
    """Adapted, exposed and rendered finite XYZ, as ``options`` say (see :func:`rgb_block`)."""
    from ..display.adaptation import adapt
    from ..display.render import render
    from ..display.spaces import rgb_space

    if options["adapt_from"] is not None:
        space = rgb_space(options["space"]) if isinstance(options["space"], str) else (
            options["space"]
        )
        XYZ = adapt(XYZ, options["adapt_from"], space.white_XYZ,
                       method=options["adapt_method"])
    if options["exposure"] != 1.0:
        XYZ = XYZ * options["exposure"]
    rendering = render(
        XYZ, space=options["space"], normalise="none", gamut=options["gamut"],
        bit_depth=options["bit_depth"],
    )
    if options["output"] == "codes":
        return np.asarray(rendering.codes).astype(dtype)
    return np.asarray(getattr(rendering, options["output"]), dtype=np.float64)
