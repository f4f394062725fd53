"""What every JSON request of the explorer's API shares: no unknown fields, no boolean steps,
and one type for a bin level (0 to the full level, finite)."""

from __future__ import annotations

from typing import Annotated

from pydantic import BaseModel, ConfigDict, Field, model_validator

from . import compute

__all__ = ["Level", "StrictRequest", "validation_message", "registries_as_imported"]

#: One bin's level, 0 to :data:`spectrocolor.app.compute.FULL_LEVEL`.
Level = Annotated[float, Field(ge=0, le=compute.FULL_LEVEL, allow_inf_nan=False)]


class StrictRequest(BaseModel):
    """A request body that refuses unknown fields and a boolean ``step_nm``."""

    model_config = ConfigDict(extra="forbid")

    @model_validator(mode="before")
    @classmethod
    def _no_bool_step(cls, data):
        # JSON true/false would pass as 1/0 (bool is an int in Python): not a step in nm
        if isinstance(data, dict) and isinstance(data.get("step_nm"), bool):
            raise ValueError("step_nm: expected a number of nm (10, 5, 2 or 1), got a boolean")
        return data


def validation_message(errors) -> str:
    """One line from pydantic's ``errors()``: the first five, each ``where: what``.

    Examples
    --------
    >>> validation_message([{"loc": ("body", "step_nm"), "msg": "Value error, not a step"}])
    'step_nm: not a step'
    """
    parts = []
    for err in errors:
        where = ".".join(str(p) for p in err.get("loc", ()) if p != "body")
        msg = str(err.get("msg", "invalid")).removeprefix("Value error, ")
        parts.append(f"{where}: {msg}" if where else msg)
    return "; ".join(parts[:5]) + (f" (and {len(parts) - 5} more)" if len(parts) > 5 else "")


def _names_now() -> tuple:
    from ..display.chain import CHAIN_NORMALISATIONS, WHITE_ADAPTATIONS
    from ..display.gamut import GAMUT_STRATEGIES
    from ..display.normalise import NORMALISATIONS
    from ..display.spaces import RGB_SPACES
    from ..display.transfer import TRANSFERS
    from ..illuminants import ILLUMINANTS, LIGHT_KINDS
    from ..observers import OBSERVERS

    return tuple(registry.names() for registry in (
        GAMUT_STRATEGIES, CHAIN_NORMALISATIONS, WHITE_ADAPTATIONS, NORMALISATIONS, RGB_SPACES,
        TRANSFERS, ILLUMINANTS, LIGHT_KINDS, OBSERVERS, compute.IMPORT_SCALES))


_AS_IMPORTED = _names_now()


def registries_as_imported() -> bool:
    """Whether the registries a request names hold the names they held when this module loaded.

    A worker process is spawned: it imports the library afresh and knows only the entries that
    importing registers. An entry registered at run time in the server (a plug-in, a test) is
    known to the server alone, so while this is False the server validates and computes such
    requests itself (in a thread), as the registries' contract -- registered in one place,
    accepted everywhere -- requires.

    Examples
    --------
    >>> registries_as_imported()
    True
    """
    return _names_now() == _AS_IMPORTED
