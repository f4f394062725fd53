"""Read spectral cubes (rows, columns, bands) from the common file formats.

Formats (chosen by the path):

* ``.npy`` — one 3-D array (H, W, K); the wavelengths must be given (``wavelengths_nm=``).
  Read lazily (memory-mapped).
* ``.npz`` — arrays ``values`` (H, W, K) and ``wavelengths_nm`` (K,) (or ``wavelengths_um``).
* ``.tif`` / ``.tiff`` — a multi-page TIFF, one page per band (or one page with K samples per
  pixel); the wavelengths in the tifffile JSON metadata as ``wavelengths_nm`` (or
  ``wavelengths`` plus ``wavelength_units``), or given. Uncompressed files are read lazily.
* ENVI — ``.hdr`` plus the raw file (or the raw file with a ``.hdr`` beside it). The header is
  parsed here: samples, lines, bands, header offset, data type, interleave (bsq/bil/bip), byte
  order, wavelength and wavelength units. Read lazily (memory-mapped).
* ``.nc`` / ``.h5`` / ``.hdf5`` / ``.nc4`` — netCDF-4/HDF5 through xarray (h5netcdf engine): a
  variable with a ``wavelength`` dimension whose coordinate has a ``units`` attribute.
* a folder of one-band PNG or TIFF images with the wavelength in each file name
  (``scene_450nm.png``, ``band-0.45um.tif``).

Wavelength units are never guessed: nanometres and micrometres are converted explicitly;
anything else (or no unit) is an error unless ``wavelength_units=`` says what they are.
"""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np

from ..errors import SpectrumError
from .cube import MappedArray, SpectralCube, wavelengths_to_nm

__all__ = ["read_cube", "read_envi_header"]

_ENVI_DTYPES = {
    1: "u1", 2: "i2", 3: "i4", 4: "f4", 5: "f8", 12: "u2", 13: "u4", 14: "i8", 15: "u8",
}
_ENVI_RAW_SUFFIXES = ("", ".img", ".raw", ".dat", ".bin", ".bsq", ".bil", ".bip", ".envi")
_NETCDF_SUFFIXES = (".nc", ".nc4", ".h5", ".hdf5", ".he5", ".cdf")
_TIFF_SUFFIXES = (".tif", ".tiff")
_FOLDER_SUFFIXES = (".png", ".tif", ".tiff")


def read_cube(
    path,
    *,
    wavelengths_nm=None,
    wavelength_units: str | None = None,
    variable: str | None = None,
) -> SpectralCube:
    """Read a spectral cube from a file or a folder of one-band images.

    Parameters
    ----------
    path : str or Path
        The file (``.npy``, ``.npz``, ``.tif``/``.tiff``, ENVI ``.hdr`` or its raw file,
        ``.nc``/``.h5``/``.hdf5``) or a folder of one-band PNG/TIFF images.
    wavelengths_nm : array_like, shape (K,), optional
        Band wavelengths in nm. Required for ``.npy``; for other formats it replaces the
        wavelengths stored in the file (its length must still match the band count).
    wavelength_units : str, optional
        Units of the wavelengths stored in the file when the file does not say ("nm" or "um");
        for a folder, the units of the numbers in the file names.
    variable : str, optional
        netCDF/HDF5 only: which variable to read when there is more than one with a
        ``wavelength`` dimension.

    Returns
    -------
    SpectralCube
        ``values`` (H, W, K) in the stored dtype (no scaling) and ``wavelengths_nm`` (K,).

    Raises
    ------
    SpectrumError
        Unknown format, missing wavelengths, unknown wavelength units, a band count that does
        not match the wavelength count, a raw file of the wrong size, images of different
        sizes.
    FileNotFoundError
        The path does not exist.
    """
    path = Path(path)
    if path.is_dir():
        cube = _read_folder(path, wavelength_units)
    elif not path.exists():
        raise FileNotFoundError(f"no such file or folder: {path}")
    else:
        suffix = path.suffix.lower()
        if suffix == ".npy":
            cube = _read_npy(path, wavelengths_nm)
        elif suffix == ".npz":
            cube = _read_npz(path, wavelengths_nm, wavelength_units)
        elif suffix in _TIFF_SUFFIXES:
            cube = _read_tiff(path, wavelengths_nm, wavelength_units)
        elif suffix in _NETCDF_SUFFIXES:
            cube = _read_netcdf(path, wavelength_units, variable, wavelengths_nm)
        elif suffix == ".hdr" or _envi_header_for(path) is not None:
            cube = _read_envi(path, wavelengths_nm, wavelength_units)
        else:
            raise SpectrumError(
                f"{path}: unknown cube format {suffix!r}; accepted: .npy, .npz, .tif/.tiff, ENVI"
                " (.hdr + raw), .nc/.h5/.hdf5, or a folder of one-band .png/.tif images"
            )
    if wavelengths_nm is not None and path.suffix.lower() != ".npy":
        cube = SpectralCube(cube.values, _given_wavelengths(wavelengths_nm, path), str(path),
                            cube.metadata)
    return cube


def _given_wavelengths(wavelengths_nm, path) -> np.ndarray:
    return wavelengths_to_nm(wavelengths_nm, "nm", f"{path} (wavelengths_nm argument)")


# --- NumPy -------------------------------------------------------------------------------


def _read_npy(path: Path, wavelengths_nm) -> SpectralCube:
    if wavelengths_nm is None:
        raise SpectrumError(
            f"{path}: a .npy file holds no wavelengths; give them (wavelengths_nm=..., or "
            "--wavelengths on the command line), or use .npz with a 'wavelengths_nm' array"
        )
    with open(path, "rb") as handle:
        try:
            version = np.lib.format.read_magic(handle)
        except ValueError:
            raise SpectrumError(f"{path}: not a NumPy .npy file (no .npy header)") from None
        read_header = {
            (1, 0): np.lib.format.read_array_header_1_0,
            (2, 0): np.lib.format.read_array_header_2_0,
        }.get(version)
        if read_header is None:
            raise SpectrumError(f"{path}: .npy format version {version} is not supported")
        try:
            shape, fortran_order, dtype = read_header(handle)
        except ValueError as exc:
            raise SpectrumError(f"{path}: damaged .npy header ({exc})") from None
        offset = handle.tell()
    if dtype.kind not in "biuf":
        raise SpectrumError(f"{path}: values must be numbers; the array holds dtype {dtype}")
    if len(shape) != 3:
        raise SpectrumError(f"{path}: a cube must have shape (rows, columns, bands); got {shape}")
    if fortran_order:
        values = MappedArray(str(path), dtype.str, tuple(reversed(shape)), offset, (2, 1, 0))
    else:
        values = MappedArray(str(path), dtype.str, tuple(shape), offset, (0, 1, 2))
    return SpectralCube(values, _given_wavelengths(wavelengths_nm, path), str(path))


def _read_npz(path: Path, wavelengths_nm, wavelength_units) -> SpectralCube:
    import zipfile

    try:
        archive = np.load(path, allow_pickle=False)
    except (ValueError, OSError, zipfile.BadZipFile) as exc:
        raise SpectrumError(f"{path}: not a NumPy .npz archive ({exc})") from None
    if not isinstance(archive, np.lib.npyio.NpzFile):
        raise SpectrumError(f"{path}: a .npy array named .npz; give the file the .npy suffix")
    with archive:
        names = set(archive.files)
        if "values" not in names:
            raise SpectrumError(
                f"{path}: no array named 'values' (the cube, shape (H, W, K)); "
                f"found {sorted(names)}"
            )
        values = archive["values"]
        if wavelengths_nm is not None:
            wavelengths = _given_wavelengths(wavelengths_nm, path)
        elif "wavelengths_nm" in names:
            wavelengths = wavelengths_to_nm(archive["wavelengths_nm"], "nm", str(path))
        elif "wavelengths_um" in names:
            wavelengths = wavelengths_to_nm(archive["wavelengths_um"], "um", str(path))
        elif "wavelengths" in names:
            wavelengths = wavelengths_to_nm(archive["wavelengths"], wavelength_units, str(path))
        else:
            raise SpectrumError(
                f"{path}: missing wavelengths: no array 'wavelengths_nm' (or 'wavelengths_um');"
                f" found {sorted(names)}"
            )
    return SpectralCube(values, wavelengths, str(path))


# --- TIFF --------------------------------------------------------------------------------


def _read_tiff(path: Path, wavelengths_nm, wavelength_units) -> SpectralCube:
    import tifffile

    try:
        tif = tifffile.TiffFile(path)
    except tifffile.TiffFileError as exc:
        raise SpectrumError(f"{path}: not a TIFF file ({exc})") from None
    with tif:
        series = tif.series[0]
        shape, axes = tuple(series.shape), series.axes
        metadata = dict(tif.shaped_metadata[0]) if tif.shaped_metadata else {}
        if len(shape) != 3:
            raise SpectrumError(
                f"{path}: a spectral TIFF must hold a 3-D stack (one page per band); got shape "
                f"{shape} (axes {axes!r})"
            )
        order = (0, 1, 2) if axes.endswith("S") else (1, 2, 0)
        offset = series.dataoffset
        if offset is not None:
            dtype = np.dtype(series.dtype).newbyteorder(tif.byteorder)
            values = MappedArray(str(path), dtype.str, shape, int(offset), order)
        else:  # compressed or scattered: read it
            values = np.transpose(series.asarray(), order)
    if wavelengths_nm is not None:
        wavelengths = _given_wavelengths(wavelengths_nm, path)
    elif "wavelengths_nm" in metadata:
        wavelengths = wavelengths_to_nm(metadata["wavelengths_nm"], "nm", str(path))
    elif "wavelengths" in metadata:
        units = metadata.get("wavelength_units", wavelength_units)
        wavelengths = wavelengths_to_nm(metadata["wavelengths"], units, str(path))
    else:
        raise SpectrumError(
            f"{path}: missing wavelengths: the TIFF metadata has no 'wavelengths_nm' (or "
            "'wavelengths' and 'wavelength_units'); give them with wavelengths_nm=..."
        )
    return SpectralCube(values, wavelengths, str(path), _plain(metadata))


def _plain(metadata: dict) -> dict:
    return {k: v for k, v in metadata.items() if k not in ("shape", "wavelengths_nm")}


# --- ENVI --------------------------------------------------------------------------------


def _envi_header_for(path: Path) -> Path | None:
    for candidate in (Path(str(path) + ".hdr"), path.with_suffix(".hdr")):
        if candidate.is_file() and candidate != path:
            return candidate
    return None


def read_envi_header(path) -> dict[str, str]:
    """The fields of an ENVI header file, lower-case keys, values as text.

    Multi-line ``{...}`` values are joined; ``;`` comment lines are skipped.

    Raises
    ------
    SpectrumError
        The file does not start with the line ``ENVI``, or a ``{`` is never closed.
    """
    path = Path(path)
    lines = path.read_text(encoding="utf-8", errors="replace").splitlines()
    if not lines or lines[0].strip() != "ENVI":
        raise SpectrumError(f"{path}: not an ENVI header (the first line must be 'ENVI')")
    fields: dict[str, str] = {}
    key, pending = None, None
    for line in lines[1:]:
        if pending is not None:
            pending += " " + line.strip()
            if "}" in line:
                fields[key] = pending
                key, pending = None, None
            continue
        if not line.strip() or line.lstrip().startswith(";") or "=" not in line:
            continue
        name, _, value = line.partition("=")
        key, value = name.strip().lower(), value.strip()
        if value.startswith("{") and "}" not in value:
            pending = value
        else:
            fields[key] = value
    if pending is not None:
        raise SpectrumError(f"{path}: the value of {key!r} opens '{{' but never closes it")
    return fields


def _envi_int(fields: dict, key: str, header: Path, default: int | None = None) -> int:
    if key not in fields:
        if default is not None:
            return default
        raise SpectrumError(f"{header}: the ENVI header has no {key!r} field")
    try:
        return int(fields[key])
    except ValueError as exc:
        raise SpectrumError(f"{header}: {key!r} must be an integer; got {fields[key]!r}") from exc


def _envi_list(text: str) -> list[str]:
    return [item.strip() for item in text.strip().strip("{}").split(",") if item.strip()]


def _read_envi(path: Path, wavelengths_nm, wavelength_units) -> SpectralCube:
    if path.suffix.lower() == ".hdr":
        header = path
        fields = read_envi_header(header)
        stem = path.with_suffix("")
        raw = next(
            (Path(str(stem) + s) for s in _ENVI_RAW_SUFFIXES if Path(str(stem) + s).is_file()),
            None,
        )
        if raw is None:
            raise SpectrumError(
                f"{header}: no raw data file beside the header (looked for {stem.name} with "
                f"suffixes {', '.join(repr(s) for s in _ENVI_RAW_SUFFIXES)})"
            )
    else:
        raw, header = path, _envi_header_for(path)
        fields = read_envi_header(header)
    samples = _envi_int(fields, "samples", header)
    lines = _envi_int(fields, "lines", header)
    bands = _envi_int(fields, "bands", header)
    offset = _envi_int(fields, "header offset", header, default=0)
    code = _envi_int(fields, "data type", header)
    if code not in _ENVI_DTYPES:
        raise SpectrumError(
            f"{header}: ENVI data type {code} is not supported; accepted: "
            + ", ".join(f"{k} ({np.dtype(v).name})" for k, v in _ENVI_DTYPES.items())
        )
    byte_order = _envi_int(fields, "byte order", header)
    if byte_order not in (0, 1):
        raise SpectrumError(
            f"{header}: 'byte order' must be 0 (little) or 1 (big); got {byte_order}"
        )
    dtype = np.dtype(("<" if byte_order == 0 else ">") + _ENVI_DTYPES[code])
    interleave = fields.get("interleave", "").lower()
    layouts = {
        "bsq": ((bands, lines, samples), (1, 2, 0)),
        "bil": ((lines, bands, samples), (0, 2, 1)),
        "bip": ((lines, samples, bands), (0, 1, 2)),
    }
    if interleave not in layouts:
        raise SpectrumError(
            f"{header}: 'interleave' must be bsq, bil or bip; got {fields.get('interleave')!r}"
        )
    file_shape, axes = layouts[interleave]
    expected = offset + samples * lines * bands * dtype.itemsize
    size = raw.stat().st_size
    if size != expected:
        raise SpectrumError(
            f"{raw}: the file has {size} bytes but the header ({samples} samples x {lines} lines x"
            f" {bands} bands of {dtype.name} + {offset} header bytes) describes {expected}"
        )
    if wavelengths_nm is not None:
        wavelengths = _given_wavelengths(wavelengths_nm, header)
    elif "wavelength" not in fields:
        raise SpectrumError(
            f"{header}: missing wavelengths: the header has no 'wavelength' field; give them "
            "with wavelengths_nm=..."
        )
    else:
        listed = _envi_list(fields["wavelength"])
        if len(listed) != bands:
            raise SpectrumError(
                f"{header}: 'wavelength' lists {len(listed)} values but 'bands' = {bands}; "
                "they must match"
            )
        try:
            numbers = [float(item) for item in listed]
        except ValueError as exc:
            raise SpectrumError(f"{header}: 'wavelength' values must be numbers") from exc
        units = fields.get("wavelength units", wavelength_units)
        wavelengths = wavelengths_to_nm(numbers, units, str(header))
    metadata = {}
    if "reflectance scale factor" in fields:
        metadata["reflectance scale factor"] = float(fields["reflectance scale factor"])
    values = MappedArray(str(raw), dtype.str, file_shape, offset, axes)
    return SpectralCube(values, wavelengths, str(header), metadata)


# --- netCDF / HDF5 -------------------------------------------------------------------------


def _read_netcdf(path: Path, wavelength_units, variable, wavelengths_nm) -> SpectralCube:
    import xarray as xr

    try:
        dataset = xr.open_dataset(path, engine="h5netcdf")
    except (OSError, ValueError) as exc:
        raise SpectrumError(f"{path}: cannot open as netCDF-4/HDF5 ({exc})") from exc
    candidates = [name for name, var in dataset.data_vars.items() if "wavelength" in var.dims]
    if variable is not None:
        if variable not in dataset.data_vars:
            raise SpectrumError(
                f"{path}: no variable {variable!r}; variables: {sorted(dataset.data_vars)}"
            )
        if "wavelength" not in dataset[variable].dims:
            raise SpectrumError(f"{path}: variable {variable!r} has no 'wavelength' dimension")
        name = variable
    elif len(candidates) == 1:
        name = candidates[0]
    elif not candidates:
        raise SpectrumError(
            f"{path}: no variable has a 'wavelength' dimension; variables: "
            f"{ {k: v.dims for k, v in dataset.data_vars.items()} }"
        )
    else:
        raise SpectrumError(
            f"{path}: several variables have a 'wavelength' dimension ({candidates}); choose one"
            " with variable=..."
        )
    array = dataset[name]
    if array.ndim != 3:
        raise SpectrumError(
            f"{path}: variable {name!r} must have 3 dimensions (two spatial + 'wavelength'); "
            f"got {array.dims}"
        )
    array = array.transpose(*[d for d in array.dims if d != "wavelength"], "wavelength")
    if wavelengths_nm is not None:
        wavelengths = _given_wavelengths(wavelengths_nm, path)
    elif "wavelength" not in dataset.coords:
        raise SpectrumError(
            f"{path}: missing wavelengths: the 'wavelength' dimension has no coordinate values"
        )
    else:
        coord = dataset["wavelength"]
        units = coord.attrs.get("units", wavelength_units)
        wavelengths = wavelengths_to_nm(coord.values, units, f"{path} ('wavelength' coordinate)")
    return SpectralCube(array, wavelengths, str(path),
                        {"variable": name, "dims": array.dims})


# --- folder of one-band images ---------------------------------------------------------------

_NAME_WAVELENGTH = re.compile(
    r"(\d+(?:\.\d+)?)\s*[-_ ]?(nm|um|µm|μm|microns?|nanometers?|micrometers?)?(?![\d.])",
    re.IGNORECASE,
)


def _wavelength_from_name(file: Path, wavelength_units) -> float:
    matches = list(_NAME_WAVELENGTH.finditer(file.stem))
    if not matches:
        raise SpectrumError(
            f"{file}: no wavelength in the file name; name band images like 'scene_450nm.png'"
        )
    with_unit = [m for m in matches if m.group(2)]
    match = with_unit[-1] if with_unit else matches[-1]
    units = match.group(2) or wavelength_units
    return float(wavelengths_to_nm([float(match.group(1))], units, f"{file} (file name)")[0])


def _read_band(file: Path) -> np.ndarray:
    if file.suffix.lower() == ".png":
        from PIL import Image

        with Image.open(file) as image:
            band = np.asarray(image)
    else:
        import tifffile

        band = tifffile.imread(file)
    if band.ndim != 2:
        raise SpectrumError(
            f"{file}: band images must have one channel; got shape {band.shape}"
        )
    return band


def _read_folder(folder: Path, wavelength_units) -> SpectralCube:
    files = sorted(f for f in folder.iterdir() if f.suffix.lower() in _FOLDER_SUFFIXES)
    if not files:
        raise SpectrumError(f"{folder}: no .png or .tif band images in the folder")
    wavelengths = np.array([_wavelength_from_name(f, wavelength_units) for f in files])
    order = np.argsort(wavelengths, kind="stable")
    sorted_nm = wavelengths[order]
    repeated = sorted_nm[1:][np.diff(sorted_nm) == 0]
    if repeated.size:
        names = [f.name for f, w in zip(files, wavelengths, strict=True) if w in repeated]
        raise SpectrumError(f"{folder}: several images for the same wavelength: {names}")
    bands = [_read_band(files[i]) for i in order]
    shapes = {band.shape for band in bands}
    dtypes = {band.dtype for band in bands}
    if len(shapes) != 1:
        raise SpectrumError(f"{folder}: band images differ in size: {sorted(shapes)}")
    if len(dtypes) != 1:
        raise SpectrumError(
            f"{folder}: band images differ in sample type: {sorted(map(str, dtypes))}"
        )
    values = np.stack(bands, axis=-1)
    return SpectralCube(values, sorted_nm, str(folder), {"files": [files[i].name for i in order]})

