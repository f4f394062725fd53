"""What every JSON request of the explorer's API shares: no unknown fields, no boolean steps,
and one type for a bin level (0 to the full level, finite)."""

from __future__ import annotations

from typing import Annotated

from pydantic import BaseModel, ConfigDict, Field, model_validator

from . import compute

__all__ = ["Level", "StrictRequest", "validation_message"]

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
