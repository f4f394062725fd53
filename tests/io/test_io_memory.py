"""The streamed delimited-table reader: memory (floats, not cell strings; issue 12) and lines.

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
from hypothesis import given, settings
from hypothesis import strategies as st

import spectrocolor as sc
from spectrocolor.io.delimited import _lines, parse_delimited

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
    # exact: decimal text parsed by float(): correctly rounded, the same double on every CPU
    np.testing.assert_array_equal(spectra.values, expected)  # 6 decimals: float() gives the same double
    assert spectra.names[-1] == f"s{SAMPLES - 1}"
    assert peak <= 2.5 * size, f"peak {peak / size:.2f} × the file size"


@settings(max_examples=300, deadline=None)
@given(st.text(alphabet=st.sampled_from(list("ab,;\t#\" 1.\n\r\x0b\x0c\x1c\x1d\x1e\x85\u2028\u2029")), max_size=60))
def test_the_streamed_lines_are_those_of_splitlines(text):
    """The reader walks the text without splitting it all at once; the lines (and so the line
    numbers in messages) must still be exactly those of str.splitlines, whatever the breaks."""
    assert list(_lines(text)) == text.splitlines()


@settings(max_examples=100, deadline=None)
@given(values=st.lists(st.lists(st.floats(-1e6, 1e6, allow_nan=False), min_size=3, max_size=3), min_size=1,
                       max_size=8),
       delimiter=st.sampled_from([",", ";", "\t"]), newline=st.sampled_from(["\n", "\r\n", "\r"]),
       quoted=st.booleans())
def test_generated_wide_tables_read_back_exactly(values, delimiter, newline, quoted):
    """Numbers written with repr (and a decimal comma for ';') come back as the same doubles."""
    def cell(v: float) -> str:
        text = repr(v).replace(".", ",") if delimiter == ";" else repr(v)
        return f'"{text}"' if quoted else text

    lines = [delimiter.join(["name", "400", "500", "600"])]
    lines += [delimiter.join([f"s{i}", *map(cell, row)]) for i, row in enumerate(values)]
    spectra = parse_delimited(newline.join(lines) + newline, "gen.csv")
    # exact: decimal text parsed by float(): correctly rounded, the same double on every CPU
    np.testing.assert_array_equal(np.atleast_2d(spectra.values), np.array(values))
    assert spectra.names == tuple(f"s{i}" for i in range(len(values)))
