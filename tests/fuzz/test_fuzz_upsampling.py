"""Fuzzing the upsampling readers and options: hostile input gets one clear error, never a crash."""

import numpy as np
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays
from PIL import Image

import spectrocolor as sc
from spectrocolor.cli import main
from spectrocolor.imagefiles import decode_png
from spectrocolor.upsampling import load_table, upsample
from spectrocolor.upsampling.fileformat import table_bytes
from upsampling_tables import rec2020_table, srgb_table

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
    np.testing.assert_array_equal(u.exact, inside)  # exact: booleans of the same comparisons with 0 and 1 on the input


def assert_exact_wherever_a_reflectance_exists(table, t):
    """Issue 27: inside the object-colour solid (the certified solver's own verdict) a query is
    exact, to 1e-9 relative (the settled paths are checked at 1e-10: see
    upsampling.moved_cells.EXACT_TOLERANCE), and every spectrum lies in [0, 1]."""
    u = upsample(table, t)
    q = t @ table.matrix.T
    solved = sc.smoothest_reflectance(q, illuminant="D65", wavelengths=(380, 780, 5))
    inside = np.asarray(solved.feasible) & np.asarray(solved.certificate.converged)
    assert u.reflectance.min() >= 0.0 and u.reflectance.max() <= 1.0
    np.testing.assert_array_equal(u.exact, inside)  # exact: booleans, the same verdict
    error = np.abs(u.reflectance @ table.weights - q).max(axis=-1)
    assert np.all(error[inside] <= 1e-9 * np.abs(q[inside]).max(axis=-1))


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.filter_too_much])
@given(arrays(np.float64, 3, elements=st.floats(-1.0, 1.0, allow_nan=False)),
       st.sampled_from([-1e-6, -1e-9, -1e-12, 0.0, 1e-12, 1e-9, 1e-6, 1e-3]))
def test_colours_near_the_solid_boundary_are_exact_when_inside(direction, depth):
    from spectrocolor.recovery.inputs import Setup
    from spectrocolor.recovery.zonotope import ray_exit

    table = rec2020_table()
    assume(np.abs(direction).max() > 1e-3)
    grey = table.matrix @ np.full(3, 0.5)
    d = table.matrix @ direction
    setup = Setup(table.wavelengths_nm, table.weights)
    reach = ray_exit(setup.solid, grey, d[None])[0]
    q = grey + (1.0 - depth) * reach * d  # relative depth `depth` below the boundary
    t = np.linalg.solve(table.matrix, q)
    assume(np.all((t >= 0.0) & (t <= 1.0)))
    assert_exact_wherever_a_reflectance_exists(table, t[None])


@settings(max_examples=40, deadline=None)
@given(arrays(np.int64, 3, elements=st.integers(0, 4)),
       arrays(np.float64, 3, elements=st.sampled_from([0.0, 1e-15, -1e-15, 1e-12, -1e-12, 1e-9, -1e-9])))
def test_cell_corners_and_their_neighbourhood_are_exact_when_inside(corner, offset):
    table = rec2020_table()  # 5 nodes per axis: corners at multiples of 1/4
    t = np.clip(corner / 4.0 + offset, 0.0, 1.0)
    assert_exact_wherever_a_reflectance_exists(table, t[None])


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


def valid_png() -> bytes:
    """A 16-bit RGB PNG of 3 x 4 pixels from the project's writer (imagecodecs, unfiltered)."""
    import tempfile
    from pathlib import Path

    from spectrocolor.imagefiles import write_image

    codes = (np.arange(36, dtype=np.uint16).reshape(3, 4, 3) * 1801)
    with tempfile.TemporaryDirectory() as folder:
        return write_image(Path(folder) / "valid.png", codes).read_bytes()


@settings(max_examples=150, deadline=None)
@given(st.data())
def test_damaged_png_files_are_refused_with_one_error(data):
    raw = bytearray(valid_png())
    for _ in range(data.draw(st.integers(1, 4))):
        at = data.draw(st.integers(0, len(raw) - 1))
        raw[at] = data.draw(st.integers(0, 255))
    if data.draw(st.booleans()):
        raw = raw[:data.draw(st.integers(0, len(raw)))]
    try:
        codes = decode_png(bytes(raw), "fuzz.png")
    except sc.SpectrumError as exc:
        assert str(exc).startswith("fuzz.png: ")
        return
    # a CRC-32 guards every chunk: only an unchanged file is read back
    assert bytes(raw) == valid_png()
    assert codes.shape == (3, 4, 3) and codes.dtype == np.uint16


@settings(max_examples=100, deadline=None)
@given(st.binary(max_size=300))
def test_random_bytes_after_a_png_signature_are_refused(tail):
    try:
        decode_png(b"\x89PNG\r\n\x1a\n" + tail, "noise.png")
    except sc.SpectrumError as exc:
        assert "noise.png" in str(exc)
    else:  # pragma: no cover - random bytes never form chunks with matching CRCs and an IEND
        raise AssertionError("random bytes were decoded as a PNG")


@settings(max_examples=80, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(st.data())
def test_damaged_texel_files_are_refused_or_read_whole(tmp_path, data):
    from spectrocolor.upsampling.texels import load_texel_coefficients, texel_bytes

    valid = texel_bytes(srgb_table(), np.full((2, 3, 3), 0.3))
    raw = bytearray(valid)
    for _ in range(data.draw(st.integers(1, 4))):
        at = data.draw(st.integers(0, len(raw) - 1))
        raw[at] = data.draw(st.integers(0, 255))
    if data.draw(st.booleans()):
        raw = raw[:data.draw(st.integers(0, len(raw)))]
    path = tmp_path / "fuzz.sctx"
    path.write_bytes(bytes(raw))
    try:
        found = load_texel_coefficients(path)
    except sc.SpectrumError as exc:
        assert str(path) in str(exc)
        return
    assert bytes(raw) == valid  # a CRC-32 guards the file: only the unchanged one is read
    assert found.nodes.shape == (2, 3, 4)


@settings(max_examples=20, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(source=st.sampled_from(["D65", "A", "", "X1", "--x"]), resolution=st.integers(-3, 70),
       strategy=st.sampled_from(["toward-grey", "clip", "nan"]))
def test_cli_upsample_options_fuzz(tmp_path, capsys, source, resolution, strategy):
    texture = tmp_path / "tex.png"
    if not texture.exists():
        Image.fromarray(np.full((2, 3, 3), 90, np.uint8)).save(texture)
    out = tmp_path / "out.sctx"
    try:
        code = main(["upsample", str(texture), "--coefficients", str(out), "--from", source,
                     "--resolution", str(min(resolution, 4) if resolution > 1 else resolution),
                     "--out-of-range", strategy, "--force"])
    except SystemExit as exc:  # argparse: a value it cannot parse ("nan" is not offered)
        code = exc.code
    err = capsys.readouterr().err
    assert code in (0, 2) and "Traceback" not in err
    if code == 0:
        assert out.exists()
