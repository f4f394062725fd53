"""Validated inputs shared by the recovery modules: colours, grids and the cached setup.

:func:`xyz_array` checks tristimulus values, :func:`grid_key` turns a wavelength argument into
the hashable ``(start_nm, stop_nm, step_nm)`` of a uniform grid, and :func:`setup_for` returns
the :class:`Setup` (weights, quadratic programme, facets of the object-colour solid and of the
cone of non-negative spectra) for one grid, observer and illuminant, cached for named ones.
"""

from __future__ import annotations

from functools import cached_property, lru_cache
from numbers import Real

import numpy as np

from ..colorimetry import weights
from ..coordinates import colour_array
from ..errors import ColorimetryError, SpectrumError
from ..illuminants import Illuminant, resolve_illuminant
from ..observers import Observer, resolve_observer
from ..spectrum import wavelength_grid
from . import qp, zonotope

#: The default grid of the recovered reflectances: 380–780 nm in 5 nm steps.
DEFAULT_WAVELENGTHS = (380.0, 780.0, 5.0)

#: The most samples a recovery grid may have. The solver's memory grows as K² and its time as
#: about K^2.5 (measured on 360–830 nm, one colour, 2 cores: K = 941 at 0.5 nm, 0.21 GiB and 7 s;
#: K = 1881 at 0.25 nm, 0.55 GiB and 36 s), so 2001 samples (0.25 nm over 360–830 nm) bound a
#: job to well under 1 GiB; 1 nm over 360–830 nm is 471 samples.
MAX_SAMPLES = 2001


class Setup:
    """Weights ``W`` (K, 3), programme and solid facets for one (grid, observer, illuminant)."""

    def __init__(self, grid: np.ndarray, W: np.ndarray):
        self.grid = grid
        self.W = W
        self.step_nm = float(grid[1] - grid[0])
        self.problem = qp.make_problem(W, self.step_nm)
        self.white = W.sum(axis=0)

    @cached_property
    def solid(self) -> zonotope.Facets:
        return zonotope.solid_facets(self.W)

    @cached_property
    def cone(self) -> zonotope.Facets:
        return zonotope.cone_facets(self.W)


@lru_cache(maxsize=32)
def _named_setup(key: tuple[float, float, float], observer: Observer, illuminant: Illuminant) -> Setup:
    grid = wavelength_grid(*key)
    return Setup(grid, weights(grid, observer=observer, illuminant=illuminant))


def grid_key(wavelengths) -> tuple[float, float, float]:
    """``(start_nm, stop_nm, step_nm)`` of a uniform grid given as such a triple or as an array.

    Parameters
    ----------
    wavelengths : tuple of float or array_like
        The grid; see :term:`wavelength grid`.

    Returns
    -------
    tuple of float
        ``(start_nm, stop_nm, step_nm)``, hashable (a cache key).

    Raises
    ------
    SpectrumError
        For a triple that does not make a grid, or an array that is not a uniform grid.

    Examples
    --------
    >>> grid_key(np.arange(400.0, 431.0, 10.0))
    (400.0, 430.0, 10.0)
    """
    if isinstance(wavelengths, tuple | list) and len(wavelengths) == 3:
        if all(isinstance(v, Real) for v in wavelengths):
            wavelength_grid(*wavelengths)  # validates
            return float(wavelengths[0]), float(wavelengths[1]), float(wavelengths[2])
    try:
        grid = np.asarray(wavelengths, dtype=float)
    except (TypeError, ValueError):
        grid = np.zeros(0)
    if grid.ndim == 1 and grid.size >= 3 and np.all(np.isfinite(grid)):
        steps = np.diff(grid)
        if np.all(steps > 0) and np.allclose(steps, steps[0], rtol=1e-9, atol=0):
            return (float(grid[0]), float(grid[-1]), float(steps[0]))
    raise SpectrumError(
        "wavelengths: expected (start_nm, stop_nm, step_nm) or a uniform increasing grid of at "
        f"least 3 samples, got {wavelengths!r}"
    )


def setup_for(wavelengths, observer, illuminant) -> tuple[Setup, str, str]:
    """The :class:`Setup` (cached for named observers and illuminants) and their labels.

    ``illuminant`` takes every form of :func:`spectrocolor.resolve_illuminant` but ``None``
    (a reflectance needs a light): a CIE name, ``"blackbody:T"``, ``"D:T"``, a temperature, a
    Spectrum on the grid, or an :class:`~spectrocolor.illuminants.Illuminant`.

    Parameters
    ----------
    wavelengths : tuple of float or array_like
        The grid; see :term:`wavelength grid`.
    observer : str, Spectrum or Observer
        Observer name or alias, colour-matching functions on the grid, or a resolved Observer.
    illuminant : str, float, Spectrum or Illuminant
        The light (not ``None``).

    Returns
    -------
    tuple of (Setup, str, str)
        The setup (grid, weights ``W`` with the perfect white at Y = 100, the QP problem, and
        lazily the solid's facets), the observer's label and the illuminant's label.

    Raises
    ------
    ColorimetryError
        For ``illuminant=None``, an unknown observer or illuminant, or a grid of more than
        :data:`MAX_SAMPLES` samples.

    Examples
    --------
    >>> setup, observer, illuminant = setup_for((400, 700, 10), "1931", "d65")
    >>> setup.W.shape, setup.step_nm, observer, illuminant
    ((31, 3), 10.0, 'CIE 1931 2°', 'D65')
    """
    key = grid_key(wavelengths)
    samples = round((key[1] - key[0]) / key[2]) + 1
    if samples > MAX_SAMPLES:
        raise ColorimetryError(
            f"wavelengths: {samples} samples ({key[0]:g}–{key[1]:g} nm at {key[2]:g} nm); the "
            f"recovery takes at most {MAX_SAMPLES} (its memory grows as the square of the "
            f"count): use a coarser step, e.g. 1 nm"
        )
    light = resolve_illuminant(illuminant)
    if light is None:
        raise ColorimetryError(
            "illuminant: reflectances need a light; None means the spectra are lights themselves"
        )
    viewer = resolve_observer(observer)
    if viewer.cacheable and light.cacheable:
        return _named_setup(key, viewer, light), viewer.name, light.label
    grid = wavelength_grid(*key)
    return Setup(grid, weights(grid, observer=viewer, illuminant=light)), viewer.name, light.label


def xyz_array(XYZ, name: str = "XYZ") -> np.ndarray:
    """Finite tristimulus values of shape (..., 3) as a float array, or a clear error.

    Parameters
    ----------
    XYZ : array_like, shape (..., 3)
        Tristimulus values, XYZ100.
    name : str, default "XYZ"
        The argument's name, for messages.

    Returns
    -------
    numpy.ndarray, shape (..., 3)
        Float64 values.

    Raises
    ------
    ColorimetryError
        For malformed input, NaN or infinity.

    Examples
    --------
    >>> xyz_array([1, 2, 3]).tolist()
    [1.0, 2.0, 3.0]
    """
    b = colour_array(XYZ, name, 3, "X, Y, Z on the Y = 100 scale")
    if not np.all(np.isfinite(b)):
        raise ColorimetryError(
            f"{name}: contains NaN or infinite values; pass finite tristimulus values")
    return b
