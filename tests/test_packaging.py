"""Every data file and static asset of the package is declared in pyproject.toml's package-data,
so an installed wheel (not only an editable checkout) has it. The patterns are expanded the way
setuptools does (glob, ``*`` never crosses a ``/``, ``**`` does)."""

from __future__ import annotations

import tomllib
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
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
