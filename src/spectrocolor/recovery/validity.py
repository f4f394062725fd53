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
:func:`.generating.generating_functions` gives both families with Y(λ₁) and Y_M(λ₁) (Figs. 9–10). His
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
from .generating import SOLUTION_CLASSES as SOLUTION_CLASSES  # re-exported: their home before the split
from .generating import GeneratingFunctions as GeneratingFunctions
from .generating import _Family as _Family  # tests/recovery/test_validity.py reaches in
from .generating import generating_functions as generating_functions
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
            True inside ``region_xy`` (and y > 0).

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
        somewhere (outside ``region_xy``).

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
        """The boundary of ``region_xy`` cut into van Trigt's classes (Figs. 7–8).

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
        ``xy`` leaves ``region_xy``, and the class is that function's. For a point on the
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
        The light the reflectances are seen under; see :term:`illuminant`.
    observer : str or Spectrum, default "1931"
        The observer of the domain's colours; see :term:`observer`.
    wavelengths : tuple of float or array_like, default (380.0, 780.0, 5.0)
        The reflectances' samples; see :term:`wavelength grid`.

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
        The light the boundary is traced under; see :term:`illuminant`.
    observer : str or Spectrum, default "1931"
        The observer; see :term:`observer`.
    wavelengths : tuple of float or array_like, default (380.0, 780.0, 5.0)
        The samples of the boundary's reflectances, nm; see :term:`wavelength grid`.

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
