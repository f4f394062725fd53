"""Sphinx configuration of the spectrocolor API reference (built offline by ``make docs``).

The reference pages are generated from the package's own public-name table
(``spectrocolor._PUBLIC``), grouped by module, so every public name is documented and nothing
is listed twice. The guides in ``docs/*.md`` are included as they are (MyST Markdown). The
gallery notebooks in ``docs/notebooks/*.ipynb`` (stored without outputs) are executed by
myst-nb on a local kernel at every build, offline, and rendered with their outputs; a cell that
fails fails the build.
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
extensions = ["sphinx.ext.autodoc", "sphinx.ext.napoleon", "myst_nb"]  # myst_nb brings myst_parser
napoleon_google_docstring = False
napoleon_numpy_docstring = True
napoleon_use_rtype = False
napoleon_use_ivar = True
autodoc_typehints = "description"
autodoc_member_order = "bysource"
source_suffix = {".rst": "restructuredtext", ".md": "myst-nb", ".ipynb": "myst-nb"}
myst_heading_anchors = 3
exclude_patterns = ["_build"]
html_theme = "alabaster"
html_static_path: list[str] = []
suppress_warnings = ["myst.xref_missing", "myst.header"]
# The gallery: run every notebook at every build (outputs always from this code), in a temporary
# folder, failing the build on any error or a cell slower than the limit.
nb_execution_mode = "force"
nb_execution_timeout = 240
nb_execution_raise_on_error = True
nb_execution_show_tb = True
nb_execution_in_temp = True
nb_merge_streams = True
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


def _copy_gallery() -> None:
    """The notebooks of docs/notebooks next to the reference, with an index page."""
    gallery = HERE / "gallery"
    shutil.rmtree(gallery, ignore_errors=True)
    gallery.mkdir()
    notebooks = sorted((HERE.parent / "notebooks").glob("*.ipynb"))
    for notebook in notebooks:
        shutil.copy(notebook, gallery / notebook.name)
    (gallery / "index.rst").write_text(
        "Gallery\n=======\n\nShort notebooks that run: the seeds' worked examples first, then each capability. "
        "Every record shows itself in Jupyter and VS Code (:mod:`spectrocolor.notebook`); these pages are the "
        "notebooks executed at this build.\n\n.. toctree::\n   :maxdepth: 1\n\n"
        + "".join(f"   {n.stem}\n" for n in notebooks) + "   notebook_reprs\n")
    (gallery / "notebook_reprs.rst").write_text(
        "How records show themselves\n===========================\n\n"
        ".. automodule:: spectrocolor.notebook\n\n"
        ".. autofunction:: spectrocolor.notebook.spectrum_view\n\n"
        ".. autoclass:: spectrocolor.notebook.SpectrumView\n\n"
        ".. automodule:: spectrocolor.notebook_hooks\n   :members:\n")


_write_reference()
_copy_guides()
_copy_gallery()
