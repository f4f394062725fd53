"""Cone responses L, M, S: spectra weighted by the CIE 2006 cone fundamentals l̄, m̄, s̄.

The CIE 2006 physiological observer (CIE 170-1:2006; Stockman & Sharpe 2000) gives the spectral
sensitivities of the long-, medium- and short-wavelength cones, for a 2° and a 10° field, as
energy-based functions each with peak 1, tabulated at 1 nm from 390 to 830 nm. The CIE 2015 XYZ
functions (``observer("2015-2")``, ``observer("2015-10")``) are a fixed 3 × 3 transform of them
(CIE 170-2:2015), so L, M, S and X, Y, Z of the CIE 2015 observers describe the same match.

A cone response is the spectrum weighted by the cone's sensitivity and summed, as X, Y, Z are
with x̄, ȳ, z̄ (:mod:`spectrocolor.colorimetry`); :func:`cone_responses` scales the sums so a
teacher can read them (see its ``normalisation``). Wavelengths outside 390–830 nm contribute
nothing: the tables end there (at 390 nm l̄, m̄ are below 0.05 % of their peaks and s̄ is 1 %
(2°) or 0.6 % (10°) of its peak).

References
----------
CIE 170-1:2006 *Fundamental chromaticity diagram with physiological axes – Part 1*, Table 6.7
(the 2° and 10° cone fundamentals, energy-based).
CIE 170-2:2015 *Fundamental chromaticity diagram with physiological axes – Part 2*, eq. 8.4
and 8.5 (the transform to the XYZ functions).
Stockman, A. & Sharpe, L. T. (2000). The spectral sensitivities of the middle- and
long-wavelength-sensitive cones derived from measurements in observers of known genotype.
*Vision Research* 40, 1711–1737.
Colour & Vision Research Laboratory (CVRL), UCL, files ``linss2_10e_1`` and ``linss10e_1``
(http://www.cvrl.org/). Sources of the files: ``data/PROVENANCE.md``.
"""

from __future__ import annotations

from functools import cache, lru_cache

import numpy as np

from .colorimetry import apply_weights
from .data_tables import load_table
from .errors import ColorimetryError, SpectrumError
from .illuminants import resolve_illuminant
from .interpolation import resample_linear
from .observers import Observer, resolve_observer
from .sampling import illuminant_on, interval_weights_nm
from .spectrum import Spectrum, validate_wavelengths

#: The shipped cone fundamentals: field size (degrees) → data file (CIE 170-1:2006, CVRL).
CONE_TABLES = {2.0: "cone_cie2006_2deg.csv", 10.0: "cone_cie2006_10deg.csv"}

#: The accepted ``normalisation`` values of :func:`cone_responses`, with what they mean.
CONE_NORMALISATIONS = {
    "white": "reflectances under an illuminant: the perfect white has L = M = S = 100",
    "equal-energy": "lights: the sensitivity-weighted mean of the light; an equal-energy light of level c "
                    "has L = M = S = c",
    "peak": "lights: Σ S(λ) l̄(λ) Δλ with the tabulated peak-1 fundamentals (light's unit × nm)",
}


def _field(field) -> float:
    """The field size in degrees (2.0 or 10.0) of a ``field`` argument, or one clear error."""
    accepted = ("2 or 10 (degrees), '2°', '10°', '2deg', '10deg', or an observer name such as "
                "'2015-2' or '2015-10' (its field size is used)")
    if isinstance(field, bool):
        raise ColorimetryError(f"field: expected {accepted}; got {field!r}")
    if isinstance(field, int | float | np.integer | np.floating):
        if float(field) in CONE_TABLES:
            return float(field)
        raise ColorimetryError(f"field: the CIE 2006 cone fundamentals exist for 2° and 10° fields; got {field!r}")
    if isinstance(field, Observer) or isinstance(field, str):
        try:
            viewer = resolve_observer(field, "field")
        except ColorimetryError:
            raise ColorimetryError(f"field: expected {accepted}; got {field!r:.80}") from None
        if viewer.field_deg in CONE_TABLES:
            return float(viewer.field_deg)
    raise ColorimetryError(f"field: expected {accepted}; got {field!r:.80}")


@cache
def _fundamentals(field_deg: float) -> Spectrum:
    header, table = load_table(CONE_TABLES[field_deg])
    result = Spectrum(table[:, 0], table[:, 1:].T.copy(), header[1:])
    result.values.setflags(write=False)
    return result


def cone_fundamentals(field="2°") -> Spectrum:
    """The CIE 2006 cone fundamentals l̄, m̄, s̄ (energy-based, each with peak 1).

    Parameters
    ----------
    field : float, str or Observer, default "2°"
        Field size: ``2`` or ``10`` (degrees), ``"2°"``, ``"10°"``, ``"2deg"``, ``"10deg"``, or any
        name of a shipped :term:`observer` (``"2015-2"``, ``"CIE 2015 10°"``, …), whose field size
        is used.

    Returns
    -------
    Spectrum
        Values of shape ``(3, 441)``: l̄, m̄, s̄ at 1 nm from 390 to 830 nm, names
        ``("l_bar", "m_bar", "s_bar")``; relative spectral sensitivity per unit energy, peak 1
        (dimensionless). Read-only and shared between calls. s̄ is zero beyond 615 nm (as in the
        CIE table).

    Raises
    ------
    ColorimetryError
        For a field other than 2° or 10°, or an unknown name, naming ``field``.

    References
    ----------
    CIE 170-1:2006, Table 6.7; CVRL ``linss2_10e_1`` and ``linss10e_1`` (module docstring).

    Examples
    --------
    >>> lms = cone_fundamentals("2°")
    >>> lms.names, lms.values.shape
    (('l_bar', 'm_bar', 's_bar'), (3, 441))
    >>> lms.values[:, lms.wavelengths_nm == 570].ravel().tolist()
    [0.999993, 0.813509, 0.0002818]
    >>> cone_fundamentals(10).values.shape
    (3, 441)
    """
    return _fundamentals(_field(field))


def cone_weights(wavelengths_nm, *, field="2°") -> np.ndarray:
    """Weights ``l̄ Δλ, m̄ Δλ, s̄ Δλ`` (K, 3) on a grid: ``L, M, S = values @ W`` for lights.

    Parameters
    ----------
    wavelengths_nm : array_like, shape (K,)
        The summation grid, nm (a :term:`wavelength grid`), at least two samples; samples outside
        390–830 nm get weight 0 (the fundamentals are tabulated only there).
    field : float, str or Observer, keyword-only
        As in :func:`cone_fundamentals`.

    Returns
    -------
    numpy.ndarray
        (K, 3) float64, nm: the fundamentals interpolated linearly at the grid, times Δλ.

    Raises
    ------
    ColorimetryError
        For fewer than two samples or a bad ``field``; SpectrumError for a bad grid.

    Examples
    --------
    >>> W = cone_weights([560.0, 570.0, 580.0])
    >>> W.shape, round(float(W[1, 0]), 5)
    ((3, 3), 9.99993)
    """
    grid = validate_wavelengths(wavelengths_nm)
    if grid.size < 2:
        raise ColorimetryError(
            f"wavelengths_nm: summation needs at least two samples (Δλ is undefined for one), got {grid.tolist()}"
        )
    return np.array(_cone_weights(grid.tobytes(), _field(field)))


@lru_cache(maxsize=64)
def _cone_weights(grid_key: bytes, field_deg: float) -> np.ndarray:
    """:func:`cone_weights` on a validated grid, read-only and cached per (grid, field)."""
    grid = np.frombuffer(grid_key, dtype=float)
    lms = _fundamentals(field_deg)
    table_nm = lms.wavelengths_nm
    inside = (grid >= table_nm[0]) & (grid <= table_nm[-1])
    result = np.zeros((grid.size, 3))
    if inside.any():
        result[inside] = resample_linear(table_nm, lms.values, grid[inside]).T
    result *= interval_weights_nm(grid)[:, None]
    result.setflags(write=False)
    return result


def cone_responses(spectrum: Spectrum, *, illuminant=None, field="2°", normalisation: str | None = None) -> np.ndarray:
    """Cone responses L, M, S of spectra, shape ``(..., 3)``, beside X, Y, Z.

    Each response is the spectrum weighted by one cone fundamental and summed at the spectrum's own
    samples (``Σ ρ(λ) S(λ) l̄(λ) Δλ`` for a reflectance ρ under a light S, ``Σ S(λ) l̄(λ) Δλ`` for a
    light), then scaled by ``normalisation``.

    Parameters
    ----------
    spectrum : Spectrum
        Spectra ``(..., K)`` (a batch ``(N, K)`` gives ``(N, 3)``). With an illuminant:
        reflectance or transmittance factors (0–1); without: lights, in any unit.
    illuminant : None, str, float, Spectrum or Illuminant, keyword-only
        ``None`` (default): the spectra are lights. Otherwise the light the factors are seen under
        (a CIE name, ``"blackbody:T"``, a Spectrum, …; see :term:`illuminant`).
    field : float, str or Observer, keyword-only
        ``"2°"`` (default) or ``"10°"``; as in :func:`cone_fundamentals` (observer names such as
        ``"2015-10"`` are accepted for their field size; see :term:`observer`).
    normalisation : {None, "white", "equal-energy", "peak"}, keyword-only
        ``None`` (default) picks ``"white"`` with an illuminant and ``"equal-energy"`` without.

        ``"white"`` (reflectances only): ``L = 100 Σ ρ S l̄ Δλ / Σ S l̄ Δλ`` and likewise M, S, so the
        perfect white has L = M = S = 100 under any light; each response is the per cent of the
        white's excitation of that cone (a von Kries-style scale), dimensionless.

        ``"equal-energy"`` (lights only): ``L = Σ S l̄ Δλ / Σ l̄ Δλ``, the light's level averaged with
        the cone's sensitivity as the weights, in the light's own unit; a light equal to c at every
        wavelength has L = M = S = c (illuminant E, 100 everywhere, gives 100, 100, 100).

        ``"peak"`` (lights only): ``Σ S l̄ Δλ`` with the tabulated fundamentals (peak 1), in the
        light's unit × nm (CVRL's scale).

    Returns
    -------
    numpy.ndarray
        L, M, S, shape ``spectrum.batch_shape + (3,)``, float64 (float32 spectra are summed in
        float32). NaN in a spectrum gives NaN in its responses.

    Raises
    ------
    ColorimetryError
        For a non-Spectrum ``spectrum``, a bad ``field``, ``illuminant`` or ``normalisation`` (or one
        that does not fit lights / reflectances), a grid with fewer than two samples or none inside
        390–830 nm, or a light under which the white excites a cone not at all, naming the argument.

    References
    ----------
    CIE 170-1:2006 (the cone fundamentals); CIE 015:2018 §7.1 (summation, as for X, Y, Z); von
    Kries, J. (1905) for the scaling to the white. See the module docstring.

    Examples
    --------
    >>> from spectrocolor import Spectrum, wavelength_grid
    >>> grid = wavelength_grid(390, 780, 5)
    >>> white = Spectrum.constant(1.0, grid)
    >>> cone_responses(white, illuminant="D65").round(6).tolist()
    [100.0, 100.0, 100.0]
    >>> cone_responses(Spectrum.constant(100.0, grid)).round(6).tolist()  # an equal-energy light
    [100.0, 100.0, 100.0]
    >>> red = Spectrum(grid, (grid >= 600).astype(float))
    >>> L, M, S = cone_responses(red, illuminant="D65", field="10°")
    >>> bool(L > M > S)
    True
    """
    if not isinstance(spectrum, Spectrum):
        raise ColorimetryError(
            f"spectrum: expected a spectrocolor.Spectrum, got {type(spectrum).__name__}; "
            "wrap arrays as Spectrum(wavelengths_nm, values)"
        )
    light = resolve_illuminant(illuminant)
    if normalisation is None:
        normalisation = "equal-energy" if light is None else "white"
    if not isinstance(normalisation, str) or normalisation not in CONE_NORMALISATIONS:
        raise ColorimetryError(
            f"normalisation: expected None or one of {', '.join(map(repr, CONE_NORMALISATIONS))}; "
            f"got {normalisation!r:.80}"
        )
    if (normalisation == "white") != (light is not None):
        needs = "an illuminant (reflectances)" if normalisation == "white" else "illuminant=None (lights)"
        raise ColorimetryError(f"normalisation: {normalisation!r} needs {needs}; {CONE_NORMALISATIONS[normalisation]}")
    grid = spectrum.wavelengths_nm
    if grid.size < 2:
        raise ColorimetryError(
            f"wavelengths_nm: summation needs at least two samples (Δλ is undefined for one), got {grid.tolist()}"
        )
    W = _cone_weights(np.ascontiguousarray(grid, dtype=float).tobytes(), _field(field))
    if light is not None:
        try:
            W = W * illuminant_on(grid, light)[:, None]
        except SpectrumError as exc:
            raise ColorimetryError(f"illuminant: {exc}") from None
    if normalisation != "peak":
        reference = W.sum(axis=0)
        if not np.all(reference > 0):
            what = "the illuminant's white" if light is not None else "an equal-energy light"
            raise ColorimetryError(
                f"{'illuminant' if light is not None else 'spectrum'}: {what} excites the cones "
                f"(L, M, S sums {np.round(reference, 9).tolist()}) not at all over "
                f"{grid[0]:g}–{grid[-1]:g} nm; the fundamentals cover 390–830 nm (s̄ ends at 615 nm)"
            )
        W = W * ((100.0 if light is not None else 1.0) / reference)
    return apply_weights(spectrum.values, W)
