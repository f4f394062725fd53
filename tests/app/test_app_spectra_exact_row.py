"""The X Y Z row in "SPECTRA exact": SPECTRA's step-1 values, 100/100/100 for the full spectrum.

Seed 002, STEP 1: ``X = k ∫ f x̄ dλ`` with ``k = 100 / (f_max ∫ x̄ dλ)``, one k per channel, "and
we can as well put it = 100". CIE's one k (100 / Σ ȳ) gives the full spectrum X ≠ 100 on
400–700 nm; the page multiplies the CIE XYZ by the model's ``channel_factors`` for the row, and
the server's ``XYZ_row`` is the same product (issue 27, part 5).
"""

from __future__ import annotations

import numpy as np

from spectrocolor.app import compute

FULL = [[30.0] * 31]  # every 10 nm bin at the full level
#: XYZ_row = 100 × (Σ of 31 products) / (the same sum in another order): a few ulps per term
RTOL = 2 * 31 * np.finfo(float).eps


def _row(normalise, display="SPECTRA 7000K", spectra=FULL):
    answer = compute.evaluate(10.0, "1931", display, normalise, "clip", spectra, adaptation="none")
    return answer, np.array([c["XYZ_row"] for c in answer["colours"]]), np.array([c["XYZ"] for c in answer["colours"]])


def test_spectra_exact_shows_the_full_spectrum_as_100_100_100():
    answer, row, cie = _row("spectra-exact")
    np.testing.assert_allclose(row[0], [100.0, 100.0, 100.0], rtol=RTOL, atol=0)
    assert abs(cie[0, 0] - 100.0) > 0.1 and abs(cie[0, 2] - 100.0) > 0.1  # CIE's one k differs
    assert abs(cie[0, 1] - 100.0) <= 100.0 * RTOL  # both put Y = 100
    assert "SPECTRA" in answer["XYZ_row_note"] and "CIE" in answer["XYZ_row_note"]


def test_the_row_is_cie_otherwise_and_always_the_models_factors_times_cie():
    rng = np.random.default_rng(27)
    spectra = rng.integers(0, 31, (3, 31)).astype(float).tolist()
    for normalise in ("fixed", "per-colour", "spectra-exact"):
        _, row, cie = _row(normalise, spectra=spectra)
        factors = np.array(compute.model(10.0, "1931", "SPECTRA 7000K", normalise=normalise,
                                          adaptation="none")["channel_factors"])
        # exact: one IEEE product of the same two doubles (JSON round-trips them), as the server forms it
        np.testing.assert_array_equal(row, cie * factors)  # what the page paints: the same product
        if normalise != "spectra-exact":
            np.testing.assert_array_equal(row, cie)  # exact: factors of exactly 1 outside spectra-exact
