"""Every Python snippet in README.md and docs/*.md runs, against the data the package ships.

The blocks of one page run in order in one namespace (a page reads as one session), in a scratch
directory that holds the files the pages name (the README's commands run there too):
``samples.csv`` and ``samples_10nm.csv`` (the
bundled ColorChecker reflectances, 380-730 nm at 10 nm), ``cube.npy``, ``scene.hdr`` (ENVI) and
``scene.nc`` (the same small reflectance cube, 400-700 nm at 10 nm), ``lamp.csv`` (CIE FL2),
``photo.png`` (an sRGB picture of the cube) and ``src/`` (the repository's
own, so paths such as ``src/spectrocolor/data/...`` resolve as they do from a clone).
A page whose snippet raises, or prints a result its comment contradicts, fails here.
"""

from __future__ import annotations

import os
import re
import shlex
import shutil
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[1]
PAGES = [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]
FENCE = re.compile(r"^```python\n(.*?)^```", re.MULTILINE | re.DOTALL)
CONSOLE = re.compile(r"^```console\n(.*?)^```", re.MULTILINE | re.DOTALL)


def python_blocks(page: Path) -> list[str]:
    """The ```python blocks of a Markdown page, in order."""
    return FENCE.findall(page.read_text(encoding="utf-8"))


def console_commands(page: Path) -> list[list[str]]:
    """The ``$ spectrocolor …`` lines of a page's console blocks as argument lists (not ``app``,
    which serves until stopped)."""
    commands = []
    for block in CONSOLE.findall(page.read_text(encoding="utf-8")):
        for line in block.splitlines():
            words = shlex.split(line, comments=True)
            if len(words) > 2 and words[0] == "$" and words[1].endswith("spectrocolor") and words[2] != "app":
                commands.append(words[2:])
    return commands


def test_the_pages_have_snippets_to_run():
    assert sum(len(python_blocks(page)) for page in PAGES) >= 8


def write_envi(header_path: Path, cube: np.ndarray, wavelengths_nm: np.ndarray) -> None:
    """A minimal ENVI pair: ``scene.hdr`` and the raw band-interleaved-by-pixel float32 data."""
    lines, samples, bands = cube.shape
    cube.astype("<f4").tofile(header_path.with_suffix(".img"))
    header_path.write_text(
        "ENVI\n"
        f"samples = {samples}\nlines = {lines}\nbands = {bands}\nheader offset = 0\n"
        "file type = ENVI Standard\ndata type = 4\ninterleave = bip\nbyte order = 0\n"
        "wavelength units = Nanometers\n"
        "wavelength = {" + ", ".join(f"{w:g}" for w in wavelengths_nm) + "}\n"
    )


def write_netcdf(path: Path, cube: np.ndarray, wavelengths_nm: np.ndarray) -> None:
    """The cube as a netCDF-4 DataArray with a ``wavelength`` coordinate in nm."""
    xr = pytest.importorskip("xarray")
    array = xr.DataArray(cube, dims=("y", "x", "wavelength"), coords={"wavelength": wavelengths_nm}, name="reflectance")
    array["wavelength"].attrs["units"] = "nm"
    array.to_netcdf(path, engine="h5netcdf")


@pytest.fixture
def scratch(tmp_path, monkeypatch):
    for name in ("samples.csv", "samples_10nm.csv"):
        shutil.copy(ROOT / "src/spectrocolor/data/reflectances_colorchecker_babel.csv", tmp_path / name)
    cube = np.random.default_rng(7).uniform(0.05, 0.95, size=(6, 8, 31))
    wavelengths_nm = np.arange(400.0, 701.0, 10.0)
    np.save(tmp_path / "cube.npy", cube)
    import spectrocolor as sc

    sc.write_spectra(sc.illuminant("FL2", sc.wavelength_grid(380, 780, 5)), tmp_path / "lamp.csv")
    pil = pytest.importorskip("PIL.Image")
    pil.fromarray((cube[..., [25, 15, 5]] * 255).astype(np.uint8)).save(tmp_path / "photo.png")
    write_envi(tmp_path / "scene.hdr", cube, wavelengths_nm)
    write_netcdf(tmp_path / "scene.nc", cube, wavelengths_nm)
    os.symlink(ROOT / "src", tmp_path / "src")
    monkeypatch.chdir(tmp_path)
    monkeypatch.setenv("MPLBACKEND", "Agg")
    return tmp_path


@pytest.mark.parametrize("page", [p for p in PAGES if python_blocks(p)], ids=lambda p: p.name)
def test_page_snippets_run(page, scratch, capsys):
    namespace: dict = {"__name__": f"snippets_of_{page.stem}"}
    for number, block in enumerate(python_blocks(page), start=1):
        code = compile(block, f"{page.name} (python block {number})", "exec")
        exec(code, namespace)  # noqa: S102 - the documentation's own examples
    capsys.readouterr()


def test_readme_commands_run(scratch, capsys):
    """Every command the README shows runs as written, on the shipped data, and succeeds."""
    from spectrocolor.cli import main

    commands = console_commands(ROOT / "README.md")
    assert len(commands) >= 10
    for words in commands:
        assert main(words) == 0, f"spectrocolor {' '.join(words)}: {capsys.readouterr().err}"
