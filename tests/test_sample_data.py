"""sc.sample_data: the bundled spectra by name, read through importlib.resources (works from a wheel)."""

from __future__ import annotations

import subprocess
import sys
import tomllib
import zipfile
from pathlib import Path

import numpy as np
import pytest

import spectrocolor as sc
from spectrocolor.errors import SpectrumError

ROOT = Path(__file__).resolve().parents[1]
DATA = ROOT / "src" / "spectrocolor" / "data"


def test_names():
    assert sc.sample_data_names() == ["colorchecker", "cie_tcs", "cie_ces", "crt_primaries",
                                      "alpha_opic_action_spectra"]


@pytest.mark.parametrize(("name", "shape", "first", "grid"), [
    ("colorchecker", (24, 36), "dark_skin", (380.0, 730.0)),
    ("cie_tcs", (14, 95), "TCS01", (360.0, 830.0)),
    ("cie_ces", (99, 401), "CES01", (380.0, 780.0)),
    ("crt_primaries", (3, 81), "red", (380.0, 780.0)),
    ("alpha_opic_action_spectra", (5, 401), "s_sc", (380.0, 780.0)),
])
def test_each_set(name, shape, first, grid):
    spectra = sc.sample_data(name)
    assert spectra.values.shape == shape
    assert spectra.names[0] == first
    assert (spectra.wavelengths_nm[0], spectra.wavelengths_nm[-1]) == grid
    assert spectra.metadata["sample_data"] == name and spectra.metadata["description"]
    assert np.all(np.isfinite(spectra.values))


def test_the_same_values_as_reading_the_file_in_the_clone():
    from_clone = sc.read_spectra(DATA / "reflectances_colorchecker_babel.csv")
    bundled = sc.sample_data("colorchecker")
    assert bundled.names == from_clone.names
    # exact: the same bytes parsed by the same reader (decimal text to the nearest double)
    np.testing.assert_array_equal(bundled.values, from_clone.values)
    # exact: the same bytes parsed by the same reader
    np.testing.assert_array_equal(bundled.wavelengths_nm, from_clone.wavelengths_nm)


def test_reflectances_are_fractions():
    for name in ("colorchecker", "cie_tcs", "cie_ces"):
        values = sc.sample_data(name).values
        assert 0.0 <= values.min() and values.max() <= 1.0, name


def test_spellings():
    reference = sc.sample_data("colorchecker").values
    for spelling in ("ColorChecker", " colorchecker ", "COLORCHECKER"):
        # exact: another spelling of the name reads the same file with the same reader
        np.testing.assert_array_equal(sc.sample_data(spelling).values, reference)
    # exact: the same file read twice by the same reader
    np.testing.assert_array_equal(sc.sample_data("CIE-TCS").values, sc.sample_data("cie_tcs").values)
    # exact: the same file read twice by the same reader
    np.testing.assert_array_equal(sc.sample_data("crt primaries").values, sc.sample_data("crt_primaries").values)


@pytest.mark.parametrize("name", ["tcs", "macbeth", "", "../PROVENANCE.md", "cmf_cie1931_2deg"])
def test_unknown_names_list_the_accepted_ones(name):
    with pytest.raises(SpectrumError) as raised:
        sc.sample_data(name)
    message = str(raised.value)
    assert repr(name) in message
    assert all(accepted in message for accepted in sc.sample_data_names())


def test_not_a_string():
    with pytest.raises(SpectrumError, match="must be a str"):
        sc.sample_data(3)


def test_the_face_stays_the_function_after_importing_the_module():
    """The module is not called ``sample_data``: importing a submodule binds it on the package."""
    import spectrocolor.samples  # noqa: F401

    assert callable(sc.sample_data) and sc.sample_data.__module__ == "spectrocolor.samples"


def test_every_file_is_packaged():
    """Each table is in the wheel's package data (pyproject.toml) and on disk."""
    from spectrocolor.samples import SAMPLE_DATA

    setuptools = tomllib.loads((ROOT / "pyproject.toml").read_text())["tool"]["setuptools"]
    patterns = setuptools["package-data"]["spectrocolor"]
    for file, _ in SAMPLE_DATA.values():
        assert (DATA / file).is_file(), file
        assert any(Path("data", file).match(pattern) for pattern in patterns), file


def test_reads_from_a_zipped_package(tmp_path):
    """importlib.resources, not a path next to the source: works where the package is a zip archive."""
    archive = tmp_path / "spectrocolor.zip"
    package = ROOT / "src" / "spectrocolor"
    with zipfile.ZipFile(archive, "w") as zipped:
        for path in package.rglob("*"):
            if path.is_file() and "__pycache__" not in path.parts and path.suffix in (".py", ".csv", ".md", ".pyi"):
                zipped.write(path, Path("spectrocolor") / path.relative_to(package))
    code = ("import spectrocolor as sc; s = sc.sample_data('cie_tcs'); "
            "assert '.zip' in sc.__file__, sc.__file__; print(s.values.shape)")
    done = subprocess.run([sys.executable, "-c", code], env={"PYTHONPATH": str(archive), "PATH": ""},
                          capture_output=True, text=True, timeout=120, cwd=tmp_path)
    assert done.returncode == 0, done.stderr[-2000:]
    assert done.stdout.strip() == "(14, 95)"
