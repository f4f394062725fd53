"""The explorer's HTTP server: static page plus a small JSON API, all computed by the library.

Security (see also :mod:`spectrocolor.app.guards` and ``docs/robustness.md``):

* it binds 127.0.0.1 unless told otherwise (see :mod:`spectrocolor.cli.app`) and answers only
  requests whose Host is this loopback server and whose Origin, if any, is its own page;
* bodies are counted as they stream in, whatever the transfer encoding, and refused (413) past
  :data:`MAX_BODY_BYTES`; JSON nested deeper than :data:`MAX_JSON_DEPTH` is refused before parsing;
* requests are validated by pydantic models (bin counts, finite numbers in range, known names);
  anything malformed gets a 4xx, and every error of every route -- 403, 404, 405, 413, 422,
  429 -- has one shape, ``{"error": "one line"}``, which the page shows;
* it never reads or writes a path that the page sends: uploads arrive as bytes or text and are
  parsed from a temporary file that a worker process creates (:mod:`spectrocolor.app.import_routes`,
  :mod:`spectrocolor.app.uploads`: other clients are answered meanwhile; 429 when all stay busy).

Fairness (issue 31): the presets, model, evaluate, metamer and export are *decoded, validated,
computed and written* in a worker lane of their own (:func:`_pooled_answer`); the loop passes bytes.
Pools limit each client by address and tab token (:func:`spectrocolor.app.guards.client_key`);
small routes take small bodies (:data:`SMALL_BODY_BYTES`), bounding FastAPI's decoding in the loop.
"""

from __future__ import annotations

import json
import tempfile
from collections.abc import Callable
from importlib import resources
from pathlib import Path
from typing import Annotated, Any, Literal

import anyio.to_thread
from fastapi import APIRouter, FastAPI, Request
from fastapi.exceptions import RequestValidationError
from fastapi.responses import FileResponse, JSONResponse, Response
from fastapi.routing import APIRoute
from fastapi.staticfiles import StaticFiles
from pydantic import Field, ValidationError, model_validator
from starlette.concurrency import run_in_threadpool
from starlette.exceptions import HTTPException

from ..display.chain import CHAIN_NORMALISATIONS, WHITE_ADAPTATIONS
from ..display.explain import GAMUT_ACTIONS
from ..display.gamut import GAMUT_STRATEGIES
from ..display.spaces import RGB_SPACES
from ..errors import ColorimetryError, SpectrumError
from ..illuminants import LIGHT_KINDS
from ..numba_support import call_noting_numpy_path, note_numpy_path
from ..spreadsheet import neutralise_cell
from . import compute
from .choices import (
    ADAPTATIONS,
    DISPLAYS,
    GAMUTS,
    LIGHT_KIND_NAMES,
    NORMALISATIONS,
    Adaptation,
    Display,
    Gamut,
    Normalise,
    Observer,
    Step,
    light_kind_options,
    observer_labels,
    select_options,
)
from .classroom import CLASS_BODY_BYTES, Classroom, ClassroomGuard, exempt_teacher_only
from .classroom import router as classroom_router
from .demos import router as demo_router
from .guards import MAX_JSON_DEPTH, BodyLimit, LocalOnly, allowed_hosts, client_key
from .import_routes import MAX_PARSERS, PARSER_TIMEOUT_S, PARSER_WAIT_S
from .import_routes import router as import_router
from .kernels import KernelStatusHeader
from .lab_routes import BUSY_HEADERS
from .lab_routes import _workers as lab_workers
from .lab_routes import router as lab_router
from .relight_routes import _workers as relight_workers
from .relight_routes import router as relight_router
from .request_models import Level, StrictRequest, registries_as_imported, validation_message
from .responses import FiniteJSONResponse
from .uploads import Busy, UploadParser
from .workers import WorkerDied, WorkerPool, WorkerTimeout

#: Largest request body, bytes, for every transfer encoding (Content-Length or chunked).
MAX_BODY_BYTES = 2_000_000
MAX_SPECTRA = 4
MAX_BINS = 301  # 400-700 nm at 1 nm
#: Body limit of the routes whose bodies are small (the page's interactive requests, the labs'),
#: bytes: five spectra of 301 levels written with 17 digits take about 30 kB.
SMALL_BODY_BYTES = 64_000
#: The interactive lane: worker processes for the page's model, evaluate, metamer and export
#: requests, kept apart from the uploads' and the labs' pools so that a long job there never
#: delays a dragged slider. One client (address and tab) uses one worker at a time, so another
#: client always finds one; a computation past INTERACTIVE_TIMEOUT_S has its worker killed (as
#: long as the labs allow: where the kernels compile on first use, the first one takes ~20 s).
INTERACTIVE_WORKERS = 2
INTERACTIVE_WAIT_S, INTERACTIVE_TIMEOUT_S = 10.0, 60.0
INTERACTIVE_WAITING_PER_CLIENT = 4  # of one client (or remote address); beyond, 429 at once
# (a waiting job holds one of the server's 40 threads: the pools' lines together hold under 40)
#: In class mode (issue 30) forty devices edit at once: the interactive lane's line holds one
#: job of each of CLASS_INTERACTIVE_WAITING devices (a page has one such request in flight)
#: instead of refusing a student's dragged bar with 429 whenever 8 others wait (a fifth of the
#: edits of a class of 40 were refused), and the server gets CLASS_THREADS threads for it.
CLASS_INTERACTIVE_WAITING, CLASS_THREADS = 48, 120

_interactive = WorkerPool(INTERACTIVE_WORKERS, INTERACTIVE_WAIT_S, INTERACTIVE_TIMEOUT_S,
                          per_client=1, max_waiting=4 * INTERACTIVE_WORKERS,
                          max_waiting_per_client=INTERACTIVE_WAITING_PER_CLIENT)

# Observer, Display, Gamut, Normalise and Adaptation (spectrocolor.app.choices) are checked
# against the library's registries when a request arrives: a name registered there is accepted.
Levels = Annotated[list[Level], Field(min_length=31, max_length=MAX_BINS)]


def _bins(step_nm: float) -> int:
    return len(compute.grid(float(step_nm)))



class ModelRequest(StrictRequest):
    step_nm: Step = 10
    observer: Observer = "1931"
    display: Display = "sRGB"
    illuminant: Levels | None = None

    @model_validator(mode="after")
    def _check(self):
        _check_illuminant(self.illuminant, self.step_nm)
        return self


class DisplayRequest(ModelRequest):
    """The model for one set of display choices (normalisation, adaptation of the white)."""

    normalise: Normalise = compute.DEFAULT_NORMALISE
    adaptation: Adaptation = compute.DEFAULT_ADAPTATION


class EvaluateRequest(DisplayRequest):
    gamut: Gamut = compute.DEFAULT_GAMUT
    spectra: Annotated[list[Levels], Field(min_length=1, max_length=MAX_SPECTRA)]
    pairs: Annotated[list[tuple[int, int]], Field(max_length=MAX_SPECTRA)] = []
    #: Setting 5's two spotlights (issue 28 item 7): each (a, b) appends the overlap of sent
    #: spectra a and b, their sum (:func:`spectrocolor.mixing.additive_mix`), which may pass
    #: the full level where both lights have light.
    additive: Annotated[list[tuple[int, int]], Field(max_length=MAX_SPECTRA - 1)] = []

    @model_validator(mode="after")
    def _check_sizes(self):
        k = _bins(self.step_nm)
        for i, s in enumerate(self.spectra):
            if len(s) != k:
                raise ValueError(
                    f"spectra[{i}] has {len(s)} bins; step {self.step_nm} nm over 400-700 nm "
                    f"needs {k}")
        for a, b in self.additive:
            if not (0 <= a < len(self.spectra) and 0 <= b < len(self.spectra)):
                raise ValueError(f"additive ({a}, {b}) names a spectrum that was not sent")
        total = len(self.spectra) + len(self.additive)
        if total > MAX_SPECTRA:
            raise ValueError(f"{len(self.spectra)} spectra and {len(self.additive)} additive mixes: "
                             f"at most {MAX_SPECTRA} colours in all")
        for a, b in self.pairs:
            if not (0 <= a < total and 0 <= b < total):
                raise ValueError(f"pair ({a}, {b}) names a spectrum that was not sent")
        return self


class MetamerRequest(ModelRequest):
    target: Levels

    @model_validator(mode="after")
    def _check_target(self):
        k = _bins(self.step_nm)
        if len(self.target) != k:
            raise ValueError(
                f"target has {len(self.target)} bins; step {self.step_nm} nm needs {k}")
        if max(self.target) <= 0:
            raise ValueError("target is black (all levels 0): every distribution is its metamer")
        return self


class PresetsRequest(StrictRequest):
    step_nm: Step = 10


class ExportRequest(StrictRequest):
    format: Literal["csv", "json"] = "csv"
    step_nm: Step = 10
    # any one-line text but path separators, quotes and angle brackets, so the page's names
    # ("sunset d = 0.15", "metameric grey: 1") round-trip unchanged through a file
    names: Annotated[list[Annotated[str, Field(min_length=1, max_length=60,
                                                 pattern=r"^[^\x00-\x1f\x7f-\x9f\u2028\u2029/\\\"<>]+$")]],
                     Field(min_length=1, max_length=MAX_SPECTRA)]
    spectra: Annotated[list[Levels], Field(min_length=1, max_length=MAX_SPECTRA)]

    @model_validator(mode="after")
    def _check_sizes(self):
        k = _bins(self.step_nm)
        if len(self.names) != len(self.spectra):
            raise ValueError(f"{len(self.names)} names for {len(self.spectra)} spectra")
        if len(set(self.names)) != len(self.names):
            raise ValueError("names must be different from each other")
        for i, s in enumerate(self.spectra):
            if len(s) != k:
                raise ValueError(
                    f"spectra[{i}] has {len(s)} bins; step {self.step_nm} nm needs {k}")
        return self


def _check_illuminant(levels, step_nm) -> None:
    if levels is None:
        return
    k = _bins(step_nm)
    if len(levels) != k:
        raise ValueError(f"illuminant has {len(levels)} bins; step {step_nm} nm needs {k}")
    if max(levels) <= 0:
        raise ValueError("illuminant is dark everywhere (all levels 0): nothing is lit")


def _message(exc: RequestValidationError | ValidationError) -> str:
    return validation_message(exc.errors())


def create_app(port: int | None = None, *, check_host: bool = True,
               classroom: Classroom | None = None) -> FastAPI:
    """The explorer's FastAPI application (static page at ``/``, JSON API under ``/api``).

    Parameters
    ----------
    port : int, optional
        The port the server is bound to: only ``Host`` values 127.0.0.1, localhost and [::1]
        with this port are answered. None accepts those names with any port (tests, or a server
        whose port is not known in advance).
    check_host : bool
        False only for a server that the user chose to open to other machines
        (``spectrocolor app --allow-remote``); foreign Origins are refused in any case.
    classroom : Classroom, optional
        Class mode (``spectrocolor app --classroom``, :mod:`spectrocolor.app.classroom`): only
        the class's announced Host and Origin are answered, and only with its join code or
        teacher key; ``port`` and ``check_host`` are then ignored.
    """
    app = FastAPI(title="spectrocolor explorer", docs_url=None, redoc_url=None, openapi_url=None,
                  default_response_class=FiniteJSONResponse)  # never NaN/inf, never a 500 for one
    static = Path(str(resources.files("spectrocolor.app") / "static"))
    parsers = UploadParser(MAX_PARSERS, PARSER_WAIT_S, PARSER_TIMEOUT_S)
    app.state.parsers = parsers  # for POST /api/import
    app.state.interactive = _interactive  # for the page's interactive requests
    app.router.on_startup.append(_warm_interactive)
    app.router.on_shutdown.append(parsers.close)
    app.router.on_shutdown.append(_interactive.close)
    _add_guards(app, port, check_host, classroom)
    _add_error_handlers(app)
    # --- classroom mode (issue 30): its routes, and the pools' exemption for the teacher only
    if classroom is not None:
        exempt_teacher_only([_interactive, lab_workers, relight_workers, parsers.pool])
        _interactive.max_waiting = CLASS_INTERACTIVE_WAITING
        app.router.on_startup.append(_threads_for_a_class)
        app.include_router(classroom_router)
    # --- end of classroom mode

    @app.get("/", include_in_schema=False)
    def index():
        return FileResponse(static / "index.html", media_type="text/html")

    app.mount("/static", StaticFiles(directory=static), name="static")
    app.include_router(lab_router)
    app.include_router(demo_router)  # GET /api/demos (issue 28: guided demonstrations)
    app.include_router(relight_router)
    app.include_router(import_router)
    app.include_router(router)
    return app


def _add_guards(app: FastAPI, port: int | None, check_host: bool,
                classroom: Classroom | None = None) -> None:
    """The middleware of :func:`create_app`, outermost last."""
    # added last = outermost: Host/Origin first, then the body count, then whether a result
    # used the NumPy path while the kernels compile (spectrocolor.app.kernels), then FastAPI
    app.add_middleware(KernelStatusHeader)
    small = {route.path: SMALL_BODY_BYTES for route in (*router.routes, *lab_router.routes)
             if isinstance(route, APIRoute) and "POST" in (route.methods or ())}
    if classroom is not None:  # classroom mode (issue 30): its small POST routes
        small.update({route.path: CLASS_BODY_BYTES for route in classroom_router.routes
                      if isinstance(route, APIRoute) and "POST" in (route.methods or ())})
    app.add_middleware(BodyLimit, max_bytes=MAX_BODY_BYTES, max_depth=MAX_JSON_DEPTH,
                       path_limits=small)
    if classroom is not None:  # classroom mode: the class's code or key, then its own Host
        app.add_middleware(ClassroomGuard, classroom=classroom)
        announced = classroom.origin.removeprefix("http://").lower()
        app.add_middleware(LocalOnly, hosts=frozenset({announced}), check_host=True)
        return
    app.add_middleware(LocalOnly, hosts=allowed_hosts(port), check_host=check_host)


def _add_error_handlers(app: FastAPI) -> None:
    """Every error of every route answered in the page's one shape, ``{"error": "one line"}``."""
    app.exception_handler(HTTPException)(_http_error)
    app.exception_handler(Exception)(_unexpected_error)
    app.exception_handler(RequestValidationError)(_invalid_request)
    app.exception_handler(ColorimetryError)(_library_error)
    app.exception_handler(SpectrumError)(_library_error)


async def _http_error(_request, exc: HTTPException):
    """403, 404, 405, 413, 429 and the like: the exception's detail as the line."""
    message = exc.detail if isinstance(exc.detail, str) else str(exc.status_code)
    return JSONResponse({"error": message}, status_code=exc.status_code, headers=exc.headers)


async def _unexpected_error(_request, exc: Exception):
    """A bug: still the page's error shape (500)."""
    return JSONResponse({"error": f"internal error ({exc.__class__.__name__})"},
                        status_code=500)


async def _invalid_request(_request, exc: RequestValidationError):
    """A request the models refuse: 422 with the first few of pydantic's messages."""
    return JSONResponse({"error": _message(exc)}, status_code=422)


async def _library_error(_request, exc: ValueError):
    """The library's refusal (SpectrumError, ColorimetryError): 422 with its message."""
    return JSONResponse({"error": str(exc)}, status_code=422)


#: The routes of SPECTRA's five settings, included by :func:`create_app` after the labs' routers;
#: their answers are never NaN/inf, like every answer of the app.
router = APIRouter(default_response_class=FiniteJSONResponse)


@router.get("/api/options")
def options():
    """The choices of the page's select boxes, read from the registries at every request."""
    # read from the registries at every request: an entry registered there is offered
    return {
        "steps_nm": list(compute.STEPS_NM),
        "steps": [[str(int(s)), compute.step_label(s)] for s in compute.STEPS_NM],
        "observers": observer_labels(),
        "displays": list(DISPLAYS),
        "gamuts": list(GAMUTS),
        "normalisations": list(NORMALISATIONS),
        "adaptations": select_options(WHITE_ADAPTATIONS, ADAPTATIONS),
        "light_kinds": light_kind_options(),  # "kind:T" lights, as the light lab offers them
        "gamut_actions": dict(GAMUT_ACTIONS),
        # [name, label, tooltip] rows of the page's select boxes
        "choices": {
            "gamut": select_options(GAMUT_STRATEGIES, GAMUTS, help_key="action"),
            "normalise": select_options(CHAIN_NORMALISATIONS, NORMALISATIONS, help_key="help"),
            "display": [[d, d, RGB_SPACES.description(d)] for d in DISPLAYS],
            "scale": select_options(compute.IMPORT_SCALES, compute.IMPORT_SCALES.names()),
            "light_kind": select_options(LIGHT_KINDS, LIGHT_KIND_NAMES),
        },
        "defaults": {"gamut": compute.DEFAULT_GAMUT, "normalise": compute.DEFAULT_NORMALISE,
                     "adaptation": compute.DEFAULT_ADAPTATION,
                     "display": DISPLAYS[0]},
        "full_level": compute.FULL_LEVEL,
    }


@router.get("/api/presets")
async def presets(request: Request, step_nm: str = "10"):
    """The presets on one grid (``step_nm`` as the page sends it), in the lane (0.13 s at 1 nm)."""
    steps = [f"{s:g}" for s in compute.STEPS_NM]
    if step_nm not in steps:
        return JSONResponse(
            {"error": f"step_nm: {step_nm[:20]!r} is not one of {', '.join(steps)} (nm)"},
            status_code=422)
    return await _pooled(request, "presets", json.dumps({"step_nm": int(step_nm)}).encode())


@router.post("/api/model")
async def model(request: Request):
    """:func:`spectrocolor.app.compute.model` of a :class:`DisplayRequest`, in the lane."""
    return await _pooled(request, "model")


@router.post("/api/evaluate")
async def evaluate(request: Request):
    """:func:`spectrocolor.app.compute.evaluate` of an :class:`EvaluateRequest`, in the lane."""
    return await _pooled(request, "evaluate")


@router.post("/api/metamer")
async def metamer(request: Request):
    """:func:`spectrocolor.app.compute.metamer` of a :class:`MetamerRequest`, in the lane."""
    return await _pooled(request, "metamer")


@router.post("/api/export")
async def export(request: Request):
    """The spectra of an :class:`ExportRequest` as a CSV or JSON file, written in the lane."""
    return await _pooled(request, "export")


def _export_file(req: ExportRequest) -> tuple[bytes, str, dict]:
    """Worker side: the file of :func:`export`, its media type and its headers."""
    with tempfile.TemporaryDirectory(prefix="spectrocolor-") as folder:
        path = Path(folder) / f"spectra.{req.format}"
        names = [neutralise_cell(n) for n in req.names] if req.format == "csv" else req.names
        compute.export_spectra(float(req.step_nm), names, req.spectra, path)
        body = path.read_bytes()
    media = "text/csv" if req.format == "csv" else "application/json"
    return body, media, {"Content-Disposition": f'attachment; filename="spectra.{req.format}"'}


def _model_answer(req: DisplayRequest) -> dict:
    return compute.model(float(req.step_nm), req.observer, req.display, req.illuminant,
                         req.normalise, req.adaptation)


def _evaluate_answer(req: EvaluateRequest) -> dict:
    return compute.evaluate(float(req.step_nm), req.observer, req.display, req.normalise,
                            req.gamut, req.spectra, req.illuminant, req.pairs, req.adaptation,
                            req.additive)


def _metamer_answer(req: MetamerRequest) -> dict:
    return compute.metamer(float(req.step_nm), req.observer, req.target, req.illuminant)


#: The interactive lane's routes: the request model and what answers it (in the worker).
_POOLED: dict[str, tuple[type[StrictRequest], Callable[[Any], Any]]] = {
    "model": (DisplayRequest, _model_answer),
    "evaluate": (EvaluateRequest, _evaluate_answer),
    "metamer": (MetamerRequest, _metamer_answer),
    "export": (ExportRequest, _export_file),
    "presets": (PresetsRequest, lambda req: compute.presets(float(req.step_nm))),
}
_JSON = "application/json"


def _error(status: int, message: str) -> tuple[int, bytes, str, dict]:
    return status, json.dumps({"error": message}).encode("utf-8"), _JSON, {}


def _pooled_answer(route: str, body: bytes) -> tuple[int, bytes, str, dict]:
    """Worker side: decode, validate and answer one request of the interactive lane:
    ``(status, body, media type, headers)``, a 422 in the one error shape for a refusal."""
    request_model, answer = _POOLED[route]
    try:
        data = json.loads(body)
    except (ValueError, RecursionError) as exc:  # UnicodeDecodeError is a ValueError
        return _error(422, f"the body is not JSON ({str(exc)[:120]})")
    try:
        req = request_model.model_validate(data)
    except ValidationError as exc:
        return _error(422, _message(exc))
    try:
        result = answer(req)
        if route == "export":
            return 200, *result
        return 200, bytes(FiniteJSONResponse(result).body), _JSON, {}
    except (SpectrumError, ColorimetryError) as exc:
        return _error(422, str(exc))


def _threads_for_a_class() -> None:
    """Class mode: CLASS_THREADS threads for the routes (a waiting job holds one)."""
    anyio.to_thread.current_default_thread_limiter().total_tokens = CLASS_THREADS


def _warm_interactive() -> None:
    """Start the interactive lane's workers with the server, each answering the default model."""
    for _ in range(INTERACTIVE_WORKERS):
        _interactive.warm(_pooled_answer, "model", b"{}")


async def _pooled(request: Request, route: str, body: bytes | None = None) -> Response:
    """Answer ``route`` in the interactive lane; the loop only hands the body's bytes over."""
    if body is None:
        body = await request.body()  # already read and counted by BodyLimit
    if not registries_as_imported():  # an entry registered at run time: the workers lack it
        status, content, media, headers = await run_in_threadpool(_pooled_answer, route, body)
        return Response(content, status_code=status, media_type=media, headers=headers)
    try:
        (status, content, media, headers), used_numpy_path = await run_in_threadpool(
            _interactive.run, call_noting_numpy_path, _pooled_answer, route, body,
            client=client_key(request))
    except Busy:
        return JSONResponse({"error": "the server is busy answering this page's or other "
                             "pages' requests; try again"}, status_code=429,
                            headers=BUSY_HEADERS)
    except WorkerTimeout:
        raise ColorimetryError(f"this computation took more than {INTERACTIVE_TIMEOUT_S:g} s "
                               "and was stopped; choose other settings") from None
    except WorkerDied:
        raise ColorimetryError("the worker computing this stopped (out of memory?); choose "
                               "other settings") from None
    if used_numpy_path:
        note_numpy_path()
    return Response(content, status_code=status, media_type=media, headers=headers)
