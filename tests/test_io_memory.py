"""Memory of the delimited-table reader: it keeps floats, not cell strings (issue 12).

The bound is derived from what the reader must hold, not from a measurement: the file's bytes
and their decoded text exist together for a moment (2 × the file size, all ASCII here), then the
text and one float64 per number. With six-decimal cells ("0.123456," is 9 bytes) the floats
take 8/9 of the file, so text + floats stays below the 2 × of the read. We allow 2.5 × the file
size: the old reader, which kept every cell as a Python string (about 50 bytes each), needed
about 11 × and fails this test.
"""

from __future__ import annotations

import tracemalloc

import numpy as np
import pytest

import spectrocolor as sc

SAMPLES, BANDS = 600, 401


def _write(path, layout: str) -> np.ndarray:
    values = np.round(np.random.default_rng(7).random((SAMPLES, BANDS)), 6)
    wavelengths = np.arange(380, 380 + BANDS)
    with open(path, "w") as out:
        if layout == "wide":
            out.write("name," + ",".join(map(str, wavelengths)) + "\n")
            for i, row in enumerate(values):
                out.write(f"s{i}," + ",".join(f"{v:.6f}" for v in row) + "\n")
        else:
            out.write("wavelength_nm," + ",".join(f"s{i}" for i in range(SAMPLES)) + "\n")
            for k, column in enumerate(values.T):
                out.write(f"{wavelengths[k]}," + ",".join(f"{v:.6f}" for v in column) + "\n")
    return values


@pytest.mark.parametrize("layout", ["wide", "long"])
def test_reading_a_table_needs_at_most_two_and_a_half_times_its_size(tmp_path, layout):
    path = tmp_path / f"{layout}.csv"
    expected = _write(path, layout)
    size = path.stat().st_size
    tracemalloc.start()
    try:
        spectra = sc.read_spectra(path)
        _, peak = tracemalloc.get_traced_memory()
    finally:
        tracemalloc.stop()
    np.testing.assert_array_equal(spectra.values, expected)  # 6 decimals: float() gives the same double
    assert spectra.names[-1] == f"s{SAMPLES - 1}"
    assert peak <= 2.5 * size, f"peak {peak / size:.2f} × the file size"
