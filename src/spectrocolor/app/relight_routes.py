"""HTTP route of setting 4's photo: ``POST /api/relight`` (issue 17).

The body is JSON: the photo's file base64-encoded, the setting's illuminant as bin levels and the
choices (source light, adaptation, gamut strategy). The answer is
:func:`spectrocolor.app.relight_photo.relight_photo`'s, computed in a worker process (spawned on
first use, so nothing of the server is copied into it) that keeps its upsampling tables between
requests: a hostile file cannot stop the server, and other clients are answered meanwhile. At
most :data:`RELIGHT_WORKERS` photos are relit at a time; a request waits up to
:data:`RELIGHT_WAIT_S` for a turn, then gets 429. The body is limited like every other by the
server's guard (``MAX_BODY_BYTES``, 413 beyond), so a photo file may have up to
:data:`MAX_PHOTO_BYTES` bytes; it is decoded and validated in the worker too
(:func:`_relight_body`), as decoding 2 MB of JSON in the server's event loop would stall every
other client. Every error has the server's one shape, ``{"error": "..."}``.
"""

from __future__ import annotations

import json
from typing import Annotated

from fastapi import APIRouter, Request
from fastapi.responses import JSONResponse
from pydantic import Field, ValidationError, model_validator
from starlette.concurrency import run_in_threadpool

from ..errors import SpectrumError
from ..numba_support import call_noting_numpy_path, note_numpy_path
from . import compute
from .choices import Gamut, Observer, Step, choice
from .guards import client_key
from .relight_photo import (
    ADAPTATIONS,
    DEFAULT_ADAPTATION,
    DEFAULT_EXPOSURE,
    EXPOSURES,
    MAX_SHOWN_SIDE_PX,
    SOURCES,
    prepare,
    relight_photo,
)
from .request_models import Level, StrictRequest, registries_as_imported, validation_message
from .workers import HEAVY_NICENESS, Busy, WorkerDied, WorkerPool, WorkerTimeout

#: Photos relit at the same time (each worker keeps its own tables).
RELIGHT_WORKERS = 1
#: Longest wait for a free worker, s (then 429), and longest relight, s.
RELIGHT_WAIT_S, RELIGHT_TIMEOUT_S = 20.0, 60.0
#: Largest photo file: base64 makes 4 characters of 3 bytes, within the server's 2 MB body.
MAX_PHOTO_BYTES = 1_400_000
_MAX_BASE64 = 4 * ((MAX_PHOTO_BYTES + 2) // 3)

router = APIRouter()


class RelightRequest(StrictRequest):
    """A photo and setting 4's illuminant (bin levels on the explorer's grid)."""

    image: Annotated[str, Field(min_length=1, max_length=_MAX_BASE64)]
    illuminant: Annotated[list[Level], Field(min_length=31, max_length=301)]
    step_nm: Step = 10
    observer: Observer = "1931"
    source: Annotated[str, choice(SOURCES)] = SOURCES[0]
    adaptation: Annotated[str, choice(tuple(ADAPTATIONS))] = DEFAULT_ADAPTATION
    gamut: Gamut = "clip"
    exposure: Annotated[str, choice(tuple(EXPOSURES))] = DEFAULT_EXPOSURE

    @model_validator(mode="after")
    def _check(self):
        bins = len(compute.grid(float(self.step_nm)))
        if len(self.illuminant) != bins:
            raise ValueError(f"illuminant has {len(self.illuminant)} bins; step {self.step_nm} nm "
                             f"over 400-700 nm needs {bins}")
        if max(self.illuminant) <= 0:
            raise ValueError("illuminant is dark everywhere (all levels 0): nothing is lit")
        return self


_workers = WorkerPool(RELIGHT_WORKERS, RELIGHT_WAIT_S, RELIGHT_TIMEOUT_S, niceness=HEAVY_NICENESS)
router.on_shutdown.append(_workers.close)


@router.get("/api/relight/options")
def relight_options():
    """The choices of the photo panel, defaults first, and its limits; starts the default table."""
    _workers.warm(prepare, SOURCES[0], "1931", 10.0)
    return photo_options()


def photo_options() -> dict:
    """The photo panel's choices and limits (what :func:`relight_options` answers), computed
    without starting a worker (the notebook widget answers it in the kernel)."""
    return {"sources": list(SOURCES),
            "adaptations": [[k, label, why] for k, (label, why) in ADAPTATIONS.items()],
            "exposures": [[k, label, why] for k, (label, why) in EXPOSURES.items()],
            "defaults": {"source": SOURCES[0], "adaptation": DEFAULT_ADAPTATION,
                         "exposure": DEFAULT_EXPOSURE},
            "max_photo_bytes": MAX_PHOTO_BYTES, "max_side_px": MAX_SHOWN_SIDE_PX}


def _decoded(body: bytes) -> RelightRequest | tuple[int, str]:
    """The :class:`RelightRequest` of ``body``, or ``(422, message)`` refusing it."""
    try:
        return RelightRequest.model_validate(json.loads(body))
    except ValidationError as exc:
        return 422, validation_message(exc.errors())
    except (ValueError, RecursionError) as exc:  # not JSON (UnicodeDecodeError included)
        return 422, f"the body is not JSON ({str(exc)[:120]})"


def _relight_body(body: bytes | RelightRequest):
    """Worker side: the relit photo of the request ``body``, or ``(422, message)`` refusing it.

    Given a :class:`RelightRequest` (validated by the server, see
    :func:`~spectrocolor.app.request_models.registries_as_imported`), relights it."""
    req = body if isinstance(body, RelightRequest) else _decoded(bytes(body))
    if isinstance(req, tuple):
        return req
    return relight_photo(req.image, req.illuminant, float(req.step_nm), req.observer, req.source,
                         req.adaptation, req.gamut, req.exposure)


@router.post("/api/relight")
async def relight(request: Request):
    """:func:`relight_photo` of a :class:`RelightRequest`, decoded and computed in the worker."""
    body = await request.body()
    job: bytes | RelightRequest = body
    if not registries_as_imported():  # validated here: an entry registered at run time counts
        checked = await run_in_threadpool(_decoded, body)
        if isinstance(checked, tuple):
            return JSONResponse({"error": checked[1]}, status_code=checked[0])
        job = checked
    try:  # the worker says whether it used the NumPy path (kernels still compiling)
        answer, used_numpy_path = await run_in_threadpool(
            _workers.run, call_noting_numpy_path, _relight_body, job, client=client_key(request))
    except Busy:
        return JSONResponse({"error": "the server is busy relighting other photos; try again"},
                            status_code=429)
    except WorkerTimeout:
        raise SpectrumError(f"image: relighting took more than {RELIGHT_TIMEOUT_S:g} s; "
                            "send a smaller photo") from None
    except WorkerDied:
        raise SpectrumError("image: the worker stopped on this photo (out of memory?); "
                            "send a smaller photo") from None
    if isinstance(answer, tuple):
        return JSONResponse({"error": answer[1]}, status_code=answer[0])
    if used_numpy_path:
        note_numpy_path()
    return answer
