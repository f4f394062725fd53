"""RGB spaces: the linear map between CIE XYZ and a display's drive values, plus its transfer.

An :class:`RGBSpace` is defined either by the chromaticities of its primaries and white
(Zawischa, seed 000, eqs. 13-19) or by the measured tristimulus values of its three primaries
at full drive, whose sum is the white (Sällström, seed 002, STEP 2 and Appendix).

Scale: ``matrix_to_XYZ @ rgb_linear`` gives XYZ on the scale of ``white_XYZ``. For spaces made
from chromaticities the white has Y = 100 (``XYZ100``: Y = 100 is the display's white at full
drive). A space made from measured primaries keeps the measurement's scale (SPECTRA's 7000 K
monitor: white Y = 106.834), so that its ``matrix_from_XYZ`` is the seed's ``matris.d``.

References
----------
D. Zawischa, How to calculate and render colours -- thin films as an example, eqs. 13-19.
P. Sällström (1999), USIP Report 99-05, STEP 2 and Appendix (phosphor table, matris.d/.equ).
IEC 61966-2-1:1999 (sRGB); SMPTE EG 432-1:2010 and Apple Display P3; Adobe RGB (1998) Color
Image Encoding (2005); ITU-R BT.2020-2 (2015).
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cache

import numpy as np

from ..errors import ColorimetryError
from ..registry import Registry
from .transfer import Transfer, spectra_excitation_table
from .transfer import transfer as _transfer

__all__ = ["RGBSpace", "rgb_space", "rgb_space_names", "SPECTRA_PHOSPHORS_XYZ"]

#: Measured XYZ of SPECTRA's monitor phosphors at full drive, columns R, G, B (seed 002,
#: Appendix table; rows X, Y, Z; "formally adjusted to a correlated colour temperature of 7000 K").
SPECTRA_PHOSPHORS_XYZ = np.array(
    [
        [44.68, 34.08, 20.12],
        [24.81, 73.16, 8.864],
        [2.586, 13.02, 105.5],
    ]
)
SPECTRA_PHOSPHORS_XYZ.setflags(write=False)


def _xy_pair(value, argument: str) -> np.ndarray:
    xy = np.asarray(value, dtype=float)
    if xy.shape != (2,) or not np.all(np.isfinite(xy)) or xy[1] <= 0 or xy.sum() > 1 + 1e-12:
        raise ColorimetryError(
            f"{argument} must be a chromaticity (x, y) with y > 0 and x + y <= 1, got {value!r}"
        )
    return xy


def _xyz_triple(value, argument: str) -> np.ndarray:
    xyz = np.asarray(value, dtype=float)
    if xyz.shape != (3,) or not np.all(np.isfinite(xyz)):
        raise ColorimetryError(f"{argument} must be three finite numbers X, Y, Z, got {value!r}")
    return xyz


def _readonly(a: np.ndarray) -> np.ndarray:
    a = np.array(a, dtype=float)
    a.setflags(write=False)
    return a


@dataclass(frozen=True, eq=False)
class RGBSpace:
    """A linear-light RGB space with a transfer function.

    Use :meth:`from_chromaticities` or :meth:`from_primaries_XYZ` to build one, or
    :func:`rgb_space` for a built-in one.

    Attributes
    ----------
    name : str
        The space's name, shown in reports and the app.
    matrix_to_XYZ : ndarray (3, 3)
        Columns are the XYZ of the red, green and blue primaries at full drive;
        ``XYZ = matrix_to_XYZ @ rgb_linear``.
    matrix_from_XYZ : ndarray (3, 3)
        Its inverse; ``rgb_linear = matrix_from_XYZ @ XYZ``.
    white_XYZ : ndarray (3,)
        XYZ of R = G = B = 1, the sum of the primaries' columns.
    transfer : transfer object
        See :mod:`spectrocolor.display.transfer`.

    Examples
    --------
    >>> srgb = rgb_space("sRGB")
    >>> srgb.primaries_xy.tolist(), srgb.white_xy.round(4).tolist()
    ([[0.64, 0.33], [0.3, 0.6], [0.15, 0.06]], [0.3127, 0.329])
    >>> srgb.luminance_row.round(4).tolist()  # Y of R, G, B at full drive (XYZ100)
    [21.2639, 71.5169, 7.2192]
    """

    name: str
    matrix_to_XYZ: np.ndarray
    matrix_from_XYZ: np.ndarray
    transfer: Transfer

    @property
    def white_XYZ(self) -> np.ndarray:
        """XYZ of full drive on all three channels, shape (3,)."""
        return self.matrix_to_XYZ.sum(axis=1)

    @property
    def white_xy(self) -> np.ndarray:
        """Chromaticity (x, y) of the white, shape (2,)."""
        w = self.white_XYZ
        return w[:2] / w.sum()

    @property
    def primaries_xy(self) -> np.ndarray:
        """Chromaticities of the red, green and blue primaries, shape (3, 2) (rows R, G, B)."""
        cols = self.matrix_to_XYZ.T
        return cols[:, :2] / cols.sum(axis=1, keepdims=True)

    @property
    def luminance_row(self) -> np.ndarray:
        """Y of each primary at full drive (Zawischa's Y_R, Y_G, Y_B), shape (3,)."""
        return self.matrix_to_XYZ[1]

    def rgb_linear_from_XYZ(self, XYZ) -> np.ndarray:
        """``(..., 3)`` XYZ (this space's scale) -> ``(..., 3)`` linear RGB (may leave 0-1).

        Parameters
        ----------
        XYZ : array_like, shape (..., 3)
            Tristimulus values on this space's scale (XYZ100 for the built-in spaces, whose
            white has Y = 100).

        Returns
        -------
        numpy.ndarray, shape (..., 3)
            Linear RGB, 1 = full drive; values outside 0–1 are out of gamut and are kept.

        Examples
        --------
        >>> srgb = rgb_space("sRGB")
        >>> srgb.rgb_linear_from_XYZ(srgb.white_XYZ).round(6).tolist()
        [1.0, 1.0, 1.0]
        >>> srgb.rgb_linear_from_XYZ([18.0, 50.0, 10.0]).round(3).tolist()  # a green outside sRGB
        [-0.235, 0.768, 0.014]
        """
        return np.asarray(XYZ, dtype=float) @ self.matrix_from_XYZ.T

    def XYZ_from_rgb_linear(self, rgb_linear) -> np.ndarray:
        """``(..., 3)`` linear RGB -> ``(..., 3)`` XYZ on this space's scale.

        Parameters
        ----------
        rgb_linear : array_like, shape (..., 3)
            Linear RGB, 1 = full drive.

        Returns
        -------
        numpy.ndarray, shape (..., 3)
            XYZ on this space's scale (XYZ100 for the built-in spaces).

        Examples
        --------
        >>> rgb_space("sRGB").XYZ_from_rgb_linear([1.0, 0.0, 0.0]).round(4).tolist()
        [41.2391, 21.2639, 1.9331]
        """
        return np.asarray(rgb_linear, dtype=float) @ self.matrix_to_XYZ.T

    @classmethod
    def from_primaries_XYZ(
        cls, red_XYZ, green_XYZ, blue_XYZ, transfer="srgb", name: str = "custom"
    ) -> RGBSpace:
        """A space from the measured XYZ of its primaries at full drive (seed 002, STEP 2).

        The white is their sum; the scale of the XYZ values is kept as given.

        Parameters
        ----------
        red_XYZ, green_XYZ, blue_XYZ : array_like, shape (3,)
            XYZ of each primary at full drive, on the scale wanted for the space (seed 002's
            phosphor measurements are in cd/m²-like units with the white near Y = 107).
        transfer : str, float or transfer object, default "srgb"
            A name in :data:`~spectrocolor.display.transfer.TRANSFERS`, a gamma number or a transfer
            object (see :func:`spectrocolor.transfer`).
        name : str, default "custom"
            The space's name.

        Returns
        -------
        RGBSpace
            ``matrix_to_XYZ`` has the three XYZ as columns.

        Raises
        ------
        ColorimetryError
            For malformed XYZ, linearly dependent primaries or an unknown transfer.

        References
        ----------
        Seed 002 (Sällström, SPECTRA), STEP 2: the monitor matrix from phosphor XYZ.

        Examples
        --------
        >>> s = RGBSpace.from_primaries_XYZ([44.68, 24.81, 2.586], [34.08, 73.16, 13.02],
        ...                                 [20.12, 8.864, 105.5])
        >>> round(float(s.matrix_from_XYZ[0, 0]), 5)   # seed 002's matris.d: +0.02994
        0.02994
        """
        to_xyz = np.column_stack(
            [
                _xyz_triple(red_XYZ, "red_XYZ"),
                _xyz_triple(green_XYZ, "green_XYZ"),
                _xyz_triple(blue_XYZ, "blue_XYZ"),
            ]
        )
        det = np.linalg.det(to_xyz)
        if not np.isfinite(det) or abs(det) < 1e-12 * np.abs(to_xyz).max() ** 3:
            raise ColorimetryError(
                "red_XYZ, green_XYZ and blue_XYZ must be linearly independent (they span no space)"
            )
        return cls(
            name=name,
            matrix_to_XYZ=_readonly(to_xyz),
            matrix_from_XYZ=_readonly(np.linalg.inv(to_xyz)),
            transfer=_transfer(transfer),
        )

    @classmethod
    def from_chromaticities(
        cls,
        red_xy,
        green_xy,
        blue_xy,
        white_xy,
        transfer="srgb",
        name: str = "custom",
        white_Y: float = 100.0,
    ) -> RGBSpace:
        """A space from primary and white chromaticities (seed 000, eqs. 13-19).

        Each primary's XYZ is ``u_i (x_i, y_i, 1 - x_i - y_i)``; the strengths ``u_i`` solve
        R + G + B = W with the white's XYZ = ``white_Y * (x_w/y_w, 1, z_w/y_w)``.

        Parameters
        ----------
        red_xy, green_xy, blue_xy : array_like, shape (2,)
            CIE 1931 chromaticities (x, y) of the primaries.
        white_xy : array_like, shape (2,)
            Chromaticity of the white (R = G = B = 1), inside the primaries' triangle.
        transfer : str, float or transfer object, default "srgb"
            A transfer name, a gamma number or a transfer object (see :func:`spectrocolor.transfer`).
        name : str, default "custom"
            The space's name.
        white_Y : float, default 100.0
            Luminance of the white; 100 gives the ``XYZ100`` scale.

        Returns
        -------
        RGBSpace
            The space; its white has XYZ ``white_Y * (x_w/y_w, 1, z_w/y_w)``.

        Raises
        ------
        ColorimetryError
            For malformed chromaticities, collinear primaries, a white outside their triangle,
            a ``white_Y`` that is not positive, or an unknown transfer.

        References
        ----------
        Seed 000 (Zawischa), eqs. 13–19; IEC 61966-2-1 for the sRGB primaries used below.

        Examples
        --------
        >>> mine = RGBSpace.from_chromaticities((0.64, 0.33), (0.30, 0.60), (0.15, 0.06), (0.3127, 0.3290))
        >>> mine.matrix_to_XYZ.round(4).tolist()
        [[41.2391, 35.7584, 18.0481], [21.2639, 71.5169, 7.2192], [1.9331, 11.9195, 95.0532]]
        """
        prim = np.array(
            [
                _xy_pair(red_xy, "red_xy"),
                _xy_pair(green_xy, "green_xy"),
                _xy_pair(blue_xy, "blue_xy"),
            ]
        )
        white = _xy_pair(white_xy, "white_xy")
        if not np.isfinite(white_Y) or white_Y <= 0:
            raise ColorimetryError(f"white_Y must be a positive number, got {white_Y!r}")
        columns = np.column_stack([prim[:, 0], prim[:, 1], 1 - prim.sum(axis=1)]).T
        if abs(np.linalg.det(columns)) < 1e-12:
            raise ColorimetryError("red_xy, green_xy and blue_xy must not lie on one line")
        white_XYZ = white_Y * np.array([white[0], white[1], 1 - white.sum()]) / white[1]
        strengths = np.linalg.solve(columns, white_XYZ)
        if np.any(strengths <= 0):
            raise ColorimetryError(
                f"white_xy {tuple(white)} must lie inside the triangle of the primaries"
            )
        red, green, blue = (columns * strengths).T
        return cls.from_primaries_XYZ(red, green, blue, transfer=transfer, name=name)

    def __repr__(self) -> str:
        return f"RGBSpace({self.name!r}, white_xy={np.round(self.white_xy, 4).tolist()})"


_D65_XY = (0.3127, 0.3290)


def _spectra_7000k() -> RGBSpace:
    p = SPECTRA_PHOSPHORS_XYZ
    return RGBSpace.from_primaries_XYZ(
        p[:, 0], p[:, 1], p[:, 2], transfer=spectra_excitation_table(), name="SPECTRA 7000K"
    )


def _spectra_equal_energy() -> RGBSpace:
    p = SPECTRA_PHOSPHORS_XYZ
    xy = (p[:2] / p.sum(axis=0)).T
    return RGBSpace.from_chromaticities(
        xy[0], xy[1], xy[2], (1 / 3, 1 / 3), transfer=spectra_excitation_table(),
        name="SPECTRA equal-energy",
    )


def _srgb() -> RGBSpace:
    return RGBSpace.from_chromaticities((0.64, 0.33), (0.30, 0.60), (0.15, 0.06), _D65_XY, transfer="srgb", name="sRGB")


def _display_p3() -> RGBSpace:
    return RGBSpace.from_chromaticities(
        (0.680, 0.320), (0.265, 0.690), (0.150, 0.060), _D65_XY, transfer="srgb", name="Display P3"
    )


def _adobe_rgb() -> RGBSpace:
    return RGBSpace.from_chromaticities(
        (0.64, 0.33), (0.21, 0.71), (0.15, 0.06), _D65_XY, transfer="adobe rgb", name="Adobe RGB (1998)"
    )


def _rec_2020() -> RGBSpace:
    return RGBSpace.from_chromaticities(
        (0.708, 0.292), (0.170, 0.797), (0.131, 0.046), _D65_XY, transfer="bt.2020", name="Rec. 2020"
    )


#: The built-in RGB spaces: name → builder (called once, on first use).
RGB_SPACES = Registry("space", "a built-in RGB space")
RGB_SPACES.add("sRGB", _srgb, "IEC 61966-2-1: Rec. 709 primaries, D65 white, the sRGB curve")
RGB_SPACES.add("Display P3", _display_p3, "DCI-P3 primaries, D65 white, the sRGB curve", aliases=("p3",))
RGB_SPACES.add(
    "Adobe RGB (1998)", _adobe_rgb, "Adobe RGB (1998): wider greens, D65 white, gamma 563/256",
    aliases=("adobe rgb",),
)
RGB_SPACES.add(
    "Rec. 2020", _rec_2020, "ITU-R BT.2020 primaries, D65 white, the BT.2020 curve",
    aliases=("rec.2020", "rec2020", "bt.2020"),
)
RGB_SPACES.add(
    "SPECTRA 7000K", _spectra_7000k, "seed 002's measured monitor (matris.d, white ≈ 7000 K, 64-level c.dat)",
    aliases=("spectra",),
)
RGB_SPACES.add(
    "SPECTRA equal-energy", _spectra_equal_energy,
    "seed 002's phosphors with the equal-energy white (matris.equ): X = Y = Z drives R = G = B",
    aliases=("spectra equal energy",),
)


def rgb_space_names() -> tuple[str, ...]:
    """Canonical names of the built-in RGB spaces (the names of :data:`RGB_SPACES`).

    Returns
    -------
    tuple of str
        The names :func:`rgb_space` accepts (aliases such as ``"p3"`` are accepted too).

    Examples
    --------
    >>> rgb_space_names()[:4]
    ('sRGB', 'Display P3', 'Adobe RGB (1998)', 'Rec. 2020')
    """
    return RGB_SPACES.names()


@cache
def _built(name: str) -> RGBSpace:
    return RGB_SPACES.get(name)()


def rgb_space(name) -> RGBSpace:
    """A built-in RGB space by name (case-insensitive), or an :class:`RGBSpace` unchanged.

    Parameters
    ----------
    name : str or RGBSpace
        ``"sRGB"``, ``"Display P3"``, ``"Adobe RGB (1998)"``, ``"Rec. 2020"``,
        ``"SPECTRA 7000K"`` (seed 002's measured monitor, transfer = its 64-level ``c.dat``),
        ``"SPECTRA equal-energy"`` (``matris.equ``: the same phosphor chromaticities with the
        equal-energy white x = y = 1/3 at Y = 100, so X = Y = Z = 100 drives R = G = B = 1).

    Returns
    -------
    RGBSpace
        The space (built once and cached; its matrices are read-only).

    Raises
    ------
    ColorimetryError
        For a name that is not a built-in space or alias.

    References
    ----------
    IEC 61966-2-1:1999 (sRGB); SMPTE EG 432-1 (Display P3); Adobe RGB (1998) Color Image
    Encoding; ITU-R BT.2020; seed 002 (SPECTRA's ``matris.d`` and ``matris.equ``).

    Examples
    --------
    >>> rgb_space("display p3")
    RGBSpace('Display P3', white_xy=[0.3127, 0.329])
    """
    if isinstance(name, RGBSpace):
        return name
    return _built(RGB_SPACES.canonical(name))
