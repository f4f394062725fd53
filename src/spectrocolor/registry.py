"""Registries: one table per family of named choices.

A family of choices (summation methods, gamut strategies, normalisations, transfer functions,
chromatic adaptation transforms, RGB spaces, observers, illuminants) is one :class:`Registry`:
an ordered table from a name to an entry and a one-line description. Validation messages, the
command line's ``choices`` and help texts, the app's option lists and the documentation are all
derived from that table, so adding a choice is adding one entry, and no list of names is ever
written twice.

Example
-------
>>> rounding = Registry("rounding", "a rounding rule")
>>> _ = rounding.add("nearest", round, "round half to even")
>>> _ = rounding.add("down", int, "truncate towards zero")
>>> rounding.names()
('nearest', 'down')
>>> rounding.get("down")(2.7)
2
>>> rounding.get("up")
Traceback (most recent call last):
...
spectrocolor.errors.ColorimetryError: rounding: 'up' is not a rounding rule; choose one of 'nearest', 'down'

Why this file is long: one class, :class:`Registry`, with its live name views and entries; every
interface (request models, options, the page, the CLI) reads choices through it, so its contract is
kept in one place.
"""

from __future__ import annotations

from collections.abc import Iterator, Mapping, Sequence
from dataclasses import dataclass, field
from types import MappingProxyType
from typing import Any, overload

from .errors import ColorimetryError


@dataclass(frozen=True)
class RegistryEntry:
    """One named choice: its name, the object that implements it, a one-line description, the
    short label an option list shows, and the texts one family needs beyond those (``extra``).

    Attributes
    ----------
    name : str
        The canonical name.
    value : object
        The implementing object.
    description : str
        One line for help texts and option lists.
    label : str
        A few words for a select box or a legend (default: the name).
    extra : mapping of str to object
        Family-specific texts or facts (read-only), such as what a gamut strategy does to a
        colour (``"action"``); :meth:`Registry.extra` reads one.

    Examples
    --------
    >>> RegistryEntry("nearest", round, "round half to even").description
    'round half to even'
    >>> RegistryEntry("nearest", round, "round half to even", "to nearest").label
    'to nearest'
    """

    name: str
    value: Any
    description: str
    label: str = ""
    extra: Mapping[str, Any] = field(default_factory=lambda: MappingProxyType({}))

    def __post_init__(self) -> None:
        object.__setattr__(self, "label", self.label or self.name)
        object.__setattr__(self, "extra", MappingProxyType(dict(self.extra)))


class Registry:
    """An ordered table of named choices for one argument.

    Parameters
    ----------
    argument : str
        The argument these names are given to (``"gamut"``, ``"method"``, ...); error messages
        name it.
    kind : str
        What one choice is, with its article, for messages (``"a gamut strategy"``).
    error : type, default ColorimetryError
        The exception raised for an unknown name (a ``ValueError`` subclass).

    Examples
    --------
    >>> rounding = Registry("rounding", "a rounding rule")
    >>> _ = rounding.add("nearest", round, "round half to even")
    >>> "nearest" in rounding, len(rounding), list(rounding)
    (True, 1, ['nearest'])
    """

    def __init__(self, argument: str, kind: str, error: type[ValueError] = ColorimetryError) -> None:
        self.argument = argument
        self.kind = kind
        self.error = error
        self._entries: dict[str, RegistryEntry] = {}
        self._aliases: dict[str, str] = {}

    def add(
        self,
        name: str,
        value: Any,
        description: str,
        aliases: tuple[str, ...] = (),
        *,
        label: str = "",
        extra: Mapping[str, Any] | None = None,
    ) -> Any:
        """Register ``value`` under ``name`` (and lower-case ``aliases``); returns ``value``.

        Parameters
        ----------
        name : str
            The canonical name (matched case-insensitively).
        value : object
            The object that implements the choice (a function, a space, …).
        description : str
            One line for help texts, option lists and the documentation.
        aliases : tuple of str, default ()
            Other names accepted for the same entry (case-insensitive).
        label : str, optional
            A few words for option lists (the app's select boxes); default the name.
        extra : mapping, optional
            Texts or facts one family's interfaces need beyond the description (see
            ``RegistryEntry.extra``).

        Returns
        -------
        object
            ``value``, so ``add`` can be used as a decorator-like one-liner.

        Raises
        ------
        ValueError
            If ``name`` (or one of ``aliases``) is registered already.

        Examples
        --------
        >>> rounding = Registry("rounding", "a rounding rule")
        >>> rounding.add("nearest", round, "round half to even", aliases=("Near",)) is round
        True
        """
        if name in self._entries:
            raise ValueError(f"{self.argument}: {name!r} is registered twice")
        taken = [a for a in (name, *aliases) if a.lower() in self._aliases]
        if taken:
            raise ValueError(f"{self.argument}: {taken[0]!r} already names {self._aliases[taken[0].lower()]!r}")
        self._entries[name] = RegistryEntry(name, value, description, label, extra or {})
        for alias in (name, *aliases):
            self._aliases[alias.lower()] = name
        return value

    def remove(self, name: str) -> RegistryEntry:
        """Unregister ``name`` and its aliases (a plug-in unloading, a test cleaning up).

        Parameters
        ----------
        name : str
            A registered name or alias (case-insensitive).

        Returns
        -------
        RegistryEntry
            The entry removed.

        Raises
        ------
        ValueError
            The registry's ``error`` class for an unknown name.

        Examples
        --------
        >>> rounding = Registry("rounding", "a rounding rule")
        >>> _ = rounding.add("nearest", round, "round half to even", aliases=("Near",))
        >>> rounding.remove("near").name, "nearest" in rounding, "near" in rounding
        ('nearest', False, False)
        """
        key = self.canonical(name)
        for alias in [a for a, target in self._aliases.items() if target == key]:
            del self._aliases[alias]
        return self._entries.pop(key)

    def entry(self, name: str, argument: str | None = None) -> RegistryEntry:
        """The whole :class:`RegistryEntry` of ``name`` (or an alias).

        Parameters
        ----------
        name : str
            A registered name or alias (case-insensitive).
        argument : str, optional
            The caller's argument name for the error message (default: the registry's).

        Returns
        -------
        RegistryEntry

        Raises
        ------
        ValueError
            The registry's ``error`` class for an unknown name.

        Examples
        --------
        >>> rounding = Registry("rounding", "a rounding rule")
        >>> _ = rounding.add("down", int, "truncate towards zero", label="truncate")
        >>> rounding.entry("DOWN").label
        'truncate'
        """
        return self._entries[self.canonical(name, argument)]

    def entries(self) -> tuple[RegistryEntry, ...]:
        """Every entry, in registration order.

        Returns
        -------
        tuple of RegistryEntry

        Examples
        --------
        >>> rounding = Registry("rounding", "a rounding rule")
        >>> _ = rounding.add("down", int, "truncate towards zero")
        >>> [e.name for e in rounding.entries()]
        ['down']
        """
        return tuple(self._entries.values())

    def names_view(self, first: str | None = None) -> RegistryNames:
        """A live, read-only sequence of the names (``first`` moved to the front).

        Unlike :meth:`names`, the view follows later :meth:`add` and :meth:`remove` calls, so a
        module can keep it as a constant (the app's option lists do).

        Parameters
        ----------
        first : str, optional
            A name listed first (a default), if registered.

        Returns
        -------
        RegistryNames

        Examples
        --------
        >>> rounding = Registry("rounding", "a rounding rule")
        >>> _ = rounding.add("nearest", round, "round half to even")
        >>> view = rounding.names_view(first="down")
        >>> _ = rounding.add("down", int, "truncate towards zero")
        >>> list(view), "down" in view, None in view
        (['down', 'nearest'], True, False)
        """
        return RegistryNames(self, first)

    def canonical(self, name: str, argument: str | None = None) -> str:
        """The registered name for ``name`` or one of its aliases (case-insensitive), or raise.

        Parameters
        ----------
        name : str
            A registered name or alias, in any case, surrounding spaces ignored.
        argument : str, optional
            The caller's argument name for the error message (default: the registry's).

        Returns
        -------
        str
            The canonical name.

        Raises
        ------
        ValueError
            The registry's ``error`` class, naming the argument and listing the names.

        Examples
        --------
        >>> rounding = Registry("rounding", "a rounding rule")
        >>> _ = rounding.add("nearest", round, "round half to even", aliases=("Near",))
        >>> _ = rounding.add("down", int, "truncate towards zero")
        >>> rounding.canonical(" near ")
        'nearest'
        """
        if isinstance(name, str):
            key = self._aliases.get(name.strip().lower())
            if key is not None:
                return key
        raise self.error(
            f"{argument or self.argument}: {name!r:.80} is not {self.kind}; choose one of "
            + ", ".join(repr(n) for n in self._entries)
        )

    def get(self, name: str, argument: str | None = None) -> Any:
        """The object registered under ``name`` (or an alias), or a clear error naming the argument.

        Parameters
        ----------
        name : str
            A registered name or alias (case-insensitive).
        argument : str, optional
            The caller's argument name for the error message (default: the registry's).

        Returns
        -------
        object
            The registered value.

        Raises
        ------
        ValueError
            The registry's ``error`` class for an unknown name.

        Examples
        --------
        >>> rounding = Registry("rounding", "a rounding rule")
        >>> _ = rounding.add("nearest", round, "round half to even", aliases=("Near",))
        >>> _ = rounding.add("down", int, "truncate towards zero")
        >>> rounding.get("down")(2.7)
        2
        """
        return self._entries[self.canonical(name, argument)].value

    def names(self) -> tuple[str, ...]:
        """The registered names, in registration order.

        Returns
        -------
        tuple of str
            Canonical names (aliases are not listed).

        Examples
        --------
        >>> rounding = Registry("rounding", "a rounding rule")
        >>> _ = rounding.add("nearest", round, "round half to even", aliases=("Near",))
        >>> _ = rounding.add("down", int, "truncate towards zero")
        >>> rounding.names()
        ('nearest', 'down')
        """
        return tuple(self._entries)

    def description(self, name: str) -> str:
        """The one-line description of ``name``.

        Parameters
        ----------
        name : str
            A registered name or alias.

        Returns
        -------
        str
            The description given to :meth:`add`.

        Raises
        ------
        ValueError
            The registry's ``error`` class for an unknown name.

        Examples
        --------
        >>> rounding = Registry("rounding", "a rounding rule")
        >>> _ = rounding.add("nearest", round, "round half to even", aliases=("Near",))
        >>> _ = rounding.add("down", int, "truncate towards zero")
        >>> rounding.description("near")
        'round half to even'
        """
        return self._entries[self.canonical(name)].description

    def label(self, name: str) -> str:
        """The short label of ``name`` for option lists (the name where none was given).

        Parameters
        ----------
        name : str
            A registered name or alias.

        Returns
        -------
        str

        Raises
        ------
        ValueError
            The registry's ``error`` class for an unknown name.

        Examples
        --------
        >>> rounding = Registry("rounding", "a rounding rule")
        >>> _ = rounding.add("down", int, "truncate towards zero", label="truncate")
        >>> _ = rounding.add("nearest", round, "round half to even")
        >>> rounding.label("down"), rounding.label("nearest")
        ('truncate', 'nearest')
        """
        return self._entries[self.canonical(name)].label

    def extra(self, name: str, key: str, default: Any = None) -> Any:
        """One family-specific text of ``name`` (``RegistryEntry.extra``), or ``default``.

        Parameters
        ----------
        name : str
            A registered name or alias.
        key : str
            The text wanted (``"action"`` for gamut strategies, ...).
        default : object, optional
            Returned where the entry has no such text.

        Returns
        -------
        object

        Examples
        --------
        >>> rounding = Registry("rounding", "a rounding rule")
        >>> _ = rounding.add("down", int, "truncate towards zero", extra={"symbol": "⌊x⌋"})
        >>> rounding.extra("down", "symbol"), rounding.extra("down", "other", "-")
        ('⌊x⌋', '-')
        """
        return self._entries[self.canonical(name)].extra.get(key, default)

    def help(self) -> str:
        """``name: description`` lines, for command-line help and the documentation.

        Returns
        -------
        str
            The entries as ``name: description``, joined by ``"; "``.

        Examples
        --------
        >>> rounding = Registry("rounding", "a rounding rule")
        >>> _ = rounding.add("nearest", round, "round half to even", aliases=("Near",))
        >>> _ = rounding.add("down", int, "truncate towards zero")
        >>> rounding.help()
        'nearest: round half to even; down: truncate towards zero'
        """
        return "; ".join(f"{entry.name}: {entry.description}" for entry in self._entries.values())

    def options(self) -> list[dict[str, str]]:
        """``[{"name": …, "description": …}, …]``: the app's option lists.

        Returns
        -------
        list of dict
            One ``{"name": str, "description": str}`` per entry, in registration order.

        Examples
        --------
        >>> rounding = Registry("rounding", "a rounding rule")
        >>> _ = rounding.add("nearest", round, "round half to even", aliases=("Near",))
        >>> _ = rounding.add("down", int, "truncate towards zero")
        >>> rounding.options()[1]
        {'name': 'down', 'description': 'truncate towards zero'}
        """
        return [{"name": e.name, "description": e.description} for e in self._entries.values()]

    def __contains__(self, name: object) -> bool:
        return isinstance(name, str) and name.strip().lower() in self._aliases

    def __iter__(self) -> Iterator[str]:
        return iter(self._entries)

    def __len__(self) -> int:
        return len(self._entries)


class RegistryNames(Sequence[str]):
    """A live, read-only sequence of a :class:`Registry`'s names, an optional default first.

    Made by :meth:`Registry.names_view`. Membership is exact (no aliases, no case folding), as
    for a fixed list of choices; anything that is not a string is simply not a member.

    Parameters
    ----------
    registry : Registry
        The table whose names are shown.
    first : str, optional
        A name listed first where registered.

    Examples
    --------
    >>> rounding = Registry("rounding", "a rounding rule")
    >>> names = RegistryNames(rounding)
    >>> _ = rounding.add("down", int, "truncate towards zero")
    >>> list(names), len(names), names[0], "DOWN" in names
    (['down'], 1, 'down', False)
    """

    def __init__(self, registry: Registry, first: str | None = None) -> None:
        self._registry = registry
        self._first = first

    def _names(self) -> tuple[str, ...]:
        names = self._registry.names()
        if self._first in names:
            return (self._first, *(n for n in names if n != self._first))
        return names

    @overload
    def __getitem__(self, index: int) -> str: ...

    @overload
    def __getitem__(self, index: slice) -> tuple[str, ...]: ...

    def __getitem__(self, index: int | slice) -> str | tuple[str, ...]:
        return self._names()[index]

    def __len__(self) -> int:
        return len(self._registry)

    def __contains__(self, name: object) -> bool:
        return isinstance(name, str) and name in self._registry.names()

    def __iter__(self) -> Iterator[str]:
        return iter(self._names())

    def __repr__(self) -> str:
        return f"RegistryNames({list(self._names())!r})"
