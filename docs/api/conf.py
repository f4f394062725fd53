"""Sphinx configuration of the spectrocolor API reference (built offline by ``make docs``).

The reference pages are generated from the package's own public-name table
(``spectrocolor._PUBLIC``), grouped by module, so every public name is documented and nothing
is listed twice. The guides in ``docs/*.md`` are included as they are (MyST Markdown).
"""

from __future__ import annotations

import importlib
import shutil
import sys
from collections import defaultdict
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parents[1] / "src"))

import spectrocolor  # noqa: E402

project = "spectrocolor"
author = "the spectrocolor developers"
release = spectrocolor.__version__
extensions = ["sphinx.ext.autodoc", "sphinx.ext.napoleon", "myst_parser"]
napoleon_google_docstring = False
napoleon_numpy_docstring = True
napoleon_use_rtype = False
napoleon_use_ivar = True
autodoc_typehints = "description"
autodoc_member_order = "bysource"
source_suffix = {".rst": "restructuredtext", ".md": "markdown"}
myst_heading_anchors = 3
exclude_patterns = ["_build"]
html_theme = "alabaster"
html_static_path: list[str] = []
suppress_warnings = ["myst.xref_missing", "myst.header"]
nitpicky = False


def _write_reference() -> None:
    """reference/<module>.rst for every module that defines public names, and reference/index.rst."""
    by_module: dict[str, list[str]] = defaultdict(list)
    for name, module in spectrocolor._PUBLIC.items():
        by_module[module].append(name)
    out = HERE / "reference"
    shutil.rmtree(out, ignore_errors=True)
    out.mkdir()
    toc = []
    for module in sorted(by_module):
        qualified = f"spectrocolor.{module}"
        doc = importlib.import_module(qualified).__doc__ or ""
        first = doc.strip().splitlines()[0] if doc.strip() else qualified
        lines = [qualified, "=" * len(qualified), "", first, "", f".. currentmodule:: {qualified}", ""]
        for name in by_module[module]:
            obj = getattr(importlib.import_module(qualified), name, None)
            if obj is None:
                raise RuntimeError(f"spectrocolor._PUBLIC names {name!r} in {qualified}, which does not define it")
            if isinstance(obj, type):
                directive = "autoclass"
                options = ["   :members:"]
            elif callable(obj):
                directive, options = "autofunction", []
            else:
                directive, options = "autodata", ["   :no-value:"]
            lines += [f".. {directive}:: {name}", *options, ""]
        (out / f"{module}.rst").write_text("\n".join(lines))
        toc.append(module)
    (out / "index.rst").write_text(
        "API reference\n=============\n\nEvery public name of ``spectrocolor``, by the module that defines it.\n\n"
        ".. toctree::\n   :maxdepth: 1\n\n" + "".join(f"   {m}\n" for m in toc)
    )


def _copy_guides() -> None:
    """The Markdown guides of docs/ (and their images) next to the reference."""
    guides = HERE / "guides"
    shutil.rmtree(guides, ignore_errors=True)
    guides.mkdir()
    for md in sorted(HERE.parent.glob("*.md")):
        shutil.copy(md, guides / md.name)
    if (HERE.parent / "images").is_dir():
        shutil.copytree(HERE.parent / "images", guides / "images")


_write_reference()
_copy_guides()
