"""Every Python snippet in README.md and docs/*.md runs, and so does every README command.

The Python blocks of one page run in order in one namespace (a page reads as one session), in a
scratch directory that holds the files the pages name: ``samples.csv`` and ``samples_10nm.csv``
(the bundled ColorChecker reflectances, 380-730 nm at 10 nm), ``cube.npy``, ``scene.hdr`` (ENVI)
and ``scene.nc`` (the same small reflectance cube, 400-700 nm at 10 nm), ``lamp.csv`` (CIE FL2),
``photo.png`` (an sRGB picture of the cube) and ``src/`` (the repository's own, so paths such as
``src/spectrocolor/data/...`` resolve as they do from a clone). A page whose snippet raises, or
prints a result its comment contradicts, fails here.

The README's console blocks run as a reader runs them after ``make run`` or ``make test``: in
order, as one bash session, in a folder that looks like the clone (``src``, ``tests`` and
``.venv``, the environment running these tests), with that environment *not* on PATH, so that
the README's own ``source .venv/bin/activate`` is what puts ``spectrocolor`` there. The README
makes its own example inputs; ``make …`` lines are left out (``tests/project/test_make_run.py`` checks
them) and ``spectrocolor app`` runs with ``--help`` (it serves until stopped). Each command must
succeed, and output the README shows (``…`` for what it leaves out) must be what it prints.
"""

from __future__ import annotations

import os
import re
import shlex
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[2]
PAGES = [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]
FENCE = re.compile(r"^```python\n(.*?)^```", re.MULTILINE | re.DOTALL)
CONSOLE = re.compile(r"^```console\n(.*?)^```", re.MULTILINE | re.DOTALL)


def python_blocks(page: Path) -> list[str]:
    """The ```python blocks of a Markdown page, in order."""
    return FENCE.findall(page.read_text(encoding="utf-8"))


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


def console_session(page: Path) -> list[tuple[str, list[str]]]:
    """The ``$ …`` commands of a page's console blocks, in order, each with the output lines the
    page shows after it."""
    session: list[tuple[str, list[str]]] = []
    for block in CONSOLE.findall(page.read_text(encoding="utf-8")):
        for line in block.splitlines():
            if line.startswith("$ "):
                session.append((line[2:], []))
            elif line.strip() and session:
                session[-1][1].append(line)
    return session


def runnable(command: str) -> str | None:
    """The command as the test runs it: None for ``make …``, ``--help`` added to ``… app …``."""
    words = shlex.split(command, comments=True)
    if words[0] == "make":
        return None
    if len(words) > 1 and words[0].endswith("spectrocolor") and words[1] == "app":
        return shlex.join([*words, "--help"])
    return command


def normalised(text: str) -> str:
    return " ".join(text.split())


def shown_output_matches(shown: list[str], printed: str) -> list[str]:
    """The shown lines (``…`` standing for anything) that no printed line matches."""
    printed_lines = [normalised(line) for line in printed.splitlines()]
    missing = []
    for line in shown:
        pieces = [normalised(piece) for piece in line.split("…") if piece.strip()]
        if pieces and not any(all(piece in out for piece in pieces) for out in printed_lines):
            missing.append(line)
    return missing


def test_readme_never_offers_the_package_index():
    text = (ROOT / "README.md").read_text(encoding="utf-8")
    assert not re.search(r"pip install [\"']?spectrocolor\b", text), \
        "spectrocolor is not on the package index: install the clone (pip install /path/to/spectrocolor)"


@pytest.mark.slow
def test_readme_commands_run_as_written(tmp_path):
    """Every command of the README's console blocks runs, in order, as a reader runs them."""
    venv = Path(sys.executable).parent.parent
    if not (venv / "bin" / "activate").is_file():
        pytest.skip(f"the tests do not run in a virtual environment ({sys.executable})")
    clone = tmp_path / "clone"
    clone.mkdir()
    for name, target in (("src", ROOT / "src"), ("tests", ROOT / "tests"), (".venv", venv)):
        os.symlink(target, clone / name)
    session = [(runnable(command), shown) for command, shown in console_session(ROOT / "README.md")]
    session = [(command, shown) for command, shown in session if command is not None]
    assert sum("spectrocolor " in command for command, _ in session) >= 12
    mark = "@@ README command "
    script = ["set -e"]
    for number, (command, _) in enumerate(session):
        script += [f"echo '{mark}{number}'", command]
    outside = {str(venv / "bin"), str(Path(sys.executable).parent)}
    env = {k: v for k, v in os.environ.items()
           if k not in ("VIRTUAL_ENV", "SPECTROCOLOR_MAKE_RUN", "PYTHONHOME")}
    env["PATH"] = os.pathsep.join(p for p in env.get("PATH", "").split(os.pathsep) if p not in outside)
    env["MPLBACKEND"] = "Agg"
    done = subprocess.run(["bash", "-c", "\n".join(script)], cwd=clone, env=env, capture_output=True,
                          text=True, timeout=900, stdin=subprocess.DEVNULL)
    parts = re.split(rf"^{re.escape(mark)}(\d+)\n", done.stdout, flags=re.MULTILINE)
    printed = {int(number): text for number, text in zip(parts[1::2], parts[2::2], strict=True)}
    if done.returncode != 0:
        failed = max(printed, default=0)
        pytest.fail(f"README command failed (status {done.returncode}): $ {session[failed][0]}\n"
                    f"{done.stderr[-2000:]}")
    assert len(printed) == len(session)
    for number, (command, shown) in enumerate(session):
        missing = shown_output_matches(shown, printed[number])
        assert not missing, f"$ {command} printed no line like {missing[0]!r}:\n{printed[number]}"
