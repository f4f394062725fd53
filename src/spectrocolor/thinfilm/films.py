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
    thickness_nm : array_like, shape (...)
        Film thickness in nm (non-negative).
    wavelengths_nm : array_like, shape (K,)
        Vacuum wavelengths in nm, within 182-1129 nm.
    angle_deg : array_like, keyword-only, default 0.0
        Angle of incidence in air, degrees in [0, 90), as :func:`~spectrocolor.thinfilm.optics.thin_film`.
    polarisation : str, keyword-only, default "unpolarised"
        ``"s"``, ``"p"`` or ``"unpolarised"``.

    Returns
    -------
    FilmOptics
        Reflectance and transmittance (0–1), shape ``(..., K)``.

    Raises
    ------
    SpectrumError
        As :func:`~spectrocolor.thinfilm.optics.thin_film`, and for wavelengths outside the
        water model's 182–1129 nm.

    References
    ----------
    Seed 000 (Zawischa); Daimon & Masumura, Appl. Opt. 46, 3811 (2007) (index of water).

    Examples
    --------
    >>> from spectrocolor import wavelength_grid
    >>> optics = soap_film([0.0, 100.0, 300.0], wavelength_grid(380, 780, 5))
    >>> optics.reflectance.shape, float(optics.reflectance[0].max())  # no film, no reflection
    ((3, 81), 0.0)
    """
    return thin_film(thickness_nm, wavelengths_nm, water(), ambient=1.0, substrate=1.0,
                     angle_deg=angle_deg, polarisation=polarisation)


def oil_on_water(thickness_nm, wavelengths_nm, *, oil: Medium | None = None, angle_deg=0.0,
                 polarisation: str = "unpolarised") -> FilmOptics:
    """An oil film floating on deep water, seen from the air (air | oil | water).

    ``oil`` defaults to :func:`~spectrocolor.thinfilm.media.typical_oil` (n_d = 1.47).

    Parameters
    ----------
    thickness_nm : array_like, shape (...)
        Oil film thickness in nm (non-negative).
    wavelengths_nm : array_like, shape (K,)
        Vacuum wavelengths in nm, within the oil's and water's ranges (350–1000 nm for the default
        oil); see :term:`wavelength grid`.
    oil : Medium, keyword-only, optional
        The oil; default the illustrative typical oil (Cauchy, n_d = 1.470, V_d = 50).
    angle_deg : array_like, keyword-only, default 0.0
        Angle of incidence in air, degrees in [0, 90).
    polarisation : str, keyword-only, default "unpolarised"
        ``"s"``, ``"p"`` or ``"unpolarised"``.

    Returns
    -------
    FilmOptics
        Reflectance and transmittance (into the water), shape ``(..., K)``.

    Raises
    ------
    SpectrumError
        As :func:`~spectrocolor.thinfilm.optics.thin_film`.

    Examples
    --------
    >>> oil_on_water(300.0, [550.0]).reflectance.round(4).tolist()
    [0.0528]
    """
    return thin_film(thickness_nm, wavelengths_nm, oil or typical_oil(), ambient=1.0,
                     substrate=water(), angle_deg=angle_deg, polarisation=polarisation)


def film_on_glass(thickness_nm, wavelengths_nm, film, *, glass: Medium | None = None,
                  glass_thickness_nm: float | None = None, angle_deg=0.0,
                  polarisation: str = "unpolarised") -> FilmOptics:
    """A coating on glass seen from the air (air | film | glass [| air]).

    Parameters
    ----------
    thickness_nm : array_like, shape (...)
        Coating thickness in nm (non-negative).
    wavelengths_nm : array_like, shape (K,)
        Vacuum wavelengths in nm.
    film : Medium, complex or array_like, shape (K,)
        Film medium (Medium, number, or ``(K,)`` array; complex for absorbing films).
    glass : Medium, keyword-only, optional
        Substrate, default N-BK7.
    glass_thickness_nm : float, keyword-only, optional
        ``None``: semi-infinite glass (reflection from the front only). A thickness (e.g.
        ``1e6`` for 1 mm): a glass plate with air behind it, its back-surface reflection added
        incoherently.
    angle_deg : array_like, keyword-only, default 0.0
        Angle of incidence in air, degrees in [0, 90).
    polarisation : str, keyword-only, default "unpolarised"
        ``"s"``, ``"p"`` or ``"unpolarised"``.

    Returns
    -------
    FilmOptics
        Reflectance and transmittance, shape ``(..., K)``.

    Raises
    ------
    SpectrumError
        As :func:`~spectrocolor.thinfilm.optics.stack_optics`.

    Examples
    --------
    >>> film_on_glass(100.0, [552.0], 1.38).reflectance.round(4).tolist()
    [0.0127]
    >>> film_on_glass(100.0, [552.0], 1.38, glass_thickness_nm=1e6).reflectance.round(4).tolist()
    [0.054]
    """
    return stack_optics(
        _as_thickness_column(thickness_nm), wavelengths_nm, [film], ambient=1.0,
        substrate=glass or bk7(), angle_deg=angle_deg, polarisation=polarisation,
        substrate_thickness_nm=glass_thickness_nm, exit_medium=constant(1.0),
    )


def _as_thickness_column(thickness_nm):
    return np.asarray(thickness_nm, dtype=float)[..., None]
