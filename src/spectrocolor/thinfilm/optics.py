"""Interference optics of thin films, vectorised over thickness × angle × wavelength.

Three models, from simplest to exact:

* :func:`two_beam_reflectance` — Zawischa's two-beam model (seed 000, eqs. 6-8): only the first
  reflections at the front and back surface interfere; a parameter β < 1 stands for the weaker
  second beam. Depends only on the optical path difference ``s = 2 d n``.
* :func:`thin_film` — one film between two semi-infinite media with all multiple reflections
  (the Airy sum of Fresnel amplitudes), s, p or unpolarised light, any angle of incidence.
* :func:`stack_optics` — any stack of layers with complex indices by the characteristic
  (transfer) matrix method, optionally on a thick substrate that is treated incoherently.

Conventions: indices ``N = n + ik`` with ``k >= 0`` (fields ``exp(i(kz − ωt))``); wavelengths
are vacuum wavelengths in nm; thicknesses are physical thicknesses in nm; the angle of incidence
is in degrees, measured in the ambient medium, which must be non-absorbing. Reflectance and
transmittance are fractions of the incident power (0-1). For unpolarised light they are the
means of the s and p values.

Why this file is long: the three optical models (two-beam, single film, exact multilayer) share the
angle, admittance and polarisation helpers and are tested against each other; one module keeps those
conventions (the sign of k, s and p) in one place.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from ..arguments import real_array, real_number
from ..errors import SpectrumError
from .media import _wavelengths, refractive_index

POLARISATIONS = ("s", "p", "unpolarised")


@dataclass(frozen=True)
class FilmOptics:
    """Reflectance and transmittance of a film or stack.

    Returned by :func:`thin_film` and :func:`stack_optics`.

    Attributes
    ----------
    wavelengths_nm : numpy.ndarray, shape (K,)
        Vacuum wavelengths, nm.
    reflectance, transmittance : numpy.ndarray, shape (..., K)
        Fractions of the incident power (0-1); the leading shape is the broadcast of the
        thickness batch and the angle batch.
    polarisation : str
        ``"s"``, ``"p"`` or ``"unpolarised"``.

    Examples
    --------
    A quarter-wave MgF₂-like layer (n = 1.38, 100 nm) on glass (n = 1.5) at 552 nm reflects
    ((1.5 − 1.38²) / (1.5 + 1.38²))² = 1.41 % instead of the bare glass's 4 %:

    >>> optics = thin_film(100.0, [552.0], 1.38, substrate=1.5)
    >>> optics.reflectance.round(5).tolist(), optics.transmittance.round(5).tolist()
    ([0.01411], [0.98589])
    >>> optics.absorptance.round(6).tolist(), optics.polarisation
    ([0.0], 'unpolarised')
    """

    wavelengths_nm: np.ndarray
    reflectance: np.ndarray
    transmittance: np.ndarray
    polarisation: str

    @property
    def absorptance(self) -> np.ndarray:
        """``1 − R − T``: fraction absorbed in the layers (and a thick slab), shape ``(..., K)``."""
        return 1.0 - self.reflectance - self.transmittance

    def spectrum(self, quantity: str = "reflectance"):
        """The reflectance or transmittance as a :class:`spectrocolor.Spectrum` (0-1).

        Parameters
        ----------
        quantity : str, default "reflectance"
            ``"reflectance"`` or ``"transmittance"``.

        Returns
        -------
        Spectrum
            Values of shape ``(..., K)`` on ``wavelengths_nm``, factors 0–1 (ready for
            :func:`spectrocolor.tristimulus` with an illuminant).

        Raises
        ------
        SpectrumError
            For any other ``quantity``.

        Examples
        --------
        >>> optics = thin_film([0.0, 100.0], [500.0, 552.0, 600.0], 1.38, substrate=1.5)
        >>> optics.spectrum("reflectance").batch_shape
        (2,)
        """
        from ..spectrum import Spectrum

        if quantity not in ("reflectance", "transmittance"):
            raise SpectrumError(
                f"quantity: expected 'reflectance' or 'transmittance', got {quantity!r}"
            )
        return Spectrum(self.wavelengths_nm, getattr(self, quantity))


def _check_polarisation(polarisation: str) -> str:
    if polarisation not in POLARISATIONS:
        raise SpectrumError(
            f"polarisation: expected one of {POLARISATIONS}, got {polarisation!r}"
        )
    return polarisation


def _numbers(values, argument: str) -> np.ndarray:
    return real_array(values, argument, "numbers", SpectrumError)


def _nonnegative(values, argument: str) -> np.ndarray:
    array = _numbers(values, argument)
    if not np.all(np.isfinite(array)) or np.any(array < 0):
        bad = array[~(np.isfinite(array) & (array >= 0))].flat[0]
        raise SpectrumError(
            f"{argument}: expected finite values >= 0 (nm), got {bad!r} (array of shape {array.shape})"
        )
    return array


def _angles(angle_deg) -> np.ndarray:
    theta = _numbers(angle_deg, "angle_deg")
    if not np.all(np.isfinite(theta)) or np.any(theta < 0) or np.any(theta >= 90):
        raise SpectrumError(
            f"angle_deg: angle of incidence must be in [0, 90) degrees, got {angle_deg!r}"
        )
    return np.radians(theta)[..., None]


def _ambient(ambient, wl) -> np.ndarray:
    n0 = refractive_index(ambient, wl)
    if np.any(n0.imag != 0):
        raise SpectrumError("ambient: the incidence medium must be non-absorbing (k = 0)")
    return n0


def _normal_index(index: np.ndarray, kx: np.ndarray) -> np.ndarray:
    """``N cos θ = sqrt(N² − kx²)`` on the branch of forward (decaying) waves, Im >= 0."""
    q = np.sqrt(index.astype(complex) ** 2 - kx**2)
    return np.where((q.imag < 0) | ((q.imag == 0) & (q.real < 0)), -q, q)


def _admittance(index: np.ndarray, q: np.ndarray, polarisation: str) -> np.ndarray:
    """Tilted optical admittance in units of the vacuum admittance (s: N cos θ, p: N / cos θ)."""
    return q if polarisation == "s" else index**2 / q


def _mean_over_polarisations(compute, polarisation: str):
    if polarisation != "unpolarised":
        return compute(polarisation)
    r_s, t_s = compute("s")
    r_p, t_p = compute("p")
    return 0.5 * (r_s + r_p), 0.5 * (t_s + t_p)


def two_beam_reflectance(opd_nm, wavelengths_nm, beta: float = 0.95) -> np.ndarray:
    """Zawischa's two-beam reflectance factor ``1 + β² − 2β cos(2π s / λ)``.

    This is eq. (6) of seed 000 divided by ``α² E₀² / 2``: relative, not a reflectance
    (multiply by the single-surface reflectance α² for an absolute value).

    Parameters
    ----------
    opd_nm : array_like, shape (...)
        Optical path difference ``s`` of the two beams in nm, non-negative
        (``s = 2 d n`` at normal incidence; see :func:`optical_path_difference`).
    wavelengths_nm : array_like, shape (K,)
        Vacuum wavelengths in nm.
    beta : float, default 0.95
        Amplitude of the back-surface beam relative to the front-surface beam, ``-1 <= β <= 1``.
        Positive (seed 000's 0.95) for a free film, where one of the two reflections changes the
        phase by π; negative when both do or neither does (a low-index coating on glass): then
        the factor is ``1 + β² + 2|β| cos(2π s / λ)``. For Fresnel amplitudes ``r₁`` (front)
        and ``r₂`` (back) at normal incidence, ``β = −r₂ / r₁``.

    Returns
    -------
    ndarray, shape ``(..., K)``
        The relative reflectance, between ``(1 − |β|)²`` and ``(1 + |β|)²``.

    Raises
    ------
    SpectrumError
        For a negative or non-finite path difference, an invalid grid, or β outside [0, 1].

    References
    ----------
    D. Zawischa, "How to calculate and render colours – thin films as an example",
    ITP, Leibniz University Hannover, eqs. (6)-(8).

    Examples
    --------
    Half a wavelength of path difference is constructive (the reflection at the front surface
    has a phase jump of π), a whole wavelength destructive:

    >>> two_beam_reflectance([250.0, 500.0], [500.0]).round(4).tolist()
    [[3.8025], [0.0025]]
    """
    s = _nonnegative(opd_nm, "opd_nm")
    wl = _wavelengths(wavelengths_nm)
    if not -1 <= real_number(beta, "beta", "-1 <= beta <= 1", SpectrumError) <= 1:
        raise SpectrumError(f"beta: expected -1 <= beta <= 1, got {beta!r}")
    with np.errstate(over="ignore"):
        phase = 2.0 * np.pi * s[..., None] / wl
    if not np.all(np.isfinite(phase)):
        raise SpectrumError(f"opd_nm: path differences up to {s.max():.3g} nm overflow the phase "
                            "2 pi s / lambda; give path differences that are finite numbers of nm")
    return 1.0 + beta * beta - 2.0 * beta * np.cos(phase)


def optical_path_difference(thickness_nm, film_index: float, angle_deg=0.0,
                            ambient_index: float = 1.0) -> np.ndarray:
    """Optical path difference ``s = 2 d sqrt(n² − n₀² sin² θ₀)`` of the two first beams (nm).

    At normal incidence this is seed 000's eq. (4), ``s = 2 d n``.

    Parameters
    ----------
    thickness_nm : array_like, shape (...)
        Physical film thickness, nm (non-negative).
    film_index : float
        Real refractive index n of the film.
    angle_deg : array_like, default 0.0
        Angle of incidence in the ambient medium, degrees in [0, 90), broadcast against
        ``thickness_nm``.
    ambient_index : float, default 1.0
        Real refractive index n₀ of the ambient medium.

    Returns
    -------
    numpy.ndarray
        ``s`` in nm, the broadcast shape of ``thickness_nm`` and ``angle_deg``.

    Raises
    ------
    SpectrumError
        For a negative thickness, an angle outside [0, 90) or an index that is not a positive
        real number.

    References
    ----------
    Seed 000 (Zawischa), eq. (4); Born & Wolf, *Principles of Optics*, §7.5.

    Examples
    --------
    >>> float(optical_path_difference(100.0, 1.33)), round(float(optical_path_difference(100.0, 1.33, 30.0)), 3)
    (266.0, 246.487)
    """
    d = _nonnegative(thickness_nm, "thickness_nm")
    theta = _angles(angle_deg)[..., 0]  # radians
    n = np.float64(real_number(film_index, "film_index", "a refractive index", SpectrumError, True))
    n0 = np.float64(real_number(ambient_index, "ambient_index", "a refractive index",
                                SpectrumError, True))
    with np.errstate(over="ignore"):
        return 2.0 * d * np.sqrt(n**2 - (n0 * np.sin(theta)) ** 2)


def thin_film(thickness_nm, wavelengths_nm, film, *, ambient=1.0, substrate=1.0,
              angle_deg=0.0, polarisation: str = "unpolarised") -> FilmOptics:
    """One coherent film between two semi-infinite media, exact (Airy sum of Fresnel terms).

    ``r = (r₀₁ + r₁₂ e^{2iδ}) / (1 + r₀₁ r₁₂ e^{2iδ})`` and
    ``t = t₀₁ t₁₂ e^{iδ} / (1 + r₀₁ r₁₂ e^{2iδ})`` with ``δ = 2π d N₁ cos θ₁ / λ``.

    Parameters
    ----------
    thickness_nm : array_like, shape (...)
        Film thickness in nm (non-negative).
    wavelengths_nm : array_like, shape (K,)
        Vacuum wavelengths in nm.
    film : Medium, complex or array_like, shape (K,)
        The film's index ``n + ik`` (:class:`~spectrocolor.thinfilm.media.Medium`, a number, or
        an array sampled on ``wavelengths_nm``).
    ambient, substrate : Medium, complex or array_like, keyword-only
        The incidence medium (non-absorbing) and the medium behind the film; default 1 (air).
    angle_deg : array_like, keyword-only, default 0.0
        Angle of incidence in the ambient medium, degrees in [0, 90), broadcastable with
        ``thickness_nm``.
    polarisation : str, keyword-only, default "unpolarised"
        ``"s"``, ``"p"`` or ``"unpolarised"`` (mean of s and p).

    Returns
    -------
    FilmOptics
        Reflectance and transmittance (into the substrate) of shape ``(..., K)``.

    Raises
    ------
    SpectrumError
        For a negative thickness, an invalid grid, angle or polarisation, an absorbing ambient,
        or an index outside a medium's range of validity.

    References
    ----------
    M. Born and E. Wolf, *Principles of Optics*, 7th ed., §1.6.4 (Cambridge, 1999);
    O. S. Heavens, *Optical Properties of Thin Solid Films* (Dover, 1991), ch. 4.

    Examples
    --------
    >>> thin_film([0.0, 100.0], [552.0], 1.38, substrate=1.5).reflectance.round(5).tolist()
    [[0.04], [0.01411]]
    """
    polarisation = _check_polarisation(polarisation)
    wl = _wavelengths(wavelengths_nm)
    d = _nonnegative(thickness_nm, "thickness_nm")[..., None]
    n0 = _ambient(ambient, wl)
    n1 = refractive_index(film, wl)
    n2 = refractive_index(substrate, wl)
    kx = n0.real * np.sin(_angles(angle_deg))
    q0, q1, q2 = (_normal_index(n, kx) for n in (n0, n1, n2))
    phase = np.exp(2j * np.pi * d * q1 / wl)

    def compute(pol):
        e0, e1, e2 = (_admittance(n, q, pol) for n, q in ((n0, q0), (n1, q1), (n2, q2)))
        r01, r12 = (e0 - e1) / (e0 + e1), (e1 - e2) / (e1 + e2)
        t01, t12 = 2 * e0 / (e0 + e1), 2 * e1 / (e1 + e2)
        denominator = 1 + r01 * r12 * phase**2
        r = (r01 + r12 * phase**2) / denominator
        t = t01 * t12 * phase / denominator
        return np.abs(r) ** 2, e2.real / e0.real * np.abs(t) ** 2

    reflectance, transmittance = _mean_over_polarisations(compute, polarisation)
    return FilmOptics(wl, reflectance, transmittance, polarisation)


def thin_film_reflectance(thickness_nm, wavelengths_nm, film, **kwargs) -> np.ndarray:
    """Reflectance (0-1) of one film, shape ``(..., K)``; arguments as :func:`thin_film`.

    Parameters
    ----------
    thickness_nm : array_like, shape (...)
        Film thickness in nm.
    wavelengths_nm : array_like, shape (K,)
        Vacuum wavelengths in nm.
    film : Medium, complex or array_like, shape (K,)
        The film's index.
    **kwargs : dict
        ``ambient``, ``substrate``, ``angle_deg``, ``polarisation`` as for :func:`thin_film`.

    Returns
    -------
    numpy.ndarray, shape (..., K)
        ``thin_film(...).reflectance``.

    Raises
    ------
    SpectrumError
        As :func:`thin_film`.

    Examples
    --------
    >>> thin_film_reflectance(100.0, [552.0], 1.38, substrate=1.5).round(5).tolist()
    [0.01411]
    """
    return thin_film(thickness_nm, wavelengths_nm, film, **kwargs).reflectance


def _layer_trig(qs, thicknesses, wl):
    """``cos δ`` and ``sin δ`` of every layer, ``δ = 2π d N cos θ / λ`` (shared by s and p)."""
    out = []
    for j, q in enumerate(qs):
        e = np.exp(2j * np.pi * thicknesses[..., j, None] * q / wl)
        inverse = 1.0 / e
        out.append((0.5 * (e + inverse), -0.5j * (e - inverse)))
    return out


def _coherent_stack(eta0, etas, eta_sub, trig):
    """Amplitude r and power T of a coherent stack from characteristic matrices.

    With ``N = n + ik`` the layer matrix is ``[[cos δ, −i sin δ / η], [−i η sin δ, cos δ]]``.
    """
    m11 = m12 = m21 = m22 = None
    for eta, (c, s) in zip(etas, trig, strict=True):
        a12, a21 = -1j * s / eta, -1j * eta * s
        if m11 is None:
            m11, m12, m21, m22 = c, a12, a21, c
        else:
            m11, m12, m21, m22 = (m11 * c + m12 * a21, m11 * a12 + m12 * c,
                                  m21 * c + m22 * a21, m21 * a12 + m22 * c)
    if m11 is None:
        b, c = 1.0 + 0j, eta_sub
    else:
        b, c = m11 + m12 * eta_sub, m21 + m22 * eta_sub
    denominator = eta0 * b + c
    r = (eta0 * b - c) / denominator
    transmittance = 4 * eta0.real * eta_sub.real / np.abs(denominator) ** 2
    return r, transmittance


def stack_optics(thicknesses_nm, wavelengths_nm, layers: Sequence, *, ambient=1.0,
                 substrate=1.0, angle_deg=0.0, polarisation: str = "unpolarised",
                 substrate_thickness_nm: float | None = None,
                 exit_medium=1.0) -> FilmOptics:
    """A multilayer stack by the transfer (characteristic) matrix method.

    Parameters
    ----------
    thicknesses_nm : array_like, shape (..., L)
        Layer thicknesses in nm, ordered from the ambient side; the leading shape is a batch
        (e.g. 1501 thickness settings).
    wavelengths_nm : array_like, shape (K,)
        Vacuum wavelengths in nm.
    layers : sequence of Medium, complex or array_like
        ``L`` media, from the ambient side (each a Medium, a number or a ``(K,)`` array; complex
        indices ``n + ik`` for absorbing layers).
    ambient : Medium, complex or array_like, keyword-only, default 1.0
        Incidence medium (non-absorbing).
    substrate : Medium, complex or array_like, keyword-only, default 1.0
        The medium below the stack (may be absorbing, e.g. a metal).
    angle_deg : array_like, keyword-only, default 0.0
        Angle of incidence in the ambient, degrees in [0, 90), broadcastable with the batch.
    polarisation : str, keyword-only, default "unpolarised"
        ``"s"``, ``"p"`` or ``"unpolarised"``.
    substrate_thickness_nm : float, keyword-only, optional
        ``None`` (default): the substrate is semi-infinite and transmittance is into it.
        A thickness: the substrate is a thick slab, treated incoherently (intensities, not
        amplitudes, add over its internal reflections), with ``exit_medium`` behind it; the
        transmittance is into the exit medium. Interfaces of the slab use ``Re(N)`` and its
        absorption ``exp(−4π Im(N cos θ) d / λ)`` per pass (weak-absorption approximation).
    exit_medium : Medium, complex or array_like, keyword-only, default 1.0
        Medium behind a thick substrate (only with ``substrate_thickness_nm``; non-absorbing).

    Returns
    -------
    FilmOptics
        Reflectance and transmittance, shape ``(..., K)``.

    Raises
    ------
    SpectrumError
        For thicknesses whose last axis is not one per layer, negative thicknesses, an invalid
        grid, angle or polarisation, or an absorbing ambient or exit medium.

    References
    ----------
    H. A. Macleod, *Thin-Film Optical Filters*, 4th ed. (CRC Press, 2010), ch. 2 (characteristic
    matrix, tilted admittances); C. C. Katsidis and D. I. Siapkas, "General transfer-matrix method
    for optical multilayer systems with coherent, partially coherent, and incoherent
    interference," Appl. Opt. 41, 3978-3987 (2002) (incoherent substrate).

    Examples
    --------
    The quarter-wave layer of :func:`thin_film`, then on a 1 mm glass slab in air (the slab's
    back surface adds its reflection incoherently):

    >>> stack_optics([100.0], [552.0], [1.38], substrate=1.5).reflectance.round(5).tolist()
    [0.01411]
    >>> slab = stack_optics([100.0], [552.0], [1.38], substrate=1.5, substrate_thickness_nm=1e6)
    >>> slab.reflectance.round(4).tolist(), slab.transmittance.round(4).tolist()
    ([0.053], [0.947])
    """
    polarisation = _check_polarisation(polarisation)
    wl = _wavelengths(wavelengths_nm)
    layers = list(layers)
    thicknesses = _nonnegative(thicknesses_nm, "thicknesses_nm")
    if thicknesses.ndim == 0 or thicknesses.shape[-1] != len(layers):
        raise SpectrumError(
            f"thicknesses_nm: last axis must hold one thickness per layer ({len(layers)}), "
            f"got shape {thicknesses.shape}"
        )
    n0 = _ambient(ambient, wl)
    n_layers = [refractive_index(m, wl) for m in layers]
    n_sub = refractive_index(substrate, wl)
    kx = n0.real * np.sin(_angles(angle_deg))
    q0, q_sub = _normal_index(n0, kx), _normal_index(n_sub, kx)
    qs = [_normal_index(n, kx) for n in n_layers]

    trig = _layer_trig(qs, thicknesses, wl)
    if substrate_thickness_nm is None:
        def coherent(pol):
            eta0 = _admittance(n0, q0, pol)
            etas = [_admittance(n, q, pol) for n, q in zip(n_layers, qs, strict=True)]
            r, t = _coherent_stack(eta0, etas, _admittance(n_sub, q_sub, pol), trig)
            return np.abs(r) ** 2, t

        reflectance, transmittance = _mean_over_polarisations(coherent, polarisation)
        shape = np.broadcast_shapes(reflectance.shape, thicknesses.shape[:-1] + (wl.size,))
        return FilmOptics(wl, np.broadcast_to(reflectance, shape).copy(),
                          np.broadcast_to(transmittance, shape).copy(), polarisation)

    d_sub = float(_nonnegative(substrate_thickness_nm, "substrate_thickness_nm"))
    n_exit = refractive_index(exit_medium, wl)
    if np.any(n_exit.imag != 0):
        raise SpectrumError(
            "exit_medium: the medium behind a thick substrate must be non-absorbing"
        )
    n_slab = n_sub.real.astype(complex)
    q_slab, q_exit = _normal_index(n_slab, kx), _normal_index(n_exit, kx)
    single_pass = np.exp(-4 * np.pi * q_sub.imag * d_sub / wl)

    def compute(pol):
        eta0, eta_slab = _admittance(n0, q0, pol), _admittance(n_slab, q_slab, pol)
        etas = [_admittance(n, q, pol) for n, q in zip(n_layers, qs, strict=True)]
        r_front, t_front = _coherent_stack(eta0, etas, eta_slab, trig)
        r_back_side, t_back_side = _coherent_stack(eta_slab, etas[::-1], eta0, trig[::-1])
        eta_exit = _admittance(n_exit, q_exit, pol)
        r_exit = np.abs((eta_slab - eta_exit) / (eta_slab + eta_exit)) ** 2
        t_exit = 1.0 - r_exit
        rf, rb = np.abs(r_front) ** 2, np.abs(r_back_side) ** 2
        loop = 1.0 - rb * r_exit * single_pass**2
        reflectance = rf + t_front * t_back_side * r_exit * single_pass**2 / loop
        transmittance = t_front * t_exit * single_pass / loop
        return reflectance, transmittance

    reflectance, transmittance = _mean_over_polarisations(compute, polarisation)
    shape = np.broadcast_shapes(reflectance.shape, thicknesses.shape[:-1] + (wl.size,))
    return FilmOptics(wl, np.broadcast_to(reflectance, shape).copy(),
                      np.broadcast_to(transmittance, shape).copy(), polarisation)
