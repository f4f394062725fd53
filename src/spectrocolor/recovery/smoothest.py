"""The smoothest reflectance with given tristimulus values (van Trigt 1990), exact and batched.

For tristimulus values ``XYZ100`` under an illuminant (perfect white ``Y = 100``) we find
the reflectance ρ(λ) that minimises the roughness ``∫ (dρ/dλ)² dλ`` over the wavelength
range subject to reproducing ``XYZ100`` — without bounds, with ``ρ ≥ 0``, or with
``0 ≤ ρ ≤ 1``.

Discretisation. On the uniform grid ``λ_k`` (step ``h``) ρ is the piecewise-linear
interpolant of its samples, so the roughness is exactly ``Σ (ρ_{k+1} − ρ_k)² / h``, and the
constraint is ``ρ @ W = XYZ100`` with ``W = spectrocolor.weights(grid, observer,
illuminant)`` — the very weights that ``spectrocolor.tristimulus`` uses, so the recovered
ρ reproduces the colour to rounding. The ends are free: minimising the discrete sum gives
the natural end conditions ``dρ/dλ = 0`` of van Trigt's Euler–Lagrange equations in the
limit ``h → 0``, and the discrete problem converges to his continuous one.

The unconstrained solution is linear in ``XYZ100`` (one K × 3 matrix, precomputed). The
bounded problems are strictly convex quadratic programmes, solved exactly by a
primal-dual active-set (semismooth Newton) method that adds and releases bounds; every
result carries a certificate (primal residual, multiplier signs, complementarity).

References
----------
C. van Trigt, "Smoothest reflectance functions. I. Definition and main results",
J. Opt. Soc. Am. A 7, 1891–1904 (1990).
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property, lru_cache
from numbers import Real

import numpy as np

from ..colorimetry import weights
from ..errors import ColorimetryError, SpectrumError
from ..illuminants import canonical_illuminant_name
from ..observers import canonical_observer_name
from ..spectrum import Spectrum, wavelength_grid
from . import _face, _qp, _zonotope

BOUNDS = ("unit", "nonnegative", None)
DEFAULT_WAVELENGTHS = (380.0, 780.0, 5.0)
#: Colours whose gauge is within this of the boundary are solved as boundary colours.
BOUNDARY_TOLERANCE = 1e-12
#: Colours this close to the boundary on which the active-set methods fail are tried on a face.
NEAR_BOUNDARY = 1e-9
#: Certificate checks (see :class:`Certificate`): relative primal and dual tolerances.
PRIMAL_TOLERANCE = 1e-12
DUAL_TOLERANCE = 1e-8


@dataclass(frozen=True)
class Certificate:
    """Evidence that each result solves the programme (arrays of the batch shape).

    Attributes
    ----------
    primal_residual : ndarray
        ``max |ρ @ W − XYZ100|``, XYZ100 units.
    bound_violation : ndarray
        Largest amount by which ρ leaves its bounds (0 when the bounds hold exactly).
    multiplier_sign_violation : ndarray
        Largest wrong-signed bound multiplier (a multiplier must be ≥ 0 at a lower bound
        and ≤ 0 at an upper bound), in units of the gradient of the roughness.
    complementarity : ndarray
        ``max_k |λ_k| · distance of ρ_k to its bound``: 0 when every non-zero multiplier
        belongs to a bound that holds with equality.
    stationarity : ndarray
        ``max |Q ρ − W μ − λ|``: the gradient condition of the Lagrangian.
    converged : ndarray of bool
        The solver settled **and** the result passes the checks: every entry finite,
        ``primal_residual <= PRIMAL_TOLERANCE * max(|ρ| @ |W|)`` (rounding level, relative to
        the colour, so that tiny colours near black are held to the same standard), bounds
        hold exactly, and multiplier signs, complementarity
        and stationarity are within ``DUAL_TOLERANCE`` relative to the size of the
        gradient. A result that fails any check (NaN included) is reported not converged.
    """

    primal_residual: np.ndarray
    bound_violation: np.ndarray
    multiplier_sign_violation: np.ndarray
    complementarity: np.ndarray
    stationarity: np.ndarray
    converged: np.ndarray


@dataclass(frozen=True)
class SmoothestResult:
    """Result of :func:`smoothest_reflectance`.

    Attributes
    ----------
    spectrum : Spectrum
        Reflectance factors (0–1 scale) of shape ``(..., K)``; NaN for infeasible colours.
    XYZ100 : ndarray (..., 3)
        The requested colours.
    feasible : ndarray of bool (...)
        Some reflectance within the bounds produces the colour.
    distance_outside : ndarray (...)
        0 inside; outside, the distance (XYZ100 units) to the farthest violated facet plane of
        the object-colour solid (``bounds="unit"``) or of the cone of non-negative spectra
        (``"nonnegative"``) — the Euclidean distance to the set when the nearest point lies
        inside a facet, a lower bound otherwise.
    roughness : ndarray (...)
        ``∫ (dρ/dλ)² dλ`` of the piecewise-linear ρ, nm⁻¹.
    multipliers : ndarray (..., 3)
        Lagrange multipliers ``μ`` of ``ρ @ W = XYZ100`` (NaN where not defined).
    certificate : Certificate
    method : ndarray of str (...)
        How each colour was solved: ``"unconstrained"`` (closed form), ``"active set"``
        (batched primal-dual active set), ``"active set restarted from interior point"``,
        ``"dense primal active set"`` (the one-at-a-time fallback), ``"boundary face"``
        (a colour on the boundary, solved on its face), ``"black or white"`` or
        ``"infeasible"``.
    bounds : str or None
    observer, illuminant : str
    """

    spectrum: Spectrum
    XYZ100: np.ndarray
    feasible: np.ndarray
    distance_outside: np.ndarray
    roughness: np.ndarray
    multipliers: np.ndarray
    certificate: Certificate
    method: np.ndarray
    bounds: str | None
    observer: str
    illuminant: str


class Setup:
    """Weights, programme and solid facets for one (grid, observer, illuminant)."""

    def __init__(self, grid: np.ndarray, W: np.ndarray):
        self.grid = grid
        self.W = W
        self.step_nm = float(grid[1] - grid[0])
        self.problem = _qp.make_problem(W, self.step_nm)
        self.white = W.sum(axis=0)

    @cached_property
    def solid(self) -> _zonotope.Facets:
        return _zonotope.solid_facets(self.W)

    @cached_property
    def cone(self) -> _zonotope.Facets:
        return _zonotope.cone_facets(self.W)


@lru_cache(maxsize=32)
def _named_setup(grid_key: tuple[float, float, float], observer: str, illuminant: str) -> Setup:
    grid = wavelength_grid(*grid_key)
    return Setup(grid, weights(grid, observer, illuminant))


def _grid_key(wavelengths) -> tuple[float, float, float]:
    if isinstance(wavelengths, tuple | list) and len(wavelengths) == 3:
        if all(isinstance(v, Real) for v in wavelengths):
            wavelength_grid(*wavelengths)  # validates
            return tuple(float(v) for v in wavelengths)
    grid = np.asarray(wavelengths, dtype=float)
    if grid.ndim == 1 and grid.size >= 3:
        steps = np.diff(grid)
        if np.all(steps > 0) and np.allclose(steps, steps[0], rtol=1e-9, atol=0):
            return (float(grid[0]), float(grid[-1]), float(steps[0]))
    raise SpectrumError(
        "wavelengths: expected (start_nm, stop_nm, step_nm) or a uniform increasing grid of at "
        f"least 3 samples, got {wavelengths!r}"
    )


def setup_for(wavelengths, observer, illuminant) -> tuple[Setup, str, str]:
    """The cached :class:`Setup` and the observer/illuminant labels."""
    key = _grid_key(wavelengths)
    if isinstance(observer, str) and isinstance(illuminant, str):
        obs, ill = canonical_observer_name(observer), canonical_illuminant_name(illuminant)
        return _named_setup(key, obs, ill), obs, ill
    if not isinstance(illuminant, str | Spectrum):
        raise ColorimetryError(
            f"illuminant: expected a CIE name such as 'D65' or a Spectrum, got {illuminant!r}"
        )
    grid = wavelength_grid(*key)
    label_obs = observer if isinstance(observer, str) else "custom observer"
    label_ill = illuminant if isinstance(illuminant, str) else "custom illuminant"
    return Setup(grid, weights(grid, observer, illuminant)), label_obs, label_ill


def _colours(XYZ) -> np.ndarray:
    try:
        b = np.asarray(XYZ, dtype=float)
    except (TypeError, ValueError):
        raise ColorimetryError(f"XYZ: expected numbers of shape (..., 3), got {XYZ!r}") from None
    if b.ndim == 0 or b.shape[-1] != 3:
        raise ColorimetryError(f"XYZ: expected shape (..., 3) (X, Y, Z on the Y=100 scale), got {b.shape}")
    if not np.all(np.isfinite(b)):
        raise ColorimetryError("XYZ: contains NaN or infinite values; pass finite tristimulus values")
    return b


def _boundary_solutions(setup: Setup, b: np.ndarray, lower: float, upper: float,
                        facet_tolerance: float = _face.FACET_TOLERANCE):
    """Exact solutions for colours on the boundary of the solid or cone (one at a time: such
    colours are rare, and each is a small dense problem on a face; see :mod:`._face`)."""
    Q = setup.problem.hessian_dense()
    out = [_face.face_solution(setup.W, Q, bi, lower, upper, facet_tolerance) for bi in b]
    return (np.array([o[0] for o in out]), np.array([o[1] for o in out]),
            np.array([o[2] for o in out]), np.array([o[3] for o in out], dtype=bool))


def smoothest_reflectance(
    XYZ,
    illuminant="D65",
    observer="1931",
    wavelengths=DEFAULT_WAVELENGTHS,
    bounds: str | None = "unit",
) -> SmoothestResult:
    """The smoothest reflectance(s) with the given tristimulus values (van Trigt 1990).

    Parameters
    ----------
    XYZ : array_like (..., 3)
        Tristimulus values on the scale where the perfect white under ``illuminant`` has
        ``Y = 100``.
    illuminant : str or Spectrum
        CIE illuminant name (default ``"D65"``) or a Spectrum sampled on the grid.
    observer : str or Spectrum
        Observer name or alias (default ``"1931"``).
    wavelengths : (start_nm, stop_nm, step_nm) or uniform array
        The grid of the recovered reflectance (default 380–780 nm in 5 nm steps).
    bounds : {"unit", "nonnegative", None}
        ``"unit"`` (default, object colours): ``0 ≤ ρ ≤ 1``; ``"nonnegative"``: ``ρ ≥ 0``;
        ``None``: unconstrained (closed form, linear in XYZ).

    Returns
    -------
    SmoothestResult
        ``.spectrum`` (..., K) plus feasibility, distance outside, roughness, multipliers and a
        certificate for every colour.

    Raises
    ------
    ColorimetryError
        For a single colour (``XYZ`` of shape (3,)) that no reflectance within the bounds can
        produce; a batch instead flags such colours and returns NaN spectra for them.

    References
    ----------
    C. van Trigt, J. Opt. Soc. Am. A 7, 1891–1904 (1990).

    Examples
    --------
    A grey (20 % of the white on the same grid) is recovered as a constant reflectance:

    >>> from spectrocolor import wavelength_grid, weights
    >>> grey = 0.2 * weights(wavelength_grid(400, 700, 10), "1931", "D65").sum(axis=0)
    >>> r = smoothest_reflectance(grey, wavelengths=(400, 700, 10))
    >>> bool(abs(r.spectrum.values - 0.2).max() < 1e-12)
    True
    """
    if bounds not in BOUNDS:
        raise ColorimetryError(f"bounds: expected one of {BOUNDS}, got {bounds!r}")
    b_in = _colours(XYZ)
    setup, obs, ill = setup_for(wavelengths, observer, illuminant)
    prob = setup.problem
    shape = b_in.shape[:-1]
    b = b_in.reshape(-1, 3)
    N, K = b.shape[0], prob.size
    rho = b @ prob.unconstrained
    mu = b @ prob.multipliers
    lam = np.zeros((N, K))
    converged = np.ones(N, dtype=bool)
    feasible = np.ones(N, dtype=bool)
    distance = np.zeros(N)
    method = np.full(N, "unconstrained", dtype=object)
    lower, upper = (None, None) if bounds is None else (0.0, 1.0 if bounds == "unit" else np.inf)
    if bounds is not None:
        cone = bounds == "nonnegative"
        facets = setup.cone if cone else setup.solid
        black = np.all(b == 0, axis=1)
        white = np.zeros(N, dtype=bool) if cone else np.all(b == setup.white, axis=1)
        # the unconstrained solution within the bounds certifies feasibility by itself
        check = np.flatnonzero(~np.all((rho >= lower) & (rho <= upper), axis=1) & ~black & ~white)
        depth = np.ones(N)
        ratio, excess, _ = _zonotope.gauge(facets, b[check], cone)
        depth[check] = -ratio if cone else 1.0 - ratio
        distance[check] = np.maximum(excess, 0.0)
        on_boundary = np.abs(depth) <= BOUNDARY_TOLERANCE
        feasible = depth >= -BOUNDARY_TOLERANCE
        distance[feasible] = 0.0
        todo = check[feasible[check] & ~on_boundary[check]]
        if todo.size:
            sol = _qp.solve_bounded(prob, b[todo], lower, upper)
            rho[todo], mu[todo], lam[todo] = sol.rho, sol.mu, sol.lam
            converged[todo] = sol.converged
            method[todo] = np.asarray(_qp.METHODS, dtype=object)[sol.method]
            # a colour that close to the boundary that the active-set methods could not
            # settle is tried on its face; the certificate decides whether that is exact
            near = todo[~sol.converged & (depth[todo] <= NEAR_BOUNDARY)]
            if near.size:
                got = _boundary_solutions(setup, b[near], lower, upper, NEAR_BOUNDARY)
                passed = _certify(prob, b[near], *got[:3], lower, upper, got[3])[-1]
                take = near[passed]
                rho[take], mu[take], lam[take] = (g[passed] for g in got[:3])
                converged[take] = True
                method[take] = "boundary face"
        if on_boundary.any():
            idx = np.flatnonzero(on_boundary)
            rho[idx], mu[idx], lam[idx], converged[idx] = _boundary_solutions(
                setup, b[idx], lower, upper)
            method[idx] = "boundary face"
        # black and white have one reflectance each; zero multipliers certify them
        rho[black], mu[black], lam[black] = 0.0, 0.0, 0.0
        rho[white], mu[white], lam[white] = 1.0, 0.0, 0.0
        method[black | white] = "black or white"
        rho[~feasible], mu[~feasible], lam[~feasible] = np.nan, np.nan, np.nan
        converged[~feasible] = False
        method[~feasible] = "infeasible"
        if not shape and not feasible[0]:
            what = "object-colour solid" if bounds == "unit" else "cone of non-negative spectra"
            white_text = ", ".join(f"{v:.8g}" for v in setup.white)
            raise ColorimetryError(
                f"XYZ: {b_in.tolist()} is outside the {what} for illuminant {ill}, observer "
                f"{obs} on {setup.grid[0]:g}–{setup.grid[-1]:g} nm at {setup.step_nm:g} nm "
                f"(distance ≥ {distance[0]:.4g} XYZ100); no reflectance with bounds={bounds!r} "
                f"produces it. XYZ must be on this grid's scale: here the perfect white is "
                f"XYZ = ({white_text}), which can differ slightly from tabulated white points"
            )
    certificate = _certify(prob, b, rho, mu, lam, lower, upper, converged)
    result_rho = rho.reshape(*shape, K)
    return SmoothestResult(
        spectrum=Spectrum(setup.grid, result_rho),
        XYZ100=b_in,
        feasible=feasible.reshape(shape),
        distance_outside=distance.reshape(shape),
        roughness=prob.objective(rho).reshape(shape),
        multipliers=mu.reshape(*shape, 3),
        certificate=Certificate(*(np.asarray(c).reshape(shape) for c in certificate)),
        method=method.astype(str).reshape(shape),
        bounds=bounds,
        observer=obs,
        illuminant=ill,
    )


def _certify(prob, b, rho, mu, lam, lower, upper, converged):
    """The certificate's measures, and ``converged`` narrowed to results that pass them."""
    with np.errstate(invalid="ignore"):
        primal = np.abs(rho @ prob.W - b).max(axis=1)
        if lower is None:
            violation = np.zeros(len(b))
            sign = np.zeros(len(b))
            comp = np.zeros(len(b))
        else:
            violation = np.maximum(lower - rho, rho - upper).max(axis=1).clip(min=0.0)
            at_lower = rho == lower
            at_upper = rho == upper
            # wrong sign: negative at a lower bound, positive at an upper one, non-zero off them
            sign = np.where(at_lower, -lam, np.where(at_upper, lam, np.abs(lam))).max(axis=1)
            gap = np.minimum(np.abs(rho - lower), np.abs(upper - rho))
            comp = (np.abs(lam) * gap).max(axis=1)
        grad = prob.hess_times(rho)
        pull = mu @ prob.W.T
        station = np.abs(grad - pull - (0.0 if lower is None else lam)).max(axis=1)
        primal_tol = PRIMAL_TOLERANCE * (np.abs(rho) @ np.abs(prob.W)).max(axis=1)
        dual_tol = DUAL_TOLERANCE * (1.0 + np.abs(grad).max(axis=1) + np.abs(pull).max(axis=1))
        finite = (np.all(np.isfinite(rho), axis=1) & np.all(np.isfinite(mu), axis=1)
                  & np.all(np.isfinite(lam), axis=1))
        passed = (finite & (primal <= primal_tol) & (violation == 0.0) & (sign <= dual_tol)
                  & (comp <= dual_tol) & (station <= dual_tol))
    return primal, violation, sign, comp, station, converged & passed
