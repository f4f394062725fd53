"""numba kernels of the table lookup and blend (imported only by :mod:`.compiled`).

Each function repeats :func:`spectrocolor.upsampling.apply.lookup` and its blend for one query,
operation for operation (see :mod:`spectrocolor.upsampling.compiled`). The per-query helpers
are inlined into the loops (``inline="always"``): as separate calls, passing the arrays cost
several times the arithmetic.
"""

from __future__ import annotations

import numba
import numpy as np

from ..numba_support import jit

__all__ = ["actual_parallel", "actual_serial", "blend_parallel", "blend_serial", "locate_parallel",
           "locate_serial"]


_jit = jit


@_jit(inline="always")
def _locate(t, q, n, move, offsets):
    """(node0..3, weight0..3, outside) of query ``q`` of ``t`` (N, 3)."""
    t0, t1, t2 = t[q, 0], t[q, 1], t[q, 2]
    outside = t0 < 0.0 or t0 > 1.0 or t1 < 0.0 or t1 > 1.0 or t2 < 0.0 or t2 > 1.0
    if outside:
        if move == 0:  # toward grey: onto the cube's surface along the segment to (½, ½, ½)
            d0, d1, d2 = t0 - 0.5, t1 - 0.5, t2 - 0.5
            limit = np.inf
            for d in (d0, d1, d2):
                if d > 0:
                    limit = min(limit, 0.5 / d)
                elif d < 0:
                    limit = min(limit, -0.5 / d)
            s = min(limit, 1.0)
            t0 = min(max(0.5 + s * d0, 0.0), 1.0)
            t1 = min(max(0.5 + s * d1, 0.0), 1.0)
            t2 = min(max(0.5 + s * d2, 0.0), 1.0)
        else:  # clip each channel
            t0 = min(max(t0, 0.0), 1.0)
            t1 = min(max(t1, 0.0), 1.0)
            t2 = min(max(t2, 0.0), 1.0)
    s0, s1, s2 = t0 * (n - 1), t1 * (n - 1), t2 * (n - 1)
    b0, b1, b2 = min(int(s0), n - 2), min(int(s1), n - 2), min(int(s2), n - 2)
    f0, f1, f2 = s0 - b0, s1 - b1, s2 - b2
    code = 4 * int(f0 >= f1) + 2 * int(f1 >= f2) + int(f0 >= f2)
    low01, high01 = min(f0, f1), max(f0, f1)
    high = max(high01, f2)
    middle = max(low01, min(high01, f2))
    low = min(low01, f2)
    node0 = (b0 * n + b1) * n + b2
    return (node0, node0 + offsets[code, 0], node0 + offsets[code, 1], node0 + offsets[code, 2],
            1.0 - high, high - middle, middle - low, low, outside)


@_jit(inline="always")
def _blend_one(t, n, move, offsets, status, values, clamp, nan_inexact, out, exact, moved, q):
    i0, i1, i2, i3, w0, w1, w2, w3, outside = _locate(t, q, n, move, offsets)
    is_exact = (not outside and status[i0] == 0 and status[i1] == 0 and status[i2] == 0
                and status[i3] == 0)
    exact[q] = is_exact
    moved[q] = outside
    if nan_inexact and not is_exact:
        for k in range(values.shape[1]):
            out[q, k] = np.nan
        return
    for k in range(values.shape[1]):
        v = values[i0, k] * w0
        v += values[i1, k] * w1
        v += values[i2, k] * w2
        v += values[i3, k] * w3
        out[q, k] = min(v, 1.0) if clamp else v


@_jit(inline="always")
def _locate_one(t, n, move, offsets, status, nodes, weights, exact, moved, q):
    i0, i1, i2, i3, w0, w1, w2, w3, outside = _locate(t, q, n, move, offsets)
    nodes[q, 0], nodes[q, 1], nodes[q, 2], nodes[q, 3] = i0, i1, i2, i3
    weights[q, 0], weights[q, 1], weights[q, 2], weights[q, 3] = w0, w1, w2, w3
    exact[q] = (not outside and status[i0] == 0 and status[i1] == 0 and status[i2] == 0
                and status[i3] == 0)
    moved[q] = outside


@_jit(parallel=True)
def blend_parallel(t, n, move, offsets, status, values, clamp, nan_inexact, out, exact, moved):
    """Blend ``values`` (n³, C) at the queries ``t`` (N, 3) into ``out`` (N, C), threaded."""
    for q in numba.prange(t.shape[0]):
        _blend_one(t, n, move, offsets, status, values, clamp, nan_inexact, out, exact, moved, q)


@_jit()
def blend_serial(t, n, move, offsets, status, values, clamp, nan_inexact, out, exact, moved):
    """:func:`blend_parallel` on one thread."""
    for q in range(t.shape[0]):
        _blend_one(t, n, move, offsets, status, values, clamp, nan_inexact, out, exact, moved, q)


@_jit(parallel=True)
def locate_parallel(t, n, move, offsets, status, nodes, weights, exact, moved):
    """Nodes (N, 4) and weights (N, 4) of the queries ``t`` (N, 3), threaded."""
    for q in numba.prange(t.shape[0]):
        _locate_one(t, n, move, offsets, status, nodes, weights, exact, moved, q)


@_jit()
def locate_serial(t, n, move, offsets, status, nodes, weights, exact, moved):
    """:func:`locate_parallel` on one thread."""
    for q in range(t.shape[0]):
        _locate_one(t, n, move, offsets, status, nodes, weights, exact, moved, q)


@_jit(inline="always")
def _actual_one(q, scale, candidates, origin, inverse, tet_nodes, node_XYZ, slack, tolerance,
                values, clamp, rows, out, nodes, weights, found, i):
    """Path 1 of :mod:`.moved_cells` for query ``i``: the first tetrahedron of actual colours
    among the candidate cells that holds it, checked on its colour, blended into ``out``."""
    found[i] = False
    for r in range(candidates.shape[1]):
        cell = candidates[i, r]
        if cell < 0:
            continue
        for p in range(6):
            d0 = q[i, 0] - origin[cell, p, 0]
            d1 = q[i, 1] - origin[cell, p, 1]
            d2 = q[i, 2] - origin[cell, p, 2]
            b1 = inverse[cell, p, 0, 0] * d0 + inverse[cell, p, 0, 1] * d1 + inverse[cell, p, 0, 2] * d2
            b2 = inverse[cell, p, 1, 0] * d0 + inverse[cell, p, 1, 1] * d1 + inverse[cell, p, 1, 2] * d2
            b3 = inverse[cell, p, 2, 0] * d0 + inverse[cell, p, 2, 1] * d1 + inverse[cell, p, 2, 2] * d2
            b0 = 1.0 - (b1 + b2 + b3)
            # NaN (an unusable tetrahedron) fails every comparison
            if not (b0 >= -slack and b1 >= -slack and b2 >= -slack and b3 >= -slack):
                continue
            w0, w1, w2, w3 = max(b0, 0.0), max(b1, 0.0), max(b2, 0.0), max(b3, 0.0)
            i0, i1 = tet_nodes[cell, p, 0], tet_nodes[cell, p, 1]
            i2, i3 = tet_nodes[cell, p, 2], tet_nodes[cell, p, 3]
            error = 0.0
            for j in range(3):
                v = (w0 * node_XYZ[i0, j] + w1 * node_XYZ[i1, j] + w2 * node_XYZ[i2, j]
                     + w3 * node_XYZ[i3, j])
                error = max(error, abs(v - q[i, j]))
            if not error <= tolerance * scale[i]:
                continue
            found[i] = True
            nodes[i, 0], nodes[i, 1], nodes[i, 2], nodes[i, 3] = i0, i1, i2, i3
            weights[i, 0], weights[i, 1], weights[i, 2], weights[i, 3] = w0, w1, w2, w3
            row = rows[i]
            for k in range(values.shape[1]):
                v = values[i0, k] * w0
                v += values[i1, k] * w1
                v += values[i2, k] * w2
                v += values[i3, k] * w3
                out[row, k] = min(max(v, 0.0), 1.0) if clamp else v
            return


@_jit(parallel=True)
def actual_parallel(q, scale, candidates, origin, inverse, tet_nodes, node_XYZ, slack, tolerance,
                    values, clamp, rows, out, nodes, weights, found):
    """Path 1 of :mod:`.moved_cells` for every query, threaded."""
    for i in numba.prange(q.shape[0]):
        _actual_one(q, scale, candidates, origin, inverse, tet_nodes, node_XYZ, slack, tolerance,
                    values, clamp, rows, out, nodes, weights, found, i)


@_jit()
def actual_serial(q, scale, candidates, origin, inverse, tet_nodes, node_XYZ, slack, tolerance,
                  values, clamp, rows, out, nodes, weights, found):
    """:func:`actual_parallel` on one thread."""
    for i in range(q.shape[0]):
        _actual_one(q, scale, candidates, origin, inverse, tet_nodes, node_XYZ, slack, tolerance,
                    values, clamp, rows, out, nodes, weights, found, i)
