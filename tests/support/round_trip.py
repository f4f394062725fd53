"""A round-trip harness for every inverse pair of conversions (after colorspacious's check_conversion).

``check_round_trip`` checks one pair ``forward``/``inverse`` four ways:

1. each gold pair both ways, within ``gold_tol`` (relative and absolute) — gold values are published, rounded numbers
   (each cites its source), so this tolerance is set by the rounding of the printed digits;
2. the gold inputs as one batch, equal to the one-by-one results (batching changes nothing);
3. the same batch broadcast to a (2, N, 3) array (leading dimensions are kept);
4. random inputs from ``sample(rng, n)`` through ``forward`` then ``inverse``, back to the start
   within ``internal_tol`` — internal consistency, set by floating-point rounding of the two
   formulas (a few ulps times the condition of the pair), not by any published table.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np


def check_round_trip(
    forward: Callable,
    inverse: Callable,
    gold: list[tuple[list[float], list[float]]],
    sample: Callable[[np.random.Generator, int], np.ndarray],
    *,
    gold_tol: float,
    internal_tol: float,
    seed: int = 0,
) -> None:
    """Assert that ``forward`` and ``inverse`` agree with the gold pairs and invert each other."""
    for a, b in gold:
        np.testing.assert_allclose(forward(np.array(a)), b, rtol=gold_tol, atol=gold_tol, err_msg=f"forward({a})")
        np.testing.assert_allclose(inverse(np.array(b)), a, rtol=gold_tol, atol=gold_tol, err_msg=f"inverse({b})")
    inputs = np.array([a for a, _ in gold], dtype=float)
    one_by_one = np.array([forward(row) for row in inputs])
    batch = forward(inputs)
    # A batched matrix product may sum in another order than one row at a time (BLAS gemm vs
    # gemv): allow a few ulps of the largest term, which bounds the rounding of a 3-term sum.
    ulps = 16 * np.finfo(float).eps
    scale = max(1.0, float(np.max(np.abs(batch))), float(np.max(np.abs(inputs))))
    np.testing.assert_allclose(batch, one_by_one, rtol=ulps, atol=ulps * scale, err_msg="batch differs from one-by-one")
    stacked = forward(np.stack([inputs, inputs]))
    assert stacked.shape == (2, *batch.shape), f"broadcast shape {stacked.shape} != {(2, *batch.shape)}"
    np.testing.assert_allclose(stacked[1], batch, rtol=ulps, atol=ulps * scale)
    start = sample(np.random.default_rng(seed), 1000)
    back = inverse(forward(start))
    np.testing.assert_allclose(back, start, rtol=internal_tol, atol=internal_tol, err_msg="random round trip")
