"""The :class:`Spectrum` type: one wavelength grid, values of shape ``(..., K)``.

A ``Spectrum`` is one spectral distribution or a whole batch of them (a list of samples,
an image cube) sampled on a single strictly increasing wavelength grid in nanometres.
It never guesses: combining spectra on different grids is an error until one of them is
explicitly resampled, and resampling never extrapolates.

Why this file is long: it holds the central value type, :class:`Spectrum`, whose methods
(arithmetic, resampling, slicing, conversion to and from JSON and arrays) are its behaviour; a class
split across modules hides what it can do.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from numbers import Real
from types import MappingProxyType
from typing import Any

import numpy as np

from . import notebook_hooks
from .arguments import real_array, real_number
from .errors import SpectrumError
from .interpolation import METHODS, interpolation_matrix, resample_linear

ArrayLike = np.ndarray | Sequence[float] | float

#: Wavelengths below this (in nm) are taken as a sign that the data is in micrometres.
_SMALLEST_PLAUSIBLE_NM = 100.0

#: The most samples a generated grid may have (0.001 nm steps over 360-830 nm is 470 001).
_MAX_GRID_SAMPLES = 10_000_000


def _finite_number(name: str, value) -> float:
    """``value`` as a float, or a SpectrumError naming ``name`` if it is not a finite number."""
    try:
        number = float(value) if not isinstance(value, (str, bytes, bool)) and np.ndim(value) == 0 else None
    except (TypeError, ValueError):
        number = None
    if number is None or not np.isfinite(number):
        raise SpectrumError(f"{name}: expected a finite number, got {value!r:.80}")
    return number


def wavelength_grid(start_nm: float, stop_nm: float, step_nm: float) -> np.ndarray:
    """Uniform grid ``start_nm, start_nm + step_nm, …, stop_nm`` (both ends included), in nm.

    Parameters
    ----------
    start_nm : float
        First wavelength, nm.
    stop_nm : float
        Last wavelength, nm; must exceed ``start_nm``.
    step_nm : float
        Sampling interval, nm; positive, and it must divide ``stop_nm - start_nm`` into whole
        steps (to 1e-9 relative): the grid is never silently shortened.

    Returns
    -------
    numpy.ndarray
        Float64 wavelengths, shape ``(K,)`` with ``K = (stop_nm - start_nm) / step_nm + 1``, nm.

    Raises
    ------
    SpectrumError
        For a non-finite number, a step that is not positive or does not divide the range,
        ``stop_nm <= start_nm``, or more than 10 000 000 samples.

    Examples
    --------
    >>> grid = wavelength_grid(400, 700, 10)
    >>> grid.size, float(grid[0]), float(grid[-1])
    (31, 400.0, 700.0)
    """
    for name, value in (("start_nm", start_nm), ("stop_nm", stop_nm), ("step_nm", step_nm)):
        try:  # float() first: np.isfinite refuses Python ints beyond 64 bits
            finite = isinstance(value, Real) and not isinstance(value, bool) and np.isfinite(float(value))
        except OverflowError:
            finite = False
        if not finite:
            raise SpectrumError(f"{name}: expected a finite number of nanometres, got {value!r:.40}")
    # in float64: float16/float32 arithmetic would round the count and pass a step that does
    # not divide the range (np.float16(0.1) is 0.09998 nm)
    start_nm, stop_nm, step_nm = float(start_nm), float(stop_nm), float(step_nm)
    if step_nm <= 0:
        raise SpectrumError(f"step_nm: must be positive, got {step_nm!r}")
    if stop_nm <= start_nm:
        raise SpectrumError(f"stop_nm: must exceed start_nm ({start_nm!r}), got {stop_nm!r}")
    count = (stop_nm - start_nm) / step_nm
    if count + 1 > _MAX_GRID_SAMPLES:
        raise SpectrumError(
            f"start_nm, stop_nm, step_nm: {step_nm!r} nm over {start_nm!r}–{stop_nm!r} nm gives "
            f"{count + 1:.3g} samples; at most {_MAX_GRID_SAMPLES} are allowed"
        )
    if abs(count - round(count)) > 1e-9 * max(1.0, count):
        raise SpectrumError(f"start_nm, stop_nm, step_nm: {step_nm!r} does not divide "
                            f"{start_nm!r}–{stop_nm!r} nm into whole steps")
    return start_nm + step_nm * np.arange(round(count) + 1, dtype=float)


def validate_wavelengths(wavelengths_nm: ArrayLike, argument: str = "wavelengths_nm") -> np.ndarray:
    """Return a read-only float64 copy of a strictly increasing, finite grid in nm, or raise.

    Parameters
    ----------
    wavelengths_nm : array_like, shape (K,)
        Wavelengths, nm.
    argument : str, default "wavelengths_nm"
        The caller's argument name, used in error messages.

    Returns
    -------
    numpy.ndarray
        Read-only float64 copy, shape (K,).

    Raises
    ------
    SpectrumError
        For non-numbers, a shape other than (K,) with K >= 1, NaN or infinity, a grid that is
        not strictly increasing, non-positive values, or a largest value below 100 (which looks
        like micrometres).

    Examples
    --------
    >>> validate_wavelengths([400, 500]).tolist()
    [400.0, 500.0]
    >>> validate_wavelengths([0.4, 0.5])  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    spectrocolor.errors.SpectrumError: wavelengths_nm: largest wavelength is 0.5; that looks like micrometres, ...
    """
    try:
        grid = np.array(wavelengths_nm, dtype=float)
    except (TypeError, ValueError) as exc:
        raise SpectrumError(f"{argument}: expected numbers in nm ({exc})") from None
    if grid.ndim != 1 or grid.size < 1:
        raise SpectrumError(f"{argument}: expected a 1-D sequence of wavelengths, got shape {grid.shape}")
    if not np.all(np.isfinite(grid)):
        raise SpectrumError(f"{argument}: contains NaN or infinity")
    steps = np.diff(grid)
    if np.any(steps <= 0):
        bad = int(np.argmax(steps <= 0))
        kind = "duplicate" if steps[bad] == 0 else "decreasing"
        raise SpectrumError(
            f"{argument}: must be strictly increasing; {kind} wavelength at position {bad + 1} "
            f"({grid[bad]:g} then {grid[bad + 1]:g} nm)"
        )
    if grid[-1] < _SMALLEST_PLAUSIBLE_NM:
        raise SpectrumError(
            f"{argument}: largest wavelength is {grid[-1]:g}; that looks like micrometres, "
            "but spectrocolor expects nanometres (multiply by 1000)"
        )
    if grid[0] <= 0:
        raise SpectrumError(f"{argument}: wavelengths must be positive nm, got {grid[0]:g}")
    grid.setflags(write=False)
    return grid


def _as_values(values: ArrayLike, size: int) -> np.ndarray:
    try:
        array = np.asarray(values)
    except (TypeError, ValueError) as exc:
        raise SpectrumError(f"values: expected an array of numbers ({exc})") from None
    if array.dtype.kind in "biu":
        array = array.astype(float)
    if array.dtype.kind != "f":
        raise SpectrumError(f"values: expected real numbers, got dtype {array.dtype}")
    if array.ndim == 0 or array.shape[-1] != size:
        raise SpectrumError(f"values: last axis must have one entry per wavelength ({size}), got shape {array.shape}")
    return array


class Spectrum:
    """Spectral distribution(s) on one wavelength grid.

    Parameters
    ----------
    wavelengths_nm : array_like, shape (K,)
        Strictly increasing, finite, positive wavelengths in nanometres (a largest value below 100
        is refused as probably micrometres); see :term:`wavelength grid`.
    values : array_like, shape (..., K)
        A single spectrum ``(K,)``, a batch ``(N, K)`` or an image ``(H, W, K)``. Reflectances and
        transmittances are factors on the 0–1 scale; lights are in the units of the data. Float32
        values stay float32 (useful for large cubes); integers become float64.
    names : sequence of str, optional
        Optional names, one per spectrum of a ``(N, K)`` batch (or one for a single spectrum).
    metadata : mapping of str to object, optional
        Optional facts about where the data came from (file format, instrument, illuminant,
        geometry, date …) as a mapping with string keys; key ``"sample_fields"`` maps field names
        to one value per sample of a batch. Kept read-only, carried by :meth:`resample`,
        :meth:`restrict` and indexing (which selects the per-sample fields too), dropped by arithmetic.

    Raises
    ------
    SpectrumError
        For a grid that is not strictly increasing, finite and in nm, values whose last axis does
        not have one entry per wavelength or that are not real numbers, names of the wrong count,
        or metadata that is not a mapping with string keys.

    Notes
    -----
    Arithmetic (``+ - * /`` with a number, an array that broadcasts against ``values`` or a
    Spectrum on the same grid) returns a new Spectrum; spectra on different grids are never
    combined silently (resample one first), and division by zero raises instead of making inf.

    Examples
    --------
    >>> s = Spectrum([400, 500, 600], [0.1, 0.5, 0.9])
    >>> (1 - s).values
    array([0.9, 0.5, 0.1])
    """

    __slots__ = ("_wavelengths_nm", "_values", "_names", "_metadata")
    _repr_html_, _repr_svg_ = notebook_hooks.html, notebook_hooks.svg  # notebooks: spectrocolor.notebook

    def __init__(
        self,
        wavelengths_nm: ArrayLike,
        values: ArrayLike,
        names: Sequence[str] | None = None,
        metadata: Mapping[str, object] | None = None,
    ):
        self._wavelengths_nm = validate_wavelengths(wavelengths_nm)
        self._values = _as_values(values, self._wavelengths_nm.size)
        self._names = self._check_names(names)
        if metadata is not None and not (isinstance(metadata, Mapping) and all(isinstance(k, str) for k in metadata)):
            raise SpectrumError(f"metadata: expected a mapping with string keys, got {type(metadata).__name__}")
        self._metadata = MappingProxyType(dict(metadata or {}))

    def _check_names(self, names: Sequence[str] | None) -> tuple[str, ...] | None:
        if names is None:
            return None
        if isinstance(names, str):
            names = (names,)
        if not isinstance(names, Sequence) or not all(isinstance(n, str) for n in names):
            raise SpectrumError(f"names: expected a sequence of strings, got {names!r:.80}")
        names = tuple(names)
        expected = 1 if self._values.ndim == 1 else self._values.shape[0]
        if self._values.ndim > 2 or len(names) != expected:
            raise SpectrumError(
                f"names: expected {expected} name(s) for values of shape {self._values.shape}, got {len(names)}"
            )
        return names

    # ------------------------------------------------------------------ properties
    @property
    def wavelengths_nm(self) -> np.ndarray:
        """Wavelength grid, shape ``(K,)``, nm (read-only)."""
        return self._wavelengths_nm

    @property
    def values(self) -> np.ndarray:
        """Spectral values, shape ``(..., K)``."""
        return self._values

    @property
    def names(self) -> tuple[str, ...] | None:
        """Names of the spectra of a batch, or ``None``."""
        return self._names

    @property
    def metadata(self) -> Mapping[str, Any]:
        """Read-only facts about the data's origin (empty unless a reader or the caller set them)."""
        return self._metadata

    @property
    def batch_shape(self) -> tuple[int, ...]:
        """Leading shape ``values.shape[:-1]``: ``()`` for one spectrum."""
        return self._values.shape[:-1]

    @property
    def interval_nm(self) -> float | None:
        """The sampling interval in nm if the grid is uniform, else ``None``."""
        steps = np.diff(self._wavelengths_nm)
        if steps.size == 0 or not np.allclose(steps, steps[0], rtol=1e-9, atol=0):
            return None
        return float(steps[0])

    def __repr__(self) -> str:
        grid = self._wavelengths_nm
        step = self.interval_nm
        spacing = f"{step:g} nm" if step is not None else "irregular"
        named = f", names={list(self._names)[:4]}{'…' if len(self._names) > 4 else ''}" if self._names else ""
        return f"Spectrum({grid[0]:g}–{grid[-1]:g} nm, {spacing}, K={grid.size}, batch_shape={self.batch_shape}{named})"

    # ------------------------------------------------------------------ constructors
    @classmethod
    def constant(cls, value: float, wavelengths_nm: ArrayLike) -> Spectrum:
        """The same ``value`` at every wavelength (e.g. 1 for the perfect reflector).

        Parameters
        ----------
        value : float
            The value at every wavelength (a reflectance factor 0–1, or a light in its units).
        wavelengths_nm : array_like, shape (K,)
            The grid, nm.

        Returns
        -------
        Spectrum
            One spectrum, values shape ``(K,)``.

        Raises
        ------
        SpectrumError
            For a non-finite ``value`` or an invalid grid.

        Examples
        --------
        >>> Spectrum.constant(1.0, [400, 550, 700]).values.tolist()
        [1.0, 1.0, 1.0]
        """
        grid = validate_wavelengths(wavelengths_nm)
        return cls(grid, np.full(grid.size, _finite_number("value", value)))

    @classmethod
    def block(
        cls,
        start_nm: float,
        stop_nm: float,
        wavelengths_nm: ArrayLike,
        inside: float = 1.0,
        outside: float = 0.0,
    ) -> Spectrum:
        """Ideal (block) spectrum: ``inside`` for ``start_nm ≤ λ ≤ stop_nm``, ``outside`` elsewhere.

        ``start_nm > stop_nm`` gives the band-stop complement (``inside`` outside the gap), as for
        the purple optimal colours.

        Parameters
        ----------
        start_nm, stop_nm : float
            Band edges, nm (both included).
        wavelengths_nm : array_like, shape (K,)
            The grid, nm.
        inside : float, default 1.0
            Value inside the band (a reflectance factor 0–1 for optimal colours).
        outside : float, default 0.0
            Value outside the band.

        Returns
        -------
        Spectrum
            One spectrum, values shape ``(K,)``.

        Raises
        ------
        SpectrumError
            For a non-finite edge or value, or an invalid grid.

        Examples
        --------
        >>> Spectrum.block(450, 550, [400, 450, 500, 550, 600]).values.tolist()
        [0.0, 1.0, 1.0, 1.0, 0.0]
        >>> Spectrum.block(550, 450, [400, 450, 500, 550, 600]).values.tolist()  # band-stop
        [1.0, 1.0, 0.0, 1.0, 1.0]
        """
        grid = validate_wavelengths(wavelengths_nm)
        start_nm, stop_nm = _finite_number("start_nm", start_nm), _finite_number("stop_nm", stop_nm)
        inside, outside = _finite_number("inside", inside), _finite_number("outside", outside)
        if start_nm <= stop_nm:
            mask = (grid >= start_nm) & (grid <= stop_nm)
        else:
            mask = (grid >= start_nm) | (grid <= stop_nm)
        return cls(grid, np.where(mask, float(inside), float(outside)))

    @classmethod
    def gaussian(cls, peak_nm: float, fwhm_nm: float, wavelengths_nm: ArrayLike, peak: float = 1.0) -> Spectrum:
        """Gaussian band of full width at half maximum ``fwhm_nm`` centred on ``peak_nm``.

        Parameters
        ----------
        peak_nm : float
            Centre wavelength, nm.
        fwhm_nm : float
            Full width at half maximum, nm (positive).
        wavelengths_nm : array_like, shape (K,)
            The grid, nm.
        peak : float, default 1.0
            Value at ``peak_nm``.

        Returns
        -------
        Spectrum
            One spectrum, ``peak · exp(-(λ - peak_nm)² / 2σ²)`` with ``σ = fwhm_nm / (2√(2 ln 2))``.

        Raises
        ------
        SpectrumError
            For a non-finite number, a width that is not positive, or an invalid grid.

        Examples
        --------
        >>> Spectrum.gaussian(550, 20, [530, 540, 550, 560]).values.round(6).tolist()
        [0.0625, 0.5, 1.0, 0.5]
        """
        peak_nm, peak = _finite_number("peak_nm", peak_nm), _finite_number("peak", peak)
        if not _finite_number("fwhm_nm", fwhm_nm) > 0:
            raise SpectrumError(f"fwhm_nm: must be positive, got {fwhm_nm!r}")
        grid = validate_wavelengths(wavelengths_nm)
        sigma = fwhm_nm / (2.0 * np.sqrt(2.0 * np.log(2.0)))
        return cls(grid, peak * np.exp(-0.5 * ((grid - peak_nm) / sigma) ** 2))

    @classmethod
    def bins(
        cls, levels: ArrayLike, start_nm: float = 400.0, step_nm: float = 10.0, full_scale: float | None = None
    ) -> Spectrum:
        """Spectrum from bin levels at ``start_nm, start_nm + step_nm, …`` (bin centres, nm).

        SPECTRA's editor has 31 bins of 10 nm at 400–700 nm with integer levels 0–30; pass
        ``full_scale=30`` to get values on the 0–1 scale (seed 002).

        Parameters
        ----------
        levels : array_like, shape (..., N)
            Bin levels, one per bin along the last axis (a batch of level sets is allowed).
        start_nm : float, default 400.0
            Centre of the first bin, nm.
        step_nm : float, default 10.0
            Bin width (the distance between centres), nm.
        full_scale : float, optional
            The level that means 1 (e.g. 30 for SPECTRA); default ``None`` keeps the levels as
            they are.

        Returns
        -------
        Spectrum
            Values ``levels / full_scale`` (or ``levels``) at the bin centres.

        Raises
        ------
        SpectrumError
            For levels that are not real numbers in a regular array (strings, complex, ragged),
            no levels, or a ``full_scale`` that is not positive.

        Examples
        --------
        >>> s = Spectrum.bins([0, 15, 30], start_nm=400, step_nm=10, full_scale=30)
        >>> s.wavelengths_nm.tolist(), s.values.tolist()
        ([400.0, 410.0, 420.0], [0.0, 0.5, 1.0])
        """
        level_array = real_array(levels, "levels", "bin levels (numbers)", SpectrumError)
        if level_array.ndim < 1 or level_array.shape[-1] < 1:
            raise SpectrumError(f"levels: expected at least one bin level, got shape {level_array.shape}")
        count = level_array.shape[-1]
        grid = start_nm + step_nm * np.arange(count, dtype=float)
        if full_scale is not None:
            full_scale = real_number(full_scale, "full_scale", "the level that means 1", SpectrumError,
                                     positive=True)
            level_array = level_array / full_scale
        return cls(grid, level_array)

    # ------------------------------------------------------------------ grid operations
    def resample(self, wavelengths_nm: ArrayLike, method: str = "linear") -> Spectrum:
        """Values on another grid inside this one's range (``"linear"``, ``"sprague"``, ``"cubic"``).

        Never extrapolates: a target outside ``wavelengths_nm``'s range raises ``SpectrumError``.

        Parameters
        ----------
        wavelengths_nm : array_like, shape (M,)
            The target grid, nm, within this spectrum's range.
        method : str, default "linear"
            ``"linear"``, ``"sprague"`` (CIE 167:2005 Sprague interpolation; at least 6 uniformly
            spaced source samples) or ``"cubic"`` (not-a-knot cubic spline, any spacing); see
            ``spectrocolor.interpolation``.

        Returns
        -------
        Spectrum
            Values of shape ``batch_shape + (M,)``, with the same names and metadata (``self`` when
            the grid is already the target).

        Raises
        ------
        SpectrumError
            For an unknown method, an invalid target grid or one that reaches outside this range.

        Examples
        --------
        >>> s = Spectrum([400, 500, 600], [0.0, 1.0, 0.0])
        >>> s.resample([450, 500, 550]).values.tolist()
        [0.5, 1.0, 0.5]
        """
        if not isinstance(method, str) or method not in METHODS:
            raise SpectrumError(f"method: {method!r:.40} is not a resampling method; choose one of {METHODS}")
        target = validate_wavelengths(wavelengths_nm)
        if target.shape == self._wavelengths_nm.shape and np.array_equal(target, self._wavelengths_nm):
            return self
        if method == "linear":  # banded: memory of the result only, for any grid size
            values = resample_linear(self._wavelengths_nm, self._values, target)
        else:
            matrix = interpolation_matrix(self._wavelengths_nm, target, method)
            values = self._values @ matrix.T.astype(self._values.dtype, copy=False)
        return Spectrum(target, values, self._names, self._metadata)

    def restrict(self, start_nm: float, stop_nm: float) -> Spectrum:
        """The samples with ``start_nm ≤ λ ≤ stop_nm`` (no interpolation).

        Parameters
        ----------
        start_nm, stop_nm : float
            The range kept, nm (both ends included, to 1e-9 nm).

        Returns
        -------
        Spectrum
            The samples inside the range, with the same names and metadata.

        Raises
        ------
        SpectrumError
            For a non-finite bound or a range that holds none of the samples.

        Examples
        --------
        >>> Spectrum([400, 500, 600, 700], [1, 2, 3, 4]).restrict(450, 700).values.tolist()
        [2.0, 3.0, 4.0]
        """
        grid = self._wavelengths_nm
        start_nm, stop_nm = _finite_number("start_nm", start_nm), _finite_number("stop_nm", stop_nm)
        keep = (grid >= start_nm - 1e-9) & (grid <= stop_nm + 1e-9)
        if not np.any(keep):
            raise SpectrumError(
                f"start_nm/stop_nm: {start_nm:g}–{stop_nm:g} nm holds none of this spectrum's samples "
                f"({grid[0]:g}–{grid[-1]:g} nm)"
            )
        return Spectrum(grid[keep], self._values[..., keep], self._names, self._metadata)

    def same_grid(self, other: Spectrum) -> bool:
        """True if ``other`` is sampled at exactly the same wavelengths.

        Parameters
        ----------
        other : Spectrum
            The spectrum to compare grids with.

        Returns
        -------
        bool
            Whether both grids have the same size and agree to 1e-9 nm.

        Examples
        --------
        >>> a = Spectrum([400, 500], [1, 1])
        >>> a.same_grid(Spectrum([400.0, 500.0], [0, 2])), a.same_grid(Spectrum([400, 510], [1, 1]))
        (True, False)
        """
        a, b = self._wavelengths_nm, other.wavelengths_nm
        return a.shape == b.shape and bool(np.allclose(a, b, rtol=0, atol=1e-9))

    def __getitem__(self, index) -> Spectrum:
        """Select spectra of a batch (the wavelength axis is always kept)."""
        if self._values.ndim == 1:
            raise SpectrumError("index: a single spectrum has no batch axis to index")
        values = self._values[index]
        names = None
        if self._names is not None and self._values.ndim == 2:
            picked = np.asarray(self._names, dtype=object)[index]
            names = tuple(np.atleast_1d(picked)) if values.ndim == 2 else (str(picked),)
        metadata: dict[str, Any] = dict(self._metadata)
        fields = metadata.pop("sample_fields", None)  # one entry per sample: select them too
        if fields and self._values.ndim == 2:
            metadata["sample_fields"] = {
                key: tuple(np.atleast_1d(np.asarray(column, dtype=object)[index])) for key, column in fields.items()
            }
        return Spectrum(self._wavelengths_nm, values, names, metadata)

    # ------------------------------------------------------------------ arithmetic
    def _operand(self, other, operation: str):
        if isinstance(other, Spectrum):
            if not self.same_grid(other):
                raise SpectrumError(
                    f"{operation}: spectra on different wavelength grids ({self!r} vs {other!r}); "
                    "resample one explicitly with .resample(other.wavelengths_nm)"
                )
            return other.values
        array = np.asarray(other)
        if array.dtype.kind not in "biuf":
            raise SpectrumError(f"{operation}: cannot combine a Spectrum with {type(other).__name__}")
        return array

    def _apply(self, other, operation: str, func, reflected: bool = False) -> Spectrum:
        operand = self._operand(other, operation)
        divisor = self._values if reflected else operand
        if func is np.true_divide and np.any(np.asarray(divisor) == 0):
            raise SpectrumError(
                f"{operation}: the divisor is zero somewhere; spectrocolor never makes inf or NaN silently"
            )
        try:
            result = func(operand, self._values) if reflected else func(self._values, operand)
        except ValueError:
            raise SpectrumError(
                f"{operation}: an array of shape {np.shape(operand)} does not broadcast against values "
                f"of shape {self._values.shape} (the last axis is wavelength, K = {self._wavelengths_nm.size})"
            ) from None
        names = self._names if np.shape(result) == self._values.shape else None
        return Spectrum(self._wavelengths_nm, result, names)

    def __add__(self, other):
        return self._apply(other, "addition", np.add)

    def __radd__(self, other):
        return self._apply(other, "addition", np.add, reflected=True)

    def __sub__(self, other):
        return self._apply(other, "subtraction", np.subtract)

    def __rsub__(self, other):
        return self._apply(other, "subtraction", np.subtract, reflected=True)

    def __mul__(self, other):
        return self._apply(other, "multiplication", np.multiply)

    def __rmul__(self, other):
        return self._apply(other, "multiplication", np.multiply, reflected=True)

    def __truediv__(self, other):
        return self._apply(other, "division", np.true_divide)

    def __neg__(self):
        return Spectrum(self._wavelengths_nm, -self._values, self._names)

    def __eq__(self, other) -> bool:
        return (
            isinstance(other, Spectrum)
            and self.same_grid(other)
            and self._values.shape == other.values.shape
            and bool(np.array_equal(self._values, other.values))
        )

    # mutable-looking array payload: not hashable (typeshed declares __hash__ a method, hence the ignore)
    __hash__ = None  # type: ignore[assignment]

    # ------------------------------------------------------------------ conversion
    def to_dict(self) -> dict:
        """JSON-ready dict ``{"wavelengths_nm": [...], "spectra": {name: [...]}}`` (1-D or 2-D only).

        Returns
        -------
        dict
            ``{"wavelengths_nm": list of float, "spectra": {name: list of float}}``; unnamed
            spectra are called ``spectrum_1``, ``spectrum_2``, …. Metadata is not included.

        Raises
        ------
        SpectrumError
            For values with more than two dimensions (an image cube).

        Examples
        --------
        >>> Spectrum([400, 500], [0.25, 0.5], names=["tile"]).to_dict()
        {'wavelengths_nm': [400.0, 500.0], 'spectra': {'tile': [0.25, 0.5]}}
        """
        if self._values.ndim > 2:
            raise SpectrumError(f"values: only single spectra or (N, K) batches go to JSON, got {self._values.shape}")
        rows = np.atleast_2d(self._values)
        names = self._names or tuple(f"spectrum_{i + 1}" for i in range(rows.shape[0]))
        return {
            "wavelengths_nm": self._wavelengths_nm.tolist(),
            "spectra": {name: row.tolist() for name, row in zip(names, rows, strict=True)},
        }

    @classmethod
    def from_dict(cls, data: dict) -> Spectrum:
        """Inverse of :meth:`to_dict`; also accepts ``{"wavelengths_nm", "values", "names"}``.

        Parameters
        ----------
        data : dict
            ``{"wavelengths_nm": [...], "spectra": {name: [...]}}`` (as written by :meth:`to_dict`)
            or ``{"wavelengths_nm": [...], "values": [...] or [[...], ...], "names": [...]}``;
            wavelengths in nm.

        Returns
        -------
        Spectrum
            One spectrum for a single entry, else an ``(N, K)`` batch with names.

        Raises
        ------
        SpectrumError
            For a missing key, non-numeric entries or rows of different lengths.

        Examples
        --------
        >>> s = Spectrum.from_dict({"wavelengths_nm": [400, 500], "spectra": {"a": [0, 1], "b": [1, 0]}})
        >>> s.names, s.values.tolist()
        (('a', 'b'), [[0.0, 1.0], [1.0, 0.0]])
        """
        if not isinstance(data, dict) or "wavelengths_nm" not in data:
            raise SpectrumError("JSON: expected an object with a 'wavelengths_nm' list")
        if "spectra" in data:
            spectra = data["spectra"]
            if not isinstance(spectra, dict) or not spectra:
                raise SpectrumError("JSON: 'spectra' must be a non-empty object of name → values")
            names = list(spectra)
            values = _json_numbers([spectra[n] for n in names], "spectra")
            if values.shape[0] == 1:
                return cls(data["wavelengths_nm"], values[0], names)
            return cls(data["wavelengths_nm"], values, names)
        if "values" in data:
            return cls(data["wavelengths_nm"], _json_numbers(data["values"], "values"), data.get("names"))
        raise SpectrumError("JSON: expected a 'spectra' object or a 'values' array")


def _json_numbers(data, argument: str) -> np.ndarray:
    """A JSON list (of equal-length lists) of numbers as a float array, or a SpectrumError."""
    try:
        return np.array(data, dtype=float)
    except (TypeError, ValueError):
        raise SpectrumError(
            f"JSON: {argument!r} must hold numbers: one list per spectrum, all of the same length"
        ) from None
