"""HTTP routes of the explorer's labs (beyond SPECTRA's five settings).

``GET /labs/<lab>`` serves a lab's page, ``GET /api/lab/<lab>/options`` its choices (from the
registries) and ``POST /api/lab/<lab>`` its numbers: the thin-film table for one film under one
light (:func:`spectrocolor.app.thinfilm_lab.thinfilm_lab`), the colour rendering of one light
(:func:`spectrocolor.app.light_lab.light_lab`). Errors use the server's one shape,
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

from . import light_lab, reflectance_lab, solid_lab, thinfilm_lab

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


class LightRequest(BaseModel):
    """One light (named, or a mixture of Gaussian primaries) and the display for the samples."""

    model_config = ConfigDict(extra="forbid")
    source: Annotated[NamedLight | LedLight, Field(discriminator="kind")]
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
    return light_lab.light_lab_options()


@router.post("/api/lab/light")
def light(req: LightRequest):
    return light_lab.light_lab(req.source.model_dump(), req.display)


@router.get("/api/lab/thinfilm/options")
def thinfilm_options():
    return thinfilm_lab.lab_options()


@router.post("/api/lab/thinfilm")
def thinfilm(req: ThinFilmRequest):
    return _table(req.film, req.model, round(req.angle_deg, 3), req.illuminant, req.observer, req.display)


class ReflectanceRequest(BaseModel):
    """One colour (x, y, Y) under one light, on one grid."""

    model_config = ConfigDict(extra="forbid")
    x: Annotated[float, Field(ge=0.0, le=1.0)]
    y: Annotated[float, Field(ge=1e-6, le=1.0)]
    Y: Annotated[float, Field(ge=1e-6, le=100.0)]
    illuminant: Annotated[str, Field(max_length=40)] = "D65"
    observer: Literal["1931", "1964"] = "1931"
    step_nm: Literal["5", "10"] = "5"


@router.get("/labs/reflectance", include_in_schema=False)
def reflectance_page():
    return _page("reflectance")


@router.get("/api/lab/reflectance/options")
def reflectance_options():
    return reflectance_lab.reflectance_lab_options()


@router.post("/api/lab/reflectance")
def reflectance(req: ReflectanceRequest):
    return reflectance_lab.reflectance_lab(req.x, req.y, req.Y, req.illuminant, req.observer, req.step_nm)


@router.post("/api/lab/reflectance/macadam")
def macadam(req: ReflectanceRequest):
    return {"Y": req.Y, "xy": reflectance_lab.macadam_xy(round(req.Y, 1), req.illuminant, req.observer, req.step_nm)}


class SolidRequest(BaseModel):
    """The solid under one light, drawn for one display; a section at Y; a sample's mismatch."""

    model_config = ConfigDict(extra="forbid")
    illuminant: Annotated[str, Field(max_length=40)] = "D65"
    display: Annotated[str, Field(max_length=40)] = "sRGB"
    Y: Annotated[float, Field(gt=0.0, lt=100.0)] = 50.0
    sample: Annotated[int, Field(ge=1, le=14, strict=True)] = 1
    second_illuminant: Annotated[str, Field(max_length=40)] = "A"


@router.get("/labs/solid", include_in_schema=False)
def solid_page():
    return _page("solid")


@router.post("/api/lab/solid")
def solid(req: SolidRequest):
    return solid_lab.solid(req.illuminant, req.display)


@router.post("/api/lab/solid/section")
def solid_section(req: SolidRequest):
    return solid_lab.section(round(req.Y, 1), req.illuminant, req.display)


@router.post("/api/lab/solid/mismatch")
def solid_mismatch(req: SolidRequest):
    return solid_lab.mismatch(req.sample, req.illuminant, req.second_illuminant, req.display)
