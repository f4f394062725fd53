"""HTTP routes of the explorer's labs (beyond SPECTRA's five settings).

``GET /labs/thinfilm`` serves the thin-film lab's page; ``GET /api/lab/thinfilm/options`` its
choices (from the registries); ``POST /api/lab/thinfilm`` the table for one film under one light
(:func:`spectrocolor.app.thinfilm_lab.thinfilm_lab`). Errors use the server's one shape,
``{"error": "..."}``, through the library's exceptions.
"""

from __future__ import annotations

from functools import lru_cache
from importlib import resources
from pathlib import Path
from typing import Annotated, Literal

from fastapi import APIRouter
from fastapi.responses import FileResponse
from pydantic import BaseModel, ConfigDict, Field

from . import thinfilm_lab

router = APIRouter()


class ThinFilmRequest(BaseModel):
    """One film under one light; the names are validated by the library's registries."""

    model_config = ConfigDict(extra="forbid")
    film: Annotated[str, Field(max_length=20)] = "soap"
    model: Annotated[str, Field(max_length=20)] = "airy"
    angle_deg: Annotated[float, Field(ge=0.0, lt=89.0)] = 0.0
    illuminant: Annotated[str, Field(max_length=40)] = thinfilm_lab.DEFAULT_LIGHT
    observer: Literal["1931", "1964"] = "1931"
    display: Annotated[str, Field(max_length=40)] = "sRGB"


@lru_cache(maxsize=32)
def _table(film: str, model: str, angle_deg: float, illuminant: str, observer: str, display: str) -> dict:
    return thinfilm_lab.thinfilm_lab(film, model, angle_deg, illuminant, observer, display)


@router.get("/labs/thinfilm", include_in_schema=False)
def thinfilm_page():
    page = Path(str(resources.files("spectrocolor.app") / "static" / "labs" / "thinfilm.html"))
    return FileResponse(page, media_type="text/html")


@router.get("/api/lab/thinfilm/options")
def thinfilm_options():
    return thinfilm_lab.lab_options()


@router.post("/api/lab/thinfilm")
def thinfilm(req: ThinFilmRequest):
    return _table(req.film, req.model, round(req.angle_deg, 3), req.illuminant, req.observer, req.display)
