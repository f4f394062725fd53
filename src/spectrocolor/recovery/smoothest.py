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

The unconstrained solution is linear in ``XYZ100`` (one K × 3 matrix, precomputed, then one
step of iterative refinement). The bounded problems are strictly convex quadratic programmes,
solved exactly by a primal-dual active-set (semismooth Newton) method that adds and releases
bounds; every result carries a certificate at rounding level
(:mod:`spectrocolor.recovery.certificate`): bounds held exactly, the colour reproduced and the
KKT conditions met to within small multiples of the rounding error of the terms summed.

References
----------
C. van Trigt, "Smoothest reflectance functions. I. Definition and main results",
J. Opt. Soc. Am. A 7, 1891–1904 (1990).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .. import notebook_hooks
from ..errors import ColorimetryError
from ..illuminants import DEFAULT_ILLUMINANT
from ..observers import DEFAULT_OBSERVER
from ..spectrum import Spectrum
from . import exact, face, qp, zonotope
from .certificate import Certificate, certify
from .inputs import DEFAULT_WAVELENGTHS, Setup, setup_for, xyz_array

__all__ = ["BOUNDS", "DEFAULT_WAVELENGTHS", "Certificate", "SmoothestResult", "setup_for",
           "smoothest_reflectance"]

BOUNDS = ("unit", "nonnegative", None)
#: Fixed-width strings for :attr:`SmoothestResult.method` (the longest name has 40 characters).
_METHOD_DTYPE = "<U48"
#: Colours whose gauge is within this of the boundary are solved as boundary colours.
BOUNDARY_TOLERANCE = 1e-12
#: Colours this close to the boundary on which the active-set methods fail are tried on a face.
NEAR_BOUNDARY = 1e-9
#: Facets tried, in order of slack, for a boundary colour whose first face solution fails.
FACET_CHOICES = 4
#: :attr:`SmoothestResult.method` of colours solved on their face in floating point, and of
#: those that only the exact rational solver (:mod:`.exact`) settled.
FACE_METHOD = "boundary face"
EXACT_METHOD = "boundary face, exact rational arithmetic"


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
        (a colour on or within 1e-9 of the boundary, solved on its face),
        ``"boundary face, exact rational arithmetic"`` (such a colour that only the exact
        solver of ``spectrocolor.recovery.exact`` settled), ``"black or white"`` or
        ``"infeasible"``.
    bounds : str or None
    observer, illuminant : str
        The conditions used.

    Examples
    --------
    >>> result = smoothest_reflectance([40.0, 40.0, 40.0], wavelengths=(400, 700, 10))
    >>> bool(result.feasible), str(result.method), result.bounds, result.spectrum.values.shape
    (True, 'unconstrained', 'unit', (31,))
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

    _repr_html_, _repr_svg_, __repr__ = notebook_hooks.html, notebook_hooks.svg, notebook_hooks.text  # notebooks


def _boundary_solutions(setup: Setup, b: np.ndarray, lower: float, upper: float,
                        facet_tolerance: float = face.FACET_TOLERANCE):
    """Exact solutions for colours on the boundary of the solid or cone (one at a time: such
    colours are rare, and each is a small dense problem on a face; see :mod:`.face`).

    Returns rho, mu, lam, whether each settled, and how each was solved (``FACE_METHOD`` or
    ``EXACT_METHOD``)."""
    Q = setup.problem.hessian_dense()
    facets = setup.cone if not np.isfinite(upper) else setup.solid
    out = [_face_or_flag(setup.W, Q, bi, lower, upper, facet_tolerance, facets) for bi in b]
    return (np.array([o[0] for o in out]), np.array([o[1] for o in out]),
            np.array([o[2] for o in out]), np.array([o[3] for o in out], dtype=bool),
            np.array([o[4] for o in out], dtype=_METHOD_DTYPE))


def _face_or_flag(W, Q, b, lower, upper, facet_tolerance, facets=None):
    """One colour's face solution (first on the setup's precomputed ``facets``, which saves
    the K³ products of forming the first level's candidates: seconds at 1 nm; then on the
    candidates formed from the weights); failing that, the dense primal active-set method from an
    exact feasible start (a colour within rounding of the boundary whose face the facet test
    could not pin down); failing that, a component far below the others' rounding (``Z = 1e-104``
    beside ``X = 2``) solved at its own scale (:func:`.face.lift_component`); failing that too,
    the solution in exact rational arithmetic (:mod:`.exact`, slow but certain). A numerical
    breakdown on one degenerate colour is that colour's failure (flagged, NaN), never the
    batch's. Returns rho, mu, lam, settled, method.
    """
    step_nm = 2.0 / Q[0, 0]

    def certified(got, colour=b):
        return got[3] and certify(W, step_nm, colour[None], got[0][None], got[1][None], lower,
                                  upper, [True]).converged[0]

    # a component far below the others' rounding is solved at its own scale first (cheap: its
    # face is known), then the setup's facets, then facets formed from the weights (K³ products)
    for rho, mu in face.lifted_candidates(W, Q, b, lower, upper):
        got = rho, mu, Q @ rho - W @ mu, True
        if certified(got):
            return (*got, FACE_METHOD)
    got, best = _float_face(W, Q, b, lower, upper, facet_tolerance, facets, certified)
    if got is not None:
        return (*got, FACE_METHOD)
    # every floating-point route missed rounding level (nearly parallel generators): exactly
    exact_got = exact.exact_solution(W, step_nm, b, lower, upper)
    if exact_got is None:
        return (*best, FACE_METHOD)
    rho, mu = exact_got
    return rho, mu, Q @ rho - W @ mu, True, EXACT_METHOD


def _float_face(W, Q, b, lower, upper, facet_tolerance, facets, certified):
    """The floating-point routes of :func:`_face_or_flag`: ``(solution, best)`` with the first
    solution ``certified`` accepts (rho, mu, lam, True), or None and the best uncertified."""
    K, m = W.shape
    failed = np.full(K, np.nan), np.full(m, np.nan), np.full(K, np.nan), False
    best = failed
    try:
        if facets is not None:
            for choice in range(FACET_CHOICES):
                got = face.face_solution(W, Q, b, lower, upper, facet_tolerance, choice, facets)
                if certified(got):
                    return got, got
        best = face.face_solution(W, Q, b, lower, upper, facet_tolerance)
        if certified(best):
            return best, best
        # a colour on an edge lies on several facets, and rounding can rank first one that
        # does not quite hold it: the next ones are tried (the certificate judges each)
        for choice in range(1, FACET_CHOICES):
            other = face.face_solution(W, Q, b, lower, upper, facet_tolerance, choice)
            if certified(other):
                return other, other
        start = qp._vertex_start(W, b, lower, upper)
        if start is not None:
            rho, mu, lam, _, ok = qp.primal_active_set(Q, W, b, lower, upper, *start)
            if ok:
                rho, mu = qp.polish(W, Q, b, rho, mu, lower, upper)
                best = rho, mu, lam, True
                if certified(best):
                    return best, best
    except (np.linalg.LinAlgError, ValueError, FloatingPointError):
        best = failed
    return None, best


def smoothest_reflectance(
    XYZ,
    *,
    illuminant=DEFAULT_ILLUMINANT,
    observer=DEFAULT_OBSERVER,
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
        The light the colour is seen under (default ``"D65"``); see :term:`illuminant`.
    observer : str or Spectrum
        The observer of the colour (default ``"1931"``); see :term:`observer`.
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
    >>> grey = 0.2 * weights(wavelength_grid(400, 700, 10), observer="1931", illuminant="D65").sum(axis=0)
    >>> r = smoothest_reflectance(grey, wavelengths=(400, 700, 10))
    >>> bool(abs(r.spectrum.values - 0.2).max() < 1e-12)
    True
    """
    if bounds not in BOUNDS:
        raise ColorimetryError(f"bounds: expected one of {BOUNDS}, got {bounds!r}")
    b_in = xyz_array(XYZ)
    setup, obs, ill = setup_for(wavelengths, observer, illuminant)
    prob = setup.problem
    shape = b_in.shape[:-1]
    b = b_in.reshape(-1, 3)
    K = prob.size
    if bounds is None:
        rho, mu, certificate, roughness = qp.solve_unconstrained_certified(prob, b)
        feasible = np.ones(len(b), dtype=bool)
        distance = np.zeros(len(b))
        # one name for all: its own width, copied (np.full would convert it once per colour)
        method = np.repeat(np.array(["unconstrained"]), len(b))
    elif bounds == "nonnegative":
        rho, mu, feasible, distance, method, certificate = _solve_scaled(setup, b)
    else:
        rho, mu, feasible, distance, method, certificate = _solve_unit(setup, b)
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
    if bounds is not None:
        with np.errstate(over="ignore"):
            roughness = prob.objective(rho)
    return SmoothestResult(
        spectrum=Spectrum(setup.grid, rho.reshape(*shape, K)),
        XYZ100=b_in,
        feasible=feasible.reshape(shape),
        distance_outside=distance.reshape(shape),
        roughness=roughness.reshape(shape),
        multipliers=mu.reshape(*shape, 3),
        certificate=certificate.reshape(shape),
        method=method.reshape(shape),
        bounds=bounds,
        observer=obs,
        illuminant=ill,
    )


def _binary_exponents(b: np.ndarray, reference: float) -> np.ndarray:
    """Per colour, the power of two that brings ``max |b|`` to the scale of ``reference``
    (0 for black)."""
    top = np.abs(b).max(axis=1)
    return np.where(top > 0, np.frexp(top)[1] - np.frexp(reference)[1], 0)


def _solve_scaled(setup: Setup, b: np.ndarray):
    """``bounds="nonnegative"``, solved at the scale of the white and scaled back exactly.

    The programme with ``ρ ≥ 0`` is homogeneous: ``ρ`` solves it for ``b`` with multipliers
    ``μ`` iff ``2^e ρ`` does for ``2^e b`` with ``2^e μ``, and every rounding error scales by
    the same power of two. So each colour is solved and certified at the scale of the white,
    where membership, the solver's tolerances and the certificate are all well within the
    floating-point range (a colour of ``Y = 1e-256`` would otherwise underflow ``|b|²`` and
    a colour of ``Y = 1e300`` overflow it), and scaled back. A result that does not survive
    the scaling exactly (it would be subnormal or overflow) is reported not converged.

    Returns rho, mu, feasible, distance, method and the certificate (measures scaled back).
    """
    prob = setup.problem
    e = _binary_exponents(b, float(np.abs(setup.white).max()))
    scaled = np.ldexp(b, -e[:, None])
    rho, mu, feasible, distance, method, converged = _solve_bounded(setup, scaled, 0.0, np.inf)
    cert = certify(prob.W, prob.step_nm, scaled, rho, mu, 0.0, np.inf, converged)
    with np.errstate(over="ignore"):
        rho_out, mu_out = np.ldexp(rho, e[:, None]), np.ldexp(mu, e[:, None])
        exact = (np.all(np.ldexp(rho_out, -e[:, None]) == rho, axis=1)
                 & np.all(np.ldexp(mu_out, -e[:, None]) == mu, axis=1))
        certificate = Certificate(
            np.ldexp(cert.primal_residual, e), cert.bound_violation,
            np.ldexp(cert.multiplier_sign_violation, e), np.ldexp(cert.stationarity, e),
            cert.rounding_ratio, cert.converged & exact)
        # an outside colour keeps a positive distance even where it underflows
        distance = np.where(feasible, 0.0, np.maximum(np.ldexp(distance, e), np.nextafter(0.0, 1.0)))
    return rho_out, mu_out, feasible, distance, method, certificate


#: Colours within this fraction of the white (per component) of black or of the white are
#: first solved as cone colours at their own scale (:func:`_solve_unit`).
NEAR_VERTEX = 2.0 ** -10


def _solve_unit(setup: Setup, b: np.ndarray):
    """``bounds="unit"``: near black and near the white by the cone at that vertex, else directly.

    Near black the object-colour solid is the cone of non-negative spectra: a colour at
    ``Y = 1e-256`` is inside the solid iff it is inside the cone, a question the solid's
    facets (offsets of the size of the white) cannot resolve below about ``1e-16`` of the
    white, but the cone's (through black) can at any scale. Such colours are solved with
    ``ρ ≥ 0`` at their own scale (:func:`_solve_scaled`); where that solution stays ``≤ 1`` it
    is the solution with ``0 ≤ ρ ≤ 1`` too (same KKT conditions, upper bound inactive). Near the
    white, ``white − b`` is exact and the same holds for ``1 − ρ`` by the symmetry ``ρ → 1 − ρ``
    of the programme; there b itself is known only to ε of the white, so a colour outside by
    less than ``BOUNDARY_TOLERANCE`` of the white is on the boundary, as elsewhere on the solid.
    Other colours, and vertex colours whose solution reaches the other bound or fails, are
    solved directly.
    """
    prob = setup.problem
    N, K = len(b), prob.size
    rho, mu = np.full((N, K), np.nan), np.full((N, 3), np.nan)
    feasible, converged = np.zeros(N, dtype=bool), np.zeros(N, dtype=bool)
    distance, method = np.zeros(N), np.full(N, "infeasible", dtype=_METHOD_DTYPE)
    done = np.zeros(N, dtype=bool)
    for flip in (False, True):
        d = setup.white - b if flip else b
        near = np.flatnonzero(~done & np.any(d != 0, axis=1)
                              & np.all(np.abs(d) <= NEAR_VERTEX * setup.white, axis=1))
        if near.size == 0:
            continue
        r, m, f, dist, meth, cert = _solve_scaled(setup, d[near])
        # the solution with ρ ≥ 0 is the unit one where it stays ≤ 1 (converged or not: at
        # this scale the solid's facets cannot do better); a failed cone solve (NaN) goes on
        # near the white, ``white − b`` carries the rounding of b (absolute, ε of the white):
        # a colour outside by less than the solid's own tolerance is left to the solid's test
        # (on its boundary, as everywhere else on the solid)
        slack = BOUNDARY_TOLERANCE * np.abs(setup.white).max() if flip else 0.0
        with np.errstate(invalid="ignore"):
            take = (~f & (dist > slack)) | np.all(r <= 1.0, axis=1)
        idx = near[take]
        rho[idx] = 1.0 - r[take] if flip else r[take]
        mu[idx] = -m[take] if flip else m[take]
        feasible[idx], distance[idx], method[idx] = f[take], dist[take], meth[take]
        # settled; the certificate below, on the values returned, is the verdict
        converged[idx] = f[take] & np.all(np.isfinite(r[take]), axis=1)
        done[idx] = True
    # a feasible vertex colour whose cone answer fails the certificate is solved on the solid
    # too (near the white, ``white − b`` rounds a zero component to ±ε of the white, which
    # can put it outside the cone), and the solid's answer replaces the cone's where certified
    retry = np.zeros(N, dtype=bool)
    vertex = np.flatnonzero(done & feasible)
    if vertex.size:
        retry[vertex] = ~certify(prob.W, prob.step_nm, b[vertex], rho[vertex], mu[vertex], 0.0, 1.0,
                                 converged[vertex]).converged
    rest = np.flatnonzero(~done | retry)
    if rest.size:
        got = _solve_bounded(setup, b[rest], 0.0, 1.0)
        better = ~retry[rest]
        again = np.flatnonzero(retry[rest])  # only the retried colours need a verdict here
        if again.size:
            better[again] = certify(prob.W, prob.step_nm, b[rest[again]], got[0][again],
                                    got[1][again], 0.0, 1.0, got[5][again]).converged
        for out, value in zip((rho, mu, feasible, distance, method, converged), got, strict=True):
            out[rest[better]] = value[better]
    certificate = certify(prob.W, prob.step_nm, b, rho, mu, 0.0, 1.0, converged)
    rho, certificate = _snapped(prob, b, rho, mu, 0.0, 1.0, converged, certificate)
    return rho, mu, feasible, distance, method, certificate


#: Samples within ``SNAP_ULPS · K · ε`` of a bound are tried at the bound (:func:`_snapped`).
SNAP_ULPS = 8


def _snapped(prob, b, rho, mu, lower, upper, converged, certificate):
    """``rho`` with each sample within rounding (``SNAP_ULPS · K · ε``) of a bound set to that
    bound, in the colours whose certificate still holds after it, and the certificate.

    A dense solve of a colour's few free samples leaves a sample that belongs at its bound free
    at the bound ± a few ulps (the spike of a vertex at ``1 − 3e-14``); at the bound it is the
    same solution to rounding, and the certificate, measured again on the snapped values, is
    the verdict: a colour whose snapped values fail it keeps its own.
    """
    K = rho.shape[-1]
    reach = SNAP_ULPS * K * np.finfo(float).eps * max(abs(lower), abs(upper), 1.0)
    with np.errstate(invalid="ignore"):
        near_lower = (rho != lower) & (np.abs(rho - lower) <= reach)
        near_upper = (rho != upper) & (np.abs(rho - upper) <= reach)
    rows = np.flatnonzero(certificate.converged & np.any(near_lower | near_upper, axis=1))
    if rows.size == 0:
        return rho, certificate
    trial = np.where(near_lower[rows], lower, np.where(near_upper[rows], upper, rho[rows]))
    again = certify(prob.W, prob.step_nm, b[rows], trial, mu[rows], lower, upper, converged[rows])
    keep = rows[again.converged]
    rho = rho.copy()
    rho[keep] = trial[again.converged]
    fields = {}
    for name in ("primal_residual", "bound_violation", "multiplier_sign_violation", "stationarity",
                 "rounding_ratio", "converged"):
        values = np.array(getattr(certificate, name), copy=True)
        values[keep] = np.asarray(getattr(again, name))[again.converged]
        fields[name] = values
    return rho, Certificate(**fields)


def _solve_bounded(setup: Setup, b: np.ndarray, lower: float, upper: float):
    """Every colour ``b`` (N, 3) with ``lower ≤ ρ ≤ upper`` (``upper`` 1 or ∞): membership, then
    the batched solver, boundary faces, black and white.

    Returns rho, mu, feasible, distance, method and whether each colour settled (not yet
    certified; NaN for infeasible colours).
    """
    prob = setup.problem
    N = len(b)
    rho, mu = qp.solve_unconstrained(prob, b, within=(lower, upper))
    converged = np.ones(N, dtype=bool)
    distance = np.zeros(N)
    method = np.full(N, "unconstrained", dtype=_METHOD_DTYPE)
    cone = not np.isfinite(upper)
    facets = setup.cone if cone else setup.solid
    black = np.all(b == 0, axis=1)
    white = np.zeros(N, dtype=bool) if cone else np.all(b == setup.white, axis=1)
    # the unconstrained solution within the bounds certifies feasibility by itself
    check = np.flatnonzero(~np.all((rho >= lower) & (rho <= upper), axis=1) & ~black & ~white)
    depth = np.ones(N)
    ratio, excess, _ = zonotope.gauge(facets, b[check], cone)
    depth[check] = -ratio if cone else 1.0 - ratio
    distance[check] = np.maximum(excess, 0.0)
    on_boundary = np.abs(depth) <= BOUNDARY_TOLERANCE
    feasible = depth >= -BOUNDARY_TOLERANCE
    distance[feasible] = 0.0
    todo = check[feasible[check] & ~on_boundary[check]]
    if todo.size:
        sol = qp.solve_bounded(prob, b[todo], lower, upper)
        rho[todo], mu[todo] = sol.rho, sol.mu
        converged[todo] = sol.converged
        method[todo] = np.asarray(qp.METHODS, dtype=_METHOD_DTYPE)[sol.method]
        # a colour that close to the boundary whose active-set result is not certified
        # (unsettled, or off rounding level: the free weights are nearly dependent there) is
        # tried on its face; the certificate decides whether that is exact
        near = todo[depth[todo] <= NEAR_BOUNDARY]
        if near.size:
            near = near[~certify(prob.W, prob.step_nm, b[near], rho[near], mu[near], lower,
                                 upper, converged[near]).converged]
        if near.size:
            got = _boundary_solutions(setup, b[near], lower, upper, NEAR_BOUNDARY)
            passed = certify(prob.W, prob.step_nm, b[near], got[0], got[1], lower, upper,
                             got[3]).converged
            take = near[passed]
            rho[take], mu[take] = got[0][passed], got[1][passed]
            converged[take] = True
            method[take] = got[4][passed]
    if on_boundary.any():
        idx = np.flatnonzero(on_boundary)
        rho[idx], mu[idx], _, converged[idx], method[idx] = _boundary_solutions(
            setup, b[idx], lower, upper)
    # black and white have one reflectance each; zero multipliers certify them
    rho[black], mu[black] = 0.0, 0.0
    rho[white], mu[white] = 1.0, 0.0
    method[black | white] = "black or white"
    rho[~feasible], mu[~feasible] = np.nan, np.nan
    converged[~feasible] = False
    method[~feasible] = "infeasible"
    return rho, mu, feasible, distance, method, converged
