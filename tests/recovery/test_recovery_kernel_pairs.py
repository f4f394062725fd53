"""Each compiled kernel of the recovery solvers against its NumPy twin, to a bound derived from rounding.

Every solver kernel exists twice: a numba kernel (:mod:`spectrocolor.recovery.numba_kernels`,
extra ``fast``) and the NumPy path, which must stay because numba is optional. Both stay because
the kernels pay for themselves; measured on the 2-core development machine (load 2-9, so take the
figures as rough), warm, best of 5, 1931 observer, D65, 380-780 nm at 5 nm (K = 81):

======================================  ================  =========  ==========
kernel (the call timed)                  colours           numba      NumPy
======================================  ================  =========  ==========
``closed_form`` (solve_unconstrained_    20 000            24 ms      679 ms
certified)
``pdas`` (solve_bounded, [0, 1])         2 000 sRGB cube    10.7 ms    61 ms
``pdas`` (the same, one channel at 0)    2 000              30 ms      271 ms
``measures`` (certify, bounded)          2 000              1.1 ms     13.8 ms
``facet_maxima`` (zonotope.gauge)        20 000             244 ms     1 875 ms
``roughness`` (Problem.objective)        20 000 rows        1.1 ms     17.7 ms
======================================  ================  =========  ==========

5.7 to 28 times faster: no kernel is deleted. The two paths sum in different orders (BLAS
blocking and FMA on one side, ``fastmath={"reassoc"}`` on the other), so they are held to each
other by bounds on that rounding, derived per test below, never bit for bit. ``γ_n`` is
:func:`spectrocolor.recovery.tolerances.gamma`, ``n ε / (1 − n ε)`` with ``ε = 2⁻⁵²``: twice
Higham's bound with the unit roundoff ``u = 2⁻⁵³`` (Higham 2002, §3.1), a margin the bounds
below do not otherwise count on.
"""

from __future__ import annotations

import numpy as np
import pytest

from spectrocolor.recovery import certificate, compiled, qp, zonotope
from spectrocolor.recovery.inputs import setup_for
from spectrocolor.recovery.tolerances import gamma

pytestmark = pytest.mark.skipif(compiled._compiled() is None, reason="numba is not installed")

EPS = np.finfo(float).eps
GRID = (400.0, 700.0, 10.0)


def _setup():
    return setup_for(GRID, "1931", "D65")[0]


def _colours(setup, count=300, seed=7):
    """Smooth reflectances, half inside (0.05, 0.95), half stretched to lie at 0 and 1 over stretches."""
    K = setup.W.shape[0]
    rng = np.random.default_rng(seed)
    smooth = np.cumsum(rng.normal(size=(count, K)), axis=1)
    smooth = (smooth - smooth.min(axis=1, keepdims=True)) / np.ptp(smooth, axis=1, keepdims=True)
    inside = 0.05 + 0.9 * smooth[: count // 2]
    touching = np.clip(2.0 * smooth[count // 2:] - 0.5, 0.0, 1.0)
    return np.concatenate([inside, touching]) @ setup.W


def _both(monkeypatch, call):
    """``call()`` compiled, then on the NumPy path."""
    monkeypatch.setenv("SPECTROCOLOR_NUMBA", "1")
    fast = call()
    monkeypatch.setenv("SPECTROCOLOR_NUMBA", "0")
    return fast, call()


def _kkt_bound(W, step_nm, b, free, solutions):
    """Bound on ``|[ρ₁ − ρ₂; μ₁ − μ₂]|`` on the free samples for two certified solutions.

    Both solve the KKT system ``[[Q, −W], [Wᵀ, 0]] [ρ; μ] = [λ; b]`` of the free samples (the
    rest hold the same bound values): their difference is ``K_F⁻¹ (r₁ − r₂)`` with residuals
    ``r = [(Q ρ − W μ)_F; Wᵀρ − b]``, which the certificate holds below its tolerances ``t``
    (:func:`.certificate.dual_tolerance`, :func:`.certificate.primal_tolerance`), so
    ``|Δ| ≤ |K_F⁻¹| (t₁ + t₂)``. The certificate measures each residual in floating point; the
    true one exceeds the measured one by at most the evaluation's own rounding, about
    ``γ_{m+4} / (DUAL_FACTOR ε) ≈ 0.2`` of the dual tolerance and half the primal one (the
    other half of PRIMAL_FACTOR), and ``K_F⁻¹`` is computed to ``cond(K_F) ε < 1e-7`` relative
    (checked): a factor 2 covers both.
    """
    Q = qp.make_problem(W, step_nm).hessian_dense()
    F = np.flatnonzero(free)
    m = W.shape[1]
    kkt = np.zeros((F.size + m, F.size + m))
    kkt[: F.size, : F.size] = Q[np.ix_(F, F)]
    kkt[: F.size, F.size:] = -W[F]
    kkt[F.size:, : F.size] = W[F].T
    assert np.linalg.cond(kkt) * EPS < 1e-7
    tol = np.zeros(F.size + m)
    for rho, mu in solutions:
        tol += np.concatenate([certificate.dual_tolerance(W, step_nm, rho[None], mu[None])[0, F],
                               certificate.primal_tolerance(W, b[None], rho[None])[0]])
    return 2.0 * np.abs(np.linalg.inv(kkt)) @ tol, F


def _certified(W, step_nm, b, rho, mu, lower, upper, monkeypatch):
    """The NumPy certificate's verdict (independent of the path that solved)."""
    monkeypatch.setenv("SPECTROCOLOR_NUMBA", "0")
    return certificate.certify(W, step_nm, b, rho, mu, lower, upper,
                               np.ones(len(b), dtype=bool)).converged


def test_closed_form_kernel_against_the_numpy_closed_form(monkeypatch):
    setup = _setup()
    prob, b = setup.problem, _colours(setup)
    fast, plain = _both(monkeypatch, lambda: qp.solve_unconstrained_certified(prob, b))
    ok = (_certified(prob.W, prob.step_nm, b, fast[0], fast[1], None, None, monkeypatch)
          & _certified(prob.W, prob.step_nm, b, plain[0], plain[1], None, None, monkeypatch))
    assert ok.all()
    for i in range(len(b)):  # unconstrained: every sample is free
        bound, F = _kkt_bound(prob.W, prob.step_nm, b[i], np.ones(prob.size, dtype=bool),
                              [(fast[0][i], fast[1][i]), (plain[0][i], plain[1][i])])
        diff = np.abs(np.concatenate([fast[0][i] - plain[0][i], fast[1][i] - plain[1][i]]))
        assert np.all(diff <= bound), (i, (diff / bound).max())


def test_active_set_kernel_against_the_numpy_iterations(monkeypatch):
    """Both from the bounds each colour's closed form violates; where both settle on the same
    active set and both are certified, they hold the same bound values (exactly) and the free
    samples agree to :func:`_kkt_bound`."""
    setup = _setup()
    prob, b = setup.problem, _colours(setup)
    start = b @ prob.unconstrained
    lo, up = start < 0.0, start > 1.0
    pending = np.flatnonzero(lo.any(axis=1) | up.any(axis=1))
    assert pending.size >= len(b) // 4
    b, lo, up = b[pending], lo[pending], up[pending]
    monkeypatch.setenv("SPECTROCOLOR_NUMBA", "1")
    fast = compiled.pdas(compiled.kernels(), prob, b, 0.0, 1.0, lo, up, 30, 3)
    monkeypatch.setenv("SPECTROCOLOR_NUMBA", "0")
    plain = qp._pdas(prob, b, 0.0, 1.0, lo, up, 30)
    # exact: both hold bound values themselves (np.where with the bound), compared as sets
    same_set = np.all((fast[0] == 0.0) == (plain[0] == 0.0), axis=1) & np.all(
        (fast[0] == 1.0) == (plain[0] == 1.0), axis=1)
    ok = (fast[4] & plain[4] & same_set
          & _certified(prob.W, prob.step_nm, b, fast[0], fast[1], 0.0, 1.0, monkeypatch)
          & _certified(prob.W, prob.step_nm, b, plain[0], plain[1], 0.0, 1.0, monkeypatch))
    assert ok.mean() > 0.9, ok.mean()
    for i in np.flatnonzero(ok):
        # exact: the solvers hold the bound values themselves (np.where with the bound)
        free = (fast[0][i] != 0.0) & (fast[0][i] != 1.0)
        bound, F = _kkt_bound(prob.W, prob.step_nm, b[i], free,
                              [(fast[0][i], fast[1][i]), (plain[0][i], plain[1][i])])
        diff = np.abs(np.concatenate([fast[0][i, F] - plain[0][i, F], fast[1][i] - plain[1][i]]))
        assert np.all(diff <= bound), (i, (diff / bound).max())


@pytest.mark.parametrize(("lower", "upper"), [(0.0, 1.0), (None, None)])
def test_measures_kernel_against_the_numpy_certificate(lower, upper, monkeypatch):
    """The certificate's measures of the same ρ, μ (unperturbed: the residuals are at rounding
    level, where only a bound on the rounding can compare them).

    * primal residual ``max_j |b_j − Σ_k ρ_k W_kj|``: a (K + 1)-term sum, within
      ``γ_{K+1} (|b| + |ρ||W|)_j`` of its exact value on either path, so the two maxima differ by
      at most twice the largest of those;
    * stationarity and wrong signs, ``max |λ_k|`` with ``λ_k = (Q ρ)_k − (W μ)_k``: each term
      passes at most ``m + 4`` roundings (two differences and a product for ``Q ρ``, m products
      and sums for ``W μ``, the difference), so each path is within
      ``γ_{m+4} (|Q||ρ| + |W||μ|)_k``; the samples at a bound are the same on both (the same ρ);
    * bound violation: single subtractions, the same on both paths (exact).
    """
    setup = _setup()
    prob, b = setup.problem, _colours(setup)
    W, h = prob.W, prob.step_nm
    if lower is None:
        rho, mu = qp.solve_unconstrained(prob, b)
    else:
        solution = qp.solve_bounded(prob, b, lower, upper)
        rho, mu = solution.rho, solution.mu
    settled = np.ones(len(b), dtype=bool)
    fast, plain = _both(monkeypatch, lambda: certificate.certify(W, h, b, rho, mu, lower, upper, settled))
    K, m = W.shape
    primal = 2 * gamma(K + 1) * (np.abs(b) + np.abs(rho) @ np.abs(W)).max(axis=1)
    dual = 2 * gamma(m + 4) * (certificate.abs_hess_times(rho, h) + np.abs(mu) @ np.abs(W).T).max(axis=1)
    assert np.all(np.abs(fast.primal_residual - plain.primal_residual) <= primal)
    assert np.all(np.abs(fast.stationarity - plain.stationarity) <= dual)
    assert np.all(np.abs(fast.multiplier_sign_violation - plain.multiplier_sign_violation) <= dual)
    # exact: the largest of single roundings lower − ρ, ρ − upper of the same ρ (no sums)
    np.testing.assert_array_equal(fast.bound_violation, plain.bound_violation)


@pytest.mark.parametrize("cone", [False, True])
def test_facet_kernel_against_the_numpy_gauge(cone, monkeypatch):
    """``v_f = n_f · (b − c)`` is a 3-term dot product, within ``γ_3 Σ_j |d_j n_jf|`` of its
    exact value on either path, so the largest ``|v_f|`` differ by at most twice the largest of
    those; for the cone the ratio divides by the same ``|d|`` on both paths (one more rounding
    of each quotient: ``2 ε`` relative). The facet is the same wherever the best two facets are
    further apart than that (integers: exact)."""
    setup = _setup()
    facets = zonotope.cone_facets(setup.W) if cone else setup.solid
    rng = np.random.default_rng(3)
    b = np.concatenate([_colours(setup), setup.white * rng.uniform(-0.2, 1.2, size=(200, 3))])
    fast, plain = _both(monkeypatch, lambda: zonotope.gauge(facets, b, cone))
    # the solid's facets come in opposite pairs (n, −n): the gauge looks at |v| of one of each
    scaled = facets.normals if cone else (facets.normals / facets.support[:, None])[: len(facets.normals) // 2]
    d = b - facets.centre
    size = np.abs(d) @ np.abs(scaled).T  # Σ_j |d_j n_jf| (N, F)
    bound = 2 * gamma(3) * size.max(axis=1)
    if cone:
        norm = np.linalg.norm(d, axis=1)
        bound = np.where(norm > 0, bound / np.where(norm > 0, norm, 1.0), 0.0) + 2 * EPS * np.abs(plain[0])
    assert np.all(np.abs(fast[0] - plain[0]) <= bound)
    values = np.sort(d @ scaled.T if cone else np.abs(d @ scaled.T), axis=1)
    gap = values[:, -1] - values[:, -2]
    if cone:
        gap = gap / np.where(norm > 0, norm, 1.0)
    clear = gap > 2 * bound
    assert clear.mean() > 0.9
    # exact: integer facet indices where no rounding can change the largest
    np.testing.assert_array_equal(fast[2][clear], plain[2][clear])


def test_roughness_kernel_against_the_numpy_objective(monkeypatch):
    """``Σ (ρ_{k+1} − ρ_k)² / h``: both paths form each difference and square alike and sum the
    K − 1 non-negative squares in different orders, each within ``γ_{K−1}`` (relative) of the
    exact sum, then divide by h (one rounding each, within the factor 2 of γ): the two agree to
    ``2 γ_{K−1}`` relative."""
    setup = _setup()
    prob = setup.problem
    rho, _ = qp.solve_unconstrained(prob, _colours(setup))
    fast, plain = _both(monkeypatch, lambda: prob.objective(rho))
    assert np.all(np.abs(fast - plain) <= 2 * gamma(prob.size - 1) * plain)
