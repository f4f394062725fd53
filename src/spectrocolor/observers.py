"""CIE standard colorimetric observers (colour-matching functions x̄, ȳ, z̄ at 1 nm).

References
----------
CIE 015:2018 *Colorimetry*, 4th ed., Tables 1 and 2 (1931 2°, 1964 10°).
CIE 170-2:2015 *Fundamental chromaticity diagram with physiological axes*, XYZ functions
(the "CIE 2015" 2° and 10° observers). Sources of the files: ``data/PROVENANCE.md``.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cache

from .data_tables import load_table
from .errors import ColorimetryError
from .registry import Registry
from .spectrum import Spectrum

#: The shipped observers: canonical name → data file, with their aliases and descriptions;
#: ``extra["key"]`` is the short name the explorer's requests use.
OBSERVERS = Registry("observer", "a shipped observer")
OBSERVERS.add(
    "CIE 1931 2°", "cmf_cie1931_2deg.csv", "CIE 1931 standard colorimetric observer, 2° field (CIE 015 Table 1)",
    aliases=("cie 1931 2", "cie1931", "1931", "2", "2deg", "2°"),
    extra={"key": "1931"},
)
OBSERVERS.add(
    "CIE 1964 10°", "cmf_cie1964_10deg.csv", "CIE 1964 supplementary observer, 10° field (CIE 015 Table 2)",
    aliases=("cie 1964 10", "cie1964", "1964", "10", "10deg", "10°"),
    extra={"key": "1964"},
)
OBSERVERS.add(
    "CIE 2015 2°", "cmf_cie2015_2deg.csv", "CIE 170-2:2015 cone-fundamental-based XYZ functions, 2°",
    aliases=("cie 2015 2", "2015-2", "2015 2deg", "2015-2deg"),
    extra={"key": "2015-2"},
)
OBSERVERS.add(
    "CIE 2015 10°", "cmf_cie2015_10deg.csv", "CIE 170-2:2015 cone-fundamental-based XYZ functions, 10°",
    aliases=("cie 2015 10", "2015-10", "2015 10deg", "2015-10deg"),
    extra={"key": "2015-10"},
)

#: The observer used wherever the caller gives none: the CIE 1931 2° standard colorimetric
#: observer (CIE 015:2018 §3.1). Stated here once; every function, the CLI and the app use it.
DEFAULT_OBSERVER = "CIE 1931 2°"


def observer_names() -> tuple[str, ...]:
    """Canonical names of the shipped observers.

    Returns
    -------
    tuple of str
        The names :func:`observer` accepts as they are (aliases such as ``"1931"`` also work).

    Examples
    --------
    >>> observer_names()
    ('CIE 1931 2°', 'CIE 1964 10°', 'CIE 2015 2°', 'CIE 2015 10°')
    """
    return OBSERVERS.names()


#: Field size (degrees) and year of each shipped observer, by canonical name.
_FIELDS = {"CIE 1931 2°": (2.0, 1931), "CIE 1964 10°": (10.0, 1964), "CIE 2015 2°": (2.0, 2015),
           "CIE 2015 10°": (10.0, 2015)}
_REFERENCES = {
    "CIE 1931 2°": "CIE 015:2018 Table 1",
    "CIE 1964 10°": "CIE 015:2018 Table 2",
    "CIE 2015 2°": "CIE 170-2:2015 (XYZ functions, 2°)",
    "CIE 2015 10°": "CIE 170-2:2015 (XYZ functions, 10°)",
}
#: The label of colour-matching functions given as a Spectrum.
CUSTOM_OBSERVER = "custom observer"


@dataclass(frozen=True, slots=True, eq=False)
class Observer:
    """An observer resolved once: its name, field, reference and colour-matching functions.

    Made by :func:`resolve_observer` (do not construct it by hand); every public function that
    takes an observer accepts one, so a value resolved once can be passed on.

    Attributes
    ----------
    name : str
        Canonical name (``"CIE 1931 2°"``, …) or ``"custom observer"`` for a user's functions.
    label : str
        Human-readable name (the same as ``name``).
    field_deg : float or None
        Field size, degrees (2 or 10); ``None`` for a custom observer.
    year : int or None
        Year of the standard (1931, 1964, 2015); ``None`` for a custom observer.
    reference : str
        The CIE table the functions come from (``data/PROVENANCE.md`` for the files).
    custom_cmfs : Spectrum or None
        The user's x̄, ȳ, z̄, shape (3, K) (custom observers only).

    Notes
    -----
    Two shipped observers are equal when their names are; a custom one is equal only to itself.
    Shipped ones are hashable cache keys (:attr:`cacheable`).

    Examples
    --------
    >>> ten = resolve_observer("10deg")
    >>> ten.name, ten.field_deg, ten.year, ten.cmfs().values.shape
    ('CIE 1964 10°', 10.0, 1964, (3, 471))
    """

    name: str
    label: str
    field_deg: float | None = None
    year: int | None = None
    reference: str = ""
    custom_cmfs: Spectrum | None = None

    @property
    def cacheable(self) -> bool:
        """Whether the observer is a shipped one (so results may be cached by it)."""
        return self.custom_cmfs is None

    def cmfs(self) -> Spectrum:
        """Colour-matching functions x̄, ȳ, z̄, shape (3, K), loaded on demand and cached.

        Returns
        -------
        Spectrum
            As :func:`observer` (read-only values, 1 nm) or the user's Spectrum.

        Examples
        --------
        >>> resolve_observer("1931").cmfs().names
        ('x_bar', 'y_bar', 'z_bar')
        """
        if self.custom_cmfs is not None:
            return self.custom_cmfs
        result = _observer(self.name)
        result.values.setflags(write=False)
        return result

    def _key(self):
        return ("custom", id(self.custom_cmfs)) if self.custom_cmfs is not None else ("cie", self.name)

    def __eq__(self, other) -> bool:
        return isinstance(other, Observer) and self._key() == other._key()

    def __hash__(self) -> int:
        return hash(self._key())

    def __repr__(self) -> str:
        return f"Observer({self.name!r})"


def resolve_observer(observer, argument: str = "observer") -> Observer:
    """The one observer resolver: a name, alias, Spectrum or :class:`Observer` → an :class:`Observer`.

    Every public function resolves its ``observer`` here once, at its entry, and passes the
    value on; inner code never parses a name again.

    Parameters
    ----------
    observer : str, Spectrum or Observer
        A name or alias of :data:`OBSERVERS` (``"1931"``, ``"1964"``, ``"2015-2"``, ``"2015-10"``,
        …), colour-matching functions as a (3, K) :class:`Spectrum`, or an :class:`Observer`
        (returned as it is); see :term:`observer` for the spellings.
    argument : str, default "observer"
        The caller's argument name, for the error message.

    Returns
    -------
    Observer

    Raises
    ------
    ColorimetryError
        For an unknown name (listing the observers), a Spectrum that is not (3, K), or any
        other type, naming ``argument``.

    References
    ----------
    CIE 015:2018 Tables 1 and 2; CIE 170-2:2015.

    Examples
    --------
    >>> resolve_observer("10 degree").name, resolve_observer("2015-10").name
    ('CIE 1964 10°', 'CIE 2015 10°')
    """
    if isinstance(observer, Observer):
        return observer
    return _parse_observer(observer, argument)


def _parse_observer(observer, argument: str) -> Observer:
    """The parsing step of :func:`resolve_observer` (one call per argument per public call)."""
    if isinstance(observer, Spectrum):
        if observer.values.shape[:-1] != (3,):
            raise ColorimetryError(
                f"{argument}: a custom observer must be a Spectrum of shape (3, K) (x̄, ȳ, z̄), "
                f"got {observer.values.shape}"
            )
        return Observer(CUSTOM_OBSERVER, CUSTOM_OBSERVER, None, None,
                        "user-supplied colour-matching functions", observer)
    if not isinstance(observer, str):
        raise ColorimetryError(f"{argument}: expected a name such as '1931' or '1964', got {observer!r}")
    key = " ".join(observer.strip().lower().replace("_", " ").replace("degree", "deg").split())
    for candidate in (observer, key, key.replace(" ", "")):
        if candidate in OBSERVERS:
            name = OBSERVERS.canonical(candidate)
            break
    else:
        name = OBSERVERS.canonical(observer, argument)  # raises, listing the observers
    field_deg, year = _FIELDS[name]
    return Observer(name, name, field_deg, year, _REFERENCES[name])


def canonical_observer_name(name: str) -> str:
    """Canonical name for an observer name or alias (``"1931"``, ``"10deg"``, …), or raise.

    A thin wrapper over :func:`resolve_observer` for callers that need a shipped observer's name.

    Parameters
    ----------
    name : str or Observer
        A canonical name or an alias of :data:`OBSERVERS`, in any case; spaces, underscores and
        "degree" for "deg" are tolerated; or a shipped :class:`Observer`.

    Returns
    -------
    str
        The canonical name, e.g. ``"CIE 1964 10°"``.

    Raises
    ------
    ColorimetryError
        For a non-string, a custom observer or an unknown observer, listing the observers.

    Examples
    --------
    >>> canonical_observer_name("10 degree"), canonical_observer_name("2015-10")
    ('CIE 1964 10°', 'CIE 2015 10°')
    """
    if isinstance(name, Observer) and name.cacheable:
        return name.name
    if not isinstance(name, str):
        raise ColorimetryError(f"observer: expected a name such as '1931' or '1964', got {name!r}")
    return resolve_observer(name).name


@cache
def _observer(canonical: str) -> Spectrum:
    header, table = load_table(OBSERVERS.get(canonical))
    return Spectrum(table[:, 0], table[:, 1:].T.copy(), header[1:])


def observer(name: str = DEFAULT_OBSERVER) -> Spectrum:
    """Colour-matching functions of a CIE standard observer.

    Parameters
    ----------
    name : str or Observer, default DEFAULT_OBSERVER ("CIE 1931 2°")
        ``"CIE 1931 2°"`` (aliases ``"1931"``, ``"2deg"``), ``"CIE 1964 10°"`` (``"1964"``,
        ``"10deg"``), ``"CIE 2015 2°"`` (``"2015-2"``), ``"CIE 2015 10°"`` (``"2015-10"``).

    Returns
    -------
    Spectrum
        Values of shape ``(3, K)``: x̄, ȳ, z̄ at 1 nm (360–830 nm for 1931/1964, 390–830 nm
        for the 2015 observers), names ``("x_bar", "y_bar", "z_bar")``. The values are read-only
        and shared between calls.

    Raises
    ------
    ColorimetryError
        For a name that is not a string or not a known observer or alias.

    References
    ----------
    CIE 015:2018, Tables 1 and 2; CIE 170-2:2015 (see the module docstring).

    Examples
    --------
    >>> observer("1931").values.shape
    (3, 471)
    >>> cmfs = observer("10deg")
    >>> cmfs.names, float(cmfs.wavelengths_nm[0]), float(cmfs.wavelengths_nm[-1])
    (('x_bar', 'y_bar', 'z_bar'), 360.0, 830.0)
    """
    if isinstance(name, Spectrum):  # the functions themselves are not a name of any
        raise ColorimetryError(f"observer: expected a name such as '1931' or '1964', got {name!r}")
    return resolve_observer(name).cmfs()
