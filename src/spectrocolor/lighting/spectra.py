"""Light spectra for the lighting metrics: checked grids, and the sample reflectances on them.

Every metric of :mod:`spectrocolor.lighting` takes a :class:`~spectrocolor.Spectrum` of
spectral power distributions ``(..., K)`` (any scale: W·nm⁻¹, W·m⁻²·nm⁻¹ or relative) and
sums at the spectrum's own samples. This module checks the grid once, in one place, and gives
the sample reflectances (CIE 13.3 test colour samples, CIE 224 colour evaluation samples) on it.

References
----------
CIE 13.3-1995 *Method of measuring and specifying colour rendering properties of light
sources* (test colour samples TCS01–TCS14, 5 nm). CIE 224:2017 *CIE 2017 colour fidelity
index for accurate scientific use* (99 colour evaluation samples, 1 nm, 380–780 nm).
CIE 167:2005 (Sprague interpolation of uniformly spaced data).
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache

import numpy as np

from ..data_tables import load_table
from ..errors import SpectrumError
from ..interpolation import interpolation_matrix
from ..registry import Registry
from ..sampling import cmfs_on, interval_weights_nm
from ..spectrum import Spectrum, wavelength_grid
from ..temperature import CCT, cct

#: Sampling intervals (nm) the metrics accept: those of CIE 224:2017 §3 and of measured data.
INTERVALS_NM = (1.0, 5.0)
#: Lights computed together: bounds the temporaries (99 samples × 3 × CHUNK) to a few MB.
CHUNK = 2048

#: How a refused grid interval is to be fixed, said from Python (the command line says its own).
RESAMPLE_HINT = "resample it, e.g. spd.resample(wavelength_grid({start:g}, {stop:g}, 1), 'sprague')"
#: The hint for irregular samples (spectrometer pixels), where Sprague interpolation does not apply.
_IRREGULAR_HINT = ("resample it, e.g. spd.resample(wavelength_grid({start:g}, {stop:g}, 1), 'linear') (Sprague "
                   "needs uniform samples), or read the file with read_spectra(..., resample_nm=1)")


@dataclass(frozen=True)
class MetricRange:
    """The samples one family of lighting metrics needs.

    Attributes
    ----------
    label : str
        The metric, for messages.
    start_nm, stop_nm : float
        The range the spectrum must cover, nm (the metrics never extrapolate).
    intervals_nm : tuple of float or None
        The sampling intervals accepted (``None``: any grid, summed with its own Δλ).
    restrict : bool
        Whether only the samples in ``[start_nm, stop_nm]`` are used (else the spectrum's own range).
    """

    label: str
    start_nm: float
    stop_nm: float
    intervals_nm: tuple | None
    restrict: bool


#: Lighting metrics and the samples each needs (name → :class:`MetricRange`). Outside 380–780 nm
#: V(λ) is below 4 × 10⁻⁵ of its peak and the CIE S 026 action spectra are not tabulated.
METRICS = Registry("metric", "a lighting metric", SpectrumError)
METRICS.add("cri", MetricRange("CIE 13.3 colour rendering", 380.0, 780.0, INTERVALS_NM, True),
            "CIE 13.3 Ra, R1–R14: 1 or 5 nm, 380 (or from 360) to 780 nm")
METRICS.add("fidelity", MetricRange("CIE 224 / TM-30 fidelity", 380.0, 780.0, INTERVALS_NM, True),
            "CIE 224 / TM-30 Rf, Rg: 1 or 5 nm, 380–780 nm")
METRICS.add("photometry", MetricRange("photometry", 380.0, 780.0, None, False),
            "luminous quantities and LER: any grid covering 380–780 nm, summed over its own range")
METRICS.add("alpha-opic", MetricRange("CIE S 026 α-opic quantities", 380.0, 780.0, None, False),
            "CIE S 026 α-opic quantities: any grid covering 380–780 nm, summed over its own range")


@dataclass(frozen=True)
class CheckedLights:
    """Lights checked for one metric (``checked_lights``).

    Attributes
    ----------
    grid : ndarray (K,)
        The samples the metric uses, nm.
    values : ndarray (N, K)
        The lights there (flattened batch); refused lights are 0, so that computing on them is
        harmless; their results are to be replaced by NaN.
    reasons : ndarray of str (N,)
        Why each light is refused, ``""`` for lights the metric computes.
    batch_shape : tuple
        The lights' batch shape (``()`` for one light).
    """

    grid: np.ndarray
    values: np.ndarray
    reasons: np.ndarray
    batch_shape: tuple

    @property
    def ok(self) -> np.ndarray:
        """Lights the metric computes, (N,) bool."""
        return self.reasons == ""

    def refuse(self, result: np.ndarray) -> np.ndarray:
        """``result`` (N, ...) with NaN in the rows of refused lights (a float copy)."""
        out = np.array(result, dtype=float)
        out[~self.ok] = np.nan
        return out

    def reasons_shaped(self) -> np.ndarray:
        """:attr:`reasons` with the batch shape."""
        return self.reasons.reshape(self.batch_shape)


def _span(grid: np.ndarray) -> str:
    return f"{grid[0]:g}–{grid[-1]:g} nm"


def checked_lights(spd, metric: str, argument: str = "spd", *, start_nm: float | None = None,
                   resample_hint: str = RESAMPLE_HINT) -> CheckedLights:
    """Check lights for a lighting metric; refuse the ones it cannot honestly compute.

    The grid is checked once (a :class:`Spectrum`; for the colour metrics a uniform 1 or 5 nm
    grid, else a :class:`SpectrumError` whose hint is ``resample_hint``). Then each light is
    refused, with a reason, when

    * the spectrum does not cover the metric's range (``measured over 400–700 nm; …``), or the
      light's values are not finite (NaN or infinite: a light measured over less than the
      others, padded with NaN, is reported with the range it was measured over);
    * it has no power (every sample 0);
    * its power is negative: ``Σ S Δλ ≤ 0`` over the samples used (an all-negative light, or
      one whose negative part outweighs the positive; isolated negative samples of measurement
      noise or interpolation overshoot are kept).

    A single light (``spd.batch_shape == ()``) that is refused raises a
    :class:`SpectrumError` naming the reason; in a batch the light's results are NaN and its
    reason is returned.

    Parameters
    ----------
    spd : Spectrum
        Spectral power distributions ``(..., K)``.
    metric : str
        A name of :data:`METRICS`: ``"cri"``, ``"fidelity"``, ``"photometry"``, ``"alpha-opic"``.
    argument : str, default "spd"
        The caller's argument name, for messages.
    start_nm : float, optional
        Override of the metric's start (CIE 13.3 starts at 360 nm where the data do).
    resample_hint : str, default :data:`RESAMPLE_HINT`
        How to fix a refused interval, formatted with ``start`` and ``stop``; the command line
        passes its own option.

    Returns
    -------
    CheckedLights
        The grid, the lights (N, K) and a reason per light (``""`` where computed).

    Raises
    ------
    SpectrumError
        For a non-Spectrum, a refused interval, or a single refused light.

    Examples
    --------
    >>> from spectrocolor import illuminant
    >>> fl2 = illuminant("FL2")
    >>> lights = Spectrum(fl2.wavelengths_nm, np.stack([fl2.values, -fl2.values, 0 * fl2.values]))
    >>> [str(r).split(":")[0] for r in checked_lights(lights, "photometry").reasons]
    ['', 'negative power', 'no power']
    """
    need = METRICS.get(metric)
    if not isinstance(spd, Spectrum):
        raise SpectrumError(
            f"{argument}: expected a spectrocolor.Spectrum of spectral power distributions, got "
            f"{type(spd).__name__}; wrap arrays as Spectrum(wavelengths_nm, values)"
        )
    start = need.start_nm if start_nm is None else float(start_nm)
    stop = need.stop_nm
    grid = spd.wavelengths_nm
    step = spd.interval_nm
    if need.intervals_nm is not None and (
            step is None or not any(np.isclose(step, s, rtol=0, atol=1e-9) for s in need.intervals_nm)):
        spacing = "an irregular grid" if step is None else f"{step:g} nm steps"
        raise SpectrumError(
            f"{argument}: {need.label} needs a uniform "
            f"{' or '.join(f'{s:g} nm' for s in need.intervals_nm)} grid, got {spacing}; "
            + (resample_hint if step is not None or resample_hint != RESAMPLE_HINT else _IRREGULAR_HINT)
            .format(start=start, stop=stop))
    values = np.asarray(spd.values, dtype=np.float64)
    shape = spd.batch_shape
    values = values.reshape(-1, values.shape[-1])
    n = len(values)
    inside = (grid >= start - 1e-9) & (grid <= stop + 1e-9)
    covered = grid[0] <= start + 1e-9 and grid[-1] >= stop - 1e-9 and (
        not need.restrict or (inside.any() and np.isclose(grid[inside][0], start)
                              and np.isclose(grid[inside][-1], stop)))
    if not covered:
        where = f"sampled {_span(grid)} at {step:g} nm" if step is not None else f"measured over {_span(grid)}"
        reason = (f"measured over less than the range: {where}; {need.label} takes samples from "
                  f"{start:g} to {stop:g} nm (the metrics never extrapolate)")
        reasons = np.full(n, reason, dtype=object)
        used = wavelength_grid(380.0, 780.0, 5.0)  # every result is NaN: any grid the metrics take
        result = CheckedLights(used, np.zeros((n, used.size)), reasons.astype(str), shape)
        _raise_single(result, argument)
        return result
    if need.restrict:
        grid, values = grid[inside], values[:, inside]
    grid = grid.copy()
    reasons = np.full(n, "", dtype=object)
    finite = np.isfinite(values)
    for i in np.flatnonzero(~finite.all(axis=1)):
        good = np.flatnonzero(finite[i])
        if good.size and np.all(finite[i, good[0]:good[-1] + 1]):
            reasons[i] = (f"measured over less than the range: values only over {_span(grid[good])} (not "
                          f"finite elsewhere); {need.label} takes {_span(grid)}")
        else:
            bad = np.flatnonzero(~finite[i])
            reasons[i] = f"not finite: {bad.size} NaN or infinite value(s), the first at {grid[bad[0]]:g} nm"
    clean = np.where(finite, values, 0.0)
    total = clean @ interval_weights_nm(grid)
    zero = np.all(clean == 0.0, axis=1) & (reasons == "")
    reasons[zero] = f"no power: every sample from {grid[0]:g} to {grid[-1]:g} nm is 0"
    negative = (total <= 0) & (reasons == "")
    for i in np.flatnonzero(negative):
        k = int(np.argmin(clean[i]))
        reasons[i] = (f"negative power: Σ S Δλ = {total[i]:.4g} over {_span(grid)} (most negative sample "
                      f"{clean[i, k]:.4g} at {grid[k]:g} nm)")
    reasons = reasons.astype(str)
    clean[reasons != ""] = 0.0
    result = CheckedLights(grid, clean, reasons, shape)
    _raise_single(result, argument)
    return result


def _raise_single(checked: CheckedLights, argument: str) -> None:
    if checked.batch_shape == () and checked.reasons[0]:
        raise SpectrumError(f"{argument}: {checked.reasons[0]}")


def light_refusals(spd, metric: str) -> np.ndarray:
    """Why a lighting metric returns NaN for each light of a batch (``""`` where it computes).

    The input checks of ``checked_lights`` (range, finite values, zero and negative
    power); the metrics' own undefined results (no CCT, no reference illuminant) are reported in
    their result records.

    Parameters
    ----------
    spd : Spectrum
        Spectral power distributions ``(..., K)``.
    metric : str
        ``"cri"``, ``"fidelity"``, ``"photometry"`` (luminous quantities, LER) or ``"alpha-opic"``.

    Returns
    -------
    numpy.ndarray of str, shape ``spd.batch_shape``
        One reason per light.

    Raises
    ------
    SpectrumError
        As ``checked_lights`` (a refused grid; a single refused light).

    Examples
    --------
    >>> from spectrocolor import illuminant
    >>> fl2 = illuminant("FL2")
    >>> light_refusals(Spectrum(fl2.wavelengths_nm, np.stack([fl2.values, -fl2.values])), "photometry")[1][:14]
    'negative power'
    """
    return checked_lights(spd, metric).reasons_shaped()


def light_grid(spd, start_nm: float, stop_nm: float, argument: str = "spd") -> tuple[np.ndarray, np.ndarray]:
    """Grid and values ``(N, K)`` of the samples of ``spd`` in ``[start_nm, stop_nm]``.

    Each light is divided by its largest absolute value (the colour metrics are scale-free;
    this keeps tiny or huge radiometric units away from underflow and overflow).

    ``spd`` must be a :class:`Spectrum` with a uniform 1 or 5 nm grid containing ``start_nm``
    and ``stop_nm`` (so no interpolation or extrapolation happens), with finite values.
    The values are flattened to ``(N, K)``; the caller restores ``spd.batch_shape``.

    Parameters
    ----------
    spd : Spectrum
        Spectral power distributions ``(..., K)``.
    start_nm, stop_nm : float
        The range the metric needs, nm (both must be samples of the grid).
    argument : str, default "spd"
        The caller's argument name, for error messages.

    Returns
    -------
    grid : numpy.ndarray, shape (K,)
        The samples in ``[start_nm, stop_nm]``, nm.
    values : numpy.ndarray, shape (N, K)
        The lights there, each divided by its largest absolute value.

    Raises
    ------
    SpectrumError
        For a non-Spectrum, an interval other than 1 or 5 nm, a grid missing ``start_nm`` or
        ``stop_nm``, or non-finite values.

    Examples
    --------
    >>> from spectrocolor import Spectrum, wavelength_grid
    >>> grid, values = light_grid(Spectrum.constant(1.0, wavelength_grid(360, 830, 5)), 380, 780)
    >>> grid[[0, -1]].tolist(), values.shape
    ([380.0, 780.0], (1, 81))
    """
    if not isinstance(spd, Spectrum):
        raise SpectrumError(
            f"{argument}: expected a spectrocolor.Spectrum of spectral power distributions, got "
            f"{type(spd).__name__}; wrap arrays as Spectrum(wavelengths_nm, values)"
        )
    step = spd.interval_nm
    grid = spd.wavelengths_nm
    if step is None or not any(np.isclose(step, s, rtol=0, atol=1e-9) for s in INTERVALS_NM):
        raise SpectrumError(
            f"{argument}: needs a uniform 1 nm or 5 nm grid, got "
            f"{'an irregular grid' if step is None else f'{step:g} nm steps'}; resample it, e.g. "
            f"spd.resample(wavelength_grid({start_nm:g}, {stop_nm:g}, 1), 'sprague')"
        )
    inside = (grid >= start_nm - 1e-9) & (grid <= stop_nm + 1e-9)
    if grid[0] > start_nm + 1e-9 or grid[-1] < stop_nm - 1e-9 or not np.isclose(grid[inside][0], start_nm):
        raise SpectrumError(
            f"{argument}: must have samples from {start_nm:g} to {stop_nm:g} nm, got "
            f"{grid[0]:g}–{grid[-1]:g} nm; the metrics never extrapolate"
        )
    values = np.asarray(spd.values, dtype=np.float64)[..., inside]
    if not np.all(np.isfinite(values)):
        raise SpectrumError(f"{argument}: values must be finite (no NaN or infinity)")
    values = values.reshape(-1, values.shape[-1])
    peak = np.abs(values).max(axis=1, keepdims=True)
    return grid[inside].copy(), values / np.where(peak > 0, peak, 1.0)


def light_cct(S: np.ndarray, wavelengths_nm: np.ndarray) -> CCT:
    """CCT (K) and Duv of lights ``S`` (N, K) on a uniform grid (CIE 1931 2°, exact projection).

    A light whose luminance Σ S ȳ Δλ is not positive has no colour: its CCT and Duv are NaN,
    and so is every metric computed from them.

    Parameters
    ----------
    S : numpy.ndarray, shape (N, K)
        Spectral power distributions (any scale).
    wavelengths_nm : numpy.ndarray, shape (K,)
        Their uniform grid, nm.

    Returns
    -------
    CCT
        ``cct_K`` and ``duv``, each of shape (N,).

    References
    ----------
    CIE 015:2018 §9.5; Y. Ohno, LEUKOS 10 (1), 47–55 (2014).

    Examples
    --------
    >>> from spectrocolor import illuminant
    >>> grid = np.arange(380.0, 781.0, 5.0)
    >>> round(float(light_cct(illuminant("D65", grid).values[None], grid).cct_K[0]), -1)
    6500.0
    """
    XYZ = S @ (cmfs_on(wavelengths_nm, "1931") * (wavelengths_nm[1] - wavelengths_nm[0]))
    result = cct(XYZ=XYZ)
    lit = XYZ[:, 1] > 0
    return CCT(np.where(lit, result.cct_K, np.nan), np.where(lit, result.duv, np.nan))


def in_chunks(compute, S: np.ndarray, *args) -> dict[str, np.ndarray]:
    """``compute(S_chunk, *args)`` (a dict of arrays with the chunk's lights first) over chunks
    of :data:`CHUNK` lights, concatenated: memory stays bounded for any number of lights.

    Parameters
    ----------
    compute : callable
        ``compute(S_chunk, *args) -> dict of str to numpy.ndarray``, each array with the
        chunk's lights on its first axis.
    S : numpy.ndarray, shape (N, K)
        The lights.
    *args : object
        Passed on to ``compute``.

    Returns
    -------
    dict of str to numpy.ndarray
        The chunks' arrays concatenated along the first axis.

    Examples
    --------
    >>> in_chunks(lambda rows: {"sum": rows.sum(axis=1)}, np.ones((5000, 3)))["sum"].shape
    (5000,)
    """
    parts = [compute(S[start:start + CHUNK], *args) for start in range(0, max(len(S), 1), CHUNK)]
    return {key: np.concatenate([part[key] for part in parts]) for key in parts[0]}


@lru_cache(maxsize=16)
def _tcs_on(grid_key: bytes) -> np.ndarray:
    grid = np.frombuffer(grid_key, dtype=float)
    header, table = load_table("reflectances_cie_tcs.csv")
    result = table[:, 1:].T @ interpolation_matrix(table[:, 0], grid, "sprague").T
    result.setflags(write=False)
    return result


def tcs_reflectances(wavelengths_nm) -> np.ndarray:
    """CIE 13.3 test colour samples TCS01–TCS14 at ``wavelengths_nm``, shape (14, K), 0–1.

    The 5 nm table is used as published at multiples of 5 nm and Sprague-interpolated
    (CIE 167) in between; ``wavelengths_nm`` must lie within 360–830 nm.

    Parameters
    ----------
    wavelengths_nm : array_like, shape (K,)
        The grid, nm, within 360–830 nm.

    Returns
    -------
    numpy.ndarray, shape (14, K)
        Reflectance factors 0–1.

    References
    ----------
    CIE 13.3-1995 (test colour samples); CIE 167:2005 (Sprague interpolation).

    Examples
    --------
    >>> tcs_reflectances([450.0, 451.0]).shape
    (14, 2)
    """
    grid = np.ascontiguousarray(wavelengths_nm, dtype=float)
    return _tcs_on(grid.tobytes())


@lru_cache(maxsize=16)
def _ces_on(grid_key: bytes) -> np.ndarray:
    grid = np.frombuffer(grid_key, dtype=float)
    header, table = load_table("lighting/ces_cie224_1nm.csv")
    rows = np.rint(grid - table[0, 0]).astype(int)
    if np.any(rows < 0) or np.any(rows >= len(table)) or not np.allclose(table[rows, 0], grid):
        raise SpectrumError(
            f"wavelengths_nm: the colour evaluation samples are tabulated at whole nanometres "
            f"380–780 nm, got {grid[0]:g}–{grid[-1]:g} nm"
        )
    result = np.ascontiguousarray(table[rows, 1:].T)
    result.setflags(write=False)
    return result


def ces_reflectances(wavelengths_nm) -> np.ndarray:
    """The 99 CIE 224:2017 / TM-30 colour evaluation samples at ``wavelengths_nm``, shape (99, K).

    Tabulated at 1 nm (380–780 nm); a 5 nm grid takes every fifth row, as the standard's
    5 nm table does.

    Parameters
    ----------
    wavelengths_nm : array_like, shape (K,)
        Whole nanometres within 380–780 nm.

    Returns
    -------
    numpy.ndarray, shape (99, K)
        Reflectance factors 0–1.

    References
    ----------
    CIE 224:2017 (colour evaluation samples); ANSI/IES TM-30-20.

    Examples
    --------
    >>> ces_reflectances([380.0, 385.0]).shape
    (99, 2)
    """
    grid = np.ascontiguousarray(wavelengths_nm, dtype=float)
    return _ces_on(grid.tobytes())
