"""Certificates of optimality for the smoothest-reflectance programmes, at rounding level.

For the programme ``min ρ Q ρ / 2`` subject to ``ρ @ W = b`` and ``lower ≤ ρ ≤ upper``
(:mod:`spectrocolor.recovery.qp`), a reflectance ``ρ`` with multipliers ``μ`` is optimal when

* it reproduces the colour: ``ρ @ W = b``;
* it keeps the bounds exactly;
* the bound multipliers ``λ = Q ρ − W μ`` vanish where ρ is off its bounds (stationarity) and
  are ≥ 0 where ``ρ = lower``, ≤ 0 where ``ρ = upper`` (signs). The programme is convex, so
  these Karush–Kuhn–Tucker conditions are sufficient.

In floating point "=" and "vanish" mean: within the rounding error of evaluating the
expression, which is bounded by the sizes of the terms actually summed (Higham 2002, §3.1):
a sum of n terms ``t_i`` computed in any order, with any blocking (so on any BLAS and any
number of threads), is within ``γ_n Σ |t_i|`` of the exact sum, ``γ_n = n ε / (1 − n ε)``.
The tolerances below (their constants are in :mod:`.tolerances`) are small multiples of those
bounds, computed per component:

* primal, component j: ``PRIMAL_FACTOR · γ_{K+1} · (Σ_k |ρ_k W_kj| + |b_j|)``;
* dual, sample k: ``DUAL_FACTOR · ε · (|Q| |ρ| + |W| |μ|)_k`` — the two terms of ``λ_k``
  are a 3-term difference and a 3-term (6 for metamers) product sum.

They grow with ``|W| |μ|`` only because those are the terms summed in ``λ``: a large
multiplier (degenerate faces) makes each term large, and ``λ`` is then known only to the
rounding of those terms. A factor, never a fixed relative slack like 1e-8, separates a
certified result from a wrong one.

References
----------
N. J. Higham, *Accuracy and Stability of Numerical Algorithms*, 2nd ed., SIAM (2002), §3.1
(rounding error of sums and inner products).
J. Nocedal, S. J. Wright, *Numerical Optimization*, 2nd ed., Springer (2006), Thm. 16.4
(KKT conditions of a convex quadratic programme).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from . import compiled
from .tolerances import DUAL_FACTOR, EPS, PRIMAL_FACTOR, gamma


def abs_hess_times(rho: np.ndarray, step_nm: float) -> np.ndarray:
    """``|Q| |ρ|`` along the last axis, for the path Laplacian ``Q`` of :mod:`.qp`."""
    a = np.abs(rho) * (2.0 / step_nm)
    out = 2.0 * a
    out[..., 0] = a[..., 0]
    out[..., -1] = a[..., -1]
    out[..., :-1] += a[..., 1:]
    out[..., 1:] += a[..., :-1]
    return out


def hess_times(rho: np.ndarray, step_nm: float) -> np.ndarray:
    """``Q ρ`` along the last axis (``ρ Q ρ / 2 = Σ (Δρ)² / h``)."""
    d = np.diff(rho, axis=-1) * (2.0 / step_nm)
    out = np.empty_like(rho)
    out[..., 0] = -d[..., 0]
    out[..., 1:-1] = d[..., :-1] - d[..., 1:]
    out[..., -1] = d[..., -1]
    return out


def primal_tolerance(W: np.ndarray, b: np.ndarray, rho: np.ndarray) -> np.ndarray:
    """Allowed ``|ρ @ W − b|`` per component (N, m)."""
    return PRIMAL_FACTOR * gamma(W.shape[0] + 1) * (np.abs(rho) @ np.abs(W) + np.abs(b))


def dual_tolerance(W: np.ndarray, step_nm: float, rho: np.ndarray, mu: np.ndarray) -> np.ndarray:
    """Allowed ``|λ_k|`` off the bounds (and wrong-signed ``λ_k`` at them), (N, K)."""
    return DUAL_FACTOR * EPS * (abs_hess_times(rho, step_nm) + np.abs(mu) @ np.abs(W).T)


@dataclass(frozen=True)
class Certificate:
    """Evidence that each result solves the programme (arrays of the batch shape).

    Attributes
    ----------
    primal_residual : ndarray
        ``max_j |ρ @ W − XYZ100|_j``, XYZ100 units.
    bound_violation : ndarray
        Largest amount by which ρ leaves its bounds (0 when the bounds hold exactly).
    multiplier_sign_violation : ndarray
        Largest wrong-signed bound multiplier ``λ = Qρ − Wμ`` (it must be ≥ 0 where
        ``ρ = lower`` and ≤ 0 where ``ρ = upper``), in units of the roughness gradient.
    stationarity : ndarray
        ``max |λ_k|`` over the samples off the bounds (same units).
    rounding_ratio : ndarray
        The largest of these measures divided by its tolerance (see the module docstring:
        small multiples of the rounding error of the terms summed): ≤ 1 passes.
    converged : ndarray of bool
        The solver settled **and** every check passes: entries finite, bounds held exactly,
        ``rounding_ratio ≤ 1``. A result that fails any check (NaN included) is reported
        not converged.
    """

    primal_residual: np.ndarray
    bound_violation: np.ndarray
    multiplier_sign_violation: np.ndarray
    stationarity: np.ndarray
    rounding_ratio: np.ndarray
    converged: np.ndarray

    def reshape(self, shape) -> Certificate:
        """The same certificate with every array reshaped to the batch shape ``shape``."""
        return Certificate(*(np.asarray(v).reshape(shape) for v in vars(self).values()))


#: Colours per block in :func:`certify` (its arrays then stay in cache).
_BLOCK = 2048


def certify(W, step_nm, b, rho, mu, lower, upper, settled) -> Certificate:
    """Check ``ρ`` (N, K) with multipliers ``μ`` (N, m) for colours ``b`` (N, m).

    ``lower``/``upper`` are scalar bounds (``None`` for the unconstrained programme);
    ``settled`` (N,) says whether the solver stopped normally. The multipliers of the bounds
    are recomputed here from ρ and μ, so nothing else of the solver's state is trusted.
    """
    N = len(b)
    found = compiled.kernels()
    if found is not None:
        out = compiled.measures(found, W, step_nm, b, rho, mu, lower, upper)
        again = np.flatnonzero(~np.isfinite(out[4]))  # NaN rows: the NumPy path's semantics
        if again.size:
            out[:, again] = _measures(W, step_nm, b[again], rho[again], mu[again], lower, upper)
    else:
        out = np.empty((5, N))
        for start in range(0, N, _BLOCK):
            part = slice(start, start + _BLOCK)
            out[:, part] = _measures(W, step_nm, b[part], rho[part], mu[part], lower, upper)
    return from_measures(out, settled)


def from_measures(measures, settled) -> Certificate:
    """The certificate of measures (5, N) — primal residual, bound violation, sign violation,
    stationarity and rounding ratio, as :func:`certify` computes them — for results that
    ``settled`` (N,): converged where every entry was finite, the bounds hold exactly and the
    ratio is at most 1."""
    primal, violation, sign, station, ratio = measures
    passed = np.isfinite(ratio) & (violation == 0.0) & (ratio <= 1.0)
    return Certificate(primal, violation, sign, station, ratio,
                       np.asarray(settled, dtype=bool) & passed)


def _measures(W, step_nm, b, rho, mu, lower, upper):
    """Primal residual, bound violation, sign violation, stationarity and rounding ratio."""
    tiny = np.finfo(float).tiny
    with np.errstate(invalid="ignore", over="ignore"):
        finite = np.all(np.isfinite(rho), axis=1) & np.all(np.isfinite(mu), axis=1)
        residual = np.abs(rho @ W - b)
        ratio_p = (residual / np.maximum(primal_tolerance(W, b, rho), tiny)).max(axis=1)
        lam = hess_times(rho, step_nm) - mu @ W.T
        tol_d = np.maximum(dual_tolerance(W, step_nm, rho, mu), tiny)
        if lower is None:
            violation = np.zeros(len(b))
            off, wrong = np.abs(lam), np.zeros_like(lam)
        else:
            violation = np.maximum(lower - rho, rho - upper).max(axis=1).clip(min=0.0)
            at_lower, at_upper = rho == lower, rho == upper
            wrong = np.where(at_lower, -lam, np.where(at_upper, lam, 0.0)).clip(min=0.0)
            off = np.where(at_lower | at_upper, 0.0, np.abs(lam))
        ratio_d = (np.maximum(off, wrong) / tol_d).max(axis=1)
        ratio = np.where(finite, np.maximum(ratio_p, ratio_d), np.inf)
    return residual.max(axis=1), violation, wrong.max(axis=1), off.max(axis=1), ratio
