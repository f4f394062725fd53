"""CIECAM02 (forward: lightness J, colourfulness M, hue angle h) and the CAM02-UCS space.

Vectorised over ``(..., 3)`` arrays. CIE 224:2017 and TM-30 use it with L_A = 100 cd/m²,
Y_b = 20, the average surround and the illuminant discounted (D = 1); those are the defaults.

CAM02-UCS (Luo, Cui & Li 2006): J' = 1.7 J / (1 + 0.007 J), M' = ln(1 + 0.0228 M) / 0.0228,
a' = M' cos h, b' = M' sin h.

The post-adaptation compression is applied to |R'| with the sign restored (CIE 159:2004,
as extended for negative cone responses by Luo & Li); CIE 224 samples under real lights
give positive responses, where every form agrees.

References
----------
CIE 159:2004 *A colour appearance model for colour management systems: CIECAM02*.
M. R. Luo, G. Cui, C. Li, "Uniform colour spaces based on CIECAM02 colour appearance model",
Color Res. Appl. 31 (4), 320–330 (2006). CIE 224:2017 §4.4.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from ..coordinates import colour_array
from ..errors import ColorimetryError
from ..registry import Registry

#: Surround parameters (F, c, N_c), CIE 159:2004 Table 1.
SURROUNDS = Registry("surround", "a CIECAM02 surround")
SURROUNDS.add("average", (1.0, 0.69, 1.0), "F = 1.0, c = 0.69, N_c = 1.0 (surface colours, CIE 224)")
SURROUNDS.add("dim", (0.9, 0.59, 0.9), "F = 0.9, c = 0.59, N_c = 0.9 (television)")
SURROUNDS.add("dark", (0.8, 0.525, 0.8), "F = 0.8, c = 0.525, N_c = 0.8 (projection in a dark room)")

#: CAT02 matrix (XYZ → sharpened RGB), CIE 159:2004.
M_CAT02 = np.array([[0.7328, 0.4296, -0.1624], [-0.7036, 1.6975, 0.0061], [0.0030, 0.0136, 0.9834]])
_M_HPE = np.array([[0.38971, 0.68898, -0.07868], [-0.22981, 1.18340, 0.04641], [0.0, 0.0, 1.0]])
_CAT02_TO_HPE = _M_HPE @ np.linalg.inv(M_CAT02)


class JMh(NamedTuple):
    """CIECAM02 lightness J (0–100), colourfulness M and hue angle h (degrees, 0–360)."""

    J: np.ndarray
    M: np.ndarray
    h: np.ndarray


def _times(matrix: np.ndarray, channels: np.ndarray) -> np.ndarray:
    """``matrix @ colour`` for channel-first colours ``(3, ...)``: three contiguous planes out."""
    return np.tensordot(matrix, channels, axes=(1, 0))


def _compress(rgb: np.ndarray, F_L) -> np.ndarray:
    """400 (F_L |x| / 100)^0.42 / (27.13 + (F_L |x| / 100)^0.42) with the sign of x, + 0.1 (in place)."""
    power = np.abs(rgb)
    power *= F_L / 100.0
    np.power(power, 0.42, out=power)
    result = 400.0 * power
    power += 27.13
    result /= power
    result = np.copysign(result, rgb, out=result)
    result += 0.1
    return result


def _check_conditions(surround: str, L_A: float, Y_b: float) -> None:
    SURROUNDS.get(surround)
    if not (np.isfinite(L_A) and L_A > 0 and np.isfinite(Y_b) and Y_b > 0):
        raise ColorimetryError(f"L_A and Y_b: expected positive numbers, got L_A={L_A!r}, Y_b={Y_b!r}")


def _forward(rgb, rgb_w, Y_w, L_A, Y_b, surround, discount_illuminant):
    """J, M and the hue direction (cos h, sin h) of CIECAM02 (CIE 159:2004 steps 1–10).

    Colours and white are CAT02 RGB (:data:`M_CAT02` applied to XYZ), channel-first, ``(3, ...)``,
    so every step works on contiguous planes; ``Y_w`` is the white's Y. The hue enters only
    through cos h and sin h = (a, b) / ‖(a, b)‖, which saves the trigonometry on large batches:
    e_t = ¼ (cos(h + 2) + 3.8) = ¼ (cos h cos 2 − sin h sin 2 + 3.8).
    """
    F, c, N_c = SURROUNDS.get(surround)
    k = 1.0 / (5.0 * L_A + 1.0)
    F_L = 0.2 * k**4 * (5.0 * L_A) + 0.1 * (1.0 - k**4) ** 2 * (5.0 * L_A) ** (1.0 / 3.0)
    D = 1.0 if discount_illuminant else F * (1.0 - np.exp((-L_A - 42.0) / 92.0) / 3.6)
    with np.errstate(divide="ignore", invalid="ignore"):
        n = Y_b / Y_w
        z = 1.48 + np.sqrt(n)
        N_bb = 0.725 * n**-0.2
        gain = D * Y_w / rgb_w + 1.0 - D
        R, G, B = _compress(_times(_CAT02_TO_HPE, rgb * gain), F_L)
        R_w, G_w, B_w = _compress(_times(_CAT02_TO_HPE, rgb_w * gain), F_L)
        a = R - 12.0 * G / 11.0 + B / 11.0
        b = (R + G - 2.0 * B) / 9.0
        chroma_ab = np.hypot(a, b)
        zero = chroma_ab == 0.0
        cos_h = np.where(zero, 1.0, a / chroma_ab)
        sin_h = np.where(zero, 0.0, b / chroma_ab)
        e_t = 0.25 * (cos_h * np.cos(2.0) - sin_h * np.sin(2.0) + 3.8)
        A = (2.0 * R + G + B / 20.0 - 0.305) * N_bb
        A_w = (2.0 * R_w + G_w + B_w / 20.0 - 0.305) * N_bb
        J = 100.0 * (A / A_w) ** (c * z)
        t = (50000.0 / 13.0 * N_c * N_bb) * e_t * chroma_ab / (R + G + 21.0 / 20.0 * B)
        C = t**0.9 * np.sqrt(J / 100.0) * (1.64 - 0.29**n) ** 0.73
    return J, C * F_L**0.25, cos_h, sin_h


def _channels(XYZ100, white_XYZ100) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """CAT02 RGB of colours and white, channel-first and broadcast, and the white's Y."""
    XYZ = colour_array(XYZ100, "XYZ100", 3, "tristimulus values")
    white = colour_array(white_XYZ100, "white_XYZ100", 3, "tristimulus values")
    XYZ, white = np.broadcast_arrays(XYZ, white)
    white = np.moveaxis(white, -1, 0)
    return _times(M_CAT02, np.moveaxis(XYZ, -1, 0)), _times(M_CAT02, white), white[1]


def cam02ucs_planes(rgb_cat02, white_cat02, white_Y, L_A: float = 100.0, Y_b: float = 20.0,
                    surround: str = "average", discount_illuminant: bool = True
                    ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """CAM02-UCS J', a', b' as three arrays from channel-first CAT02 RGB ``(3, ...)``.

    The layout for large batches (CIE 224: 99 samples × many lights), where :data:`M_CAT02`
    is folded into the spectral weights so the sharpened RGB come straight out of one matrix
    product; ``white_Y`` is the white's Y. :func:`cam02ucs_jab` is the same from XYZ ``(..., 3)``.

    Parameters
    ----------
    rgb_cat02 : numpy.ndarray, shape (3, ...)
        ``M_CAT02 @ XYZ`` of the colours, channel first.
    white_cat02 : numpy.ndarray, shape (3, ...)
        ``M_CAT02 @ XYZ_w`` of the white, broadcast against ``rgb_cat02``.
    white_Y : float or numpy.ndarray
        Y of the white.
    L_A : float, default 100.0
        Adapting luminance, cd/m².
    Y_b : float, default 20.0
        Relative luminance of the background (same scale as Y_w).
    surround : str, default "average"
        ``"average"``, ``"dim"`` or ``"dark"`` (:data:`SURROUNDS`).
    discount_illuminant : bool, default True
        ``True``: complete adaptation, D = 1 (as CIE 224 prescribes); else D from F and L_A.

    Returns
    -------
    tuple of numpy.ndarray
        J', a', b', each of the colours' shape.

    Raises
    ------
    ColorimetryError
        For an unknown surround or viewing conditions out of range.

    References
    ----------
    M. R. Luo, G. Cui, C. Li, Color Res. Appl. 31, 320–330 (2006) (CAM02-UCS).

    Examples
    --------
    >>> XYZ, white = np.array([19.31, 23.93, 10.14]), np.array([98.88, 90.0, 32.03])
    >>> J, a, b = cam02ucs_planes(M_CAT02 @ XYZ, M_CAT02 @ white, white[1], 200.0, 18.0)
    >>> [round(float(v), 3) for v in (J, a, b)]
    [61.122, -27.426, -5.769]
    """
    _check_conditions(surround, L_A, Y_b)
    J, M, cos_h, sin_h = _forward(rgb_cat02, white_cat02, white_Y, L_A, Y_b, surround, discount_illuminant)
    M_prime = np.log1p(0.0228 * M) / 0.0228
    return 1.7 * J / (1.0 + 0.007 * J), M_prime * cos_h, M_prime * sin_h


def ciecam02_jmh(XYZ100, white_XYZ100, L_A: float = 100.0, Y_b: float = 20.0,
                 surround: str = "average", discount_illuminant: bool = True) -> JMh:
    """CIECAM02 J, M, h of colours ``(..., 3)`` seen under the white ``white_XYZ100``.

    Parameters
    ----------
    XYZ100 : array_like, shape (..., 3)
        Tristimulus values on the scale of the white (white Y_w = 100 usually).
    white_XYZ100 : array_like, shape (..., 3)
        Adopted white, broadcast against ``XYZ100``.
    L_A : float, default 100.0
        Adapting luminance, cd/m².
    Y_b : float, default 20.0
        Relative luminance of the background (same scale as Y_w).
    surround : str, default "average"
        ``"average"``, ``"dim"`` or ``"dark"`` (:data:`SURROUNDS`).
    discount_illuminant : bool, default True
        ``True``: complete adaptation, D = 1 (as CIE 224 prescribes); else D from F and L_A.

    Returns
    -------
    JMh

    References
    ----------
    CIE 159:2004, steps 1–10 of the forward model.

    Examples
    --------
    The CIECAM02 worked example of Luo & Li, "CIECAM02 and its recent developments" (2013),
    sample 1 (J = 48.0314, M = 38.7789, h = 191.0452; colour-science gives the same):

    >>> jmh = ciecam02_jmh([19.31, 23.93, 10.14], [98.88, 90.0, 32.03], 200.0, 18.0,
    ...                    discount_illuminant=False)
    >>> [round(float(v), 4) for v in jmh]
    [48.0314, 38.7789, 191.0452]
    """
    _check_conditions(surround, L_A, Y_b)
    J, M, cos_h, sin_h = _forward(*_channels(XYZ100, white_XYZ100), L_A, Y_b, surround, discount_illuminant)
    return JMh(J, M, np.degrees(np.arctan2(sin_h, cos_h)) % 360.0)


def cam02ucs_jab(XYZ100, white_XYZ100, L_A: float = 100.0, Y_b: float = 20.0,
                 surround: str = "average", discount_illuminant: bool = True) -> np.ndarray:
    """CAM02-UCS J', a', b' ``(..., 3)`` of colours seen under ``white_XYZ100``.

    The same as ``cam02ucs(ciecam02_jmh(...))`` without the round trip through the hue angle
    (the fast path for the 99 samples × many lights of CIE 224). Arguments as
    :func:`ciecam02_jmh`.

    Parameters
    ----------
    XYZ100 : array_like, shape (..., 3)
        Tristimulus values on the scale of the white.
    white_XYZ100 : array_like, shape (..., 3)
        Adopted white, broadcast against ``XYZ100``.
    L_A : float, default 100.0
        Adapting luminance, cd/m².
    Y_b : float, default 20.0
        Relative luminance of the background (same scale as Y_w).
    surround : str, default "average"
        ``"average"``, ``"dim"`` or ``"dark"`` (:data:`SURROUNDS`).
    discount_illuminant : bool, default True
        ``True``: complete adaptation, D = 1 (as CIE 224 prescribes); else D from F and L_A.

    Returns
    -------
    numpy.ndarray, shape (..., 3)
        J', a', b'.

    References
    ----------
    M. R. Luo, G. Cui, C. Li, Color Res. Appl. 31, 320–330 (2006) (CAM02-UCS).

    Examples
    --------
    >>> cam02ucs_jab([19.31, 23.93, 10.14], [98.88, 90.0, 32.03], 200.0, 18.0).round(3).tolist()
    [61.122, -27.426, -5.769]
    """
    return np.stack(cam02ucs_planes(*_channels(XYZ100, white_XYZ100), L_A, Y_b, surround, discount_illuminant),
                    axis=-1)


def cam02ucs(jmh: JMh) -> np.ndarray:
    """CAM02-UCS J', a', b' ``(..., 3)`` from CIECAM02 J, M, h.

    Parameters
    ----------
    jmh : JMh
        CIECAM02 lightness J, colourfulness M and hue angle h (degrees), from
        :func:`ciecam02_jmh`.

    Returns
    -------
    numpy.ndarray, shape (..., 3)
        ``J' = 1.7 J / (1 + 0.007 J)``, ``M' = ln(1 + 0.0228 M) / 0.0228``, ``a' = M' cos h``,
        ``b' = M' sin h``.

    References
    ----------
    M. R. Luo, G. Cui, C. Li, Color Res. Appl. 31, 320–330 (2006) (CAM02-UCS).

    Examples
    --------
    >>> cam02ucs(JMh(np.array(50.0), np.array(0.0), np.array(0.0))).round(4).tolist()
    [62.963, 0.0, 0.0]
    """
    J, M, h = jmh
    M_prime = np.log1p(0.0228 * M) / 0.0228
    radians = np.radians(h)
    return np.stack([1.7 * J / (1.0 + 0.007 * J), M_prime * np.cos(radians), M_prime * np.sin(radians)], axis=-1)
