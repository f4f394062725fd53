"""CIE 13.3-1995 colour rendering index: Ra and the special indices R1–R14, batched.

For each light: its CCT and Duv (CIE 1931 2°, :func:`spectrocolor.cct`); the reference
illuminant of that CCT (:func:`~spectrocolor.lighting.reference.cri_reference`); the 14 test
colour samples under both in the CIE 1960 UCS, the test side carried to the reference white by
the von Kries-type transform of CIE 13.3 eq. (6) (the c, d coordinates); CIE 1964 U*V*W*
with W* = 25 Y^(1/3) − 17 (Y of the sample, the light's own Y = 100) and U* = 13 W* (u − u_r),
V* = 13 W* (v − v_r); the difference ΔE_i; Ri = 100 − 4.6 ΔE_i; Ra = mean of R1–R8.

The sums run over the spectrum's own samples from 360 nm (or its first sample, which must be
≤ 380 nm) to 780 nm, at 1 or 5 nm; the 5 nm test colour samples are Sprague-interpolated
(CIE 167) between their tabulated points.

CIE 13.3 asks that the light be close to the Planckian locus: the chromaticity distance to the
reference, ΔC = ``|Duv|`` in the 1960 diagram, should be at most 5.4 × 10⁻³. Results are returned
for every light; ``meaningful`` says which lights meet this (and have a CCT at all).

CIE reports the indices as whole numbers: each Ri is rounded first and Ra is the mean of the
rounded R1–R8, itself rounded (``rounding="integer"``). That rule, not the choice of reference
illuminant, is what makes CIE 015's printed Ra of FL1–FL12 (e.g. FL8: 95, where the unrounded
mean is 95.50) come out of the exact computation.

Lights that cannot be rendered honestly — no power, negative power, values that are not finite,
a spectrum that does not cover 380–780 nm — get NaN and a ``reason`` in a batch, and a
:class:`~spectrocolor.errors.SpectrumError` alone (:func:`~spectrocolor.lighting.spectra.checked_lights`).

References
----------
CIE 13.3-1995 *Method of measuring and specifying colour rendering properties of light
sources*, §5 (eqs. 1–10). CIE 015:2018 §9.5 (CCT, Duv).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .. import notebook_hooks
from ..coordinates import uv_1960
from ..errors import SpectrumError
from ..registry import Registry
from ..sampling import cmfs_on
from ..spectrum import Spectrum
from .reference import cri_reference
from .spectra import RESAMPLE_HINT, checked_lights, in_chunks, light_cct, tcs_reflectances

#: CIE 13.3 §5.3: largest chromaticity distance ΔC between light and reference.
DELTA_C_LIMIT = 5.4e-3


def _whole(values: np.ndarray) -> np.ndarray:
    """Round half away from zero to whole numbers (95.5 → 96, −83.5 → −84)."""
    return np.sign(values) * np.floor(np.abs(values) + 0.5)


def _unrounded(Ri: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    return Ri[..., :8].mean(axis=-1), Ri


def _integer(Ri: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    whole = _whole(Ri)
    return _whole(whole[..., :8].mean(axis=-1)), whole


#: How the indices are reported: name → function ``Ri (..., 14) → (Ra, Ri)``.
ROUNDINGS = Registry("rounding", "a rounding of the colour rendering indices")
ROUNDINGS.add("none", _unrounded, "Ri as computed; Ra the mean of R1–R8 (full precision)")
ROUNDINGS.add("integer", _integer,
              "CIE 13.3 as CIE reports it: each Ri rounded to a whole number (half away from zero), "
              "Ra the mean of the rounded R1–R8, rounded to a whole number")


@dataclass(frozen=True)
class CRI:
    """Colour rendering of lights by CIE 13.3; every array has the lights' batch shape.

    Attributes
    ----------
    Ra : ndarray
        General colour rendering index (mean of R1–R8).
    Ri : ndarray, shape (..., 14)
        Special colour rendering indices R1–R14 (``Ri[..., 8]`` is R9, saturated red).
    cct_K, duv : ndarray
        Correlated colour temperature (K) and Duv of the light (CIE 1960 UCS).
    meaningful : ndarray of bool
        A CCT exists and ``|Duv|`` ≤ 5.4 × 10⁻³ (CIE 13.3 §5.3).
    reason : ndarray of str
        Why a light's indices are NaN (refused input, no CCT, no reference illuminant); ``""``
        where they are computed.
    rounding : str
        The rounding of :data:`ROUNDINGS` used (``"none"`` or ``"integer"``).

    References
    ----------
    CIE 13.3-1995, *Method of measuring and specifying colour rendering properties of light
    sources*.

    Examples
    --------
    >>> from spectrocolor import colour_rendering_index, illuminant
    >>> cri = colour_rendering_index(illuminant("FL2"))
    >>> round(float(cri.Ra), 1), round(float(cri.Ri[8]), 1), bool(cri.meaningful)  # Ra, R9
    (64.2, -83.9, True)
    """

    Ra: np.ndarray
    Ri: np.ndarray
    cct_K: np.ndarray
    duv: np.ndarray
    meaningful: np.ndarray
    reason: np.ndarray
    rounding: str = "none"

    _repr_html_, _repr_svg_, __repr__ = notebook_hooks.html, notebook_hooks.svg, notebook_hooks.text  # notebooks

    @property
    def R9(self) -> np.ndarray:
        """Special index of TCS09 (strong red)."""
        return self.Ri[..., 8]


def _cd(uv: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    u, v = uv[..., 0], uv[..., 1]
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        return (4.0 - u - 10.0 * v) / v, (1.708 * v + 0.404 - 1.481 * u) / v


def _uvw(XYZ100: np.ndarray, uv: np.ndarray, uv_white: np.ndarray) -> np.ndarray:
    with np.errstate(invalid="ignore"):
        W = 25.0 * np.cbrt(XYZ100[..., 1]) - 17.0
    return np.stack([13.0 * W * (uv[..., 0] - uv_white[..., None, 0]),
                     13.0 * W * (uv[..., 1] - uv_white[..., None, 1]), W], axis=-1)


def _sample_XYZ100(S: np.ndarray, products: np.ndarray, V_delta: np.ndarray) -> np.ndarray:
    """XYZ (N, samples, 3) of the samples under lights S (N, K), each light scaled to Y = 100."""
    count = products.shape[0]
    XYZ = S @ products.transpose(1, 0, 2).reshape(products.shape[1], -1)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        k = 100.0 / (S @ V_delta)
        return XYZ.reshape(len(S), count, 3) * k[:, None, None]


def _rendering_rows(S: np.ndarray, grid: np.ndarray, W: np.ndarray, products: np.ndarray) -> dict:
    """R1–R14, CCT, Duv and the validity of lights S (N, K), for :func:`in_chunks`.

    ``products`` are the test colour samples times the weights, (14, K, 3).
    """
    temperature = light_cct(S, grid)
    R = cri_reference(temperature.cct_K, grid)
    uv_test, uv_ref = uv_1960(S @ W), uv_1960(R @ W)
    XYZ_t = _sample_XYZ100(S, products, W[:, 1])
    XYZ_r = _sample_XYZ100(R, products, W[:, 1])
    uv_t, uv_r = uv_1960(XYZ_t), uv_1960(XYZ_r)

    # CIE 13.3 eq. (6): adapt the samples under the test light to the reference white
    c_t, d_t = _cd(uv_test)
    c_r, d_r = _cd(uv_ref)
    c_i, d_i = _cd(uv_t)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        cc = (c_r / c_t)[:, None] * c_i
        dd = (d_r / d_t)[:, None] * d_i
        denominator = 16.518 + 1.481 * cc - dd
        uv_adapted = np.stack([(10.872 + 0.404 * cc - 4.0 * dd) / denominator, 5.520 / denominator], axis=-1)

    delta_E = np.linalg.norm(_uvw(XYZ_r, uv_r, uv_ref) - _uvw(XYZ_t, uv_adapted, uv_ref), axis=-1)
    meaningful = np.isfinite(temperature.cct_K) & (np.abs(temperature.duv) <= DELTA_C_LIMIT)
    return {"Ri": 100.0 - 4.6 * delta_E, "cct_K": temperature.cct_K, "duv": temperature.duv,
            "meaningful": meaningful}


def undefined_reasons(
    Ra: np.ndarray, cct_K: np.ndarray, refused: np.ndarray, values: np.ndarray | None = None
) -> np.ndarray:
    """Reasons for NaN results: the refusal, else no CCT, else negative samples, else no reference.

    Parameters
    ----------
    Ra : numpy.ndarray, shape (N,)
        A metric's main result (NaN where undefined).
    cct_K : numpy.ndarray, shape (N,)
        The lights' CCTs, K.
    refused : numpy.ndarray of str, shape (N,)
        Input refusals (:attr:`CheckedLights.reasons`).
    values : numpy.ndarray, shape (N, K), optional
        The lights' spectral values: a light with a negative sample whose result is NaN is said to
        be so (a test colour under it can have negative tristimulus values, which a colour
        appearance model's fractional powers leave undefined).

    Returns
    -------
    numpy.ndarray of str, shape (N,)
        ``""`` where ``Ra`` is a number.

    Examples
    --------
    >>> undefined_reasons(np.array([80.0, np.nan]), np.array([4000.0, np.nan]), np.array(["", ""])).tolist()
    ['', 'no correlated colour temperature (no luminance, or far from the Planckian locus)']
    """
    reasons = np.asarray(refused, dtype=object).copy()
    no_cct = ~np.isfinite(cct_K) & (reasons == "")
    reasons[no_cct] = "no correlated colour temperature (no luminance, or far from the Planckian locus)"
    other = ~np.isfinite(Ra) & (reasons == "")
    negative = np.zeros(other.shape, bool) if values is None else np.any(np.asarray(values) < 0, axis=-1)
    for i in np.flatnonzero(other):
        reasons[i] = (f"undefined at the CCT {cct_K[i]:.0f} K: the light has negative samples, so a test "
                      "colour under it has negative tristimulus values" if negative[i]
                      else f"no reference illuminant at the CCT {cct_K[i]:.0f} K")
    return reasons.astype(str)


def colour_rendering_index(spd, rounding: str = "none", *, resample_hint: str = RESAMPLE_HINT) -> CRI:
    """CIE 13.3 colour rendering index of lights ``(..., K)``.

    Parameters
    ----------
    spd : Spectrum
        Spectral power distributions (any scale), uniform 1 or 5 nm, with samples from
        380 nm (or below, down to 360 nm) to 780 nm.
    rounding : {"none", "integer"}, default "none"
        ``"integer"`` reports the indices as CIE 13.3 does: each Ri rounded to a whole number,
        Ra the mean of the rounded R1–R8, rounded (:data:`ROUNDINGS`).
    resample_hint : str, keyword-only
        How a refused grid interval is to be fixed (the command line names its own option).

    Returns
    -------
    CRI
        Ra, R1–R14, CCT, Duv, the validity flag and a reason for each NaN, with
        ``spd.batch_shape``.

    Raises
    ------
    SpectrumError
        For a grid other than 1 or 5 nm, and for a single light that is refused (no power,
        negative power, not finite, not covering 380–780 nm); in a batch such a light gets NaN.

    References
    ----------
    CIE 13.3-1995, §5. CIE 015:2004, Table T.8.2 (Ra of FL1–FL12, as whole numbers).

    Examples
    --------
    >>> from spectrocolor import illuminant
    >>> result = colour_rendering_index(illuminant("FL2"))
    >>> round(float(result.Ra), 2)
    64.16
    >>> float(colour_rendering_index(illuminant("FL8"), rounding="integer").Ra)  # CIE prints 95
    95.0
    """
    report = ROUNDINGS.get(rounding)
    rounding = ROUNDINGS.canonical(rounding)
    if not isinstance(spd, Spectrum):
        raise SpectrumError(f"spd: expected a spectrocolor.Spectrum of spectral power distributions, got "
                            f"{type(spd).__name__}; wrap arrays as Spectrum(wavelengths_nm, values)")
    # from 360 nm, or from the spectrum's first sample if that lies between 360 and 380 nm
    start = min(max(360.0, float(spd.wavelengths_nm[0])), 380.0)
    checked = checked_lights(spd, "cri", start_nm=start, resample_hint=resample_hint)
    grid, S = checked.grid, checked.values
    peak = np.abs(S).max(axis=1, keepdims=True)
    S = S / np.where(peak > 0, peak, 1.0)  # scale-free: keep tiny or huge units away from under/overflow
    W = cmfs_on(grid, "1931") * (grid[1] - grid[0])
    r = in_chunks(_rendering_rows, S, grid, W, tcs_reflectances(grid)[:, :, None] * W[None])
    Ra, Ri = report(checked.refuse(r["Ri"]))
    cct_K, duv = checked.refuse(r["cct_K"]), checked.refuse(r["duv"])
    shape = checked.batch_shape
    return CRI(
        Ra=Ra.reshape(shape),
        Ri=Ri.reshape(*shape, 14),
        cct_K=cct_K.reshape(shape),
        duv=duv.reshape(shape),
        meaningful=(r["meaningful"] & checked.ok).reshape(shape),
        reason=undefined_reasons(Ra, cct_K, checked.reasons, checked.values).reshape(shape),
        rounding=rounding,
    )
