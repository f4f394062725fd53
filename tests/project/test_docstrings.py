"""The API reference is complete: every public name has a full numpydoc docstring (issue 11, point 5).

For every name in ``spectrocolor._PUBLIC`` that is a function or a class, and for every public
method of the public classes, the docstring must have

- every parameter of the signature (``self``/``cls`` excepted) in ``Parameters`` (or ``Other
  Parameters``; for classes also ``Attributes``, which is how a result record documents its
  fields), each with a type after the colon (words such as ``optional`` or ``keyword-only`` alone
  are not a type); ``*args`` and ``**kwargs`` may share one entry;
- a ``Returns`` (or ``Yields``) section when the function returns a value;
- an ``Examples`` section.

The section parser is our own (a few lines; numpydoc is not a dependency). Properties are data,
not methods, and are not checked here. Run ``python tests/project/test_docstrings.py`` for the counts.
"""

from __future__ import annotations

import ast
import importlib
import inspect
import re
import textwrap

import spectrocolor

_UNDERLINE = re.compile(r"^\s*-{3,}\s*$")
_ENTRY = re.compile(r"^(?P<names>\*{0,2}[A-Za-z_][\w]*(?:\s*,\s*\*{0,2}[A-Za-z_][\w]*)*)\s*(?::\s*(?P<type>.*))?$")
#: Words in a type field that do not name a type.
_NOT_A_TYPE = re.compile(r"\b(optional|keyword[- ]only|positional[- ]only|default\b.*)", re.IGNORECASE)


def sections(doc: str) -> dict[str, list[str]]:
    """Split a numpydoc docstring into ``{section title: lines}`` (the summary is ``""``)."""
    lines = inspect.cleandoc(doc or "").splitlines()
    out: dict[str, list[str]] = {"": []}
    title = ""
    i = 0
    while i < len(lines):
        if i + 1 < len(lines) and lines[i].strip() and _UNDERLINE.match(lines[i + 1]):
            title = lines[i].strip()
            out.setdefault(title, [])
            i += 2
            continue
        out[title].append(lines[i])
        i += 1
    return out


def parameter_entries(lines: list[str]) -> dict[str, str]:
    """``{name: type}`` for the entries of a Parameters-like section (type ``""`` when missing)."""
    entries: dict[str, str] = {}
    body = textwrap.dedent("\n".join(lines)).splitlines()
    for line in body:
        if not line.strip() or line[:1].isspace():
            continue
        match = _ENTRY.match(line.strip())
        if match is None:
            continue
        kind = (match.group("type") or "").strip()
        for name in match.group("names").split(","):
            entries[name.strip().lstrip("*")] = kind
    return entries


def has_type(kind: str) -> bool:
    """A type field names a type once ``optional``/``keyword-only``/``default …`` are removed."""
    return bool(_NOT_A_TYPE.sub("", kind).strip(" ,;"))


def _returns_value(func) -> bool:
    """Whether ``func`` returns (or yields) something other than None, judged from its source."""
    func = inspect.unwrap(func)
    annotation = inspect.signature(func).return_annotation
    if annotation not in (inspect.Signature.empty, None, "None"):
        return True
    try:
        tree = ast.parse(textwrap.dedent(inspect.getsource(func)))
    except (OSError, TypeError, SyntaxError):
        return False
    top = tree.body[0]
    stack = list(ast.iter_child_nodes(top))
    while stack:
        node = stack.pop()
        if isinstance(node, ast.FunctionDef | ast.AsyncFunctionDef | ast.Lambda | ast.ClassDef):
            continue  # nested scopes return for themselves
        if isinstance(node, ast.Yield | ast.YieldFrom):
            return True
        if isinstance(node, ast.Return) and node.value is not None:
            if not (isinstance(node.value, ast.Constant) and node.value.value is None):
                return True
        stack.extend(ast.iter_child_nodes(node))
    return False


def _own_init(cls) -> bool:
    """Whether the class's constructor is defined in Python (its own or a dataclass's), not a builtin."""
    init = cls.__init__
    return inspect.isfunction(init) and init is not object.__init__


def audit(qualname: str, obj, *, is_class: bool) -> dict[str, list[str]]:
    """Problems of one public callable: ``{"examples": …, "returns": …, "untyped": […], "undocumented": […]}``."""
    doc = inspect.getdoc(obj) if not is_class else (obj.__dict__.get("__doc__") or "")
    parts = sections(doc)
    documented: dict[str, str] = {}
    titles = ("Parameters", "Other Parameters") + (("Attributes",) if is_class else ())
    if is_class and _own_init(obj):
        init_doc = obj.__init__.__doc__ if obj.__init__.__qualname__.startswith(obj.__qualname__) else None
        if init_doc:
            documented.update(parameter_entries(sections(init_doc).get("Parameters", [])))
    for title in titles:
        documented.update(parameter_entries(parts.get(title, [])))
    params: list[inspect.Parameter] = []
    if not is_class or _own_init(obj):
        try:
            params = list(inspect.signature(obj).parameters.values())
        except (TypeError, ValueError):
            params = []
    problems: dict[str, list[str]] = {"examples": [], "returns": [], "untyped": [], "undocumented": []}
    for p in params:
        if p.name in ("self", "cls"):
            continue
        if p.name not in documented:
            problems["undocumented"].append(p.name)
        elif not has_type(documented[p.name]):
            problems["untyped"].append(p.name)
    if not any("Examples" == t for t in parts) or not "".join(parts.get("Examples", [])).strip():
        problems["examples"].append("no Examples section")
    if not is_class and _returns_value(obj) and not ({"Returns", "Yields"} & set(parts)):
        problems["returns"].append("no Returns section")
    return problems


def public_callables() -> list[tuple[str, object, bool]]:
    """``(qualified name, object, is_class)`` for every public function, class and public method."""
    found: list[tuple[str, object, bool]] = []
    for name in sorted(spectrocolor._PUBLIC):
        try:
            obj = getattr(spectrocolor, name)
        except (AttributeError, ImportError) as error:  # a broken public name is a finding too
            found.append((name, error, False))
            continue
        if inspect.isclass(obj):
            found.append((name, obj, True))
            for attr, value in vars(obj).items():
                if attr.startswith("_"):
                    continue
                if isinstance(value, staticmethod | classmethod):
                    value = value.__func__
                if inspect.isfunction(value):
                    found.append((f"{name}.{attr}", value, False))
        elif inspect.isfunction(obj):
            found.append((name, obj, False))
    return found


def report() -> tuple[dict[str, dict[str, int]], dict[str, dict[str, list[str]]]]:
    """Counts and per-name problems over all public callables."""
    keys = (
        "checked",
        "missing Examples",
        "missing Returns",
        "missing parameter types",
        "undocumented parameters",
        "not importable",
    )
    counts = {group: dict.fromkeys(keys, 0) for group in ("public names", "methods")}
    failing: dict[str, dict[str, list[str]]] = {}
    for qualname, obj, is_class in public_callables():
        tally = counts["methods" if "." in qualname else "public names"]
        tally["checked"] += 1
        if isinstance(obj, Exception):
            tally["not importable"] += 1
            failing[qualname] = {"import": [str(obj)]}
            continue
        problems = audit(qualname, obj, is_class=is_class)
        tally["missing Examples"] += bool(problems["examples"])
        tally["missing Returns"] += bool(problems["returns"])
        tally["missing parameter types"] += bool(problems["untyped"])
        tally["undocumented parameters"] += bool(problems["undocumented"])
        problems = {k: v for k, v in problems.items() if v}
        if problems:
            failing[qualname] = problems
    return counts, failing


# -- the parser itself ------------------------------------------------------------------------------


def _sample(a, b, *args, c=1, **kwargs):
    """Summary.

    Parameters
    ----------
    a : float
        Text.
    b : optional
        No type.
    *args, **kwargs
        Passed on.

    Returns
    -------
    float
        Something.
    """
    return a


def test_parser_reads_numpydoc_sections():
    problems = audit("_sample", _sample, is_class=False)
    assert problems["undocumented"] == ["c"]
    assert problems["untyped"] == ["b", "args", "kwargs"]
    assert problems["examples"] == ["no Examples section"]
    assert problems["returns"] == []
    assert has_type("array_like, shape (K,), optional") and not has_type("keyword-only, optional")


def test_returns_detection():
    def returns_none(x):
        if x:
            return
        return None

    def generator():
        yield 1

    assert not _returns_value(returns_none)
    assert _returns_value(generator) and _returns_value(_sample)


# -- the API ----------------------------------------------------------------------------------------


def test_public_api_docstrings_are_complete():
    counts, failing = report()
    lines = [f"{name}: {problems}" for name, problems in sorted(failing.items())]
    checked = sum(tally["checked"] for tally in counts.values())
    assert not failing, f"{len(failing)} of {checked} public callables are incomplete:\n" + "\n".join(lines)


def test_every_public_module_imports():
    for module in sorted(set(spectrocolor._PUBLIC.values())):
        importlib.import_module(f"spectrocolor.{module}")


if __name__ == "__main__":
    totals, bad = report()
    for group, tally in totals.items():
        print(f"{group}: " + ", ".join(f"{key} {value}" for key, value in tally.items()))
    for name, problems in sorted(bad.items()):
        print(f"  {name}: {problems}")
