"""The smoothest-reflectance KKT system solved in O(K) per right-hand side (:class:`PinnedKKT`).

The compiled refinement of the closed form (:mod:`.numba_kernels`) uses these factors instead of
the dense inverse of :attr:`.qp.Problem.kkt_inverse`; :func:`.qp.make_problem` builds them.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.linalg import lu_factor, solve_banded


@dataclass(frozen=True)
class PinnedKKT:
    """The KKT system ``[[Q, −W], [Wᵀ, 0]] [δρ; δμ] = [s; r]`` solved in O(K) per right-hand side.

    ``Q`` is singular (constants), so it is pinned at the first sample:
    ``Q̂ = Q + c e₀ e₀ᵀ`` with ``c = 2/h`` is a positive definite tridiagonal matrix, factored
    once by the Thomas algorithm. With ``t = δρ₀``, ``Q̂ δρ = s + W δμ + c e₀ t``, so
    ``δρ = y + P [δμ; t]`` with ``y = Q̂⁻¹ s`` and ``P = Q̂⁻¹ [W, c e₀]``, and the ``m + 1``
    unknowns ``[δμ; t]`` solve ``S [δμ; t] = [r − Wᵀ y; −y₀]`` with
    ``S = [[Wᵀ P], [P₀ − e_m]]``. Each refinement step then costs a tridiagonal solve and
    ``O(K m)`` products, where the dense inverse of :attr:`Problem.kkt_inverse` costs
    ``O((K + m)²)``.

    Attributes
    ----------
    sub : ndarray (K,)
        Sub-diagonal of ``Q̂`` (``sub[k]`` couples sample k to k − 1; ``sub[0] = 0``), nm⁻¹.
    sup_factor, inverse_denominator : ndarray (K,)
        The Thomas algorithm's forward-sweep factors (super-diagonal over pivot; 1 / pivot).
    P : ndarray (K, m + 1)
        ``Q̂⁻¹ [W, c e₀]``.
    S_lu : ndarray (m + 1, m + 1)
        LU factors of ``S`` (``scipy.linalg.lu_factor`` layout), with pivots ``S_piv``.
    S_piv : ndarray (m + 1,) of int64

    References
    ----------
    G. H. Golub, C. F. Van Loan, *Matrix Computations*, 4th ed., Johns Hopkins (2013), §4.3
    (tridiagonal systems) and §2.1.4 (rank-one changes).
    """

    sub: np.ndarray
    sup_factor: np.ndarray
    inverse_denominator: np.ndarray
    P: np.ndarray
    S_lu: np.ndarray
    S_piv: np.ndarray


def _pinned_kkt(prob) -> PinnedKKT:
    """Factor the pinned Hessian of ``prob`` (a :class:`.qp.Problem`) and form ``P`` and ``S``
    (see :class:`PinnedKKT`)."""
    W = prob.W
    K, m = W.shape
    diag, off = prob.hessian_bands()
    c = 2.0 / prob.step_nm
    diag = diag.copy()
    diag[0] += c
    sub = np.concatenate([[0.0], off])
    sup_factor, inverse_denominator = np.empty(K), np.empty(K)
    previous = 0.0
    for k in range(K):
        inverse_denominator[k] = 1.0 / (diag[k] - sub[k] * previous)
        previous = (off[k] if k < K - 1 else 0.0) * inverse_denominator[k]
        sup_factor[k] = previous
    rhs = np.zeros((K, m + 1))
    rhs[:, :m] = W
    rhs[0, m] = c
    bands = np.zeros((3, K))
    bands[0, 1:], bands[1], bands[2, :-1] = off, diag, off
    P = solve_banded((1, 1), bands, rhs)
    S = np.concatenate([W.T @ P, P[:1]], axis=0)
    S[m, m] -= 1.0
    S_lu, S_piv = lu_factor(S)
    return PinnedKKT(sub, sup_factor, inverse_denominator, np.ascontiguousarray(P), S_lu,
                     S_piv.astype(np.int64))
