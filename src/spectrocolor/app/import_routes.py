"""HTTP route of the page's Load: ``POST /api/import`` reads a measurement file in a worker process.

The body is JSON (an :class:`ImportRequest`): the file's bytes base64-encoded (as the page sends
them, so that the server decodes them as :func:`spectrocolor.read_spectra` decodes a file: a
byte-order mark, UTF-8, else cp1252 where unambiguous) or its text. The body (up to the server's
``MAX_BODY_BYTES``) is decoded and validated in the upload pool's workers
(:func:`_decoded_import`), and the file parsed there too (:mod:`spectrocolor.app.uploads`), so a
hostile file never holds the event loop and other clients are answered meanwhile; at most
:data:`MAX_PARSERS` files are read at a time, a request waits up to :data:`PARSER_WAIT_S` for a
turn, then gets 429. Every error has the server's one shape, ``{"error": "..."}``.

``POST /api/lab/light/upload`` is the light-source lab's upload: the same body, decoding, pool
and budgets, the file read by the same reader (:func:`spectrocolor.read_spectra`), but its first
spectrum resampled to the lab's 380-780 nm grid (:func:`spectrocolor.app.light_lab.read_light_file`)
instead of the explorer's 400-700 nm levels.
"""

from __future__ import annotations

import base64
import binascii
import json
import tempfile
from typing import Annotated

from fastapi import APIRouter, Request
from fastapi.responses import JSONResponse, Response
from pydantic import Field, ValidationError, model_validator
from starlette.concurrency import run_in_threadpool

from ..errors import SpectrumError
from ..interpolation import METHODS as INTERPOLATION_METHODS
from . import compute, light_lab
from .choices import Observer, Step, choice
from .guards import MAX_JSON_DEPTH, client_key, json_depth
from .request_models import StrictRequest, validation_message
from .responses import FiniteJSONResponse
from .uploads import Busy, UploadParser
from .workers import WorkerDied, WorkerTimeout

__all__ = ["ImportRequest", "router", "MAX_PARSERS", "PARSER_WAIT_S", "PARSER_TIMEOUT_S", "MAX_IMPORT_SPECTRA",
           "MAX_IMPORT_BYTES", "MAX_IMPORT_BASE64"]

#: Imports parsed at the same time, each in a worker process; more wait up to PARSER_WAIT_S,
#: then get 429.
MAX_PARSERS = 2
PARSER_WAIT_S = 10.0
#: Longest parse of one upload, seconds.
PARSER_TIMEOUT_S = 60.0
#: Spectra one imported file may hold; the page lets the user choose which to edit.
MAX_IMPORT_SPECTRA = 64
#: Largest imported file, bytes (as text: characters), and its base64 length.
MAX_IMPORT_BYTES = 1_000_000
MAX_IMPORT_BASE64 = 4 * ((MAX_IMPORT_BYTES + 2) // 3)


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


#: The import route, included by :func:`spectrocolor.app.server.create_app`.
router = APIRouter(default_response_class=FiniteJSONResponse)


@router.post("/api/import")
async def import_(request: Request):
    """The spectra of an uploaded file (an :class:`ImportRequest`), parsed in a worker process
    (429 when all stay busy). Its body, up to 2 MB, is decoded and validated in the upload
    pool's workers too (:func:`_decoded_import`): decoding it here would hold the event loop."""
    return await _uploaded(request, _import, "import")


async def _uploaded(request: Request, answer, verb: str) -> Response:
    """An upload route's answer: ``request``'s body decoded and validated in an upload worker
    (:func:`_decoded_import`), then ``answer(decoded, parsers, client)`` in a thread; the pool's
    refusals worded alike for both routes (``verb``: what the user should do again)."""
    parsers: UploadParser = request.app.state.parsers
    client = client_key(request)
    try:
        decoded = await run_in_threadpool(parsers.pool.run, _decoded_import,
                                          await request.body(), client=client)
        if isinstance(decoded, str):
            return JSONResponse({"error": decoded}, status_code=422)
        return await run_in_threadpool(answer, decoded, parsers, client)
    except Busy:
        return JSONResponse({"error": "the server is busy reading other files; try again"},
                            status_code=429)
    except (WorkerTimeout, WorkerDied):
        raise SpectrumError("the upload could not be read (too large or too slow to decode); "
                            f"{verb} a smaller file") from None


def _decoded_import(body: bytes) -> tuple[ImportRequest, bytes | str] | str:
    """Worker side: the :class:`ImportRequest` of ``body`` and its file (the bytes of
    ``content_base64``, else the text ``content``), or the one line refusing it."""
    try:
        req = ImportRequest.model_validate(json.loads(body))
        content = req.file_bytes()
    except (ValueError, RecursionError) as exc:  # not JSON, not base64, or refused by the model
        return validation_message(exc.errors()) if isinstance(exc, ValidationError) else \
            str(exc)[:300] if isinstance(exc, SpectrumError) else f"the body is not JSON ({str(exc)[:120]})"
    raw = content if isinstance(content, bytes) else content.encode("utf-8")
    if req.filename.lower().endswith(".json") and json_depth(raw) > MAX_JSON_DEPTH:
        return f"{req.filename}: JSON nested deeper than {MAX_JSON_DEPTH} levels"
    return req, content


def _import(decoded: tuple[ImportRequest, bytes | str], parsers: UploadParser, client) -> Response:
    """The import answer, parsed in a worker and written here, in a thread (not the loop)."""
    req, content = decoded  # bytes are decoded in the worker, as read_spectra decodes a file
    suffix = ".json" if req.filename.lower().endswith(".json") else ".csv"
    # in a worker process: other clients keep being answered meanwhile
    return FiniteJSONResponse(parsers.parse(req.filename, content, suffix, float(req.step_nm),
                                            req.method, req.scale, MAX_IMPORT_SPECTRA,
                                            client=client, observer=req.observer))


@router.post("/api/lab/light/upload")
async def light_upload(request: Request):
    """The light in an uploaded file (an :class:`ImportRequest`; only ``filename`` and the content
    matter) for the light-source lab: ``label``, ``spd`` (81 values at 380-780 nm, peak 1) and
    ``note``. Decoded, validated and read in the upload pool's workers, as ``POST /api/import``."""
    return await _uploaded(request, _light, "upload")


def _light(decoded: tuple[ImportRequest, bytes | str], parsers: UploadParser, client) -> Response:
    """The light-lab upload's answer, read in an upload worker (a private temporary folder)."""
    req, content = decoded
    suffix = ".json" if req.filename.lower().endswith(".json") else ".csv"  # as the Load: formats are sniffed
    with tempfile.TemporaryDirectory(prefix="spectrocolor-upload-") as folder:
        try:
            answer = parsers.pool.run(light_lab.read_light_file, folder, content, suffix, client=client)
        except SpectrumError as exc:
            raise SpectrumError(str(exc).replace(light_lab.FILE_NAME, req.filename)) from None
        except WorkerTimeout:
            raise SpectrumError(f"{req.filename}: reading it took more than {parsers.pool.timeout_s:g} s "
                                "and was stopped; upload a smaller file") from None
        except WorkerDied:
            raise SpectrumError(f"{req.filename}: the reader stopped on this file (out of memory?); "
                                "upload a smaller file") from None
    label = answer["label"].replace(light_lab.FILE_NAME, req.filename)[:light_lab.MAX_LABEL_CHARS]
    return FiniteJSONResponse({**answer, "label": label})
