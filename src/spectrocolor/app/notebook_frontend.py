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
import posixpath
import re
from collections.abc import Mapping, Sequence
from importlib import resources

#: The explorer's entry module; it and every module it imports make the widget's front end.
ENTRY = "main.js"

_IMPORT = re.compile(
    r'^import\s*\{([^}]*)\}\s*from\s*["\']((?:\.\.?/)+[A-Za-z0-9_./-]*\.js)["\']\s*;?[ \t]*(//[^\n]*)?$', re.M)
_EXPORT_LIST = re.compile(r"^export\s*\{([^}]*)\}\s*;?[ \t]*(//[^\n]*)?$", re.M)
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


def resolve(importer: str, specifier: str) -> str:
    """The module a relative import names, as a path from the modules' common root.

    ``importer`` is the importing module's path (``"labs/light.js"``), ``specifier`` the import's
    text (``"./common.js"``, ``"../js/client.js"``); the answer is normalised
    (``"labs/common.js"``, ``"js/client.js"``), so every module has one key however it is reached.

    Examples
    --------
    >>> resolve("labs/common.js", "../js/client.js"), resolve("main.js", "./state.js")
    ('js/client.js', 'state.js')
    """
    path = posixpath.normpath(posixpath.join(posixpath.dirname(importer), specifier))
    if path.startswith("../") or path == ".." or path.startswith("/"):
        raise AssemblyError(f"{importer}: the import {specifier!r} leaves the modules' folder")
    return path


def _export_list(names: str, module: str) -> list[str]:
    out = []
    for item in (p.strip() for p in names.split(",")):
        if not item:
            continue
        pieces = item.split()
        if len(pieces) == 1 and _IDENT.match(pieces[0]):
            out.append(pieces[0])
        elif len(pieces) == 3 and pieces[1] == "as" and _IDENT.match(pieces[0]) and _IDENT.match(pieces[2]):
            out.append(f"{pieces[2]}: {pieces[0]}")
        else:
            raise AssemblyError(f"{module}: cannot rewrite the exported name {item!r}")
    return out


def _rewrite(name: str, text: str) -> tuple[str, list[str], list[str]]:
    """One module's body with its imports and exports rewritten: (body, exported names, modules
    it imports, as resolved paths)."""
    needs: list[str] = []

    def imported(m: re.Match) -> str:
        need = resolve(name, m.group(2))
        needs.append(need)
        return f"const {{{_import_bindings(m.group(1), name)}}} = __spectrocolorModules[{json.dumps(need)}];"

    listed: list[str] = []

    def export_list(m: re.Match) -> str:
        listed.extend(_export_list(m.group(1), name))
        return ""

    body = _IMPORT.sub(imported, text)
    body = _EXPORT_LIST.sub(export_list, body)
    exports = [m.group(1) for m in _EXPORT.finditer(body)] + listed
    body = _EXPORT.sub("", body)
    for number, line in enumerate(body.splitlines(), 1):
        stripped = line.lstrip()
        if re.match(r"(import|export)\b(?!\.)", stripped) or re.search(r"\bimport\s*\(|\bimport\.meta\b", line):
            raise AssemblyError(f"{name}, line {number}: cannot rewrite {stripped[:80]!r} (only "
                                "`import {a, b as c} from \"./m.js\"` (or \"../dir/m.js\"), "
                                "`export function/const/class` and `export {a, b as c}`)")
    return body, exports, needs


def assemble_esm(sources: Mapping[str, str], entry: str | Sequence[str] = ENTRY) -> str:
    """The explorer's ES modules as one script defining ``createExplorer(env)``.

    Parameters
    ----------
    sources : mapping of str to str
        Module path (``"state.js"``, or ``"labs/light.js"`` for modules in several folders) to its
        text; each entry and every module it imports, directly or not, must be there. Relative
        imports (``./m.js``, ``../js/m.js``) are resolved against the importing module's folder
        (:func:`resolve`), so a module is one key (and runs once) however it is reached.
    entry : str or sequence of str
        The module(s) to run, in order (as a page's module scripts: their top levels run when
        ``createExplorer`` is called).

    Returns
    -------
    str
        JavaScript text: ``function createExplorer({document, window, location, history,
        localStorage, sessionStorage, fetch})`` that evaluates the modules in dependency order,
        each with those globals replaced by ``env``'s, and returns their exports by path.
        It has no ``import`` statement left.

    Raises
    ------
    AssemblyError
        A module is missing, an import leaves the modules' folder, the imports form a circle, or
        a module uses an import or export form other than named imports of relative ``*.js``
        paths, ``export function/const/class`` and ``export {a, b as c}``.

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

    for first in ([entry] if isinstance(entry, str) else list(entry)):
        visit(first, ())
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


def shadow_css(css: str) -> str:
    """A page's style for a shadow root: ``:root`` and ``body`` become the widget's host and its
    page element (``.sc-body``)."""
    css = re.sub(r":root\b", ":host", css)
    return re.sub(r"(?<![\w.#-])body\b", ".sc-body", css)


def page_css() -> str:
    """The explorer's palette and style (``static/theme.css``, ``static/style.css``) for a shadow
    root: ``:root`` and ``body`` are the widget's host and its page element."""
    return shadow_css(_static("theme.css") + _static("style.css")) + _WIDGET_CSS


@functools.cache
def widget_esm() -> str:
    """The widget's front end: the assembled explorer, its page and the glue, one ES module."""
    glue = _static("notebook", "widget.js")
    head = (f"const PAGE_MARKUP = {json.dumps(page_markup())};\n"
            f"const PAGE_CSS = {json.dumps(page_css())};\n")
    return assemble_esm(explorer_sources()) + head + glue


# ---------------------------------------------------------------------------- the labs
#: The labs a notebook can open (``static/labs/<name>.html``).
LABS = ("light", "reflectance", "solid", "thinfilm")

_SCRIPT = re.compile(r"<script\b([^>]*)>(.*?)</script>", re.S | re.I)
_STYLESHEET = re.compile(r"<link\b[^>]*\brel=[\"']stylesheet[\"'][^>]*>", re.I)
_ATTR = re.compile(r"""\b(src|href|type)=["']([^"']*)["']""", re.I)

#: The lab page in a widget: as tall as its content; the links to the server's other pages (the
#: explorer and the other labs) are hidden, as the explorer widget hides its links to the labs; the
#: page is a size container, so that the labs' narrow layouts follow the widget's width (a notebook's
#: output area), not the window's (see :func:`container_css`).
_LAB_WIDGET_CSS = """
.sc-body { min-height: 0; border-radius: 8px; container-type: inline-size; }
header nav { display: none; }
"""


def container_css(css: str) -> str:
    """``@media`` width queries as ``@container`` queries of the widget's page (``.sc-body``).

    Examples
    --------
    >>> container_css("@media (max-width: 760px) { main { display: block; } }")
    '@container (max-width: 760px) { main { display: block; } }'
    """
    return re.sub(r"@media\s*\(\s*(max|min)-width\s*:\s*([\d.]+(?:px|em|rem))\s*\)", r"@container (\1-width: \2)", css)


def static_sources() -> dict[str, str]:
    """Every ES module of the page and the labs, keyed by its path under ``static/``
    (``"js/client.js"``, ``"labs/light.js"``): the keys :func:`resolve` gives."""
    root = resources.files("spectrocolor.app").joinpath("static")
    out = {}
    for folder in ("js", "labs"):
        for p in root.joinpath(folder).iterdir():
            if p.name.endswith(".js"):
                out[f"{folder}/{p.name}"] = p.read_text(encoding="utf-8")
    return out


def _static_path(url: str, page: str) -> str:
    if not url.startswith("/static/") or ".." in url.split("/"):
        raise AssemblyError(f"{page}: cannot load {url[:80]!r} in a notebook (only /static/ files)")
    return url.removeprefix("/static/")


def lab_page(name: str) -> tuple[str, str, list[str]]:
    """A lab's page as the widget needs it: ``(markup, css, entries)``.

    ``markup`` is the body of ``static/labs/<name>.html`` without its scripts, ``css`` its
    stylesheets (in the page's order) for a shadow root, ``entries`` its module scripts as paths
    under ``static/`` (``["labs/light.js", "js/demos.js"]``), run in that order.

    Raises
    ------
    AssemblyError
        ``name`` is not a lab, or the page has a script or stylesheet the widget cannot load (an
        inline or classic script, a file outside ``/static/``).

    Examples
    --------
    >>> markup, css, entries = lab_page("thinfilm")
    >>> entries[0], 'id="thickness"' in markup, ":host" in css
    ('labs/thinfilm.js', True, True)
    """
    if name not in LABS:
        raise AssemblyError(f"lab: expected one of {', '.join(LABS)}, got {name!r:.40}")
    page = f"static/labs/{name}.html"
    html = _static("labs", f"{name}.html")
    entries = []
    for m in _SCRIPT.finditer(html):
        attrs = dict((k.lower(), v) for k, v in _ATTR.findall(m.group(1)))
        if attrs.get("type") != "module" or "src" not in attrs or m.group(2).strip():
            raise AssemblyError(f"{page}: only <script type=\"module\" src=\"/static/...\"> can run in a "
                                f"notebook, got {m.group(0)[:80]!r}")
        entries.append(_static_path(attrs["src"], page))
    styles = []
    for m in _STYLESHEET.finditer(html):
        href = dict((k.lower(), v) for k, v in _ATTR.findall(m.group(0))).get("href", "")
        styles.append(shadow_css(_static(*_static_path(href, page).split("/"))))
    body = re.search(r"<body[^>]*>(.*)</body>", html, re.S)
    if body is None:
        raise AssemblyError(f"{page} has no <body>")
    return _SCRIPT.sub("", body.group(1)), container_css("\n".join(styles)) + _LAB_WIDGET_CSS, entries


@functools.cache
def lab_widget_esm(name: str) -> str:
    """A lab's widget front end: its modules (and those they import, across folders) assembled,
    its page and style, and the labs' glue (``static/notebook/lab_widget.js``), one ES module."""
    markup, css, entries = lab_page(name)
    head = (f"const PAGE_MARKUP = {json.dumps(markup)};\n"
            f"const PAGE_CSS = {json.dumps(css)};\n"
            f"const LAB = {json.dumps(name)};\n")
    return assemble_esm(static_sources(), entries) + head + _static("notebook", "lab_widget.js")
