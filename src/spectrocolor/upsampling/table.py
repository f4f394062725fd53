"""The spectral upsampling table: certified smoothest reflectances at the nodes of a colour cube.

A table covers the cube ``[0, 1]^3`` of *table coordinates* ``t`` with ``n`` equally spaced
nodes per axis. Table coordinates are linear RGB of a display space (``space="sRGB"``, any
built-in or custom :class:`~spectrocolor.RGBSpace`) or, with ``space="XYZ"``, tristimulus
values divided component-wise by the perfect white (``XYZ100 / white``). One linear map, the
*colour map* ``XYZ100 = matrix @ t``, ties them to the tristimulus values of reflectances under
the table's illuminant on its wavelength grid:

* RGB spaces: ``matrix = A @ M``, where ``M`` is the space's ``matrix_to_XYZ`` and ``A`` is the
  Bradford adaptation from the space's white to the perfect white ``W.sum(axis=0)`` of the
  weights ``W`` (so ``t = (1, 1, 1)`` is the perfect reflector ρ = 1 and ``t = 0.5`` is the
  centre of the object-colour solid, ρ = 0.5);
* ``"XYZ"``: ``matrix = diag(W.sum(axis=0))``.

At every node the smoothest reflectance with ``0 ≤ ρ ≤ 1`` (van Trigt 1990, solved by
:func:`spectrocolor.smoothest_reflectance`) is computed and *re-checked here*: finite, bounds
held exactly, colour reproduced to :data:`NODE_TOLERANCE` relative, solver certificate passed.
A node that fails (its colour lies outside the object-colour solid, or the solver cannot
certify it) is handled by the node strategy ``"toward-grey"``: its colour is moved along the
segment to the solid's centre ``t = (0.5, 0.5, 0.5)`` to the farthest point (bisection,
:data:`BISECTION_STEPS` halvings) at which a certified solution exists, and the node is marked
``moved`` (status 1). Blending by the grid weights is not exact in tetrahedra with a moved
vertex; :mod:`spectrocolor.upsampling.moved_cells` settles their queries (exact wherever a
reflectance exists, flagged outside the object-colour solid).

Per cell the table records the roughness excess of interpolation over the true optimum:

* ``cell_excess_bound`` (nm⁻¹): a rigorous upper bound. The optimal roughness ``v(XYZ)`` is
  convex with subgradient ``μ`` (the Lagrange multipliers of the node), and the roughness
  ``J`` is convex, so for ``ρ = Σ β_i ρ_i`` in a tetrahedron
  ``J(ρ) − v(XYZ) ≤ min_j max_i [R_i − R_j − μ_j · (XYZ_i − XYZ_j)]``;
* ``cell_excess_measured`` (nm⁻¹): the largest excess found by solving exactly at the centroid
  of each of the cell's six tetrahedra.

References
----------
C. van Trigt, "Smoothest reflectance functions. I. Definition and main results", J. Opt. Soc.
Am. A 7, 1891–1904 (1990).
H. Freudenthal, "Simplizialzerlegungen von beschränkter Flachheit", Ann. Math. 43, 580–582
(1942) (the six-tetrahedron split of a cube used for interpolation).
"""

from __future__ import annotations

from dataclasses import dataclass
from numbers import Integral

import numpy as np

from .. import notebook_hooks
from ..colorimetry import weights
from ..errors import ColorimetryError

__all__ = ["UpsamplingTable", "upsampling_table", "NODE_TOLERANCE", "NODE_STATUS"]

#: Relative tolerance of a node's colour: ``max|ρ @ W − XYZ100| ≤ NODE_TOLERANCE · max|XYZ100|``.
NODE_TOLERANCE = 1e-11
#: Halvings of the segment to the centre for a node that must be moved.
BISECTION_STEPS = 24
#: Node status codes (uint8 in the file).
NODE_STATUS = {0: "exact", 1: "moved toward grey"}
#: Resolutions accepted (nodes per axis).
MIN_RESOLUTION, MAX_RESOLUTION = 2, 129
#: Wavelength samples of the default grid (380-780 nm in 5 nm steps).
DEFAULT_SAMPLES = 81
#: Memory of building a table, in units of its node reflectances (n³ K float64): the batch
#: solver's working arrays. Measured peaks (``/usr/bin/time -v``, interpreter excluded): about
#: 9x at n = 17, 10x at n = 25, 10x at n = 65 (1.8 GiB).
BUILD_FACTOR = 12

GREY = np.array([0.5, 0.5, 0.5])


@dataclass(frozen=True, eq=False)
class UpsamplingTable:
    """A spectral upsampling table (see the module docstring for what each part means).

    Attributes
    ----------
    wavelengths_nm : ndarray (K,)
        The uniform wavelength grid of the reflectances.
    reflectance : ndarray (n, n, n, K), float64
        Node reflectances (0–1 scale), indexed by the table coordinates' grid indices.
    node_XYZ100 : ndarray (n, n, n, 3)
        The colour each node's reflectance actually produces (``ρ @ W``).
    node_status : ndarray (n, n, n), uint8
        0 exact, 1 moved toward grey (see :data:`NODE_STATUS`).
    roughness : ndarray (n, n, n)
        ``Σ (Δρ)² / Δλ`` of each node (nm⁻¹).
    multipliers : ndarray (n, n, n, 3)
        Lagrange multipliers μ of each node's colour constraint (roughness per XYZ100 unit).
    cell_excess_bound, cell_excess_measured : ndarray (n-1, n-1, n-1)
        Roughness excess of interpolation over the optimum (nm⁻¹); NaN in cells with a moved
        node, where interpolation is not exact and no bound is claimed.
    matrix : ndarray (3, 3)
        The colour map ``XYZ100 = matrix @ t``.
    weights : ndarray (K, 3)
        The tristimulus weights ``W`` (illuminant × observer × Δλ, perfect white Y = 100).
    space, illuminant, observer : str
        Labels of what the table was built for.

    References
    ----------
    C. van Trigt, J. Opt. Soc. Am. A 7, 1891–1904 (1990) (the smoothest reflectances at the
    nodes).

    Examples
    --------
    >>> from spectrocolor import upsampling_table
    >>> table = upsampling_table("sRGB", "D65", resolution=3, measure_excess=False)
    >>> table
    UpsamplingTable(space='sRGB', illuminant='D65', observer='CIE 1931 2°', resolution=3, K=81, moved_nodes=0)
    >>> table.node_XYZ100[2, 2, 2].round(3).tolist()  # the white node
    [95.043, 100.0, 108.88]
    """

    wavelengths_nm: np.ndarray
    reflectance: np.ndarray
    node_XYZ100: np.ndarray
    node_status: np.ndarray
    roughness: np.ndarray
    multipliers: np.ndarray
    cell_excess_bound: np.ndarray
    cell_excess_measured: np.ndarray
    matrix: np.ndarray
    weights: np.ndarray
    space: str
    illuminant: str
    observer: str

    @property
    def resolution(self) -> int:
        """Nodes per axis ``n``."""
        return self.reflectance.shape[0]

    @property
    def all_exact(self) -> bool:
        """True when every node is exact, so every query inside the cube is reproduced."""
        return bool(np.all(self.node_status == 0))

    @property
    def flat_reflectance(self) -> np.ndarray:
        """Node reflectances as a C-contiguous ``(n³, K)`` view (node ``(i, j, k)`` at row
        ``(i n + j) n + k``)."""
        return self.reflectance.reshape(-1, self.reflectance.shape[-1])

    _repr_html_, _repr_svg_ = notebook_hooks.html, notebook_hooks.svg  # notebooks: spectrocolor.notebook

    def __repr__(self) -> str:
        moved = int(np.count_nonzero(self.node_status))
        return (f"UpsamplingTable(space={self.space!r}, illuminant={self.illuminant!r}, "
                f"observer={self.observer!r}, resolution={self.resolution}, "
                f"K={self.wavelengths_nm.size}, moved_nodes={moved})")


def colour_map(space, weights: np.ndarray) -> tuple[np.ndarray, str]:
    """The matrix ``XYZ100 = matrix @ t`` and the space's label (see the module docstring).

    Parameters
    ----------
    space : str or RGBSpace
        A display space (its linear RGB, Bradford-adapted so that RGB = 1 is the perfect white
        under the weights' illuminant) or ``"XYZ"`` (XYZ100 divided by the perfect white).
    weights : numpy.ndarray, shape (K, 3)
        Tristimulus weights (perfect white Y = 100).

    Returns
    -------
    matrix : numpy.ndarray, shape (3, 3)
        ``XYZ100 = matrix @ t``.
    label : str
        The space's name.

    Examples
    --------
    >>> from spectrocolor import wavelength_grid, weights
    >>> matrix, label = colour_map("sRGB", weights(wavelength_grid(380, 780, 5), illuminant="D65"))
    >>> label, (matrix @ [1.0, 1.0, 1.0]).round(3).tolist()
    ('sRGB', [95.043, 100.0, 108.88])
    """
    white = weights.sum(axis=0)
    if isinstance(space, str) and space.strip().upper() == "XYZ":
        return np.diag(white), "XYZ"
    from ..display.adaptation import adaptation_matrix
    from ..display.spaces import rgb_space

    rgb = rgb_space(space)
    return adaptation_matrix(rgb.white_XYZ, white, "bradford") @ rgb.matrix_to_XYZ, rgb.name


def node_coordinates(n: int) -> np.ndarray:
    """Table coordinates of the nodes, ``(n, n, n, 3)``: ``t[i, j, k] = (i, j, k) / (n - 1)``.

    Parameters
    ----------
    n : int
        Nodes per axis.

    Returns
    -------
    numpy.ndarray, shape (n, n, n, 3)
        The coordinates, 0–1.

    Examples
    --------
    >>> node_coordinates(3)[2, 1, 0].tolist()
    [1.0, 0.5, 0.0]
    """
    axis = np.linspace(0.0, 1.0, n)
    return np.stack(np.meshgrid(axis, axis, axis, indexing="ij"), axis=-1)


def _resolution(resolution) -> int:
    if (isinstance(resolution, bool) or not isinstance(resolution, Integral)
            or not MIN_RESOLUTION <= int(resolution) <= MAX_RESOLUTION):
        raise ColorimetryError(
            f"resolution: expected an integer number of nodes per axis from {MIN_RESOLUTION} "
            f"to {MAX_RESOLUTION}, got {resolution!r}"
        )
    return int(resolution)


def _solve_checked(XYZ100, illuminant, observer, wavelengths):
    """Smoothest bounded reflectances, re-checked here; (ρ, μ, roughness, ok)."""
    from ..recovery.smoothest import smoothest_reflectance

    result = smoothest_reflectance(XYZ100, illuminant=illuminant, observer=observer, wavelengths=wavelengths,
                                   bounds="unit")
    rho = np.asarray(result.spectrum.values, dtype=float)
    return rho, np.asarray(result.multipliers, dtype=float), result, (
        np.asarray(result.feasible) & np.asarray(result.certificate.converged))


def verify_reflectances(rho: np.ndarray, XYZ100: np.ndarray, weights: np.ndarray,
                        tolerance: float = NODE_TOLERANCE) -> np.ndarray:
    """True where ρ is finite, ``0 ≤ ρ ≤ 1`` exactly and ``ρ @ W`` reproduces ``XYZ100`` to
    ``tolerance`` relative to ``max|XYZ100|`` (per colour; black must be reproduced exactly).

    Parameters
    ----------
    rho : numpy.ndarray, shape (..., K)
        Reflectances (0–1).
    XYZ100 : numpy.ndarray, shape (..., 3)
        The colours they must produce.
    weights : numpy.ndarray, shape (K, 3)
        Tristimulus weights.
    tolerance : float, default NODE_TOLERANCE
        Relative tolerance on the colour.

    Returns
    -------
    numpy.ndarray of bool, shape (...)
        Whether each reflectance is valid and exact.

    Examples
    --------
    >>> import numpy as np
    >>> from spectrocolor import wavelength_grid, weights
    >>> W = weights(wavelength_grid(380, 780, 5), illuminant="D65")
    >>> rho = np.full((2, 81), 0.5)
    >>> rho[1, 0] = 1.2  # above 1: not a reflectance
    >>> verify_reflectances(rho, rho @ W, W).tolist()
    [True, False]
    """
    with np.errstate(invalid="ignore"):
        finite = np.all(np.isfinite(rho), axis=-1)
        inside = np.all((rho >= 0.0) & (rho <= 1.0), axis=-1)
        error = np.abs(rho @ weights - XYZ100).max(axis=-1)
        scale = np.abs(XYZ100).max(axis=-1)
        return finite & inside & (error <= tolerance * scale)


def _toward_grey(t_fail, matrix, illuminant, observer, wavelengths, weights):
    """Bisection on the segment from each failed node to the centre: the farthest certified
    point. Returns (t, ρ, μ, result-roughness)."""
    lo = np.zeros(len(t_fail))
    hi = np.ones(len(t_fail))
    for _ in range(BISECTION_STEPS):
        mid = 0.5 * (lo + hi)
        t_mid = GREY + mid[:, None] * (t_fail - GREY)
        XYZ = t_mid @ matrix.T
        rho, _, _, ok = _solve_checked(XYZ, illuminant, observer, wavelengths)
        ok &= verify_reflectances(rho, XYZ, weights)
        lo = np.where(ok, mid, lo)
        hi = np.where(ok, hi, mid)
    t_moved = GREY + lo[:, None] * (t_fail - GREY)
    XYZ = t_moved @ matrix.T
    rho, mu, result, ok = _solve_checked(XYZ, illuminant, observer, wavelengths)
    if not np.all(ok & verify_reflectances(rho, XYZ, weights)):
        raise ColorimetryError(
            "the smoothest-reflectance solver could not certify the centre of the object-colour "
            "solid for this illuminant/observer/grid; no table can be built"
        )
    return rho, mu, np.asarray(result.roughness, dtype=float)


# the six tetrahedra of the Freudenthal split, as corner offsets (i, j, k) within a cell:
# the path 0 -> e_a -> e_a + e_b -> (1, 1, 1) for each order (a, b, c) of the axes
_ORDERS = ((0, 1, 2), (0, 2, 1), (1, 0, 2), (1, 2, 0), (2, 0, 1), (2, 1, 0))


def tetrahedron_corners() -> np.ndarray:
    """Corner offsets of the six tetrahedra, ``(6, 4, 3)`` integers; tetrahedron ``p`` holds
    the points whose fractional coordinates are ordered as ``_ORDERS[p]`` (largest first).

    Returns
    -------
    numpy.ndarray of int64, shape (6, 4, 3)
        Offsets 0/1 of each tetrahedron's corners within a cell, from (0, 0, 0) to (1, 1, 1).

    Examples
    --------
    >>> tetrahedron_corners()[0].tolist()
    [[0, 0, 0], [1, 0, 0], [1, 1, 0], [1, 1, 1]]
    """
    corners = np.zeros((6, 4, 3), dtype=np.int64)
    for p, order in enumerate(_ORDERS):
        for step, axis in enumerate(order):
            corners[p, step + 1:, axis] = 1
    return corners


def _cell_tetrahedra(n: int) -> tuple[np.ndarray, np.ndarray]:
    """Grid indices ``(c, c, c, 6, 4, 3)`` and flat node indices ``(c, c, c, 6, 4)`` of the
    corners of every tetrahedron of every cell (``c = n − 1``)."""
    base = np.stack(np.meshgrid(*(np.arange(n - 1),) * 3, indexing="ij"), axis=-1)
    corners = base[..., None, None, :] + tetrahedron_corners()
    return corners, (corners[..., 0] * n + corners[..., 1]) * n + corners[..., 2]


def _excess_bound(n, XYZ, R, mu, exact):
    """Rigorous per-cell bound ``max_tet min_j max_i [R_i − R_j − μ_j · (XYZ_i − XYZ_j)]``."""
    flat = _cell_tetrahedra(n)[1]
    X, Rf, M, E = XYZ.reshape(-1, 3), R.ravel(), mu.reshape(-1, 3), exact.ravel()
    Xc, Rc, Mc = X[flat], Rf[flat], M[flat]  # (..., 6, 4[, 3])
    # gap[..., j, i] = R_i − R_j − μ_j · (X_i − X_j)
    gap = (Rc[..., None, :] - Rc[..., :, None]
           - np.einsum("...jc,...jic->...ji", Mc, Xc[..., None, :, :] - Xc[..., :, None, :]))
    per_tet = gap.max(axis=-1).min(axis=-1)
    cell = np.maximum(per_tet.max(axis=-1), 0.0)
    cell_exact = E[flat].all(axis=(-1, -2))
    return np.where(cell_exact, cell, np.nan)


def _excess_measured(n, reflectance, exact, matrix, illuminant, observer, wavelengths, step):
    """Roughness of the interpolated ρ minus the exact optimum at every tetrahedron centroid."""
    corners, flat = _cell_tetrahedra(n)
    blend = reflectance.reshape(-1, reflectance.shape[-1])[flat].mean(axis=-2)  # (c,c,c,6,K)
    XYZ = (corners.mean(axis=-2) / (n - 1)) @ matrix.T
    rho, _, result, ok = _solve_checked(XYZ.reshape(-1, 3), illuminant, observer, wavelengths)
    optimum = np.where(ok, np.asarray(result.roughness, dtype=float), np.nan)
    interp = np.sum(np.diff(blend, axis=-1) ** 2, axis=-1) / step
    excess = (interp - optimum.reshape(interp.shape)).max(axis=-1)
    cell_exact = exact.ravel()[flat].all(axis=(-1, -2))
    return np.where(cell_exact, excess, np.nan)


def table_build_bytes(resolution: int, samples: int) -> int:
    """Memory of building a table of ``resolution`` nodes per axis on ``samples`` wavelengths.

    :data:`BUILD_FACTOR` times the node reflectances (n³ K float64): the batch solver's working
    arrays, as measured.

    Parameters
    ----------
    resolution : int
        Nodes per axis ``n``.
    samples : int
        Wavelength samples ``K``.

    Returns
    -------
    int
        Bytes (an estimate from measured peaks, rounded up).

    Examples
    --------
    >>> round(table_build_bytes(65, 81) / 2**30, 2)   # the largest resolution of the CLI: GiB
    1.99
    """
    return BUILD_FACTOR * int(resolution) ** 3 * int(samples) * 8


def upsampling_table(space="sRGB", illuminant="D65", observer="1931",
                     wavelengths=(380.0, 780.0, 5.0), resolution: int = 17,
                     measure_excess: bool = True, *, memory_budget=None) -> UpsamplingTable:
    """Build a spectral upsampling table from certified smoothest reflectances.

    Parameters
    ----------
    space : str or RGBSpace
        Table coordinates: a display space's linear RGB (default ``"sRGB"``; e.g.
        ``"Rec. 2020"``) or ``"XYZ"`` (XYZ100 divided by the perfect white).
    illuminant : str or Spectrum
        The light under which the reflectances produce the colours (default ``"D65"``); see
        :term:`illuminant`.
    observer : str
        Observer name or alias (default ``"1931"``).
    wavelengths : (start_nm, stop_nm, step_nm)
        Uniform grid of the reflectances (default 380–780 nm in 5 nm steps).
    resolution : int
        Nodes per axis ``n`` (2 to 129; default 17, i.e. 16 cells per axis, 4913 nodes).
    measure_excess : bool
        Solve exactly at the six tetrahedron centroids of every cell to record the measured
        roughness excess (``6 (n−1)³`` extra solves); otherwise ``cell_excess_measured`` is NaN.
    memory_budget : int or str, keyword-only, optional
        The most memory the build may take (about ``table_build_bytes``; n = 65 on the default grid:
        2 GiB); see :term:`memory budget`.

    Returns
    -------
    UpsamplingTable

    Raises
    ------
    ColorimetryError
        For a resolution outside 2..129, an unknown space, illuminant or observer.
    spectrocolor.errors.BudgetError
        (a ``ColorimetryError``) When building the table would exceed the memory budget.

    References
    ----------
    C. van Trigt, J. Opt. Soc. Am. A 7, 1891–1904 (1990).

    Examples
    --------
    >>> table = upsampling_table("sRGB", "D65", resolution=3, measure_excess=False)
    >>> table.resolution, table.all_exact, table.reflectance.shape
    (3, True, (3, 3, 3, 81))
    >>> bool(abs(table.reflectance[2, 2, 2] - 1.0).max() < 1e-9)   # white: ρ = 1
    True
    """
    from ..budget import check_bytes

    n = _resolution(resolution)
    t = node_coordinates(n).reshape(-1, 3)
    black = _solve_checked(np.zeros((1, 3)), illuminant, observer, wavelengths)[2]
    grid = np.array(black.spectrum.wavelengths_nm, dtype=float)
    check_bytes(table_build_bytes(n, grid.size),
                f"resolution {n}: building a table of {n}³ nodes on {grid.size} wavelengths",
                budget=memory_budget)
    W = np.asarray(weights(grid, observer=observer, illuminant=illuminant), dtype=float)
    matrix, space_name = colour_map(space, W)
    target = t @ matrix.T
    # The white corner is the perfect reflector by construction, a vertex of the object-colour
    # solid: the rounding of t @ matrix.T can put it an ulp outside, so it is set exactly.
    target[np.all(t == 1.0, axis=-1)] = W.sum(axis=0)
    rho, mu, result, ok = _solve_checked(target, illuminant, observer, wavelengths)
    R = np.asarray(result.roughness, dtype=float).copy()
    ok &= verify_reflectances(rho, target, W)
    status = np.where(ok, 0, 1).astype(np.uint8)
    if not ok.all():
        bad = np.flatnonzero(~ok)
        rho[bad], mu[bad], R[bad] = _toward_grey(t[bad], matrix, illuminant, observer,
                                                 wavelengths, W)
    shape = (n, n, n)
    reflectance = np.ascontiguousarray(rho.reshape(*shape, -1))
    node_XYZ = reflectance @ W
    exact = status.reshape(shape) == 0
    bound = _excess_bound(n, node_XYZ, R.reshape(shape), mu.reshape(*shape, 3), exact)
    if measure_excess:
        measured = _excess_measured(n, reflectance, exact, matrix, illuminant, observer,
                                    wavelengths, float(grid[1] - grid[0]))
    else:
        measured = np.full((n - 1,) * 3, np.nan)
    return UpsamplingTable(
        wavelengths_nm=grid, reflectance=reflectance, node_XYZ100=node_XYZ,
        node_status=status.reshape(shape), roughness=R.reshape(shape),
        multipliers=mu.reshape(*shape, 3), cell_excess_bound=bound,
        cell_excess_measured=measured, matrix=matrix, weights=W, space=space_name,
        illuminant=black.illuminant, observer=black.observer,
    )
