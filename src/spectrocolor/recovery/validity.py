"""Domains of validity of the unconstrained smoothest reflectance (van Trigt 1990, Figs. 7–12).

The unconstrained smoothest reflectance is linear in the tristimulus values,
``ρ = XYZ100 @ U`` (``U`` of shape (3, K), :func:`smoothest_reflectance` with
``bounds=None``). Writing ``XYZ100 = (Y / y) (x, y, 1 − x − y)`` gives, at every sample k,

    ρ_k(x, y, Y) = (Y / y) · ℓ_k(x, y),   ℓ_k(x, y) = a_k x + b_k y + c_k,

with ``a_k = U_0k − U_2k``, ``b_k = U_1k − U_2k``, ``c_k = U_2k``. Hence, at a fixed
chromaticity:

* whether ρ ≥ 0 does not depend on Y: the chromaticities where the unconstrained solution is
  a non-negative reflectance form the convex polygon ``ℓ_k(x, y) ≥ 0`` for all k, bounded by
  straight lines on which ρ vanishes at one wavelength — in practice (and in van Trigt's
  figures) at either end of the range, ``ρ(λ_b) = 0`` and ``ρ(λ_e) = 0``;
* ρ ≤ 1 holds for ``Y ≤ y / max_k ℓ_k(x, y)``: the maximum luminance factor
  ``Y/Y0 = y / (Y0 max_k ℓ_k)`` (``Y0 = 100``, the perfect white) up to which the
  unconstrained solution is a physical reflectance (van Trigt's Figs. 11–12).

Within this domain the bounded (``bounds="unit"``) and unconstrained solutions coincide.

On the boundary the solution touches zero, in one of van Trigt's two classes (the names of his
Figs. 5 and 6): **class 1**, zero at an end of the range (the straight end lines), with an
inflection at λ₁; **class 2**, an interior zero with zero slope at λ₁ (the curved branch).
Inside, the solution is the white plus the boundary function on the ray from the white
(``ρ = ε + (1 − ε) ρ(λ; λ₁)``), so the domain splits into fans from the white, one per class
(Figs. 7–8: :meth:`DomainOfValidity.boundary_pieces`, :meth:`DomainOfValidity.solution_class`).
:func:`generating_functions` gives both families with Y(λ₁) and Y_M(λ₁) (Figs. 9–10). His
"a"/"b" split of each class is not made: the seed prints both formulas without saying which
is which.

References
----------
C. van Trigt, "Smoothest reflectance functions. I. Definition and main results",
J. Opt. Soc. Am. A 7, 1891–1904 (1990), Figs. 7–12.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..errors import ColorimetryError
from ..illuminants import DEFAULT_ILLUMINANT
from ..observers import DEFAULT_OBSERVER
from .inputs import DEFAULT_WAVELENGTHS, setup_for

#: Chromaticity triangle x, y, z ≥ 0 that the clipping starts from.
_TRIANGLE = np.array([[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]])


@dataclass(frozen=True)
class BoundaryPiece:
    """One class's stretch of the boundary of the domain of validity (van Trigt Figs. 7–8).

    Attributes
    ----------
    solution_class : str
        ``"1"`` (ρ vanishes at an end of the range: a straight end line) or ``"2"`` (ρ vanishes
        at an interior sample: the curved branch).
    zero_nm : float
        For class 1 the end sample (λ_b or λ_e, nm) where ρ vanishes; NaN for class 2.
    xy : ndarray (M + 1, 2)
        The vertices along the piece, counter-clockwise; the first and the last are the
        piece's end points.
    edge_wavelengths_nm : ndarray (M,)
        The sample where ρ vanishes along each edge of the piece, nm.
    """

    solution_class: str
    zero_nm: float
    xy: np.ndarray
    edge_wavelengths_nm: np.ndarray


@dataclass(frozen=True)
class SolutionClass:
    """Van Trigt's class at given chromaticities (:meth:`DomainOfValidity.solution_class`).

    Attributes
    ----------
    solution_class : ndarray of str (...)
        ``"1"``, ``"2"`` or ``""`` (undefined: the white itself, non-finite input).
    zero_nm : ndarray (...)
        The sample (nm) where the boundary function on the ray from the white vanishes: λ_b or
        λ_e for class 1, an interior sample (within half a step of λ₁) for class 2.
    boundary_xy : ndarray (..., 2)
        Where that ray leaves the domain of validity.
    """

    solution_class: np.ndarray
    zero_nm: np.ndarray
    boundary_xy: np.ndarray


@dataclass(frozen=True)
class DomainOfValidity:
    """Where the unconstrained smoothest reflectance is physical, for one illuminant/observer/grid.

    Attributes
    ----------
    wavelengths_nm : ndarray (K,)
    line_coefficients : ndarray (K, 3)
        ``(a_k, b_k, c_k)``: ρ at sample k is ``(Y / y)(a_k x + b_k y + c_k)``.
    region_xy : ndarray (P, 2)
        Vertices (counter-clockwise) of the convex polygon of chromaticities where the
        unconstrained solution is non-negative (for every Y > 0).
    edge_wavelengths_nm : ndarray (P,)
        For the edge from vertex i to i+1, the wavelength at which ρ reaches 0 along it.
    illuminant, observer : str
        The conditions used.
    white_xy : ndarray (2,)
        Chromaticity of the white (every sample 1) with these weights.

    Examples
    --------
    >>> domain = domain_of_validity("D65", wavelengths=(400, 700, 10))
    >>> domain.region_xy.shape, domain.edge_wavelengths_nm[:3].tolist()
    ((31, 2), [540.0, 530.0, 520.0])
    """

    wavelengths_nm: np.ndarray
    line_coefficients: np.ndarray
    region_xy: np.ndarray
    edge_wavelengths_nm: np.ndarray
    illuminant: str
    observer: str
    white_xy: np.ndarray

    def _levels(self, xy) -> np.ndarray:
        c = np.asarray(xy, dtype=float)
        if c.ndim == 0 or c.shape[-1] != 2:
            raise ColorimetryError(f"xy: expected chromaticities of shape (..., 2), got {c.shape}")
        a, b, k = self.line_coefficients.T
        return c[..., :1] * a + c[..., 1:] * b + k

    def nonnegative(self, xy) -> np.ndarray:
        """Whether the unconstrained solution is ≥ 0 at chromaticities ``xy`` (..., 2), y > 0.

        Parameters
        ----------
        xy : array_like, shape (..., 2)
            CIE 1931 chromaticities.

        Returns
        -------
        numpy.ndarray of bool, shape (...)
            True inside :attr:`region_xy` (and y > 0).

        Examples
        --------
        >>> domain = domain_of_validity("D65", wavelengths=(400, 700, 10))
        >>> domain.nonnegative([[0.3127, 0.3290], [0.70, 0.29]]).tolist()
        [True, False]
        """
        c = np.asarray(xy, dtype=float)
        return np.all(self._levels(c) >= 0.0, axis=-1) & (c[..., 1] > 0)

    def max_luminance_factor(self, xy) -> np.ndarray:
        """Largest ``Y/Y0`` (0–1 scale, ``Y0`` the perfect white) at chromaticities ``xy``
        (..., 2) for which the unconstrained solution stays ≤ 1; NaN where it is negative
        somewhere (outside :attr:`region_xy`).

        Parameters
        ----------
        xy : array_like, shape (..., 2)
            CIE 1931 chromaticities.

        Returns
        -------
        numpy.ndarray, shape (...)
            ``Y / Y0`` on the 0–1 scale, or NaN outside the region.

        References
        ----------
        C. van Trigt, J. Opt. Soc. Am. A 7, 1891–1904 (1990), Figs. 7–12.

        Examples
        --------
        >>> domain = domain_of_validity("D65", wavelengths=(400, 700, 10))
        >>> round(float(domain.max_luminance_factor([0.3127, 0.3290])), 4)
        0.9973
        """
        c = np.asarray(xy, dtype=float)
        top = self._levels(c).max(axis=-1)
        with np.errstate(divide="ignore", invalid="ignore"):
            value = c[..., 1] / (100.0 * top)
        return np.where(self.nonnegative(c), value, np.nan)

    def end_lines(self) -> tuple[np.ndarray, np.ndarray]:
        """Coefficients ``(a, b, c)`` of the lines ``a x + b y + c = 0`` on which the
        unconstrained solution vanishes at the first (λ_b) and the last (λ_e) sample.

        Returns
        -------
        tuple of numpy.ndarray
            ``(first, last)``, each ``(a, b, c)`` of shape (3,), in xy chromaticity.

        Examples
        --------
        >>> first, last = domain_of_validity("D65", wavelengths=(400, 700, 10)).end_lines()
        >>> first.shape, last.shape
        ((3,), (3,))
        """
        return self.line_coefficients[0], self.line_coefficients[-1]

    def end_line_equations(self) -> np.ndarray:
        """The end lines in van Trigt's form ``α x + β y = 1`` (captions of his Figs. 7–8).

        Returns
        -------
        numpy.ndarray, shape (2, 2)
            ``[[α_b, β_b], [α_e, β_e]]``: the line on which the unconstrained solution vanishes
            at the first sample λ_b, then at the last sample λ_e (dimensionless; xy chromaticity).

        References
        ----------
        C. van Trigt, J. Opt. Soc. Am. A 7, 1891–1904 (1990), the equations
        ``(1 − ν₁z₀/(ν₃x₀)) x + (1 − ν₂z₀/(ν₃y₀)) y = 1`` and Figs. 7–8.

        Examples
        --------
        >>> eq = domain_of_validity("A", wavelengths=(360, 830, 1)).end_line_equations()
        >>> np.round(eq[0], 4).tolist(), np.round(eq[1], 2).tolist()
        ([0.8584, 1.2291], [-26.58, 20.6])
        """
        lines = np.stack(self.end_lines())
        with np.errstate(divide="ignore", invalid="ignore"):
            return -lines[:, :2] / lines[:, 2:]

    def boundary_pieces(self) -> list[BoundaryPiece]:
        """The boundary of :attr:`region_xy` cut into van Trigt's classes (Figs. 7–8).

        Consecutive edges on which the unconstrained solution vanishes at an end sample form a
        class-1 piece (one straight segment per end line); consecutive edges on which it
        vanishes at interior samples form a class-2 piece (the curved branch). The first and
        last vertex of each piece are the classes' end points.

        Returns
        -------
        list of BoundaryPiece
            In counter-clockwise order.

        Examples
        --------
        >>> pieces = domain_of_validity("D65", wavelengths=(380, 780, 10)).boundary_pieces()
        >>> [(p.solution_class, p.zero_nm) for p in pieces]
        [('1', 380.0), ('1', 780.0), ('2', nan)]
        """
        labels, poly, grid = self.edge_wavelengths_nm, self.region_xy, self.wavelengths_nm
        n = len(labels)
        if n == 0:
            return []
        end = np.isin(labels, grid[[0, -1]])
        keys = [(("1", float(lab)) if e else (("2", np.nan) if np.isfinite(lab) else ("", np.nan)))
                for lab, e in zip(labels, end, strict=True)]

        def same(p, q):
            return p[0] == q[0] and (p[1] == q[1] or (np.isnan(p[1]) and np.isnan(q[1])))

        starts = [i for i in range(n) if not same(keys[i], keys[i - 1])] or [0]
        pieces = []
        for a, b in zip(starts, starts[1:] + [starts[0] + n], strict=True):
            idx = np.arange(a, b + 1) % n
            edges = np.arange(a, b) % n
            pieces.append(BoundaryPiece(keys[a][0], keys[a][1], poly[idx], labels[edges]))
        return pieces

    def solution_class(self, xy) -> SolutionClass:
        """Van Trigt's class of the unconstrained solution at chromaticities ``xy`` (Figs. 7–8).

        Inside the domain the unconstrained solution is ``ε + (1 − ε) ρ(λ; λ₁)``: the white plus
        the generating function whose chromaticity is where the ray from the white through
        ``xy`` leaves :attr:`region_xy`, and the class is that function's. For a point on the
        boundary it is the class of its own function; points outside are classified by the same
        ray (their solution is negative somewhere).

        Parameters
        ----------
        xy : array_like, shape (..., 2)
            CIE 1931 chromaticities.

        Returns
        -------
        SolutionClass
            ``solution_class`` (``"1"``, ``"2"``, or ``""`` at the white and for non-finite
            input), ``zero_nm`` (the sample where the boundary function vanishes: an end for
            class 1) and ``boundary_xy``, each of the leading shape of ``xy``.

        References
        ----------
        C. van Trigt, J. Opt. Soc. Am. A 7, 1891–1904 (1990), Figs. 5–8 and the
        decomposition ``ρ(λ) = ε + (1 − ε) ρ(λ; λ₁)``.

        Examples
        --------
        >>> d = domain_of_validity("D65", wavelengths=(360, 830, 1))
        >>> c = d.solution_class([[0.4500, 0.4707], [0.5455, 0.3829]])  # van Trigt Figs. 6 and 5
        >>> c.solution_class.tolist(), c.zero_nm.tolist()
        (['1', '2'], [360.0, 500.0])
        """
        c = np.asarray(xy, dtype=float)
        if c.ndim == 0 or c.shape[-1] != 2:
            raise ColorimetryError(f"xy: expected chromaticities of shape (..., 2), got {c.shape}")
        flat = c.reshape(-1, 2)
        poly, labels = self.region_xy, self.edge_wavelengths_nm
        white = self.white_xy
        edge = np.roll(poly, -1, axis=0) - poly
        start = poly - white

        def cross(p, q):
            return p[..., 0] * q[..., 1] - p[..., 1] * q[..., 0]

        hit = np.full(len(flat), -1)
        point = np.full((len(flat), 2), np.nan)
        chunk = max(1, 2 ** 20 // max(len(poly), 1))
        for s0 in range(0, len(flat), chunk):
            d = flat[s0:s0 + chunk, None, :] - white
            denom = cross(d, edge[None])
            with np.errstate(divide="ignore", invalid="ignore"):
                t = cross(start[None], edge[None]) / denom
                u = cross(start[None], d) / denom
                # the ray leaves a counter-clockwise polygon through the edge it crosses outwards
                miss = np.where((denom > 0) & (t > 0), np.maximum(-u, u - 1.0), np.inf)
                best = np.argmin(np.where(np.isnan(miss), np.inf, miss), axis=1)
                rows = np.arange(len(d))
                ok = np.isfinite(miss[rows, best])
                exit_xy = white + t[rows, best, None] * d[rows, 0]
            hit[s0:s0 + chunk] = np.where(ok, best, -1)
            point[s0:s0 + chunk] = np.where(ok[:, None], exit_xy, np.nan)
        found = hit >= 0
        label = np.where(found, labels[np.maximum(hit, 0)], np.nan)
        end = np.isin(label, self.wavelengths_nm[[0, -1]])
        name = np.where(~found | np.isnan(label), "", np.where(end, "1", "2"))
        shape = c.shape[:-1]
        return SolutionClass(name.reshape(shape), label.reshape(shape), point.reshape(*shape, 2))


def _clip(polygon: np.ndarray, labels: np.ndarray, line: np.ndarray, label: float):
    """Sutherland–Hodgman: the part of a convex polygon where ``a x + b y + c ≥ 0``.

    ``labels[i]`` names the edge from vertex i to i+1; a new edge along the line gets
    ``label``."""
    value = polygon @ line[:2] + line[2]
    if np.all(value >= 0):
        return polygon, labels
    out, out_labels = [], []
    n = len(polygon)
    for i in range(n):
        j = (i + 1) % n
        p, q, vp, vq = polygon[i], polygon[j], value[i], value[j]
        if vp >= 0:
            out.append(p)
            out_labels.append(labels[i])
        if (vp >= 0) != (vq >= 0):
            out.append(p + (q - p) * (vp / (vp - vq)))
            out_labels.append(label if vp >= 0 else labels[i])
    if not out:
        return np.empty((0, 2)), np.empty(0)
    return np.array(out), np.array(out_labels)


def domain_of_validity(
    illuminant=DEFAULT_ILLUMINANT, *, observer=DEFAULT_OBSERVER, wavelengths=DEFAULT_WAVELENGTHS
) -> DomainOfValidity:
    """The domain of validity of the unconstrained smoothest reflectance.

    Parameters
    ----------
    illuminant : str or Spectrum, default "D65"
        The light the colours are seen under (a CIE name, ``"blackbody:T"``, ``"D:T"``, or a
        Spectrum sampled on the grid).
    observer : str or Spectrum, default "1931"
        Observer name or alias, or colour-matching functions on the grid.
    wavelengths : tuple of float or array_like, default (380.0, 780.0, 5.0)
        ``(start_nm, stop_nm, step_nm)`` or a uniform grid in nm: the reflectances' samples.

    Returns
    -------
    DomainOfValidity
        The polygon of chromaticities with a non-negative unconstrained solution, the lines
        bounding it, and :meth:`DomainOfValidity.max_luminance_factor`.

    References
    ----------
    C. van Trigt, J. Opt. Soc. Am. A 7, 1891–1904 (1990), Figs. 7–12.

    Examples
    --------
    >>> d = domain_of_validity("D65", wavelengths=(400, 700, 10))
    >>> bool(d.nonnegative([0.3127, 0.3290]))
    True
    """
    setup, obs, ill = setup_for(wavelengths, observer, illuminant)
    U = setup.problem.unconstrained
    coefficients = np.stack([U[0] - U[2], U[1] - U[2], U[2]], axis=1)
    polygon, labels = _TRIANGLE.copy(), np.full(3, np.nan)
    for k in range(len(coefficients)):
        polygon, labels = _clip(polygon, labels, coefficients[k], setup.grid[k])
        if len(polygon) == 0:
            break
    return DomainOfValidity(
        wavelengths_nm=setup.grid,
        line_coefficients=coefficients,
        region_xy=polygon,
        edge_wavelengths_nm=labels,
        illuminant=ill,
        observer=obs,
        white_xy=setup.white[:2] / setup.white.sum(),
    )


@dataclass(frozen=True)
class BoundaryLocus:
    """Van Trigt's boundary locus (Figs. 3–4): chromaticities of the cumulative weights.

    Attributes
    ----------
    wavelengths_nm : ndarray (K,)
    left_xy : ndarray (K, 2)
        Chromaticity of ``f(λ) = Σ_{λ_b ≤ λ_k ≤ λ} w_k`` (the block from λ_b to λ; van
        Trigt's ``x_b(λ), y_b(λ)``), NaN where it is black.
    right_xy : ndarray (K, 2)
        Chromaticity of ``g(λ) = Σ_{λ ≤ λ_k ≤ λ_e} w_k`` (the block from λ to λ_e).
    white_xy : ndarray (2,)
        Chromaticity of the white (every sample 1).
    """

    wavelengths_nm: np.ndarray
    left_xy: np.ndarray
    right_xy: np.ndarray
    white_xy: np.ndarray


def _xy(XYZ):
    total = XYZ.sum(axis=-1, keepdims=True)
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.where(total > 0, XYZ[..., :2] / np.where(total > 0, total, 1.0), np.nan)


def boundary_locus(illuminant=DEFAULT_ILLUMINANT, *, observer=DEFAULT_OBSERVER,
                   wavelengths=DEFAULT_WAVELENGTHS) -> BoundaryLocus:
    """The left and right branches of van Trigt's boundary locus for one illuminant.

    Parameters
    ----------
    illuminant : str or Spectrum, default "D65"
        The light (a CIE name, ``"blackbody:T"``, ``"D:T"``, or a Spectrum on the grid).
    observer : str or Spectrum, default "1931"
        Observer name or alias, or colour-matching functions on the grid.
    wavelengths : tuple of float or array_like, default (380.0, 780.0, 5.0)
        ``(start_nm, stop_nm, step_nm)`` or a uniform grid in nm.

    Returns
    -------
    BoundaryLocus
        The grid, the xy of the left (λ_b … λ) and right (λ … λ_e) block reflectances, and the
        white's xy.

    References
    ----------
    C. van Trigt, J. Opt. Soc. Am. A 7, 1891–1904 (1990), Figs. 3–4 and Eq. (8).

    Examples
    --------
    >>> loc = boundary_locus("D65", wavelengths=(400, 700, 10))
    >>> bool(abs(loc.left_xy[-1] - loc.white_xy).max() < 1e-12)
    True
    """
    setup, _, _ = setup_for(wavelengths, observer, illuminant)
    left = np.cumsum(setup.W, axis=0)
    right = np.cumsum(setup.W[::-1], axis=0)[::-1]
    return BoundaryLocus(setup.grid, _xy(left), _xy(right), _xy(setup.white))


#: Van Trigt's two classes of generating function ρ(λ; λ₁), as his Figs. 5 and 6 name them.
SOLUTION_CLASSES = {
    "1": "zero at an end of the range (λ_b or λ_e), inflection at λ₁ (Fig. 6, Class 1b)",
    "2": "zero with zero slope at an interior wavelength λ₁ (Fig. 5, Class 2b)",
}


def _rounding_bound(K: int) -> float:
    """``γ_n = n ε / (1 − n ε)`` for the ``n = 2K + 8`` roundings on the way to one ρ_k.

    A generating function is built from its multipliers μ (a cross product: 2 products and a
    difference per component), ``(W μ)_k`` (3 products, 2 sums), two running sums over at most K
    samples each and one subtraction (the shift that puts the zero where it belongs); ``n`` counts
    them, with a margin of 2 (Higham, *Accuracy and Stability of Numerical Algorithms*, 2nd ed.,
    §3.1, Lemma 3.1)."""
    n = 2 * K + 8
    eps = np.finfo(float).eps / 2
    return n * eps / (1.0 - n * eps)


def _from_multipliers(W, a, b, anchor):
    """Reflectances ``ρ`` (P, K) with ``Q ρ ∝ W μ``, ``μ = a_p × b_p``, zero at ``anchor`` (P,).

    ``Q`` is the path Laplacian of the roughness ``Σ (Δρ)² / h`` with free (natural) ends, so
    ``ρ_{k+1} − ρ_k ∝ −Σ_{i ≤ k} (W μ)_i`` and ``whiteᵀ μ = 0`` makes the last slope zero as
    well: every such ρ is the unconstrained smoothest reflectance of its own colour
    ``ρ @ W`` (the KKT conditions ``Q ρ = W μ'``, ``Wᵀ ρ = ρ @ W`` hold with ``μ' ∝ μ``). The
    callers pass ``a``, ``b`` whose cross product is orthogonal to the white (class 1:
    ``white × w(λ₁)``; class 2: ``G(λ₁) × F(λ₁)``, the right and left cumulative weights, equal
    to ``white × F(λ₁)`` without the cancellation of ``white − F`` at the red end). Returns ρ
    with the sign that makes it mostly non-negative, and ``bound`` (P, K): a bound on the
    rounding error of each sample (:func:`_rounding_bound` times the same sums of absolute
    values)."""
    a = np.broadcast_to(a, b.shape)
    mu = np.cross(a, b)
    mu_abs = np.abs(a[:, [1, 2, 0]] * b[:, [2, 0, 1]]) + np.abs(a[:, [2, 0, 1]] * b[:, [1, 2, 0]])
    K = W.shape[0]
    rows = np.arange(len(b))

    def double_sum(r):
        slope = -np.cumsum(r, axis=1)[:, :-1]
        return np.concatenate([np.zeros((len(r), 1)), np.cumsum(slope, axis=1)], axis=1)

    rho = double_sum(mu @ W.T)
    size = -double_sum(mu_abs @ np.abs(W).T)  # Σ of |terms| behind each ρ_k, ≥ 0
    rho = rho - rho[rows, anchor][:, None]
    bound = _rounding_bound(K) * (size + size[rows, anchor][:, None])
    rho = np.where(rho.sum(axis=1, keepdims=True) < 0, -rho, rho)
    return rho, bound


class _Family:
    """Evaluate ρ(λ; λ₁) of one class for many λ₁ at once, and refine the λ₁ of the default set."""

    #: Largest step in xy between neighbouring functions of the default set (refined below it).
    XY_STEP = 0.01

    def __init__(self, grid, W, white):
        self.grid, self.W, self.white = grid, W, white
        self.h = float(grid[1] - grid[0])
        self.mid = grid[:-1] + 0.5 * self.h
        self.F = np.cumsum(W, axis=0)[:-1]  # weights left of each segment midpoint
        self.G = np.cumsum(W[::-1], axis=0)[::-1][1:]  # and right of it

    def _at(self, table, at, lam):
        return np.stack([np.interp(lam, at, table[:, j]) for j in range(table.shape[1])], axis=1)

    def evaluate(self, name, end, lam):
        """``(ρ scaled to maximum 1, valid, zero sample)`` for class ``name`` at ``lam``."""
        if name == "2":  # zero slope at λ₁: cumulative weights between segment midpoints
            a, b = self._at(self.G, self.mid, lam), self._at(self.F, self.mid, lam)
            anchor = np.clip(np.floor((lam - self.grid[0]) / self.h + 0.5).astype(int), 0,
                             len(self.grid) - 1)
        else:  # inflection at λ₁: the weight row at λ₁, zero at the end sample ``end``
            a, b = self.white, self._at(self.W, self.grid, lam)
            anchor = np.full(len(lam), end)
        rho, bound = _from_multipliers(self.W, a, b, anchor)
        top = rho.max(axis=1)
        valid = np.all(rho >= -bound, axis=1) & (top > bound.max(axis=1))
        with np.errstate(invalid="ignore", divide="ignore"):
            rho = rho / top[:, None]
        return rho, valid, anchor

    def refined(self, name, end, lam):
        """The default set: ``lam`` plus midpoints wherever neighbours are more than
        :attr:`XY_STEP` apart in xy (or one of them is not a reflectance), down to 1e-4 of a step
        in λ₁, so that each family reaches the ends of its stretch of the boundary."""
        lam = np.unique(lam)
        rho, valid, anchor = self.evaluate(name, end, lam)
        for _ in range(64):
            XYZ = rho @ self.W
            with np.errstate(invalid="ignore", divide="ignore"):
                xy = XYZ[:, :2] / XYZ.sum(axis=1, keepdims=True)
            far = np.linalg.norm(np.diff(xy, axis=0), axis=1)
            far = np.where(np.isfinite(far), far, np.inf)
            split = ((valid[:-1] | valid[1:]) & (far > self.XY_STEP)
                     & (np.diff(lam) > 1e-4 * self.h))
            if not split.any():
                break
            new = 0.5 * (lam[:-1][split] + lam[1:][split])
            rho_new, valid_new, anchor_new = self.evaluate(name, end, new)
            order = np.argsort(np.concatenate([lam, new]), kind="stable")
            lam = np.concatenate([lam, new])[order]
            rho = np.concatenate([rho, rho_new])[order]
            valid = np.concatenate([valid, valid_new])[order]
            anchor = np.concatenate([anchor, anchor_new])[order]
        return lam, rho, valid, anchor


@dataclass(frozen=True)
class GeneratingFunctions:
    """Van Trigt's generating functions ``ρ(λ; λ₁)`` on the sampled grid (Figs. 5–6, 9–10).

    On the boundary of the domain of validity the unconstrained smoothest reflectance touches
    0. Van Trigt names two families of such functions (his figure captions):

    * **Class 1** (Fig. 6): ρ is zero *at an end* of the range, ``ρ(λ_b) = 0`` or
      ``ρ(λ_e) = 0``, and has an inflection at λ₁. Its chromaticities lie on the straight end
      lines of :class:`DomainOfValidity`. His Fig. 6 (D65) draws two of them for λ₁ = 500 and
      564 nm on the λ_b = 360 nm line.
    * **Class 2** (Fig. 5): ρ has an *interior* zero with zero slope at λ₁:
      ``ρ(λ₁) = dρ/dλ(λ₁) = 0``. Its chromaticities form the curved part of the boundary. His
      Fig. 5 (D65) draws two for λ₁ = 500 and 564 nm.

    Each class comes in an "a" and a "b" variant in the paper; our copy of it (seed 004) prints
    both end-line formulas and both Y(λ₁) formulas without saying which is a and which is b, so
    the split is not made here: class-1 rows carry the end (``zero_nm``) instead.

    Discrete form (piecewise-linear ρ, roughness ``Σ(Δρ)²/h``, free ends): the multipliers of
    the colour constraint are ``μ ∝ white × v`` (so that ``Σ_j μ_j = 0`` in van Trigt's
    normalisation) with ``v = w(λ₁)``, the weight row at λ₁ (class 1: ``(Wμ)(λ₁) = 0``, the
    discrete ``d²ρ/dλ² = 0``), or ``v = F(λ₁)``, the cumulative weights ``Σ_{i ≤ k} w_i``
    (the slope of the segment from λ_k to λ_{k+1}) interpolated between segment midpoints
    (class 2: zero slope at λ₁). At a grid sample λ₁ = λ_k the class-2 function is zero at λ_k
    with equal neighbours; at a midpoint it is zero at both samples, a vertex of
    :attr:`DomainOfValidity.region_xy`. Only functions that are non-negative (to within the
    rounding bound of their construction) belong to the family; λ₁ and its complementary
    wavelength (when the line from the white through the spectral colour λ₁ meets the
    spectral locus again) give the same class-1 function, and both are listed.

    Each function is scaled to maximum 1; its luminance factor is then van Trigt's
    ``Y(λ₁)/Y₀``, the largest for which the unconstrained solution at that chromaticity is a
    reflectance (Figs. 9–10, solid), and ``Y_M(λ₁)/Y₀`` is the largest luminance factor of any
    object colour of that chromaticity (Figs. 9–10, dashed: the optimal colour).

    Attributes
    ----------
    wavelengths_nm : ndarray (K,)
        The grid, nm.
    lambda1_nm : ndarray (P,)
        Van Trigt's parameter λ₁, nm: the inflection (class 1) or the interior zero (class 2).
    solution_class : ndarray of str (P,)
        ``"1"`` (zero at λ_b or λ_e) or ``"2"`` (interior zero with zero slope at λ₁).
    zero_nm : ndarray (P,)
        Where ρ is 0, nm: the end sample (class 1) or the sample nearest λ₁ (class 2).
    xy : ndarray (P, 2)
        CIE 1931 chromaticity of each function (under the illuminant).
    reflectance : ndarray (P, K)
        ``ρ(λ; λ₁)``, maximum 1, minimum 0 (0–1 scale).
    luminance_factor : ndarray (P,)
        ``Y(λ₁)/Y₀`` (0–1 scale, ``Y₀`` the perfect white).
    max_luminance_factor : ndarray (P,)
        ``Y_M(λ₁)/Y₀`` (0–1 scale).

    References
    ----------
    C. van Trigt, "Smoothest reflectance functions. I. Definition and main results",
    J. Opt. Soc. Am. A 7, 1891–1904 (1990), Figs. 5–6 and 9–10.
    """

    wavelengths_nm: np.ndarray
    lambda1_nm: np.ndarray
    solution_class: np.ndarray
    zero_nm: np.ndarray
    xy: np.ndarray
    reflectance: np.ndarray
    luminance_factor: np.ndarray
    max_luminance_factor: np.ndarray

    def family(self, solution_class: str, zero_nm: float | None = None) -> np.ndarray:
        """Indices of one family: class ``"2"``, or class ``"1"`` at the end ``zero_nm``.

        Parameters
        ----------
        solution_class : {"1", "2"}
            Van Trigt's class.
        zero_nm : float, optional
            For class 1, the end sample (λ_b or λ_e, nm) whose line is wanted; default both.

        Returns
        -------
        numpy.ndarray of int
            Row indices, in increasing λ₁.

        Examples
        --------
        >>> g = generating_functions("D65", wavelengths=(380, 780, 10))
        >>> bool(np.all(g.zero_nm[g.family("1", 380.0)] == 380.0))
        True
        """
        if solution_class not in SOLUTION_CLASSES:
            raise ColorimetryError(f"solution_class: expected one of {sorted(SOLUTION_CLASSES)}, "
                                   f"got {solution_class!r}")
        keep = self.solution_class == solution_class
        if zero_nm is not None:
            keep &= self.zero_nm == float(zero_nm)
        rows = np.flatnonzero(keep)
        return rows[np.argsort(self.lambda1_nm[rows], kind="stable")]


def generating_functions(illuminant=DEFAULT_ILLUMINANT, *, observer=DEFAULT_OBSERVER,
                         wavelengths=DEFAULT_WAVELENGTHS, lambda1_nm=None) -> GeneratingFunctions:
    """Van Trigt's generating functions ``ρ(λ; λ₁)`` of both classes, with ``Y(λ₁)`` and ``Y_M(λ₁)``.

    Parameters
    ----------
    illuminant : str or Spectrum, default "D65"
        The light (a CIE name, ``"blackbody:T"``, ``"D:T"``, or a Spectrum on the grid).
    observer : str or Spectrum, default "1931"
        Observer name or alias, or colour-matching functions on the grid.
    wavelengths : tuple of float or array_like, default (380.0, 780.0, 5.0)
        ``(start_nm, stop_nm, step_nm)`` or a uniform grid in nm.
    lambda1_nm : array_like, optional
        The values of λ₁ (nm) to evaluate, within the grid's range; default every grid sample.
        Class 1 is evaluated at each (for both ends), class 2 at those at least half a step
        inside the range.

    Returns
    -------
    GeneratingFunctions
        Every non-negative ρ(λ; λ₁) of either class (0–1 scale, maximum 1): class 2 first,
        then class 1 at λ_b, then class 1 at λ_e, each in increasing λ₁; their chromaticities,
        luminance factors Y(λ₁)/Y₀ and the optimal colours' Y_M(λ₁)/Y₀. The default set is
        every grid sample, refined where neighbouring functions are more than
        ``_Family.XY_STEP`` = 0.01 apart in xy (so each family reaches both ends of its stretch
        of the boundary). Y_M takes most of the time: a ray against the solid's K(K − 1)
        facets per function (seconds at 1 nm over 360–830 nm, about a thousand functions).

    Raises
    ------
    ColorimetryError
        For λ₁ outside the grid or not finite.

    References
    ----------
    C. van Trigt, J. Opt. Soc. Am. A 7, 1891–1904 (1990), Figs. 5–6 and 9–10.

    Examples
    --------
    >>> g = generating_functions("D65", wavelengths=(380, 780, 10))
    >>> sorted(set(g.solution_class.tolist()))
    ['1', '2']
    >>> bool(abs(g.reflectance.max(axis=1) - 1).max() < 1e-12 and g.reflectance.min() > -1e-12)
    True
    """
    from . import zonotope

    setup, _, _ = setup_for(wavelengths, observer, illuminant)
    grid, W, white = setup.grid, setup.W, setup.white
    K, h = len(grid), setup.step_nm
    lam = grid.copy() if lambda1_nm is None else np.atleast_1d(np.asarray(lambda1_nm, dtype=float))
    if lam.ndim != 1 or lam.size == 0 or not np.all(np.isfinite(lam)) or lam.min() < grid[0] \
            or lam.max() > grid[-1]:
        raise ColorimetryError(f"lambda1_nm: expected finite wavelengths within the grid "
                               f"{grid[0]:g}–{grid[-1]:g} nm, got {lambda1_nm!r:.80}")
    family = _Family(grid, W, white)
    rows = {"class": [], "lambda1": [], "zero": [], "rho": []}
    for name, end in (("2", None), ("1", 0), ("1", K - 1)):
        lam_p = lam if name == "1" else lam[(lam >= grid[0] + 0.5 * h) & (lam <= grid[-1] - 0.5 * h)]
        if len(lam_p) == 0:
            continue
        if lambda1_nm is None:
            lam_p, rho, keep, anchor = family.refined(name, end, lam_p)
        else:
            rho, keep, anchor = family.evaluate(name, end, lam_p)
        rows["class"].append(np.full(keep.sum(), name))
        rows["lambda1"].append(lam_p[keep])
        rows["zero"].append(grid[anchor[keep]])
        rows["rho"].append(rho[keep])
    if not rows["rho"]:
        rows = {"class": [np.empty(0, dtype=str)], "lambda1": [np.empty(0)], "zero": [np.empty(0)],
                "rho": [np.empty((0, K))]}
    rho = np.concatenate(rows["rho"])
    XYZ = rho @ W
    with np.errstate(invalid="ignore", divide="ignore"):
        xy = XYZ[:, :2] / XYZ.sum(axis=1, keepdims=True)
        direction = XYZ / XYZ[:, 1:2]
    Y = XYZ[:, 1] / white[1]
    # the optimal colour of each chromaticity: where the ray from black leaves the solid
    YM = zonotope.ray_exit(setup.solid, np.zeros(3), direction) / white[1]
    return GeneratingFunctions(grid, np.concatenate(rows["lambda1"]), np.concatenate(rows["class"]),
                               np.concatenate(rows["zero"]), xy, rho, Y, YM)
