"""Work bounded by the input's size: guards and readers are linear on hostile input.

Each check times one function on an input and on the same kind of input 16 times longer, and
compares the two (never an absolute time): a linear function takes about 16 times longer, a
quadratic one about 256 times. The bound, 64, leaves a factor of 4 for a loaded machine. Each
time is the best of several batches of calls, each batch long enough for the clock.

The inputs are the ones that were quadratic (or worse) before: an unterminated JSON string of
escaped quotes (the server's nesting guard froze every client for 10 s on 40 kB), blank lines
before a CGATS field list (``^\\s*`` tried from every line), long wide-table headers and field
lists (``set(columns)`` rebuilt for every column), digit runs in the number grammar, and
illuminant names padded with spaces (``\\s*(k)?\\s*$`` after a lazy ``.*?``: cubic).
"""

from __future__ import annotations

import time

import pytest

from spectrocolor.app.guards import json_depth
from spectrocolor.errors import ColorimetryError, SpectrumError
from spectrocolor.illuminants import canonical_illuminant
from spectrocolor.io import parse_spectra
from spectrocolor.io.cgats import looks_like_cgats
from spectrocolor.io.cxf import looks_like_cxf
from spectrocolor.io.qtx import looks_like_qtx
from spectrocolor.io.tm27 import looks_like_tm27

FACTOR = 16  # the large input is this many times the small one
BOUND = 64  # FACTOR * 4: linear passes, quadratic (FACTOR ** 2 = 256) does not


def seconds_per_call(function, argument, batch_s: float = 0.02, batches: int = 5) -> float:
    """Best time of one call of ``function(argument)``, from ``batches`` batches of calls."""
    calls, start = 0, time.perf_counter()
    while time.perf_counter() - start < batch_s:  # calibrate: calls per batch
        function(argument)
        calls += 1
    best = float("inf")
    for _ in range(batches):
        start = time.perf_counter()
        for _ in range(calls):
            function(argument)
        best = min(best, (time.perf_counter() - start) / calls)
    return best


def assert_linear(function, make, size: int) -> None:
    """``function`` on ``make(FACTOR * size)`` takes at most BOUND times ``make(size)``'s time."""
    small, large = make(size), make(FACTOR * size)
    assert len(large) >= FACTOR * len(small) * 0.5
    t_small = seconds_per_call(function, small)
    t_large = seconds_per_call(function, large, batches=3)
    assert t_large <= BOUND * t_small, (
        f"{function.__name__}: {t_large / t_small:.0f} x the time for {FACTOR} x the input "
        f"({t_small * 1e3:.3f} ms -> {t_large * 1e3:.3f} ms): not linear")


def quietly(function):
    """``function`` with its one clear error swallowed (the time is what is measured)."""
    def call(argument):
        try:
            function(argument)
        except (SpectrumError, ColorimetryError):
            pass
    call.__name__ = function.__name__
    return call


@pytest.mark.parametrize("make", [
    lambda n: b'"' + b'\\"' * n,  # the unterminated string of escaped quotes
    lambda n: b'["a\\\\", ' * n,  # escaped backslashes before closing quotes
    lambda n: b"[" * n,  # deep nesting
    lambda n: b'{"x": [1.5, 2.5], "s": "[["},' * n,  # ordinary JSON
], ids=["escaped-quotes", "escaped-backslashes", "brackets", "ordinary"])
def test_the_json_nesting_guard_is_linear(make):
    assert_linear(json_depth, make, 500)


def test_the_nesting_guard_counts_what_a_parser_sees():
    assert json_depth(b'"' + b'\\"' * 20_000) == 0
    assert json_depth(b'["\\\\", [[1]]]') == 3  # an escaped backslash ends before the quote
    assert json_depth(b'["\\"[[[[", [1]]') == 2  # an escaped quote does not end the string


@pytest.mark.parametrize(("function", "make"), [
    (looks_like_qtx, lambda n: "[" + "STD " * n),
    (looks_like_qtx, lambda n: "[x STANDARD_DATA\n" * n),
    (looks_like_qtx, lambda n: " \n" * n + "[" * n),
    (looks_like_cxf, lambda n: "<!--" + " " * n + "-->"),
    (looks_like_cxf, lambda n: "<a>" * n),
], ids=["qtx-open-bracket", "qtx-no-index", "qtx-brackets", "cxf-comment", "cxf-nesting"])
def test_recognising_qtx_and_cxf_is_linear(function, make):
    assert_linear(function, make, 2000)


@pytest.mark.parametrize("make", [
    lambda n: "\n" * n,
    lambda n: " \n" * n,
    lambda n: "\r\n \t" * n,
    lambda n: " " * n + "x",
], ids=["newlines", "space-lines", "crlf-tabs", "one-long-line"])
def test_recognising_cgats_is_linear(make):
    assert_linear(looks_like_cgats, make, 2000)


@pytest.mark.parametrize("make", [
    lambda n: "\n" * n + "x",
    lambda n: "  \n" * n,
    lambda n: "# a comment\n" * n,
    lambda n: "Sample," + ",".join(f"{380 + i}" for i in range(n)) + "\n",
    lambda n: "CGATS.17\nBEGIN_DATA_FORMAT\nSAMPLE_ID " + " ".join(f"SPEC_{400 + i / 1e4:.4f}" for i in range(n))
              + "\nEND_DATA_FORMAT\nBEGIN_DATA\n" + " ".join("1" for _ in range(n + 1)) + "\nEND_DATA\n",
    lambda n: "wavelength_nm,a\n400," + "1" * n + "x\n",
], ids=["blank-lines", "space-lines", "comments", "wide-header", "cgats-fields", "digit-run"])
def test_reading_hostile_tables_is_linear(make):
    assert_linear(quietly(lambda text: parse_spectra(text, "hostile")), make, 2000)


def test_finding_the_tm27_document_element_is_linear():
    assert_linear(looks_like_tm27, lambda n: "<!--" + " " * n + '--><IESTM2714 version="1"/>', 4000)


@pytest.mark.parametrize("make", [
    lambda n: "d:1" + " " * n + "x",
    lambda n: "blackbody:" + " " * n + "k",
    lambda n: " " * n + "D65",
], ids=["padded-temperature", "padded-unit", "padded-name"])
def test_resolving_an_illuminant_name_is_linear(make):
    assert_linear(quietly(canonical_illuminant), make, 50)
