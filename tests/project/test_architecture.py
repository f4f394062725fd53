"""The import graph follows docs/design.md: dependencies point down, the two trunks stay apart.

Every ``import`` in the package (module level and inside functions) is classified by the layer
of the importing and the imported module; an import that points up, or from one trunk into the
other, fails with the exact file and line.
"""

from __future__ import annotations

import ast
import functools
from dataclasses import dataclass
from pathlib import Path

PACKAGE = Path(__file__).resolve().parents[2] / "src" / "spectrocolor"

# layer name -> rank; a module may import modules of its own rank or lower, with the trunk rule below
RANK = {"foundation": 0, "data": 1, "spectra": 2, "colour": 2, "colorimetry": 3, "applications": 4,
        "presentation": 5, "interfaces": 6}

FOUNDATION = {"errors", "registry", "arguments", "budget", "safe_write", "imagefiles", "spreadsheet",
              "numba_support", "__init__",
              "__main__", "notebook_hooks", "_version"}
DATA = {"data_tables"}
SPECTRA = {"spectrum", "interpolation", "sampling", "observers", "illuminants", "radiators", "spectrum_io", "io",
           "samples"}
COLOUR = {"coordinates", "differences", "display"}
COLORIMETRY = {"colorimetry", "astm_e308", "bandpass", "chromaticity", "cones", "temperature"}
APPLICATIONS = {"recovery", "thinfilm", "images", "lighting", "mixing", "upsampling",
                "display_emission"}
PRESENTATION = {"plot", "pictures", "report", "labels", "notebook"}
PRESENTATION_MODULES = {"plots", "vector_graphic", "report", "pictures", "figures"}
INTERFACES = {"cli", "app"}


def layer(parts: tuple[str, ...]) -> str:
    """The layer of module ``spectrocolor.<parts>``."""
    head, tail = parts[0], parts[-1]
    if head in INTERFACES:
        return "interfaces"
    if head in APPLICATIONS and len(parts) > 1 and tail in PRESENTATION_MODULES:
        return "presentation"
    for name, members in (("foundation", FOUNDATION), ("data", DATA), ("spectra", SPECTRA), ("colour", COLOUR),
                          ("colorimetry", COLORIMETRY), ("applications", APPLICATIONS),
                          ("presentation", PRESENTATION)):
        if head in members:
            return name
    raise AssertionError(f"spectrocolor.{'.'.join(parts)} is in no layer of docs/design.md; add it there and here")


def module_parts(path: Path) -> tuple[str, ...]:
    rel = path.relative_to(PACKAGE).with_suffix("")
    parts = rel.parts
    return parts[:-1] if parts[-1] == "__init__" and len(parts) > 1 else parts


def imported(path: Path, parts: tuple[str, ...]):
    """(line, imported module parts) for every import of a spectrocolor module in ``path``."""
    package = parts if path.name == "__init__.py" else parts[:-1]
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.ImportFrom):
            if node.level:
                base = package[: len(package) - (node.level - 1)]
                target = (*base, *(node.module.split(".") if node.module else ()))
                if node.module is None:  # from . import x, y: modules, or names of the package itself
                    for alias in node.names:
                        candidate = (*base, alias.name)
                        is_module = PACKAGE.joinpath(*candidate).with_suffix(".py").exists() or \
                            PACKAGE.joinpath(*candidate).is_dir()
                        if is_module or base:
                            yield node.lineno, candidate if is_module else base
                    continue
            elif node.module and node.module.split(".")[0] == "spectrocolor":
                target = tuple(node.module.split(".")[1:])
            else:
                continue
            if target:
                yield node.lineno, target
        elif isinstance(node, ast.Import):
            for alias in node.names:
                names = alias.name.split(".")
                if names[0] == "spectrocolor" and len(names) > 1:
                    yield node.lineno, tuple(names[1:])


def allowed(source: str, target: str) -> bool:
    if {source, target} == {"spectra", "colour"}:
        return False  # the two trunks never import each other
    return RANK[target] <= RANK[source]


def test_imports_point_down_and_the_trunks_stay_apart():
    violations = []
    for path in sorted(PACKAGE.rglob("*.py")):
        parts = module_parts(path)
        if parts in (("__init__",), ("__main__",)):
            continue  # the lazy public-name table and the entry point see everything
        source = layer(parts)
        for line, target_parts in imported(path, parts):
            target = layer(target_parts)
            if not allowed(source, target):
                violations.append(f"{path.relative_to(PACKAGE)}:{line}: {source} imports {target} "
                                  f"(spectrocolor.{'.'.join(target_parts)})")
    assert not violations, "imports against docs/design.md:\n" + "\n".join(violations)


def test_every_module_has_a_layer():
    for path in PACKAGE.rglob("*.py"):
        parts = module_parts(path)
        if parts not in (("__init__",), ("__main__",)):
            layer(parts)


# --- no circles: the whole package's import graph is acyclic -------------------------------------
#
# Every import in src/spectrocolor, at module level and inside functions, is resolved to the module
# it loads: ``from .x import name`` to ``x`` (or to ``x.name`` where that is a submodule), and an
# import of ``a.b.c`` also loads the packages ``a`` and ``a.b`` (their ``__init__``), unless the
# importer sits inside them (then they are already loading). The graph with every edge must be
# acyclic: a function-local import that closes a circle only hides it until someone moves it to the
# top. Function-local imports that close no circle may stay (optional heavy dependencies, lazy
# loading). Nothing inside the package imports the package face (``spectrocolor/__init__.py``, the
# lazy table of public names): it would hide the real edges from this graph.


@dataclass(frozen=True)
class Edge:
    source: str  # dotted module name below spectrocolor ("" is the package face)
    target: str
    where: str  # file:line of the import
    local: bool  # inside a function
    face: bool  # an import of the package face (import spectrocolor; from spectrocolor import name)
    via: str = ""  # the import that loads this package implicitly (its target), if any

    def describe(self) -> str:
        how = " (function-local)" if self.local else ""
        how += f" (loading {self.via})" if self.via else ""
        def name(module):
            return f"spectrocolor.{module}" if module else "spectrocolor"

        return f"{name(self.source)} -> {name(self.target)}  {self.where}{how}"


def dotted(path: Path, root: Path) -> str:
    parts = path.relative_to(root).with_suffix("").parts
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def is_module(name: str, root: Path) -> bool:
    base = root.joinpath(*name.split("."))
    return base.with_suffix(".py").is_file() or (base / "__init__.py").is_file()


def _imports(tree: ast.AST):
    """(import node, whether it sits inside a function) for every import in ``tree``."""
    stack = [(tree, False)]
    while stack:
        node, local = stack.pop()
        if isinstance(node, (ast.Import, ast.ImportFrom)):
            yield node, local
            continue
        inner = local or isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.Lambda))
        stack.extend((child, inner) for child in ast.iter_child_nodes(node))


@functools.lru_cache(maxsize=4)
def import_edges(root: Path = PACKAGE) -> tuple[Edge, ...]:
    """Every import of a module of the package under ``root``, resolved (see above)."""
    edges = []
    for path in sorted(root.rglob("*.py")):
        source = dotted(path, root)
        package = source.split(".") if path.name == "__init__.py" else source.split(".")[:-1]
        package = [p for p in package if p]
        tree = ast.parse(path.read_text(encoding="utf-8"))
        found = []  # (line, target, local, face)
        for node, local in sorted(_imports(tree), key=lambda t: t[0].lineno):
            if isinstance(node, ast.Import):
                for alias in node.names:
                    head, *rest = alias.name.split(".")
                    if head == root.name:
                        found.append((node.lineno, ".".join(rest), local, not rest))
            elif isinstance(node, ast.ImportFrom):
                if node.level:
                    base = package[: len(package) - (node.level - 1)] + (node.module.split(".") if node.module else [])
                elif node.module and node.module.split(".")[0] == root.name:
                    base = node.module.split(".")[1:]
                else:
                    continue
                module = ".".join(base)
                for alias in node.names:
                    sub = f"{module}.{alias.name}" if module else alias.name
                    if is_module(sub, root):
                        found.append((node.lineno, sub, local, False))
                    else:  # a name defined in (or re-exported by) the module itself
                        found.append((node.lineno, module, local, not module))
        where = path.relative_to(root.parent).as_posix()
        for line, target, local, face in found:
            if target != source:
                edges.append(Edge(source, target, f"{where}:{line}", local, face))
            parts = target.split(".")
            for n in range(1, len(parts)):  # the packages that importing ``target`` loads first
                ancestor = ".".join(parts[:n])
                if ancestor != source and not f"{source}.".startswith(f"{ancestor}."):
                    edges.append(Edge(source, ancestor, f"{where}:{line}", local, False, target))
    return tuple(edges)


def cycles(edges) -> list[tuple[list[str], list[Edge]]]:
    """Each strongly connected group of modules (Tarjan) with one shortest circle through it (edges)."""
    out: dict[str, list[Edge]] = {}
    for e in edges:
        out.setdefault(e.source, []).append(e)
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    groups = []

    def visit(v):  # recursion depth is bounded by the number of modules (a few hundred)
        index[v] = low[v] = len(index)
        stack.append(v)
        on_stack.add(v)
        for e in out.get(v, ()):
            if e.target not in index:
                visit(e.target)
                low[v] = min(low[v], low[e.target])
            elif e.target in on_stack:
                low[v] = min(low[v], index[e.target])
        if low[v] == index[v]:
            group = set()
            while True:
                w = stack.pop()
                on_stack.discard(w)
                group.add(w)
                if w == v:
                    break
            if len(group) > 1:
                groups.append(group)

    for v in sorted({e.source for e in edges} | {e.target for e in edges}):
        if v not in index:
            visit(v)
    found = []
    for group in groups:  # breadth-first from the group's first module back to itself
        start = min(group)
        came: dict[str, Edge] = {}
        queue = [start]
        while queue and start not in came:
            v = queue.pop(0)
            for e in out.get(v, ()):
                if e.target in group and e.target not in came:
                    came[e.target] = e
                    queue.append(e.target)
        path, v = [], start
        while True:
            path.append(came[v])
            v = came[v].source
            if v == start:
                break
        found.append((sorted(group), path[::-1]))
    return found


def report(circles) -> str:
    return "\n".join(f"circle {n}: {len(group)} modules ({', '.join(group)}), for example\n    "
                     + "\n    ".join(e.describe() for e in path) for n, (group, path) in enumerate(circles, 1))


def test_no_import_circle_at_module_level():
    circles = cycles([e for e in import_edges() if not e.local])
    assert not circles, "import circles (module-level imports):\n" + report(circles)


def test_no_function_local_import_hides_a_circle():
    """The graph of every import, function-local ones included, is acyclic: moving any import to
    the top of its module would create no circle."""
    circles = cycles(import_edges())
    assert not circles, ("import circles once function-local imports count (move shared parts to a "
                         "module of their own):\n" + report(circles))


def test_nothing_inside_the_package_imports_the_package_face():
    """``import spectrocolor`` (as sc) or ``from spectrocolor import name`` inside the package loads
    the lazy public table and hides the module really used; import the defining module instead.
    Doctest lines (``>>>``) are text in docstrings, so they are not imports here."""
    faces = list(dict.fromkeys(e.where for e in import_edges() if e.face and e.source != ""))
    assert not faces, "imports of the package face inside the package:\n" + "\n".join(faces)


def test_the_graph_sees_every_kind_of_import(tmp_path):
    """The checks above on a small package: a circle closed by a function-local import, one through
    a package's ``__init__``, and the package face imported in three spellings."""
    root = tmp_path / "spectrocolor"
    (root / "sub").mkdir(parents=True)
    files = {
        "__init__.py": "",
        "a.py": "from . import b\n",
        "b.py": "def f():\n    from .a import g\n    import spectrocolor as sc\n",
        "c.py": "from .sub import x\nimport spectrocolor\n",
        "sub/__init__.py": "from .d import x\n",
        "sub/d.py": "from ..c import y\nfrom spectrocolor import weights\nfrom spectrocolor import a\n",
        "e.py": '"""\n>>> import spectrocolor as sc\n"""\nfrom .sub import d\n',
    }
    for name, text in files.items():
        (root / name).write_text(text)
    edges = import_edges(root)
    assert list(dict.fromkeys(e.where for e in edges if e.face)) == [
        "spectrocolor/b.py:3", "spectrocolor/c.py:2", "spectrocolor/sub/d.py:2"]
    assert len(cycles([e for e in edges if not e.local])) == 1  # c -> sub (its __init__) -> sub.d -> c
    circles = cycles(edges)
    assert sorted(group for group, _ in circles) == [["a", "b"], ["c", "sub", "sub.d"]]
    local = next(path for group, path in circles if group == ["a", "b"])
    assert any(e.local and e.where == "spectrocolor/b.py:2" for e in local)
    assert "(function-local)" in report(circles)
