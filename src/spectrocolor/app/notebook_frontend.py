"""The notebook widget's front end: the explorer's page and ES modules as one ES module.

anywidget loads a widget's front end as a single ES module, so the relative imports between the
explorer's modules (``static/js/*.js``) cannot resolve there. :func:`assemble_esm` wraps each
module's text in a function that returns its exports, rewrites its imports to read those of the
modules it needs (in dependency order), and wraps the whole graph in ``createExplorer(env)``,
whose parameters stand for the page's globals (``document``, ``window``, ``location``,
``history``, the storages, ``fetch``): :mod:`spectrocolor.app.notebook_widget`'s glue
(``static/notebook/widget.js``) gives them, scoped to one widget. :func:`widget_esm` is that, the
page's markup (``static/index.html`` without its scripts) and style (``static/style.css`` for a
shadow root) and the glue, read from the package at run time, so the widget is always the
explorer of this version.

Example
-------
>>> "function createExplorer(" in widget_esm()
True
"""

from __future__ import annotations

import functools
import json
import re
from collections.abc import Mapping
from importlib import resources

#: The explorer's entry module; it and every module it imports make the widget's front end.
ENTRY = "main.js"

_IMPORT = re.compile(r'^import\s*\{([^}]*)\}\s*from\s*["\']\./([A-Za-z0-9_-]+\.js)["\']\s*;?[ \t]*(//[^\n]*)?$', re.M)
_EXPORT = re.compile(r"^export\s+(?=(?:async\s+function\*?|function\*?|const|class)\s+([A-Za-z_$][\w$]*))", re.M)
_IDENT = re.compile(r"^[A-Za-z_$][\w$]*$")


class AssemblyError(ValueError):
    """The explorer's modules use a form of ``import``/``export`` that :func:`assemble_esm` cannot
    rewrite (it names the module and the line)."""


# ---------------------------------------------------------------------------- the front end
def _import_bindings(names: str, module: str) -> str:
    parts = []
    for item in (p.strip() for p in names.split(",")):
        if not item:
            continue
        pieces = item.split()
        if len(pieces) == 1 and _IDENT.match(pieces[0]):
            parts.append(pieces[0])
        elif len(pieces) == 3 and pieces[1] == "as" and _IDENT.match(pieces[0]) and _IDENT.match(pieces[2]):
            parts.append(f"{pieces[0]}: {pieces[2]}")
        else:
            raise AssemblyError(f"{module}: cannot rewrite the imported name {item!r}")
    return ", ".join(parts)


def _rewrite(name: str, text: str) -> tuple[str, list[str], list[str]]:
    """One module's body with its imports and exports rewritten: (body, exported names, modules
    it imports)."""
    needs: list[str] = []

    def imported(m: re.Match) -> str:
        needs.append(m.group(2))
        return f"const {{{_import_bindings(m.group(1), name)}}} = __spectrocolorModules[{json.dumps(m.group(2))}];"

    body = _IMPORT.sub(imported, text)
    exports = [m.group(1) for m in _EXPORT.finditer(body)]
    body = _EXPORT.sub("", body)
    for number, line in enumerate(body.splitlines(), 1):
        stripped = line.lstrip()
        if re.match(r"(import|export)\b(?!\.)", stripped) or re.search(r"\bimport\s*\(|\bimport\.meta\b", line):
            raise AssemblyError(f"{name}, line {number}: cannot rewrite {stripped[:80]!r} (only "
                                "`import {a, b as c} from \"./m.js\"` and `export function/const/class`)")
    return body, exports, needs


def assemble_esm(sources: Mapping[str, str], entry: str = ENTRY) -> str:
    """The explorer's ES modules as one script defining ``createExplorer(env)``.

    Parameters
    ----------
    sources : mapping of str to str
        Module file name (``"state.js"``) to its text; ``entry`` and every module it imports,
        directly or not, must be there.
    entry : str
        The module to run (its top level runs when ``createExplorer`` is called).

    Returns
    -------
    str
        JavaScript text: ``function createExplorer({document, window, location, history,
        localStorage, sessionStorage, fetch})`` that evaluates the modules in dependency order,
        each with those globals replaced by ``env``'s, and returns their exports by file name.
        It has no ``import`` statement left.

    Raises
    ------
    AssemblyError
        A module is missing, the imports form a circle, or a module uses an import or export form
        other than named imports of ``./*.js`` and ``export function/const/class``.

    Examples
    --------
    >>> sources = {"a.js": "export const A = 1;",
    ...            "b.js": 'import {A} from "./a.js";\\nexport const B = A + 1;'}
    >>> text = assemble_esm(sources, "b.js")
    >>> 'const {A} = __spectrocolorModules["a.js"];' in text
    True
    """
    order: list[str] = []
    rewritten: dict[str, tuple[str, list[str]]] = {}
    visiting: set[str] = set()

    def visit(name: str, chain: tuple[str, ...]) -> None:
        if name in rewritten:
            return
        if name in visiting:
            raise AssemblyError(f"the explorer's modules import each other in a circle: {' -> '.join((*chain, name))}")
        if name not in sources:
            raise AssemblyError(f"{chain[-1] if chain else 'entry'} imports {name}, which is not among the modules")
        visiting.add(name)
        body, exports, needs = _rewrite(name, sources[name])
        for need in needs:
            visit(need, (*chain, name))
        visiting.discard(name)
        rewritten[name] = (body, exports)
        order.append(name)

    visit(entry, ())
    out = ["// The SPECTRA explorer's ES modules, assembled into one by spectrocolor.app.notebook_widget",
           "// (each module's text unchanged but for its import and export keywords).",
           "function createExplorer({document, window, location, history, localStorage, sessionStorage, fetch}) {",
           "  const __spectrocolorModules = {};"]
    for name in order:
        body, exports = rewritten[name]
        out += [f"  // ---------------------------------------------------------------- {name}",
                f"  __spectrocolorModules[{json.dumps(name)}] = (() => {{", body,
                f"  return {{{', '.join(exports)}}};", "  })();"]
    out += ["  return __spectrocolorModules;", "}"]
    return "\n".join(out) + "\n"


def _static(*parts: str) -> str:
    return resources.files("spectrocolor.app").joinpath("static", *parts).read_text(encoding="utf-8")


def explorer_sources() -> dict[str, str]:
    """The explorer's ES modules (``static/js/*.js``), file name to text."""
    folder = resources.files("spectrocolor.app").joinpath("static", "js")
    return {p.name: p.read_text(encoding="utf-8") for p in folder.iterdir() if p.name.endswith(".js")}


def page_markup() -> str:
    """The explorer page's body (``static/index.html``) without its scripts."""
    html = _static("index.html")
    m = re.search(r"<body[^>]*>(.*)</body>", html, re.S)
    if m is None:
        raise AssemblyError("static/index.html has no <body>")
    return re.sub(r"<script\b.*?</script>", "", m.group(1), flags=re.S)


#: What the widget changes in the page's style: the page's ``body`` is the widget's ``.sc-body``,
#: it is as tall as its content (not the window), and the links to the labs (other pages of the
#: server) are hidden.
_WIDGET_CSS = """
.sc-body { min-height: 0; background: var(--bg); color: var(--text); border-radius: 8px; }
.labs, #light-metrics a { display: none; }
"""


def page_css() -> str:
    """The explorer's style (``static/style.css``) for a shadow root: ``:root`` and ``body`` are
    the widget's host and its page element."""
    css = _static("style.css")
    css = re.sub(r":root\b", ":host", css)
    css = re.sub(r"(?<![\w.#-])body\b", ".sc-body", css)
    return css + _WIDGET_CSS


@functools.cache
def widget_esm() -> str:
    """The widget's front end: the assembled explorer, its page and the glue, one ES module."""
    glue = _static("notebook", "widget.js")
    head = (f"const PAGE_MARKUP = {json.dumps(page_markup())};\n"
            f"const PAGE_CSS = {json.dumps(page_css())};\n")
    return assemble_esm(explorer_sources()) + head + glue
