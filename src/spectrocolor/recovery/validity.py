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
        """Whether the unconstrained solution is ≥ 0 at chromaticities ``xy`` (..., 2), y > 0."""
        c = np.asarray(xy, dtype=float)
        return np.all(self._levels(c) >= 0.0, axis=-1) & (c[..., 1] > 0)

    def max_luminance_factor(self, xy) -> np.ndarray:
        """Largest ``Y/Y0`` (0–1 scale, ``Y0`` the perfect white) at chromaticities ``xy``
        (..., 2) for which the unconstrained solution stays ≤ 1; NaN where it is negative
        somewhere (outside :attr:`region_xy`)."""
        c = np.asarray(xy, dtype=float)
        top = self._levels(c).max(axis=-1)
        with np.errstate(divide="ignore", invalid="ignore"):
            value = c[..., 1] / (100.0 * top)
        return np.where(self.nonnegative(c), value, np.nan)

    def end_lines(self) -> tuple[np.ndarray, np.ndarray]:
        """Coefficients ``(a, b, c)`` of the lines ``a x + b y + c = 0`` on which the
        unconstrained solution vanishes at the first (λ_b) and the last (λ_e) sample."""
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
    illuminant="D65", observer="1931", wavelengths=DEFAULT_WAVELENGTHS
) -> DomainOfValidity:
    """The domain of validity of the unconstrained smoothest reflectance.

    Parameters
    ----------
    illuminant, observer, wavelengths
        As for :func:`spectrocolor.smoothest_reflectance`.

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
