"""The explorer's labs inside a notebook: :func:`explore_lab` (``sc.explore_lab("thinfilm")``).

``explore_lab(name)`` returns a notebook widget showing one of the explorer's labs (light sources,
smoothest reflectance, object-colour solid, thin films). As :func:`~spectrocolor.app.notebook_widget.explore`
does for the explorer, it runs the lab's own page (``static/labs/<name>.html``, its stylesheets)
and ES modules (``static/labs/<name>.js``, ``labs/common.js`` and the ``js/*.js`` modules they
import, joined into one module by :func:`spectrocolor.app.notebook_frontend.lab_widget_esm`) in a
shadow root, and the lab's requests travel to the kernel as widget messages instead of HTTP; the
kernel answers them with the server's lab routes themselves (:mod:`spectrocolor.app.lab_routes`:
the same request models, the route functions, the same JSON), computing in the kernel's own
process rather than in a worker.

Edits flow back. A lab keeps its state in its address (the hash: ``#film=soap&d=350``); in the
widget each change of it reaches the kernel as ``widget.state`` (a dict of the address's
parameters, as text), and assigning ``widget.state`` in Python moves the page there. The kernel
also keeps the last answer of the lab's main computation as ``widget.result`` (the JSON the page
drew), and ``widget.spectrum`` reads the spectrum it shows: the light's SPD (light lab), the
smoothest reflectances (reflectance lab), the film's reflectance at the chosen thickness
(thin-film lab).

Messages (front end to kernel, one dict each, answered by :func:`handle_lab_message`):

* ``{"kind": "request", ...}`` as :func:`~spectrocolor.app.notebook_widget.handle_message`, answered
  by :func:`answer_lab_request` (the lab routes; any other route as the explorer widget answers it);
* ``{"kind": "state", "address": "film=soap&d=350"}`` sets ``widget.state`` after checking the text
  (:func:`check_address`);
* anything else gets ``{"kind": "error", "message": "one line"}``, never a traceback.

Example
-------
>>> check_address("film=soap&d=350")
{'film': 'soap', 'd': '350'}
"""

from __future__ import annotations

import functools
import json
import math
import re
import typing
from collections.abc import Mapping
from numbers import Real
from typing import Any
from urllib.parse import parse_qsl, urlencode, urlsplit

import numpy as np

from ..errors import ColorimetryError, SpectrumError
from ..spectrum import Spectrum
from .notebook_frontend import LABS, lab_widget_esm
from .notebook_widget import EXTRA_HINT, _json, _refusal, _request, answer_request

__all__ = ["ADDRESS_KEYS", "LABS", "answer_lab_request", "check_address", "explore_lab", "handle_lab_message"]

#: The parameters of each lab's address (the hash its page keeps its state in, read by the lab's
#: ``decode``), which :func:`explore_lab` accepts as keywords.
ADDRESS_KEYS: dict[str, tuple[str, ...]] = {
    "light": ("kind", "name", "T", "display", "leds"),
    "reflectance": ("light", "step", "x", "y", "Y"),
    "solid": ("light", "display", "Y", "sample", "second", "yaw", "pitch", "mismatch"),
    "thinfilm": ("film", "model", "light", "display", "angle", "d"),
}
#: Longest address the widget keeps, characters; most parameters; longest value.
MAX_ADDRESS_CHARS, MAX_PARAMETERS, MAX_VALUE_CHARS = 2000, 40, 200
_KEY = re.compile(r"^[A-Za-z_][A-Za-z0-9_]{0,19}$")


def _lab_name(lab: Any) -> str:
    if not isinstance(lab, str) or lab not in LABS:
        raise SpectrumError(f"lab: expected one of {', '.join(repr(n) for n in LABS)}, got {lab!r:.40}")
    return lab


# ---------------------------------------------------------------------------- the lab routes
@functools.cache
def _routes() -> tuple[dict, dict]:
    """The lab routes: GET path to its answer, POST path to (request model, the route's function).

    The POST routes are read from the lab routes' router, so a route added there is answered here
    too, by the route's own function (called without a request: it computes in this process, not
    in a worker). The GET routes (options) are the functions they return, as calling those routes
    would start a worker process in the kernel.
    """
    from fastapi.routing import APIRoute
    from pydantic import BaseModel

    from . import lab_routes as r
    from . import light_lab, reflectance_lab, solid_lab, thinfilm_lab

    gets = {"/api/lab/light/options": light_lab.light_lab_options,
            "/api/lab/thinfilm/options": thinfilm_lab.lab_options,
            "/api/lab/reflectance/options": reflectance_lab.reflectance_lab_options,
            "/api/lab/solid/options": solid_lab.solid_lab_options}
    posts = {}
    for route in r.router.routes:
        if isinstance(route, APIRoute) and "POST" in (route.methods or ()):
            hints = typing.get_type_hints(route.endpoint)
            models = [h for h in hints.values() if isinstance(h, type) and issubclass(h, BaseModel)]
            if len(models) == 1:
                posts[route.path] = (models[0], route.endpoint)
    return gets, posts


def lab_routes() -> tuple[tuple[str, str], ...]:
    """The (method, path) of every lab route the widget answers.

    Examples
    --------
    >>> ("POST", "/api/lab/thinfilm") in lab_routes()
    True
    """
    gets, posts = _routes()
    return tuple(("GET", p) for p in gets) + tuple(("POST", p) for p in posts)


def answer_lab_request(method: str, path: str, body: str | None) -> dict:
    """The server's answer to one request of a lab's page, computed in the kernel.

    The lab routes (:func:`lab_routes`) are validated by the server's request models and answered
    by the functions its routes call; any other route (``GET /api/demos`` for the Demos panel) as
    :func:`~spectrocolor.app.notebook_widget.answer_request` answers it. Returns ``{"status",
    "body" (text), "media", "headers"}``; a refusal is ``{"error": "one line"}`` with status 4xx.

    Examples
    --------
    >>> answer_lab_request("GET", "/api/lab/solid/options", None)["status"]
    200
    >>> json.loads(answer_lab_request("POST", "/api/lab/solid", '{"Y": 500}')["body"])["error"]
    'Y: Input should be less than 100'
    """
    from pydantic import ValidationError

    from .request_models import validation_message

    gets, posts = _routes()
    route = urlsplit(path).path
    if method == "GET" and route in gets:
        return _json(200, gets[route]())
    if method == "POST" and route in posts:
        model, answer = posts[route]
        try:
            data = json.loads(body or "")
        except (ValueError, RecursionError) as exc:
            return _refusal(422, f"the body is not JSON ({str(exc)[:120]})")
        try:
            request = model.model_validate(data)
        except ValidationError as exc:
            return _refusal(422, validation_message(exc.errors()))
        try:
            response = answer(request, None)  # the route itself, computing in this process
        except (SpectrumError, ColorimetryError) as exc:  # as the server's handler of the library's refusals
            return _refusal(422, str(exc))
        return {"status": response.status_code, "body": bytes(response.body).decode("utf-8"),
                "media": "application/json", "headers": {}}
    if route in gets or route in posts:
        return _refusal(405, "Method Not Allowed")
    return answer_request(method, path, body)


# ---------------------------------------------------------------------------- state
def check_address(address: Any) -> dict[str, str]:
    """A lab's address (its hash, without ``#``) as a dict of its parameters, checked.

    Raises
    ------
    SpectrumError
        One line: not text, too long (:data:`MAX_ADDRESS_CHARS`), too many parameters, a name
        that is not a plain identifier, or a value over :data:`MAX_VALUE_CHARS` characters.

    Examples
    --------
    >>> check_address("light=D65&x=0.3")
    {'light': 'D65', 'x': '0.3'}
    >>> check_address("x" * 3000)
    Traceback (most recent call last):
    ...
    spectrocolor.errors.SpectrumError: address: 3000 characters; at most 2000
    """
    if not isinstance(address, str):
        raise SpectrumError(f"address: expected text (the lab's hash), got {type(address).__name__}")
    if len(address) > MAX_ADDRESS_CHARS:
        raise SpectrumError(f"address: {len(address)} characters; at most {MAX_ADDRESS_CHARS}")
    pairs = parse_qsl(address.removeprefix("#"), keep_blank_values=True, max_num_fields=MAX_PARAMETERS) \
        if address.count("&") < MAX_PARAMETERS else None
    if pairs is None:
        raise SpectrumError(f"address: more than {MAX_PARAMETERS} parameters")
    out = {}
    for key, value in pairs:
        if not _KEY.match(key):
            raise SpectrumError(f"address: parameter name {key!r:.30} is not a plain name (letters, digits, _)")
        if len(value) > MAX_VALUE_CHARS:
            raise SpectrumError(f"address: {key}'s value has {len(value)} characters; at most {MAX_VALUE_CHARS}")
        out[key] = value
    return out


def _address_value(key: str, value: Any) -> str:
    if isinstance(value, bool) or not isinstance(value, (str, Real)):
        raise SpectrumError(f"{key}: expected text or a number, got {type(value).__name__}")
    if isinstance(value, Real):
        if not math.isfinite(float(value)):
            raise SpectrumError(f"{key}: expected a finite number, got {value!r}")
        return f"{float(value):.10g}" if not isinstance(value, int) else str(value)
    if len(value) > MAX_VALUE_CHARS:
        raise SpectrumError(f"{key}: {len(value)} characters; at most {MAX_VALUE_CHARS}")
    return value


def initial_address(lab: str, spectrum: Spectrum | None = None, **address: Any) -> str:
    """The address :func:`explore_lab` opens ``lab`` at (see there), as text.

    Examples
    --------
    >>> initial_address("thinfilm", film="oil", d=420)
    'film=oil&d=420'
    """
    lab = _lab_name(lab)
    unknown = sorted(set(address) - set(ADDRESS_KEYS[lab]))
    if unknown:
        raise SpectrumError(f"{unknown[0]}: not a setting of the {lab} lab; expected one of "
                            f"{', '.join(ADDRESS_KEYS[lab])}" + (" or spectrum" if lab == "reflectance" else ""))
    state = {k: _address_value(k, v) for k, v in address.items()}
    if spectrum is not None:
        if lab != "reflectance":
            raise SpectrumError(f"spectrum: only the reflectance lab starts from a spectrum (its colour); "
                                f"the {lab} lab takes {', '.join(ADDRESS_KEYS[lab])}")
        if {"x", "y", "Y"} & set(address):
            raise SpectrumError("spectrum: give either a spectrum or x, y, Y, not both")
        xyY = reflectance_xyY(spectrum, state.get("light", "D65"))
        state.update({k: f"{v:.6g}" for k, v in zip(("x", "y", "Y"), xyY, strict=True)})
    text = urlencode(state)
    check_address(text)
    return text


def reflectance_xyY(spectrum: Spectrum, light: str = "D65") -> tuple[float, float, float]:
    """The colour (CIE 1931 x, y and Y in %) of one reflectance under ``light``, as the
    reflectance lab takes it.

    Examples
    --------
    >>> import numpy as np
    >>> x, y, Y = reflectance_xyY(Spectrum(np.arange(380, 781, 5.0), np.full(81, 0.5)))
    >>> round(x, 4), round(y, 4), round(Y, 6)
    (0.3127, 0.329, 50.0)
    """
    from ..colorimetry import tristimulus

    if not isinstance(spectrum, Spectrum):
        raise SpectrumError(f"spectrum: expected a spectrocolor.Spectrum, got {type(spectrum).__name__}")
    if spectrum.values.ndim != 1:
        raise SpectrumError(f"spectrum: expected one reflectance, got a batch of shape {spectrum.values.shape}")
    XYZ = np.asarray(tristimulus(spectrum, illuminant=light), dtype=float)
    total = float(XYZ.sum())
    if not (np.all(np.isfinite(XYZ)) and total > 0 and 0 < XYZ[1] <= 100):
        raise SpectrumError(f"spectrum: its luminance factor under {light} is {XYZ[1]:.4g} %; the reflectance "
                            "lab takes a colour with Y in (0, 100] %")
    return float(XYZ[0] / total), float(XYZ[1] / total), float(XYZ[1])


# ---------------------------------------------------------------------------- messages
def handle_lab_message(lab: str, message: Any) -> dict:
    """The kernel's reply to one message of a lab widget's front end (see the module's docstring).

    Never raises for a malformed message: it is answered ``{"kind": "error", "message": "one
    line"}`` (or, for a request, in the server's error shape). A ``"state"`` message is answered
    ``{"kind": "state", "address": text, "state": {...}}``, which the widget then takes.

    Examples
    --------
    >>> handle_lab_message("thinfilm", {"kind": "state", "address": "d=420"})["state"]
    {'d': '420'}
    >>> handle_lab_message("thinfilm", {"kind": "edited"})["message"]
    "message: 'kind' must be 'request' or 'state', got 'edited'"
    """
    _lab_name(lab)
    if not isinstance(message, Mapping):
        return {"kind": "error", "message": f"message: expected an object, got {type(message).__name__}"}
    kind = message.get("kind")
    if kind == "request":  # checked as the explorer's (at most MAX_BODY_CHARS of body)
        return _request(message, answer_lab_request)
    if kind == "state":
        address = message.get("address")
        try:
            return {"kind": "state", "address": address, "state": check_address(address)}
        except SpectrumError as exc:
            return {"kind": "error", "message": str(exc)}
    return {"kind": "error", "message": f"message: 'kind' must be 'request' or 'state', got {kind!r:.40}"}


# ---------------------------------------------------------------------------- the widget
def _result_spectrum(lab: str, result: Mapping | None, state: Mapping[str, str]) -> Spectrum:
    if result is None:
        raise SpectrumError(f"the {lab} lab has not shown a result yet (display the widget and wait for it)")
    wl = np.asarray(result["wavelengths_nm"], dtype=float)
    if lab == "light":
        return Spectrum(wl, np.asarray(result["spd"], dtype=float), names=(str(result["label"]),))
    if lab == "reflectance":
        shown = {n: s["reflectance"] for n, s in result["solutions"].items() if s["reflectance"] is not None}
        if not shown:
            raise SpectrumError("no reflectance has this colour under this light (the lab shows none)")
        return Spectrum(wl, np.asarray(list(shown.values()), dtype=float), names=tuple(shown))
    if lab == "thinfilm":
        thickness = np.asarray(result["thickness_nm"], dtype=float)
        try:
            d = float(state.get("d", "350"))
        except ValueError:
            d = 350.0
        row = int(np.argmin(np.abs(thickness - d))) if math.isfinite(d) else 0
        return Spectrum(wl, np.asarray(result["reflectance"][row], dtype=float),
                        names=(f"{result['film']} {thickness[row]:g} nm",))
    raise SpectrumError(f"the {lab} lab shows no one spectrum (widget.result holds its numbers)")


@functools.cache
def _widget_class(lab: str) -> type:
    try:
        import anywidget
        import traitlets

        from . import lab_routes  # noqa: F401  (the request models need the app extra: FastAPI, pydantic)
    except ImportError as exc:
        raise ImportError(f"sc.explore_lab needs the notebook extra ({exc.name} is missing): {EXTRA_HINT}") from None
    esm = lab_widget_esm(lab)  # (the class body below names its property `lab`)

    class LabWidget(anywidget.AnyWidget):
        """One of the explorer's labs as a notebook widget (see :func:`explore_lab`)."""

        _esm = esm
        address = traitlets.Unicode("").tag(sync=True)
        #: the last error the kernel sent the front end (a refused message), "" when none
        last_error = traitlets.Unicode("")

        def __init__(self, address: str):
            #: the last answer of the lab's main computation (``POST /api/lab/<lab>``), None before
            self.result: dict | None = None
            super().__init__(address=address)
            self.on_msg(self._on_message)

        @property
        def lab(self) -> str:
            return lab

        @traitlets.validate("address")
        def _valid_address(self, proposal):
            check_address(proposal["value"])
            return proposal["value"]

        def _on_message(self, _widget, content, _buffers):
            reply = handle_lab_message(lab, content)
            if reply["kind"] == "state":
                self.address = reply["address"]
                return
            if reply["kind"] == "error":
                self.last_error = reply["message"]
            elif (reply["kind"] == "response" and reply["status"] == 200 and isinstance(content, Mapping)
                  and urlsplit(content.get("path", "")).path == f"/api/lab/{lab}"
                  and content.get("method") == "POST"):
                self.result = json.loads(reply["body"])
            self.send(reply)

        @property
        def state(self) -> dict[str, str]:
            """The lab's state as its address has it (parameter to text); assign a dict to move the page."""
            return check_address(self.address)

        @state.setter
        def state(self, value: Mapping[str, Any]) -> None:
            if not isinstance(value, Mapping):
                raise SpectrumError(f"state: expected a dict of the address's parameters, got {type(value).__name__}")
            self.address = urlencode({str(k): _address_value(str(k), v) for k, v in value.items()})

        @property
        def spectrum(self) -> Spectrum:
            """The spectrum the lab shows (see :func:`explore_lab`), from :attr:`result`."""
            return _result_spectrum(lab, self.result, self.state)

    LabWidget.__name__ = LabWidget.__qualname__ = f"{lab.capitalize()}LabWidget"
    return LabWidget


def explore_lab(lab: str, spectrum: Spectrum | None = None, **settings: Any):
    """One of the explorer's labs as a notebook widget.

    Parameters
    ----------
    lab : {"light", "reflectance", "solid", "thinfilm"}
        The lab: light sources (colour rendering of a light), the smoothest reflectance of a
        colour, the object-colour solid, thin-film interference colours.
    spectrum : Spectrum, optional
        Reflectance lab only: one reflectance (0-1) whose colour, CIE 1931 xyY under the lab's
        light (``light=``, default D65), the lab starts from.
    **settings : str or float
        The lab's starting state, as its address names it (``spectrocolor.app.notebook_labs.ADDRESS_KEYS``): light lab
        ``kind`` ("named" or "leds"), ``name`` (a light such as "FL2", or a light kind such as
        "blackbody" with ``T`` in K), ``display``, ``leds`` ("peak:width:power,..."); reflectance
        lab ``light``, ``step`` (nm), ``x``, ``y``, ``Y`` (%); solid lab ``light``, ``display``,
        ``Y``, ``sample``, ``second``, ``yaw``, ``pitch``; thin-film lab ``film``, ``model``,
        ``light``, ``display``, ``angle`` (degrees), ``d`` (thickness, nm). Text or numbers; the
        page checks the values as it checks its address (an unknown value falls back to its
        default).

    Returns
    -------
    anywidget widget
        A ``<Lab>LabWidget`` (an anywidget): display it. ``widget.state`` is the lab's state as
        edited in the page (a dict of its address's parameters, as text; assign one to move the
        page), ``widget.result`` the last answer of the lab's computation (the JSON the page
        drew, computed in the kernel) and ``widget.spectrum`` the spectrum it shows (light lab:
        the light's relative SPD; reflectance lab: the smoothest reflectances, one row each;
        thin-film lab: the film's reflectance at the chosen thickness).

    Raises
    ------
    ImportError
        The ``notebook`` extra is not installed (``pip install 'spectrocolor[notebook]'``).
    SpectrumError
        An unknown lab or setting, or a value that is neither text nor a finite number (one line).

    Examples
    --------
    >>> import spectrocolor as sc
    >>> w = sc.explore_lab("thinfilm", film="soap", d=420)  # doctest: +SKIP
    >>> w  # doctest: +SKIP
    >>> w.state["d"], w.spectrum  # doctest: +SKIP
    """
    address = initial_address(lab, spectrum, **settings)
    return _widget_class(lab)(address)
