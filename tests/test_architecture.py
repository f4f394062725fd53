"""The import graph follows docs/design.md: dependencies point down, the two trunks stay apart.

Every ``import`` in the package (module level and inside functions) is classified by the layer
of the importing and the imported module; an import that points up, or from one trunk into the
other, fails with the exact file and line.
"""

from __future__ import annotations

import ast
from pathlib import Path

PACKAGE = Path(__file__).resolve().parents[1] / "src" / "spectrocolor"

# layer name -> rank; a module may import modules of its own rank or lower, with the trunk rule below
RANK = {"foundation": 0, "data": 1, "spectra": 2, "colour": 2, "colorimetry": 3, "applications": 4,
        "presentation": 5, "interfaces": 6}

FOUNDATION = {"errors", "registry", "arguments", "budget", "safe_write", "spreadsheet", "numba_support", "__init__",
              "__main__", "notebook_hooks"}
DATA = {"data_tables"}
SPECTRA = {"spectrum", "interpolation", "sampling", "observers", "illuminants", "spectrum_io", "io"}
COLOUR = {"coordinates", "differences", "display"}
COLORIMETRY = {"colorimetry", "astm_e308", "bandpass", "chromaticity", "temperature"}
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
