"""One-line helpers for the common films: a soap film in air, oil on water, a film on glass."""

from __future__ import annotations

import numpy as np

from .media import Medium, bk7, constant, typical_oil, water
from .optics import FilmOptics, stack_optics, thin_film


def soap_film(thickness_nm, wavelengths_nm, *, angle_deg=0.0,
              polarisation: str = "unpolarised") -> FilmOptics:
    """A free-standing soap film (water, Daimon & Masumura 2007) in air, exact single film.

    Parameters
    ----------
    thickness_nm
        Film thickness in nm, shape ``(...)``.
    wavelengths_nm
        Vacuum wavelengths in nm, shape ``(K,)``, within 182-1129 nm.
    angle_deg, polarisation
        As :func:`~spectrocolor.thinfilm.optics.thin_film`.
    """
    return thin_film(thickness_nm, wavelengths_nm, water(), ambient=1.0, substrate=1.0,
                     angle_deg=angle_deg, polarisation=polarisation)


def oil_on_water(thickness_nm, wavelengths_nm, *, oil: Medium | None = None, angle_deg=0.0,
                 polarisation: str = "unpolarised") -> FilmOptics:
    """An oil film floating on deep water, seen from the air (air | oil | water).

    ``oil`` defaults to :func:`~spectrocolor.thinfilm.media.typical_oil` (n_d = 1.47).
    """
    return thin_film(thickness_nm, wavelengths_nm, oil or typical_oil(), ambient=1.0,
                     substrate=water(), angle_deg=angle_deg, polarisation=polarisation)


def film_on_glass(thickness_nm, wavelengths_nm, film, *, glass: Medium | None = None,
                  glass_thickness_nm: float | None = None, angle_deg=0.0,
                  polarisation: str = "unpolarised") -> FilmOptics:
    """A coating on glass seen from the air (air | film | glass [| air]).

    Parameters
    ----------
    film
        Film medium (Medium, number, or ``(K,)`` array; complex for absorbing films).
    glass
        Substrate, default N-BK7.
    glass_thickness_nm
        ``None``: semi-infinite glass (reflection from the front only). A thickness (e.g.
        ``1e6`` for 1 mm): a glass plate with air behind it, its back-surface reflection added
        incoherently.
    """
    return stack_optics(
        _as_thickness_column(thickness_nm), wavelengths_nm, [film], ambient=1.0,
        substrate=glass or bk7(), angle_deg=angle_deg, polarisation=polarisation,
        substrate_thickness_nm=glass_thickness_nm, exit_medium=constant(1.0),
    )


def _as_thickness_column(thickness_nm):
    return np.asarray(thickness_nm, dtype=float)[..., None]
