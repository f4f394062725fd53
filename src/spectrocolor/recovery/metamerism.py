"""Metamers: Cohen's fundamental metamer and metameric black, metamerism index, colour shifts.

For weights ``W`` (K, 3) of an observer under an illuminant (``XYZ100 = ρ @ W``), Cohen's
projector ``R = W (WᵀW)⁻¹ Wᵀ`` splits every reflectance into its *fundamental metamer*
``R ρ`` (the part that the observer sees, shared by all its metamers) and its *metameric
black* ``ρ − R ρ`` (invisible: ``(ρ − Rρ) @ W = 0``).

References
----------
J. B. Cohen, W. E. Kappauf, "Metameric color stimuli, fundamental metamers, and Wyszecki's
metameric blacks", Am. J. Psychol. 95, 537–564 (1982).
CIE 015:2018 *Colorimetry*, §8.2 (special metamerism index: change in illuminant).
C. van Trigt (1990), J. Opt. Soc. Am. A 7, 1891, Fig. 1 (colour shifts D65 → A).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..arguments import refuse_overflow
from ..colorimetry import weights
from ..coordinates import lab
from ..differences import delta_e_2000
from ..display.adaptation import adapt
from ..errors import ColorimetryError, SpectrumError
from ..illuminants import DEFAULT_ILLUMINANT, resolve_illuminant
from ..observers import DEFAULT_OBSERVER, resolve_observer
from ..spectrum import Spectrum

#: Why a result of finite reflectances is refused: their colours overflowed the float range.
_OVERFLOW = ("values this large overflow the colours' tristimulus values or CIELAB (reflectance "
             "factors are 0-1; values beyond about 1e300 cannot be weighted)")


def _reflectance(spectrum, argument: str) -> Spectrum:
    if not isinstance(spectrum, Spectrum):
        raise SpectrumError(f"{argument}: expected a Spectrum of reflectance factors, got {type(spectrum).__name__}")
    return spectrum


def cohen_projector(wavelengths_nm, *, illuminant=DEFAULT_ILLUMINANT, observer=DEFAULT_OBSERVER) -> np.ndarray:
    """Cohen's matrix ``R`` (K, K): the orthogonal projector onto the span of the weights.

    ``R = W (Wᵀ W)⁻¹ Wᵀ``: ``R ρ`` is the fundamental metamer of ρ, ``(I − R) ρ`` its
    metameric black.

    Parameters
    ----------
    wavelengths_nm : array_like, shape (K,)
        The grid, nm.
    illuminant : str or Spectrum, default "D65"
        The light under which the projector keeps the colours; see :term:`illuminant`.
    observer : str or Spectrum, default "1931"
        Observer name or alias.

    Returns
    -------
    numpy.ndarray, shape (K, K)
        Symmetric, idempotent, of rank 3.

    References
    ----------
    J. B. Cohen and W. E. Kappauf, Am. J. Psychol. 95, 537–564 (1982) (matrix R).

    Examples
    --------
    >>> import numpy as np
    >>> from spectrocolor import wavelength_grid
    >>> R = cohen_projector(wavelength_grid(400, 700, 10))
    >>> R.shape, round(float(np.trace(R)), 9), bool(np.allclose(R @ R, R))
    ((31, 31), 3.0, True)
    """
    W = np.asarray(weights(wavelengths_nm, observer=observer, illuminant=illuminant))
    return W @ np.linalg.solve(W.T @ W, W.T)


def fundamental_metamer(spectrum: Spectrum, *, illuminant=DEFAULT_ILLUMINANT, observer=DEFAULT_OBSERVER) -> Spectrum:
    """The fundamental metamer ``R ρ`` of reflectance(s) ``(..., K)``: same XYZ, no black.

    Parameters
    ----------
    spectrum : Spectrum
        Reflectance factors (0–1), ``(..., K)``.
    illuminant : str or Spectrum, default "D65"
        The light the sample's colour is taken under; see :term:`illuminant`.
    observer : str or Spectrum, default "1931"
        Observer name or alias.

    Returns
    -------
    Spectrum
        ``R ρ`` (may leave 0–1), same names.

    References
    ----------
    J. B. Cohen and W. E. Kappauf (1982); see :func:`cohen_projector`.

    Examples
    --------
    >>> from spectrocolor import Spectrum, tristimulus, wavelength_grid
    >>> sample = Spectrum.gaussian(550, 80, wavelength_grid(400, 700, 10), peak=0.8)
    >>> tristimulus(fundamental_metamer(sample), illuminant="D65").round(4).tolist()
    [29.3969, 50.8161, 5.5021]
    >>> tristimulus(sample, illuminant="D65").round(4).tolist()
    [29.3969, 50.8161, 5.5021]
    """
    s = _reflectance(spectrum, "spectrum")
    R = cohen_projector(s.wavelengths_nm, illuminant=illuminant, observer=observer)
    return Spectrum(s.wavelengths_nm, s.values @ R.T, s.names)


def metameric_black(spectrum: Spectrum, *, illuminant=DEFAULT_ILLUMINANT, observer=DEFAULT_OBSERVER) -> Spectrum:
    """The metameric black ``ρ − R ρ``: tristimulus values exactly zero (to rounding).

    Parameters
    ----------
    spectrum : Spectrum
        Reflectance factors (0–1), ``(..., K)``.
    illuminant : str or Spectrum, default "D65"
        The light under which the black has no colour; see :term:`illuminant`.
    observer : str or Spectrum, default "1931"
        Observer name or alias.

    Returns
    -------
    Spectrum
        ``ρ − R ρ``, same names; adds to the fundamental metamer to give ρ.

    References
    ----------
    J. B. Cohen and W. E. Kappauf (1982); see :func:`cohen_projector`.

    Examples
    --------
    >>> from spectrocolor import Spectrum, tristimulus, wavelength_grid
    >>> sample = Spectrum.gaussian(550, 80, wavelength_grid(400, 700, 10), peak=0.8)
    >>> bool(abs(tristimulus(metameric_black(sample), illuminant="D65")).max() < 1e-12)
    True
    """
    s = _reflectance(spectrum, "spectrum")
    R = cohen_projector(s.wavelengths_nm, illuminant=illuminant, observer=observer)
    return Spectrum(s.wavelengths_nm, s.values - s.values @ R.T, s.names)


#: The illuminant under which :func:`metamerism_index` measures the mismatch when none is given:
#: CIE illuminant A (CIE 015:2018, special metamerism index for a change in illuminant).
DEFAULT_TEST_ILLUMINANT = "A"


def metamerism_index(
    spectrum1: Spectrum,
    spectrum2: Spectrum,
    *,
    reference=DEFAULT_ILLUMINANT,
    test=DEFAULT_TEST_ILLUMINANT,
    observer=DEFAULT_OBSERVER,
) -> np.ndarray:
    """CIE special metamerism index for a change in illuminant, with CIEDE2000.

    ΔE00 between the two samples under the ``test`` illuminant (each in CIELAB relative to
    the test illuminant's white). The pair should match under ``reference``; if it does not,
    CIE 015 corrects the second sample multiplicatively in XYZ by the ratio of the
    reference-illuminant values, which is applied here.

    Parameters
    ----------
    spectrum1, spectrum2 : Spectrum
        Reflectance factors (0–1) on the same grid; broadcast against each other.
    reference : str, float, Spectrum or Illuminant, keyword-only
        The light under which the pair matches (default ``"D65"``); see :term:`illuminant`.
    test : str, float, Spectrum or Illuminant, keyword-only
        The light under which the mismatch is measured (default ``"A"``,
        :data:`DEFAULT_TEST_ILLUMINANT`); see :term:`illuminant`.
    observer : str, Spectrum or Observer, keyword-only
        Observer name or alias (default CIE 1931 2°), or colour-matching functions.

    Returns
    -------
    ndarray (...)
        ΔE00 under the test illuminant.

    Raises
    ------
    SpectrumError
        For input that is not a Spectrum, spectra on different grids or batches that do not
        broadcast.
    ColorimetryError
        For finite reflectances so large (near 1e308) that their colours overflow the float
        range (NaN in a spectrum gives NaN for its pair, as everywhere).

    References
    ----------
    CIE 015:2018 (special metamerism index: change in illuminant); CIE 142-2001 (ΔE00).

    Examples
    --------
    >>> from spectrocolor import Spectrum, wavelength_grid
    >>> sample = Spectrum.gaussian(550, 80, wavelength_grid(400, 700, 10), peak=0.8)
    >>> round(float(metamerism_index(sample, fundamental_metamer(sample))), 3)
    0.708
    """
    s1, s2 = _reflectance(spectrum1, "spectrum1"), _reflectance(spectrum2, "spectrum2")
    if not np.array_equal(s1.wavelengths_nm, s2.wavelengths_nm):
        raise SpectrumError("spectrum2: must share spectrum1's wavelength grid; resample it first")
    try:
        np.broadcast_shapes(s1.values.shape[:-1], s2.values.shape[:-1])
    except ValueError:
        raise SpectrumError(f"spectrum1, spectrum2: batches of shapes {s1.values.shape[:-1]} and "
                            f"{s2.values.shape[:-1]} do not broadcast; pass pairs in matching batches") from None
    grid = s1.wavelengths_nm
    observer = resolve_observer(observer)  # each argument resolved once, naming it in errors
    reference, test = resolve_illuminant(reference, "reference"), resolve_illuminant(test, "test")
    W_ref = np.asarray(weights(grid, observer=observer, illuminant=reference))
    W_test = np.asarray(weights(grid, observer=observer, illuminant=test))
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        ref1, ref2 = s1.values @ W_ref, s2.values @ W_ref
        correction = np.where(ref2 > 0, ref1 / ref2, 1.0)
        test1, test2 = s1.values @ W_test, s2.values @ W_test * correction
        white = W_test.sum(axis=0)
        lab1, lab2 = lab(test1, white), lab(test2, white)
    refuse_overflow(np.concatenate(np.broadcast_arrays(lab1, lab2), axis=-1), [s1.values, s2.values],
                    "spectrum1, spectrum2", _OVERFLOW)
    try:
        return delta_e_2000(lab1, lab2)
    except ColorimetryError as error:  # finite CIELAB that large still overflows CIEDE2000's C^7
        raise ColorimetryError(f"spectrum1, spectrum2: {_OVERFLOW} ({error})") from None


@dataclass(frozen=True)
class ColourShift:
    """CIELAB of samples under the source illuminant and, adapted, under the target.

    ``lab_source`` (..., 3) is relative to the source white; ``lab_target`` (..., 3) is the
    sample's colour under the target illuminant, adapted back to the source white with
    ``method`` and expressed relative to the source white; ``shift_ab`` = a*b* difference.
    """

    lab_source: np.ndarray
    lab_target: np.ndarray
    shift_ab: np.ndarray
    method: str


def colour_shift(spectrum: Spectrum, source="D65", target="A", observer="1931",
                 method: str = "bradford") -> ColourShift:
    """Colour shifts of reflectances when the light changes (van Trigt 1990, Fig. 1).

    The samples' XYZ under ``target`` are mapped to corresponding colours under ``source``
    by a chromatic adaptation transform (:func:`spectrocolor.adapt`), and compared in
    CIELAB with their XYZ under ``source``.

    Parameters
    ----------
    spectrum : Spectrum
        Reflectance factors (0–1), ``(..., K)``.
    source : str or Spectrum, default "D65"
        The reference light.
    target : str or Spectrum, default "A"
        The new light.
    observer : str or Spectrum, default "1931"
        Observer name or alias.
    method : str, default "bradford"
        Chromatic adaptation transform (see :func:`spectrocolor.adapt`).

    Returns
    -------
    ColourShift
        ``lab_source``, ``lab_target`` (…, 3) relative to the source white and the a*b* shift.

    Raises
    ------
    SpectrumError
        For input that is not a Spectrum.
    ColorimetryError
        For finite reflectances so large (near 1e308) that their colours overflow the float
        range, and as :func:`spectrocolor.adapt` for an unknown method.

    References
    ----------
    C. van Trigt, J. Opt. Soc. Am. A 7, 1891–1904 (1990), Fig. 1.

    Examples
    --------
    >>> from spectrocolor import Spectrum, wavelength_grid
    >>> green = Spectrum.gaussian(550, 80, wavelength_grid(400, 700, 10), peak=0.8)
    >>> colour_shift(green).shift_ab.round(2).tolist()  # a*, b* shift from D65 to A
    [-19.07, -0.68]
    """
    s = _reflectance(spectrum, "spectrum")
    W_s = np.asarray(weights(s.wavelengths_nm, observer=observer, illuminant=source))
    W_t = np.asarray(weights(s.wavelengths_nm, observer=observer, illuminant=target))
    white_s, white_t = W_s.sum(axis=0), W_t.sum(axis=0)
    with np.errstate(invalid="ignore", over="ignore"):
        lab_s = lab(s.values @ W_s, white_s)
        lab_t = lab(adapt(s.values @ W_t, white_t, white_s, method=method), white_s)
        shift = lab_t[..., 1:] - lab_s[..., 1:]
    refuse_overflow(np.concatenate([lab_s, lab_t, shift], axis=-1), [s.values], "spectrum", _OVERFLOW)
    return ColourShift(lab_s, lab_t, shift, method)
