"""Sphinx configuration of the spectrocolor API reference (built offline by ``make docs``).

The reference pages are generated from the package's own public-name tables
(``spectrocolor._PUBLIC`` and every subpackage's ``__all__``; see ``reference_pages.py``),
grouped by module, so every public name is documented and nothing is listed twice. Every
cross-reference must resolve (``nitpicky``): names in numpydoc types are marked as references
(``_mark_types``), and another name of a documented object (``sc.render`` for
``spectrocolor.display.render.render``) links to it (``_resolve_alias``).

The guides in ``docs/*.md`` are included as they are (MyST Markdown), in the reading order of
``index.rst``. The gallery notebooks in ``docs/notebooks/*.ipynb`` (stored without outputs) are
executed by myst-nb on a local kernel at every build, offline, and rendered with their outputs;
a cell that fails fails the build.
"""

from __future__ import annotations

import importlib
import re
import shutil
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parents[1] / "src"))
sys.path.insert(0, str(HERE))

from reference_pages import documented_targets, identity, reference_pages  # noqa: E402
from sphinx.ext.napoleon import _process_docstring as _napoleon_process_docstring  # noqa: E402

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
autodoc_typehints_description_target = "documented"  # a dataclass's fields are its Attributes, not Parameters again
autodoc_member_order = "bysource"
source_suffix = {".rst": "restructuredtext", ".md": "myst-nb", ".ipynb": "myst-nb"}
myst_heading_anchors = 3
exclude_patterns = ["_build"]
html_theme = "alabaster"
html_static_path: list[str] = []
# Headings that skip a level are allowed in the guides; no cross-reference warning is suppressed.
suppress_warnings = ["myst.header"]
# The gallery: run every notebook at every build (outputs always from this code), in a temporary
# folder, failing the build on any error or a cell slower than the limit.
nb_execution_mode = "force"
nb_execution_timeout = 240
nb_execution_raise_on_error = True
nb_execution_show_tb = True
nb_execution_in_temp = True
nb_merge_streams = True
# Every cross-reference must resolve (a broken one fails `make docs`, which builds with -W).
nitpicky = True
# Names of other projects that the docstrings and annotations mention. Their inventories
# (intersphinx) cannot be fetched here (the build is offline) and none is shipped, so they stay
# unlinked. Third-party and standard-library names only, never one of spectrocolor's own.
nitpick_ignore = [
    ("py:class", name)
    for name in (
        # NumPy (ndarray in nearly every signature; ArrayLike/NDArray in annotations)
        "numpy.ndarray", "numpy.memmap", "numpy.dtype", "numpy.float64", "numpy.uint8", "numpy.uint16",
        "numpy.typing.ArrayLike", "numpy.typing.NDArray",
        # matplotlib (plot functions take and return Axes), dask (images.upsample_dask)
        "matplotlib.axes.Axes", "dask.array.Array",
        # the Python standard library: paths and mappings in annotations
        "os.PathLike", "pathlib.Path", "collections.abc.Mapping",
    )
]


def _write_reference() -> None:
    """reference/<module>.rst for every module that defines public names, and reference/index.rst."""
    out = HERE / "reference"
    shutil.rmtree(out, ignore_errors=True)
    out.mkdir()
    for name, text in reference_pages().items():
        (out / name).write_text(text)


def _copy_guides() -> None:
    """The Markdown guides of docs/ (and their images) next to the reference."""
    guides = HERE / "guides"
    shutil.rmtree(guides, ignore_errors=True)
    guides.mkdir()
    for md in sorted(HERE.parent.glob("*.md")):
        shutil.copy(md, guides / md.name)
    for folder in ("images", "upsampling"):  # pictures, and the reference readers the guides link to
        if (HERE.parent / folder).is_dir():
            shutil.copytree(HERE.parent / folder, guides / folder)


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
        ".. automodule:: spectrocolor.notebook\n   :no-index:\n\n"
        "Every name of :mod:`spectrocolor.notebook` is documented in the API reference, among them "
        ":func:`~spectrocolor.notebook.spectrum_view` and :class:`~spectrocolor.notebook.SpectrumView`.\n\n"
        ".. automodule:: spectrocolor.notebook_hooks\n   :members:\n")


_write_reference()
_copy_guides()
_copy_gallery()


# -- types in numpydoc fields ------------------------------------------------------------------
# A numpydoc type such as ``ndarray, shape (..., 3), optional`` is prose around names. Left as
# it is, Sphinx cross-references every word ("shape", "3", "optional"). After napoleon has
# turned the sections into fields, the names in each type are marked as references (the short
# name of a documented object to its page, ``ndarray`` to NumPy's) and the rest kept as text.
_NAME = re.compile(r"~?[A-Za-z_]\w*(\.[A-Za-z_]\w*)*")
_TYPE_FIELD = re.compile(r"^(\s*:(?:type|vartype) [^:]+: )(.+)$")
#: Words that read like names in a type but are prose (numpydoc's vocabulary).
_PROSE = {"optional", "array_like", "array-like", "sequence", "callable", "scalar", "iterable",
          "mapping", "function", "keyword-only", "path-like", "file-like", "number", "shape"}
#: Short names of other projects' types as the docstrings spell them.
_EXTERNAL = {"ndarray": "numpy.ndarray", "np.ndarray": "numpy.ndarray", "np.memmap": "numpy.memmap",
             "float64": "numpy.float64", "uint8": "numpy.uint8", "uint16": "numpy.uint16",
             "ArrayLike": "numpy.typing.ArrayLike", "DataArray": "xarray.DataArray",
             "DataFrame": "pandas.DataFrame", "Axes": "matplotlib.axes.Axes", "Figure": "matplotlib.figure.Figure",
             "Path": "pathlib.Path", "PathLike": "os.PathLike"}


def _short_names() -> dict[str, str]:
    """Short name -> documented dotted name, for the short names that are unique."""
    counts: dict[str, list[str]] = {}
    for dotted in documented_targets().values():
        counts.setdefault(dotted.rsplit(".", 1)[1], []).append(dotted)
    return {short: dotted[0] for short, dotted in counts.items() if len(dotted) == 1}


_SHORT = _short_names()


def _split_type(spec: str) -> list[str]:
    """The pieces of a type and the separators between them (top-level ``,``, ``or``, ``|``)."""
    pieces, depth, quote, start, i = [], 0, "", 0, 0
    while i < len(spec):
        c = spec[i]
        if quote:
            quote = "" if c == quote else quote
        elif c in "\"'":
            quote = c
        elif c in "([{":
            depth += 1
        elif c in ")]}":
            depth -= 1
        elif depth == 0:
            for sep in (", ", " or ", " | "):
                if spec.startswith(sep, i):
                    pieces += [spec[start:i], sep]
                    start = i = i + len(sep)
                    break
            else:
                i += 1
            continue
        i += 1
    return [*pieces, spec[start:]]


def _mark_type(spec: str) -> str:
    out = []
    for index, piece in enumerate(_split_type(spec)):
        if index % 2 or "`" in piece:  # a separator, or a piece marked up already
            out.append(piece)
        elif _NAME.fullmatch(piece) and piece.lower() not in _PROSE:
            target = _EXTERNAL.get(piece) or _SHORT.get(piece.lstrip("~")) or piece
            tilde = "" if target.startswith("~") or "." not in target else "~"
            out.append(f":py:class:`{tilde}{target}`")
        elif piece:
            out.append("*" + piece.replace("\\", "\\\\").replace("*", "\\*").replace("`", "\\`") + "*")
    return "".join(out)


_IVAR = re.compile(r"^(\s*):(ivar|vartype) ([^:]+,[^:]+):(.*)$")


def _mark_types(app, what, name, obj, options, lines: list[str]) -> None:
    """Mark the names in every type field; give each of ``a, b : T`` (Attributes) its own field."""
    split: list[str] = []
    for line in lines:
        match = _IVAR.match(line)
        if match:
            indent, kind, names, rest = match.groups()
            split += [f"{indent}:{kind} {each.strip()}:{rest}" for each in names.split(",")]
        else:
            split.append(line)
    for index, line in enumerate(split):
        match = _TYPE_FIELD.match(line)
        if match:
            split[index] = match.group(1) + _mark_type(match.group(2).strip())
    lines[:] = split


def _numpydoc(app, what, name, obj, options, lines: list[str]) -> None:
    """napoleon, except on a value's or property's docstring without sections.

    napoleon reads such a docstring's first ``text: more`` as ``type: description`` (Google
    style), so "The default memory budget: 1 GiB" would become a type named "The default
    memory budget"; numpydoc has no such form.
    """
    if what in ("data", "attribute", "property") and not any(set(line.strip()) == {"-"} for line in lines):
        return
    _napoleon_process_docstring(app, what, name, obj, options, lines)


# -- aliases -----------------------------------------------------------------------------------
# ``sc.render`` and ``spectrocolor.display.render`` are the same function, documented once as
# ``spectrocolor.display.render.render``; a reference to another name of a documented object
# (the package face, a subpackage's re-export, a name imported into the current module) is
# resolved by importing it and linking the object's one documented name. A reference to an
# object that is documented nowhere stays broken.
_TARGETS = documented_targets()


def _import(dotted: str):
    """(object, its last name) as Python finds ``dotted``: attributes first, then submodules."""
    parts = dotted.split(".")
    try:
        obj = importlib.import_module(parts[0])
    except ImportError:
        return None
    for index, part in enumerate(parts[1:], start=2):
        if hasattr(obj, part):
            obj = getattr(obj, part)
            continue
        try:
            obj = importlib.import_module(".".join(parts[:index]))
        except ImportError:
            return None
    return obj, parts[-1]


def _resolve_alias(app, env, node, contnode):
    if node.get("refdomain") != "py":
        return None
    target = node["reftarget"].lstrip(".~")
    contexts = [node.get("py:module"), ".".join(filter(None, (node.get("py:module"), node.get("py:class"))))]
    for prefix in (*filter(None, contexts), None):
        found = _import(f"{prefix}.{target}" if prefix else target)
        if found is None or not f"{prefix or ''}.{target}".lstrip(".").startswith("spectrocolor"):
            continue
        obj, name = found
        dotted = _TARGETS.get(identity(name, obj))
        if dotted:
            return _link(app, env, node, contnode, dotted)
    head, _, rest = target.partition(".")
    if target in _SHORT:  # the short name of a documented object, from a module that does not import it
        return _link(app, env, node, contnode, _SHORT[target])
    if rest and head in _SHORT:  # Class.member
        return _link(app, env, node, contnode, f"{_SHORT[head]}.{rest}") or _field(app, env, node, contnode, head, rest)
    if node.get("py:class") and "." not in target:  # a field of the class being documented
        return _field(app, env, node, contnode, node["py:class"], target)
    return None


def _field(app, env, node, contnode, cls: str, name: str):
    """A dataclass field (listed under the class's Variables, without a target of its own): the class."""
    dotted = _SHORT.get(cls)
    found = _import(dotted) if dotted else None
    if found and name in getattr(found[0], "__dataclass_fields__", {}):
        return _link(app, env, node, contnode, dotted)
    return None


def _link(app, env, node, contnode, dotted: str):
    return env.get_domain("py").resolve_xref(env, node["refdoc"], app.builder, "obj", dotted, node, contnode)


def setup(app):
    for listener in list(app.events.listeners.get("autodoc-process-docstring", [])):
        if listener.handler is _napoleon_process_docstring:
            app.disconnect(listener.id)
    app.connect("autodoc-process-docstring", _numpydoc)
    app.connect("autodoc-process-docstring", _mark_types, priority=600)  # after napoleon's (500)
    app.connect("missing-reference", _resolve_alias)
