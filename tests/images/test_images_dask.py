"""The xarray accessor on dask: lazy until computed, runs on a real dask.distributed
LocalCluster with 2 workers, and equals the NumPy path (no seams at chunk boundaries)."""

from __future__ import annotations

import pickle
import threading

import numpy as np
import pytest

da = pytest.importorskip("dask.array")
distributed = pytest.importorskip("distributed")
xr = pytest.importorskip("xarray")

import dask  # noqa: E402

from spectrocolor.errors import SpectrumError  # noqa: E402
from spectrocolor.images import (  # noqa: E402
    cube_to_lab,
    cube_to_rgb,
    cube_to_xyz,
    read_cube,
)

WAVELENGTHS = np.arange(400.0, 701.0, 10.0)
pytestmark = pytest.mark.cluster


def _cube(shape=(23, 17), seed=1) -> np.ndarray:
    rng = np.random.default_rng(seed)
    centres = rng.uniform(400, 700, size=(*shape, 2, 1))
    bumps = rng.uniform(0, 0.45, size=(*shape, 2, 1)) * np.exp(
        -0.5 * ((WAVELENGTHS - centres) / 35.0) ** 2)
    return 0.02 + bumps.sum(axis=-2)


def _array(values, chunks) -> xr.DataArray:
    return xr.DataArray(
        da.from_array(values, chunks=chunks), dims=("y", "x", "wavelength"),
        coords={"wavelength": ("wavelength", WAVELENGTHS, {"units": "nm"})})


@pytest.fixture(scope="module")
def client():
    cluster = distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=False,
                                       dashboard_address=":0")
    with distributed.Client(cluster) as client:
        yield client
    cluster.close()


_calls = {"n": 0}
_lock = threading.Lock()


def _counted(block):
    with _lock:
        _calls["n"] += 1
    return block


def test_lazy_until_computed(client):
    values = _cube()
    source = da.from_array(values, chunks=(8, 6, -1)).map_blocks(_counted, dtype=values.dtype)
    cube = xr.DataArray(source, dims=("y", "x", "wavelength"), coords={"wavelength": WAVELENGTHS})
    _calls["n"] = 0
    XYZ = cube.spectro.to_xyz(illuminant="D65")
    lab = cube.spectro.to_lab(illuminant="D65")
    rgb = cube.spectro.to_rgb(illuminant="D65")
    assert _calls["n"] == 0  # nothing ran
    for result in (XYZ, lab, rgb):
        assert isinstance(result.data, da.Array)
    assert XYZ.dims == ("y", "x", "XYZ") and list(XYZ["XYZ"].values) == ["X", "Y", "Z"]
    XYZ.compute()
    assert _calls["n"] == 9  # 3 x 3 chunks, each read once


@pytest.mark.parametrize("chunks", [(8, 6, -1), (1, 17, -1), (23, 1, -1), (5, 4, 31)])
def test_cluster_equals_numpy_path(client, chunks):
    values = _cube()
    cube = _array(values, chunks)
    XYZ, lab, rgb8, rgb16 = dask.compute(
        cube.spectro.to_xyz(illuminant="D65"),
        cube.spectro.to_lab(illuminant="A", observer="1964"),
        cube.spectro.to_rgb(illuminant="C", gamut="preserve-luminance", exposure=1.3),
        cube.spectro.to_rgb(illuminant="C", bit_depth=16, space="Display P3"),
    )
    np.testing.assert_allclose(XYZ.values, cube_to_xyz(values, WAVELENGTHS, illuminant="D65"),
                               rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(
        lab.values, cube_to_lab(values, WAVELENGTHS, illuminant="A", observer="1964"),
        rtol=1e-12, atol=1e-12)
    # exact: codes of floats that agree to ~1e-13: a code moves only at a half-code tie, which these inputs do not
    # reach (dask chunks split rows)
    np.testing.assert_array_equal(
        rgb8.values, cube_to_rgb(values, WAVELENGTHS, illuminant="C",
                                 gamut="preserve-luminance", exposure=1.3))
    # exact: codes of floats that agree to ~1e-13: a code moves only at a half-code tie, which these inputs do not
    # reach (dask chunks split rows)
    np.testing.assert_array_equal(
        rgb16.values, cube_to_rgb(values, WAVELENGTHS, illuminant="C", bit_depth=16,
                                  space="Display P3"))
    assert rgb8.dtype == np.uint8 and rgb16.dtype == np.uint16


def test_no_seams_between_chunks(client):
    """A smooth horizontal gradient: adjacent pixels across a chunk edge differ no more than
    adjacent pixels inside a chunk."""
    ramp = np.linspace(0.05, 0.95, 40)[None, :, None] * np.ones((6, 40, WAVELENGTHS.size))
    XYZ = _array(ramp, (3, 7, -1)).spectro.to_xyz(illuminant="D65").compute().values
    steps = np.diff(XYZ[..., 1], axis=1)
    np.testing.assert_allclose(steps, steps[0, 0], rtol=1e-9)


def test_wavelength_split_across_chunks_is_an_error(client):
    cube = _array(_cube(), (8, 6, 10))
    with pytest.raises(SpectrumError, match=r"rechunk first with array.chunk\(\{'wavelength'"):
        cube.spectro.to_xyz(illuminant="D65")
    rechunked = cube.chunk({"wavelength": -1}).spectro.to_xyz(illuminant="D65").compute()
    np.testing.assert_allclose(rechunked.values,
                               cube_to_xyz(_cube(), WAVELENGTHS, illuminant="D65"), rtol=1e-12)


def test_wavelength_coordinate_in_micrometres(client):
    values = _cube((4, 3))
    cube = xr.DataArray(values, dims=("row", "col", "wavelength"),
                        coords={"wavelength": ("wavelength", WAVELENGTHS / 1000,
                                               {"units": "um"})})
    np.testing.assert_allclose(cube.spectro.to_xyz(illuminant="D65").values,
                               cube_to_xyz(values, WAVELENGTHS, illuminant="D65"), rtol=1e-12)
    bad = cube.assign_coords(wavelength=("wavelength", WAVELENGTHS, {"units": "furlong"}))
    with pytest.raises(SpectrumError, match="unknown wavelength units 'furlong'"):
        bad.spectro.to_xyz(illuminant="D65")
    with pytest.raises(SpectrumError, match="no 'wavelength' dimension"):
        cube.rename(wavelength="band").spectro.to_xyz(illuminant="D65")


def test_disk_cube_ships_as_a_reference(client, tmp_path):
    values = _cube((30, 20)).astype(np.float32)
    raw = tmp_path / "scene.img"
    np.ascontiguousarray(values, "<f4").tofile(raw)  # BIP
    (tmp_path / "scene.hdr").write_text(
        "ENVI\nsamples = 20\nlines = 30\nbands = 31\ndata type = 4\ninterleave = bip\n"
        "byte order = 0\nwavelength units = nm\nwavelength = {"
        + ", ".join(f"{w:g}" for w in WAVELENGTHS) + "}\n")
    cube = read_cube(tmp_path / "scene.hdr").to_xarray(chunks=(8, 8))
    graph = dict(cube.data.__dask_graph__())
    assert len(pickle.dumps(graph)) < values.nbytes / 4  # no data in the graph
    XYZ = client.compute(cube.spectro.to_xyz(illuminant="D65")).result()
    np.testing.assert_allclose(XYZ.values, cube_to_xyz(values, WAVELENGTHS, illuminant="D65"),
                               rtol=1e-12, atol=1e-12)


@pytest.mark.slow
def test_process_workers_read_the_file_themselves(tmp_path):
    """Two worker processes: functions, weights and the on-disk cube pickle across."""
    values = _cube((16, 12)).astype(np.float32)
    np.save(tmp_path / "cube.npy", values)
    cube = read_cube(tmp_path / "cube.npy", wavelengths_nm=WAVELENGTHS).to_xarray(chunks=(5, 5))
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=":0") as cluster, \
            distributed.Client(cluster) as client:
        rgb = client.compute(cube.spectro.to_rgb(illuminant="D65")).result()
        workers = client.run(lambda: __import__("os").getpid())
    assert len(set(workers.values())) == 2
    # exact: codes of floats that agree to ~1e-13: a code moves only at a half-code tie, which these inputs do not
    # reach (dask chunks split rows)
    np.testing.assert_array_equal(rgb.values, cube_to_rgb(values, WAVELENGTHS, illuminant="D65"))


def test_cli_image_on_the_cluster(client, tmp_path, capsys):
    from PIL import Image

    from spectrocolor.cli import main

    values = _cube((21, 13))
    np.savez(tmp_path / "cube.npz", values=values, wavelengths_nm=WAVELENGTHS)
    out = tmp_path / "rgb.png"
    code = main(["image", str(tmp_path / "cube.npz"), "--illuminant", "D65", "--out", str(out),
                 "--scheduler", client.scheduler.address, "--chunks", "8,5"])
    assert code == 0, capsys.readouterr().err
    with Image.open(out) as image:
        # exact: codes of floats that agree to ~1e-13: a code moves only at a half-code tie, which these inputs do not
        # reach (dask chunks split rows)
        np.testing.assert_array_equal(np.asarray(image),
                                      cube_to_rgb(values, WAVELENGTHS, illuminant="D65"))
