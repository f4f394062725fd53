"""The ``.spectro`` accessor on xarray DataArrays with a ``wavelength`` dimension.

Registered when :mod:`spectrocolor.images` is imported::

    import spectrocolor.images  # noqa: F401  (registers .spectro)
    XYZ = cube.spectro.to_xyz(illuminant="D65")          # dims (..., "XYZ")
    lab = cube.spectro.to_lab(illuminant="D65")          # dims (..., "Lab")
    rgb8 = cube.spectro.to_rgb(illuminant="D65")         # dims (..., "RGB"), uint8
    spectra = rgb.spectro.upsample(table)                # RGB (..., "RGB") -> (..., "wavelength")

On a dask-backed array nothing is computed until ``.compute()``: the conversion is one
``xr.apply_ufunc(..., dask="parallelized")`` whose per-chunk function is the same block
function the NumPy path uses (:mod:`spectrocolor.images.blocks`), so it runs unchanged on a
``dask.distributed`` cluster. The wavelength axis must be one chunk (each pixel needs all its
bands): rechunk with ``cube.chunk({"wavelength": -1})``; it is never rechunked silently.

The ``wavelength`` coordinate must be in nm, or carry ``units`` "nm" or "um"/"µm"
(converted).
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from ..display.gamut import DEFAULT_GAMUT
from ..errors import SpectrumError
from ..observers import DEFAULT_OBSERVER
from .convert import plan_conversion
from .cube import wavelengths_to_nm

__all__ = ["SpectroAccessor"]


@xr.register_dataarray_accessor("spectro")
class SpectroAccessor:
    """Colorimetry of spectral DataArrays (see the module docstring).

    Not constructed directly: ``import spectrocolor.images`` registers it as the ``.spectro``
    accessor of every ``xarray.DataArray``, and ``array.spectro`` builds one.

    Parameters
    ----------
    array : xarray.DataArray
        Spectral values with a ``wavelength`` dimension and coordinate (nm, or with a
        ``units`` attribute "nm", "um" or "µm").

    Examples
    --------
    >>> import numpy as np
    >>> import xarray as xr
    >>> import spectrocolor.images  # registers DataArray.spectro
    >>> cube = xr.DataArray(np.full((2, 3, 31), 0.5), dims=("y", "x", "wavelength"),
    ...                     coords={"wavelength": np.arange(400, 701, 10)})
    >>> XYZ = cube.spectro.to_xyz(illuminant="D65")
    >>> XYZ.dims, float(XYZ.sel(XYZ="Y")[0, 0].round(6))
    (('y', 'x', 'XYZ'), 50.0)
    """

    def __init__(self, array: xr.DataArray) -> None:
        self._array = array

    @property
    def wavelengths_nm(self) -> np.ndarray:
        """The ``wavelength`` coordinate in nm (units attribute honoured; default nm).

        Raises
        ------
        SpectrumError
            Without a ``wavelength`` dimension or coordinate, or for unknown units.

        Examples
        --------
        >>> import numpy as np
        >>> import xarray as xr
        >>> import spectrocolor.images  # registers DataArray.spectro
        >>> cube = xr.DataArray(np.full((2, 3, 31), 0.5), dims=("y", "x", "wavelength"),
        ...                     coords={"wavelength": np.arange(400, 701, 10)})
        >>> micrometres = cube.assign_coords(wavelength=np.arange(400, 701, 10) / 1000)
        >>> micrometres.coords["wavelength"].attrs["units"] = "um"
        >>> micrometres.spectro.wavelengths_nm[:2].tolist()
        [400.0, 410.0]
        """
        array = self._array
        if "wavelength" not in array.dims:
            raise SpectrumError(
                f"the DataArray has no 'wavelength' dimension (dims {array.dims}); rename the "
                "spectral dimension to 'wavelength'"
            )
        if "wavelength" not in array.coords:
            raise SpectrumError("the 'wavelength' dimension has no coordinate values (in nm)")
        coord = array.coords["wavelength"]
        return wavelengths_to_nm(coord.values, coord.attrs.get("units", "nm"),
                                 "DataArray 'wavelength' coordinate")

    def _apply(self, plan, name: str, components: tuple[str, str, str]) -> xr.DataArray:
        array = self._array
        chunks = array.chunksizes.get("wavelength") if array.chunks is not None else None
        if chunks is not None and len(chunks) > 1:
            raise SpectrumError(
                f"the 'wavelength' dimension is split into {len(chunks)} dask chunks {chunks}; "
                "each pixel needs all its bands: rechunk first with "
                "array.chunk({'wavelength': -1})"
            )
        result = xr.apply_ufunc(
            plan.function,
            array,
            kwargs=plan.keywords,
            input_core_dims=[["wavelength"]],
            output_core_dims=[[name]],
            dask="parallelized",
            output_dtypes=[plan.dtype],
            dask_gufunc_kwargs={"output_sizes": {name: 3}},
            keep_attrs=False,
        )
        result = result.assign_coords({name: list(components)})
        result.attrs.update({"quantity": plan.quantity})
        if plan.white_XYZ is not None:
            result.attrs["white_XYZ"] = np.asarray(plan.white_XYZ).tolist()
        return result

    def to_xyz(self, illuminant=None, observer=DEFAULT_OBSERVER, method: str = "sum",
               scale: float = 1.0) -> xr.DataArray:
        """CIE XYZ per pixel, dims (..., "XYZ"); arguments as :func:`cube_to_xyz`.

        Parameters
        ----------
        illuminant : str or Spectrum, optional
            The light for reflectances (result XYZ100); ``None`` for lights.
        observer : str, default DEFAULT_OBSERVER
            Observer name or alias.
        method : str, default "sum"
            Summation method, as for :func:`spectrocolor.weights`.
        scale : float, default 1.0
            Factor from the stored values to reflectance (0–1).

        Returns
        -------
        xarray.DataArray
            Lazy on dask input; coordinate ``XYZ`` = X, Y, Z; attributes ``quantity`` and, for
            reflectances, ``white_XYZ``.

        Raises
        ------
        SpectrumError
            For a missing or split ``wavelength`` dimension, as :attr:`wavelengths_nm`.

        Examples
        --------
        >>> import numpy as np
        >>> import xarray as xr
        >>> import spectrocolor.images  # registers DataArray.spectro
        >>> cube = xr.DataArray(np.full((2, 3, 31), 0.5), dims=("y", "x", "wavelength"),
        ...                     coords={"wavelength": np.arange(400, 701, 10)})
        >>> XYZ = cube.spectro.to_xyz(illuminant="D65")
        >>> XYZ.attrs["quantity"], float(XYZ.sel(XYZ="Y")[0, 0].round(6))
        ('XYZ100', 50.0)
        """
        plan = plan_conversion("xyz", self.wavelengths_nm, illuminant=illuminant,
                               observer=observer, method=method, scale=scale)
        return self._apply(plan, "XYZ", ("X", "Y", "Z"))

    def to_lab(self, illuminant=None, observer=DEFAULT_OBSERVER, method: str = "sum",
               scale: float = 1.0, white_XYZ=None) -> xr.DataArray:
        """CIELAB per pixel, dims (..., "Lab"); arguments as :func:`cube_to_lab`.

        Parameters
        ----------
        illuminant : str or Spectrum, optional
            The light for reflectances; ``None`` for lights (then give ``white_XYZ``).
        observer : str, default DEFAULT_OBSERVER
            Observer name or alias.
        method : str, default "sum"
            Summation method, as for :func:`spectrocolor.weights`.
        scale : float, default 1.0
            Factor from the stored values to reflectance (0–1).
        white_XYZ : array_like, shape (3,), optional
            Reference white; default the perfect reflector under ``illuminant`` on this grid.

        Returns
        -------
        xarray.DataArray
            Coordinate ``Lab`` = L*, a*, b*; attribute ``white_XYZ`` says which white was used.

        Raises
        ------
        SpectrumError
            For a missing or split ``wavelength`` dimension.

        Examples
        --------
        >>> import numpy as np
        >>> import xarray as xr
        >>> import spectrocolor.images  # registers DataArray.spectro
        >>> cube = xr.DataArray(np.full((2, 3, 31), 0.5), dims=("y", "x", "wavelength"),
        ...                     coords={"wavelength": np.arange(400, 701, 10)})
        >>> lab = cube.spectro.to_lab(illuminant="D65")
        >>> lab.coords["Lab"].values.tolist(), float(lab.sel(Lab="L*")[0, 0].round(3))
        (['L*', 'a*', 'b*'], 76.069)
        """
        plan = plan_conversion("lab", self.wavelengths_nm, illuminant=illuminant,
                               observer=observer, method=method, scale=scale,
                               white_XYZ=white_XYZ)
        return self._apply(plan, "Lab", ("L*", "a*", "b*"))

    def to_rgb(self, illuminant=None, observer=DEFAULT_OBSERVER, method: str = "sum",
               scale: float = 1.0, space="sRGB", gamut: str = DEFAULT_GAMUT, exposure: float = 1.0,
               adaptation: str | None = "bradford", bit_depth: int = 8,
               output: str = "codes") -> xr.DataArray:
        """Display RGB per pixel, dims (..., "RGB"); arguments as :func:`cube_to_rgb`.

        Parameters
        ----------
        illuminant : str or Spectrum, optional
            The light for reflectances; ``None`` for lights.
        observer : str, default DEFAULT_OBSERVER
            Observer name or alias.
        method : str, default "sum"
            Summation method.
        scale : float, default 1.0
            Factor from the stored values to reflectance (0–1).
        space : str or RGBSpace, default "sRGB"
            Display space.
        gamut : str, default DEFAULT_GAMUT
            Per-pixel gamut strategy (default ``"desaturate"``; see :func:`spectrocolor.render`).
        exposure : float, default 1.0
            Multiplier on XYZ before rendering.
        adaptation : str or None, default "bradford"
            Chromatic adaptation from the illuminant's white to the display white.
        bit_depth : int, default 8
            8 or 16 for ``output="codes"``.
        output : str, default "codes"
            "codes", "rgb_linear" or "rgb_encoded".

        Returns
        -------
        xarray.DataArray
            Coordinate ``RGB`` = R, G, B; uint8/uint16 codes or float64 values.

        Raises
        ------
        SpectrumError
            For a missing or split ``wavelength`` dimension.
        ColorimetryError
            For an unknown space, gamut, adaptation or output.

        Examples
        --------
        >>> import numpy as np
        >>> import xarray as xr
        >>> import spectrocolor.images  # registers DataArray.spectro
        >>> cube = xr.DataArray(np.full((2, 3, 31), 0.5), dims=("y", "x", "wavelength"),
        ...                     coords={"wavelength": np.arange(400, 701, 10)})
        >>> cube.spectro.to_rgb(illuminant="D65").values[0, 0].tolist()
        [188, 188, 188]
        """
        plan = plan_conversion("rgb", self.wavelengths_nm, illuminant=illuminant,
                               observer=observer, method=method, scale=scale, space=space,
                               gamut=gamut, exposure=exposure, adaptation=adaptation,
                               bit_depth=bit_depth, output=output)
        return self._apply(plan, "RGB", ("R", "G", "B"))

    def upsample(self, table, out_of_range: str = "toward-grey", dim: str = "RGB") -> xr.DataArray:
        """Reflectance spectra of an RGB DataArray by an upsampling table, dims (..., "wavelength").

        The array holds table coordinates (linear RGB of the table's space, 0–1; decode 8/16-bit
        codes first with :func:`spectrocolor.upsampling.rgb_linear_from_image`) along ``dim``.
        Each block goes through :func:`spectrocolor.upsampling.upsample_spectra`, so the numbers
        equal the NumPy path's and :func:`spectrocolor.upsampling.upsample_dask`'s bit for bit;
        on a dask-backed array the result is lazy, chunked like the input's other dimensions
        (``dim`` is taken as one chunk).

        Parameters
        ----------
        table : UpsamplingTable
            From :func:`spectrocolor.upsampling_table` or :func:`spectrocolor.upsampling.load_table`.
        out_of_range : str, default "toward-grey"
            A key of :data:`spectrocolor.upsampling.OUT_OF_RANGE_STRATEGIES` ("nan" gives NaN
            spectra for colours not reproduced exactly).
        dim : str, default "RGB"
            The dimension of length 3 holding the channels (as made by :meth:`to_rgb`).

        Returns
        -------
        xarray.DataArray
            float64 reflectance factors (0–1) with a ``wavelength`` coordinate in nm (attribute
            ``units`` "nm") replacing ``dim``; attributes ``quantity`` ("reflectance"),
            ``space``, ``illuminant``, ``observer`` and ``out_of_range``.

        Raises
        ------
        ColorimetryError
            For something other than an UpsamplingTable, an unknown strategy, or ``dim`` missing,
            not of length 3, or an array that already has a ``wavelength`` dimension.

        Examples
        --------
        >>> import numpy as np
        >>> import xarray as xr
        >>> import spectrocolor.images  # registers DataArray.spectro
        >>> from spectrocolor import upsampling_table
        >>> table = upsampling_table("sRGB", "D65", resolution=3, measure_excess=False)
        >>> rgb = xr.DataArray(np.full((2, 4, 3), 0.5), dims=("y", "x", "RGB"))
        >>> cube = rgb.spectro.upsample(table)
        >>> cube.dims, cube.sizes["wavelength"], float(cube[0, 0, 0].round(9))
        (('y', 'x', 'wavelength'), 81, 0.5)
        """
        from functools import partial

        from ..errors import ColorimetryError
        from ..upsampling import OUT_OF_RANGE_STRATEGIES, UpsamplingTable, upsample_spectra

        if not isinstance(table, UpsamplingTable):
            raise ColorimetryError(f"table: expected an UpsamplingTable, got {type(table).__name__}")
        out_of_range = OUT_OF_RANGE_STRATEGIES.canonical(out_of_range)
        array = self._array
        if dim not in array.dims or array.sizes[dim] != 3:
            raise ColorimetryError(
                f"dim: the DataArray needs a dimension {dim!r} of length 3 holding the channels; "
                f"its dims are {dict(array.sizes)}")
        if "wavelength" in array.dims:
            raise ColorimetryError("the DataArray already has a 'wavelength' dimension; upsample "
                                   "takes RGB values")
        if array.chunks is not None:
            array = array.chunk({dim: -1})
        wavelengths_nm = table.wavelengths_nm
        result = xr.apply_ufunc(
            partial(upsample_spectra, table),
            array,
            kwargs={"out_of_range": out_of_range},
            input_core_dims=[[dim]],
            output_core_dims=[["wavelength"]],
            dask="parallelized",
            output_dtypes=[np.float64],
            dask_gufunc_kwargs={"output_sizes": {"wavelength": wavelengths_nm.size}},
            keep_attrs=False,
        )
        result = result.assign_coords(wavelength=("wavelength", wavelengths_nm, {"units": "nm"}))
        result.attrs.update({"quantity": "reflectance", "space": table.space,
                             "illuminant": table.illuminant, "observer": table.observer,
                             "out_of_range": out_of_range})
        return result
