"""Compile the upsampling kernels before they are needed (:func:`warm_up`).

Kept apart from :mod:`.compiled` (the kernels' switch and wrappers, which :mod:`.apply`
imports): warming up runs the lookup, the blend and the relighting, so it sits above them.
"""

from __future__ import annotations

from concurrent.futures import ThreadPoolExecutor

import numpy as np

from .apply import lookup, texel_coefficients, upsample
from .compiled import kernels
from .relight import relight
from .table import upsampling_table

__all__ = ["warm_up"]


def warm_up() -> bool:
    """Compile (or load from the cache) every kernel now rather than on first use.

    Runs the lookup and the blend of a small table (:func:`~spectrocolor.upsampling.lookup`,
    :func:`~spectrocolor.upsampling.upsample`, :func:`~spectrocolor.upsampling.relight`,
    :func:`~spectrocolor.upsampling.texel_coefficients`) from the main thread (the parallel
    kernels) and from another thread (the serial ones), and undoes the filters of a one-pixel
    PNG, so that each kernel is compiled for the array types the library passes it. Building
    the table compiles the smoothest-reflectance kernels too
    (:func:`spectrocolor.recovery.warmup.warm_up`).

    Returns
    -------
    bool
        Whether the kernels are in use (False without numba or with ``SPECTROCOLOR_NUMBA=0``).

    Examples
    --------
    >>> isinstance(warm_up(), bool)
    True
    """
    found = kernels()
    if found is None:
        return False
    table = upsampling_table("sRGB", "D65", wavelengths=(400.0, 700.0, 20.0), resolution=3,
                             measure_excess=False)
    colours = np.array([[0.5, 0.4, 0.3], [1.2, 0.5, -0.1]])

    def use_every_kernel():
        lookup(table, colours)
        texel_coefficients(table, colours)
        upsample(table, colours)
        relight(table, colours, "A")

    use_every_kernel()
    with ThreadPoolExecutor(1) as other_thread:  # .result() raises what the thread raised
        other_thread.submit(use_every_kernel).result()
    return True
