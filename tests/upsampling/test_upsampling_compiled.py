"""The compiled kernel (numba, extra "fast") against the NumPy path, and the clean fallback.

Both paths do the same floating-point operations in the same order (no fastmath), so they are
held to ULPS units in the last place of the largest value (measured: identical bits on x86-64;
the margin covers a compiler that contracts a multiply-add).
"""

import os
import subprocess
import sys
import threading

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

import spectrocolor as sc
from spectrocolor.upsampling import colours_under, lookup, texel_coefficients, upsample, upsample_spectra
from spectrocolor.upsampling.compiled import kernels
from upsampling_tables import rec2020_table, srgb_table

pytest.importorskip("numba", reason="the compiled kernel needs numba (pip install spectrocolor[fast])")

ULPS = 4
#: Queries solved in cells with moved nodes (path 2 of upsampling.moved_cells) are held to this,
#: relative to the largest value: their spectra come from the recovery solver's compiled or
#: NumPy route, two certified solutions of one strictly convex programme (measured 4e-15 apart;
#: the certificate's rounding level allows ~1e-13). Path 1 (the actual-colour blend) does the
#: kernel's operations in its order and is held to ULPS like the plain blend.
SETTLED = 1e-12
STRATEGIES = ("toward-grey", "clip", "nan")

# in the cube, outside it (HDR and negative wide-gamut values) and exactly on its faces
coordinate = st.one_of(st.floats(-0.5, 2.5, allow_nan=False), st.sampled_from([0.0, 0.5, 1.0]))
queries = arrays(np.float64, st.tuples(st.integers(1, 60), st.just(3)), elements=coordinate)


def numpy_path(function, *arguments):
    with pytest.MonkeyPatch.context() as patch:
        patch.setenv("SPECTROCOLOR_NUMBA", "0")
        assert kernels() is None
        return function(*arguments)


def assert_close_in_ulps(compiled, reference, settled=None):
    """Equal to ULPS units in the last place, except rows ``settled`` (to SETTLED relative)."""
    compiled, reference = np.asarray(compiled), np.asarray(reference)
    assert compiled.shape == reference.shape and compiled.dtype == reference.dtype
    assert np.array_equal(np.isnan(compiled), np.isnan(reference))
    settled = np.zeros(compiled.shape[:-1], dtype=bool) if settled is None else settled
    scale = np.abs(reference[~np.isnan(reference)]).max(initial=1.0)
    difference = np.where(np.isnan(reference), 0.0, np.abs(compiled - reference))
    assert difference[~settled].max(initial=0.0) <= ULPS * np.spacing(scale)
    assert difference[settled].max(initial=0.0) <= SETTLED * scale


def test_the_kernel_is_used_when_numba_is_installed(monkeypatch):
    monkeypatch.delenv("SPECTROCOLOR_NUMBA", raising=False)
    assert kernels() is not None
    monkeypatch.setenv("SPECTROCOLOR_NUMBA", "0")
    assert kernels() is None


@settings(max_examples=40, deadline=None)
@given(queries, st.sampled_from(STRATEGIES), st.booleans())
def test_spectra_equal_the_numpy_path(t, strategy, wide):
    table = rec2020_table() if wide else srgb_table()
    ours = upsample(table, t, strategy)
    reference = numpy_path(upsample, table, t, strategy)
    assert_close_in_ulps(ours.reflectance, reference.reflectance, reference.path == 2)
    # exact: booleans of the same comparisons on the input in both paths
    assert np.array_equal(ours.exact, reference.exact)
    # exact: booleans of the same comparisons on the input in both paths
    assert np.array_equal(ours.moved, reference.moved)
    assert np.nanmax(ours.reflectance, initial=0.0) <= 1.0


@settings(max_examples=40, deadline=None)
@given(queries, st.sampled_from(STRATEGIES), st.booleans())
def test_relighting_and_coefficients_equal_the_numpy_path(t, strategy, wide):
    table = rec2020_table() if wide else srgb_table()
    W_A = np.asarray(sc.weights(table.wavelengths_nm, illuminant="A"))
    XYZ, exact = colours_under(table, t, W_A, strategy)
    XYZ_ref, exact_ref = numpy_path(colours_under, table, t, W_A, strategy)
    settled = numpy_path(upsample, table, t, strategy).path
    assert_close_in_ulps(XYZ, XYZ_ref, settled == 2)
    assert np.array_equal(exact, exact_ref)  # exact: booleans of the same comparisons on the input in both paths
    found, found_ref = lookup(table, t, strategy), numpy_path(lookup, table, t, strategy)
    # exact: integer indices of the same single roundings (no fastmath) in both paths
    assert np.array_equal(found.nodes, found_ref.nodes)
    assert_close_in_ulps(found.weights, found_ref.weights)
    # exact: booleans of the same comparisons on the input in both paths
    assert np.array_equal(found.exact, found_ref.exact) and np.array_equal(found.moved, found_ref.moved)
    nodes, weights, exact = texel_coefficients(table, t, strategy)
    nodes_ref, weights_ref, exact_ref = numpy_path(texel_coefficients, table, t, strategy)
    # exact: integer indices of the same single roundings (no fastmath) in both paths
    assert np.array_equal(nodes, nodes_ref) and nodes.dtype == np.uint32
    assert_close_in_ulps(weights, weights_ref)
    assert np.array_equal(exact, exact_ref)  # exact: booleans of the same comparisons on the input in both paths


def test_shapes_and_out_arrays_as_the_numpy_path():
    table = srgb_table()
    t = np.random.default_rng(5).random((4, 5, 3)) * 1.2
    reference = numpy_path(upsample_spectra, table, t)
    assert_close_in_ulps(upsample_spectra(table, t), reference)
    single = upsample(table, t[0, 0])
    assert single.reflectance.shape == (81,) and single.exact.shape == ()
    assert_close_in_ulps(single.reflectance, reference[0, 0])
    contiguous = np.empty((4, 5, 81))
    assert upsample_spectra(table, t, out=contiguous) is not None
    assert_close_in_ulps(contiguous, reference)
    strided = np.empty((4, 5, 162))[..., ::2]  # not contiguous: written through a copy
    upsample_spectra(table, t, out=strided)
    assert_close_in_ulps(strided, reference)
    assert upsample_spectra(table, np.empty((0, 3))).shape == (0, 81)


def test_worker_threads_use_the_serial_kernel_with_the_same_numbers():
    table = srgb_table()
    t = np.random.default_rng(6).random((5000, 3))
    main_thread = upsample_spectra(table, t)
    results = []
    worker = threading.Thread(target=lambda: results.append(upsample_spectra(table, t)))
    worker.start()
    worker.join()
    # exact: per-pixel blend of 4 nodes in a fixed order (no BLAS, no sum across pixels), whatever the batch or block
    # (serial and parallel kernels)
    assert np.array_equal(results[0], main_thread)


def test_without_numba_the_numpy_path_runs(tmp_path):
    """numba made unimportable in a fresh interpreter: kernels() is None and upsample works."""
    script = (
        "import sys; sys.modules['numba'] = None\n"
        "import numpy as np\n"
        "from spectrocolor.upsampling import upsample, upsampling_table\n"
        "from spectrocolor.upsampling.compiled import kernels\n"
        "assert kernels() is None\n"
        "table = upsampling_table('sRGB', 'D65', resolution=3, measure_excess=False)\n"
        "u = upsample(table, [[0.5, 0.5, 0.5], [1.5, 0.2, 0.2]])\n"
        "print(u.exact.tolist(), u.moved.tolist(), float(abs(u.reflectance[0] - 0.5).max()) < 1e-9)\n"
    )
    environment = {k: v for k, v in os.environ.items() if k != "SPECTROCOLOR_NUMBA"}
    done = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, timeout=300,
                          env=environment, cwd=tmp_path)
    assert done.returncode == 0, done.stderr
    assert done.stdout.strip() == "[True, False] [False, True] True"


def test_a_function_that_cannot_be_cached_is_compiled_without_a_cache():
    """numba refuses cache=True where no cache folder can be used (here: source without a file)."""
    import numba

    from spectrocolor.upsampling.numba_kernels import _jit

    namespace = {}
    exec(compile("def twice(x):\n    return 2 * x\n", "<no file>", "exec"), namespace)
    with pytest.raises(RuntimeError, match="cannot cache"):
        numba.njit(cache=True)(namespace["twice"])
    assert _jit()(namespace["twice"])(21) == 42
