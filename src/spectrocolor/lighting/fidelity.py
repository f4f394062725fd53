"""Colour fidelity and gamut: CIE 224:2017 Rf and ANSI/IES TM-30-20 Rf, Rg and the 16 hue bins.

For each light: its CCT (CIE 1931 2°, exact projection, :func:`spectrocolor.cct`); the
reference illuminant of that CCT
(:func:`~spectrocolor.lighting.reference.fidelity_reference`); the 99 colour evaluation
samples (CES) under both, with the CIE 1964 10° observer, each light scaled so that its own
Y₁₀ = 100; CIECAM02 with L_A = 100 cd/m², Y_b = 20, average surround and D = 1; CAM02-UCS
J'a'b' (:mod:`~spectrocolor.lighting.cam02ucs`); the colour differences ΔE_i;

* Rf,i = 10 ln(exp((100 − 6.73 ΔE_i)/10) + 1) per sample, Rf from the mean ΔE (CIE 224 eq. 9);
* the hue bins j = 1…16 of 22.5° by the sample's hue under the reference; per bin the mean
  a'b' under test and reference; Rg = 100 × area of the test polygon / area of the reference
  polygon (TM-30-20 eq. 7); Rf,hj from the bin's mean ΔE; the chroma shift
  Rcs,hj = (Δa' cos θj + Δb' sin θj) / ‖ref_j‖ and the hue shift
  Rhs,hj = (−Δa' sin θj + Δb' cos θj) / ‖ref_j‖ with θj the bin's middle angle (TM-30-20
  §4.6; Rcs,hj is returned as a fraction, multiply by 100 for the per cent TM-30 prints).

TM-30-18/20/24 compute Rf exactly as CIE 224:2017. The spectrum's own samples from 380 to
780 nm are used, at 1 or 5 nm (the CES are tabulated at 1 nm; 5 nm takes every fifth).

References
----------
CIE 224:2017 *CIE 2017 colour fidelity index for accurate scientific use*.
ANSI/IES TM-30-20 *IES method for evaluating light source color rendition*, §4–§6.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .. import notebook_hooks
from ..sampling import cmfs_on
from .cam02ucs import M_CAT02, cam02ucs_planes
from .reference import fidelity_reference
from .spectra import RESAMPLE_HINT, ces_reflectances, checked_lights, in_chunks, light_cct

#: Scaling factor of CIE 224:2017 eq. (8).
CF = 6.73
#: Number of hue bins (TM-30-20 §4.6).
HUE_BINS = 16


@dataclass(frozen=True)
class Fidelity:
    """CIE 224 / TM-30 results; every array has the lights' batch shape in front.

    Attributes
    ----------
    Rf, Rg : ndarray
        Fidelity index and gamut index.
    Rf_i : ndarray, shape (..., 99)
        Fidelity of each colour evaluation sample.
    Rf_h, Rcs_h, Rhs_h : ndarray, shape (..., 16)
        Per hue bin: fidelity, chroma shift (fraction) and hue shift (fraction); NaN for a bin
        without samples.
    cct_K, duv : ndarray
        CCT (K) and Duv of the light.
    test_ab, reference_ab : ndarray, shape (..., 16, 2)
        Mean CAM02-UCS a', b' of each hue bin under the light and the reference (the corners
        of the colour vector graphic).
    reason : ndarray of str
        Why a light's indices are NaN (refused input, no CCT, no reference illuminant at its
        CCT); ``""`` where they are computed.

    References
    ----------
    CIE 224:2017, *CIE 2017 colour fidelity index for accurate scientific use*; ANSI/IES
    TM-30-20.

    Examples
    --------
    >>> from spectrocolor import colour_fidelity, illuminant
    >>> result = colour_fidelity(illuminant("FL2"))
    >>> result.Rf_h.shape, result.test_ab.shape, round(float(result.cct_K))
    ((16,), (16, 2), 4224)
    """

    Rf: np.ndarray
    Rg: np.ndarray
    Rf_i: np.ndarray
    Rf_h: np.ndarray
    Rcs_h: np.ndarray
    Rhs_h: np.ndarray
    cct_K: np.ndarray
    duv: np.ndarray
    test_ab: np.ndarray
    reference_ab: np.ndarray
    reason: np.ndarray

    _repr_html_, _repr_svg_, __repr__ = notebook_hooks.html, notebook_hooks.svg, notebook_hooks.text  # notebooks


def rf_from_delta_e(delta_E):
    """Fidelity 0–100 from a CAM02-UCS colour difference (CIE 224:2017 eq. 9).

    Parameters
    ----------
    delta_E : array_like
        Mean CAM02-UCS colour difference(s) ΔE'.

    Returns
    -------
    numpy.ndarray
        ``10 ln(1 + exp((100 − c_f ΔE') / 10))`` with c_f = 6.73.

    References
    ----------
    CIE 224:2017, eq. (9).

    Examples
    --------
    >>> round(float(rf_from_delta_e(0.0)), 4)
    100.0005
    """
    return 10.0 * np.log1p(np.exp((100.0 - CF * np.asarray(delta_E, dtype=float)) / 10.0))


def _jab(S: np.ndarray, products: np.ndarray, W10: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """CAM02-UCS J', a', b' (each (N, 99)) of the samples under lights S (N, K).

    ``products`` (3, K, 99) are the samples' weights in CAT02 RGB (``M_CAT02`` folded in), so
    each sharpened channel is one contiguous matrix product; each light is scaled to Y₁₀ = 100.
    """
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        k = 100.0 / (S @ W10[:, 1])
        white = (S @ (W10 @ M_CAT02.T)).T * k  # CAT02 RGB of the white, (3, N)
        rgb = np.empty((3, len(S), products.shape[-1]))
        for channel in range(3):
            np.matmul(S, products[channel], out=rgb[channel])
        rgb *= k[:, None]
    return cam02ucs_planes(rgb, white[:, :, None], 100.0)


def _polygon_area(ab: np.ndarray) -> np.ndarray:
    a, b = ab[..., 0], ab[..., 1]
    return 0.5 * np.sum(a * np.roll(b, -1, axis=-1) - np.roll(a, -1, axis=-1) * b, axis=-1)


def _bin_means(hue_deg, test_ab, reference_ab, delta_E):
    """Per light and hue bin (by ``hue_deg`` under the reference): mean a'b' and mean ΔE.

    One ``bincount`` over flat (light, bin) indices; a bin without samples gives NaN.
    """
    N, count = delta_E.shape
    with np.errstate(invalid="ignore"):
        bins = np.floor(hue_deg / (360.0 / HUE_BINS))
    valid = np.isfinite(bins)
    index = (np.arange(N)[:, None] * HUE_BINS + np.where(valid, bins, 0).astype(np.intp))[valid]

    def mean(values):
        sums = np.bincount(index, weights=values[valid], minlength=N * HUE_BINS)
        return sums.reshape(N, HUE_BINS)

    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        members = mean(np.ones_like(delta_E))
        members = np.where(members > 0, members, np.nan)
        test = np.stack([mean(test_ab[..., 0]), mean(test_ab[..., 1])], axis=-1) / members[..., None]
        reference = np.stack([mean(reference_ab[..., 0]), mean(reference_ab[..., 1])], axis=-1) / members[..., None]
        return test, reference, mean(delta_E) / members


def _fidelity_rows(S: np.ndarray, grid: np.ndarray, W10: np.ndarray, products: np.ndarray) -> dict:
    """Every CIE 224 / TM-30 quantity of lights S (N, K), flat, for :func:`in_chunks`."""
    temperature = light_cct(S, grid)
    R = fidelity_reference(temperature.cct_K, grid)
    J_t, a_t, b_t = _jab(S, products, W10)
    J_r, a_r, b_r = _jab(R, products, W10)
    delta_E = np.sqrt((J_t - J_r) ** 2 + (a_t - a_r) ** 2 + (b_t - b_r) ** 2)  # (N, 99)

    hue_ref = np.degrees(np.arctan2(b_r, a_r)) % 360.0
    test_ab, reference_ab, bin_delta_E = _bin_means(hue_ref, np.stack([a_t, b_t], axis=-1),
                                                    np.stack([a_r, b_r], axis=-1), delta_E)
    theta = np.radians((np.arange(HUE_BINS) + 0.5) * 360.0 / HUE_BINS)
    shift = test_ab - reference_ab
    norm = np.linalg.norm(reference_ab, axis=-1)
    with np.errstate(invalid="ignore", divide="ignore"):
        Rg = 100.0 * _polygon_area(test_ab) / _polygon_area(reference_ab)
        Rcs = (shift[..., 0] * np.cos(theta) + shift[..., 1] * np.sin(theta)) / norm
        Rhs = (-shift[..., 0] * np.sin(theta) + shift[..., 1] * np.cos(theta)) / norm
    return {
        "Rf": rf_from_delta_e(delta_E.mean(axis=1)), "Rg": Rg, "Rf_i": rf_from_delta_e(delta_E),
        "Rf_h": rf_from_delta_e(bin_delta_E), "Rcs_h": Rcs, "Rhs_h": Rhs,
        "cct_K": temperature.cct_K, "duv": temperature.duv, "test_ab": test_ab, "reference_ab": reference_ab,
    }


def colour_fidelity(spd, *, resample_hint: str = RESAMPLE_HINT) -> Fidelity:
    """CIE 224:2017 / ANSI/IES TM-30-20 colour fidelity and gamut of lights ``(..., K)``.

    Parameters
    ----------
    spd : Spectrum
        Spectral power distributions (any scale), uniform 1 or 5 nm, with samples from 380 to
        780 nm.
    resample_hint : str, keyword-only
        How a refused grid interval is to be fixed (the command line names its own option).

    Returns
    -------
    Fidelity
        Every index with ``spd.batch_shape``, and a reason for each NaN.

    Raises
    ------
    SpectrumError
        As for :func:`~spectrocolor.lighting.cri.colour_rendering_index`: a grid other than 1 or 5
        nm, or a single light that is refused; in a batch such a light gets NaN.

    References
    ----------
    CIE 224:2017, §4. ANSI/IES TM-30-20, §4–§6.

    Examples
    --------
    >>> from spectrocolor import illuminant
    >>> result = colour_fidelity(illuminant("FL2"))
    >>> round(float(result.Rf), 1), round(float(result.Rg), 1)
    (70.1, 86.4)
    """
    from .cri import undefined_reasons

    checked = checked_lights(spd, "fidelity", resample_hint=resample_hint)
    grid, S = checked.grid, checked.values
    peak = np.abs(S).max(axis=1, keepdims=True)
    S = S / np.where(peak > 0, peak, 1.0)  # scale-free: keep tiny or huge units away from under/overflow
    W10 = cmfs_on(grid, "1964") * (grid[1] - grid[0])
    ces = ces_reflectances(grid)
    products = np.ascontiguousarray(((W10 @ M_CAT02.T).T[:, None, :] * ces[None]).transpose(0, 2, 1))  # (3, K, 99)
    r = {key: checked.refuse(value) for key, value in
         in_chunks(_fidelity_rows, S, grid, W10, products).items()}
    shape = checked.batch_shape
    return Fidelity(
        Rf=r["Rf"].reshape(shape),
        Rg=r["Rg"].reshape(shape),
        Rf_i=r["Rf_i"].reshape(*shape, 99),
        Rf_h=r["Rf_h"].reshape(*shape, HUE_BINS),
        Rcs_h=r["Rcs_h"].reshape(*shape, HUE_BINS),
        Rhs_h=r["Rhs_h"].reshape(*shape, HUE_BINS),
        cct_K=r["cct_K"].reshape(shape),
        duv=r["duv"].reshape(shape),
        test_ab=r["test_ab"].reshape(*shape, HUE_BINS, 2),
        reference_ab=r["reference_ab"].reshape(*shape, HUE_BINS, 2),
        reason=undefined_reasons(r["Rf"], r["cct_K"], checked.reasons, checked.values).reshape(shape),
    )
