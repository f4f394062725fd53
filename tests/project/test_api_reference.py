"""The API reference documents every public name, and the docs are built to check every reference.

Public names: the package face ``spectrocolor._PUBLIC`` and the ``__all__`` of every subpackage.
Each must be the object of an autodoc directive (``autofunction``, ``autoclass``, ``autodata``,
``automodule … :members:``) in the reference pages that ``docs/api/conf.py`` writes (from
``docs/api/reference_pages.py``) or in the hand-written sources (``docs/api/*.rst``, the guides).
The pages are generated here without Sphinx and parsed; nothing is built, so this stays fast.
"""

from __future__ import annotations

import importlib
import importlib.util
import inspect
import re
from pathlib import Path

import pytest

import spectrocolor

ROOT = Path(__file__).resolve().parents[2]
DOCS = ROOT / "docs"
DIRECTIVE = re.compile(
    r"^(?:\.\. |```\{)(?P<kind>py:module|currentmodule|module|automodule|autoclass|autofunction|autodata|"
    r"autoexception|automethod|autoattribute)(?:::|\})\s*(?P<target>\S+)(?P<options>(?:\n[ \t]+:[\w-]+:.*)*)",
    re.MULTILINE,
)


def _reference_pages():
    spec = importlib.util.spec_from_file_location("reference_pages", DOCS / "api" / "reference_pages.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def documented(text: str) -> set[tuple[str, str]]:
    """(module, name) of every object that the autodoc directives of one source document."""
    names: set[tuple[str, str]] = set()
    current = ""
    for match in DIRECTIVE.finditer(text):
        kind, target = match["kind"], match["target"]
        if kind in ("py:module", "currentmodule", "module"):
            current = target
        elif kind == "automodule":
            if ":members:" in match["options"] and ":no-index:" not in match["options"]:
                module = importlib.import_module(target)
                names |= {(target, name) for name in getattr(module, "__all__", ())}
                names |= {(target, name) for name, obj in vars(module).items()
                          if not name.startswith("_") and getattr(obj, "__module__", None) == target}
        elif target.startswith("spectrocolor."):
            names.add(tuple(target.rsplit(".", 1)))
        else:
            names.add((current, target))
    return names


def resolve(module: str, name: str):
    """The object as autodoc finds it: the module imported, then the name looked up in it."""
    obj = importlib.import_module(module)
    for part in name.split("."):
        obj = getattr(obj, part)
    return obj


def public_names() -> dict[str, object]:
    """``spectrocolor.X`` for the face and ``spectrocolor.sub.X`` for each subpackage -> object."""
    names = {f"spectrocolor.{name}": getattr(spectrocolor, name) for name in spectrocolor._PUBLIC}
    for package in _reference_pages().subpackages():
        for name in getattr(package, "__all__", ()):
            names[f"{package.__name__}.{name}"] = getattr(package, name)
    return names


@pytest.fixture(scope="module")
def documented_objects() -> dict[tuple, str]:
    pages = _reference_pages().reference_pages()
    texts = [*pages.values(), *(path.read_text(encoding="utf-8") for path in (DOCS / "api").glob("*.rst")),
             *(path.read_text(encoding="utf-8") for path in DOCS.glob("*.md"))]
    found: dict[tuple, str] = {}
    for text in texts:
        for module, name in documented(text):
            obj = resolve(module, name)
            found[(id(obj), name.rsplit(".", 1)[-1])] = f"{module}.{name}"
            if inspect.isclass(obj) or inspect.isroutine(obj):
                found[(id(obj), None)] = f"{module}.{name}"
    return found


def test_every_public_name_is_in_the_reference(documented_objects):
    names = public_names()
    assert len(names) > 200
    missing = sorted(
        dotted for dotted, obj in names.items()
        if (id(obj), None) not in documented_objects and (id(obj), dotted.rsplit(".", 1)[1]) not in documented_objects
    )
    assert not missing, f"{len(missing)} public names are not in the API reference: {missing}"


def test_the_guides_import_only_documented_names(documented_objects):
    """``from spectrocolor.x import a, b`` in a guide: each of a, b is documented."""
    imported = re.compile(r"^from (spectrocolor[\w.]*) import (?:\(([^)]*)\)|([^\n#]+))", re.MULTILINE)
    undocumented = []
    for page in DOCS.glob("*.md"):
        for module, in_parentheses, on_the_line in imported.findall(page.read_text(encoding="utf-8")):
            for name in (n.split(" as ")[0].strip() for n in (in_parentheses or on_the_line).split(",")):
                if name:
                    obj = getattr(importlib.import_module(module), name)
                    if inspect.ismodule(obj):
                        continue
                    if (id(obj), None) not in documented_objects and (id(obj), name) not in documented_objects:
                        undocumented.append(f"{page.name}: {module}.{name}")
    assert not undocumented, undocumented


def test_each_name_is_documented_once():
    pages = _reference_pages().reference_pages()
    seen: dict[tuple, str] = {}
    for text in pages.values():
        for module, name in documented(text):
            obj = resolve(module, name)
            key = (id(obj),) if inspect.isclass(obj) or inspect.isroutine(obj) else (id(obj), name)
            assert key not in seen, f"{module}.{name} is documented twice (also as {seen[key]})"
            seen[key] = f"{module}.{name}"


def test_the_build_checks_every_reference():
    conf = (DOCS / "api" / "conf.py").read_text(encoding="utf-8")
    assert re.search(r"^nitpicky = True$", conf, re.MULTILINE)
    assert "xref_missing" not in conf and "ref.python" not in conf and "ref.class" not in conf
    makefile = (ROOT / "Makefile").read_text(encoding="utf-8")
    assert re.search(r"sphinx-build .*-W", makefile)
    # nitpick_ignore names other projects only
    ignored = re.search(r"^nitpick_ignore = \[(.*?)^\]", conf, re.MULTILINE | re.DOTALL)[1]
    assert "spectrocolor" not in ignored


def test_the_guides_are_in_reading_order_after_getting_started():
    index = (DOCS / "api" / "index.rst").read_text(encoding="utf-8")
    listed = re.findall(r"^   guides/(\S+)$", index, re.MULTILINE)
    assert listed[0] == "getting-started"
    assert sorted(listed) == sorted(path.stem for path in DOCS.glob("*.md")), "every guide once in the toctree"
    assert listed != sorted(listed)  # an order chosen for reading, not the file names'
