"""Spectral bandpass correction of measured data: ASTM E308's Stearns & Stearns rule.

A spectrophotometer does not report the reflectance at λⱼ but its average over the instrument's
bandpass around λⱼ, which flattens peaks and fills valleys. ASTM E308 corrects for this with the
three-point rule of Stearns & Stearns (1988), derived for a **triangular bandpass whose full width
at half maximum equals the measurement interval** (α = 0.083 ≈ 1/12, the second moment of that
triangle in units of the interval squared):

* inside: ``R'ⱼ = −α Rⱼ₋₁ + (1 + 2α) Rⱼ − α Rⱼ₊₁``;
* at the first and last wavelength: ``R'₁ = (1 + α) R₁ − α R₂`` and ``R'ₙ = (1 + α) Rₙ − α Rₙ₋₁``.

Every ``R`` on the right is a *measured* value (the rule is one fixed linear map, the matrix of
:func:`stearns_stearns_matrix`). The matrix is symmetric and each of its rows and columns sums
to one, so a constant spectrum is unchanged and folding it into weights (E308 Table 6, see
:func:`spectrocolor.astm_e308.astm_e308_table6_weights`) keeps the white point.

**What "FWHM honoured" means here.** The rule is only valid for a bandpass equal to the interval.
:func:`bandpass_correction` therefore checks every bandpass it knows of — the ``bandpass_nm``
argument, a TM-27 file's ``BandwidthFWHM`` (``metadata["bandwidth_fwhm_nm"]``) or an ENVI-style
per-band ``metadata["fwhm_nm"]`` — against the data's interval and refuses (with the numbers) when
one differs by more than 5 %; a bandpass it cannot know is assumed equal to the interval and the
assumption is written into the result's metadata. Data a TM-27 file declares already corrected
(``BandwidthCorrected`` true) are refused. Nothing is ever corrected without being asked.

References
----------
Stearns, E. I. & Stearns, R. E. (1988). An example of a method for correcting radiance data for
bandpass error. *Color Research & Application* 13(4), 257–259.
ASTM E308-17, *Standard Practice for Computing the Colors of Objects by Using the CIE System*
(correction for spectral bandpass; Tables 5 and 6).
"""

from __future__ import annotations

import numpy as np

from .errors import SpectrumError
from .registry import Registry
from .spectrum import Spectrum

#: The Stearns & Stearns coefficient used by ASTM E308 (triangular bandpass = interval).
STEARNS_ALPHA = 0.083
#: Largest relative difference between a declared bandpass (FWHM) and the interval accepted.
BANDPASS_TOLERANCE = 0.05


def stearns_stearns_matrix(count: int, alpha: float = STEARNS_ALPHA) -> np.ndarray:
    """The (count, count) matrix ``B`` of the Stearns & Stearns rule: ``R_corrected = B @ R_measured``.

    Parameters
    ----------
    count : int
        Number of measured wavelengths (at least 2).
    alpha : float, default 0.083
        The coefficient; E308 uses 0.083.

    Returns
    -------
    numpy.ndarray, shape (count, count)
        Tridiagonal and symmetric; every row and column sums to 1.

    Raises
    ------
    SpectrumError
        For fewer than two wavelengths.

    References
    ----------
    Stearns & Stearns (1988); ASTM E308-17 (bandpass correction).

    Examples
    --------
    >>> stearns_stearns_matrix(3)
    array([[ 1.083, -0.083,  0.   ],
           [-0.083,  1.166, -0.083],
           [ 0.   , -0.083,  1.083]])
    """
    if count < 2:
        raise SpectrumError(f"spectrum: the bandpass correction needs at least two wavelengths, got {count}")
    matrix = np.diag(np.full(count, 1.0 + 2.0 * alpha))
    matrix[[0, -1], [0, -1]] = 1.0 + alpha
    neighbours = np.arange(count - 1)
    matrix[neighbours, neighbours + 1] = -alpha
    matrix[neighbours + 1, neighbours] = -alpha
    return matrix


def _declared_bandpasses(spectrum: Spectrum, bandpass_nm) -> list[tuple[str, np.ndarray]]:
    """(where, FWHM values in nm) for every bandpass the caller or the file declared."""
    found = []
    if bandpass_nm is not None:
        found.append(("bandpass_nm", bandpass_nm))
    for key in ("bandwidth_fwhm_nm", "fwhm_nm"):
        if key in spectrum.metadata:
            found.append((f"metadata['{key}']", spectrum.metadata[key]))
    checked = []
    for where, value in found:
        try:
            numbers = np.atleast_1d(np.asarray(value, dtype=float))
        except (TypeError, ValueError):
            raise SpectrumError(f"{where}: expected a bandpass (FWHM) in nm, got {value!r:.60}") from None
        if numbers.size == 0 or not np.all(np.isfinite(numbers) & (numbers > 0)):
            raise SpectrumError(f"{where}: expected positive finite bandpass values (FWHM) in nm, got {value!r:.60}")
        checked.append((where, numbers))
    return checked


def _stearns_stearns(spectrum: Spectrum, bandpass_nm) -> Spectrum:
    count = spectrum.wavelengths_nm.size
    if count < 2:
        raise SpectrumError(f"spectrum: the bandpass correction needs at least two wavelengths, got {count}")
    step = spectrum.interval_nm
    if step is None:
        raise SpectrumError(
            "spectrum: the Stearns & Stearns correction needs a uniform wavelength interval (it assumes a "
            "triangular bandpass equal to the interval); resample the data first"
        )
    declared = spectrum.metadata.get("bandwidth_corrected", ())  # TM-27: one value, or one per distribution
    declared = declared if isinstance(declared, (tuple, list)) else (declared,)
    if any(str(flag).strip().lower() in ("true", "1", "yes") for flag in declared):
        raise SpectrumError("spectrum: the file declares the data already bandwidth-corrected (BandwidthCorrected)")
    for where, fwhm in _declared_bandpasses(spectrum, bandpass_nm):
        worst = float(fwhm[np.argmax(np.abs(fwhm - step))])
        if abs(worst - step) > BANDPASS_TOLERANCE * step:
            raise SpectrumError(
                f"{where}: a bandpass (FWHM) of {worst:g} nm is not the data's {step:g} nm interval; the "
                f"Stearns & Stearns correction (ASTM E308) holds only for a triangular bandpass equal to the "
                f"interval (within {BANDPASS_TOLERANCE:.0%}), so the data are not corrected"
            )
    measured = spectrum.values
    infinite = np.isinf(measured).reshape(-1, count).any(axis=0)
    if infinite.any():
        where = spectrum.wavelengths_nm[infinite]
        raise SpectrumError(  # ∞ − ∞ in the correction would be NaN: no reading to correct
            f"spectrum: infinite values at {where[0]:g} nm{' and elsewhere' if where.size > 1 else ''}; "
            "the correction accepts finite readings, or NaN for a masked one"
        )
    finite = np.abs(measured[np.isfinite(measured)])
    if finite.size and finite.max() > np.finfo(float).max / (1.0 + 4.0 * STEARNS_ALPHA):
        raise SpectrumError(  # |corrected| ≤ (1 + 4α) max |measured|: beyond, float64 overflows
            f"spectrum: values up to {finite.max():.3g} would overflow float64 in the correction; "
            "scale the data first (the correction is linear)"
        )
    corrected = (1.0 + 2.0 * STEARNS_ALPHA) * measured  # the matrix's three diagonals, so a NaN (masked)
    corrected[..., 1:] -= STEARNS_ALPHA * measured[..., :-1]  # reading spoils only its two neighbours
    corrected[..., :-1] -= STEARNS_ALPHA * measured[..., 1:]
    corrected[..., [0, -1]] = (1.0 + STEARNS_ALPHA) * measured[..., [0, -1]] - STEARNS_ALPHA * measured[..., [1, -2]]
    metadata = dict(spectrum.metadata)
    metadata["bandpass_correction"] = (
        f"Stearns & Stearns (ASTM E308), alpha {STEARNS_ALPHA}, triangular bandpass = the {step:g} nm interval"
    )
    return Spectrum(spectrum.wavelengths_nm, corrected, spectrum.names, metadata)


#: Bandpass correction methods: name → function (spectrum, bandpass_nm) → corrected Spectrum.
BANDPASS_METHODS = Registry("method", "a bandpass correction method", SpectrumError)
BANDPASS_METHODS.add(
    "stearns-stearns",
    _stearns_stearns,
    "ASTM E308's three-point rule, triangular bandpass equal to the interval",
    aliases=("stearns 1988", "stearns1988"),
)


def bandpass_correction(spectrum: Spectrum, method: str = "stearns-stearns", *, bandpass_nm=None) -> Spectrum:
    """Correct measured spectra for the instrument's spectral bandpass (ASTM E308).

    Use it on data from an instrument whose bandpass equals its measurement interval (typically
    10 nm data from a 10 nm bandpass), then compute colour with ``method="astm-e308"`` (E308
    Table 5). Equivalently, leave the data as measured and use ``method="astm-e308-table6"``.

    Parameters
    ----------
    spectrum : Spectrum
        Measured reflectance or transmittance factors (any batch shape) on a uniform grid of at
        least two wavelengths.
    method : str, default "stearns-stearns"
        A name in :data:`BANDPASS_METHODS`; E308's Stearns & Stearns rule is the one provided.
    bandpass_nm : float or array_like, optional, keyword-only
        The instrument's bandpass (FWHM), nm, if known; checked against the interval like the
        bandpasses a file declares (see the module docstring).

    Returns
    -------
    Spectrum
        The corrected spectra on the same grid, with the names and metadata kept and
        ``metadata["bandpass_correction"]`` saying what was assumed.

    Raises
    ------
    SpectrumError
        For a spectrum that is not a Spectrum, an irregular grid, a single wavelength, a
        declared bandpass that differs from the interval by more than 5 %, data declared already
        corrected, or an unknown method.

    References
    ----------
    Stearns & Stearns (1988), *Color Res. Appl.* 13, 257–259; ASTM E308-17 (bandpass correction).

    Examples
    --------
    >>> from spectrocolor import Spectrum
    >>> measured = Spectrum([500, 510, 520, 530], [0.2, 0.4, 0.4, 0.2])
    >>> bandpass_correction(measured).values.round(4).tolist()
    [0.1834, 0.4166, 0.4166, 0.1834]
    """
    if not isinstance(spectrum, Spectrum):
        raise SpectrumError(f"spectrum: expected a Spectrum, got {type(spectrum).__name__}")
    return BANDPASS_METHODS.get(method)(spectrum, bandpass_nm)
