"""The optional compiled kernels of :mod:`spectrocolor.upsampling.apply` (numba, extra ``fast``).

One pass per query does what the NumPy path does in several: move a query outside the cube
``[0, 1]^3`` by the strategy, find its cell and Freudenthal tetrahedron, form the barycentric
weights and either blend the four node rows of a value table (spectra: ``K`` channels;
relighting: the 3-channel table of node colours under the new light, so no spectrum is ever
formed) or write the four node indices and weights (texture baking, :func:`lookup`). A
third kernel undoes PNG scanline filters for :mod:`spectrocolor.upsampling.png_reader`.

Every floating-point operation is the NumPy path's, in the same order (no ``fastmath``, so no
reassociation or fused multiply-add), and the tests hold both paths to a few ulps with
hypothesis. Without numba, or with the environment variable ``SPECTROCOLOR_NUMBA=0``,
:func:`kernels` returns None and the NumPy path runs.

The switch, the compile cache and the thread rule (parallel kernels from the main thread,
serial ones from any other) are :mod:`spectrocolor.numba_support`'s.
"""

from __future__ import annotations

from concurrent.futures import ThreadPoolExecutor
from functools import lru_cache
from types import SimpleNamespace

import numpy as np

from ..numba_support import pick, use_compiled

__all__ = ["MOVE_CODES", "kernels", "run_blend", "run_locate", "warm_up"]

#: The out-of-range strategies the kernel implements: strategy name -> how a query outside the
#: cube is moved (0 toward grey, 1 clip per channel). Other strategies use the NumPy path.
MOVE_CODES = {"toward-grey": 0, "clip": 1, "nan": 1}


@lru_cache(maxsize=1)
def _compiled():
    try:
        from . import numba_kernels
    except ImportError:  # numba is not installed (the extra "fast")
        return None
    return SimpleNamespace(blend=(numba_kernels.blend_serial, numba_kernels.blend_parallel),
                           locate=(numba_kernels.locate_serial, numba_kernels.locate_parallel),
                           unfilter_png=numba_kernels.unfilter_png)


def kernels():
    """The compiled kernels, or None without numba, with ``SPECTROCOLOR_NUMBA=0`` or while another
    process compiles them (:func:`spectrocolor.numba_support.use_compiled`).

    Returns
    -------
    types.SimpleNamespace or None
        ``blend`` and ``locate``, each a (serial, parallel) pair of numba dispatchers, and
        ``unfilter_png`` (PNG scanline filters, :mod:`spectrocolor.upsampling.png_reader`).

    Examples
    --------
    >>> k = kernels()
    >>> k is None or len(k.blend) == 2
    True
    """
    if not use_compiled():
        return None
    return _compiled()


def run_blend(found_kernels, t, n, move, offsets, status, values, clamp, nan_inexact, out):
    """Blend ``values`` (n³, C) at queries ``t`` (N, 3) into ``out`` (N, C); (exact, moved)."""
    exact = np.empty(t.shape[0], dtype=np.bool_)
    moved = np.empty(t.shape[0], dtype=np.bool_)
    pick(found_kernels.blend)(t, n, move, offsets, status, values, clamp, nan_inexact, out,
                                  exact, moved)
    return exact, moved


def run_locate(found_kernels, t, n, move, offsets, status, node_dtype=np.intp,
               weight_dtype=np.float64):
    """Nodes (N, 4), weights (N, 4) (computed in float64, stored as ``weight_dtype``), exact
    and moved (N,) of the queries ``t``."""
    count = t.shape[0]
    nodes = np.empty((count, 4), dtype=node_dtype)
    weights = np.empty((count, 4), dtype=weight_dtype)
    exact = np.empty(count, dtype=np.bool_)
    moved = np.empty(count, dtype=np.bool_)
    pick(found_kernels.locate)(t, n, move, offsets, status, nodes, weights, exact, moved)
    return nodes, weights, exact, moved


def warm_up() -> bool:
    """Compile (or load from the cache) every kernel now rather than on first use.

    Runs the lookup and the blend of a small table (:func:`~spectrocolor.upsampling.lookup`,
    :func:`~spectrocolor.upsampling.upsample`, :func:`~spectrocolor.upsampling.relight`,
    :func:`~spectrocolor.upsampling.texel_coefficients`) from the main thread (the parallel
    kernels) and from another thread (the serial ones), and undoes the filters of a one-pixel
    PNG, so that each kernel is compiled for the array types the library passes it. Building
    the table compiles the smoothest-reflectance kernels too
    (:func:`spectrocolor.recovery.compiled.warm_up`).

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
    from .apply import lookup, texel_coefficients, upsample
    from .relight import relight
    from .table import upsampling_table

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
    found.unfilter_png(np.zeros((1, 1, 3), dtype=np.uint8), np.zeros(1, dtype=np.uint8),
                       np.empty((1, 1, 3), dtype=np.uint8))
    return True
