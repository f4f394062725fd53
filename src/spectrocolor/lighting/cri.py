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

References
----------
CIE 13.3-1995 *Method of measuring and specifying colour rendering properties of light
sources*, §5 (eqs. 1–10). CIE 015:2018 §9.5 (CCT, Duv).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..coordinates import uv_1960
from ..sampling import cmfs_on
from ..spectrum import Spectrum
from .reference import cri_reference
from .spectra import in_chunks, light_cct, light_grid, tcs_reflectances

#: CIE 13.3 §5.3: largest chromaticity distance ΔC between light and reference.
DELTA_C_LIMIT = 5.4e-3


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


def colour_rendering_index(spd) -> CRI:
    """CIE 13.3 colour rendering index of lights ``(..., K)``.

    Parameters
    ----------
    spd : Spectrum
        Spectral power distributions (any scale), uniform 1 or 5 nm, with samples from
        380 nm (or below, down to 360 nm) to 780 nm.

    Returns
    -------
    CRI
        Ra, R1–R14, CCT, Duv and the validity flag, with ``spd.batch_shape``.

    References
    ----------
    CIE 13.3-1995, §5.

    Examples
    --------
    >>> from spectrocolor import illuminant
    >>> result = colour_rendering_index(illuminant("FL2"))
    >>> round(float(result.Ra))  # CIE 015:2018 Table 10 lists Ra = 64 for FL2
    64
    """
    # from 360 nm, or from the spectrum's first sample if that lies between 360 and 380 nm
    start = min(max(360.0, float(spd.wavelengths_nm[0])), 380.0) if isinstance(spd, Spectrum) else 380.0
    grid, S = light_grid(spd, start, 780.0)
    W = cmfs_on(grid, "1931") * (grid[1] - grid[0])
    r = in_chunks(_rendering_rows, S, grid, W, tcs_reflectances(grid)[:, :, None] * W[None])
    shape = spd.batch_shape
    return CRI(
        Ra=r["Ri"][:, :8].mean(axis=1).reshape(shape),
        Ri=r["Ri"].reshape(*shape, 14),
        cct_K=r["cct_K"].reshape(shape),
        duv=r["duv"].reshape(shape),
        meaningful=r["meaningful"].reshape(shape),
    )
