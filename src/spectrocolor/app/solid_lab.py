"""The explorer's object-colour solid lab: optimal colours, MacAdam limits, a display's gamut and
metamer mismatch, every number from :mod:`spectrocolor.recovery`.

The object-colour solid holds every colour a reflectance 0 ≤ ρ ≤ 1 can have under a light. The
page draws it in CIELAB (against the light's white) as stacked MacAdam limits — the optimal colours
of constant luminance factor Y — with the edges of a display's RGB cube inside it, and a section at
a chosen Y in the chromaticity diagram. For a test-colour sample it adds the metamer mismatch
region: where all the reflectances that match the sample under this light can land under a
second light.

References
----------
D. L. MacAdam, J. Opt. Soc. Am. 25, 361 (1935); C. van Trigt, J. Opt. Soc. Am. A 7, 1891 (1990);
A. D. Logvinenko, B. Funt and C. Godau, "Metamer mismatching", IEEE Trans. Image Process. 23, 34
(2014).
"""

from __future__ import annotations

from functools import lru_cache

import numpy as np

from ..errors import ColorimetryError
from ..illuminants import illuminant_label, resolve_illuminant

GRID = (380.0, 780.0, 10.0)
LEVELS_Y = tuple(float(y) for y in range(5, 100, 5))
HUES = 72
CUBE_EDGE_SAMPLES = 16


def _light(illuminant, argument: str = "illuminant") -> str:
    light = resolve_illuminant(illuminant, argument)
    if light is None or not light.cacheable:
        raise ColorimetryError(f"{argument}: the lab takes a named light (e.g. 'D65', 'A'), got {illuminant!r:.60}")
    return light.name


#: The displays the solid lab offers, a selection of :data:`~spectrocolor.display.spaces.RGB_SPACES`
#: (checked there by :func:`solid_lab_options`).
DISPLAYS = ("sRGB", "Display P3", "Adobe RGB (1998)", "Rec. 2020", "SPECTRA 7000K")


def solid_lab_options() -> dict:
    """The lab's lights and displays (from the registries).

    Examples
    --------
    >>> solid_lab_options()["displays"][:2]
    ['sRGB', 'Display P3']
    """
    from ..display.spaces import RGB_SPACES
    from ..illuminants import ILLUMINANTS

    return {"illuminants": ILLUMINANTS.names(), "displays": [RGB_SPACES.canonical(d) for d in DISPLAYS]}


def _shown(XYZ100: np.ndarray, white: np.ndarray, display: str) -> np.ndarray:
    """Display codes of colours seen under a light of white ``white`` (Bradford to the display's white)."""
    from ..display.adaptation import adapt
    from ..display.render import render
    from ..display.spaces import rgb_space

    space = rgb_space(display)
    return np.asarray(render(adapt(XYZ100, white, space.white_XYZ), space, gamut="desaturate").codes).astype(int)


@lru_cache(maxsize=8)
def solid(illuminant="D65", display: str = "sRGB") -> dict:
    """The solid as MacAdam limits at Y = 5, 10, …, 95 in CIELAB, with display codes, and the
    edges of the display's RGB cube (its colours adapted to the light's white) in CIELAB.

    Parameters
    ----------
    illuminant : str
        A named light.
    display : str
        A built-in RGB space.

    Returns
    -------
    dict
        ``levels``: [{``Y``, ``lab`` (72 × 3), ``rgb8`` (72 × 3)}]; ``cube_edges_lab``: 12 edges of
        16 points each; ``white_XYZ``; ``illuminant``; ``display``.

    Examples
    --------
    >>> s = solid("D65")
    >>> len(s["levels"]), len(s["levels"][0]["lab"]), len(s["cube_edges_lab"])
    (19, 72, 12)
    """
    from ..colorimetry import white_point
    from ..coordinates import lab
    from ..display.adaptation import adapt
    from ..display.spaces import rgb_space
    from ..recovery.optimal import macadam_limits
    from ..spectrum import wavelength_grid

    light = _light(illuminant)
    white = white_point(light, wavelengths_nm=wavelength_grid(*GRID))
    levels = []
    for Y in LEVELS_Y:
        XYZ = macadam_limits(Y, illuminant=light, observer="1931", wavelengths=GRID, samples=HUES)
        levels.append({"Y": Y, "lab": np.round(lab(XYZ, white), 3).tolist(),
                       "rgb8": _shown(XYZ, white, display).tolist()})
    space = rgb_space(display)
    t = np.linspace(0.0, 1.0, CUBE_EDGE_SAMPLES)[:, None]
    corners = np.array([[i >> 2 & 1, i >> 1 & 1, i & 1] for i in range(8)], dtype=float)
    edges = [(a, b) for a in range(8) for b in range(a + 1, 8) if np.abs(corners[a] - corners[b]).sum() == 1]
    cube = []
    for a, b in edges:
        rgb = corners[a] + t * (corners[b] - corners[a])
        to_Y100 = 100.0 / space.white_XYZ[1]  # the display's white as Y = 100, adapted to the light's white
        XYZ = adapt(space.XYZ_from_rgb_linear(rgb) * to_Y100, space.white_XYZ * to_Y100, white)
        cube.append(np.round(lab(XYZ, white), 3).tolist())
    return {"levels": levels, "cube_edges_lab": cube, "white_XYZ": np.round(white, 6).tolist(),
            "illuminant": illuminant_label(light), "display": space.name}


def section(Y: float, illuminant="D65", display: str = "sRGB") -> dict:
    """The solid's section at luminance factor ``Y`` (%) in the chromaticity diagram.

    Returns
    -------
    dict
        ``macadam_xy`` (180 × 2), ``display_xy`` (the display's primaries), ``white_xy``,
        ``locus_xy``.

    Examples
    --------
    >>> len(section(50.0)["macadam_xy"])
    180
    """
    from ..chromaticity import spectral_locus
    from ..colorimetry import white_point
    from ..coordinates import xy
    from ..display.spaces import rgb_space
    from ..recovery.optimal import macadam_limits
    from ..spectrum import wavelength_grid

    if not (np.isfinite(Y) and 0 < Y < 100):
        raise ColorimetryError(f"Y: a section needs 0 < Y < 100 (percent of the perfect white), got {Y!r}")
    light = _light(illuminant)
    white = white_point(light, wavelengths_nm=wavelength_grid(*GRID))
    return {
        "Y": float(Y),
        "macadam_xy": np.round(xy(macadam_limits(float(Y), illuminant=light, observer="1931", wavelengths=GRID,
                                                 samples=180)), 5).tolist(),
        "display_xy": np.round(rgb_space(display).primaries_xy, 5).tolist(),
        "white_xy": np.round(xy(white), 5).tolist(),
        "locus_xy": np.round(spectral_locus("1931").xy, 5).tolist(),
    }


#: The explorer's grids (400-700 nm at these steps, nm) that a hand-off's levels may be on.
EXPLORER_STEPS_NM = (10.0, 5.0, 2.0, 1.0)
#: The explorer's full level (a reflectance of 1).
EXPLORER_FULL_LEVEL = 30.0


def explorer_reflectance(levels, step_nm: float) -> np.ndarray:
    """A reflectance on the lab's grid from the explorer's levels (0-30 on 400-700 nm at ``step_nm``).

    Level 30 is a reflectance of 1. The lab's grid (380-780 nm, 10 nm) is filled by linear
    interpolation inside 400-700 nm and by the end values outside it (the explorer has no
    levels there; the eye's weights beyond 700 nm and below 400 nm are small).

    Raises
    ------
    ColorimetryError
        ``step_nm`` not one of :data:`EXPLORER_STEPS_NM`, a level count other than the grid's,
        or a level outside 0-30 or not finite.

    Examples
    --------
    >>> r = explorer_reflectance([15.0] * 31, 10.0)
    >>> r.shape, float(r.min()), float(r.max())
    ((41,), 0.5, 0.5)
    """
    from ..spectrum import wavelength_grid

    if step_nm not in EXPLORER_STEPS_NM:
        raise ColorimetryError(f"levels_step_nm: expected one of {EXPLORER_STEPS_NM} nm, got {step_nm!r}")
    bins = int(round(300.0 / step_nm)) + 1
    values = np.asarray(levels, dtype=float)
    if values.ndim != 1 or values.size != bins:
        raise ColorimetryError(f"levels: expected {bins} levels (400-700 nm at {step_nm:g} nm), "
                               f"got {values.size}")
    if not np.all(np.isfinite(values)) or values.min() < 0.0 or values.max() > EXPLORER_FULL_LEVEL:
        raise ColorimetryError("levels: expected finite levels from 0 to 30")
    own = np.linspace(400.0, 700.0, bins)
    return np.interp(wavelength_grid(*GRID), own, values / EXPLORER_FULL_LEVEL)


@lru_cache(maxsize=16)
def mismatch_of_levels(levels: tuple, step_nm: float, illuminant="D65", second_illuminant="A",
                       display: str = "sRGB") -> dict:
    """:func:`mismatch` of a sample handed over by the explorer: its levels (0-30, 400-700 nm at
    ``step_nm``; see :func:`explorer_reflectance`). ``sample`` in the answer is the text
    ``"from the explorer"``.

    Examples
    --------
    >>> region = mismatch_of_levels((15.0,) * 31, 10.0, "D65", "A")
    >>> region["sample"], len(region["region_lab"])
    ('from the explorer', 100)
    """
    return _mismatch_of(explorer_reflectance(levels, step_nm), "from the explorer", illuminant,
                        second_illuminant, display)


@lru_cache(maxsize=64)
def mismatch(sample: int, illuminant="D65", second_illuminant="A", display: str = "sRGB") -> dict:
    """Metamer mismatch region of CIE test-colour sample ``sample`` (1-14) for a change of light.

    Returns
    -------
    dict
        ``sample_xy`` and ``sample_lab`` under the second light; ``region_xy`` and
        ``region_lab`` (100 boundary colours of the region under the second light, CIELAB
        against its white); ``rgb8`` of the sample under each light; the labels.

    Examples
    --------
    >>> region = mismatch(1, "D65", "A")
    >>> len(region["region_lab"]), region["second_illuminant"]
    (100, 'A')
    """
    from ..lighting.spectra import tcs_reflectances
    from ..spectrum import wavelength_grid

    if isinstance(sample, bool) or not isinstance(sample, int | np.integer) or not 1 <= sample <= 14:
        raise ColorimetryError(f"sample: expected a CIE test-colour sample number 1-14, got {sample!r}")
    reflectance = tcs_reflectances(wavelength_grid(*GRID))[sample - 1]
    return _mismatch_of(reflectance, int(sample), illuminant, second_illuminant, display)


def _mismatch_of(reflectance: np.ndarray, sample, illuminant, second_illuminant, display) -> dict:
    """The answer of :func:`mismatch` for a reflectance on the lab's grid."""
    from ..colorimetry import weights
    from ..coordinates import lab, xy
    from ..recovery.metamers import metamer_mismatch_region
    from ..spectrum import wavelength_grid

    first, second = _light(illuminant), _light(second_illuminant, "second_illuminant")
    grid = wavelength_grid(*GRID)
    W1, W2 = weights(grid, illuminant=first), weights(grid, illuminant=second)
    XYZ1, XYZ2 = reflectance @ W1, reflectance @ W2
    region = metamer_mismatch_region(XYZ1, illuminant=first, second_illuminant=second, observer="1931",
                                     wavelengths=GRID, directions=100)
    white2 = W2.sum(axis=0)
    return {
        "sample": sample, "illuminant": illuminant_label(first), "second_illuminant": illuminant_label(second),
        "sample_xy": np.round(xy(XYZ2), 5).tolist(), "sample_lab": np.round(lab(XYZ2, white2), 3).tolist(),
        "region_xy": np.round(xy(region.boundary_XYZ100), 5).tolist(),
        "region_lab": np.round(lab(region.boundary_XYZ100, white2), 3).tolist(),
        # how far the region reaches from the sample's own colour under the second light
        "region_dEab_max": round(float(np.max(np.linalg.norm(
            lab(region.boundary_XYZ100, white2) - lab(XYZ2, white2), axis=-1))), 2),
        "rgb8_first": _shown(XYZ1[None], W1.sum(axis=0), display)[0].tolist(),
        "rgb8_second": _shown(XYZ2[None], white2, display)[0].tolist(),
    }
