"""Metamers under a change of illuminant: mismatch regions and smooth, bounded metamers.

All reflectances ``0 ≤ ρ ≤ 1`` with the colour ``XYZ100`` under a first illuminant (weights
``W1``) have, under a second illuminant (weights ``W2``), colours that fill a convex body:
the *metamer mismatch region*. Its support function in a direction ``d`` is the linear
programme ``max d · (ρ @ W2)`` subject to ``ρ @ W1 = XYZ100`` and ``0 ≤ ρ ≤ 1``; the
maximising reflectances are 0/1 except at no more than three samples. Solving it for many
directions gives points on the boundary of the region (and the region's outer polytope).

A *smooth* metamer that is as different as asked is the smoothest reflectance (van Trigt's
roughness, ``bounds="unit"``) with six equality constraints: ``ρ @ W1 = XYZ100`` and
``ρ @ W2 = XYZ100_second``, with ``XYZ100_second`` chosen inside the mismatch region —
e.g. a fraction ``amount`` of the way from the sample's own colour under the second
illuminant to the boundary point farthest from it in CIEDE2000.

References
----------
A. D. Logvinenko, B. Funt, C. Godau, "Metamer mismatching", IEEE Trans. Image Process. 23,
34–43 (2014) (the region and its extreme, two-transition-like metamers).
C. van Trigt, J. Opt. Soc. Am. A 7, 1891–1904 (1990) (the smoothness criterion).
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache

import numpy as np

from ..colorimetry import weights
from ..coordinates import lab
from ..differences import delta_e_2000
from ..errors import ColorimetryError
from ..illuminants import DEFAULT_ILLUMINANT, Illuminant, resolve_illuminant
from ..observers import DEFAULT_OBSERVER, Observer, resolve_observer
from ..spectrum import Spectrum, wavelength_grid
from . import qp, zonotope
from .certificate import Certificate, certify
from .inputs import DEFAULT_WAVELENGTHS, grid_key, setup_for, xyz_array
from .optimal import object_colour_membership
from .smoothest import smoothest_reflectance


@dataclass(frozen=True)
class MismatchRegion:
    """The metamer mismatch region of one colour under a second illuminant.

    Attributes
    ----------
    XYZ100 : ndarray (3,)
        The colour under the first illuminant (its perfect white ``Y = 100``).
    directions : ndarray (n, 3)
        Unit directions in the second illuminant's XYZ100 space.
    support : ndarray (n,)
        ``max d · XYZ100_second`` over all metamers: the region lies in every half-space
        ``d · XYZ ≤ support``.
    boundary_XYZ100 : ndarray (n, 3)
        Colours under the second illuminant of the extreme metamers (on the boundary).
    extreme_metamers : Spectrum (n, K)
        The extreme metamers themselves (0/1 except at a few samples).
    illuminant, second_illuminant, observer : str
        The conditions used: the lights' labels (:func:`spectrocolor.illuminant_label`) and the
        observer's name; see :term:`illuminant`.

    Examples
    --------
    >>> import numpy as np
    >>> from spectrocolor import wavelength_grid, weights
    >>> grid = wavelength_grid(400, 700, 10)
    >>> grey = np.full(grid.size, 0.4)  # a flat 40 % reflectance
    >>> region = metamer_mismatch_region(grey @ weights(grid, illuminant="D65"), wavelengths=(400, 700, 10),
    ...                                  directions=50)
    >>> region.support.shape, region.extreme_metamers.values.shape, region.second_illuminant
    ((50,), (50, 31), 'A')
    """

    XYZ100: np.ndarray
    directions: np.ndarray
    support: np.ndarray
    boundary_XYZ100: np.ndarray
    extreme_metamers: Spectrum
    illuminant: str
    second_illuminant: str
    observer: str

    def contains(self, XYZ_second, tolerance: float = 1e-9) -> np.ndarray:
        """Whether colours (..., 3) under the second illuminant satisfy every supporting
        half-space (an outer bound of the region: exact up to the direction sampling).

        Parameters
        ----------
        XYZ_second : array_like, shape (..., 3)
            Colours under the second illuminant, XYZ100 (its perfect white Y = 100).
        tolerance : float, default 1e-9
            Slack on each half-space, XYZ100 units.

        Returns
        -------
        numpy.ndarray of bool, shape (...)
            True where every supporting half-space holds.

        Examples
        --------
        >>> import numpy as np
        >>> from spectrocolor import wavelength_grid, weights
        >>> grid = wavelength_grid(400, 700, 10)
        >>> grey = np.full(grid.size, 0.4)  # a flat 40 % reflectance
        >>> region = metamer_mismatch_region(grey @ weights(grid, illuminant="D65"), wavelengths=(400, 700, 10),
        ...                                  directions=50)
        >>> region.contains([grey @ weights(grid, illuminant="A"), [90.0, 40.0, 5.0]]).tolist()
        [True, False]
        """
        b = np.asarray(XYZ_second, dtype=float)
        return np.all(b @ self.directions.T <= self.support + tolerance, axis=-1)


@dataclass(frozen=True)
class MetamerResult:
    """Smoothest reflectances matching colours under two illuminants.

    Attributes
    ----------
    spectrum : Spectrum (..., K)
        Reflectance factors (0–1); NaN where no reflectance within the bounds matches both.
    XYZ100, XYZ100_second : ndarray (..., 3)
        The colours asked for under the first and the second illuminant.
    feasible : ndarray of bool (...)
    roughness : ndarray (...)
        ``∫ (dρ/dλ)² dλ`` of the piecewise-linear ρ, nm⁻¹.
    certificate : Certificate
        As for :func:`smoothest_reflectance`, with the six equality constraints.
    """

    spectrum: Spectrum
    XYZ100: np.ndarray
    XYZ100_second: np.ndarray
    feasible: np.ndarray
    roughness: np.ndarray
    certificate: Certificate


#: The light the metamers are seen under when the caller gives none: CIE illuminant A
#: (incandescent, CIE 015:2018 §4.1), the classic change from daylight.
DEFAULT_SECOND_ILLUMINANT = "A"


def _resolve_conditions(illuminant, second_illuminant, observer) -> tuple[Illuminant, Illuminant, Observer]:
    """The two lights and the observer, resolved once at a public function's entry.

    Both lights take every form of :func:`spectrocolor.resolve_illuminant` but ``None``.
    """
    first = resolve_illuminant(illuminant, "illuminant")
    second = resolve_illuminant(second_illuminant, "second_illuminant")
    if first is None or second is None:
        argument = "illuminant" if first is None else "second_illuminant"
        raise ColorimetryError(f"{argument}: reflectances need a light; None means the spectra are lights themselves")
    return first, second, resolve_observer(observer)


def _pair_weights(wavelengths, observer: Observer, illuminant: Illuminant, second_illuminant: Illuminant):
    setup, obs, ill = setup_for(wavelengths, observer, illuminant)
    W2 = np.asarray(weights(setup.grid, observer=observer, illuminant=second_illuminant))
    return setup, W2, obs, ill, second_illuminant.label


@lru_cache(maxsize=16)
def _pair_problem(grid_key, observer: Observer, illuminant: Illuminant, second_illuminant: Illuminant) -> qp.Problem:
    grid = wavelength_grid(*grid_key)
    W = np.concatenate([np.asarray(weights(grid, observer=observer, illuminant=illuminant)),
                        np.asarray(weights(grid, observer=observer, illuminant=second_illuminant))], axis=1)
    return qp.make_problem(W, grid_key[2])


def _polish(x: np.ndarray, A: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Make a simplex vertex exact: values left at 0 or 1 stay; the others absorb the
    rounding of ``x @ A = b`` by a minimum-norm correction (kept if it stays in bounds)."""
    x = np.clip(x, 0.0, 1.0)
    free = np.flatnonzero((x > 0) & (x < 1))
    if free.size:
        y = x.copy()
        y[free] += np.linalg.lstsq(A[free].T, b - x @ A, rcond=None)[0]
        if np.all((y >= 0) & (y <= 1)):
            return y
    return x


def metamer_mismatch_region(
    XYZ,
    *,
    illuminant=DEFAULT_ILLUMINANT,
    second_illuminant=DEFAULT_SECOND_ILLUMINANT,
    observer=DEFAULT_OBSERVER,
    wavelengths=DEFAULT_WAVELENGTHS,
    directions: int | np.ndarray = 200,
) -> MismatchRegion:
    """The metamer mismatch region of a colour for a change of illuminant.

    Parameters
    ----------
    XYZ : array_like (3,)
        The colour under ``illuminant`` (perfect white ``Y = 100``); it must lie in the
        object-colour solid.
    illuminant, second_illuminant : str, float, Spectrum or Illuminant, keyword-only
        The light the metamers match under (default ``"D65"``) and the one they are seen under
        (default ``"A"``, :data:`DEFAULT_SECOND_ILLUMINANT`); not ``None``; see :term:`illuminant`.
    observer : str, Spectrum or Observer, keyword-only
        The observer of both colours (default CIE 1931 2°); see :term:`observer`.
    wavelengths : tuple of float or array_like, default (380.0, 780.0, 5.0)
        The reflectances' samples; see :term:`wavelength grid`.
    directions : int or ndarray (n, 3)
        Number of directions (spread evenly on the sphere) or the directions themselves.

    Returns
    -------
    MismatchRegion

    Raises
    ------
    ColorimetryError
        If ``XYZ`` is not a single colour in the object-colour solid.

    References
    ----------
    A. D. Logvinenko, B. Funt, C. Godau, IEEE Trans. Image Process. 23, 34–43 (2014).

    Examples
    --------
    >>> import numpy as np
    >>> from spectrocolor import wavelength_grid, weights
    >>> grid = wavelength_grid(400, 700, 10)
    >>> grey = np.full(grid.size, 0.4)  # a flat 40 % reflectance
    >>> region = metamer_mismatch_region(grey @ weights(grid, illuminant="D65"), wavelengths=(400, 700, 10),
    ...                                  directions=50)
    >>> bool(region.contains(grey @ weights(grid, illuminant="A")))  # the grey itself under A
    True
    """
    from scipy.optimize import linprog

    b = xyz_array(XYZ)
    if b.shape != (3,):
        raise ColorimetryError(f"XYZ: expected one colour of shape (3,), got {b.shape}")
    illuminant, second_illuminant, observer = _resolve_conditions(illuminant, second_illuminant, observer)
    setup, W2, obs, ill, ill2 = _pair_weights(wavelengths, observer, illuminant,
                                              second_illuminant)
    member = object_colour_membership(b, illuminant=illuminant, observer=observer, wavelengths=wavelengths)
    if not member.inside:
        raise ColorimetryError(
            f"XYZ: {b.tolist()} is outside the object-colour solid for illuminant {ill} "
            f"(distance ≥ {float(member.distance_outside):.4g} XYZ100); it has no metamers")
    if isinstance(directions, int | np.integer):
        if directions < 4:
            raise ColorimetryError(f"directions: expected at least 4, got {directions}")
        dirs = zonotope.sphere_directions(int(directions))
    else:
        dirs = np.asarray(directions, dtype=float)
        if dirs.ndim != 2 or dirs.shape[1] != 3 or not np.all(np.isfinite(dirs)):
            raise ColorimetryError(f"directions: expected an int or an (n, 3) array, got {dirs.shape}")
        dirs = dirs / np.linalg.norm(dirs, axis=1, keepdims=True)
    W1 = setup.W
    K = W1.shape[0]
    extremes = np.empty((len(dirs), K))
    for i, d in enumerate(dirs):
        res = linprog(-(W2 @ d), A_eq=W1.T, b_eq=b, bounds=[(0.0, 1.0)] * K,
                      method="highs-ds", options={"primal_feasibility_tolerance": 1e-10})
        if res.status != 0:  # pragma: no cover - the colour was checked to be inside
            raise ColorimetryError(f"XYZ: linear programme failed ({res.message})")
        extremes[i] = _polish(res.x, W1, b)
    boundary = extremes @ W2
    return MismatchRegion(
        XYZ100=b,
        directions=dirs,
        support=np.einsum("ij,ij->i", boundary, dirs),
        boundary_XYZ100=boundary,
        extreme_metamers=Spectrum(setup.grid, extremes),
        illuminant=ill,
        second_illuminant=ill2,
        observer=obs,
    )


def smoothest_metamer(
    XYZ,
    XYZ_second,
    *,
    illuminant=DEFAULT_ILLUMINANT,
    second_illuminant=DEFAULT_SECOND_ILLUMINANT,
    observer=DEFAULT_OBSERVER,
    wavelengths=DEFAULT_WAVELENGTHS,
) -> MetamerResult:
    """The smoothest reflectance(s) ``0 ≤ ρ ≤ 1`` with given colours under two illuminants.

    Minimises van Trigt's roughness ``∫ (dρ/dλ)² dλ`` subject to ``ρ @ W1 = XYZ`` and
    ``ρ @ W2 = XYZ_second`` (six equality constraints), exactly, with the same solver and
    certificate as :func:`spectrocolor.smoothest_reflectance`.

    Parameters
    ----------
    XYZ, XYZ_second : array_like (..., 3)
        Colours under ``illuminant`` and ``second_illuminant`` (each white ``Y = 100``).

    illuminant, second_illuminant : str, float, Spectrum or Illuminant, keyword-only
        The lights of ``XYZ`` (default ``"D65"``) and of ``XYZ_second`` (default ``"A"``); not
        ``None``; see :term:`illuminant`.
    observer : str, Spectrum or Observer, keyword-only
        The observer of both colours (default CIE 1931 2°); see :term:`observer`.
    wavelengths : tuple of float or array_like, default (380.0, 780.0, 5.0)
        The reflectances' samples; see :term:`wavelength grid`.

    Returns
    -------
    MetamerResult
        Pairs that no reflectance can match (``XYZ_second`` outside the mismatch region)
        are flagged and NaN; a single such pair raises :class:`ColorimetryError`.

    Raises
    ------
    ColorimetryError
        For shapes that differ, or a single pair that no reflectance can match.

    References
    ----------
    C. van Trigt, J. Opt. Soc. Am. A 7, 1891–1904 (1990) (smoothest reflectance).

    Examples
    --------
    >>> import numpy as np
    >>> from spectrocolor import wavelength_grid, weights
    >>> grid = wavelength_grid(400, 700, 10)
    >>> grey = np.full(grid.size, 0.4)  # a flat 40 % reflectance
    >>> pair = smoothest_metamer(grey @ weights(grid, illuminant="D65"), grey @ weights(grid, illuminant="A"),
    ...                          wavelengths=(400, 700, 10))
    >>> bool(abs(pair.spectrum.values - 0.4).max() < 1e-9)  # the grey is the smoothest
    True
    """
    from scipy.optimize import linprog

    b1, b2 = xyz_array(XYZ), xyz_array(XYZ_second, "XYZ_second")
    if b1.shape != b2.shape:
        raise ColorimetryError(f"XYZ_second: shape {b2.shape} differs from XYZ's {b1.shape}")
    illuminant, second_illuminant, observer = _resolve_conditions(illuminant, second_illuminant, observer)
    setup, W2, obs, ill, ill2 = _pair_weights(wavelengths, observer, illuminant,
                                              second_illuminant)
    if all(v.cacheable for v in (observer, illuminant, second_illuminant)):
        prob = _pair_problem(grid_key(wavelengths), observer, illuminant, second_illuminant)
    else:
        prob = qp.make_problem(np.concatenate([setup.W, W2], axis=1), setup.step_nm)
    shape = b1.shape[:-1]
    b = np.concatenate([b1, b2], axis=-1).reshape(-1, 6)
    N, K = len(b), prob.size
    rho, mu = qp.solve_unconstrained(prob, b)
    lam = np.zeros((N, K))
    converged = np.ones(N, dtype=bool)
    feasible = np.ones(N, dtype=bool)
    todo = np.flatnonzero(~np.all((rho >= 0) & (rho <= 1), axis=1))
    for i in todo:  # one small linear programme per colour decides feasibility
        res = linprog(np.zeros(K), A_eq=prob.W.T, b_eq=b[i], bounds=[(0.0, 1.0)] * K,
                      method="highs-ds", options={"primal_feasibility_tolerance": 1e-10})
        feasible[i] = res.status == 0
    todo = todo[feasible[todo]]
    if todo.size:
        sol = qp.solve_bounded(prob, b[todo], 0.0, 1.0)
        rho[todo], mu[todo], lam[todo] = sol.rho, sol.mu, sol.lam
        converged[todo] = sol.converged
    rho[~feasible], mu[~feasible], lam[~feasible] = np.nan, np.nan, np.nan
    converged[~feasible] = False
    if not shape and not feasible[0]:
        raise ColorimetryError(
            f"XYZ_second: {b2.tolist()} under {ill2} is outside the metamer mismatch region of "
            f"{b1.tolist()} under {ill}; no reflectance 0 ≤ ρ ≤ 1 matches both")
    certificate = certify(prob.W, prob.step_nm, b, rho, mu, 0.0, 1.0, converged)
    return MetamerResult(
        spectrum=Spectrum(setup.grid, rho.reshape(*shape, K)),
        XYZ100=b1,
        XYZ100_second=b2,
        feasible=feasible.reshape(shape),
        roughness=prob.objective(rho).reshape(shape),
        certificate=certificate.reshape(shape),
    )


@dataclass(frozen=True)
class DifferentMetamer:
    """A smooth metamer chosen to look as different as asked under a second illuminant.

    Attributes
    ----------
    metamer : MetamerResult
    reference_XYZ100_second : ndarray (3,)
        The sample's own colour under the second illuminant.
    farthest_XYZ100_second : ndarray (3,)
        The boundary point of the mismatch region farthest from it (CIEDE2000).
    delta_e_2000 : float
        ΔE00 between the sample and the metamer under the second illuminant (CIELAB relative
        to that illuminant's white).
    max_delta_e_2000 : float
        ΔE00 of the farthest boundary point (the most any metamer can differ, up to the
        direction sampling).
    region : MismatchRegion
    """

    metamer: MetamerResult
    reference_XYZ100_second: np.ndarray
    farthest_XYZ100_second: np.ndarray
    delta_e_2000: float
    max_delta_e_2000: float
    region: MismatchRegion


def most_different_metamer(
    sample,
    amount: float = 0.9,
    *,
    illuminant=DEFAULT_ILLUMINANT,
    second_illuminant=DEFAULT_SECOND_ILLUMINANT,
    observer=DEFAULT_OBSERVER,
    wavelengths=DEFAULT_WAVELENGTHS,
    directions: int = 200,
) -> DifferentMetamer:
    """A smooth, bounded metamer of ``sample`` that differs as much as asked under a second light.

    Parameters
    ----------
    sample : Spectrum (K,) or array_like (3,)
        A reflectance (on the grid of ``wavelengths``) or its colour under ``illuminant``;
        for a colour, its smoothest reflectance stands for the sample.
    amount : float, default 0.9
        0 ≤ amount < 1: the metamer's colour under ``second_illuminant`` lies this fraction
        of the way from the sample's to the farthest point of the mismatch region.
    illuminant, second_illuminant : str, float, Spectrum or Illuminant, keyword-only
        The light the metamer matches the sample under (default ``"D65"``) and the one where it
        differs (default ``"A"``); not ``None``; see :term:`illuminant`.
    observer : str, Spectrum or Observer, keyword-only
        The observer of both colours (default CIE 1931 2°); see :term:`observer`.
    wavelengths : tuple of float or array_like, default (380.0, 780.0, 5.0)
        The reflectances' samples; see :term:`wavelength grid`.
    directions : int, default 200
        Directions used to sample the mismatch region.

    Returns
    -------
    DifferentMetamer
        The metamer, its colour under the second light, the farthest colour and the ΔE00
        values reached and possible.

    Raises
    ------
    ColorimetryError
        For ``amount`` outside [0, 1), a sample not on the grid, or a colour outside the
        object-colour solid.

    References
    ----------
    A. D. Logvinenko, B. Funt, C. Godau (2014) (mismatch region); C. van Trigt (1990)
    (smoothest reflectance).

    Examples
    --------
    >>> import numpy as np
    >>> from spectrocolor import wavelength_grid, weights
    >>> grid = wavelength_grid(400, 700, 10)
    >>> grey = np.full(grid.size, 0.4)  # a flat 40 % reflectance
    >>> different = most_different_metamer(grey @ weights(grid, illuminant="D65"), amount=0.5,
    ...                                    wavelengths=(400, 700, 10), directions=50)
    >>> round(float(different.delta_e_2000), 2), round(float(different.max_delta_e_2000), 2)
    (16.55, 22.81)
    """
    a = float(amount)
    if not 0.0 <= a < 1.0:
        raise ColorimetryError(f"amount: expected 0 ≤ amount < 1, got {amount!r}")
    illuminant, second_illuminant, observer = _resolve_conditions(illuminant, second_illuminant, observer)
    setup, W2, obs, ill, ill2 = _pair_weights(wavelengths, observer, illuminant,
                                              second_illuminant)
    if isinstance(sample, Spectrum):
        if sample.values.shape != (len(setup.grid),) or not np.allclose(
                sample.wavelengths_nm, setup.grid, rtol=0, atol=1e-9):
            raise ColorimetryError(
                "sample: expected one reflectance on the grid of `wavelengths` "
                f"({setup.grid[0]:g}–{setup.grid[-1]:g} nm, {len(setup.grid)} samples); "
                "resample it first")
        rho = sample.values
    else:
        rho = smoothest_reflectance(sample, illuminant=illuminant, observer=observer,
                                    wavelengths=wavelengths).spectrum.values
    XYZ1, reference = rho @ setup.W, rho @ W2
    region = metamer_mismatch_region(XYZ1, illuminant=illuminant, second_illuminant=second_illuminant,
                                     observer=observer, wavelengths=wavelengths, directions=directions)
    white2 = W2.sum(axis=0)
    de = delta_e_2000(lab(reference, white2), lab(region.boundary_XYZ100, white2))
    far = region.boundary_XYZ100[int(np.argmax(de))]
    result = smoothest_metamer(XYZ1, reference + a * (far - reference), illuminant=illuminant,
                               second_illuminant=second_illuminant, observer=observer, wavelengths=wavelengths)
    got = float(delta_e_2000(lab(reference, white2), lab(result.spectrum.values @ W2, white2)))
    return DifferentMetamer(result, reference, far, got, float(de.max()), region)
