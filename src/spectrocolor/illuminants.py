"""CIE illuminants: the vocabulary of lights, resolved once into :class:`Illuminant` values.

The formulas of the lights that have one (Planckian radiators, illuminant A, the CIE daylight
series) are in :mod:`spectrocolor.radiators`; the lights named ``"kind:T"`` are the entries of
:data:`LIGHT_KINDS`, a registry one can add to.

References
----------
CIE 015:2018 *Colorimetry*, 4th ed.: §4.1 and Table 5 (illuminant A formula with
c₂ = 1.435 × 10⁻² m·K), §4.1.2 and Table 6 (daylight basis S0, S1, S2 and the xD, yD, M1, M2
formulae), Tables 8–10 (FL1–FL12, LED-B1–B5). CODATA 2018 (second radiation constant
c₂ = 1.438 776 877 × 10⁻² m·K). Sources of the files: ``data/PROVENANCE.md``.

Why this file is long: it is the vocabulary of lights: the registry of CIE names, the registry of
kinds of light named by a temperature (:data:`LIGHT_KINDS`, :class:`LightKind`), the typed
:class:`Illuminant` with its cached SPD, and the one resolver every argument that names a light goes
through; the formulas were moved to :mod:`spectrocolor.radiators`, and what remains is one concept.
"""

from __future__ import annotations

import re
from collections.abc import Callable, Iterator, Mapping
from dataclasses import dataclass
from functools import cache, lru_cache

import numpy as np

from .data_tables import load_table
from .errors import ColorimetryError, SpectrumError
from .radiators import blackbody, daylight, daylight_xy, illuminant_A_values
from .registry import Registry
from .spectrum import Spectrum, validate_wavelengths, wavelength_grid

#: The CIE illuminants by name: value "formula" (A), "constant" (E) or "table" (a CIE table in
#: data/illuminants/), with one-line descriptions (CIE 015:2018 §4, Tables 5-10).
ILLUMINANTS = Registry("illuminant", "a CIE illuminant name (or use 'blackbody:T' / 'D:T' for other temperatures)")
ILLUMINANTS.add("A", "formula", "incandescent tungsten, a 2856 K Planckian radiator (CIE 015 eq. 4.1)")
ILLUMINANTS.add("B", "table", "direct sunlight, about 4874 K (obsolete; CIE 015 Table 10 note)")
ILLUMINANTS.add("C", "table", "average daylight, about 6774 K (obsolete; seed 001's illuminant)")
for _cct in (50, 55, 65, 75):
    ILLUMINANTS.add(f"D{_cct}", "table", f"CIE daylight, about {_cct}00 K")
ILLUMINANTS.add("E", "constant", "equal energy: 100 at every wavelength")
for _i, _kind in enumerate(("standard",) * 6 + ("broadband",) * 3 + ("three-band",) * 3, start=1):
    ILLUMINANTS.add(f"FL{_i}", "table", f"CIE fluorescent lamp {_i} ({_kind})")
for _i in range(1, 6):
    ILLUMINANTS.add(f"LED-B{_i}", "table", f"CIE phosphor-converted white LED {_i} (CIE 015 Table 10)")
_DEFAULT_GRID = (300.0, 830.0, 5.0)
#: Temperatures accepted for Planckian radiators, K. Below about 100 K the relative SPD
#: over 360–830 nm underflows to zero (exp(c₂/λT) overflows), so nothing meaningful remains.
MIN_TEMPERATURE_K, MAX_TEMPERATURE_K = 100.0, 1.0e6


def illuminant_names() -> tuple[str, ...]:
    """Names of the CIE illuminants accepted by :func:`illuminant`.

    Returns
    -------
    tuple of str
        Canonical names: A, B, C, D50–D75, E, FL1–FL12, LED-B1–B5. Blackbodies (``"blackbody:T"``)
        and daylights of any temperature (``"D:T"``) are accepted too but not listed.

    Examples
    --------
    >>> names = illuminant_names()
    >>> names[:8], len(names)
    (('A', 'B', 'C', 'D50', 'D55', 'D65', 'D75', 'E'), 25)
    """
    return ILLUMINANTS.names()


def canonical_illuminant_name(name: str) -> str:
    """``"d65"``, ``"FL 11"``, ``"led_b1"`` → ``"D65"``, ``"FL11"``, ``"LED-B1"``; or raise.

    Parameters
    ----------
    name : str
        A CIE illuminant name in any case, with or without spaces or underscores (``"F2"`` is
        read as ``"FL2"``).

    Returns
    -------
    str
        One of :func:`illuminant_names`.

    Raises
    ------
    ColorimetryError
        For a non-string or an unknown name (use :func:`canonical_illuminant` for
        ``"blackbody:T"``, ``"D:T"`` and temperatures).

    Examples
    --------
    >>> canonical_illuminant_name("fl 11"), canonical_illuminant_name("led_b1"), canonical_illuminant_name("F2")
    ('FL11', 'LED-B1', 'FL2')
    """
    if not isinstance(name, str):
        raise ColorimetryError(f"illuminant: expected a name such as 'D65', got {name!r}")
    key = re.sub(r"[\s_]+", "", name.strip().upper())
    key = re.sub(r"^LED-?B", "LED-B", key)
    key = re.sub(r"^F(\d)", r"FL\1", key) if not key.startswith("FL") else key
    return ILLUMINANTS.canonical(key if key in ILLUMINANTS else name)


#: The illuminant used wherever a reflectance needs one and the caller gives none: CIE D65
#: (CIE 015:2018 §4.1, the standard daylight illuminant). Stated here once; every function,
#: the CLI and the app take their default from this constant.
DEFAULT_ILLUMINANT = "D65"

@dataclass(frozen=True, slots=True)
class LightKind:
    """A family of lights with one parameter, a temperature: what ``"prefix:T"`` names.

    Registered in :data:`LIGHT_KINDS` (its name is the :attr:`Illuminant.kind`, its aliases
    the other words accepted before the colon); the resolver, the explorer's light lab, its
    request validation, ``/api/options`` and the command line's help read it from there.

    Attributes
    ----------
    prefix : str
        The word of the canonical name, ``"blackbody"`` in ``"blackbody:6504"``, ``"D"`` in
        ``"D:5000"``.
    label_template : str
        The :attr:`Illuminant.label`, formatted with ``T`` (kelvin): ``"blackbody {T:g} K"``.
    spd : callable
        ``spd(temperature_K, wavelengths_nm) -> Spectrum``, the relative SPD (``wavelengths_nm``
        None: the kind's own grid).
    reference : str
        Where the distribution is defined.
    min_K, max_K : float
        The temperatures accepted, K (within ``MIN_TEMPERATURE_K``–``MAX_TEMPERATURE_K``).
    validate : callable or None
        ``validate(temperature_K)`` raising :class:`ColorimetryError` with the kind's own message
        (the daylight series: :func:`~spectrocolor.radiators.daylight_xy`); None: the range above.
    by_formula : bool
        Whether the SPD is a formula defined at every wavelength (not interpolated from a table).

    Examples
    --------
    >>> kind = LIGHT_KINDS.get("bb")
    >>> kind.prefix, kind.label(2856.0), kind.min_K
    ('blackbody', 'blackbody 2856 K', 100.0)
    """

    prefix: str
    label_template: str
    spd: Callable[[float, np.ndarray | None], Spectrum]
    reference: str
    min_K: float = MIN_TEMPERATURE_K
    max_K: float = MAX_TEMPERATURE_K
    validate: Callable[[float], object] | None = None
    by_formula: bool = True

    def label(self, temperature_K: float) -> str:
        """The light's short name at ``temperature_K`` (:attr:`label_template` filled in).

        Parameters
        ----------
        temperature_K : float
            Temperature, K.

        Returns
        -------
        str

        Examples
        --------
        >>> LIGHT_KINDS.get("daylight").label(5000.0)
        'CIE daylight 5000 K'
        """
        return self.label_template.format(T=temperature_K)

    def check(self, temperature_K: float) -> None:
        """Raise :class:`ColorimetryError` unless the kind is defined at ``temperature_K``.

        Parameters
        ----------
        temperature_K : float
            Temperature, K.

        Raises
        ------
        ColorimetryError
            Outside the kind's range (the message of :attr:`validate` where it has one).

        Examples
        --------
        >>> LIGHT_KINDS.get("D").check(6500.0)
        >>> try:
        ...     LIGHT_KINDS.get("D").check(3000.0)
        ... except ColorimetryError as error:
        ...     print(error)
        cct_K: the CIE daylight series is defined for 4000–25000 K, got 3000.0
        """
        if self.validate is not None:
            self.validate(temperature_K)
        elif not self.min_K <= temperature_K <= self.max_K:
            raise ColorimetryError(
                f"temperature_K: {self.prefix} is defined for {self.min_K:g}–{self.max_K:g} K, got {temperature_K!r}")


#: The lights named ``"kind:T"`` (T in kelvin), by kind: a :class:`LightKind` each. The word
#: before the colon is the kind's name or an alias, in any case. Add one entry and the resolver,
#: the explorer (light lab, request validation, ``/api/options``) and ``--help`` offer it.
LIGHT_KINDS = Registry("illuminant", "a light kind ('kind:T', T in kelvin)")
LIGHT_KINDS.add(
    "blackbody",
    LightKind("blackbody", "blackbody {T:g} K", blackbody,
              "Planck's law; CIE 015:2018 §4.1; CODATA 2018 c₂ = 1.438776877e-2 m·K"),
    "a Planckian radiator at temperature_K (Planck's law, CODATA 2018 c₂)",
    aliases=("planck", "bb"), label="Planckian radiator",
    extra={"form": "a Planckian radiator at T kelvin"},
)
LIGHT_KINDS.add(
    "daylight",
    LightKind("D", "CIE daylight {T:g} K", daylight,
              "CIE 015:2018 §4.1.2, eqs. (4.7)–(4.10) and Table 6 (S0, S1, S2)",
              min_K=4000.0, max_K=25000.0, validate=daylight_xy, by_formula=False),
    "the CIE daylight series at correlated colour temperature temperature_K",
    aliases=("D",), label="CIE daylight",
    extra={"form": "the CIE daylight of correlated colour temperature T, 4000–25000 K"},
)


def _temperature_key(name: str) -> tuple[str, str] | None:
    """``(kind, temperature text)`` of ``"blackbody:6504 K"``-style names, or None (linear time).

    The word before the first colon is looked up in :data:`LIGHT_KINDS` (any case); the kind
    returned is its registered name.
    """
    word, colon, value = name.partition(":")
    if not colon or word.strip() not in LIGHT_KINDS:
        return None
    value = value.strip()
    if len(value) > 1 and value[-1] in "kK":
        value = value[:-1].rstrip()
    return (LIGHT_KINDS.canonical(word.strip()), value) if value else None


def _temperature_forms(conjunction: str = ", ") -> str:
    """``'blackbody:T', 'D:T'``: the registered kinds' forms, for messages."""
    return conjunction.join(f"'{LIGHT_KINDS.get(name).prefix}:T'" for name in LIGHT_KINDS)


def _accepted_sources() -> str:
    forms = ", ".join(
        f"'{LIGHT_KINDS.get(name).prefix}:T' ({LIGHT_KINDS.extra(name, 'form', LIGHT_KINDS.description(name))})"
        for name in LIGHT_KINDS)
    return (f"a CIE name such as 'D65' or 'A', {forms}, a temperature in kelvin (a blackbody), or a "
            "spectrocolor.Spectrum with one distribution")


class _IlluminantKinds(Mapping[str, str]):
    """``{kind: what defines it}``: "cie", the registered :data:`LIGHT_KINDS`, "spectrum" (live)."""

    _FIXED = {
        "cie": "a CIE illuminant of ILLUMINANTS: a table, the formula of A, or the constant E",
        "spectrum": "a user's Spectrum with one distribution, used on its own samples",
    }

    def _table(self) -> dict[str, str]:
        kinds = {name: LIGHT_KINDS.description(name) for name in LIGHT_KINDS}
        return {"cie": self._FIXED["cie"], **kinds, "spectrum": self._FIXED["spectrum"]}

    def __getitem__(self, kind: str) -> str:
        return self._table()[kind]

    def __iter__(self) -> Iterator[str]:
        return iter(self._table())

    def __len__(self) -> int:
        return len(LIGHT_KINDS) + 2

    def __repr__(self) -> str:
        return repr(self._table())


#: The kinds of light an :class:`Illuminant` can be, with what defines each: ``"cie"``, every
#: kind of :data:`LIGHT_KINDS` (``"blackbody"``, ``"daylight"``, …) and ``"spectrum"``. A live,
#: read-only mapping: it follows the registry.
ILLUMINANT_KINDS: Mapping[str, str] = _IlluminantKinds()
_REFERENCES = {
    "A": "CIE 015:2018 §4.1, eq. (4.1) (c₂ = 1.435e-2 m·K, 2848 K)",
    "E": "CIE 015:2018 §4.1 (equal-energy illuminant)",
    "spectrum": "user-supplied spectral power distribution",
}


@dataclass(frozen=True, slots=True, eq=False)
class Illuminant:
    """A light resolved once: what the colorimetry needs, never parsed again.

    Made by :func:`resolve_illuminant` (do not construct it by hand); every public function
    that takes an illuminant accepts one, so a value resolved once can be passed on.

    Attributes
    ----------
    name : str
        Canonical name: a CIE name (``"D65"``, ``"FL11"``), ``"blackbody:T"`` or ``"D:T"`` (T in
        kelvin, as ``%g``); for a Spectrum, its own name or ``"user illuminant"``.
    label : str
        Short human-readable name (:func:`illuminant_label`): ``"D65"``, ``"blackbody 3000 K"``,
        ``"CIE daylight 5000 K"``.
    kind : str
        One of :data:`ILLUMINANT_KINDS`: ``"cie"``, a kind of :data:`LIGHT_KINDS` (``"blackbody"``,
        ``"daylight"``, …) or ``"spectrum"``.
    temperature_K : float or None
        Temperature of a blackbody or correlated colour temperature of a daylight, K.
    reference : str
        Where the distribution is defined (the CIE table, formula or standard; ``data/PROVENANCE.md``
        for the files).
    spectrum : Spectrum or None
        The user's distribution (kind ``"spectrum"`` only).

    Notes
    -----
    Two named illuminants are equal when their canonical names are; one made from a Spectrum is
    equal only to itself. Named ones are hashable cache keys (:attr:`cacheable`).

    Examples
    --------
    >>> light = resolve_illuminant("blackbody:3000 K")
    >>> light.name, light.label, light.kind, light.temperature_K
    ('blackbody:3000', 'blackbody 3000 K', 'blackbody', 3000.0)
    >>> light.spd([560.0]).values.tolist()
    [100.0]
    >>> resolve_illuminant("d65") == resolve_illuminant("D65")
    True
    """

    name: str
    label: str
    kind: str
    temperature_K: float | None = None
    reference: str = ""
    spectrum: Spectrum | None = None

    @property
    def cacheable(self) -> bool:
        """Whether the light is named (so results computed under it may be cached by it)."""
        return self.kind != "spectrum"

    @property
    def canonical(self):
        """What :func:`canonical_illuminant` returns: the canonical name, or the user's Spectrum."""
        return self.spectrum if self.kind == "spectrum" else self.name

    @property
    def by_formula(self) -> bool:
        """Whether the distribution is a formula defined at every wavelength (A, blackbodies)."""
        if self.kind in LIGHT_KINDS:
            return bool(LIGHT_KINDS.get(self.kind).by_formula)
        return self.name == "A"

    @property
    def tabulated(self) -> bool:
        """Whether the distribution is a CIE table (interpolated, never extrapolated)."""
        return self.kind == "cie" and ILLUMINANTS.get(self.name) == "table"

    def spd(self, wavelengths_nm=None, method: str = "linear") -> Spectrum:
        """The relative spectral power distribution, computed on demand and cached.

        Parameters
        ----------
        wavelengths_nm : array_like, optional
            Grid, nm; ``None`` for the light's own grid (as :func:`illuminant`).
        method : str, default "linear"
            Interpolation for tabulated lights and user spectra (see :meth:`Spectrum.resample`).

        Returns
        -------
        Spectrum
            Relative SPD, dimensionless (the CIE tables are 100 at 560 nm). For a named light the
            values are read-only and shared between calls.

        Raises
        ------
        ColorimetryError
            For a grid outside a table's or the user's range (never extrapolated).

        Examples
        --------
        >>> resolve_illuminant("D65").spd([560.0, 600.0]).values.tolist()
        [100.0, 90.0062]
        """
        if self.spectrum is not None:  # kind "spectrum"
            if wavelengths_nm is None:
                return self.spectrum
            try:
                return self.spectrum.resample(wavelengths_nm, method)
            except SpectrumError as exc:
                raise ColorimetryError(f"illuminant: {exc}") from None
        try:
            key = None if wavelengths_nm is None else validate_wavelengths(wavelengths_nm).tobytes()
        except SpectrumError as exc:
            if not self.tabulated:
                raise
            raise ColorimetryError(f"illuminant {self.name}: {exc}") from None
        compute = _named_spd if isinstance(method, str) else _named_spd.__wrapped__  # (resample names a bad one)
        return compute(self.name, self.kind, self.temperature_K, key, method)

    def _key(self):
        return (self.kind, id(self.spectrum)) if self.kind == "spectrum" else (self.kind, self.name)

    def __eq__(self, other) -> bool:
        return isinstance(other, Illuminant) and self._key() == other._key()

    def __hash__(self) -> int:
        return hash(self._key())

    def __repr__(self) -> str:
        return f"Illuminant({self.name!r}, kind={self.kind!r})"


@lru_cache(maxsize=128)
def _named_spd(name: str, kind: str, temperature_K, grid_key: bytes | None, method: str) -> Spectrum:
    """A named light's SPD on a grid (``None``: its own), read-only and cached."""
    wavelengths_nm = None if grid_key is None else np.frombuffer(grid_key, dtype=float)
    if kind != "cie" and kind in LIGHT_KINDS:
        result = LIGHT_KINDS.get(kind).spd(temperature_K, wavelengths_nm)
    elif name == "A":
        grid = _table("A").wavelengths_nm if wavelengths_nm is None else validate_wavelengths(wavelengths_nm)
        result = Spectrum(grid, illuminant_A_values(grid), ("A",))
    elif name == "E":
        grid = wavelength_grid(*_DEFAULT_GRID) if wavelengths_nm is None else validate_wavelengths(wavelengths_nm)
        result = Spectrum(grid, np.full(grid.size, 100.0), ("E",))
    elif wavelengths_nm is None:
        result = _table(name)
    else:
        try:
            result = _table(name).resample(wavelengths_nm, method)
        except SpectrumError as exc:
            raise ColorimetryError(f"illuminant {name}: {exc}") from None
    result.values.setflags(write=False)
    return result


def _named(name: str) -> Illuminant:
    """The :class:`Illuminant` of a canonical CIE name."""
    reference = _REFERENCES.get(name) or (
        f"CIE 015:2018 Tables 5–10: {ILLUMINANTS.description(name)} (data/PROVENANCE.md)")
    return Illuminant(name, name, "cie", None, reference)


def temperature_light(kind: str, temperature_K, argument: str = "illuminant") -> Illuminant:
    """The light of a kind of :data:`LIGHT_KINDS` at a temperature: what ``"kind:T"`` resolves to.

    Parameters
    ----------
    kind : str
        A name or alias of :data:`LIGHT_KINDS` (any case): ``"blackbody"``, ``"bb"``, ``"D"``, ...
    temperature_K : float
        Temperature, K (``MIN_TEMPERATURE_K``–``MAX_TEMPERATURE_K``, and the kind's range).
    argument : str, default "illuminant"
        The name of the caller's argument, used in the error message.

    Returns
    -------
    Illuminant
        Named ``"prefix:T"`` (T as ``%g``), of kind the registered name.

    Raises
    ------
    ColorimetryError
        For an unknown kind or a temperature the kind does not accept.

    Examples
    --------
    >>> temperature_light("D", 6500).name, temperature_light("planck", 2856).label
    ('D:6500', 'blackbody 2856 K')
    """
    return _temperature_light(LIGHT_KINDS.canonical(kind, argument), temperature_K, argument)


def _temperature_light(name: str, temperature_K, argument: str, given: str | None = None) -> Illuminant:
    """:func:`temperature_light` of a registered ``name``; ``given`` is the text quoted in errors."""
    light_kind: LightKind = LIGHT_KINDS.get(name)
    temperature = _temperature(temperature_K, argument)
    try:
        light_kind.check(temperature)
    except ColorimetryError as exc:  # name the caller's argument, not the kind's
        quoted = given if given is not None else f"{light_kind.prefix}:{temperature:g}"
        raise ColorimetryError(f"{argument}: {quoted!r:.40}: {exc}") from None
    temperature = float(f"{temperature:g}")
    return Illuminant(f"{light_kind.prefix}:{temperature:g}", light_kind.label(temperature), name, temperature,
                      light_kind.reference)


def resolve_illuminant(illuminant, argument: str = "illuminant") -> Illuminant | None:
    """The one illuminant resolver: any accepted form → an :class:`Illuminant` (or ``None``).

    Every public function resolves its light arguments here once, at its entry, and passes the
    resulting value on; inner code never parses a name again. ``None`` means the same thing
    everywhere: no illuminant, so the spectra are lights (sources), not reflectances.

    Parameters
    ----------
    illuminant : None, str, int, float, Spectrum or Illuminant
        ``None``, a CIE name, ``"blackbody:T"``, ``"D:T"``, a temperature in kelvin, a
        :class:`Spectrum` with one distribution, or an :class:`Illuminant` (returned as it is); see
        :term:`illuminant` for the spellings and ranges.
    argument : str, default "illuminant"
        The name of the caller's argument, used in the error message.

    Returns
    -------
    Illuminant or None
        ``None`` for ``None``; else the resolved light.

    Raises
    ------
    ColorimetryError
        For anything else, naming ``argument`` and listing the accepted forms.

    References
    ----------
    CIE 015:2018 §4.1 and Tables 5–10 (the CIE illuminants); see the module docstring.

    Examples
    --------
    >>> resolve_illuminant("fl 11").name, resolve_illuminant(6504).name, resolve_illuminant("daylight:5000K").label
    ('FL11', 'blackbody:6504', 'CIE daylight 5000 K')
    >>> try:
    ...     resolve_illuminant("blackbody:cold", "second_illuminant")
    ... except ColorimetryError as error:
    ...     print(str(error)[:55])
    second_illuminant: 'blackbody:cold' needs a temperature
    """
    if illuminant is None or isinstance(illuminant, Illuminant):
        return illuminant
    return _parse_illuminant(illuminant, argument)


def _parse_illuminant(illuminant, argument: str) -> Illuminant:
    """The parsing step of :func:`resolve_illuminant` (one call per argument per public call)."""
    if isinstance(illuminant, Spectrum):
        if illuminant.values.ndim != 1:
            raise ColorimetryError(
                f"{argument}: expected one spectral distribution, got a batch of shape {illuminant.batch_shape}"
            )
        label = illuminant.names[0] if illuminant.names and illuminant.names[0] else "user illuminant"
        return Illuminant(label, label, "spectrum", None, _REFERENCES["spectrum"], illuminant)
    if isinstance(illuminant, int | float | np.integer | np.floating) and not isinstance(illuminant, bool):
        return temperature_light("blackbody", illuminant, argument)
    if isinstance(illuminant, str):
        match = _temperature_key(illuminant)
        if match:
            try:
                value = float(match[1])
            except ValueError:
                raise ColorimetryError(
                    f"{argument}: {illuminant!r} needs a temperature in kelvin after the colon, e.g. 'blackbody:6504'"
                ) from None
            return _temperature_light(match[0], value, argument, illuminant)
        try:
            return _named(canonical_illuminant_name(illuminant))
        except ColorimetryError:
            raise ColorimetryError(
                f"{argument}: {illuminant!r:.80} is not a CIE illuminant name ({', '.join(ILLUMINANTS)}); "
                f"other forms: {_temperature_forms()}, a temperature in kelvin, a Spectrum, or None for lights"
            ) from None
    raise ColorimetryError(
        f"{argument}: expected None (no illuminant: the spectra are lights), {_accepted_sources()}; "
        f"got {illuminant!r:.80}")


def canonical_illuminant(illuminant, argument: str = "illuminant"):
    """The one illuminant vocabulary of spectrocolor, resolved to a canonical form.

    A thin wrapper over :func:`resolve_illuminant` for callers that want a plain value (a
    hashable name) rather than an :class:`Illuminant`.

    Parameters
    ----------
    illuminant : None, str, int, float, Spectrum or Illuminant
        Any form :func:`resolve_illuminant` accepts.
    argument : str
        The name of the caller's argument, used in the error message.

    Returns
    -------
    None, str or Spectrum
        ``None``; a canonical name (``"D65"``, ``"blackbody:6504"``, ``"D:5000"``), hashable and
        usable as a cache key; or the Spectrum itself.

    Raises
    ------
    ColorimetryError
        For anything else, naming ``argument`` and listing the accepted forms.

    Examples
    --------
    >>> canonical_illuminant("fl 11"), canonical_illuminant(6504), canonical_illuminant("daylight:5000K")
    ('FL11', 'blackbody:6504', 'D:5000')
    """
    resolved = resolve_illuminant(illuminant, argument)
    return None if resolved is None else resolved.canonical


def _temperature(value, argument: str) -> float:
    value = float(value)
    if not (np.isfinite(value) and MIN_TEMPERATURE_K <= value <= MAX_TEMPERATURE_K):
        raise ColorimetryError(
            f"{argument}: a temperature must be {MIN_TEMPERATURE_K:g}–{MAX_TEMPERATURE_K:g} K, got {value!r}"
        )
    return value


def illuminant_label(illuminant) -> str:
    """A short human-readable name of an illuminant given in any accepted form.

    Parameters
    ----------
    illuminant : None, str, int, float, Spectrum or Illuminant
        Any form :func:`resolve_illuminant` accepts.

    Returns
    -------
    str
        The canonical CIE name, ``"blackbody T K"``, ``"CIE daylight T K"``, the Spectrum's name
        (``"user illuminant"`` when it has none), or ``"none (lights)"`` for ``None``
        (:attr:`Illuminant.label`).

    Raises
    ------
    ColorimetryError
        As :func:`resolve_illuminant`.

    Examples
    --------
    >>> illuminant_label("d50"), illuminant_label(3000), illuminant_label(None)
    ('D50', 'blackbody 3000 K', 'none (lights)')
    """
    resolved = resolve_illuminant(illuminant)
    return "none (lights)" if resolved is None else resolved.label


@cache
def _table(name: str) -> Spectrum:
    header, table = load_table(f"illuminants/{name}.csv")
    return Spectrum(table[:, 0], table[:, 1], (name,))


def illuminant(name, wavelengths_nm=None, method: str = "linear") -> Spectrum:
    """Relative spectral power distribution of an illuminant named in the library's vocabulary.

    Parameters
    ----------
    name : str, int, float or Spectrum
        Any form :func:`canonical_illuminant` accepts except ``None``: ``"A"`` (evaluated from
        its defining formula on any grid), ``"E"`` (equal energy, 100 everywhere), ``"B"``,
        ``"C"``, ``"D50"``, ``"D55"``, ``"D65"``, ``"D75"``, ``"FL1"``–``"FL12"``,
        ``"LED-B1"``–``"LED-B5"`` (the CIE tables, 5 nm); ``"blackbody:T"`` or a number
        (:func:`blackbody`); ``"D:T"`` (:func:`daylight`); a Spectrum (resampled if a grid is
        given).
    wavelengths_nm : array_like, optional
        Grid to return, nm. ``None``: the table's own grid (A: 300–780 nm, E: 300–830 nm, 5 nm;
        blackbody 360–830 nm at 1 nm; daylight 300–830 nm at 5 nm). Tabulated illuminants are
        interpolated with ``method`` (default linear, as CIE 015 recommends for the daylight series)
        and never extrapolated; see :term:`wavelength grid`.
    method : str, default "linear"
        Interpolation for tabulated illuminants (see :meth:`Spectrum.resample`).

    Returns
    -------
    Spectrum
        Relative SPD (arbitrary units; the CIE tables are 100 at 560 nm).

    Raises
    ------
    ColorimetryError
        For ``None``, an unknown name, or a grid outside the table's range (never extrapolated).

    References
    ----------
    CIE 015:2018 §4.1 and Tables 5–10 (see the module docstring).

    Examples
    --------
    >>> float(illuminant("D65", [560.0]).values[0])
    100.0
    >>> float(illuminant("blackbody:2856", [560.0]).values[0])
    100.0
    """
    light = resolve_illuminant(name, "name")
    if light is None:
        raise ColorimetryError(f"name: expected {_accepted_sources()}; got None")
    return light.spd(wavelengths_nm, method)
