"""The explorer's HTTP server: static page plus a small JSON API, all computed by the library.

Security: it binds 127.0.0.1 unless told otherwise (see :mod:`spectrocolor.cli.app`), accepts
only JSON bodies of bounded size validated by pydantic models (bin counts, finite numbers in
range, known names), answers anything malformed with a 4xx and a one-line message, and never
reads or writes a path that the page sends: uploads arrive as text and are parsed from a
temporary file that the server itself creates.
"""

from __future__ import annotations

import tempfile
from importlib import resources
from pathlib import Path
from typing import Annotated, Literal

from fastapi import FastAPI, Request
from fastapi.exceptions import RequestValidationError
from fastapi.responses import FileResponse, JSONResponse, Response
from fastapi.staticfiles import StaticFiles
from pydantic import BaseModel, ConfigDict, Field, model_validator

from spectrocolor.errors import ColorimetryError, SpectrumError

from . import compute

MAX_BODY_BYTES = 2_000_000
MAX_SPECTRA = 4
MAX_BINS = 301  # 400-700 nm at 1 nm

Step = Literal[10, 5, 2, 1]
Observer = Literal["1931", "1964", "2015-2", "2015-10"]
Display = Literal["sRGB", "SPECTRA 7000K", "Display P3", "SPECTRA equal-energy"]
Gamut = Literal["flag", "clip", "preserve-luminance", "desaturate"]
Normalise = Literal["fixed", "per-colour"]
Level = Annotated[float, Field(ge=0, le=compute.FULL_LEVEL, allow_inf_nan=False)]
Levels = Annotated[list[Level], Field(min_length=31, max_length=MAX_BINS)]


def _bins(step_nm: float) -> int:
    return len(compute.grid(float(step_nm)))


class _Strict(BaseModel):
    model_config = ConfigDict(extra="forbid")

    @model_validator(mode="before")
    @classmethod
    def _no_bool_step(cls, data):
        # JSON true/false would pass as 1/0 (bool is an int in Python): not a step in nm
        if isinstance(data, dict) and isinstance(data.get("step_nm"), bool):
            raise ValueError("step_nm: expected a number of nm (10, 5, 2 or 1), got a boolean")
        return data


class ModelRequest(_Strict):
    step_nm: Step = 10
    observer: Observer = "1931"
    display: Display = "sRGB"
    illuminant: Levels | None = None

    @model_validator(mode="after")
    def _check(self):
        _check_illuminant(self.illuminant, self.step_nm)
        return self


class EvaluateRequest(ModelRequest):
    normalise: Normalise = "fixed"
    gamut: Gamut = "flag"
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


class ImportRequest(_Strict):
    filename: Annotated[str, Field(min_length=1, max_length=200)]
    content: Annotated[str, Field(min_length=1, max_length=1_000_000)]
    step_nm: Step = 10
    method: Literal["linear", "sprague", "cubic"] = "linear"
    scale: Literal["peak", "unit", "levels"] = "peak"


class ExportRequest(_Strict):
    format: Literal["csv", "json"] = "csv"
    step_nm: Step = 10
    names: Annotated[list[Annotated[str, Field(min_length=1, max_length=60,
                                                 pattern=r"^[\w .,()+\-]+$")]],
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


def create_app() -> FastAPI:
    """The explorer's FastAPI application (static page at ``/``, JSON API under ``/api``)."""
    app = FastAPI(title="spectrocolor explorer", docs_url=None, redoc_url=None, openapi_url=None)
    static = Path(str(resources.files("spectrocolor.app") / "static"))

    @app.middleware("http")
    async def _limit_body(request: Request, call_next):
        length = request.headers.get("content-length")
        if length is not None and (not length.isdigit() or int(length) > MAX_BODY_BYTES):
            return JSONResponse({"error": f"request body larger than {MAX_BODY_BYTES} bytes"},
                                status_code=413)
        return await call_next(request)

    @app.exception_handler(RequestValidationError)
    async def _invalid(_request, exc: RequestValidationError):
        return JSONResponse({"error": _message(exc)}, status_code=422)

    @app.exception_handler(SpectrumError)
    @app.exception_handler(ColorimetryError)
    async def _library(_request, exc: ValueError):
        return JSONResponse({"error": str(exc)}, status_code=422)

    @app.get("/", include_in_schema=False)
    def index():
        return FileResponse(static / "index.html", media_type="text/html")

    app.mount("/static", StaticFiles(directory=static), name="static")

    @app.get("/api/options")
    def options():
        return {
            "steps_nm": list(compute.STEPS_NM),
            "observers": compute.OBSERVERS,
            "displays": list(compute.DISPLAYS),
            "gamuts": list(compute.GAMUTS),
            "normalisations": list(compute.NORMALISATIONS),
            "full_level": compute.FULL_LEVEL,
        }

    @app.get("/api/presets")
    def presets(step_nm: str = "10"):
        if step_nm not in ("10", "5", "2", "1"):
            return JSONResponse(
                {"error": f"step_nm: {step_nm[:20]!r} is not one of 10, 5, 2, 1 (nm)"},
                status_code=422)
        return compute.presets(float(step_nm))

    @app.post("/api/model")
    def model(req: ModelRequest):
        return compute.model(float(req.step_nm), req.observer, req.display, req.illuminant)

    @app.post("/api/evaluate")
    def evaluate(req: EvaluateRequest):
        return compute.evaluate(float(req.step_nm), req.observer, req.display, req.normalise,
                                req.gamut, req.spectra, req.illuminant, req.pairs)

    @app.post("/api/metamer")
    def metamer(req: MetamerRequest):
        return compute.metamer(float(req.step_nm), req.observer, req.target, req.illuminant)

    @app.post("/api/import")
    def import_(req: ImportRequest):
        suffix = ".json" if req.filename.lower().endswith(".json") else ".csv"
        with tempfile.TemporaryDirectory(prefix="spectrocolor-") as folder:
            path = Path(folder) / f"upload{suffix}"
            path.write_text(req.content, encoding="utf-8")
            try:
                return compute.import_spectra(path, float(req.step_nm), req.method, req.scale,
                                              max_spectra=MAX_SPECTRA)
            except SpectrumError as exc:
                raise SpectrumError(str(exc).replace(str(path), req.filename)) from None

    @app.post("/api/export")
    def export(req: ExportRequest):
        with tempfile.TemporaryDirectory(prefix="spectrocolor-") as folder:
            path = Path(folder) / f"spectra.{req.format}"
            compute.export_spectra(float(req.step_nm), req.names, req.spectra, path)
            body = path.read_bytes()
        media = "text/csv" if req.format == "csv" else "application/json"
        return Response(body, media_type=media, headers={
            "Content-Disposition": f'attachment; filename="spectra.{req.format}"'})

    return app


