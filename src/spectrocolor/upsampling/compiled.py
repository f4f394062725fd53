"""The optional compiled kernels of :mod:`spectrocolor.upsampling.apply` (numba, extra ``fast``).

One pass per query does what the NumPy path does in several: move a query outside the cube
``[0, 1]^3`` by the strategy, find its cell and Freudenthal tetrahedron, form the barycentric
weights and either blend the four node rows of a value table (spectra: ``K`` channels;
relighting: the 3-channel table of node colours under the new light, so no spectrum is ever
formed) or write the four node indices and weights (texture baking, :func:`lookup`). PNG
scanline filters are undone by libpng (:mod:`spectrocolor.imagefiles`), not here.

Every floating-point operation is the NumPy path's, in the same order (no ``fastmath``, so no
reassociation or fused multiply-add), and the tests hold both paths to a few ulps with
hypothesis. Without numba, or with the environment variable ``SPECTROCOLOR_NUMBA=0``,
:func:`kernels` returns None and the NumPy path runs.

The switch, the compile cache and the thread rule (parallel kernels from the main thread,
serial ones from any other) are :mod:`spectrocolor.numba_support`'s.
"""

from __future__ import annotations

from functools import lru_cache
from types import SimpleNamespace

import numpy as np

from ..numba_support import pick, use_compiled

__all__ = ["MOVE_CODES", "kernels", "run_actual", "run_blend", "run_locate"]

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
                           actual=(numba_kernels.actual_serial, numba_kernels.actual_parallel))


def kernels():
    """The compiled kernels, or None without numba, with ``SPECTROCOLOR_NUMBA=0`` or while another
    process compiles them (:func:`spectrocolor.numba_support.use_compiled`).

    Returns
    -------
    types.SimpleNamespace or None
        ``blend``, ``locate`` and ``actual`` (path 1 of :mod:`.moved_cells`), each a (serial,
        parallel) pair of numba dispatchers.

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


def run_actual(found_kernels, q, scale, candidates, origin, inverse, tet_nodes, node_XYZ, slack,
               tolerance, values, clamp, rows, out):
    """Path 1 of :mod:`.moved_cells` for queries ``q`` (m, 3): writes ``out[rows[i]]`` where
    found; returns (found (m,), nodes (m, 4), weights (m, 4))."""
    m = q.shape[0]
    found = np.empty(m, dtype=np.bool_)
    nodes = np.zeros((m, 4), dtype=np.intp)
    weights = np.zeros((m, 4))
    pick(found_kernels.actual)(q, scale, candidates, origin, inverse, tet_nodes, node_XYZ, slack,
                               tolerance, values, clamp, rows, out, nodes, weights, found)
    return found, nodes, weights
