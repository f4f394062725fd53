"""Chromatic adaptation between whites: von Kries-type transforms in a choice of sensor spaces.

``adapt`` maps tristimulus values seen under one white to the corresponding values under
another: ``XYZ_t = M^-1 diag(M w_t / M w_s) M XYZ_s``, where M is the sensor ("cone") matrix.
The source white maps exactly onto the target white (whites are used as given, including their
luminance).

Sensor matrices: Bradford (Lam 1985), von Kries (Hunt-Pointer-Estevez, normalised to D65),
CAT02 (CIECAM02), CAT16 (CAM16), XYZ scaling, and ``"display rgb"``: the display's own
primaries, which is SPECTRA's "adapted to the screen" variant -- ``matris.equ`` makes an
equal-energy spectrum come out as R = G = B, i.e. it scales the display's R, G, B so that the
source white becomes the display white (seed 002, "Why not include the effect of chromatic
adaptation?").

References
----------
K. M. Lam (1985), Metamerism and colour constancy, PhD thesis, University of Bradford.
N. Moroney et al. (2002), The CIECAM02 color appearance model, IS&T/SID CIC10.
C. Li et al. (2017), Comprehensive color solutions: CAM16, CAT16, and CAM16-UCS, Color Res.
Appl. 42, 703-718.
M. D. Fairchild (2013), Color Appearance Models, 3rd ed., ch. 9 (von Kries, HPE matrix).
P. Sällström (1999), USIP Report 99-05, Appendix (matris.equ).
"""

from __future__ import annotations

import numpy as np

from ..arguments import real_array
from ..coordinates import colour_array
from ..errors import ColorimetryError
from ..registry import Registry
from .spaces import rgb_space

__all__ = ["ADAPTATION_METHODS", "adaptation_matrix", "adapt"]

_SENSORS = {
    "bradford": [
        [0.8951, 0.2664, -0.1614],
        [-0.7502, 1.7135, 0.0367],
        [0.0389, -0.0685, 1.0296],
    ],
    "von kries": [
        [0.40024, 0.70760, -0.08081],
        [-0.22630, 1.16532, 0.04570],
        [0.0, 0.0, 0.91822],
    ],
    "cat02": [
        [0.7328, 0.4296, -0.1624],
        [-0.7036, 1.6975, 0.0061],
        [0.0030, 0.0136, 0.9834],
    ],
    "cat16": [
        [0.401288, 0.650173, -0.051461],
        [-0.250268, 1.204414, 0.045854],
        [-0.002079, 0.048952, 0.953127],
    ],
    "xyz scaling": np.eye(3),
}

_DESCRIPTIONS = {
    "bradford": "Bradford (Lam 1985; ICC v4's transform)",
    "von kries": "von Kries with Hunt-Pointer-Estévez cone responses",
    "cat02": "CAT02 (CIECAM02's transform)",
    "cat16": "CAT16 (CAM16's transform)",
    "xyz scaling": "scale X, Y, Z by the ratio of the whites",
}
#: The chromatic adaptation transforms: name → sensor matrix, or ``None`` for "display rgb"
#: (SPECTRA's "adapted to the screen": von Kries in the display's own RGB).
ADAPTATION_METHODS = Registry("method", "a chromatic adaptation transform")
for _name, _matrix in _SENSORS.items():
    ADAPTATION_METHODS.add(_name, np.asarray(_matrix, dtype=float), _DESCRIPTIONS[_name])
ADAPTATION_METHODS.add("display rgb", None, "von Kries in the display's linear RGB (SPECTRA, seed 002)")


def _white(value, argument: str) -> np.ndarray:
    w = real_array(value, argument, "XYZ of a white")
    if w.shape != (3,) or not np.all(np.isfinite(w)) or w[1] <= 0:
        raise ColorimetryError(f"{argument} must be XYZ of a white with Y > 0, got {value!r}")
    return w


def _sensor(method: str, space) -> np.ndarray:
    key = ADAPTATION_METHODS.canonical(method)
    if key == "display rgb":
        if space is None:
            raise ColorimetryError('method="display rgb" needs space (an RGBSpace or its name)')
        return rgb_space(space).matrix_from_XYZ
    if space is not None:
        raise ColorimetryError(f'space is used only with method="display rgb", not {method!r}')
    return ADAPTATION_METHODS.get(key)


def adaptation_matrix(
    source_white_XYZ, target_white_XYZ, method: str = "bradford", space=None
) -> np.ndarray:
    """The (3, 3) matrix A with ``XYZ_target = A @ XYZ_source``; see :func:`adapt`.

    ``A = M⁻¹ diag(M w_t / M w_s) M`` with M the sensor matrix of ``method``.

    Parameters
    ----------
    source_white_XYZ : array_like, shape (3,)
        XYZ of the white the colours are seen under (Y > 0; any scale shared with the colours).
    target_white_XYZ : array_like, shape (3,)
        XYZ of the white to adapt to (Y > 0).
    method : str, default "bradford"
        A name in :data:`ADAPTATION_METHODS`: ``"bradford"``, ``"von kries"``, ``"cat02"``,
        ``"cat16"``, ``"xyz scaling"`` or ``"display rgb"``.
    space : RGBSpace or str, optional
        The display whose linear RGB is the sensor space; only (and required) for
        ``method="display rgb"``.

    Returns
    -------
    numpy.ndarray
        A, float64, shape (3, 3); ``A @ source_white_XYZ == target_white_XYZ``.

    Raises
    ------
    ColorimetryError
        For a malformed white, an unknown method, ``space`` given or missing against the
        method, or whites that give non-positive sensor responses.

    References
    ----------
    Lam (1985) (Bradford); Moroney et al. (2002) (CAT02); Li et al. (2017) (CAT16); seed 002
    (``matris.equ``); see the module docstring.

    Examples
    --------
    >>> from spectrocolor import white_point
    >>> A = adaptation_matrix(white_point("A"), white_point("D65"))
    >>> (A @ white_point("A")).round(3).tolist()
    [95.043, 100.0, 108.88]
    """
    ws = _white(source_white_XYZ, "source_white_XYZ")
    wt = _white(target_white_XYZ, "target_white_XYZ")
    m = _sensor(method, space)
    gains = (m @ wt) / (m @ ws)
    if not np.all(np.isfinite(gains)) or np.any(gains <= 0):
        raise ColorimetryError(
            f"the whites {ws.tolist()} and {wt.tolist()} give non-positive sensor responses "
            f"under method {method!r}; they cannot be adapted"
        )
    return np.linalg.inv(m) @ (gains[:, None] * m)


def adapt(
    XYZ, source_white_XYZ, target_white_XYZ, method: str = "bradford", space=None
) -> np.ndarray:
    """Corresponding colours under another white (von Kries-type chromatic adaptation).

    Parameters
    ----------
    XYZ : array_like, shape (..., 3)
        Tristimulus values seen under the source white (any scale shared with the whites).
    source_white_XYZ, target_white_XYZ : array_like, shape (3,)
        The whites, e.g. ``white_point("A")`` and ``white_point("D65")``.
    method : {"bradford", "von kries", "cat02", "cat16", "xyz scaling", "display rgb"}
        The sensor space in which channels are scaled. ``"display rgb"`` uses the primaries of
        ``space`` (SPECTRA's "adapted to the screen").
    space : RGBSpace or str, optional
        Only for ``method="display rgb"``.

    Returns
    -------
    ndarray, shape (..., 3)
        Corresponding colours under the target white, on the scale of the input.

    Raises
    ------
    ColorimetryError
        As :func:`adaptation_matrix`, and for malformed ``XYZ``.

    References
    ----------
    Fairchild (2013), *Color Appearance Models*, ch. 9; see the module docstring.

    Examples
    --------
    >>> a = adapt([109.85, 100.0, 35.585], [109.85, 100.0, 35.585], [95.047, 100.0, 108.883])
    >>> [round(float(v), 3) for v in a]
    [95.047, 100.0, 108.883]
    """
    xyz = colour_array(XYZ, "XYZ", 3, "tristimulus values X, Y, Z")
    a = adaptation_matrix(source_white_XYZ, target_white_XYZ, method, space)
    return xyz @ a.T
