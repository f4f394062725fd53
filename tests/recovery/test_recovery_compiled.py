"""The compiled kernels of the smoothest-reflectance solvers against the NumPy path.

With numba installed the closed form, the active-set iterations and the certificate's measures
run compiled (``spectrocolor.recovery.compiled``); ``SPECTROCOLOR_NUMBA=0`` runs the NumPy path.
Both must answer every colour the same way (feasible or not; certified), and every certified
answer of either must pass the independent KKT check of ``tests/support/kkt_check.py``. Which solver
settles a colour (closed form, active set, restart, dense fallback, face) turns on rounding in the
first iterations, so on the CPU's vector width and BLAS kernel: it is not compared. The kernels
sum in another order than BLAS, so solutions are compared to the rounding of the closed form's
own product, not bit for bit.
"""

from __future__ import annotations

import os
import subprocess
import sys
import threading

import numpy as np
import pytest

import spectrocolor as sc
from kkt_check import kkt_violation
from spectrocolor.recovery import certificate, compiled, qp
from spectrocolor.recovery.inputs import setup_for

pytestmark = pytest.mark.skipif(compiled._compiled() is None, reason="numba is not installed")

EPS = np.finfo(float).eps
GRIDS = [(380.0, 780.0, 10.0), (400.0, 700.0, 5.0)]


def _colours(grid, illuminant="D65", count=120):
    """Interior, saturated, near-boundary (depth 1e-6 and 1e-9) and outside colours."""
    setup = setup_for(grid, "1931", illuminant)[0]
    W = setup.W
    K = W.shape[0]
    rng = np.random.default_rng(11)
    smooth = np.cumsum(rng.normal(size=(count, K)), axis=1)
    smooth = (smooth - smooth.min(axis=1, keepdims=True)) / np.ptp(smooth, axis=1, keepdims=True)
    interior = (0.05 + 0.9 * smooth) @ W
    saturated = smooth @ W
    vertices = (rng.normal(size=(count, 3)) @ W.T > 0).astype(float) @ W
    centre = setup.white / 2
    near = np.concatenate([centre + (vertices - centre) * (1 - d) for d in (1e-6, 1e-9)])
    outside = centre + (vertices[:20] - centre) * 1.01
    return np.concatenate([interior, saturated, near, outside])


def _solve(XYZ, grid, bounds, monkeypatch, numba_on):
    monkeypatch.setenv("SPECTROCOLOR_NUMBA", "1" if numba_on else "0")
    return sc.smoothest_reflectance(XYZ, wavelengths=grid, bounds=bounds)


@pytest.mark.parametrize("bounds", ["unit", "nonnegative", None])
@pytest.mark.parametrize("grid", GRIDS)
def test_both_paths_answer_every_colour_alike_and_pass_the_independent_check(grid, bounds,
                                                                            monkeypatch):
    XYZ = _colours(grid)
    fast = _solve(XYZ, grid, bounds, monkeypatch, True)
    plain = _solve(XYZ, grid, bounds, monkeypatch, False)
    # exact: booleans; every colour lies 1e-9 of its size or more from the boundary (_colours),
    # 1e4 times the rounding of either path's facet test
    np.testing.assert_array_equal(fast.feasible, plain.feasible)
    assert fast.feasible.sum() > len(XYZ) // 2
    for result in (fast, plain):
        assert result.certificate.converged[result.feasible].all()
    if bounds is None:
        return
    W = setup_for(grid, "1931", "D65")[0].W
    upper = 1.0 if bounds == "unit" else np.inf
    for result in (fast, plain):
        for i in np.flatnonzero(result.feasible)[::3]:
            ratio = kkt_violation(W, grid[2], result.spectrum.values[i], upper, result.multipliers[i])
            assert ratio <= 1.0, (i, ratio, result.method[i])


@pytest.mark.parametrize("grid", GRIDS)
def test_closed_forms_agree_to_the_rounding_of_the_product(grid, monkeypatch):
    prob = setup_for(grid, "1931", "D65")[0].problem
    XYZ = _colours(grid)
    rho_fast, mu_fast = qp.solve_unconstrained(prob, XYZ)
    monkeypatch.setenv("SPECTROCOLOR_NUMBA", "0")
    rho_plain, mu_plain = qp.solve_unconstrained(prob, XYZ)
    # each is the exact minimiser to within a few roundings of the terms of b @ U
    scale = np.abs(XYZ) @ np.abs(prob.unconstrained)
    assert np.all(np.abs(rho_fast - rho_plain) <= 64 * EPS * scale)
    scale_mu = np.abs(XYZ) @ np.abs(prob.multipliers)
    assert np.all(np.abs(mu_fast - mu_plain) <= 64 * EPS * scale_mu)


@pytest.mark.parametrize(("lower", "upper"), [(0.0, 1.0), (0.0, np.inf), (None, None)])
def test_certificate_measures_agree_with_the_numpy_path(lower, upper, monkeypatch):
    grid = (400.0, 700.0, 10.0)
    prob = setup_for(grid, "1931", "D65")[0].problem
    XYZ = _colours(grid)
    rho, mu = qp.solve_unconstrained(prob, XYZ)
    if lower is not None:
        rho = np.clip(rho, lower, upper)
    # perturbations far above rounding, so the measures do not depend on the summation order
    rng = np.random.default_rng(5)
    # exact: np.clip returns the bound values themselves
    rho = np.where((rho == 0.0) | (rho == 1.0), rho, rho + 1e-7 * rng.normal(size=rho.shape))
    mu = mu + 1e-6 * rng.normal(size=mu.shape)
    rho[3, 4] = np.nan  # measured again by the NumPy path: its NaN semantics
    mu[5, 1] = np.inf
    settled = np.ones(len(XYZ), dtype=bool)
    fast = certificate.certify(prob.W, prob.step_nm, XYZ, rho, mu, lower, upper, settled)
    monkeypatch.setenv("SPECTROCOLOR_NUMBA", "0")
    plain = certificate.certify(prob.W, prob.step_nm, XYZ, rho, mu, lower, upper, settled)
    for name in ("primal_residual", "multiplier_sign_violation", "stationarity", "rounding_ratio"):
        a, b = getattr(fast, name), getattr(plain, name)
        np.testing.assert_allclose(a, b, rtol=1e-6, atol=0, equal_nan=True, err_msg=name)
    # exact: maxima of single roundings (lower − ρ, ρ − upper): no sums, alike on both paths
    np.testing.assert_array_equal(fast.bound_violation, plain.bound_violation)
    # exact: booleans of ratio ≤ 1 where every ratio is ≥ 8e8 (perturbations far above rounding) or NaN
    np.testing.assert_array_equal(fast.converged, plain.converged)
    assert not fast.converged[3] and not fast.converged[5]


@pytest.mark.parametrize("illuminants", [("D65",), ("D65", "A")])
def test_closed_form_kernel_measures_what_the_certificate_measures(illuminants, monkeypatch):
    """The closed-form kernel forms ρ and μ and measures them in the same passes (unrolled for
    three weights, general for more, as for metamers under two illuminants). Given a basis
    perturbed far above rounding (so that the measures do not depend on the summation order),
    its measures and roughness are those :func:`.certificate.certify` and
    :meth:`.qp.Problem.objective` give for the ρ and μ it returns."""
    grid = (400.0, 700.0, 10.0)
    W = np.concatenate([setup_for(grid, "1931", name)[0].W for name in illuminants], axis=1)
    prob = qp.make_problem(W, grid[2])
    m = W.shape[1]
    rng = np.random.default_rng(3)
    b = rng.uniform(0.05, 0.95, size=(200, W.shape[0])) @ W
    basis = prob.basis
    solutions = basis.solutions * (1 + 1e-7 * rng.normal(size=basis.solutions.shape))
    multipliers = basis.multipliers * (1 + 1e-6 * rng.normal(size=basis.multipliers.shape))
    t, primal, dual = compiled._factors(grid[2], W.shape[0])
    pin = prob.pinned
    stacked = np.vstack([pin.sub, pin.sup_factor, pin.inverse_denominator, pin.P.T])
    rho, mu = np.empty((len(b), W.shape[0])), np.empty((len(b), m))
    out, rough = np.empty((5, len(b))), np.empty(len(b))
    compiled._compiled().closed_form(*compiled._layouts(W), b, basis.inverse, solutions,
                                     multipliers, t, stacked, pin.S_lu, pin.S_piv, 0, primal,
                                     dual, -np.inf, np.inf, rho, mu, out, rough)
    np.testing.assert_allclose(rho, (b @ basis.inverse) @ solutions, rtol=1e-12, atol=1e-14)
    monkeypatch.setenv("SPECTROCOLOR_NUMBA", "0")
    plain = certificate.certify(W, grid[2], b, rho, mu, None, None, np.ones(len(b), dtype=bool))
    assert plain.rounding_ratio.min() > 1e3  # far from rounding, as intended
    for row, name in enumerate(("primal_residual", "bound_violation",
                                "multiplier_sign_violation", "stationarity", "rounding_ratio")):
        np.testing.assert_allclose(out[row], getattr(plain, name), rtol=1e-6, atol=0,
                                   err_msg=name)
    np.testing.assert_allclose(rough, prob.objective(rho), rtol=1e-12)


def test_the_kernels_run_from_worker_threads(monkeypatch):
    """dask calls from its worker threads: the compiled path must give the main thread's answer."""
    monkeypatch.setenv("SPECTROCOLOR_NUMBA", "1")
    grid = (380.0, 780.0, 10.0)
    XYZ = _colours(grid)
    expected = sc.smoothest_reflectance(XYZ, wavelengths=grid)
    results = [None, None]

    def work(slot):
        results[slot] = sc.smoothest_reflectance(XYZ, wavelengths=grid)

    threads = [threading.Thread(target=work, args=(slot,)) for slot in range(2)]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()
    for got in results:
        # exact: the same call on the same input (threads of one process)
        np.testing.assert_array_equal(got.spectrum.values, expected.spectrum.values)
        # exact: the same call on the same input (threads of one process)
        np.testing.assert_array_equal(got.certificate.converged, expected.certificate.converged)


def test_the_switch_selects_the_numpy_path(monkeypatch):
    monkeypatch.setenv("SPECTROCOLOR_NUMBA", "off")
    assert compiled.kernels() is None
    monkeypatch.setenv("SPECTROCOLOR_NUMBA", "1")
    assert compiled.kernels() is not None


def test_without_numba_the_numpy_path_runs(tmp_path):
    """numba made unimportable in a fresh interpreter: kernels() is None and every path solves."""
    script = (
        "import sys; sys.modules['numba'] = None\n"
        "import numpy as np\n"
        "import spectrocolor as sc\n"
        "from spectrocolor.recovery.compiled import kernels\n"
        "assert kernels() is None\n"
        "XYZ = [[40.0, 40.0, 40.0], [35.0, 30.0, 20.0], [30.0, 20.0, 3.0]]\n"
        "got = [sc.smoothest_reflectance(XYZ, wavelengths=(400, 700, 10), bounds=b)"
        " for b in ('unit', 'nonnegative', None)]\n"
        "print([bool(r.certificate.converged.all()) for r in got], got[0].method.tolist())\n"
    )
    environment = {k: v for k, v in os.environ.items() if k != "SPECTROCOLOR_NUMBA"}
    done = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True,
                          timeout=300, env=environment, cwd=tmp_path)
    assert done.returncode == 0, done.stderr
    assert done.stdout.strip() == ("[True, True, True] ['unconstrained', 'unconstrained', "
                                   "'active set']")
