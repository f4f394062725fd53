"""Colour differences between CIELAB colours: ΔE*ab (CIE 1976) and ΔE00 (CIEDE2000).

Both take ``(..., 3)`` L*a*b* arrays that broadcast against each other and return the
broadcast leading shape. Compute L*a*b* with :func:`spectrocolor.lab` against the same
white for both colours.
"""

from __future__ import annotations

import numpy as np

from .arguments import real_number, refuse_overflow
from .coordinates import colour_array
from .errors import ColorimetryError

__all__ = ["delta_e_76", "delta_e_2000"]

_OVERFLOW = ("{} overflows the float range: CIELAB values this large are not colours (L* is "
             "0-100, a* and b* within a few hundred)")


def _lab_pair(lab1, lab2) -> tuple[np.ndarray, np.ndarray]:
    """Both CIELAB arrays, checked, and broadcastable against each other."""
    lab1 = colour_array(lab1, "lab1", 3, "CIELAB L*, a*, b*")
    lab2 = colour_array(lab2, "lab2", 3, "CIELAB L*, a*, b*")
    try:
        np.broadcast_shapes(lab1.shape, lab2.shape)
    except ValueError:
        raise ColorimetryError(
            f"lab1, lab2: shapes {lab1.shape} and {lab2.shape} do not broadcast; pass colours in matching batches"
        ) from None
    return lab1, lab2


def delta_e_76(lab1, lab2) -> np.ndarray:
    """CIE 1976 colour difference ΔE*ab: the Euclidean distance in CIELAB.

    Parameters
    ----------
    lab1, lab2 : array_like, shape (..., 3)
        L*a*b* colours; broadcast against each other.

    Returns
    -------
    ndarray, shape (...)
        ΔE*ab in CIELAB units, with the broadcast leading shape of the inputs.

    Raises
    ------
    ColorimetryError
        For malformed input or shapes that do not broadcast, and for finite colours so far
        apart (values near 1e154 and beyond) that the difference overflows the float range.

    References
    ----------
    CIE 015:2018, section 8.2.3.

    Examples
    --------
    >>> round(float(delta_e_76([50.0, 2.0, -3.0], [52.0, 2.0, 1.0])), 6)  # √(2² + 4²)
    4.472136
    """
    lab1, lab2 = _lab_pair(lab1, lab2)
    with np.errstate(over="ignore", invalid="ignore"):
        distance = np.sqrt(np.sum((lab1 - lab2) ** 2, axis=-1))
    return refuse_overflow(distance, [lab1, lab2], "lab1, lab2", _OVERFLOW.format("ΔE*ab"))


def _hue_deg(b: np.ndarray, a_prime: np.ndarray) -> np.ndarray:
    """Hue angle in [0, 360) degrees; 0 where a' = b = 0 (Sharma et al. eq. 4)."""
    hue = np.degrees(np.arctan2(b, a_prime)) % 360.0
    return np.where(hue >= 360.0, 0.0, hue)


def delta_e_2000(lab1, lab2, *, k_L: float = 1.0, k_C: float = 1.0, k_H: float = 1.0) -> np.ndarray:
    """CIEDE2000 colour difference ΔE00.

    Implements the formula exactly as written out by Sharma, Wu and Dalal (2005),
    including their conventions at the hue discontinuity: the mean hue of two colours whose
    hues differ by more than 180° is taken on the short arc, and where either colour is
    neutral (C' = 0) the hue difference is 0 and the mean hue is the sum of the hues.
    The result is symmetric in its arguments.

    Parameters
    ----------
    lab1, lab2 : array_like, shape (..., 3)
        L*a*b* colours; broadcast against each other.
    k_L, k_C, k_H : float, keyword-only
        Parametric weighting factors (1 for the reference conditions).

    Returns
    -------
    ndarray, shape (...)
        ΔE00, with the broadcast leading shape of the inputs.

    Raises
    ------
    ColorimetryError
        For a weighting factor that is not positive and finite, malformed input or shapes
        that do not broadcast, and for finite colours so large (values near 1e44 and beyond:
        C'⁷ overflows) that the difference would not be finite.

    References
    ----------
    CIE 142-2001, *Improvement to industrial colour-difference evaluation*.
    G. Sharma, W. Wu and E. N. Dalal, "The CIEDE2000 color-difference formula:
    implementation notes, supplementary test data, and mathematical observations",
    Color Res. Appl. 30 (1), 21-30 (2005), eqs. 1-22.

    Examples
    --------
    Pair 1 of Sharma et al.'s test data (ΔE00 = 2.0425):

    >>> round(float(delta_e_2000([50.0, 2.6772, -79.7751], [50.0, 0.0, -82.7485])), 4)
    2.0425
    """
    for name, k in (("k_L", k_L), ("k_C", k_C), ("k_H", k_H)):
        real_number(k, name, "a weighting factor (1 for the reference conditions)", positive=True)
    lab1, lab2 = _lab_pair(lab1, lab2)
    with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
        difference = _ciede2000(lab1, lab2, k_L, k_C, k_H)
    return refuse_overflow(difference, [lab1, lab2], "lab1, lab2", _OVERFLOW.format("ΔE00"))


def _ciede2000(lab1: np.ndarray, lab2: np.ndarray, k_L: float, k_C: float, k_H: float) -> np.ndarray:
    """Sharma, Wu and Dalal's eqs. 1-22 on checked arrays (see :func:`delta_e_2000`)."""
    L1, a1, b1 = lab1[..., 0], lab1[..., 1], lab1[..., 2]
    L2, a2, b2 = lab2[..., 0], lab2[..., 1], lab2[..., 2]

    # eqs. 2-4: a' stretched so that neutrals stay neutral
    C_mean = (np.hypot(a1, b1) + np.hypot(a2, b2)) / 2.0
    C_mean7 = C_mean**7
    G = 0.5 * (1.0 - np.sqrt(C_mean7 / (C_mean7 + 25.0**7)))
    a1p, a2p = (1.0 + G) * a1, (1.0 + G) * a2
    C1p, C2p = np.hypot(a1p, b1), np.hypot(a2p, b2)
    h1p, h2p = _hue_deg(b1, a1p), _hue_deg(b2, a2p)

    # eqs. 5-10: differences
    dLp = L2 - L1
    dCp = C2p - C1p
    chromatic = (C1p * C2p) != 0
    dh = h2p - h1p
    dh = np.where(dh > 180.0, dh - 360.0, np.where(dh < -180.0, dh + 360.0, dh))
    dhp = np.where(chromatic, dh, 0.0)
    dHp = 2.0 * np.sqrt(C1p * C2p) * np.sin(np.radians(dhp / 2.0))

    # eqs. 11-22: means, weighting functions, rotation term
    Lp_mean = (L1 + L2) / 2.0
    Cp_mean = (C1p + C2p) / 2.0
    h_sum = h1p + h2p
    far = np.abs(h1p - h2p) > 180.0
    hp_mean = np.where(
        ~chromatic,
        h_sum,
        np.where(far, np.where(h_sum < 360.0, h_sum + 360.0, h_sum - 360.0), h_sum) / 2.0,
    )
    T = (
        1.0
        - 0.17 * np.cos(np.radians(hp_mean - 30.0))
        + 0.24 * np.cos(np.radians(2.0 * hp_mean))
        + 0.32 * np.cos(np.radians(3.0 * hp_mean + 6.0))
        - 0.20 * np.cos(np.radians(4.0 * hp_mean - 63.0))
    )
    d_theta = 30.0 * np.exp(-(((hp_mean - 275.0) / 25.0) ** 2))
    Cp_mean7 = Cp_mean**7
    R_C = 2.0 * np.sqrt(Cp_mean7 / (Cp_mean7 + 25.0**7))
    L_term = (Lp_mean - 50.0) ** 2
    S_L = 1.0 + 0.015 * L_term / np.sqrt(20.0 + L_term)
    S_C = 1.0 + 0.045 * Cp_mean
    S_H = 1.0 + 0.015 * Cp_mean * T
    R_T = -np.sin(np.radians(2.0 * d_theta)) * R_C

    dL = dLp / (k_L * S_L)
    dC = dCp / (k_C * S_C)
    dH = dHp / (k_H * S_H)
    return np.sqrt(dL**2 + dC**2 + dH**2 + R_T * dC * dH)
