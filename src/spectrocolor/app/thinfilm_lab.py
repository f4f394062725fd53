"""The explorer's thin-film lab: every number of the page from :mod:`spectrocolor.thinfilm`.

For one film (medium, model, angle of incidence) under one light, the page receives a table over
thickness 0-``max_thickness_nm`` in 1 nm steps: the reflectance spectrum (380-780 nm, 5 nm), the
colour's XYZ, xy and display codes. Moving the thickness slider or animating a draining film is
then a lookup in that table, so it repaints in the same frame, and every value shown is the
library's. The page asks for a new table only when the film, the model, the angle or the light
changes.

Models (seed 000 and beyond):

``two-beam``
    Zawischa's eq. (6): the first two reflected beams, relative factor ``1 + β² − 2β cos(2πs/λ)``,
    ``s`` the optical path difference ``2 d √(n² − sin²θ)`` at the film's index at 560 nm. For the
    soap film β = 0.95 as in the seed; for the other films β = −r₂/r₁ from the Fresnel amplitudes
    of the two surfaces at 560 nm, normal incidence (negative for a low-index coating on glass,
    whose two reflections both change the phase). Not a reflectance: the colours are scaled so
    the brightest is full white, as the seed does.
``airy``
    The exact single film (all multiple reflections, Fresnel coefficients of the real media,
    unpolarised light), on a semi-infinite substrate.
``matrix``
    The characteristic-matrix (transfer-matrix) stack; for a coating on glass it adds the glass
    plate's back surface (1 mm, incoherent), which the Airy film on semi-infinite glass leaves
    out — the difference is the light reflected by the back of the plate.

References
----------
D. Zawischa, "How to calculate and render colours – thin films as an example" (seed 000).
O. S. Heavens, *Optical Properties of Thin Solid Films* (Dover, 1991), ch. 4 (matrix method).
"""

from __future__ import annotations

import numpy as np

from ..errors import ColorimetryError, SpectrumError
from ..illuminants import illuminant_label, resolve_illuminant
from ..registry import Registry

WAVELENGTHS_NM = np.arange(380.0, 781.0, 5.0)
THICKNESS_STEP_NM = 1.0
MAX_THICKNESS_NM = 1500.0
TWO_BEAM_BETA = 0.95
GLASS_PLATE_NM = 1.0e6  # 1 mm glass for the matrix model's back surface
DEFAULT_LIGHT = "blackbody:6504"  # seed 000's light


def _soap(thickness_nm, angle_deg, model):
    from ..thinfilm.media import water
    from ..thinfilm.optics import stack_optics, thin_film

    if model == "matrix":
        return stack_optics(thickness_nm[:, None], WAVELENGTHS_NM, [water()], angle_deg=angle_deg)
    return thin_film(thickness_nm, WAVELENGTHS_NM, water(), angle_deg=angle_deg)


def _oil(thickness_nm, angle_deg, model):
    from ..thinfilm.media import typical_oil, water
    from ..thinfilm.optics import stack_optics, thin_film

    if model == "matrix":
        return stack_optics(thickness_nm[:, None], WAVELENGTHS_NM, [typical_oil()], substrate=water(),
                            angle_deg=angle_deg)
    return thin_film(thickness_nm, WAVELENGTHS_NM, typical_oil(), substrate=water(), angle_deg=angle_deg)


def _coating(index: float):
    def film(thickness_nm, angle_deg, model):
        from ..thinfilm.films import film_on_glass

        plate = GLASS_PLATE_NM if model == "matrix" else None
        return film_on_glass(thickness_nm, WAVELENGTHS_NM, index, glass_thickness_nm=plate, angle_deg=angle_deg)

    return film


def _index_at_560(medium: str) -> tuple[float, float]:
    """(film index, substrate index) at 560 nm: the two-beam model's single index."""
    from ..thinfilm.media import bk7, typical_oil, water

    if medium == "soap":
        return float(np.real(water().refractive_index([560.0])[0])), 1.0
    if medium == "oil":
        return float(np.real(typical_oil().refractive_index([560.0])[0])), 1.33
    return FILMS.get(medium)[1], float(np.real(bk7().refractive_index([560.0])[0]))


#: The films of the lab: name → (optics function, coating index or None), with descriptions.
FILMS = Registry("film", "a film of the thin-film lab", SpectrumError)
FILMS.add("soap", (_soap, None), "soap film: water (Daimon & Masumura 2007) in air, both sides")
FILMS.add("oil", (_oil, None), "oil on water: a film of n_d = 1.47 floating on deep water")
FILMS.add("mgf2", (_coating(1.38), 1.38), "MgF₂ coating (n = 1.38) on N-BK7 glass: an anti-reflection layer")
FILMS.add("tio2", (_coating(2.40), 2.40), "TiO₂ coating (n = 2.40) on N-BK7 glass: a high-index layer")

#: The optical models of the lab.
MODELS = Registry("model", "a thin-film model", SpectrumError)
MODELS.add("two-beam", "two-beam", "Zawischa's two-beam interference (β = 0.95), relative")
MODELS.add("airy", "airy", "exact single film: all multiple reflections (Airy), semi-infinite substrate")
MODELS.add("matrix", "matrix", "transfer-matrix stack; coatings on a 1 mm glass plate with its back surface")


def reflectance_table(film: str, model: str, angle_deg: float, max_thickness_nm: float = MAX_THICKNESS_NM):
    """Reflectance factors of ``film`` at thickness 0, 1, …, ``max_thickness_nm`` nm.

    Parameters
    ----------
    film : str
        A name in :data:`FILMS`.
    model : str
        A name in :data:`MODELS`.
    angle_deg : float
        Angle of incidence in air, degrees, 0 ≤ θ < 89.
    max_thickness_nm : float
        The table's largest thickness, nm (1-5000).

    Returns
    -------
    thickness_nm : ndarray, shape (N,)
    reflectance : ndarray, shape (N, K)
        On :data:`WAVELENGTHS_NM`; for ``"two-beam"`` the relative factor of seed 000's eq. (6).

    Examples
    --------
    >>> d, R = reflectance_table("soap", "airy", 0.0, max_thickness_nm=10)
    >>> d.tolist()[:3], R.shape
    ([0.0, 1.0, 2.0], (11, 81))
    >>> float(R[0].max()) < 1e-12   # no film, no reflection
    True
    """
    film = FILMS.canonical(film)
    optics_of, _ = FILMS.get(film)
    model = MODELS.canonical(model)
    angle = float(angle_deg)
    if not (np.isfinite(angle) and 0.0 <= angle < 89.0):
        raise SpectrumError(f"angle_deg: expected 0 <= angle < 89 degrees, got {angle_deg!r}")
    top = float(max_thickness_nm)
    if not (np.isfinite(top) and 1.0 <= top <= 5000.0):
        raise SpectrumError(f"max_thickness_nm: expected 1-5000 nm, got {max_thickness_nm!r}")
    thickness_nm = np.arange(0.0, top + 0.5 * THICKNESS_STEP_NM, THICKNESS_STEP_NM)
    if model == "two-beam":
        from ..thinfilm.optics import optical_path_difference, two_beam_reflectance

        n_film, n_substrate = _index_at_560(film)
        front, back = (1.0 - n_film) / (1.0 + n_film), (n_film - n_substrate) / (n_film + n_substrate)
        beta = TWO_BEAM_BETA if film == "soap" else -back / front
        opd = optical_path_difference(thickness_nm, n_film, angle)
        return thickness_nm, two_beam_reflectance(opd, WAVELENGTHS_NM, beta)
    return thickness_nm, np.asarray(optics_of(thickness_nm, angle, model).reflectance)


def thinfilm_lab(film: str = "soap", model: str = "airy", angle_deg: float = 0.0, illuminant=DEFAULT_LIGHT,
                 observer: str = "1931", display: str = "sRGB", max_thickness_nm: float = MAX_THICKNESS_NM) -> dict:
    """Everything the lab page shows for one film under one light, as JSON-ready lists.

    Parameters
    ----------
    film, model, angle_deg, max_thickness_nm
        As :func:`reflectance_table`.
    illuminant : str or float
        The lab's light, a name or a temperature (default ``"blackbody:6504"``, seed 000's light);
        see :term:`illuminant`.
    observer : str
        An observer name (default CIE 1931 2°).
    display : str
        A built-in RGB space.

    Returns
    -------
    dict
        ``wavelengths_nm`` (K), ``thickness_nm`` (N), ``reflectance`` (N × K, 6 decimals),
        ``XYZ`` (N × 3, relative to the perfect reflector), ``xy`` (N × 2), ``rgb8`` (N × 3, the
        colours scaled so the brightest is full white, luminance-preserving gamut handling, seed
        000), ``locus_xy`` (the spectral locus), ``white_xy``, and the names used.

    Examples
    --------
    >>> lab = thinfilm_lab(max_thickness_nm=5)
    >>> lab["rgb8"][0]                    # no film: black
    [0, 0, 0]
    >>> len(lab["thickness_nm"]), lab["illuminant"]
    (6, 'blackbody 6504 K')
    """
    from ..chromaticity import spectral_locus
    from ..colorimetry import white_point
    from ..coordinates import xy as chromaticity
    from ..spectrum import Spectrum
    from ..thinfilm.colour import film_colours

    light = resolve_illuminant(illuminant)
    if light is None or not light.cacheable:
        raise ColorimetryError(
            f"illuminant: the lab takes a named light (e.g. 'D65', 'blackbody:6504'), got {illuminant!r:.60}"
        )
    thickness_nm, reflectance = reflectance_table(film, model, angle_deg, max_thickness_nm)
    colours = film_colours(Spectrum(WAVELENGTHS_NM, reflectance), illuminant=light, observer=observer,
                           exposure="global-max", space=display, gamut="preserve-luminance")
    xy = np.nan_to_num(colours.xy, nan=-1.0)  # black (no film) has no chromaticity: -1 marks it
    locus = spectral_locus(observer)
    return {
        "film": FILMS.canonical(film), "model": MODELS.canonical(model), "angle_deg": float(angle_deg),
        "illuminant": illuminant_label(light), "observer": str(observer), "display": str(display),
        "wavelengths_nm": WAVELENGTHS_NM.tolist(),
        "thickness_nm": thickness_nm.tolist(),
        "reflectance": np.round(reflectance, 6).tolist(),
        "XYZ": np.round(colours.XYZ100, 6).tolist(),
        "xy": np.round(xy, 6).tolist(),
        "rgb8": colours.rgb8.astype(int).tolist(),
        "locus_xy": np.round(locus.xy, 5).tolist(),
        "white_xy": np.round(chromaticity(white_point(light, observer=observer, wavelengths_nm=WAVELENGTHS_NM)),
                             6).tolist(),
    }


def lab_options() -> dict:
    """The lab's choices with descriptions, from the registries (for the page's option lists).

    Examples
    --------
    >>> [f["name"] for f in lab_options()["films"]]
    ['soap', 'oil', 'mgf2', 'tio2']
    """
    from ..display.spaces import RGB_SPACES
    from ..illuminants import ILLUMINANTS

    return {
        "films": FILMS.options(),
        "models": MODELS.options(),
        "illuminants": [{"name": DEFAULT_LIGHT, "description": "6504 K Planckian radiator (seed 000)"},
                        *ILLUMINANTS.options()],
        "displays": RGB_SPACES.options(),
        "max_thickness_nm": MAX_THICKNESS_NM,
    }
