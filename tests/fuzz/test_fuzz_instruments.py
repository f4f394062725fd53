"""Fuzzing the instrument-export readers (OceanView/SpectraSuite, UPRtek, Sekonic, Konica Minolta)
and the ``resample_nm`` option: every input is a Spectrum or one one-line SpectrumError.

The corpus files themselves also go through ``test_fuzz_io.py``'s random damage (it reads every
file in ``tests/data/io``); here the texts are built from each format's own vocabulary, so the
generated files get past identification and into the readers' deeper checks.
"""

from pathlib import Path

import numpy as np
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import spectrocolor as sc
from spectrocolor import Spectrum, SpectrumError
from spectrocolor.io import parse_spectra

CORPUS = Path(__file__).parents[1] / "data" / "io"
SETTINGS = settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.too_slow])

NUMBERS = st.sampled_from(["0", "1", "-1", "0.5", "1e3", "1e309", "nan", "inf", "", "x", "0,5", "3.5", "٣", "0_5",
                           "999999999999", "2048", "380", "381", "780", "360"])
HEADER_KEYS = st.sampled_from(["Number of Pixels in Spectrum", "Number of Pixels in Processed Spectrum", "XAxis mode",
                               "Integration Time (sec)", "Integration Time (usec)", "Scans to average",
                               "Boxcar width", "Spectrometer", "Date", "Data from Transmission Node",
                               "Data from AbsoluteIrradiance Node"])
SEPARATORS = st.sampled_from(["\t", " ", ",", "\t\t", ";"])


def _outcome(call):
    try:
        return call()
    except SpectrumError as exc:
        assert "\n" not in str(exc), str(exc)
        return exc


def _check(result):
    assert isinstance(result, (Spectrum, SpectrumError))
    if isinstance(result, Spectrum):
        assert np.all(np.isfinite(result.values)) and result.values.shape[-1] == result.wavelengths_nm.size


@SETTINGS
@given(header=st.lists(st.tuples(HEADER_KEYS, NUMBERS), max_size=6),
       rows=st.lists(st.tuples(NUMBERS, SEPARATORS, NUMBERS), max_size=30),
       processed=st.booleans(), end=st.booleans(), percent=st.sampled_from([None, True, False]))
def test_generated_oceanview_exports(header, rows, processed, end, percent):
    kind = "Processed " if processed else ""
    lines = [f"{key}: {value}" if not key.startswith("Data from") else key for key, value in header]
    lines += [f">>>>>Begin {kind}Spectral Data<<<<<"] + [f"{a}{sep}{b}" for a, sep, b in rows]
    if end:
        lines.append(f">>>>>End {kind}Spectral Data<<<<<")
    _check(_outcome(lambda: parse_spectra("\n".join(lines) + "\n", "fuzz.txt", percent)))


LABELS = st.sampled_from(["LUX", "CCT", "Duv", "Model Name", "Memo", "Title", "Tcp [K]", "⊿uv", "Illuminance [lx]",
                          "Ev", "Tcp", "x", "y", "Date", "Time", "Data Name", "380nm", "381nm", "360nm", "361 nm",
                          "Spectral Data 380[nm]", "Spectral Data 385[nm]", "Spectral Data 381nm [mW/m²nm]",
                          "Spectral Data 382nm [lm]", "Spectrum[0]", "Spectrum[1]", "Spectrum[2]", ""])


@SETTINGS
@given(rows=st.lists(st.tuples(LABELS, st.lists(NUMBERS, max_size=3)), min_size=1, max_size=40),
       delimiter=st.sampled_from(["\t", ",", ";"]), percent=st.sampled_from([None, True, False]))
def test_generated_light_meter_exports(rows, delimiter, percent):
    text = "\n".join(delimiter.join([label, *values]) for label, values in rows) + "\n"
    _check(_outcome(lambda: parse_spectra(text, "fuzz.csv", percent)))


@SETTINGS
@given(name=st.sampled_from(["oceanview_flame.txt", "uprtek_mk350.xls", "sekonic_c800.csv", "cl500a_memory.csv",
                             "cary_winuv_cp1252.csv"]),
       step=st.one_of(st.floats(allow_nan=True, allow_infinity=True), st.integers(-3, 10**9), st.just("1"),
                      st.just(None), st.booleans()))
def test_resample_nm_any_value(name, step):
    result = _outcome(lambda: sc.read_spectra(CORPUS / name, resample_nm=step))
    _check(result)
    if isinstance(result, Spectrum) and step is not None:
        assert result.interval_nm is not None and "resampled" in result.metadata
