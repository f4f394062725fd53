"""HTTP routes of the explorer's labs (beyond SPECTRA's five settings).

``GET /labs/<lab>`` serves a lab's page, ``GET /api/lab/<lab>/options`` its choices (from the
registries) and ``POST /api/lab/<lab>`` its numbers: the thin-film table for one film under one
light (:func:`spectrocolor.app.thinfilm_lab.thinfilm_lab`), the colour rendering of one light
(:func:`spectrocolor.app.light_lab.light_lab`). Errors use the server's one shape,
``{"error": "..."}``, through the library's exceptions.

The numbers are computed in worker processes (:class:`~spectrocolor.app.workers.WorkerPool`,
:data:`LAB_WORKERS` at a time): a fresh thin-film table or reflectance takes up to about a second
of maths, which in a request thread would hold the interpreter lock while other clients wait.
A computation that passes :data:`LAB_TIMEOUT_S` has its worker killed; when the workers stay busy
for :data:`LAB_WAIT_S` the answer is 429. Opening a lab's options starts a worker.
"""

from __future__ import annotations

from functools import lru_cache
from importlib import resources
from pathlib import Path
from typing import Annotated, Literal

import numpy as np
from fastapi import APIRouter, Request
from fastapi.responses import FileResponse, JSONResponse, Response
from pydantic import BaseModel, ConfigDict, Field

from ..errors import ColorimetryError
from ..illuminants import MAX_TEMPERATURE_K, MIN_TEMPERATURE_K
from ..numba_support import call_noting_numpy_path, note_numpy_path
from . import light_lab, reflectance_lab, solid_lab, thinfilm_lab
from .choices import LabObserver, LightKindName, choice
from .guards import client_key
from .responses import FiniteJSONResponse
from .workers import HEAVY_NICENESS, Busy, WorkerDied, WorkerPool, WorkerTimeout

router = APIRouter()

#: Lab computations run at the same time, each in a worker process.
LAB_WORKERS = 2
#: Longest wait for a free worker, s (then 429), and longest computation, s.
LAB_WAIT_S, LAB_TIMEOUT_S = 10.0, 60.0

#: The header of a busy answer: the pages try the same request again after this many seconds.
BUSY_HEADERS = {"Retry-After": "1"}

_workers = WorkerPool(LAB_WORKERS, LAB_WAIT_S, LAB_TIMEOUT_S, niceness=HEAVY_NICENESS)
router.on_shutdown.append(_workers.close)


def _ready() -> bool:
    """Worker side: import the labs (run when a lab's options are asked for)."""
    return True


def _rendered(function, *args) -> bytes:
    """Worker side: ``function(*args)`` written as JSON text (bytes returned as they are).

    The worker writes the answer, not the server: the thin-film table is 1.3 MB of JSON, and
    writing it in the server's process held the interpreter lock for a tenth of a second per
    request, stalling every other client's request (a third of the server's time under a class
    of 40, ``bench/bench_server_load.py --only classroom``). NaN or an infinity raise
    :class:`~spectrocolor.errors.ColorimetryError` (``FiniteJSONResponse``).
    """
    answer = function(*args)
    return answer if isinstance(answer, bytes) else bytes(FiniteJSONResponse(answer).body)


def _computed(request: Request | None, function, *args):
    """``function(*args)`` in a lab worker, with the server's answers for a busy or stuck one.
    With no request (a notebook widget calling the route: :mod:`spectrocolor.app.notebook_labs`),
    in this process."""
    if request is None:
        return Response(_rendered(function, *args), media_type="application/json")
    client = client_key(request)  # (address, the tab's token)
    try:  # the worker says whether it used the NumPy path (kernels still compiling)
        answer, used_numpy_path = _workers.run(call_noting_numpy_path, _rendered, function, *args,
                                               client=client)
    except Busy:
        return JSONResponse({"error": "the server is busy computing for other pages; try again"},
                            status_code=429, headers=BUSY_HEADERS)
    except WorkerTimeout:
        raise ColorimetryError(f"this computation took more than {LAB_TIMEOUT_S:g} s and was "
                               "stopped; choose other settings") from None
    except WorkerDied:
        raise ColorimetryError("the worker computing this stopped (out of memory?); choose other "
                               "settings") from None
    if used_numpy_path:
        note_numpy_path()
    return Response(answer, media_type="application/json")


class ThinFilmRequest(BaseModel):
    """One film under one light; the names are validated by the library's registries."""

    model_config = ConfigDict(extra="forbid")
    film: Annotated[str, Field(max_length=20)] = "soap"
    model: Annotated[str, Field(max_length=20)] = "airy"
    angle_deg: Annotated[float, Field(ge=0.0, lt=89.0)] = 0.0
    illuminant: Annotated[str, Field(max_length=40)] = thinfilm_lab.DEFAULT_LIGHT
    observer: LabObserver = "1931"
    display: Annotated[str, Field(max_length=40)] = "sRGB"


@lru_cache(maxsize=32)
def _table(film: str, model: str, angle_deg: float, illuminant: str, observer: str, display: str) -> dict:
    return thinfilm_lab.thinfilm_lab(film, model, angle_deg, illuminant, observer, display)


@lru_cache(maxsize=32)
def _table_json(film: str, model: str, angle_deg: float, illuminant: str, observer: str,
                display: str) -> bytes:
    """Worker side: :func:`_table` as JSON text, kept (writing it takes longer than reading it)."""
    return _rendered(_table, film, model, angle_deg, illuminant, observer, display)


class NamedLight(BaseModel):
    model_config = ConfigDict(extra="forbid")
    kind: Literal["named"]
    name: Annotated[str, Field(max_length=40)]


class LedLight(BaseModel):
    model_config = ConfigDict(extra="forbid")
    kind: Literal["leds"]
    peaks_nm: Annotated[list[float], Field(min_length=1, max_length=light_lab.MAX_PRIMARIES)]
    widths_nm: Annotated[list[float], Field(min_length=1, max_length=light_lab.MAX_PRIMARIES)]
    powers: Annotated[list[float], Field(min_length=1, max_length=light_lab.MAX_PRIMARIES)]


class TemperatureLight(BaseModel):
    """A kind of :data:`~spectrocolor.illuminants.LIGHT_KINDS` (checked live) at a temperature."""

    model_config = ConfigDict(extra="forbid")
    kind: Literal["temperature"]
    light: LightKindName
    temperature_K: Annotated[float, Field(ge=MIN_TEMPERATURE_K, le=MAX_TEMPERATURE_K)]


class SpdLight(BaseModel):
    """A measured light as the lab's upload answered it (``POST /api/lab/light/upload``): its
    label and its powers at 380, 385, …, 780 nm (not negative; not all zero, checked by
    :func:`~spectrocolor.app.light_lab.measured_spd`)."""

    model_config = ConfigDict(extra="forbid")
    kind: Literal["spd"]
    label: Annotated[str, Field(min_length=1, max_length=light_lab.MAX_LABEL_CHARS)]
    values: Annotated[list[Annotated[float, Field(ge=0.0, allow_inf_nan=False)]],
                      Field(min_length=light_lab.WAVELENGTHS_NM.size, max_length=light_lab.WAVELENGTHS_NM.size)]


class ExplorerLight(BaseModel):
    """The explorer's distribution handed to the lab (js/handoff.js): its levels (0-30) at
    400, 400 + ``step_nm``, …, 700 nm (length and range checked by
    :func:`~spectrocolor.app.light_lab.explorer_spd`) and its name."""

    model_config = ConfigDict(extra="forbid")
    kind: Literal["explorer"]
    label: Annotated[str, Field(max_length=light_lab.MAX_LABEL_CHARS)] = ""
    step_nm: Literal[1, 5, 10]
    levels: Annotated[list[Annotated[float, Field(ge=0.0, le=light_lab.EXPLORER_FULL, allow_inf_nan=False)]],
                      Field(min_length=31, max_length=301)]


class LightRequest(BaseModel):
    """One light (named, of a kind at a temperature, a mixture of Gaussian primaries, a
    measured SPD, or the explorer's distribution over 400-700 nm) and the display for the
    samples."""

    model_config = ConfigDict(extra="forbid")
    source: Annotated[NamedLight | TemperatureLight | LedLight | SpdLight | ExplorerLight,
                      Field(discriminator="kind")]
    display: Annotated[str, Field(max_length=40)] = "sRGB"


def _page(name: str) -> FileResponse:
    page = Path(str(resources.files("spectrocolor.app") / "static" / "labs" / f"{name}.html"))
    return FileResponse(page, media_type="text/html")


@router.get("/labs/thinfilm", include_in_schema=False)
def thinfilm_page():
    return _page("thinfilm")


@router.get("/labs/light", include_in_schema=False)
def light_page():
    return _page("light")


@router.get("/api/lab/light/options")
def light_options():
    _workers.warm(_ready)
    return light_lab.light_lab_options()


@router.post("/api/lab/light")
def light(req: LightRequest, request: Request):
    # the SPD here, from this process's registries (a kind registered at run time is unknown to
    # the spawned workers); the worker computes the metrics from the numbers
    spd, label = light_lab.light_spd(req.source.model_dump())
    return _computed(request, _light_json, np.asarray(spd, dtype=float).tobytes(), label,
                     req.display)


@lru_cache(maxsize=64)
def _light_json(spd_bytes: bytes, label: str, display: str) -> bytes:
    """Worker side: :func:`~spectrocolor.app.light_lab.light_lab_of` of an SPD given as its
    float64 bytes, as JSON text, kept: a class asks for the same few lights again and again
    (0.1 to 0.3 s each), and the bytes make the SPD itself the key."""
    return _rendered(light_lab.light_lab_of, np.frombuffer(spd_bytes, dtype=float), label, display)


@router.get("/api/lab/thinfilm/options")
def thinfilm_options():
    _workers.warm(_ready)
    return thinfilm_lab.lab_options()


@router.post("/api/lab/thinfilm")
def thinfilm(req: ThinFilmRequest, request: Request):
    return _computed(request, _table_json, req.film, req.model, round(req.angle_deg, 3), req.illuminant,
                     req.observer, req.display)


class ReflectanceRequest(BaseModel):
    """One colour (x, y, Y) under one light, on one grid."""

    model_config = ConfigDict(extra="forbid")
    x: Annotated[float, Field(ge=0.0, le=1.0)]
    y: Annotated[float, Field(ge=1e-6, le=1.0)]
    Y: Annotated[float, Field(ge=1e-6, le=100.0)]
    illuminant: Annotated[str, Field(max_length=40)] = "D65"
    observer: LabObserver = "1931"
    step_nm: Annotated[str, choice(reflectance_lab.STEPS_NM.names_view())] = "5"


@router.get("/labs/reflectance", include_in_schema=False)
def reflectance_page():
    return _page("reflectance")


@router.get("/api/lab/reflectance/options")
def reflectance_options():
    _workers.warm(_ready)
    return reflectance_lab.reflectance_lab_options()


@router.post("/api/lab/reflectance")
def reflectance(req: ReflectanceRequest, request: Request):
    return _computed(request, reflectance_lab.reflectance_lab, req.x, req.y, req.Y, req.illuminant,
                     req.observer, req.step_nm)


@router.post("/api/lab/reflectance/macadam")
def macadam(req: ReflectanceRequest, request: Request):
    return _computed(request, _macadam, req.Y, req.illuminant, req.observer, req.step_nm)


def _macadam(Y: float, illuminant: str, observer: str, step_nm: str) -> dict:
    """Worker side: the MacAdam limit at ``Y`` (rounded to 0.1 for the cache), with ``Y``."""
    return {"Y": Y, "xy": reflectance_lab.macadam_xy(round(Y, 1), illuminant, observer, step_nm)}


class SolidRequest(BaseModel):
    """The solid under one light, drawn for one display; a section at Y; a sample's mismatch."""

    model_config = ConfigDict(extra="forbid")
    illuminant: Annotated[str, Field(max_length=40)] = "D65"
    display: Annotated[str, Field(max_length=40)] = "sRGB"
    Y: Annotated[float, Field(gt=0.0, lt=100.0)] = 50.0
    sample: Annotated[int, Field(ge=1, le=14, strict=True)] = 1
    second_illuminant: Annotated[str, Field(max_length=40)] = "A"
    #: A sample handed over by the explorer (issue 28 item 6): its levels, 0-30 on 400-700 nm at
    #: ``levels_step_nm``; given, it replaces ``sample`` in the mismatch region.
    levels: Annotated[list[Annotated[float, Field(ge=0.0, le=30.0, allow_inf_nan=False)]],
                      Field(min_length=31, max_length=301)] | None = None
    levels_step_nm: Literal[10, 5, 2, 1] = 10


@router.get("/labs/solid", include_in_schema=False)
def solid_page():
    _workers.warm(_ready)  # its options route needs no worker: start one with the page
    return _page("solid")


@router.get("/api/lab/solid/options")
def solid_options():
    return solid_lab.solid_lab_options()


@router.post("/api/lab/solid")
def solid(req: SolidRequest, request: Request):
    return _computed(request, solid_lab.solid, req.illuminant, req.display)


@router.post("/api/lab/solid/section")
def solid_section(req: SolidRequest, request: Request):
    return _computed(request, solid_lab.section, round(req.Y, 1), req.illuminant, req.display)


@router.post("/api/lab/solid/mismatch")
def solid_mismatch(req: SolidRequest, request: Request):
    if req.levels is not None:
        return _computed(request, solid_lab.mismatch_of_levels, tuple(req.levels), float(req.levels_step_nm),
                         req.illuminant, req.second_illuminant, req.display)
    return _computed(request, solid_lab.mismatch, req.sample, req.illuminant, req.second_illuminant,
                     req.display)
