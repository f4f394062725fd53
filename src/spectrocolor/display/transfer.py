"""Transfer (excitation) functions between linear drive and encoded signal, and integer codes.

A *transfer* maps linear channel values ``rgb_linear`` (0 = black, 1 = the channel at full
drive) to encoded signal values ``rgb_encoded`` (0-1) and back. Three kinds exist:

* :class:`SRGBCurve` -- the piecewise sRGB curve of IEC 61966-2-1:1999 (also used by
  Display P3);
* :class:`PowerLaw` -- a pure power law ``encoded = linear ** (1/gamma)`` (gamma 2.2, SPECTRA's
  2.204, Adobe RGB (1998)'s 563/256);
* :class:`BT2020Curve` -- the ITU-R BT.2020 camera curve;
* :class:`LevelTable` -- a *measured* excitation function: the light emitted at each of N
  signal levels (SPECTRA's 64-level ``c.dat``). Encoding picks the nearest level, as SPECTRA's
  ``digit()`` routine does.

Encoding refuses values outside [0, 1]: bringing colours into range is the job of a gamut
strategy (:mod:`spectrocolor.display.gamut`), never a silent side effect of encoding.
NaN passes through as NaN (and encodes to no integer code: :func:`to_codes` refuses it).

References
----------
IEC 61966-2-1:1999, Multimedia systems and equipment -- Colour measurement and management --
Part 2-1: Default RGB colour space -- sRGB.
ITU-R Recommendation BT.2020-2 (2015), Parameter values for ultra-high definition television.
Adobe Systems (2005), Adobe RGB (1998) Color Image Encoding, version 2005-05.
P. Sällström (1999), A computer program for visualising the relation between colour and
spectral energy distribution, USIP Report 99-05, Appendix ("c.dat", gamma 2.204).

Why this file is long: the four transfer kinds, their registry and the integer coding form one
contract (encode, decode, refuse values outside [0, 1], NaN passes through); each kind is a small
class whose docstring carries its standard, and the coding functions are checked against every kind.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..arguments import real_array
from ..errors import ColorimetryError
from ..registry import Registry

__all__ = [
    "TransferCurve",
    "SRGBCurve",
    "PowerLaw",
    "BT2020Curve",
    "LevelTable",
    "Transfer",
    "transfer",
    "transfer_names",
    "spectra_excitation_table",
    "to_codes",
    "from_codes",
]


def _check_unit_range(values: np.ndarray, argument: str) -> np.ndarray:
    values = real_array(values, argument, "encoded values 0-1")
    bad = (values < 0.0) | (values > 1.0)
    if np.any(bad):
        raise ColorimetryError(
            f"{argument} must lie in [0, 1] (NaN allowed); got values from "
            f"{np.nanmin(values):.6g} to {np.nanmax(values):.6g}. Bring colours into the "
            "display's range with a gamut strategy before encoding."
        )
    return values


class TransferCurve:
    """What every transfer does: encode linear drive to a signal and decode it back.

    Both directions refuse values outside [0, 1] (bringing colours into range is a gamut
    strategy's job, never a side effect of encoding); NaN passes through as NaN, except in a
    :class:`LevelTable`, where NaN has no level and is refused. Each kind implements the two
    directions on checked arrays (``_encode``, ``_decode``); the checks and the documentation
    live here once.

    Examples
    --------
    >>> curve = SRGBCurve()
    >>> isinstance(curve, TransferCurve), curve.encode([0.0, 0.18, 1.0]).round(4).tolist()
    (True, [0.0, 0.4614, 1.0])
    >>> curve.encode([1.2])  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    spectrocolor.errors.ColorimetryError: rgb_linear must lie in [0, 1] (NaN allowed); got ...
    """

    __slots__ = ()

    def encode(self, rgb_linear) -> np.ndarray:
        """Linear 0-1 -> encoded 0-1.

        Parameters
        ----------
        rgb_linear : array_like
            Linear drive values (relative emission) in [0, 1].

        Returns
        -------
        numpy.ndarray
            Encoded signal values in [0, 1], same shape.

        Raises
        ------
        ColorimetryError
            For values outside [0, 1]: bring colours into gamut first (a gamut strategy).

        Examples
        --------
        >>> PowerLaw(2.2).encode([0.18]).round(4).tolist()
        [0.4587]
        """
        return self._encode(_check_unit_range(rgb_linear, "rgb_linear"))

    def decode(self, rgb_encoded) -> np.ndarray:
        """Encoded 0-1 -> linear 0-1.

        Parameters
        ----------
        rgb_encoded : array_like
            Encoded signal values in [0, 1].

        Returns
        -------
        numpy.ndarray
            Linear drive values (relative emission) in [0, 1], same shape.

        Raises
        ------
        ColorimetryError
            For values outside [0, 1].

        Examples
        --------
        >>> PowerLaw(2.2).decode([0.5]).round(4).tolist()
        [0.2176]
        """
        return self._decode(_check_unit_range(rgb_encoded, "rgb_encoded"))

    def _encode(self, x: np.ndarray) -> np.ndarray:
        raise NotImplementedError

    def _decode(self, v: np.ndarray) -> np.ndarray:
        raise NotImplementedError


@dataclass(frozen=True)
class SRGBCurve(TransferCurve):
    """The sRGB transfer function of IEC 61966-2-1:1999.

    ``encoded = 12.92 * linear`` for ``linear <= threshold``, else
    ``1.055 * linear ** (1/2.4) - 0.055``.

    Parameters
    ----------
    threshold : float
        Linear break point. The standard's value is 0.0031308 (encoded 0.04045). Zawischa
        (seed 000, eqs. 22-23) prints 0.00304, the value of the 1996 sRGB proposal; with it the
        two branches differ by 1e-5 at the break (0.039277 vs 0.039287), invisible at 8 bits
        but not continuous. Pass ``threshold=0.00304`` to reproduce the seed exactly.
    name : str, default "sRGB (IEC 61966-2-1)"
        Label shown in reports.

    References
    ----------
    IEC 61966-2-1:1999, §4.2 (the sRGB encoding); seed 000, eqs. 22–23.

    Examples
    --------
    >>> curve = SRGBCurve()
    >>> curve.encode([0.0, 0.18, 1.0]).round(4).tolist(), curve.decode([0.5]).round(4).tolist()
    ([0.0, 0.4614, 1.0], [0.214])
    >>> SRGBCurve(threshold=0.00304).encode([0.00304]).round(6).tolist()  # seed 000's break point
    [0.039277]
    """

    threshold: float = 0.0031308
    name: str = "sRGB (IEC 61966-2-1)"

    def _encode(self, x: np.ndarray) -> np.ndarray:
        with np.errstate(invalid="ignore"):
            power = 1.055 * np.power(np.maximum(x, self.threshold), 1 / 2.4) - 0.055
        return np.where(x <= self.threshold, 12.92 * x, power)

    def _decode(self, v: np.ndarray) -> np.ndarray:
        knee = 12.92 * self.threshold
        with np.errstate(invalid="ignore"):
            power = np.power((np.maximum(v, knee) + 0.055) / 1.055, 2.4)
        return np.where(v <= knee, v / 12.92, power)


@dataclass(frozen=True)
class PowerLaw(TransferCurve):
    """A pure power law: ``encoded = linear ** (1 / gamma)``, ``linear = encoded ** gamma``.

    Parameters
    ----------
    gamma : float
        Display exponent (> 0): 2.2 for a generic CRT (seed 000), 2.204 for SPECTRA's monitor
        (seed 002), 563/256 = 2.19921875 for Adobe RGB (1998).
    name : str, optional
        Label shown in reports; default ``"gamma <gamma>"``.

    Raises
    ------
    ColorimetryError
        For a gamma that is not positive and finite.

    Examples
    --------
    >>> curve = PowerLaw(2.2)
    >>> curve, curve.encode([0.18]).round(4).tolist(), curve.decode([0.5]).round(4).tolist()
    (PowerLaw(gamma=2.2, name='gamma 2.2'), [0.4587], [0.2176])
    """

    gamma: float
    name: str = ""

    def __post_init__(self):
        if not np.isfinite(self.gamma) or self.gamma <= 0:
            raise ColorimetryError(f"gamma: a power-law transfer needs a positive, finite "
                                   f"exponent, got {self.gamma!r}")
        if not self.name:
            object.__setattr__(self, "name", f"gamma {self.gamma:g}")

    def _encode(self, x: np.ndarray) -> np.ndarray:
        return np.power(x, 1.0 / self.gamma)

    def _decode(self, v: np.ndarray) -> np.ndarray:
        return np.power(v, self.gamma)



@dataclass(frozen=True)
class BT2020Curve(TransferCurve):
    """The ITU-R BT.2020 transfer curve (camera OETF; BT.709's shape with exact constants).

    ``encoded = 4.5 * linear`` below ``beta = 0.018053968510807``, else
    ``alpha * linear ** 0.45 - (alpha - 1)`` with ``alpha = 1.09929682680944``.

    Parameters
    ----------
    name : str, default "ITU-R BT.2020"
        Label shown in reports.
    alpha : float, default 1.09929682680944
        The curve's α.
    beta : float, default 0.018053968510807
        The linear break point β.

    References
    ----------
    ITU-R Recommendation BT.2020-2 (2015), Table 4.

    Examples
    --------
    >>> curve = BT2020Curve()
    >>> curve.encode([0.01, 0.18]).round(4).tolist(), curve.decode([0.5]).round(4).tolist()
    ([0.045, 0.4088], [0.2597])
    """

    name: str = "ITU-R BT.2020"
    alpha: float = 1.09929682680944
    beta: float = 0.018053968510807

    def _encode(self, x: np.ndarray) -> np.ndarray:
        with np.errstate(invalid="ignore"):
            power = self.alpha * np.power(np.maximum(x, self.beta), 0.45) - (self.alpha - 1)
        return np.where(x < self.beta, 4.5 * x, power)

    def _decode(self, v: np.ndarray) -> np.ndarray:
        knee = 4.5 * self.beta
        with np.errstate(invalid="ignore"):
            power = np.power((np.maximum(v, knee) + self.alpha - 1) / self.alpha, 1 / 0.45)
        return np.where(v < knee, v / 4.5, power)


@dataclass(frozen=True, eq=False)
class LevelTable(TransferCurve):
    """A measured excitation function: the relative emission at each of N signal levels.

    Parameters
    ----------
    levels : array_like, shape (N,)
        Emission at levels 0..N-1 as a fraction of full emission: strictly increasing, starting
        at 0 and ending at 1 (SPECTRA's ``c.dat``: 64 numbers, 0 at level 0, 1 at level 63).
    name : str, default "measured levels"
        Label shown in reports.

    Notes
    -----
    Encoding a linear value picks the level whose emission is nearest (SPECTRA's ``digit()``:
    "scans the list, finds the nearest value and returns the index"); ties go to the lower
    level. The encoded value is ``index / (N - 1)``; decoding returns the table's emission.

    Raises
    ------
    ColorimetryError
        For levels that are not a 1-D table of at least 2 values increasing strictly from 0 to 1.

    References
    ----------
    Seed 002 (Sällström 1999), Appendix: ``c.dat`` and ``digit()``.

    Examples
    --------
    >>> table = LevelTable([0.0, 0.2, 0.6, 1.0])
    >>> table.index([0.1, 0.35, 0.5]).tolist()  # nearest level; the tie at 0.1 goes down
    [0, 1, 2]
    >>> table.encode([0.35]).round(4).tolist(), table.decode([1 / 3]).tolist()
    ([0.3333], [0.2])
    """

    levels: np.ndarray
    name: str = "measured levels"

    def __post_init__(self):
        levels = np.array(self.levels, dtype=float)
        if levels.ndim != 1 or levels.size < 2:
            raise ColorimetryError(f"levels must be a 1-D table of >= 2 values, got {levels.shape}")
        if levels[0] != 0.0 or levels[-1] != 1.0 or np.any(np.diff(levels) <= 0):
            raise ColorimetryError(
                "levels must increase strictly from 0 (level 0) to 1 (the top level)"
            )
        levels.setflags(write=False)
        object.__setattr__(self, "levels", levels)

    @property
    def n_levels(self) -> int:
        """Number of signal levels N."""
        return int(self.levels.size)

    def index(self, rgb_linear) -> np.ndarray:
        """Nearest level index (0..N-1) for linear values in [0, 1]; NaN is refused.

        Parameters
        ----------
        rgb_linear : array_like
            Linear drive values (relative emission) in [0, 1].

        Returns
        -------
        numpy.ndarray of int
            Level indices, same shape (ties go to the lower level).

        Raises
        ------
        ColorimetryError
            For values outside [0, 1] or NaN.

        Examples
        --------
        >>> LevelTable([0.0, 0.2, 0.6, 1.0]).index([0.35, 1.0]).tolist()
        [1, 3]
        """
        return self._nearest(_check_unit_range(rgb_linear, "rgb_linear"))

    def _nearest(self, x: np.ndarray) -> np.ndarray:
        if np.any(np.isnan(x)):
            raise ColorimetryError("rgb_linear contains NaN, which has no signal level")
        upper = np.clip(np.searchsorted(self.levels, x, side="left"), 1, self.n_levels - 1)
        lower = upper - 1
        take_upper = (self.levels[upper] - x) < (x - self.levels[lower])
        return np.where(take_upper, upper, lower)

    def _encode(self, x: np.ndarray) -> np.ndarray:
        return self._nearest(x) / (self.n_levels - 1)

    def _decode(self, v: np.ndarray) -> np.ndarray:
        return self.levels[np.rint(v * (self.n_levels - 1)).astype(int)]



Transfer = SRGBCurve | PowerLaw | BT2020Curve | LevelTable


def spectra_excitation_table(gamma: float = 2.204, n_levels: int = 64) -> LevelTable:
    """SPECTRA's ``c.dat``: ``(level / (N-1)) ** gamma`` for N levels (seed 002, Appendix).

    With the defaults, 50 % excitation is nearest to level 46 of 63.

    Parameters
    ----------
    gamma : float, default 2.204
        Exponent of the excitation function (SPECTRA's fit to its monitor).
    n_levels : int, default 64
        Number of signal levels N (SPECTRA's 6-bit DAC: 64).

    Returns
    -------
    LevelTable
        Emission at each level as a fraction of full emission (0 at level 0, 1 at N - 1).

    Raises
    ------
    ColorimetryError
        For ``n_levels`` that is not an integer >= 2.

    References
    ----------
    Seed 002 (Sällström 1999), Appendix: ``c.dat`` and gamma 2.204.

    Examples
    --------
    >>> table = spectra_excitation_table()
    >>> table.n_levels, int(table.index(0.5)), round(float(table.levels[46]), 4)
    (64, 46, 0.5)
    """
    if int(n_levels) != n_levels or n_levels < 2:
        raise ColorimetryError(f"n_levels must be an integer >= 2, got {n_levels!r}")
    n = int(n_levels)
    levels = (np.arange(n) / (n - 1)) ** float(gamma)
    return LevelTable(levels, name=f"SPECTRA c.dat ({n} levels, gamma {gamma:g})")


#: The named transfer functions: name → transfer object.
TRANSFERS = Registry("transfer", "a transfer function (or give a gamma number or a transfer object)")
TRANSFERS.add("srgb", SRGBCurve(), "IEC 61966-2-1 sRGB curve (linear segment below 0.0031308)")
TRANSFERS.add(
    "srgb-1996", SRGBCurve(threshold=0.00304, name="sRGB, 1996 threshold 0.00304 (seed 000)"),
    "the 1996 sRGB draft's threshold 0.00304, as seed 000 prints it",
)
TRANSFERS.add("linear", PowerLaw(1.0, name="linear"), "no encoding: codes proportional to linear RGB")
TRANSFERS.add("gamma 2.2", PowerLaw(2.2), "pure power law, gamma 2.2")
TRANSFERS.add("gamma 2.204", PowerLaw(2.204), "pure power law, gamma 2.204 (SPECTRA's excitation fit)")
TRANSFERS.add("adobe rgb", PowerLaw(563 / 256, name="Adobe RGB (1998), gamma 563/256"), "gamma 563/256")
TRANSFERS.add("bt.2020", BT2020Curve(), "ITU-R BT.2020 opto-electronic curve")
TRANSFERS.add("spectra c.dat", spectra_excitation_table(), "SPECTRA's 64-level excitation table (seed 002)")


def transfer_names() -> tuple[str, ...]:
    """Names accepted by :func:`transfer` (the names of :data:`TRANSFERS`).

    Returns
    -------
    tuple of str
        The registered transfer names, in registration order.

    Examples
    --------
    >>> transfer_names()[:3]
    ('srgb', 'srgb-1996', 'linear')
    """
    return TRANSFERS.names()


def transfer(spec) -> Transfer:
    """A transfer object from a name (see :func:`transfer_names`), a gamma number, or itself.

    Parameters
    ----------
    spec : str, float or transfer object
        ``"srgb"``, ``"srgb-1996"``, ``"linear"``, ``"gamma 2.2"``, ``"gamma 2.204"``,
        ``"adobe rgb"``, ``"bt.2020"``, ``"spectra c.dat"``; a number is a power-law gamma.

    Returns
    -------
    SRGBCurve, PowerLaw, BT2020Curve or LevelTable
        An object with ``encode(rgb_linear)`` and ``decode(rgb_encoded)`` on 0–1 values; a
        transfer object is returned unchanged.

    Raises
    ------
    ColorimetryError
        For an unknown name.

    References
    ----------
    IEC 61966-2-1:1999; ITU-R BT.2020-2; Adobe RGB (1998); seed 002 (see the module docstring).

    Examples
    --------
    >>> transfer("srgb").encode([0.0, 0.0031308, 0.5, 1.0]).round(4).tolist()
    [0.0, 0.0404, 0.7354, 1.0]
    >>> transfer(2.2)
    PowerLaw(gamma=2.2, name='gamma 2.2')
    """
    if isinstance(spec, SRGBCurve | PowerLaw | BT2020Curve | LevelTable):
        return spec
    if isinstance(spec, int | float) and not isinstance(spec, bool):
        return PowerLaw(float(spec))
    return TRANSFERS.get(spec)


def _check_bit_depth(bit_depth) -> None:
    """Refuse anything but a whole number of bits 1-32 (NaN, inf, 8.5, "8", True)."""
    ok = isinstance(bit_depth, int | float | np.integer | np.floating) and not isinstance(
        bit_depth, bool | np.bool_)
    if not (ok and 1 <= bit_depth <= 32 and float(bit_depth).is_integer()):  # NaN fails 1 <= NaN
        raise ColorimetryError(f"bit_depth must be an integer from 1 to 32, got {bit_depth!r}")


def to_codes(rgb_encoded, bit_depth: int = 8) -> np.ndarray:
    """Encoded 0-1 values to integer codes ``round(encoded * (2**bit_depth - 1))``.

    Rounds half to even (NumPy's ``rint``). Zawischa's Fortran truncates with ``int()``; its
    text says "rounded to integer", which is what this does.

    Parameters
    ----------
    rgb_encoded : array_like, shape (...)
        Encoded values in [0, 1]; NaN is refused.
    bit_depth : int, default 8
        1 to 32 bits (6 for SPECTRA's 18-bit DAC, 8, 10, 12, 16).

    Returns
    -------
    ndarray of int64, shape (...)
        Codes 0 … 2**bit_depth - 1 (``rgb8`` for 8 bits).

    Raises
    ------
    ColorimetryError
        For a bit depth that is not an integer 1–32, values outside [0, 1], or NaN.

    Examples
    --------
    >>> to_codes([0.0, 0.5, 1.0]).tolist(), to_codes([0.5], bit_depth=16).tolist()
    ([0, 128, 255], [32768])
    """
    _check_bit_depth(bit_depth)
    v = _check_unit_range(rgb_encoded, "rgb_encoded")
    if np.any(np.isnan(v)):
        raise ColorimetryError("rgb_encoded contains NaN, which has no integer code")
    return np.rint(v * (2 ** int(bit_depth) - 1)).astype(np.int64)


def from_codes(codes, bit_depth: int = 8) -> np.ndarray:
    """Integer codes to encoded 0-1 values, ``codes / (2**bit_depth - 1)``.

    Parameters
    ----------
    codes : array_like of int, shape (...)
        Codes 0 … 2**bit_depth - 1.
    bit_depth : int, default 8
        1 to 32 bits.

    Returns
    -------
    numpy.ndarray of float, shape (...)
        Encoded values in [0, 1] (``rgb_encoded``); decode them with the space's transfer.

    Raises
    ------
    ColorimetryError
        For a bit depth that is not an integer 1–32, or codes outside the range.

    Examples
    --------
    >>> from_codes([0, 128, 255]).round(4).tolist()
    [0.0, 0.502, 1.0]
    """
    _check_bit_depth(bit_depth)
    codes = real_array(codes, "codes", "integer codes")
    top = 2 ** int(bit_depth) - 1
    if np.any(codes < 0) or np.any(codes > top):
        raise ColorimetryError(f"codes must lie in 0..{top} for bit_depth {bit_depth}")
    return codes / top
