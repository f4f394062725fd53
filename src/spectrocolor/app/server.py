"""The explorer's HTTP server: static page plus a small JSON API, all computed by the library.

Security (see also :mod:`spectrocolor.app.guards` and ``docs/robustness.md``):

* it binds 127.0.0.1 unless told otherwise (see :mod:`spectrocolor.cli.app`) and answers only
  requests whose Host is this loopback server and whose Origin, if any, is its own page;
* bodies are counted as they stream in, whatever the transfer encoding, and refused (413) past
  :data:`MAX_BODY_BYTES`; JSON nested deeper than :data:`MAX_JSON_DEPTH` is refused before parsing;
* requests are validated by pydantic models (bin counts, finite numbers in range, known names);
  anything malformed gets a 4xx, and every error of every route -- 403, 404, 405, 413, 422,
  429 -- has one shape, ``{"error": "one line"}``, which the page shows;
* it never reads or writes a path that the page sends: uploads arrive as text and are parsed
  from a temporary file that a worker process creates, at most :data:`MAX_PARSERS` at a time
  (:mod:`spectrocolor.app.uploads`: other clients are answered meanwhile; 429 when all stay
  busy).
"""

from __future__ import annotations

import base64
import binascii
import tempfile
from importlib import resources
from pathlib import Path
from typing import Annotated, Literal

from fastapi import APIRouter, FastAPI, Request
from fastapi.exceptions import RequestValidationError
from fastapi.responses import FileResponse, JSONResponse, Response
from fastapi.staticfiles import StaticFiles
from pydantic import Field, model_validator
from starlette.exceptions import HTTPException

from ..display.chain import CHAIN_NORMALISATIONS, WHITE_ADAPTATIONS
from ..display.explain import GAMUT_ACTIONS
from ..display.gamut import GAMUT_STRATEGIES
from ..display.spaces import RGB_SPACES
from ..errors import ColorimetryError, SpectrumError
from ..illuminants import LIGHT_KINDS
from ..interpolation import METHODS as INTERPOLATION_METHODS
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
    choice,
    light_kind_options,
    observer_labels,
    select_options,
)
from .guards import BodyLimit, LocalOnly, allowed_hosts, json_depth
from .kernels import KernelStatusHeader
from .lab_routes import router as lab_router
from .relight_routes import router as relight_router
from .request_models import Level, StrictRequest
from .responses import FiniteJSONResponse
from .uploads import Busy, UploadParser

#: Largest request body, bytes, for every transfer encoding (Content-Length or chunked).
MAX_BODY_BYTES = 2_000_000
#: Deepest JSON nesting accepted in a body or an imported file (the API needs 3).
MAX_JSON_DEPTH = 32
#: Imports parsed at the same time, each in a worker process; more wait up to PARSER_WAIT_S,
#: then get 429.
MAX_PARSERS = 2
PARSER_WAIT_S = 10.0
#: Longest parse of one upload, seconds.
PARSER_TIMEOUT_S = 60.0
MAX_SPECTRA = 4
#: Spectra one imported file may hold; the page lets the user choose which to edit.
MAX_IMPORT_SPECTRA = 64
MAX_BINS = 301  # 400-700 nm at 1 nm
#: Largest imported file, bytes (as text: characters), and its base64 length.
MAX_IMPORT_BYTES = 1_000_000
MAX_IMPORT_BASE64 = 4 * ((MAX_IMPORT_BYTES + 2) // 3)

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

    @model_validator(mode="after")
    def _check_sizes(self):
        k = _bins(self.step_nm)
        for i, s in enumerate(self.spectra):
            if len(s) != k:
                raise ValueError(
                    f"spectra[{i}] has {len(s)} bins; step {self.step_nm} nm over 400-700 nm "
                    f"needs {k}")
        for a, b in self.pairs:
            if not (0 <= a < len(self.spectra) and 0 <= b < len(self.spectra)):
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


class ImportRequest(StrictRequest):
    """An uploaded file: its text (``content``, already decoded) or, as the page sends it, its
    bytes (``content_base64``), decoded on the server as the library decodes a file
    (:func:`spectrocolor.io.decode_text`), so Latin-1/cp1252 exports read as they do on the
    command line. ``observer``: the page's observer, for the note on the file's declared conditions."""

    filename: Annotated[str, Field(min_length=1, max_length=200)]
    content: Annotated[str | None, Field(min_length=1, max_length=1_000_000)] = None
    content_base64: Annotated[str | None, Field(min_length=1, max_length=MAX_IMPORT_BASE64)] = None
    step_nm: Step = 10
    method: Annotated[str, choice(INTERPOLATION_METHODS)] = "linear"
    scale: Annotated[str, choice(compute.IMPORT_SCALES.names_view())] = "peak"
    observer: Observer | None = None

    @model_validator(mode="after")
    def _one_content(self):
        if (self.content is None) == (self.content_base64 is None):
            raise ValueError("give the file as content (text) or content_base64 (its bytes), one of them")
        return self

    def file_bytes(self) -> bytes | str:
        """The file: bytes decoded from ``content_base64``, else the text ``content``."""
        if self.content_base64 is None:
            assert self.content is not None  # _one_content
            return self.content
        try:
            data = base64.b64decode(self.content_base64, validate=True)
        except (binascii.Error, ValueError):
            raise SpectrumError(f"{self.filename}: content_base64 is not base64 (RFC 4648: A-Z a-z 0-9 + / =)") \
                from None
        if not data or len(data) > MAX_IMPORT_BYTES:
            raise SpectrumError(f"{self.filename}: the file must be 1 to {MAX_IMPORT_BYTES} bytes, got {len(data)}")
        return data


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


def _message(exc: RequestValidationError) -> str:
    parts = []
    for err in exc.errors():
        where = ".".join(str(p) for p in err.get("loc", ()) if p != "body")
        msg = str(err.get("msg", "invalid")).removeprefix("Value error, ")
        parts.append(f"{where}: {msg}" if where else msg)
    return "; ".join(parts[:5]) + (f" (and {len(parts) - 5} more)" if len(parts) > 5 else "")


def create_app(port: int | None = None, *, check_host: bool = True) -> FastAPI:
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
    """
    app = FastAPI(title="spectrocolor explorer", docs_url=None, redoc_url=None, openapi_url=None,
                  default_response_class=FiniteJSONResponse)  # never NaN/inf, never a 500 for one
    static = Path(str(resources.files("spectrocolor.app") / "static"))
    parsers = UploadParser(MAX_PARSERS, PARSER_WAIT_S, PARSER_TIMEOUT_S)
    app.state.parsers = parsers  # for POST /api/import
    app.router.on_shutdown.append(parsers.close)
    _add_guards(app, port, check_host)
    _add_error_handlers(app)

    @app.get("/", include_in_schema=False)
    def index():
        return FileResponse(static / "index.html", media_type="text/html")

    app.mount("/static", StaticFiles(directory=static), name="static")
    app.include_router(lab_router)
    app.include_router(relight_router)
    app.include_router(router)
    return app


def _add_guards(app: FastAPI, port: int | None, check_host: bool) -> None:
    """The middleware of :func:`create_app`, outermost last."""
    # added last = outermost: Host/Origin first, then the body count, then whether a result
    # used the NumPy path while the kernels compile (spectrocolor.app.kernels), then FastAPI
    app.add_middleware(KernelStatusHeader)
    app.add_middleware(BodyLimit, max_bytes=MAX_BODY_BYTES, max_depth=MAX_JSON_DEPTH)
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
def presets(step_nm: str = "10"):
    """The preset distributions on one grid (``step_nm`` as the page sends it)."""
    steps = [f"{s:g}" for s in compute.STEPS_NM]
    if step_nm not in steps:
        return JSONResponse(
            {"error": f"step_nm: {step_nm[:20]!r} is not one of {', '.join(steps)} (nm)"},
            status_code=422)
    return compute.presets(float(step_nm))


@router.post("/api/model")
def model(req: DisplayRequest):
    """:func:`spectrocolor.app.compute.model` for one set of display choices."""
    return compute.model(float(req.step_nm), req.observer, req.display, req.illuminant,
                         req.normalise, req.adaptation)


@router.post("/api/evaluate")
def evaluate(req: EvaluateRequest):
    """:func:`spectrocolor.app.compute.evaluate` of the spectra sent."""
    return compute.evaluate(float(req.step_nm), req.observer, req.display, req.normalise,
                            req.gamut, req.spectra, req.illuminant, req.pairs,
                            req.adaptation)


@router.post("/api/metamer")
def metamer(req: MetamerRequest):
    """:func:`spectrocolor.app.compute.metamer` of the target."""
    return compute.metamer(float(req.step_nm), req.observer, req.target, req.illuminant)


@router.post("/api/import")
def import_(req: ImportRequest, request: Request):  # a plain def: run in FastAPI's threads
    """The spectra of an uploaded file, parsed in a worker process (429 when all stay busy)."""
    parsers: UploadParser = request.app.state.parsers
    content = req.file_bytes()  # bytes are decoded in the worker, as read_spectra decodes a file
    suffix = ".json" if req.filename.lower().endswith(".json") else ".csv"
    raw = content if isinstance(content, bytes) else content.encode("utf-8")
    if suffix == ".json" and json_depth(raw) > MAX_JSON_DEPTH:
        raise SpectrumError(f"{req.filename}: JSON nested deeper than {MAX_JSON_DEPTH} levels")
    try:  # in a worker process: other clients keep being answered meanwhile
        return parsers.parse(req.filename, content, suffix, float(req.step_nm),
                             req.method, req.scale, MAX_IMPORT_SPECTRA,
                             client=request.client.host if request.client else None,
                             observer=req.observer)
    except Busy:
        return JSONResponse({"error": "the server is busy reading other files; try again"},
                            status_code=429)


@router.post("/api/export")
def export(req: ExportRequest):
    """The spectra as a CSV or JSON file to download."""
    with tempfile.TemporaryDirectory(prefix="spectrocolor-") as folder:
        path = Path(folder) / f"spectra.{req.format}"
        names = [neutralise_cell(n) for n in req.names] if req.format == "csv" else req.names
        compute.export_spectra(float(req.step_nm), names, req.spectra, path)
        body = path.read_bytes()
    media = "text/csv" if req.format == "csv" else "application/json"
    return Response(body, media_type=media, headers={
        "Content-Disposition": f'attachment; filename="spectra.{req.format}"'})
