"""The SPECTRA explorer inside a notebook: :func:`explore` (``sc.explore(spectrum)``).

``explore(spectrum)`` returns a notebook widget showing the explorer's setting 1 with that
distribution as its bars. It is the explorer itself, not a second implementation: the page's own
markup (``static/index.html``), style (``static/style.css``) and ES modules (``static/js/*.js``,
``main.js`` and everything it imports) run in the notebook, inside a shadow root of their own, and
the computations are the server's: the front end's requests travel to the kernel as widget
messages instead of HTTP, and the kernel answers them with the functions behind the server's routes
(:func:`spectrocolor.app.server.options`, the validation and computation of the interactive lane,
:mod:`spectrocolor.app.compute`). Edits flow back: ``widget.spectrum`` is the edited distribution.

Why anywidget: it is a maintained, small widget layer on the Jupyter widget protocol that works
unchanged in JupyterLab, Notebook 7, VS Code's notebooks and Colab; its front end is a plain ES
module (here assembled from the explorer's own modules), with no build step, no JavaScript
toolchain and no separate front-end package to install or keep in step with the Python side.

How the explorer's modules become one module (:mod:`spectrocolor.app.notebook_frontend`): anywidget
loads the widget's front end as a single ES module, so the relative imports between the explorer's modules cannot
resolve. Each module's text is wrapped in a function that returns its exports, its imports are
rewritten to read those of the modules it needs (in dependency order), and the whole graph is
wrapped in ``createExplorer(env)``, whose parameters stand for the page's globals: ``document``
(the widget's shadow root: ``getElementById`` and ``querySelector`` find only this widget's
elements, so two widgets on one page never mix), ``window``, ``location`` and ``history`` (the
explorer keeps its state in the address; here the address is the widget's own, and a change of
it carries the edited distribution to the kernel), the storages (in memory) and ``fetch`` (a
request through the kernel that answers with a real :class:`Response`). The front end's own glue
is ``static/notebook/widget.js``.

Messages (front end to kernel, one dict each, answered by :func:`handle_message`):

* ``{"kind": "request", "id": n, "method": "GET"|"POST", "path": "/api/...", "body": text}`` is
  answered ``{"kind": "response", "id": n, "status": ..., "body": text, "media": ..., "headers":
  {...}}``, errors in the server's one shape (``{"error": "one line"}``);
* ``{"kind": "edited", "levels": [...], "step_nm": s}`` sets the widget's distribution after
  checking it (:func:`check_levels`);
* anything else gets ``{"kind": "error", "message": "one line"}``, never a traceback.

Needs the ``notebook`` extra (anywidget) and the ``app`` extra (the server's request models).

Example
-------
>>> from spectrocolor.app.notebook_widget import check_levels
>>> check_levels([30.0] * 31, 10)[:3]
[30.0, 30.0, 30.0]
"""

from __future__ import annotations

import functools
import json
import math
from collections.abc import Callable, Mapping
from numbers import Real
from typing import Any
from urllib.parse import parse_qs, urlsplit

import numpy as np

from ..errors import SpectrumError
from ..spectrum import Spectrum
from .notebook_frontend import AssemblyError, assemble_esm, widget_esm

__all__ = ["AssemblyError", "answer_request", "assemble_esm", "check_levels", "explore", "handle_message",
           "levels_of", "widget_esm"]

#: What a user installs for :func:`explore`.
EXTRA_HINT = "pip install 'spectrocolor[notebook]'"
#: Longest request body the widget answers, characters: the server's limit for the page's
#: interactive requests (``SMALL_BODY_BYTES``), and its general limit for a photo to relight.
MAX_BODY_CHARS = 64_000
MAX_PHOTO_BODY_CHARS = 2_000_000
MAX_PATH_CHARS = 300
_POSTED = {"/api/model": "model", "/api/evaluate": "evaluate", "/api/metamer": "metamer",
           "/api/export": "export"}

# ---------------------------------------------------------------------------- levels
def check_levels(levels: Any, step_nm: Any) -> list[float]:
    """A distribution's bin levels, checked for the explorer's grid of ``step_nm``.

    Parameters
    ----------
    levels : sequence of real
        One level per bin of 400-700 nm, each finite and in 0-30 (SPECTRA's levels).
    step_nm : float
        The bin width, nm: one of the explorer's (10, 5, 2 or 1).

    Returns
    -------
    list of float

    Raises
    ------
    SpectrumError
        One line naming what is wrong: the step, the count, or the first bad level.

    Examples
    --------
    >>> check_levels([0] * 31, 10)[0]
    0.0
    >>> check_levels([0] * 30, 10)
    Traceback (most recent call last):
    ...
    spectrocolor.errors.SpectrumError: levels: 30 levels; the explorer's 10 nm grid over 400-700 nm has 31 bins
    """
    from . import compute

    if isinstance(step_nm, bool) or not isinstance(step_nm, Real) or float(step_nm) not in compute.STEPS_NM:
        raise SpectrumError(f"step_nm: expected one of {', '.join(f'{s:g}' for s in compute.STEPS_NM)} (nm), "
                            f"got {step_nm!r:.40}")
    bins = len(compute.grid(float(step_nm)))
    if isinstance(levels, (str, bytes)) or not hasattr(levels, "__len__"):
        raise SpectrumError(f"levels: expected a list of {bins} numbers, got {type(levels).__name__}")
    if len(levels) != bins:
        raise SpectrumError(f"levels: {len(levels)} levels; the explorer's {float(step_nm):g} nm grid over "
                            f"400-700 nm has {bins} bins")
    out = []
    for i, v in enumerate(levels):
        if isinstance(v, bool) or not isinstance(v, Real) or not math.isfinite(float(v)) \
                or not 0 <= float(v) <= compute.FULL_LEVEL:
            raise SpectrumError(f"levels[{i}]: expected a number in 0-{compute.FULL_LEVEL:g}, got {v!r:.40}")
        out.append(float(v))
    return out


def levels_of(spectrum: Spectrum, step_nm: float = 10, scale: str = "peak") -> tuple[list[float], float]:
    """A distribution as the explorer's levels, and the unit of a level.

    Returns ``(levels, unit)``: ``spectrum`` resampled linearly onto the 400-700 nm grid of
    ``step_nm`` and scaled as the explorer's Load scales a file (``scale``: ``"peak"``, its peak
    is level 30; ``"unit"``, values are factors 0-1; ``"levels"``, values are levels already),
    and the value of one level in ``spectrum``'s units (``levels * unit`` gives the values back).

    Examples
    --------
    >>> import numpy as np
    >>> s = Spectrum(np.arange(380, 781, 5.0), np.linspace(0.2, 1.0, 81))
    >>> levels, unit = levels_of(s, 10, "unit")
    >>> len(levels), round(levels[-1], 9), round(unit * 30, 12)
    (31, 25.2, 1.0)
    """
    from . import compute

    if not isinstance(spectrum, Spectrum):
        raise SpectrumError(f"spectrum: expected a spectrocolor.Spectrum, got {type(spectrum).__name__}")
    if spectrum.values.ndim != 1:
        raise SpectrumError(f"spectrum: expected one distribution, got a batch of shape {spectrum.values.shape}; "
                            "explore one of them")
    check_levels([0.0] * len(compute.grid(float(step_nm))) if isinstance(step_nm, Real) else None, step_nm)
    if scale not in compute.IMPORT_SCALES.names():
        raise SpectrumError(f"scale: expected one of {', '.join(compute.IMPORT_SCALES.names())}, got {scale!r:.40}")
    wl = compute.grid(float(step_nm))
    lo, hi = float(spectrum.wavelengths_nm[0]), float(spectrum.wavelengths_nm[-1])
    if lo > wl[0] or hi < wl[-1]:
        raise SpectrumError(f"spectrum: covers {lo:g}-{hi:g} nm; the explorer needs 400-700 nm and never extrapolates")
    values = spectrum.resample(wl).values
    if scale == "peak":
        peak = float(values.max())
        if not peak > 0:
            raise SpectrumError("spectrum: zero everywhere in 400-700 nm; cannot scale its peak to level 30")
        unit = peak / compute.FULL_LEVEL
    else:
        unit = 1.0 / compute.FULL_LEVEL if scale == "unit" else 1.0
    levels = values / unit
    if levels.min() < 0 or levels.max() > compute.FULL_LEVEL * (1 + 1e-9):
        raise SpectrumError(f"spectrum: after scale {scale!r} the levels run from {levels.min():.4g} to "
                            f"{levels.max():.4g}; they must lie in 0-{compute.FULL_LEVEL:g} (choose scale 'peak')")
    return np.clip(levels, 0, compute.FULL_LEVEL).tolist(), unit


# ---------------------------------------------------------------------------- messages
def _json(status: int, payload: Any) -> dict:
    from .responses import FiniteJSONResponse

    return {"status": status, "body": bytes(FiniteJSONResponse(payload).body).decode("utf-8"),
            "media": "application/json", "headers": {}}


def _refusal(status: int, message: str) -> dict:
    return _json(status, {"error": message})


def answer_request(method: str, path: str, body: str | None) -> dict:
    """The answer of the explorer's server to one request, computed in the kernel.

    Returns ``{"status", "body" (text), "media", "headers"}``; a refusal or an error is
    ``{"error": "one line"}`` with status 4xx/5xx, as the server answers it.
    """
    from . import relight_routes, server

    route = urlsplit(path)
    if method == "GET" and route.path == "/api/options":
        return _json(200, server.options())
    if method == "GET" and route.path == "/api/demos":
        from .demos import demos_route

        return _json(200, demos_route())
    if method == "GET" and route.path == "/api/relight/options":
        return _json(200, relight_routes.photo_options())
    if method == "GET" and route.path == "/api/presets":
        step = parse_qs(route.query).get("step_nm", ["10"])[0]
        steps = [f"{s:g}" for s in server.compute.STEPS_NM]
        if step not in steps:
            return _refusal(422, f"step_nm: {step[:20]!r} is not one of {', '.join(steps)} (nm)")
        status, content, media, headers = server._pooled_answer("presets", json.dumps({"step_nm": int(step)}).encode())
        return {"status": status, "body": content.decode("utf-8"), "media": media, "headers": headers}
    if method == "POST" and route.path in _POSTED:
        status, content, media, headers = server._pooled_answer(_POSTED[route.path], (body or "").encode("utf-8"))
        return {"status": status, "body": content.decode("utf-8"), "media": media, "headers": headers}
    if method == "POST" and route.path == "/api/relight":
        answer = relight_routes._relight_body((body or "").encode("utf-8"))
        return _refusal(*answer) if isinstance(answer, tuple) else _json(200, answer)
    if route.path == "/api/import":
        return _refusal(404, "Load… is not available in the notebook: read the file with sc.read_spectra "
                        "and pass a spectrum to sc.explore")
    return _refusal(404, f"{route.path[:80]} is not available in the notebook widget")


def _request(message: Mapping, answer: Callable[[str, str, str | None], dict] | None = None) -> dict:
    """A request message's reply: checked as :func:`handle_message` says, then answered by
    ``answer(method, path, body)`` (default :func:`answer_request`)."""
    rid, method, path, body = (message.get(k) for k in ("id", "method", "path", "body"))
    if isinstance(rid, bool) or not isinstance(rid, int) or not 0 <= rid < 2**53:
        return {"kind": "error", "message": "request: 'id' must be a whole number 0 to 2**53"}
    reply = {"kind": "response", "id": rid}
    if method not in ("GET", "POST"):
        return {**reply, **_refusal(405, f"request: method must be GET or POST, got {method!r:.20}")}
    if not isinstance(path, str) or not path.startswith("/") or len(path) > MAX_PATH_CHARS:
        return {**reply, **_refusal(404, f"request: 'path' must be a text of the server's routes, at most "
                                          f"{MAX_PATH_CHARS} characters")}
    if body is not None and not isinstance(body, str):
        return {**reply, **_refusal(422, "request: 'body' must be text (JSON) or null")}
    limit = MAX_PHOTO_BODY_CHARS if path.startswith("/api/relight") else MAX_BODY_CHARS
    if body is not None and len(body) > limit:
        return {**reply, **_refusal(413, f"request: the body has {len(body)} characters; at most {limit}")}
    try:
        return {**reply, **(answer or answer_request)(method, path, body)}
    except (SpectrumError, ValueError) as exc:  # the library's refusal (ColorimetryError is a ValueError)
        return {**reply, **_refusal(422, str(exc).splitlines()[0][:300] if str(exc) else type(exc).__name__)}
    except Exception as exc:  # a bug: still the page's one error shape, as the server's
        return {**reply, **_refusal(500, f"internal error ({exc.__class__.__name__})")}


def handle_message(message: Any) -> dict:
    """The kernel's reply to one message of the widget's front end (see the module's docstring).

    Never raises: anything malformed is answered ``{"kind": "error", "message": "one line"}`` (or,
    for a request, the server's error shape). An ``"edited"`` message is answered
    ``{"kind": "edited", "levels": [...], "step_nm": s}`` with the checked levels, which the
    widget then takes.

    Examples
    --------
    >>> handle_message({"kind": "dance"})["message"]
    "message: 'kind' must be 'request' or 'edited', got 'dance'"
    >>> handle_message({"kind": "edited", "levels": [5] * 31, "step_nm": 10})["levels"][:2]
    [5.0, 5.0]
    """
    if not isinstance(message, Mapping):
        return {"kind": "error", "message": f"message: expected an object, got {type(message).__name__}"}
    kind = message.get("kind")
    if kind == "request":
        return _request(message)
    if kind == "edited":
        try:
            step = message.get("step_nm", 10)
            return {"kind": "edited", "levels": check_levels(message.get("levels"), step), "step_nm": float(step)}
        except SpectrumError as exc:
            return {"kind": "error", "message": str(exc)}
    return {"kind": "error", "message": f"message: 'kind' must be 'request' or 'edited', got {kind!r:.40}"}


# ---------------------------------------------------------------------------- the widget
@functools.cache
def _widget_class() -> type:
    try:
        import anywidget
        import traitlets

        from . import server  # noqa: F401  (the request models need the app extra: FastAPI, pydantic)
    except ImportError as exc:
        raise ImportError(f"sc.explore needs the notebook extra ({exc.name} is missing): {EXTRA_HINT}") from None

    class ExplorerWidget(anywidget.AnyWidget):
        """The SPECTRA explorer's setting 1 as a notebook widget (see :func:`explore`)."""

        _esm = widget_esm()
        levels: traitlets.List = traitlets.List().tag(sync=True)
        step_nm = traitlets.Float(10.0).tag(sync=True)
        name = traitlets.Unicode("").tag(sync=True)
        #: the last error the kernel sent the front end (a refused message), "" when none
        last_error = traitlets.Unicode("")

        def __init__(self, levels, step_nm, name, unit):
            self._unit = unit
            super().__init__(levels=levels, step_nm=step_nm, name=name)
            self.on_msg(self._on_message)

        @traitlets.validate("levels")
        def _valid_levels(self, proposal):
            return check_levels(proposal["value"], self.step_nm)

        def _on_message(self, _widget, content, _buffers):
            reply = handle_message(content)
            if reply["kind"] == "edited":
                with self.hold_sync(), self.hold_trait_notifications():
                    self.step_nm = reply["step_nm"]
                    self.levels = reply["levels"]
                return
            if reply["kind"] == "error":
                self.last_error = reply["message"]
            self.send(reply)

        @property
        def spectrum(self) -> Spectrum:
            """The distribution as edited: levels times the unit of a level, on the grid."""
            from . import compute

            wl = compute.grid(float(self.step_nm))
            return Spectrum(wl, np.asarray(self.levels, dtype=float) * self._unit,
                            names=(self.name,) if self.name else None)

        @spectrum.setter
        def spectrum(self, value: Spectrum) -> None:
            levels, unit = levels_of(value, self.step_nm, "peak")
            self._unit = unit
            self.levels = levels

    return ExplorerWidget


def explore(spectrum: Spectrum | None = None, *, step_nm: float = 10, scale: str = "peak",
            name: str | None = None):
    """The SPECTRA explorer's setting 1 with ``spectrum`` as its bars, as a notebook widget.

    Parameters
    ----------
    spectrum : Spectrum, optional
        One distribution covering 400-700 nm (an emission spectrum or a reflectance); resampled
        linearly onto the explorer's grid. None: the explorer's first default (equal energy).
    step_nm : {10, 5, 2, 1}
        The bin width, nm (10: SPECTRA's 31 bins, whole levels).
    scale : {"peak", "unit", "levels"}
        How values become levels 0-30, as the explorer's Load: the peak at 30, factors 0-1
        times 30, or levels already.
    name : str, optional
        The name shown on the patch (default: the spectrum's own, if it has one).

    Returns
    -------
    anywidget widget
        An ``ExplorerWidget`` (an anywidget): display it (the last expression of a cell). ``widget.spectrum`` is the
        distribution as edited in the page (on the explorer's grid, in ``spectrum``'s units:
        levels times the value of one level), ``widget.levels`` its levels 0-30 and
        ``widget.step_nm`` the grid. Assigning ``widget.spectrum`` (or ``widget.levels``) redraws
        the page. Every colour it shows is computed by the library in the kernel.

    Raises
    ------
    ImportError
        The ``notebook`` extra is not installed (``pip install 'spectrocolor[notebook]'``).
    SpectrumError
        The spectrum, step or scale is not one the explorer can show (one line saying why).

    Examples
    --------
    >>> import spectrocolor as sc
    >>> w = sc.explore(sc.illuminant("D65", sc.wavelength_grid(380, 780, 5)))  # doctest: +SKIP
    >>> w  # doctest: +SKIP
    """
    from . import compute

    if spectrum is None:
        check_levels([0.0] * len(compute.grid(float(step_nm))) if isinstance(step_nm, Real) else None, step_nm)
        first = compute.presets(float(step_nm))["setting1"][0]
        levels, unit, default_name = first["levels"], 1.0 / compute.FULL_LEVEL, first["name"]
    else:
        levels, unit = levels_of(spectrum, step_nm, scale)
        default_name = spectrum.names[0] if spectrum.names else ""
    if name is not None and not isinstance(name, str):
        raise SpectrumError(f"name: expected text, got {type(name).__name__}")
    return _widget_class()(levels, float(step_nm), (default_name if name is None else name)[:80], unit)
