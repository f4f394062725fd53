"""Fuzzing the upsampling readers and options: hostile input gets one clear error, never a crash."""

import numpy as np
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays
from PIL import Image

import spectrocolor as sc
from spectrocolor.cli import main
from spectrocolor.upsampling import load_table, upsample
from spectrocolor.upsampling.fileformat import table_bytes
from upsampling_tables import srgb_table

VALID = None


def valid_bytes() -> bytes:
    global VALID
    if VALID is None:
        from spectrocolor.upsampling import upsampling_table

        VALID = table_bytes(upsampling_table(resolution=2, measure_excess=False))
    return VALID


@settings(max_examples=80, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(st.binary(max_size=400))
def test_random_bytes_are_refused_cleanly(tmp_path, data):
    path = tmp_path / "fuzz.scup"
    path.write_bytes(data)
    try:
        load_table(path)
    except sc.SpectrumError as exc:
        assert str(path) in str(exc)
    else:  # pragma: no cover - random bytes never form a valid table with a matching CRC
        raise AssertionError("random bytes were accepted as a table")


@settings(max_examples=80, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(st.data())
def test_mutated_tables_are_refused_or_read_whole(tmp_path, data):
    raw = bytearray(valid_bytes())
    for _ in range(data.draw(st.integers(1, 4))):
        at = data.draw(st.integers(0, len(raw) - 1))
        raw[at] = data.draw(st.integers(0, 255))
    if data.draw(st.booleans()):
        raw = raw[:data.draw(st.integers(0, len(raw)))]
    path = tmp_path / "mutated.scup"
    path.write_bytes(bytes(raw))
    try:
        table = load_table(path)
    except sc.SpectrumError:
        return
    # only an unchanged file (a mutation that rewrote a byte with itself) may be read
    assert bytes(raw) == valid_bytes()
    assert table.resolution == 2


@settings(max_examples=60, deadline=None)
@given(arrays(np.float64, st.tuples(st.integers(1, 6), st.just(3)),
              elements=st.floats(allow_nan=True, allow_infinity=True, width=64)))
def test_any_floats_give_bounded_spectra_or_one_error(values):
    table = srgb_table()
    try:
        u = upsample(table, values)
    except sc.ColorimetryError as exc:
        assert "rgb_linear" in str(exc)
        assert not np.all(np.isfinite(values))
        return
    assert u.reflectance.min() >= 0.0 and u.reflectance.max() <= 1.0
    inside = np.all((values >= 0) & (values <= 1), axis=-1)
    np.testing.assert_array_equal(u.exact, inside)


@settings(max_examples=25, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(to=st.text(max_size=12), adapt=st.sampled_from(["none", "bradford", "cat16"]),
       strategy=st.sampled_from(["toward-grey", "clip"]))
def test_cli_options_fuzz(tmp_path, capsys, to, adapt, strategy):
    source = tmp_path / "in.png"
    if not source.exists():
        Image.fromarray(np.full((3, 4, 3), 200, np.uint8)).save(source)
    out = tmp_path / "out.png"
    try:
        code = main(["relight", str(source), "--to", to, "--adapt", adapt, "--resolution", "2",
                     "--out-of-range", strategy, "--force", "--out", str(out)])
    except SystemExit as exc:  # argparse: an option value it cannot parse (e.g. "--x")
        code = exc.code
    err = capsys.readouterr().err
    assert code in (0, 2)
    assert "Traceback" not in err
    if code == 0:
        assert out.exists()
