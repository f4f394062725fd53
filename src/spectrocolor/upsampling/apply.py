"""Apply an upsampling table: table coordinates → reflectance spectra by tetrahedral blending.

Each query ``t`` (linear RGB, or XYZ100 / white for an ``"XYZ"`` table) falls in one cell of
the node grid and, within it, in one of the six Freudenthal tetrahedra (chosen by the order of
its fractional coordinates). Its barycentric weights ``β`` (non-negative, summing to one) give
``ρ = Σ β_i ρ_i`` over the tetrahedron's four nodes.

What "exact" means. The colour map is linear and ``Σ β_i t_i = t``, so
``ρ @ W = Σ β_i (ρ_i @ W) = matrix @ t`` whenever every node reproduces its own colour; nodes
are checked to 1e-11 relative (:data:`~spectrocolor.upsampling.table.NODE_TOLERANCE`), so a
query in a tetrahedron of exact nodes is reproduced to that order (tests hold it to 1e-9), and
``0 ≤ ρ ≤ 1`` holds exactly (the blend is convex; the rounding excursion above 1 of at most a
few ulps is clamped). A query inside the cube in a tetrahedron with a node moved toward grey
(its colour outside the object-colour solid) is settled by :mod:`.moved_cells`: exact
wherever some reflectance produces it (a blend by the nodes' actual colours, or a certified
solve), flagged otherwise. Queries outside the cube follow a named strategy from
:data:`OUT_OF_RANGE_STRATEGIES` and are reported ``exact=False``; ``Upsampled.path`` says
which way each query went.

References
----------
J. M. Kasson, S. I. Nin, W. Plouffe, J. L. Hafner, "Performing color space conversions with
three-dimensional linear interpolation", J. Electronic Imaging 4, 226–250 (1995)
(tetrahedral interpolation).

Why this file is long: every way of applying a table (spectra, colours under a light, texel
coefficients, blocks of an image, dask arrays) rests on the one tetrahedral lookup and the out-of-
range strategies defined here; a split would make each caller import the internals of the lookup.
"""

from __future__ import annotations

import weakref
from dataclasses import dataclass
from functools import lru_cache

import numpy as np

from ..errors import ColorimetryError
from ..registry import Registry
from .compiled import MOVE_CODES, run_blend, run_locate
from .compiled import kernels as compiled_kernels
from .moved_cells import EXACT_NODES, OUTSIDE_CUBE, UNSETTLED, settle
from .table import GREY, UpsamplingTable

__all__ = ["OUT_OF_RANGE_STRATEGIES", "Lookup", "Upsampled", "lookup", "upsample",
           "upsample_spectra", "colours_under", "texel_coefficients", "upsample_blocks",
           "upsample_dask"]


def _toward_grey(t: np.ndarray) -> np.ndarray:
    """Move each point along the segment to grey (0.5, 0.5, 0.5) onto the cube's surface."""
    d = t - GREY
    with np.errstate(divide="ignore", invalid="ignore"):
        limit = np.where(d > 0, 0.5 / d, np.where(d < 0, -0.5 / d, np.inf)).min(axis=-1)
    s = np.minimum(limit, 1.0)[..., None]
    return np.clip(GREY + s * d, 0.0, 1.0)


#: Strategies for queries the table cannot reproduce exactly (outside the cube ``[0, 1]^3``, or
#: in a tetrahedron with a moved node). Each maps points outside the cube into it; ``"nan"``
#: additionally returns NaN spectra for every inexact query.
OUT_OF_RANGE_STRATEGIES = Registry("out_of_range", "an out-of-range strategy")
OUT_OF_RANGE_STRATEGIES.add(
    "toward-grey", _toward_grey,
    "move the colour along the segment to grey (0.5, 0.5, 0.5) onto the cube's surface; blend "
    "moved nodes where the table has them")
OUT_OF_RANGE_STRATEGIES.add(
    "clip", lambda t: np.clip(t, 0.0, 1.0),
    "clip each channel to [0, 1]; blend moved nodes where the table has them")
OUT_OF_RANGE_STRATEGIES.add(
    "nan", lambda t: np.clip(t, 0.0, 1.0),
    "NaN spectra for every colour that is not reproduced exactly")


def _strategy(name: str) -> str:
    return OUT_OF_RANGE_STRATEGIES.canonical(name)


def _coordinates(t, argument: str = "rgb_linear") -> np.ndarray:
    try:
        a = np.asarray(t, dtype=np.float64)
    except (TypeError, ValueError):
        raise ColorimetryError(
            f"{argument}: expected numbers of shape (..., 3), got {type(t).__name__}") from None
    if a.ndim == 0 or a.shape[-1] != 3:
        raise ColorimetryError(f"{argument}: expected shape (..., 3), got {a.shape}")
    if not np.all(np.isfinite(a)):
        raise ColorimetryError(f"{argument}: contains NaN or infinite values; pass finite values")
    return a


#: Axes by decreasing fraction (ties: lower axis first) for the comparison code
#: ``4 [f0 >= f1] + 2 [f1 >= f2] + [f0 >= f2]``; codes 1 and 6 cannot occur.
_ORDER_OF_CODE = np.array([(2, 1, 0), (0, 1, 2), (1, 2, 0), (1, 0, 2), (2, 0, 1), (0, 2, 1),
                           (0, 1, 2), (0, 1, 2)], dtype=np.intp)


@lru_cache(maxsize=16)
def _path_offsets(n: int) -> np.ndarray:
    """Flat offsets of the 2nd, 3rd and 4th tetrahedron corner from the cell's base node, per
    comparison code: cumulative sums of the strides ``(n², n, 1)`` in the code's axis order."""
    strides = np.array([n * n, n, 1], dtype=np.intp)
    offsets = np.cumsum(strides[_ORDER_OF_CODE], axis=-1)
    offsets.setflags(write=False)
    return offsets


@dataclass(frozen=True)
class Lookup:
    """Where each query lands: four node indices and their barycentric weights.

    Attributes
    ----------
    nodes : ndarray (..., 4) of intp
        Flat node indices (``(i n + j) n + k``).
    weights : ndarray (..., 4) float64
        Barycentric weights, ≥ 0, summing to 1 (to rounding).
    exact : ndarray of bool (...)
        The query was inside the cube and its four nodes are exact.
    moved : ndarray of bool (...)
        The query was outside the cube and was moved into it by the strategy.
    """

    nodes: np.ndarray
    weights: np.ndarray
    exact: np.ndarray
    moved: np.ndarray


def lookup(table: UpsamplingTable, rgb_linear, out_of_range: str = "toward-grey") -> Lookup:
    """Tetrahedron and barycentric weights of each query (see the module docstring).

    Parameters
    ----------
    table : UpsamplingTable
        From :func:`spectrocolor.upsampling_table`.
    rgb_linear : array_like (..., 3)
        Table coordinates (linear RGB of the table's space, or XYZ100 / white).
    out_of_range : str, default "toward-grey"
        A key of :data:`OUT_OF_RANGE_STRATEGIES`.

    Returns
    -------
    Lookup
        ``nodes`` and barycentric ``weights`` of each query's tetrahedron, ``exact`` (the
        query was inside the cube) and ``moved``.

    Raises
    ------
    ColorimetryError
        For a table of the wrong type, malformed coordinates or an unknown strategy.

    Examples
    --------
    >>> from spectrocolor import upsampling_table
    >>> table = upsampling_table("sRGB", "D65", resolution=3, measure_excess=False)
    >>> lookup(table, [[0.5, 0.5, 0.5], [1.2, 0.5, 0.1]]).exact.tolist()
    [True, False]
    """
    _check_table(table)
    name = _strategy(out_of_range)
    t = _coordinates(rgb_linear)
    compiled = _compiled_kernels(name)
    if compiled is not None:
        lead = t.shape[:-1]
        nodes, weights, exact, moved = run_locate(compiled, _flat(t), *_kernel_table(table, name))
        return Lookup(nodes.reshape(*lead, 4), weights.reshape(*lead, 4), exact.reshape(lead),
                      moved.reshape(lead))
    move = OUT_OF_RANGE_STRATEGIES.get(name)
    outside = np.any((t < 0.0) | (t > 1.0), axis=-1)
    if outside.any():
        t = t.copy()
        t[outside] = move(t[outside])
    n = table.resolution
    s = t * (n - 1)
    base = np.minimum(s.astype(np.intp), n - 2)  # t >= 0 here, so truncation is floor
    f = s - base
    code = ((f[..., 0] >= f[..., 1]).astype(np.intp) * 4 + (f[..., 1] >= f[..., 2]) * 2
            + (f[..., 0] >= f[..., 2]))
    f0, f1, f2 = f[..., 0], f[..., 1], f[..., 2]
    low01, high01 = np.minimum(f0, f1), np.maximum(f0, f1)
    high = np.maximum(high01, f2)  # the fractions sorted by selection (no rounding)
    middle = np.maximum(low01, np.minimum(high01, f2))
    low = np.minimum(low01, f2)
    weights = np.empty((*t.shape[:-1], 4))
    np.subtract(1.0, high, out=weights[..., 0])
    np.subtract(high, middle, out=weights[..., 1])
    np.subtract(middle, low, out=weights[..., 2])
    weights[..., 3] = low
    nodes = np.empty((*t.shape[:-1], 4), dtype=np.intp)
    nodes[..., 0] = (base[..., 0] * n + base[..., 1]) * n + base[..., 2]
    np.add(nodes[..., :1], _path_offsets(n)[code], out=nodes[..., 1:])
    if table.all_exact:
        exact = ~outside
    else:
        exact = ~outside & np.all(table.node_status.ravel()[nodes] == 0, axis=-1)
    return Lookup(nodes, weights, exact, outside)


def _check_table(table) -> None:
    if not isinstance(table, UpsamplingTable):
        raise ColorimetryError(f"table: expected an UpsamplingTable, got {type(table).__name__}")


def _compiled_kernels(name: str):
    """The compiled kernels for strategy ``name`` (canonical), or None: use the NumPy path."""
    return compiled_kernels() if name in MOVE_CODES else None


def _flat(t: np.ndarray) -> np.ndarray:
    """Coordinates (..., 3) as the C-contiguous (N, 3) float64 array the kernels take."""
    return np.ascontiguousarray(t.reshape(-1, 3), dtype=np.float64)


def _kernel_table(table: UpsamplingTable, name: str) -> tuple[int, int, np.ndarray, np.ndarray]:
    """(n, move code, path offsets, flat node status): the table as the kernels take it."""
    n = table.resolution
    status = np.ascontiguousarray(table.node_status, dtype=np.uint8).reshape(-1)
    return n, MOVE_CODES[name], _path_offsets(n), status


def _apply(table: UpsamplingTable, rgb_linear, name: str, values: np.ndarray, clamp: bool,
           out: np.ndarray | None = None, from_spectra=None, settle_moved: bool = True
           ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Blend the node rows ``values`` (n³, C) at the queries: (result (..., C), exact, moved,
    path).

    ``clamp`` applies ``min(·, 1)`` (reflectances); strategy ``"nan"`` gives NaN rows for
    inexact queries. The compiled kernel when available, else :func:`lookup` and :func:`_blend`.
    Then, unless ``settle_moved`` is false, queries inside the cube in tetrahedra with moved
    nodes are settled by :func:`.moved_cells.settle`: blended by the nodes' actual colours, or
    solved (``from_spectra`` maps solved spectra (s, K) to result rows; None: the spectra
    themselves).
    """
    t = _coordinates(rgb_linear)
    lead, channels = t.shape[:-1], values.shape[1]
    compiled = _compiled_kernels(name)
    if compiled is None:
        found = lookup(table, t, name)
        flat_out = None if out is None else out.reshape(-1, channels)
        result = _blend(values, found, flat_out).reshape(-1, channels)
        if clamp:
            np.minimum(result, 1.0, out=result)
        exact, moved = found.exact.reshape(-1), found.moved.reshape(-1)
        if name == "nan":
            result[~exact] = np.nan
    else:
        direct = (out is not None and out.dtype == np.float64 and out.flags.c_contiguous
                  and out.size == int(np.prod(lead, dtype=np.int64)) * channels)
        result = (out.reshape(-1, channels) if direct and out is not None
                  else np.empty((t.size // 3, channels)))
        exact, moved = run_blend(compiled, _flat(t), *_kernel_table(table, name),
                                 np.ascontiguousarray(values, dtype=np.float64), clamp,
                                 name == "nan", result)
    path = np.where(moved, OUTSIDE_CUBE, np.where(exact, EXACT_NODES, UNSETTLED)).astype(np.uint8)
    if settle_moved and not table.all_exact:
        _settle(table, t.reshape(-1, 3), values, clamp, from_spectra, result, exact, path)
    if out is not None and not np.may_share_memory(out, result):  # result is a view of out, or new
        out[...] = result.reshape(out.shape)
        result = out
    return (result.reshape(*lead, channels), exact.reshape(lead), moved.reshape(lead),
            path.reshape(lead))


def _settle(table, t, values, clamp, from_spectra, result, exact, path) -> None:
    """Settle, in place, the inexact queries inside the cube (see :mod:`.moved_cells`)."""
    chosen = np.flatnonzero(path == UNSETTLED)
    if chosen.size == 0:
        return
    got = settle(table, t[chosen], values, clamp, result, chosen)
    path[chosen] = got.path
    rows = chosen[got.solved]
    if rows.size:
        result[rows] = got.spectra if from_spectra is None else from_spectra(got.spectra)
    exact[chosen[got.blended]] = True
    exact[rows] = True


def _blend(values: np.ndarray, found: Lookup, out: np.ndarray | None = None) -> np.ndarray:
    """``Σ_j weights_j · values[nodes_j]`` along a new last axis of length values.shape[1]."""
    lead = found.nodes.shape[:-1]
    idx = found.nodes.reshape(-1, 4)
    w = found.weights.reshape(-1, 4)
    result = np.multiply(values[idx[:, 0]], w[:, :1], out=out)
    scratch = np.empty_like(result)
    for j in range(1, 4):
        np.take(values, idx[:, j], axis=0, out=scratch)
        scratch *= w[:, j:j + 1]
        result += scratch
    return result.reshape(*lead, values.shape[1])


@dataclass(frozen=True)
class Upsampled:
    """Result of :func:`upsample`.

    Attributes
    ----------
    reflectance : ndarray (..., K)
        Reflectance factors (0–1), on ``wavelengths_nm``; NaN where ``out_of_range="nan"``
        refused a query.
    wavelengths_nm : ndarray (K,)
    exact : ndarray of bool (...)
        The spectrum reproduces the query's colour (``table.matrix @ t``) to 1e-9 relative
        and lies in [0, 1]: every query inside the cube whose colour some reflectance
        produces (inside the object-colour solid), unless ``settle_moved=False``.
    moved : ndarray of bool (...)
        The query lay outside the cube and was moved by the strategy.
    out_of_range : str
        The strategy used.
    path : ndarray of uint8 (...)
        How each query was answered: a code of
        :data:`spectrocolor.upsampling.moved_cells.PATHS` (0 blend of exact nodes, 1 blend by
        the nodes' actual colours, 2 certified solve, 3 outside the solid, 4 outside the cube,
        5 not settled).
    """

    reflectance: np.ndarray
    wavelengths_nm: np.ndarray
    exact: np.ndarray
    moved: np.ndarray
    out_of_range: str
    path: np.ndarray


def upsample(table: UpsamplingTable, rgb_linear, out_of_range: str = "toward-grey", *,
             settle_moved: bool = True) -> Upsampled:
    """Reflectance spectra for colours, by tetrahedral blending of the table's nodes.

    In tetrahedra with nodes moved toward grey (wide-gamut spaces), queries inside the cube
    are settled exactly wherever a reflectance exists
    (:mod:`spectrocolor.upsampling.moved_cells`): blended by the nodes' actual colours, or solved by the certified
    smoothest-reflectance solver; colours outside the object-colour solid keep the table's
    blend and ``exact=False``.

    Parameters
    ----------
    table : UpsamplingTable
    rgb_linear : array_like (..., 3)
        Linear RGB of the table's space (or XYZ100 / white for an ``"XYZ"`` table). Decode
        8/16-bit images first with :func:`spectrocolor.upsampling.rgb_linear_from_image`.
    out_of_range : {"toward-grey", "clip", "nan"}
        What to do with queries that cannot be reproduced exactly (see
        :data:`OUT_OF_RANGE_STRATEGIES`); they are reported in ``exact``/``moved``.
    settle_moved : bool, keyword-only, default True
        Settle the queries in tetrahedra with moved nodes exactly (above); False keeps the plain
        grid blend there (path 5, ``exact=False``), at the table's full speed.

    Returns
    -------
    Upsampled

    Examples
    --------
    >>> from spectrocolor.upsampling import upsampling_table
    >>> table = upsampling_table("sRGB", "D65", resolution=3, measure_excess=False)
    >>> u = upsample(table, [[0.2, 0.5, 0.7], [1.5, 0.5, 0.5]])
    >>> u.exact.tolist(), u.moved.tolist()
    ([True, False], [False, True])
    >>> XYZ = u.reflectance[0] @ table.weights
    >>> bool(abs(XYZ - table.matrix @ [0.2, 0.5, 0.7]).max() < 1e-9 * XYZ.max())
    True
    """
    _check_table(table)
    out_of_range = _strategy(out_of_range)
    rho, exact, moved, path = _apply(table, rgb_linear, out_of_range, table.flat_reflectance,
                                     True, settle_moved=settle_moved)
    return Upsampled(rho, table.wavelengths_nm, exact, moved, out_of_range, path)


def upsample_spectra(table: UpsamplingTable, rgb_linear, out_of_range: str = "toward-grey",
                     out: np.ndarray | None = None, *, settle_moved: bool = True) -> np.ndarray:
    """Only the spectra of :func:`upsample` (``(..., K)`` float64), optionally into ``out``.

    Parameters
    ----------
    table : UpsamplingTable
        From :func:`spectrocolor.upsampling_table`.
    rgb_linear : array_like, shape (..., 3)
        Table coordinates.
    out_of_range : str, default "toward-grey"
        A key of :data:`OUT_OF_RANGE_STRATEGIES` (``"nan"`` gives NaN spectra outside).
    out : numpy.ndarray, shape (..., K), optional
        Where to write the spectra.
    settle_moved : bool, keyword-only, default True
        As in :func:`upsample`.

    Returns
    -------
    numpy.ndarray, shape (..., K)
        Reflectance factors (0–1).

    Raises
    ------
    ColorimetryError
        As :func:`lookup`.

    Examples
    --------
    >>> from spectrocolor import upsampling_table
    >>> table = upsampling_table("sRGB", "D65", resolution=3, measure_excess=False)
    >>> spectra = upsample_spectra(table, [[0.5, 0.5, 0.5]])
    >>> spectra.shape, bool(abs(spectra - 0.5).max() < 1e-9)  # mid grey: a flat 50 %
    ((1, 81), True)
    """
    _check_table(table)
    out_of_range = _strategy(out_of_range)
    return _apply(table, rgb_linear, out_of_range, table.flat_reflectance, True, out,
                  settle_moved=settle_moved)[0]


#: Node colours per table and weights (relighting an image block by block reuses them; a
#: threaded 4913 x 81 matrix product costs as much as blending 10⁵ colours on a busy machine).
_NODE_COLOURS: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()
_NODE_COLOURS_PER_TABLE = 8


def node_colours(table: UpsamplingTable, weights) -> np.ndarray:
    """Colours of the nodes under other weights ``(K, 3)``: ``(n³, 3)`` = ``ρ_nodes @ weights``.

    Parameters
    ----------
    table : UpsamplingTable
        From :func:`spectrocolor.upsampling_table`.
    weights : array_like, shape (K, 3)
        Tristimulus weights on the table's grid.

    Returns
    -------
    numpy.ndarray, shape (n³, 3)
        The nodes' colours on the weights' scale (read-only; cached per table and weights).

    Raises
    ------
    ColorimetryError
        For weights of another shape.

    Examples
    --------
    >>> from spectrocolor import upsampling_table
    >>> table = upsampling_table("sRGB", "D65", resolution=3, measure_excess=False)
    >>> from spectrocolor import weights
    >>> node_colours(table, weights(table.wavelengths_nm, illuminant="A")).shape
    (27, 3)
    """
    W = np.asarray(weights, dtype=np.float64)
    K = table.wavelengths_nm.size
    if W.shape != (K, 3):
        raise ColorimetryError(f"weights: expected shape ({K}, 3) on the table's grid, got {W.shape}")
    cached = _NODE_COLOURS.setdefault(table, {})
    key = W.tobytes()
    if key not in cached:
        if len(cached) >= _NODE_COLOURS_PER_TABLE:
            cached.pop(next(iter(cached)))
        colours = table.flat_reflectance @ W
        colours.setflags(write=False)
        cached[key] = colours
    return cached[key]


def colours_under(table: UpsamplingTable, rgb_linear, weights, out_of_range: str = "toward-grey",
                  *, settle_moved: bool = True):
    """The colour of each query's upsampled spectrum under other weights, without the spectra.

    Because blending is linear, ``(Σ β_i ρ_i) @ W' = Σ β_i (ρ_i @ W')``: the node colours under
    the new weights form a 3-channel table and each query costs four 3-vector gathers instead
    of four K-vector gathers. Equal to ``upsample(...).reflectance @ weights`` to rounding.

    Parameters
    ----------
    table : UpsamplingTable
        From :func:`spectrocolor.upsampling_table`.
    rgb_linear : array_like (..., 3)
        Table coordinates.
    weights : ndarray (K, 3)
        E.g. ``spectrocolor.weights(table.wavelengths_nm, illuminant="A")`` (XYZ100 under A).
    out_of_range : str, default "toward-grey"
        A key of :data:`OUT_OF_RANGE_STRATEGIES`.
    settle_moved : bool, keyword-only, default True
        As in :func:`upsample`: queries in tetrahedra with moved nodes take the colour of their
        exact spectrum (the actual-colour blend, or the certified solve's spectrum under
        ``weights``).

    Returns
    -------
    XYZ : ndarray (..., 3)
        Colours under the new weights, on their scale.
    exact : ndarray of bool (...)
        Whether each query's spectrum reproduces it under the table's own light (as
        :attr:`Upsampled.exact`).

    Examples
    --------
    >>> from spectrocolor import upsampling_table
    >>> table = upsampling_table("sRGB", "D65", resolution=3, measure_excess=False)
    >>> from spectrocolor import weights
    >>> XYZ, exact = colours_under(table, [[1.0, 1.0, 1.0]], weights(table.wavelengths_nm, illuminant="A"))
    >>> XYZ.round(3).tolist(), exact.tolist()  # the white reflects 1 everywhere: A's white
    ([[109.849, 100.0, 35.582]], [True])
    """
    _check_table(table)
    out_of_range = _strategy(out_of_range)
    W = np.asarray(weights, dtype=np.float64)
    XYZ, exact, _, _ = _apply(table, rgb_linear, out_of_range, node_colours(table, W), False,
                              from_spectra=lambda rho: rho @ W, settle_moved=settle_moved)
    return XYZ, exact


def texel_coefficients(table: UpsamplingTable, rgb_linear, out_of_range: str = "toward-grey"):
    """Per-texel coefficients for texture baking: four node indices and four weights.

    A renderer holding the table evaluates the texel's reflectance at any wavelength as
    ``Σ_j weights[j] · ρ_{nodes[j]}(λ)`` (linear interpolation between the table's wavelength
    samples), with no lookup at render time.

    Parameters
    ----------
    table : UpsamplingTable
        From :func:`spectrocolor.upsampling_table`.
    rgb_linear : array_like, shape (..., 3)
        Table coordinates of the texels.
    out_of_range : str, default "toward-grey"
        A key of :data:`OUT_OF_RANGE_STRATEGIES`.

    Returns
    -------
    nodes : ndarray (..., 4) uint32
        Flat node indices into the table's ``(n³, K)`` reflectance array.
    weights : ndarray (..., 4) float32
        Barycentric weights (sum to 1 within float32 rounding, ~1e-7).
    exact : ndarray of bool (...)
        Whether each texel was inside the table's cube.

    Examples
    --------
    >>> from spectrocolor import upsampling_table
    >>> table = upsampling_table("sRGB", "D65", resolution=3, measure_excess=False)
    >>> nodes, weights, exact = texel_coefficients(table, [[0.5, 0.5, 0.5]])
    >>> nodes.dtype.name, weights.dtype.name, round(float(weights.sum()), 6), exact.tolist()
    ('uint32', 'float32', 1.0, [True])
    """
    _check_table(table)
    name = _strategy(out_of_range)
    compiled = _compiled_kernels(name)
    if compiled is None:
        found = lookup(table, rgb_linear, name)
        return found.nodes.astype(np.uint32), found.weights.astype(np.float32), found.exact
    t = _coordinates(rgb_linear)
    lead = t.shape[:-1]
    nodes, weights, exact, _ = run_locate(compiled, _flat(t), *_kernel_table(table, name),
                                          np.uint32, np.float32)
    return nodes.reshape(*lead, 4), weights.reshape(*lead, 4), exact.reshape(lead)


def upsample_blocks(table: UpsamplingTable, image, out_of_range: str = "toward-grey",
                    max_block_mib: float = 64.0):
    """Stream the spectra of a large image in row blocks of bounded memory.

    Parameters
    ----------
    table : UpsamplingTable
        From :func:`spectrocolor.upsampling_table`.
    image : array_like (H, ...) with last axis 3, e.g. a ``np.memmap``
        Linear table coordinates; only one block is read and converted at a time.
    out_of_range : str, default "toward-grey"
        A key of :data:`OUT_OF_RANGE_STRATEGIES`.
    max_block_mib : float, default 64.0
        Budget of one block's spectra (float64), MiB.

    Yields
    ------
    (slice, ndarray)
        The rows and their spectra ``(rows, ..., K)``.

    Raises
    ------
    ColorimetryError
        For an image whose last axis is not 3 or a budget that is not positive.

    Examples
    --------
    >>> import numpy as np
    >>> from spectrocolor import upsampling_table
    >>> table = upsampling_table("sRGB", "D65", resolution=3, measure_excess=False)
    >>> blocks = list(upsample_blocks(table, np.full((4, 2, 3), 0.5), max_block_mib=0.001))
    >>> len(blocks), blocks[0][0], blocks[0][1].shape
    (4, slice(0, 1, None), (1, 2, 81))
    """
    shape = tuple(np.shape(image))
    if len(shape) < 2 or shape[-1] != 3:
        raise ColorimetryError(f"image: expected shape (H, ..., 3), got {shape}")
    max_block_mib = float(max_block_mib)
    if not np.isfinite(max_block_mib) or max_block_mib <= 0:
        raise ColorimetryError(f"max_block_mib: expected a positive number, got {max_block_mib!r}")
    per_row = int(np.prod(shape[1:-1], dtype=np.int64)) * table.wavelengths_nm.size * 8 * 3
    rows = max(1, int(max_block_mib * 2**20) // max(per_row, 1))
    for start in range(0, shape[0], rows):
        block = slice(start, min(start + rows, shape[0]))
        yield block, upsample_spectra(table, image[block], out_of_range)


def upsample_dask(table: UpsamplingTable, rgb_linear, out_of_range: str = "toward-grey"):
    """Lazy spectra of a dask array ``(..., 3)`` (chunked on the leading axes): ``(..., K)``.

    Each chunk goes through :func:`upsample_spectra`, so the numbers equal the NumPy path's.

    Parameters
    ----------
    table : UpsamplingTable
        From :func:`spectrocolor.upsampling_table`.
    rgb_linear : dask.array.Array, shape (..., 3)
        Table coordinates (the last axis is rechunked to one chunk).
    out_of_range : str, default "toward-grey"
        A key of :data:`OUT_OF_RANGE_STRATEGIES`.

    Returns
    -------
    dask.array.Array, shape (..., K)
        Lazy float64 reflectances, chunked like the input's leading axes.

    Raises
    ------
    ColorimetryError
        For an unknown strategy or an array whose last axis is not 3.

    Examples
    --------
    >>> import dask.array as da
    >>> from spectrocolor import upsampling_table
    >>> table = upsampling_table("sRGB", "D65", resolution=3, measure_excess=False)
    >>> spectra = upsample_dask(table, da.full((4, 2, 3), 0.5, chunks=(2, 2, 3)))
    >>> spectra.shape, spectra.chunks[0]
    ((4, 2, 81), (2, 2))
    """
    import dask.array as da

    _strategy(out_of_range)
    if rgb_linear.ndim == 0 or rgb_linear.shape[-1] != 3:
        raise ColorimetryError(f"rgb_linear: expected shape (..., 3), got {rgb_linear.shape}")
    arr = rgb_linear.rechunk({rgb_linear.ndim - 1: 3})
    K = table.wavelengths_nm.size
    return da.map_blocks(upsample_spectra, table, arr, out_of_range, dtype=np.float64,
                         chunks=(*arr.chunks[:-1], (K,)))
