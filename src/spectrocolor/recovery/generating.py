"""Van Trigt's generating functions ρ(λ; λ₁) of the two solution classes (his Figs. 5, 6, 9 and 10).

The boundary of the domain of validity (:mod:`.validity`) is traced by unconstrained smoothest
reflectances that touch zero: class 1 with a zero at an end of the range and an inflection at
λ₁, class 2 with an interior zero of zero slope at λ₁. This module builds both families from
their multipliers, with a bound on the rounding of every sample, and the luminance factors
Y(λ₁) and Y_M(λ₁) of their colours.

References
----------
C. van Trigt, "Smoothest reflectance functions. I. Definition and main results",
J. Opt. Soc. Am. A 7, 1891–1904 (1990), Figs. 5, 6, 9 and 10.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..errors import ColorimetryError
from ..illuminants import DEFAULT_ILLUMINANT
from ..observers import DEFAULT_OBSERVER
from . import zonotope
from .inputs import DEFAULT_WAVELENGTHS, setup_for

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
        The light that weights the functions; see :term:`illuminant`.
    observer : str or Spectrum, default "1931"
        Whose colour-matching functions are weighted; see :term:`observer`.
    wavelengths : tuple of float or array_like, default (380.0, 780.0, 5.0)
        The functions' samples; see :term:`wavelength grid`.
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
    setup, _, _ = setup_for(wavelengths, observer, illuminant)
    grid, W, white = setup.grid, setup.W, setup.white
    K, h = len(grid), setup.step_nm
    lam = grid.copy() if lambda1_nm is None else np.atleast_1d(np.asarray(lambda1_nm, dtype=float))
    if lam.ndim != 1 or lam.size == 0 or not np.all(np.isfinite(lam)) or lam.min() < grid[0] \
            or lam.max() > grid[-1]:
        raise ColorimetryError(f"lambda1_nm: expected finite wavelengths within the grid "
                               f"{grid[0]:g}–{grid[-1]:g} nm, got {lambda1_nm!r:.80}")
    family = _Family(grid, W, white)
    rows: dict[str, list[np.ndarray]] = {"class": [], "lambda1": [], "zero": [], "rho": []}
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
