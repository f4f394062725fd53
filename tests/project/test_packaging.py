"""Every data file and static asset of the package is declared in pyproject.toml's package-data,
so an installed wheel (not only an editable checkout) has it. The patterns are expanded the way
setuptools does (glob, ``*`` never crosses a ``/``, ``**`` does)."""

from __future__ import annotations

import tomllib
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
PACKAGE = ROOT / "src" / "spectrocolor"


def test_every_non_python_file_is_package_data():
    setuptools = tomllib.loads((ROOT / "pyproject.toml").read_text())["tool"]["setuptools"]
    declared = {p for pattern in setuptools["package-data"]["spectrocolor"] for p in PACKAGE.glob(pattern)}
    files = {p for p in PACKAGE.rglob("*")
             if p.is_file() and p.suffix not in (".py", ".pyc") and "__pycache__" not in p.parts}
    assert files, "no data files found"
    undeclared = sorted(p.relative_to(PACKAGE).as_posix() for p in files - declared)
    assert not undeclared, f"not in [tool.setuptools.package-data]: {undeclared}"


def test_the_license_file_matches_the_metadata_and_ships_with_the_package():
    project = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]
    assert project["license"] == "MIT"
    assert project["license-files"] == ["LICENSE"]
    assert (ROOT / "LICENSE").read_text().splitlines()[0] == "MIT License"


def test_the_package_says_it_is_typed():
    """PEP 561: editors and mypy read the package's own annotations only where py.typed ships."""
    setuptools = tomllib.loads((ROOT / "pyproject.toml").read_text())["tool"]["setuptools"]
    assert (PACKAGE / "py.typed").is_file()
    assert "py.typed" in setuptools["package-data"]["spectrocolor"]
    classifiers = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]["classifiers"]
    assert "Typing :: Typed" in classifiers


def _tracked_tree(destination: Path) -> Path:
    """A copy of the files git tracks (and untracked, unignored ones), as a fresh clone has them."""
    import shutil
    import subprocess

    listed = subprocess.run(["git", "ls-files", "--cached", "--others", "--exclude-standard", "-z"], cwd=ROOT,
                            capture_output=True, check=True).stdout.decode().split("\0")
    for name in filter(None, listed):
        source = ROOT / name
        if source.is_file():
            target = destination / name
            target.parent.mkdir(parents=True, exist_ok=True)
            shutil.copy2(source, target)
    return destination


def test_the_sdist_leaves_the_tests_out_cleanly_and_builds_the_same_wheel(tmp_path, monkeypatch):
    """MANIFEST.in prunes tests/ (the suite runs from the clone); the sdist's wheel has every package file."""
    import os
    import tarfile
    import zipfile

    from setuptools import build_meta

    tree = _tracked_tree(tmp_path / "clone")
    monkeypatch.chdir(tree)
    sdist = build_meta.build_sdist(str(tmp_path / "dist"))
    with tarfile.open(tmp_path / "dist" / sdist) as archive:
        names = [name.split("/", 1)[1] for name in archive.getnames() if "/" in name]
        archive.extractall(tmp_path / "unpacked", filter="data")
    assert not [n for n in names if n.startswith(("tests/", "docs/", "bench/", "tools/"))]
    assert {"LICENSE", "README.md", "pyproject.toml", "src/spectrocolor/py.typed"} <= set(names)
    sources = {p.relative_to(tree).as_posix() for p in (tree / "src" / "spectrocolor").rglob("*")
               if p.is_file() and "__pycache__" not in p.parts}
    assert sources <= set(names), sorted(sources - set(names))[:5]

    unpacked = tmp_path / "unpacked" / sdist.removesuffix(".tar.gz")
    monkeypatch.chdir(unpacked)
    os.makedirs(tmp_path / "wheel")
    wheel = build_meta.build_wheel(str(tmp_path / "wheel"))
    with zipfile.ZipFile(tmp_path / "wheel" / wheel) as archive:
        packaged = {name for name in archive.namelist() if name.startswith("spectrocolor/")}
    expected = {"spectrocolor/" + s.removeprefix("src/spectrocolor/") for s in sources}
    assert expected <= packaged, sorted(expected - packaged)[:5]
