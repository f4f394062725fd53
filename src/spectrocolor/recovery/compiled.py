"""The optional compiled kernels of the smoothest-reflectance solvers (numba, extra ``fast``).

Three kernels (:mod:`.numba_kernels`) take one colour at a time through what the NumPy path
does with whole-batch arrays: the closed form with its refinement
(:func:`.qp.solve_unconstrained`), the primal-dual active-set iterations (:func:`.qp._pdas`)
and the certificate's measures (:func:`.certificate.certify`). Each colour's samples stay in
the processor's cache, and the refinement of the closed form is an O(K) solve
(:class:`.pinned_kkt.PinnedKKT`) instead of a product with the dense KKT inverse.

The kernels sum in another order than BLAS does, so their results agree with the NumPy
path's to rounding rather than bit for bit; the certificate's tolerances hold for any order of
summation, and the tests hold the kernels' certificate measures to the NumPy path's and both
paths' solutions to each other. Without numba, or with ``SPECTROCOLOR_NUMBA=0``, :func:`kernels`
returns None and the NumPy path runs (:mod:`spectrocolor.numba_support`: switch, cache and
thread rule).
"""

from __future__ import annotations

from functools import lru_cache
from types import SimpleNamespace

import numpy as np

from ..numba_support import use_compiled
from . import tolerances

__all__ = ["closed_form", "facet_maxima", "kernels", "measures", "pdas", "roughness"]


@lru_cache(maxsize=1)
def _compiled():
    try:
        from . import numba_kernels as nk
    except ImportError:  # numba is not installed (the extra "fast")
        return None
    return SimpleNamespace(closed_form=nk.closed_form, pdas=nk.pdas, measures=nk.measures,
                           facet_maxima=nk.facet_maxima, roughness=nk.roughness)


def kernels():
    """The compiled kernels, or None without numba, with ``SPECTROCOLOR_NUMBA=0`` or while another
    process compiles them (:func:`spectrocolor.numba_support.use_compiled`).

    Returns
    -------
    types.SimpleNamespace or None
        ``closed_form``, ``pdas``, ``measures``, ``facet_maxima`` and ``roughness``: numba
        dispatchers.

    Examples
    --------
    >>> k = kernels()
    >>> k is None or callable(k.pdas)
    True
    """
    if not use_compiled():
        return None
    return _compiled()


def _factors(step_nm: float, size: int):
    """``2/h``, ``PRIMAL_FACTOR γ_{K+1}`` and ``DUAL_FACTOR``: the certificate's constants."""
    return (2.0 / step_nm, tolerances.PRIMAL_FACTOR * tolerances.gamma(size + 1),
            tolerances.DUAL_FACTOR)


def _operand(a):
    """``a`` as a writable, C-ordered float64 array: the one array type the kernels are
    compiled for (a read-only or Fortran-ordered input would otherwise compile them again)."""
    return np.require(a, dtype=np.float64, requirements=("C", "W"))


def _layouts(W):
    """``Wᵀ`` and ``|W|ᵀ`` (m, K), contiguous: the kernels' layout of the weights."""
    WT = np.ascontiguousarray(np.asarray(W, dtype=np.float64).T)
    return WT, np.abs(WT)


def closed_form(found, prob, b, refine_steps, lowest=-np.inf, highest=np.inf):
    """Unconstrained minimisers, multipliers, certificate measures and roughness of colours
    ``b``: ``rho`` (N, K), ``mu`` (N, m), the measures (5, N) of :func:`.certificate.certify`
    and ``Σ (Δρ)² / h`` (N,).

    Each closed form is refined (by :class:`.pinned_kkt.PinnedKKT`, at most ``refine_steps`` times)
    while its ratio exceeds a quarter; colours with a value below ``lowest`` or above
    ``highest`` are left unrefined and unmeasured (ratio ∞, roughness NaN).
    """
    b = _operand(b)
    K, m = prob.W.shape
    rho, mu, out = np.empty((len(b), K)), np.empty((len(b), m)), np.empty((5, len(b)))
    rough = np.empty(len(b))
    t, primal, dual = _factors(prob.step_nm, K)
    pin = prob.pinned
    stacked = np.vstack([pin.sub, pin.sup_factor, pin.inverse_denominator, pin.P.T])
    basis = prob.basis
    found.closed_form(*_layouts(prob.W), b, basis.inverse, basis.solutions, basis.multipliers, t,
                      stacked, pin.S_lu, pin.S_piv, refine_steps, primal, dual, float(lowest),
                      float(highest), rho, mu, out, rough)
    return rho, mu, out, rough


def pdas(found, prob, b, lower, upper, lo_act, up_act, max_iter, refine_steps):
    """:func:`.qp._pdas` compiled: returns rho, mu, lam, iterations, converged.

    With ``lo_act = up_act = None`` each colour starts from the bounds its (unrefined) closed
    form violates, as :func:`.qp.solve_bounded` does; a colour that violates none is returned
    as its closed form, converged after 0 iterations.
    """
    b = _operand(b)
    N, (K, m) = len(b), prob.W.shape
    from_closed_form = lo_act is None
    if from_closed_form:
        lo, up = np.empty((N, K), dtype=np.bool_), np.empty((N, K), dtype=np.bool_)
    else:
        lo = np.array(lo_act, dtype=np.bool_, order="C")
        up = np.array(up_act, dtype=np.bool_, order="C")
    rho, mu, lam = np.empty((N, K)), np.empty((N, m)), np.empty((N, K))
    iterations, converged = np.zeros(N, dtype=np.int64), np.zeros(N, dtype=np.bool_)
    t, primal, dual = _factors(prob.step_nm, K)
    found.pdas(*_layouts(prob.W), b, prob.unconstrained, prob.multipliers, -t, t, float(lower),
               float(upper), lo, up, from_closed_form, max_iter, refine_steps, primal, dual, rho,
               mu, lam, iterations, converged)
    return rho, mu, lam, iterations, converged


def measures(found, W, step_nm, b, rho, mu, lower, upper):
    """The certificate's five measures (5, N) (:func:`.certificate.certify`); rows holding a
    NaN or an infinity come back with an infinite ratio, for the caller to measure again."""
    b, rho, mu = _operand(b), _operand(rho), _operand(mu)
    out = np.empty((5, len(b)))
    t, primal, dual = _factors(step_nm, W.shape[0])
    bounded = lower is not None
    found.measures(*_layouts(W), t, b, rho, mu, float(lower) if bounded else 0.0,
                   float(upper) if bounded else 0.0, bounded, primal, dual, out)
    return out


def facet_maxima(found, b, centre, normals, absolute):
    """Per colour, ``(top, index)``: the largest ``normals · (b − centre)`` (of its absolute value
    with ``absolute``) and the facet attaining it, first on ties (:func:`.zonotope.gauge`)."""
    b = _operand(b)
    top, index = np.empty(len(b)), np.empty(len(b), dtype=np.int64)
    found.facet_maxima(b, np.asarray(centre, dtype=np.float64),
                       _operand(np.asarray(normals).T), absolute,
                       top, index)
    return top, index


def roughness(found, rho, step_nm):
    """``Σ (Δρ)² / h`` of each row of ``rho`` (N, K) (:meth:`.qp.Problem.objective`)."""
    rho = _operand(rho)
    out = np.empty(len(rho))
    found.roughness(rho, float(step_nm), out)
    return out
