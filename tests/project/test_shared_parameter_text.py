"""Shared parameter text is written once, in the glossary, not pasted (issue 24, part 6).

The meaning of a parameter that many functions share (an illuminant, an observer, a wavelength
grid, the memory budget, percent or fraction, the atomic write behind every writer) is defined
once, in ``docs/glossary.md``; a docstring says in one line what the parameter means *for that
function* and links the definition with ``:term:``. This test keeps it so. Over every public
function, class and method of every module of the package (names without a leading underscore,
defined in that module), it reads the numpydoc sections that describe entries (Parameters, Other
Parameters, Returns, Yields, Raises, Warns, Attributes) and fails

* when two entries carry the same description of :data:`MIN_SHARED_LINES` or more lines
  (whitespace folded), naming both places: a third copy of a text would be the next paste;
* when an entry named like a glossary term (:data:`GLOSSARY_NAMES`) has a description longer than
  :data:`MAX_UNLINKED_LINES` lines without a ``:term:`` link: a long unlinked text is the
  definition written again;
* when a ``:term:`` in any docstring of the package names no term of the glossary (Sphinx, with
  ``nitpicky``, fails on it too, but only when the docs are built).

``MIN_SHARED_LINES`` is 2 description lines, i.e. an entry of three lines with its type line:
a one-line description (``The grid, nm.``) is short enough to say again; two lines or more are a
paragraph that wants one home.
"""

from __future__ import annotations

import importlib
import inspect
import pkgutil
import re
import textwrap
from collections import defaultdict
from collections.abc import Iterator
from pathlib import Path

import spectrocolor

ROOT = Path(__file__).resolve().parents[2]
GLOSSARY = ROOT / "docs" / "glossary.md"

#: Sections whose entries are ``name : type`` (or a type alone) followed by an indented description.
ENTRY_SECTIONS = ("Parameters", "Other Parameters", "Returns", "Yields", "Raises", "Warns", "Attributes")
#: Two entries with the same description of at least this many (non-blank) lines are a paste.
MIN_SHARED_LINES = 2
#: An entry named like a glossary term may describe itself in this many lines without a link.
MAX_UNLINKED_LINES = 1
#: Entry names (parameters, and the exception every atomic writer raises) -> the glossary term
#: that defines what they share.
GLOSSARY_NAMES = {
    "illuminant": "illuminant",
    "second_illuminant": "illuminant",
    "observer": "observer",
    "wavelengths": "wavelength grid",
    "wavelengths_nm": "wavelength grid",
    "memory_budget": "memory budget",
    "max_block_mib": "block",
    "percent": "percent",
    "OutputError": "atomic write",
}

_UNDERLINE = re.compile(r"^\s*-{3,}\s*$")
_TERM = re.compile(r":term:`([^`]+)`")


def sections(doc: str) -> dict[str, list[str]]:
    """``{section title: lines}`` of a numpydoc docstring (the summary is under ``""``)."""
    lines = inspect.cleandoc(doc or "").splitlines()
    out: dict[str, list[str]] = {"": []}
    title = ""
    index = 0
    while index < len(lines):
        if index + 1 < len(lines) and lines[index].strip() and _UNDERLINE.match(lines[index + 1]):
            title = lines[index].strip()
            out.setdefault(title, [])
            index += 2
            continue
        out[title].append(lines[index])
        index += 1
    return out


def entries(lines: list[str]) -> list[tuple[str, list[str]]]:
    """``(head, description lines)`` of each entry of a section: the head is the unindented line."""
    found: list[tuple[str, list[str]]] = []
    for line in textwrap.dedent("\n".join(lines)).splitlines():
        if line.strip() and not line[:1].isspace():
            found.append((line.strip(), []))
        elif found and line.strip():
            found[-1][1].append(line.strip())
    return found


def entry_names(head: str) -> list[str]:
    """The names an entry head documents: ``a, b : float`` -> a, b; ``spectrocolor.x.OutputError`` -> OutputError."""
    names = head.split(" : ")[0] if " : " in head else head
    return [name.strip().lstrip("*").rsplit(".", 1)[-1] for name in names.split(",")]


def public_modules() -> list:
    """Every module of the package whose dotted name has no part with a leading underscore."""
    modules = [spectrocolor]
    for info in pkgutil.walk_packages(spectrocolor.__path__, "spectrocolor."):
        if any(part.startswith("_") for part in info.name.split(".")):
            continue
        modules.append(importlib.import_module(info.name))
    return modules


def public_objects() -> Iterator[tuple[str, object]]:
    """``(qualified name, object)`` of every public function, class and method, each object once."""
    seen: set[int] = set()
    for module in public_modules():
        for name, obj in sorted(vars(module).items()):
            if name.startswith("_") or getattr(obj, "__module__", None) != module.__name__:
                continue
            if not (inspect.isfunction(obj) or inspect.isclass(obj)) or id(obj) in seen:
                continue
            seen.add(id(obj))
            yield f"{module.__name__}.{name}", obj
            if inspect.isclass(obj):
                for attr, value in vars(obj).items():
                    if attr.startswith("_") and attr != "__init__":
                        continue
                    if isinstance(value, staticmethod | classmethod):
                        value = value.__func__
                    if inspect.isfunction(value) and id(value) not in seen:
                        seen.add(id(value))
                        yield f"{module.__name__}.{name}.{attr}", value


def docstring(obj: object) -> str:
    """The object's own docstring (a class's, not one inherited)."""
    return (obj.__dict__.get("__doc__") if inspect.isclass(obj) else obj.__doc__) or ""


def described_entries(objects) -> Iterator[tuple[str, str, str, list[str]]]:
    """``(place, section, head, description lines)`` of every entry of every docstring."""
    for qualname, obj in objects:
        for title, lines in sections(docstring(obj)).items():
            if title in ENTRY_SECTIONS:
                for head, description in entries(lines):
                    yield qualname, title, head, description


def pasted_descriptions(objects) -> list[str]:
    """One line per pair of entries that share a description of MIN_SHARED_LINES lines or more."""
    by_text: dict[str, list[str]] = defaultdict(list)
    for place, title, head, description in described_entries(objects):
        if len(description) >= MIN_SHARED_LINES:
            by_text[" ".join(" ".join(description).split())].append(f"{place} [{title}] {head}")
    problems = []
    for text, places in by_text.items():
        first = places[0]
        problems += [f"{first}  ==  {other}: the same {text[:80]!r}…; define it once in docs/glossary.md "
                     f"and link it with :term:" for other in places[1:]]
    return problems


def unlinked_glossary_entries(objects) -> list[str]:
    """One line per entry named like a glossary term whose long description has no ``:term:``."""
    problems = []
    for place, title, head, description in described_entries(objects):
        terms = {GLOSSARY_NAMES[name] for name in entry_names(head) if name in GLOSSARY_NAMES}
        if terms and len(description) > MAX_UNLINKED_LINES and ":term:" not in " ".join(description):
            problems.append(f"{place} [{title}] {head}: {len(description)} lines without a :term: link "
                            f"(say what it means here in one line and link :term:`{sorted(terms)[0]}`)")
    return problems


def glossary_terms(text: str) -> set[str]:
    """The terms of the ``{glossary}`` blocks of a MyST page (lower case, as Sphinx matches them)."""
    terms: set[str] = set()
    for block in re.findall(r"^```\{glossary\}\n(.*?)^```", text, re.MULTILINE | re.DOTALL):
        terms |= {line.strip().lower() for line in block.splitlines() if line.strip() and not line[:1].isspace()}
    return terms


def terms_used(text: str) -> set[str]:
    """The terms that ``:term:`` roles in a text name (``:term:`text <term>``` names ``term``)."""
    used = set()
    for inner in _TERM.findall(text):
        match = re.fullmatch(r"(?s).*<(.+)>", inner)
        used.add(" ".join((match.group(1) if match else inner).split()).lower())
    return used


# -- the checker itself, on the text the docstrings carried before the glossary ------------------

_OLD_LIGHT = """The light the colours are seen under (a CIE name, ``"blackbody:T"``, ``"D:T"``, or a
        Spectrum sampled on the grid)."""


def _old_first(spectrum, *, illuminant="D65"):
    """Summary.

    Parameters
    ----------
    spectrum : Spectrum
        Reflectance factors (0–1).
    illuminant : str or Spectrum, default "D65"
        {light}
    """


def _old_second(spectrum, *, illuminant="D65", observer="1931"):
    """Summary.

    Parameters
    ----------
    spectrum : Spectrum
        Reflectance factors (0–1).
    illuminant : str or Spectrum, default "D65"
        {light}
    observer : str, Spectrum or Observer
        Observer name or alias, colour-matching functions on the grid, or an
        :class:`~spectrocolor.observers.Observer` (default :data:`~spectrocolor.DEFAULT_OBSERVER`).
    """


def _new(spectrum, *, illuminant="D65"):
    """Summary.

    Parameters
    ----------
    spectrum : Spectrum
        Reflectance factors (0–1).
    illuminant : str or Spectrum, default "D65"
        The light the colours are seen under; see :term:`illuminant`.
    """


for _function in (_old_first, _old_second):
    _function.__doc__ = _function.__doc__.format(light=_OLD_LIGHT)


def test_the_checker_finds_pasted_and_unlinked_text():
    old = [("m._old_first", _old_first), ("m._old_second", _old_second)]
    pasted = pasted_descriptions(old)
    assert len(pasted) == 1 and "m._old_first [Parameters] illuminant" in pasted[0]
    assert "m._old_second [Parameters] illuminant" in pasted[0]
    unlinked = unlinked_glossary_entries(old)
    assert [line.split(" [")[0] for line in unlinked] == ["m._old_first", "m._old_second", "m._old_second"]
    assert "observer" in unlinked[2]
    assert pasted_descriptions([("m._new", _new), ("m._old_first", _old_first)]) == []
    assert unlinked_glossary_entries([("m._new", _new)]) == []


def test_the_parsers():
    assert entry_names("illuminant, second_illuminant : str") == ["illuminant", "second_illuminant"]
    assert entry_names("spectrocolor.safe_write.OutputError") == ["OutputError"]
    assert entry_names("*args, **kwargs") == ["args", "kwargs"]
    assert glossary_terms("```{glossary}\nlight\nIlluminant\n  The light.\n```\n") == {"light", "illuminant"}
    assert terms_used("see :term:`the grid <wavelength\n grid>` and :term:`Observer`") == {"wavelength grid",
                                                                                          "observer"}


# -- the package --------------------------------------------------------------------------------


def test_no_two_public_docstrings_share_a_description():
    problems = pasted_descriptions(list(public_objects()))
    assert not problems, f"{len(problems)} pasted descriptions:\n" + "\n".join(problems)


def test_glossary_parameters_link_the_glossary():
    problems = unlinked_glossary_entries(list(public_objects()))
    assert not problems, f"{len(problems)} long descriptions of glossary terms without a link:\n" + "\n".join(problems)


def test_every_term_used_is_in_the_glossary():
    defined = glossary_terms(GLOSSARY.read_text(encoding="utf-8"))
    assert set(GLOSSARY_NAMES.values()) <= defined, "GLOSSARY_NAMES names a term docs/glossary.md lacks"
    texts = [(module.__name__, module.__doc__ or "") for module in public_modules()]
    texts += [(qualname, docstring(obj)) for qualname, obj in public_objects()]
    missing = [f"{place}: :term:`{term}`" for place, text in texts for term in sorted(terms_used(text))
               if term not in defined]
    assert not missing, "terms not in docs/glossary.md:\n" + "\n".join(missing)


def test_the_glossary_is_in_the_reading_order():
    index = (ROOT / "docs" / "api" / "index.rst").read_text(encoding="utf-8")
    assert re.search(r"^\s+guides/glossary$", index, re.MULTILINE)


if __name__ == "__main__":  # the current findings, for a clean-up
    everything = list(public_objects())
    for line in pasted_descriptions(everything) + unlinked_glossary_entries(everything):
        print(line)
