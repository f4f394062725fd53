"""CIE standard colorimetric observers (colour-matching functions x̄, ȳ, z̄ at 1 nm).

References
----------
CIE 015:2018 *Colorimetry*, 4th ed., Tables 1 and 2 (1931 2°, 1964 10°).
CIE 170-2:2015 *Fundamental chromaticity diagram with physiological axes*, XYZ functions
(the "CIE 2015" 2° and 10° observers). Sources of the files: ``data/PROVENANCE.md``.
"""

from __future__ import annotations

from functools import cache

from .data_tables import load_table
from .errors import ColorimetryError
from .registry import Registry
from .spectrum import Spectrum

#: The shipped observers: canonical name → data file, with their aliases and descriptions.
OBSERVERS = Registry("observer", "a shipped observer")
OBSERVERS.add(
    "CIE 1931 2°", "cmf_cie1931_2deg.csv", "CIE 1931 standard colorimetric observer, 2° field (CIE 015 Table 1)",
    aliases=("cie 1931 2", "cie1931", "1931", "2", "2deg", "2°"),
)
OBSERVERS.add(
    "CIE 1964 10°", "cmf_cie1964_10deg.csv", "CIE 1964 supplementary observer, 10° field (CIE 015 Table 2)",
    aliases=("cie 1964 10", "cie1964", "1964", "10", "10deg", "10°"),
)
OBSERVERS.add(
    "CIE 2015 2°", "cmf_cie2015_2deg.csv", "CIE 170-2:2015 cone-fundamental-based XYZ functions, 2°",
    aliases=("cie 2015 2", "2015-2", "2015 2deg", "2015-2deg"),
)
OBSERVERS.add(
    "CIE 2015 10°", "cmf_cie2015_10deg.csv", "CIE 170-2:2015 cone-fundamental-based XYZ functions, 10°",
    aliases=("cie 2015 10", "2015-10", "2015 10deg", "2015-10deg"),
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


def canonical_observer_name(name: str) -> str:
    """Canonical name for an observer name or alias (``"1931"``, ``"10deg"``, …), or raise.

    The one observer resolver: every function, the command line and the app pass observer
    names through it.

    Parameters
    ----------
    name : str
        A canonical name or an alias of :data:`OBSERVERS`, in any case; spaces, underscores and
        "degree" for "deg" are tolerated.

    Returns
    -------
    str
        The canonical name, e.g. ``"CIE 1964 10°"``.

    Raises
    ------
    ColorimetryError
        For a non-string or an unknown observer, listing the observers.

    Examples
    --------
    >>> canonical_observer_name("10 degree"), canonical_observer_name("2015-10")
    ('CIE 1964 10°', 'CIE 2015 10°')
    """
    if not isinstance(name, str):
        raise ColorimetryError(f"observer: expected a name such as '1931' or '1964', got {name!r}")
    key = " ".join(name.strip().lower().replace("_", " ").replace("degree", "deg").split())
    for candidate in (name, key, key.replace(" ", "")):
        if candidate in OBSERVERS:
            return OBSERVERS.canonical(candidate)
    return OBSERVERS.canonical(name)  # raises, listing the observers


@cache
def _observer(canonical: str) -> Spectrum:
    header, table = load_table(OBSERVERS.get(canonical))
    return Spectrum(table[:, 0], table[:, 1:].T.copy(), header[1:])


def observer(name: str = "1931") -> Spectrum:
    """Colour-matching functions of a CIE standard observer.

    Parameters
    ----------
    name : str, default "1931"
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
    result = _observer(canonical_observer_name(name))
    result.values.setflags(write=False)
    return result
