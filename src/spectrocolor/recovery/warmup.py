"""Compile the smoothest-reflectance kernels before they are needed: ``python -m spectrocolor.recovery.warmup``.

Kept apart from :mod:`.compiled` (the kernels' switch and wrappers, which the solvers import):
warming up runs the solvers, so it sits above them.
"""

from __future__ import annotations

import numpy as np

from .compiled import kernels
from .smoothest import smoothest_reflectance

__all__ = ["warm_up"]


def warm_up() -> bool:
    """Compile (or load from the cache) every kernel now rather than on first use.

    The first use on a machine compiles the kernels, about 35 s on a 2-core machine (longer
    under load), and caches them beside :mod:`.numba_kernels`; later processes load them in well
    under a second. ``make test`` calls this before the tests (whose servers must not spend their
    time limits compiling), as ``python -m spectrocolor.recovery.warmup``; the explorer calls it
    in a background process while its pages use the NumPy path (:mod:`spectrocolor.app.kernels`).

    Returns
    -------
    bool
        Whether the kernels are in use (False without numba or with ``SPECTROCOLOR_NUMBA=0``).

    Examples
    --------
    >>> isinstance(warm_up(), bool)
    True
    """
    if kernels() is None:
        return False
    colours = np.array([[40.0, 40.0, 40.0], [30.0, 20.0, 3.0], [60.0, 30.0, 5.0]])
    for bounds in ("unit", "nonnegative", None):
        smoothest_reflectance(colours, wavelengths=(400.0, 700.0, 20.0), bounds=bounds)
    return True


if __name__ == "__main__":  # python -m spectrocolor.recovery.warmup
    print("recovery kernels", "compiled and cached" if warm_up() else "not in use (NumPy path)")
