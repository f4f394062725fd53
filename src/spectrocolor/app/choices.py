"""The explorer's choices, read from the library's registries: one source for the request models,
``/api/options`` and the page's select boxes.

A request field that names a choice is typed ``Annotated[str, choice(names)]``, ``names`` a live
sequence (a
:class:`~spectrocolor.registry.RegistryNames` view, or a fixed selection): it is checked against
the registry *when the request arrives*, so an entry registered after this module was imported
is accepted at once, and an unknown name gets pydantic's own message, ``Input should be 'a', 'b'
or 'c'`` (a 422 naming the accepted values). The JSON schema lists the names registered when it
is generated. :func:`select_options` gives the page its ``[name, label, help]`` rows.

Example: the gamut strategies. ``GAMUTS`` is a live view of
:data:`~spectrocolor.display.gamut.GAMUT_STRATEGIES` (the default first); ``Gamut`` types the
request field; ``select_options(GAMUT_STRATEGIES, GAMUTS, help_key="action")`` fills the page's
select box. A new strategy is one ``GAMUT_STRATEGIES.add(...)`` (``docs/design.md``).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import Annotated, Any, Literal, TypeAlias

from pydantic import GetCoreSchemaHandler, GetJsonSchemaHandler
from pydantic.json_schema import JsonSchemaValue
from pydantic_core import CoreSchema, PydanticCustomError, core_schema

from ..display.chain import (
    CHAIN_NORMALISATIONS,
    DEFAULT_CHAIN_NORMALISATION,
    DEFAULT_WHITE_ADAPTATION,
    WHITE_ADAPTATIONS,
)
from ..display.gamut import DEFAULT_GAMUT, GAMUT_STRATEGIES
from ..display.spaces import RGB_SPACES
from ..illuminants import LIGHT_KINDS
from ..observers import OBSERVERS
from ..registry import Registry

__all__ = [
    "ADAPTATIONS", "Adaptation", "DISPLAYS", "Display", "GAMUTS", "Gamut", "LAB_OBSERVER_KEYS",
    "LIGHT_KIND_NAMES", "LabObserver", "LightKindName", "light_kind_options",
    "NORMALISATIONS", "Normalise", "OBSERVER_KEYS", "Observer", "Step", "choice", "expected_text",
    "observer_key", "observer_labels", "select_options",
]


def expected_text(names: Sequence[object]) -> str:
    """``'a', 'b' or 'c'``: the accepted values as pydantic's ``literal_error`` writes them.

    Parameters
    ----------
    names : sequence
        The accepted values.

    Returns
    -------
    str

    Examples
    --------
    >>> expected_text(["flag", "clip", "desaturate"])
    "'flag', 'clip' or 'desaturate'"
    >>> expected_text([10, 5])
    '10 or 5'
    """
    shown = [repr(n) for n in names]
    return shown[0] if len(shown) == 1 else f"{', '.join(shown[:-1])} or {shown[-1]}"


class _LiveChoice:
    """Pydantic metadata: the value must be one of ``names()`` *now* (exact, case-sensitive)."""

    def __init__(self, names: Callable[[], Sequence[Any]]) -> None:
        self._names = names

    def _check(self, value: Any) -> Any:
        names = tuple(self._names())
        if isinstance(value, str) and value in names:
            return value
        raise PydanticCustomError("literal_error", "Input should be {expected}",
                                  {"expected": expected_text(names)})

    def __get_pydantic_core_schema__(self, source: Any, handler: GetCoreSchemaHandler) -> CoreSchema:
        return core_schema.no_info_plain_validator_function(self._check)

    def __get_pydantic_json_schema__(self, schema: CoreSchema, handler: GetJsonSchemaHandler) -> JsonSchemaValue:
        return {"type": "string", "enum": list(self._names())}


def choice(names: Sequence[str]) -> _LiveChoice:
    """Pydantic metadata for ``Annotated[str, choice(names)]``: one of ``names`` when validated.

    Parameters
    ----------
    names : sequence of str
        A live view (:meth:`~spectrocolor.registry.Registry.names_view`) or a fixed selection.

    Returns
    -------
    object
        Metadata for :data:`typing.Annotated` (a pydantic model field).

    Examples
    --------
    >>> from pydantic import BaseModel
    >>> class Pick(BaseModel):
    ...     gamut: Annotated[str, choice(GAMUTS)] = DEFAULT_GAMUT
    >>> Pick(gamut="clip").gamut
    'clip'
    >>> Pick.model_json_schema()["properties"]["gamut"]["enum"][0]
    'desaturate'
    """
    return _LiveChoice(lambda: names)


def select_options(registry: Registry, names: Sequence[str], help_key: str | None = None) -> list[list[str]]:
    """``[[name, label, help], ...]`` for a select box: label and help from the registry.

    Parameters
    ----------
    registry : Registry
        The table the names belong to.
    names : sequence of str
        The names offered, in order.
    help_key : str, optional
        The entry's ``extra`` text shown as the option's tooltip (default: its description).

    Returns
    -------
    list of [str, str, str]

    Examples
    --------
    >>> select_options(GAMUT_STRATEGIES, ["flag"], help_key="action")
    [['flag', 'SPECTRA: cannot be reproduced', 'shown black']]
    """
    rows = []
    for name in names:
        entry = registry.entry(name)
        help_text = entry.extra.get(help_key, entry.description) if help_key else entry.description
        rows.append([name, entry.label, help_text])
    return rows


#: Gamut strategies, the library's default first (never a bare black patch); "flag" is
#: SPECTRA's strict one. Live: follows the registry.
GAMUTS = GAMUT_STRATEGIES.names_view(first=DEFAULT_GAMUT)
#: The explorer's normalisations (A exact, B per colour, A as SPECTRA computed it), live.
NORMALISATIONS = CHAIN_NORMALISATIONS.names_view(first=DEFAULT_CHAIN_NORMALISATION)
#: How the reference white E is shown, the default first, live.
ADAPTATIONS = WHITE_ADAPTATIONS.names_view(first=DEFAULT_WHITE_ADAPTATION)
#: The displays the explorer offers, a selection of :data:`RGB_SPACES` (those whose transfer the
#: page's fast path encodes, as SPECTRA's two and the usual two): checked against it here.
DISPLAYS = ("sRGB", "SPECTRA 7000K", "Display P3", "SPECTRA equal-energy")
for _name in DISPLAYS:
    if RGB_SPACES.canonical(_name) != _name:  # pragma: no cover - a renamed space
        raise RuntimeError(f"the explorer's display {_name!r} is not a canonical name of RGB_SPACES")


def observer_key(name: str) -> str:
    """The explorer's short key of a shipped observer (``"1931"``): its ``extra["key"]``, else its name.

    Parameters
    ----------
    name : str
        A name or alias of :data:`~spectrocolor.observers.OBSERVERS`.

    Returns
    -------
    str

    Examples
    --------
    >>> observer_key("CIE 1964 10°")
    '1964'
    """
    return str(OBSERVERS.extra(name, "key", OBSERVERS.canonical(name)))


def _observer_keys() -> tuple[str, ...]:
    return tuple(observer_key(name) for name in OBSERVERS.names())


def observer_labels() -> dict[str, str]:
    """``{key: canonical name}`` of every shipped observer, for the page's select box.

    Returns
    -------
    dict of str to str

    Examples
    --------
    >>> observer_labels()["2015-10"]
    'CIE 2015 10°'
    """
    return {observer_key(name): name for name in OBSERVERS.names()}


class _ObserverKeys(Sequence[str]):
    """The short keys of :data:`~spectrocolor.observers.OBSERVERS`, live."""

    def __getitem__(self, index: Any) -> Any:
        return _observer_keys()[index]

    def __len__(self) -> int:
        return len(OBSERVERS)

    def __contains__(self, key: object) -> bool:
        return isinstance(key, str) and key in _observer_keys()


#: The observers' short keys the explorer's requests use ("1931", "1964", "2015-2", ...), live.
OBSERVER_KEYS: Sequence[str] = _ObserverKeys()

#: The observers the labs offer (their tables are computed for these two), checked against the
#: registry here.
LAB_OBSERVER_KEYS = ("1931", "1964")
if not set(LAB_OBSERVER_KEYS) <= set(OBSERVER_KEYS):  # pragma: no cover - a renamed observer
    raise RuntimeError(f"the labs' observers {LAB_OBSERVER_KEYS} are not all keys of OBSERVERS")

#: The kinds of light named by a temperature (``"blackbody"``, ``"daylight"``, ...), live: a
#: view of :data:`~spectrocolor.illuminants.LIGHT_KINDS`.
LIGHT_KIND_NAMES = LIGHT_KINDS.names_view()


def light_kind_options() -> list[dict[str, Any]]:
    """The light kinds for a select box: name, label, help and the temperatures accepted, K.

    Returns
    -------
    list of dict
        ``{"name", "label", "help", "min_K", "max_K"}`` per kind of
        :data:`~spectrocolor.illuminants.LIGHT_KINDS`, in registration order (read live).

    Examples
    --------
    >>> [(k["name"], k["label"], k["min_K"]) for k in light_kind_options()][:2]
    [('blackbody', 'Planckian radiator', 100.0), ('daylight', 'CIE daylight', 4000.0)]
    """
    rows = []
    for name, label, help_text in select_options(LIGHT_KINDS, LIGHT_KIND_NAMES):
        kind = LIGHT_KINDS.get(name)
        rows.append({"name": name, "label": label, "help": help_text, "min_K": kind.min_K, "max_K": kind.max_K})
    return rows


#: The explorer's bin widths, nm (400-700 nm in 31, 61, 151 or 301 bins): written once, here;
#: :data:`spectrocolor.app.compute.STEPS_NM` and ``/api/options`` are made from it. A Literal, so
#: JSON 10 and 10.0 are both 10 nm.
Step: TypeAlias = Literal[10, 5, 2, 1]
#: Request-field types: checked against the registries when a request arrives.
Gamut: TypeAlias = Annotated[str, choice(GAMUT_STRATEGIES.names_view())]  # registry order, as the Literal it replaced
Normalise: TypeAlias = Annotated[str, choice(NORMALISATIONS)]
Adaptation: TypeAlias = Annotated[str, choice(ADAPTATIONS)]
Display: TypeAlias = Annotated[str, choice(DISPLAYS)]
Observer: TypeAlias = Annotated[str, choice(OBSERVER_KEYS)]
LabObserver: TypeAlias = Annotated[str, choice(LAB_OBSERVER_KEYS)]
LightKindName: TypeAlias = Annotated[str, choice(LIGHT_KIND_NAMES)]
