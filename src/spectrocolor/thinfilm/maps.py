"""Pictures of films from thickness maps, through a thickness (× angle) → colour lookup table.

Computing a spectrum per pixel of a 3840 × 2160 frame would take minutes; the colour of a film
depends only on its thickness (and the angle of incidence), so the colours are computed once
on a fine thickness grid (default 0.5 nm; a few thousand spectra) and every pixel takes the
nearest thickness entry. Tables with an angle grid interpolate linearly between the two
neighbouring angles (colours change fast with angle near grazing incidence, and a coarse grid
would show as bands); see :meth:`ColourTable.lookup`. Exposure is set once for the whole
table (``"global-max"``: the brightest colour the table holds becomes full drive), so every
frame rendered through one table is consistent.

Thickness maps: :func:`wedge`, :func:`draining_film`, :func:`bubble`, or a user's array from
:func:`read_thickness_map` (``.npy`` in nm, or a 16-bit PNG with a stated nm per count).
NaN marks pixels without film; they get the ``background`` colour.

Why this file is long: the thickness-to-colour lookup table and the three pictures made with it (a
still, an animation of a draining film, a thickness map read from a file) share the table's grid and
its interpolation; each picture is short.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..display.transfer import Transfer
from ..errors import SpectrumError
from ..imagefiles import image_header, read_image, write_gif
from .colour import film_colours
from .optics import FilmOptics

#: The last angle of an angle grid is capped here (grazing incidence reflects everything).
_MAX_ANGLE_DEG = 89.9
#: Memory of one table entry while its colour is rendered (XYZ, drive values, codes), bytes.
TABLE_ENTRY_BYTES = 160
#: Memory of one spectral sample of a table entry while its optics are computed (complex
#: amplitudes, reflectance factors), bytes: measured about 90 (soap film, 81 samples).
SAMPLE_BYTES = 128


@dataclass(frozen=True)
class ColourTable:
    """8-bit colours of a film on a uniform thickness grid (and optionally an angle grid).

    Attributes
    ----------
    thickness_step_nm : float
        Spacing of the thickness grid, nm; entry ``i`` is ``i * thickness_step_nm``.
    angle_step_deg : float or None
        Spacing of the angle grid, degrees (entry ``j`` is ``j * angle_step_deg``, the last one capped at
        89.9°); ``None`` when the table was built for one angle.
    rgb8 : numpy.ndarray of uint8, shape (angles, thicknesses, 3)
        8-bit codes.
    description : str
        What the table was built from (film, light, observer, exposure).
    rgb_linear : numpy.ndarray, optional
        Linear drive values (after exposure and gamut strategy) of the same entries, float64;
        needed to interpolate between angles (tables with an angle grid).
    transfer : transfer object, optional
        The display's transfer function (``encode``), to turn interpolated linear values into
        codes as :func:`spectrocolor.render` does.

    Examples
    --------
    >>> import numpy as np
    >>> from spectrocolor import colour_table, soap_film
    >>> table = colour_table(soap_film, 600.0, thickness_step_nm=1.0, max_angle_deg=60.0, angle_step_deg=30.0)
    >>> table.rgb8.shape, table.angles_deg.tolist(), table.max_thickness_nm
    ((3, 601, 3), [0.0, 30.0, 60.0], 600.0)
    """

    thickness_step_nm: float
    angle_step_deg: float | None
    rgb8: np.ndarray
    description: str
    rgb_linear: np.ndarray | None = None
    transfer: Transfer | None = None

    @property
    def angles_deg(self) -> np.ndarray | None:
        """The table's angle grid (degrees), or ``None`` for a one-angle table."""
        if self.angle_step_deg is None:
            return None
        return np.minimum(np.arange(self.rgb8.shape[0]) * self.angle_step_deg, _MAX_ANGLE_DEG)

    @property
    def max_thickness_nm(self) -> float:
        return (self.rgb8.shape[1] - 1) * self.thickness_step_nm

    def lookup(self, thickness_nm, angle_deg=None, background=(0, 0, 0)) -> np.ndarray:
        """Colour codes of a thickness map, shape ``(..., 3)`` ``uint8``.

        Each pixel takes the nearest thickness entry. With an angle grid, the colour is
        interpolated linearly in angle between the two neighbouring grid angles, in *linear
        light*: the linear drive values of the two entries are mixed and then encoded, as
        :func:`spectrocolor.render` encodes. Linear drive is linear in XYZ and XYZ is linear in
        the reflectance spectrum, so (for colours inside the gamut, with the table's single
        exposure) this equals the colour of the linearly interpolated spectrum; mixing the
        encoded codes instead would darken the midpoints of fast transitions, which is where
        the interpolation matters.

        Parameters
        ----------
        thickness_nm : array_like
            Film thickness per pixel in nm, any shape; NaN = no film (``background``).
        angle_deg : array_like, optional
            Angle of incidence per pixel in degrees (same shape, NaN allowed where thickness
            is NaN), within the table's angle grid ``0 .. angles_deg[-1]``; required if and
            only if the table has an angle grid.
        background : tuple of int, default (0, 0, 0)
            8-bit colour of the pixels without film.

        Returns
        -------
        numpy.ndarray of uint8, shape (..., 3)
            8-bit codes.

        Raises
        ------
        SpectrumError
            For thicknesses or angles outside the table, or an angle map given to (or missing
            for) a table.

        Examples
        --------
        >>> import numpy as np
        >>> from spectrocolor import colour_table, soap_film
        >>> table = colour_table(soap_film, 600.0, thickness_step_nm=1.0, max_angle_deg=60.0,
        ...                      angle_step_deg=30.0)
        >>> table.lookup(np.array([300.0, np.nan]), np.array([15.0, np.nan])).tolist()
        [[101, 151, 124], [0, 0, 0]]
        """
        d = np.asarray(thickness_nm)
        if d.dtype.kind != "f":
            d = d.astype(np.float32)
        film = ~np.isnan(d)
        if np.any(d[film] < 0) or np.any(d[film] > self.max_thickness_nm + 0.5 * self.
                                          thickness_step_nm):
            raise SpectrumError(
                f"thickness_nm: values must lie in 0-{self.max_thickness_nm:g} nm (the table's "
                "range; build a larger table) or be NaN for no film"
            )
        if self.angle_step_deg is None:
            if angle_deg is not None:
                raise SpectrumError("angle_deg: this table was built for one angle only")
            index = np.rint(np.where(film, d, 0) / self.thickness_step_nm).astype(np.intp)
            out = self.rgb8.reshape(-1, 3)[index]
            out[~film] = np.asarray(background, dtype=np.uint8)
            return out
        if angle_deg is None:
            raise SpectrumError("angle_deg: this table has an angle grid; give an angle map")
        a = np.asarray(angle_deg, dtype=d.dtype)
        if a.shape != d.shape:
            raise SpectrumError(f"angle_deg: expected shape {d.shape}, got {a.shape}")
        out = np.empty((*d.shape, 3), dtype=np.uint8)
        out[~film] = np.asarray(background, dtype=np.uint8)
        out[film] = self._interpolate_angle(d[film], a[film])
        return out

    def _interpolate_angle(self, d: np.ndarray, a: np.ndarray) -> np.ndarray:
        """Codes (N, 3) for film pixels: nearest thickness, linear in angle (linear light)."""
        if self.rgb_linear is None or self.transfer is None:
            raise SpectrumError("this table holds no linear values; build it with colour_table")
        grid = self.angles_deg
        assert grid is not None  # lookup() comes here only for a table with an angle grid
        if not np.all((a >= 0) & (a <= grid[-1])):
            raise SpectrumError(
                f"angle_deg: values must lie in 0-{grid[-1]:g}° (the table's angle grid; build "
                "it with a larger max_angle_deg)"
            )
        count = self.rgb8.shape[1]
        lower = np.minimum((a / self.angle_step_deg).astype(np.intp), grid.size - 2)
        weight = ((a - grid[lower]) / np.diff(grid)[lower])[:, None]
        row = lower * count + np.rint(d / self.thickness_step_nm).astype(np.intp)
        linear = self.rgb_linear.reshape(-1, 3)
        row0 = np.take(linear, row, axis=0)
        mixed = np.take(linear, row + count, axis=0)
        mixed -= row0
        mixed *= weight
        mixed += row0
        # 8-bit code k + 1 starts where the encoded value reaches (k + 0.5) / 255: the same
        # rounding to the nearest code as encode-then-round, without a power per pixel.
        steps = self.transfer.decode((np.arange(255) + 0.5) / 255)
        return np.searchsorted(steps, mixed, side="right").astype(np.uint8)


def colour_table(film, max_thickness_nm: float, *, thickness_step_nm: float = 0.5,
                 max_angle_deg: float | None = None, angle_step_deg: float = 1.0,
                 wavelengths_nm=None, memory_budget=None, **colour_options) -> ColourTable:
    """Build a :class:`ColourTable` for a film model.

    The films' spectra are computed in blocks of thicknesses sized by the memory budget
    (:func:`spectrocolor.budget.block_bytes`), so a fine or long table takes the memory of its
    colours only; those are checked against the budget before anything is computed.

    Parameters
    ----------
    film : callable
        ``film(thickness_nm, wavelengths_nm, angle_deg=...) -> FilmOptics`` such as
        :func:`~spectrocolor.thinfilm.films.soap_film` (reflectance is used).
    max_thickness_nm : float
        Largest thickness in the table (nm).
    thickness_step_nm : float, keyword-only, default 0.5
        Thickness grid spacing (nm).
    max_angle_deg : float, keyword-only, optional
        ``None``: normal incidence only. Otherwise an angle grid ``0, angle_step_deg, ...``
        up to this angle (< 90), in degrees.
    angle_step_deg : float, keyword-only, default 1.0
        Angle grid spacing, degrees (only with ``max_angle_deg``).
    wavelengths_nm : array_like, shape (K,), keyword-only, optional
        Spectral grid, nm (default 380-780 nm at 5 nm).
    memory_budget : int or str, keyword-only, optional
        The most memory the table may take; see :term:`memory budget`.
    **colour_options : dict
        Passed to :func:`~spectrocolor.thinfilm.colour.film_colours` (illuminant, observer,
        exposure, gain, space, gamut).

    Returns
    -------
    ColourTable
        8-bit codes of shape ``(angles, thicknesses, 3)`` (one angle without an angle grid).

    Raises
    ------
    SpectrumError
        For a thickness range or step that is not positive, an angle grid outside (0, 90),
        a ``film`` that does not return FilmOptics, and as :func:`film_colours`.
    spectrocolor.errors.BudgetError
        (a ``SpectrumError``) When the table's entries (``max_thickness_nm / thickness_step_nm``
        thicknesses times the angles) exceed the memory budget.

    Examples
    --------
    >>> from spectrocolor import soap_film
    >>> table = colour_table(soap_film, 600.0, thickness_step_nm=1.0)
    >>> table.rgb8.shape, table.max_thickness_nm
    ((1, 601, 3), 600.0)
    >>> table.description
    'soap_film, blackbody 6504 K, observer CIE 1931 2°, exposure global-max'
    """
    from ..budget import check_bytes

    if not (np.isfinite(max_thickness_nm) and max_thickness_nm > 0):
        raise SpectrumError(f"max_thickness_nm: expected a positive number, got {max_thickness_nm}")
    if not (np.isfinite(thickness_step_nm) and thickness_step_nm > 0):
        raise SpectrumError(f"thickness_step_nm: expected > 0, got {thickness_step_nm}")
    wl = np.arange(380.0, 781.0, 5.0) if wavelengths_nm is None else wavelengths_nm
    count = int(np.ceil(min(max_thickness_nm / thickness_step_nm, 1e18) - 1e-9)) + 1
    angles: np.ndarray
    if max_angle_deg is None:
        angles, angle_step = np.zeros(1), None
    else:
        if not (0 < max_angle_deg < 90 and angle_step_deg > 0):
            raise SpectrumError("max_angle_deg must be in (0, 90) and angle_step_deg > 0")
        check_bytes(8 * (int(np.ceil(min(max_angle_deg / angle_step_deg, 1e18) - 1e-9)) + 1),
                    f"max_angle_deg / angle_step_deg: {max_angle_deg:g} / {angle_step_deg:g} deg",
                    budget=memory_budget)
        angles = np.arange(int(np.ceil(max_angle_deg / angle_step_deg - 1e-9)) + 1) * angle_step_deg
        angles = np.minimum(angles, _MAX_ANGLE_DEG)
        angle_step = float(angle_step_deg)
    check_bytes(angles.size * count * TABLE_ENTRY_BYTES,
                f"max_thickness_nm / thickness_step_nm: a table of {count} thicknesses x "
                f"{angles.size} angle(s)", budget=memory_budget)
    d = np.arange(count) * thickness_step_nm
    colours = _table_colours(film, d, np.asarray(wl, dtype=float), angles, colour_options, memory_budget)
    description = (f"{getattr(film, '__name__', 'film')}, {colours.illuminant}, observer "
                   f"{colours.observer}, exposure {colours.exposure}")
    if angle_step is None:
        return ColourTable(float(thickness_step_nm), None, colours.rgb8, description)
    from ..display.spaces import rgb_space

    transfer = rgb_space(colour_options.get("space", "sRGB")).transfer
    return ColourTable(float(thickness_step_nm), angle_step, colours.rgb8, description,
                       colours.rendering.rgb_linear, transfer)


def _table_colours(film, d: np.ndarray, wl: np.ndarray, angles: np.ndarray, colour_options: dict,
                   memory_budget):
    """The colours of every (angle, thickness) entry, the spectra computed in blocks of thicknesses."""
    from ..budget import block_bytes
    from .colour import colours_of, film_weights

    per_thickness = angles.size * max(wl.size, 1) * SAMPLE_BYTES
    step = max(1, block_bytes(memory_budget) // per_thickness)
    quantity = colour_options.get("quantity", "reflectance")
    if d.size <= step:  # one block: the films' colours as film_colours gives them
        return film_colours(_optics(film, d, wl, angles), **colour_options)
    W = film_weights(wl, **colour_options)
    XYZ100 = np.empty((angles.size, d.size, 3))
    for start in range(0, d.size, step):
        optics = _optics(film, d[start:start + step], wl, angles)
        XYZ100[:, start:start + step] = optics.spectrum(quantity).values @ W
    return colours_of(XYZ100, **colour_options)


def _optics(film, d: np.ndarray, wl: np.ndarray, angles: np.ndarray) -> FilmOptics:
    optics = film(d, wl, angle_deg=angles[:, None])
    if not isinstance(optics, FilmOptics):
        raise SpectrumError("film: must return FilmOptics (e.g. soap_film, thin_film)")
    return optics


def render_thickness_map(thickness_nm, table: ColourTable, angle_deg=None,
                         background=(0, 0, 0)) -> np.ndarray:
    """An ``(H, W, 3)`` ``uint8`` image of a thickness map (nm); see :meth:`ColourTable.lookup`.

    Parameters
    ----------
    thickness_nm : array_like, shape (H, W)
        Film thickness per pixel, nm, within the table's range; NaN where there is no film.
    table : ColourTable
        From :func:`colour_table`.
    angle_deg : array_like, shape (H, W), optional
        Angle of incidence per pixel, degrees; required if and only if the table has an
        angle grid.
    background : tuple of int, default (0, 0, 0)
        8-bit colour of the pixels without film.

    Returns
    -------
    numpy.ndarray of uint8, shape (H, W, 3)
        The picture's 8-bit codes (encoded with the table's space, sRGB by default).

    Raises
    ------
    SpectrumError
        For a map that is not 2-D, thicknesses or angles outside the table, or an angle map
        given to (or missing for) a table.

    Examples
    --------
    >>> import numpy as np
    >>> from spectrocolor import colour_table, soap_film
    >>> table = colour_table(soap_film, 600.0, thickness_step_nm=1.0)
    >>> image = render_thickness_map(np.array([[0.0, 300.0], [np.nan, 600.0]]), table,
    ...                              background=(255, 255, 255))
    >>> image.shape, image.dtype.name, image[1, 0].tolist()
    ((2, 2, 3), 'uint8', [255, 255, 255])
    """
    d = np.asarray(thickness_nm)
    if d.ndim != 2:
        raise SpectrumError(f"thickness_nm: expected an (H, W) map, got shape {d.shape}")
    return table.lookup(d, angle_deg, background)


def _size(width: int, height: int) -> None:
    if int(width) != width or int(height) != height or width < 1 or height < 1:
        raise SpectrumError(f"width and height must be positive integers, got {width}, {height}")


def wedge(width: int, height: int, max_thickness_nm: float,
          min_thickness_nm: float = 0.0) -> np.ndarray:
    """A wedge: thickness rising linearly from left to right (nm), shape ``(height, width)``.

    Parameters
    ----------
    width, height : int
        Image size in pixels.
    max_thickness_nm : float
        Thickness at the right edge, nm.
    min_thickness_nm : float, default 0.0
        Thickness at the left edge, nm.

    Returns
    -------
    numpy.ndarray of float32, shape (height, width)
        Thickness per pixel, nm.

    Raises
    ------
    SpectrumError
        For a size that is not a positive whole number.

    Examples
    --------
    >>> wedge(5, 2, 400.0)[0].tolist()
    [0.0, 100.0, 200.0, 300.0, 400.0]
    """
    _size(width, height)
    row = np.linspace(min_thickness_nm, max_thickness_nm, width, dtype=np.float32)
    return np.broadcast_to(row, (height, width)).copy()


def draining_film(width: int, height: int, *, time_s: float, film_height_m: float = 0.05,
                  viscosity_Pa_s: float = 1.0e-3, density_kg_m3: float = 1000.0) -> np.ndarray:
    """A vertical soap film draining under gravity: ``h(x, t) = 2 sqrt(η x / (ρ g t))`` (nm).

    The similarity solution of lubrication flow in a vertical film with immobile (surfactant-
    laden) surfaces: the flux per unit width ``q = ρ g h³ / (12 η)`` and ``∂h/∂t + ∂q/∂x = 0``
    give the profile above, ``x`` measured down from the top edge. The film is thinnest (black)
    at the top and thickens downward; it thins everywhere as ``t^(-1/2)``.

    Parameters
    ----------
    width, height : int
        Image size in pixels; the film spans ``film_height_m`` vertically.
    time_s : float, keyword-only
        Time since the film was drawn (s, > 0).
    film_height_m : float, keyword-only, default 0.05
        Height of the film, m.
    viscosity_Pa_s : float, keyword-only, default 1.0e-3
        Dynamic viscosity η of the liquid, Pa·s (water at 20 °C).
    density_kg_m3 : float, keyword-only, default 1000.0
        Density ρ of the liquid, kg/m³.

    Returns
    -------
    numpy.ndarray of float32, shape (height, width)
        Thickness per pixel, nm (uniform along each row).

    Raises
    ------
    SpectrumError
        For a size that is not a positive whole number or a parameter that is not positive.

    References
    ----------
    K. J. Mysels, K. Shinoda and S. Frankel, *Soap Films: Studies of their Thinning and a
    Bibliography* (Pergamon, 1959).

    Examples
    --------
    >>> import numpy as np
    >>> h = draining_film(3, 4, time_s=10.0)
    >>> h.shape, bool(np.all(np.diff(h[:, 0]) > 0))  # thickening downward
    ((4, 3), True)
    """
    _size(width, height)
    if not (time_s > 0 and film_height_m > 0 and viscosity_Pa_s > 0 and density_kg_m3 > 0):
        raise SpectrumError("time_s, film_height_m, viscosity_Pa_s, density_kg_m3 must be > 0")
    x = (np.arange(height, dtype=np.float64) + 0.5) / height * film_height_m
    h_nm = 2.0 * np.sqrt(viscosity_Pa_s * x / (density_kg_m3 * 9.80665 * time_s)) * 1e9
    return np.broadcast_to(h_nm.astype(np.float32)[:, None], (height, width)).copy()


def bubble(size: int, *, top_thickness_nm: float = 80.0, bottom_thickness_nm: float = 900.0,
           swirl: float = 0.15) -> tuple[np.ndarray, np.ndarray]:
    """A soap bubble seen from afar: thickness (nm) and angle of incidence (degrees) per pixel.

    A sphere filling a ``size × size`` image; the viewer sees the mirror image of a uniform
    sky, so the angle of incidence at a point is the angle between its normal and the line of
    sight. Drainage makes the film thin at the top and thick at the bottom (linear in height);
    ``swirl`` adds an illustrative marbling of that relative amplitude (0 for none). Pixels
    outside the sphere are NaN.

    Parameters
    ----------
    size : int
        Image side in pixels.
    top_thickness_nm : float, keyword-only, default 80.0
        Film thickness at the top of the bubble, nm.
    bottom_thickness_nm : float, keyword-only, default 900.0
        Film thickness at the bottom, nm.
    swirl : float, keyword-only, default 0.15
        Relative amplitude of the marbling.

    Returns
    -------
    thickness_nm : numpy.ndarray of float32, shape (size, size)
        Film thickness, nm; NaN outside the sphere.
    angle_deg : numpy.ndarray of float32, shape (size, size)
        Angle of incidence, degrees; NaN outside the sphere.

    Raises
    ------
    SpectrumError
        For a size that is not a positive whole number.

    Examples
    --------
    >>> import numpy as np
    >>> thickness_nm, angle_deg = bubble(4)
    >>> np.isnan(thickness_nm[0]).tolist(), round(float(angle_deg[1, 1]), 1)
    ([True, False, False, True], 20.7)
    """
    _size(size, size)
    c = (np.arange(size, dtype=np.float32) + 0.5) / size * 2 - 1
    u, v = np.meshgrid(c, c)
    r2 = u * u + v * v
    inside = r2 < 1.0
    z = np.sqrt(np.where(inside, 1.0 - r2, 0.0))
    thickness = top_thickness_nm + (bottom_thickness_nm - top_thickness_nm) * (1 + v) / 2
    thickness *= 1 + swirl * np.sin(7 * u + 3 * np.sin(5 * v)) * np.cos(4 * v - 2 * u)
    angle = np.degrees(np.arccos(np.clip(z, 0.0, 1.0)))
    nan = np.float32(np.nan)
    return np.where(inside, thickness, nan), np.where(inside, angle, nan)


def read_thickness_map(path, nm_per_count: float | None = None) -> np.ndarray:
    """Read a thickness map: ``.npy`` (float, nm) or ``.png`` (8/16-bit grey, counts).

    Parameters
    ----------
    path : str or os.PathLike
        A ``.npy`` file (2-D, nm) or a greyscale ``.png`` (8 or 16 bit counts).
    nm_per_count : float, optional
        Required for PNG: thickness in nm per grey count (e.g. 0.05 maps a 16-bit range to
        0-3277 nm). Must not be given for ``.npy`` (already in nm).

    Returns
    -------
    numpy.ndarray of float32, shape (H, W)
        Thickness per pixel, nm.

    Raises
    ------
    SpectrumError
        For another suffix, a scale given or missing against the format, a map that is not
        2-D numbers, or a PNG that is not greyscale.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> import numpy as np
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     np.save(pathlib.Path(folder) / "wedge.npy", wedge(4, 2, 300.0))
    ...     read_thickness_map(pathlib.Path(folder) / "wedge.npy")[0].tolist()
    [0.0, 100.0, 200.0, 300.0]
    """
    path = Path(path)
    suffix = path.suffix.lower()
    if suffix == ".npy":
        if nm_per_count is not None:
            raise SpectrumError("nm_per_count: a .npy map is already in nm; do not give a scale")
        from ..budget import npy_claim

        npy_claim(path, held=3.0)  # the array, its float32 copy and the picture's work
        data = np.load(path, allow_pickle=False)
        if data.ndim != 2 or data.dtype.kind not in "fiu":
            raise SpectrumError(f"{path}: expected a 2-D numeric array, got {data.shape}")
        return data.astype(np.float32)
    if suffix == ".png":
        if nm_per_count is None or not nm_per_count > 0:
            raise SpectrumError(
                "nm_per_count: a PNG holds grey counts; state the thickness per count in nm"
            )
        from ..budget import check_bytes

        header = image_header(path)
        check_bytes(header.width * header.height * 12, f"{path}: {header.width} x {header.height} "
                    "pixels (counts, their float32 thicknesses and the picture's work)")
        if header.format != "PNG" or header.channels != 1 or header.dtype not in (np.uint8, np.uint16):
            raise SpectrumError(
                f"{path}: expected a greyscale PNG (8 or 16 bit), got {header.format} with "
                f"{header.channels} channels of {header.dtype.name}"
            )
        counts = read_image(path)
        return counts.astype(np.float32) * np.float32(nm_per_count)
    raise SpectrumError(f"{path}: thickness maps must be .npy or .png")


def draining_film_gif(path, table: ColourTable, width: int, height: int, times_s,
                      frame_ms: int = 100, **film_options) -> Path:
    """An animated GIF of :func:`draining_film` at the given times, rendered through ``table``.

    Needs Pillow. Thicknesses beyond the table's range are an error, so build the table up
    to the thickest frame (the earliest time, bottom edge).

    Parameters
    ----------
    path : str or os.PathLike
        Output ``.gif``.
    table : ColourTable
        From :func:`colour_table` (one angle).
    width, height : int
        Frame size in pixels.
    times_s : sequence of float
        Times since the film was drawn, s (one frame each).
    frame_ms : int, default 100
        Display time of each frame, ms.
    **film_options : dict
        ``film_height_m``, ``viscosity_Pa_s``, ``density_kg_m3`` for :func:`draining_film`.

    Returns
    -------
    pathlib.Path
        The file written (atomically: :func:`spectrocolor.imagefiles.write_gif`).

    Raises
    ------
    SpectrumError
        For no times, or thicknesses beyond the table.
    spectrocolor.safe_write.OutputError
        As for :func:`~spectrocolor.imagefiles.write_gif`, which writes it; see
        :term:`atomic write`.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> from PIL import Image
    >>> from spectrocolor import colour_table, soap_film
    >>> table = colour_table(soap_film, 1200.0, thickness_step_nm=5.0)
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     path = draining_film_gif(pathlib.Path(folder) / "film.gif", table, 8, 8, [2.0e4, 4.0e4])
    ...     with Image.open(path) as gif:
    ...         print(gif.n_frames, gif.size)
    2 (8, 8)
    """
    frames = [render_thickness_map(draining_film(width, height, time_s=t, **film_options), table)
              for t in times_s]
    if not frames:
        raise SpectrumError("times_s: need at least one time")
    return write_gif(path, frames, frame_ms=frame_ms, loop=0)  # atomic, like every writer
