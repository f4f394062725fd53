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
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass
from typing import Any

from .errors import ColorimetryError


@dataclass(frozen=True)
class RegistryEntry:
    """One named choice: its name, the object that implements it and a one-line description.

    Attributes
    ----------
    name : str
        The canonical name.
    value : object
        The implementing object.
    description : str
        One line for help texts and option lists.

    Examples
    --------
    >>> RegistryEntry("nearest", round, "round half to even").description
    'round half to even'
    """

    name: str
    value: Any
    description: str


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

    def add(self, name: str, value: Any, description: str, aliases: tuple[str, ...] = ()) -> Any:
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

        Returns
        -------
        object
            ``value``, so ``add`` can be used as a decorator-like one-liner.

        Raises
        ------
        ValueError
            If ``name`` is registered already.

        Examples
        --------
        >>> rounding = Registry("rounding", "a rounding rule")
        >>> rounding.add("nearest", round, "round half to even", aliases=("Near",)) is round
        True
        """
        if name in self._entries:
            raise ValueError(f"{self.argument}: {name!r} is registered twice")
        self._entries[name] = RegistryEntry(name, value, description)
        for alias in (name, *aliases):
            self._aliases[alias.lower()] = name
        return value

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
