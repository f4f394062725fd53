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


@dataclass(frozen=True)
class GeneratingFunctions:
    """Van Trigt's generating functions ``ρ(λ; λ₁)`` on the sampled grid (Figs. 5–6, 9–10).

    On the boundary of the domain of validity the unconstrained smoothest reflectance
    touches 0 somewhere. Where two consecutive samples' lines ``ρ_k = 0`` and ``ρ_{k+1} = 0``
    meet (a vertex of :attr:`DomainOfValidity.region_xy`), ρ vanishes at both, so it touches
    zero with zero slope at ``λ₁ = (λ_k + λ_{k+1}) / 2``: the discrete form of van Trigt's
    condition ``ρ(λ₁) = dρ/dλ(λ₁) = 0`` for his Class 1 (an interior zero). Vertices on an
    end line (``ρ(λ_b) = 0`` or ``ρ(λ_e) = 0``) give his Class 2 (zero at an end). Each
    function is scaled so that its maximum is 1; its luminance factor is then van Trigt's
    ``Y(λ₁)/Y₀``, the largest for which the unconstrained solution at that chromaticity is a
    reflectance (Fig. 9–10, solid), and ``Y_M(λ₁)/Y₀`` is the largest luminance factor of any
    object colour of that chromaticity (Fig. 9–10, dashed: the optimal colour).

    The class labels are this discrete reading, not van Trigt's definitions (his Eq. (23) is
    not in our copy of the paper), and need not match his: his Class 2 functions (Fig. 5)
    have interior λ₁ (500 and 564 nm), and his a/b split of each class is not made here.

    Attributes
    ----------
    wavelengths_nm : ndarray (K,)
    touch_nm : ndarray (P,)
        λ₁ for each vertex: where ρ touches 0 (an end sample for Class 2).
    solution_class : ndarray of str (P,)
        ``"1"`` (interior zero with zero slope) or ``"2"`` (zero at λ_b or λ_e).
    xy : ndarray (P, 2)
        Chromaticity of each vertex.
    reflectance : ndarray (P, K)
        ``ρ(λ; λ₁)``, maximum 1, minimum 0.
    luminance_factor : ndarray (P,)
        ``Y(λ₁)/Y₀`` (0–1).
    max_luminance_factor : ndarray (P,)
        ``Y_M(λ₁)/Y₀`` (0–1).
    """

    wavelengths_nm: np.ndarray
    touch_nm: np.ndarray
    solution_class: np.ndarray
    xy: np.ndarray
    reflectance: np.ndarray
    luminance_factor: np.ndarray
    max_luminance_factor: np.ndarray


def generating_functions(illuminant=DEFAULT_ILLUMINANT, *, observer=DEFAULT_OBSERVER,
                         wavelengths=DEFAULT_WAVELENGTHS) -> GeneratingFunctions:
    """Van Trigt's generating functions ``ρ(λ; λ₁)`` with ``Y(λ₁)`` and ``Y_M(λ₁)``.

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
    GeneratingFunctions
        For each touching wavelength λ₁: the reflectance (0–1), its luminance factor and the
        optimal colour's.

    References
    ----------
    C. van Trigt, J. Opt. Soc. Am. A 7, 1891–1904 (1990), Eq. (23)–(26), Figs. 5–6, 9–10.

    Examples
    --------
    >>> g = generating_functions("D65", wavelengths=(380, 780, 10))
    >>> bool(abs(g.reflectance.max(axis=1) - 1).max() < 1e-12 and abs(g.reflectance.min(axis=1)).max() < 1e-9)
    True
    """
    from . import zonotope

    domain = domain_of_validity(illuminant, observer=observer, wavelengths=wavelengths)
    setup, _, _ = setup_for(wavelengths, observer, illuminant)
    grid, labels, poly = domain.wavelengths_nm, domain.edge_wavelengths_nm, domain.region_xy
    before = np.roll(labels, 1)  # the edge that ends at vertex i
    keep = np.isfinite(labels) & np.isfinite(before)
    xy, a, b = poly[keep], before[keep], labels[keep]
    end = np.isin(a, grid[[0, -1]]) | np.isin(b, grid[[0, -1]])
    touch = np.where(end, np.where(np.isin(a, grid[[0, -1]]), a, b), 0.5 * (a + b))
    order = np.argsort(touch)
    xy, touch, end = xy[order], touch[order], end[order]
    XYZ = np.stack([xy[:, 0] / xy[:, 1], np.ones(len(xy)), (1 - xy.sum(axis=1)) / xy[:, 1]], axis=1)
    rho = XYZ @ setup.problem.unconstrained
    scale = rho.max(axis=1)
    rho = rho / scale[:, None]
    Y = 1.0 / scale / setup.white[1]
    # the optimal colour of each chromaticity: where the ray from black leaves the solid
    YM = zonotope.ray_exit(setup.solid, np.zeros(3), XYZ) / setup.white[1]
    return GeneratingFunctions(grid, touch, np.where(end, "2", "1"), xy, rho, Y, YM)
