"""The pages of the API reference, generated from the package's own public-name tables.

Every public name is documented exactly once:

* the package face, ``spectrocolor._PUBLIC`` (``sc.tristimulus``, …), on the page of the module
  that defines each name;
* the ``__all__`` of every subpackage (``spectrocolor.images.plan_conversion``, …): a name the
  face already documents is not repeated; any other goes on the page of the module that defines
  it when that module has a page, else on the subpackage's own page;
* :data:`ALSO_DOCUMENTED`: module-level names outside both tables that the public docstrings
  point to (the memory-budget environment variable, the CRI roundings, the bundled media, …).

``docs/api/conf.py`` writes :func:`reference_pages` to ``docs/api/reference/`` at every build;
``tests/project/test_api_reference.py`` checks the same pages without building, and
:func:`documented_targets` serves ``conf.py``'s resolver of aliases (``sc.render`` is documented
as ``spectrocolor.display.render.render``).
"""

from __future__ import annotations

import importlib
import inspect
import pkgutil
import re
from collections import defaultdict
from types import ModuleType

import spectrocolor

#: Module (relative to ``spectrocolor``) -> names outside ``_PUBLIC`` and every ``__all__`` that
#: public docstrings refer to, documented on that module's page: the records public functions
#: return (``OptimalColours``, ``Certificate``, …), the constants their defaults name, and the
#: helpers they point to. A name added to ``_PUBLIC`` or an ``__all__`` later is documented once.
ALSO_DOCUMENTED: dict[str, tuple[str, ...]] = {
    "bandpass": ("BANDPASS_METHODS", "stearns_stearns_matrix"),
    "budget": ("ENVIRONMENT_VARIABLE", "MIN_MEMORY_BUDGET"),
    "display.chain": ("DEFAULT_CHAIN_NORMALISATION", "DEFAULT_WHITE_ADAPTATION"),
    "display.explain": ("explain",),
    "display.gamut": ("DEFAULT_GAMUT", "clip"),
    "illuminants": ("ILLUMINANT_KINDS",),
    "imagefiles": ("read_image", "write_image", "image_header", "ImageHeader", "write_gif", "read_png",
                   "decode_png", "png_header", "iter_png_rows", "PNGHeader", "MAX_PIXELS",
                   "write_png_blocks", "write_tiff_blocks", "paeth_filter"),
    "images.convert": ("masked_fill",),
    "io.conditions": ("PERCENT_SUSPICION",),
    "io.cxf": ("spectra_to_cxf", "report_to_cxf"),
    "io.oceanview": ("resampled",),
    "io.xlsx": ("parse_xlsx", "sheet_names"),
    "lighting.cri": ("ROUNDINGS",),
    "lighting.photometry": ("spectral_values",),
    "lighting.summary": ("HEADLINE",),
    "notebook.colours": ("Swatches",),
    "pictures": ("TINT_HUE_ANCHORS", "swatch_image", "strip_image"),
    "recovery.certificate": ("Certificate",),
    "recovery.metamerism": ("ColourShift", "DEFAULT_TEST_ILLUMINANT"),
    "recovery.metamers": ("MetamerResult", "DifferentMetamer", "DEFAULT_SECOND_ILLUMINANT"),
    "recovery.optimal": ("MAX_HUE_SAMPLES", "OptimalColours", "SolidMembership"),
    "recovery.validity": ("SolutionClass", "BoundaryPiece"),
    "registry": ("RegistryEntry", "RegistryNames"),
    "safe_write": ("OutputError",),
    "thinfilm.maps": ("ColourTable",),
    "thinfilm.media": ("read_medium_csv", "table", "water", "bk7", "fused_silica", "typical_oil"),
    "thinfilm.zawischa": ("ZawischaStrip",),
    "upsampling.relight": ("Relit",),
    "upsampling.texels": ("table_fingerprint", "texel_bytes"),
}


def subpackages() -> list[ModuleType]:
    """Every subpackage of ``spectrocolor`` (imported), in name order."""
    return [
        importlib.import_module(f"spectrocolor.{info.name}")
        for info in sorted(pkgutil.iter_modules(spectrocolor.__path__), key=lambda info: info.name)
        if info.ispkg
    ]


def _module(relative: str) -> ModuleType:
    return importlib.import_module(f"spectrocolor.{relative}")


def identity(name: str, obj: object) -> tuple:
    """Identity of a documented object: the object itself, or for plain values its name too."""
    if inspect.isclass(obj) or inspect.isroutine(obj) or inspect.ismodule(obj):
        return ("object", id(obj))
    return ("value", name, id(obj))


def _assigned_in(package: ModuleType, name: str) -> str:
    """The module of ``package`` (relative to ``spectrocolor``) whose source assigns ``name``."""
    assignment = re.compile(rf"^{re.escape(name)}\s*(:[^=]*)?=", re.MULTILINE)
    for module in [package, *(importlib.import_module(f"{package.__name__}.{info.name}")
                              for info in pkgutil.iter_modules(package.__path__))]:
        if getattr(module, name, None) is getattr(package, name) and assignment.search(inspect.getsource(module)):
            return module.__name__.removeprefix("spectrocolor.")
    raise RuntimeError(f"no module of {package.__name__} assigns {name}")


def page_names() -> dict[str, list[str]]:
    """Module (relative to ``spectrocolor``) -> the names documented on its page, in order."""
    pages: dict[str, list[str]] = defaultdict(list)
    seen: set[tuple] = set()

    def add(module: str, name: str) -> None:
        obj = getattr(_module(module), name, None)
        if obj is None:
            raise RuntimeError(f"the reference names {name!r} in spectrocolor.{module}, which does not define it")
        if identity(name, obj) not in seen:
            seen.add(identity(name, obj))
            pages[module].append(name)

    for name, module in spectrocolor._PUBLIC.items():
        add(module, name)
    for package in subpackages():
        relative = package.__name__.removeprefix("spectrocolor.")
        for name in getattr(package, "__all__", ()):
            obj = getattr(package, name)
            if identity(name, obj) in seen:
                continue
            if inspect.isclass(obj) or inspect.isroutine(obj):
                defined_in = obj.__module__.removeprefix("spectrocolor.")
                add(defined_in if defined_in in pages else relative, name)
            else:  # a value: on the page of the module whose source assigns it (its ``#:`` comment)
                add(_assigned_in(package, name), name)
    for module, names in ALSO_DOCUMENTED.items():
        for name in names:
            add(module, name)
    return dict(pages)


def _directive(module: ModuleType, name: str) -> list[str]:
    obj = getattr(module, name)
    if inspect.isclass(obj):
        return [f".. autoclass:: {name}", "   :members:", ""]
    if inspect.isroutine(obj):
        return [f".. autofunction:: {name}", ""]
    return [f".. autodata:: {name}", "   :no-value:", ""]


def reference_pages() -> dict[str, str]:
    """File name (in ``docs/api/reference/``) -> reStructuredText of every reference page."""
    pages = page_names()
    objects = {f"spectrocolor.{relative}.{name}" for relative, names in pages.items() for name in names}
    files: dict[str, str] = {}
    for relative in sorted(pages):
        qualified = f"spectrocolor.{relative}"
        module = _module(relative)
        doc = (module.__doc__ or "").strip()
        first = doc.splitlines()[0] if doc else qualified
        # the module's own target, unless an object has its name (spectrocolor.upsampling.relight)
        module_directive = "currentmodule" if qualified in objects else "py:module"
        lines = [qualified, "=" * len(qualified), "", f".. {module_directive}:: {qualified}", "", first, ""]
        for name in pages[relative]:
            lines += _directive(module, name)
        files[f"{relative}.rst"] = "\n".join(lines)
    files["index.rst"] = (
        "API reference\n=============\n\nEvery public name of ``spectrocolor`` (the package face ``sc.*`` and every "
        "subpackage's ``__all__``), by the module that defines it. A name of the face, such as ``sc.render``, is "
        "documented once, under its module (``spectrocolor.display.render.render``).\n\n"
        ".. toctree::\n   :maxdepth: 1\n\n" + "".join(f"   {relative}\n" for relative in sorted(pages))
    )
    return files


def documented_targets() -> dict[tuple, str]:
    """Identity key of every documented object -> its documented dotted name."""
    targets: dict[tuple, str] = {}
    for relative, names in page_names().items():
        module = _module(relative)
        for name in names:
            targets[identity(name, getattr(module, name))] = f"spectrocolor.{relative}.{name}"
    return targets
