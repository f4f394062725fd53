"""The certificate's rounding constants and refinement steps: shared by the solvers and the kernels.

:mod:`.certificate` (the NumPy path) and :mod:`.compiled` (the numba kernels' wrappers) both
need the same tolerances, so they live here, below both: see :mod:`.certificate` for their
derivation (small multiples of Higham's bound ``γ_n`` on the rounding error of an n-term sum).

References
----------
N. J. Higham, *Accuracy and Stability of Numerical Algorithms*, 2nd ed., SIAM (2002), §3.1.
"""

from __future__ import annotations

import numpy as np

__all__ = ["DUAL_FACTOR", "EPS", "PRIMAL_FACTOR", "REFINE_STEPS", "gamma"]

EPS = float(np.finfo(float).eps)
#: Multiple of the worst-case rounding bound allowed for ``ρ @ W − b`` (half of it for the
#: rounding of the evaluation in any order, half for the rounding of ρ itself).
PRIMAL_FACTOR = 2.0
#: Multiple of ``ε (|Q||ρ| + |W||μ|)_k`` allowed for ``λ_k`` off the bounds and for a wrong
#: sign at them: ``γ_6 ≈ 6 ε`` bounds the rounding of one evaluation, the solver's iterative
#: refinement leaves at most about as much again, and a factor 2 keeps the verdict the same
#: for every summation order.
DUAL_FACTOR = 32.0
#: Iterative-refinement steps of the reduced solves (:func:`.qp._reduced_solve`,
#: :func:`.dense_active_set.equality_qp`, the compiled kernels): what brings a solve to the
#: certificate's rounding level.
REFINE_STEPS = 3


def gamma(n: int) -> float:
    """Higham's ``γ_n = n ε / (1 − n ε)``: relative error bound of an n-term sum.

    Examples
    --------
    >>> bool(abs(gamma(1) - 2.0 ** -52) < 1e-30)
    True
    """
    return n * EPS / (1.0 - n * EPS)
