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
  order, wavelength and wavelength units, and the fields that say how to read the numbers:
  ``reflectance scale factor`` (values are divided by it), ``data ignore value`` (those values
  become NaN: masked), ``bbl`` (bad bands, 0 in the list, are dropped) and ``fwhm`` (kept as
  ``metadata["fwhm_nm"]``; no bandpass correction is applied). ``raw=True`` skips the first three
  and returns the stored numbers, with the fields in ``metadata``. Read lazily; the file's size is
  checked against the header before anything is read.
* MATLAB ``.mat`` — v5 (scipy.io) and v7.3 (HDF5, h5py; read lazily), as the CAVE, ICVL and
  Harvard collections distribute their cubes: the one 3-D numeric variable (or ``variable=``),
  MATLAB's (rows, columns, bands) order; wavelengths from a variable named ``wavelengths_nm``
  (nm), or ``wavelengths``/``wavelength``/``bands``/``wl`` with ``wavelength_units=``, or given.
* ``.nc`` / ``.h5`` / ``.hdf5`` / ``.nc4`` — netCDF-4/HDF5 through xarray (h5netcdf engine): a
  variable with a ``wavelength`` dimension whose coordinate has a ``units`` attribute.
* a folder of one-band PNG or TIFF images with the wavelength in each file name
  (``scene_450nm.png``, ``band-0.45um.tif``).

Wavelength units are never guessed: nanometres and micrometres are converted explicitly;
anything else (or no unit) is an error unless ``wavelength_units=`` says what they are.

Sizes are checked before anything is read (:mod:`spectrocolor.budget`): the size a header
claims against the file's length and against the bytes the file really stores on disk (a sparse
file promising 310 GB of holes is refused, not read for hours); compressed data (``.npz``
members, compressed TIFF, MATLAB v5, chunked v7.3 datasets) against the compressed bytes times
:data:`~spectrocolor.budget.MAX_COMPRESSION_RATIO`; and what must be held in memory (formats
that cannot be read lazily) against the memory budget. Lazily read cubes are not limited by the
budget: they are converted in blocks.

Why this file is long: one reader per cube format (NumPy, TIFF, ENVI, MATLAB, NetCDF/HDF5) behind
one :func:`read_cube`, each checking its header against the memory budget and the file's length
before it reads; they share the checks and the metadata record, and the ENVI reader, kept ours for
the reasons given at its top, is most of the length.
"""

from __future__ import annotations

import re
import struct
import zlib
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any, NamedTuple

import numpy as np

from ..budget import check_bytes, check_file_claim, claimed_bytes, format_size, npy_claim
from ..budget import memory_budget as budget_in_force
from ..errors import SpectrumError
from ..imagefiles import image_header, read_image
from .cube import MappedArray, SpectralCube, wavelengths_to_nm

if TYPE_CHECKING:  # for an annotation only: the worker's module is imported on first use
    from concurrent.futures import ProcessPoolExecutor

__all__ = ["read_cube", "read_envi_header", "CorrectedArray", "MatlabH5Array"]

_MAT_WAVELENGTH_NAMES = ("wavelengths_nm", "wavelengths", "wavelength", "bands", "wl", "lambda")
_MAT_CLASS_BYTES = {
    "double": 8, "single": 4, "int8": 1, "uint8": 1, "int16": 2, "uint16": 2,
    "int32": 4, "uint32": 4, "int64": 8, "uint64": 8,
}

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
    raw: bool = False,
    memory_budget=None,
) -> SpectralCube:
    """Read a spectral cube from a file or a folder of one-band images.

    Parameters
    ----------
    path : str or Path
        The file (``.npy``, ``.npz``, ``.tif``/``.tiff``, ENVI ``.hdr`` or its raw file,
        ``.nc``/``.h5``/``.hdf5``) or a folder of one-band PNG/TIFF images.
    wavelengths_nm : array_like, shape (K,), optional
        Band wavelengths in nm. Required for ``.npy``; for other formats it replaces the wavelengths
        stored in the file (its length must still match the band count); see
        :term:`wavelength grid`.
    wavelength_units : str, optional
        Units of the wavelengths stored in the file when the file does not say ("nm" or "um");
        for a folder, the units of the numbers in the file names.
    variable : str, optional
        netCDF/HDF5 and MATLAB: which variable to read when more than one could be the cube.
    raw : bool, keyword-only, default False
        ENVI only: return the stored numbers without applying the header's reflectance scale
        factor, data ignore value and bad-band list (they are then in ``metadata``). Default
        False: applied, and ``metadata["applied"]`` says what was done.
    memory_budget : int or str, keyword-only, optional
        The most bytes the cube may take when its format is read whole (``.npz``, compressed TIFF,
        MATLAB v5, a folder of images); lazily read cubes are streamed instead; see
        :term:`memory budget`.

    Returns
    -------
    SpectralCube
        ``values`` (H, W, K) in the stored dtype (ENVI with corrections: float32, NaN where
        masked) and ``wavelengths_nm`` (K,).

    Raises
    ------
    SpectrumError
        Unknown format, missing wavelengths, unknown wavelength units, a band count that does
        not match the wavelength count, a raw file of the wrong size, images of different
        sizes.
    spectrocolor.errors.BudgetError
        (a ``SpectrumError``) A header that claims more data than the file holds or stores on
        disk (sparse files), compressed data claiming an impossible expansion, or a cube that
        must be read whole and exceeds the memory budget.
    FileNotFoundError
        The path does not exist.

    References
    ----------
    ENVI header format (L3Harris, *ENVI Header Files*); TIFF 6.0; netCDF-4/HDF5.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> import numpy as np
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     path = pathlib.Path(folder) / "grey.npy"
    ...     np.save(path, np.full((2, 3, 31), 0.5))
    ...     cube = read_cube(path, wavelengths_nm=np.arange(400, 701, 10))
    >>> cube.shape, cube.wavelengths_nm[[0, -1]].tolist()
    ((2, 3, 31), [400.0, 700.0])
    """
    path = Path(path)
    budget = budget_in_force(memory_budget)
    if path.is_dir():
        cube = _read_folder(path, wavelength_units, budget)
    elif not path.exists():
        raise FileNotFoundError(f"no such file or folder: {path}")
    else:
        suffix = path.suffix.lower()
        if suffix == ".npy":
            cube = _read_npy(path, wavelengths_nm)
        elif suffix == ".npz":
            cube = _read_npz(path, wavelengths_nm, wavelength_units, budget)
        elif suffix in _TIFF_SUFFIXES:
            cube = _read_tiff(path, wavelengths_nm, wavelength_units, budget)
        elif suffix == ".mat":
            cube = _read_mat(path, wavelengths_nm, wavelength_units, variable, budget)
        elif suffix in _NETCDF_SUFFIXES:
            cube = _read_netcdf(path, wavelength_units, variable, wavelengths_nm)
        elif suffix == ".hdr" or _envi_header_for(path) is not None:
            cube = _read_envi(path, wavelengths_nm, wavelength_units, raw)
        else:
            raise SpectrumError(
                f"{path}: unknown cube format {suffix!r}; accepted: .npy, .npz, .tif/.tiff, ENVI"
                " (.hdr + raw), .mat (MATLAB v5 or v7.3), .nc/.h5/.hdf5, or a folder of one-band"
                " .png/.tif images"
            )
    if wavelengths_nm is not None and path.is_dir():  # the file readers apply them themselves
        cube = SpectralCube(cube.values, _given_wavelengths(wavelengths_nm, path), str(path),
                            cube.metadata)
    return cube


def _given_wavelengths(wavelengths_nm, path) -> np.ndarray:
    return wavelengths_to_nm(wavelengths_nm, "nm", f"{path} (wavelengths_nm argument)")


def _describe(shape, dtype) -> str:
    return f"shape {tuple(int(s) for s in shape)} of {np.dtype(dtype).name}"


# --- NumPy -------------------------------------------------------------------------------


def _read_npy(path: Path, wavelengths_nm) -> SpectralCube:
    if wavelengths_nm is None:
        raise SpectrumError(
            f"{path}: a .npy file holds no wavelengths; give them (wavelengths_nm=..., or "
            "--wavelengths on the command line), or use .npz with a 'wavelengths_nm' array"
        )
    shape, dtype, offset, fortran_order = npy_claim(path, held=None)  # read lazily: streamed
    if dtype.kind not in "biuf":
        raise SpectrumError(f"{path}: values must be numbers; the array holds dtype {dtype}")
    if len(shape) != 3:
        raise SpectrumError(f"{path}: a cube must have shape (rows, columns, bands); got {shape}")
    if fortran_order:
        values = MappedArray(str(path), dtype.str, tuple(reversed(shape)), offset, (2, 1, 0))
    else:
        values = MappedArray(str(path), dtype.str, tuple(shape), offset, (0, 1, 2))
    return SpectralCube(values, _given_wavelengths(wavelengths_nm, path), str(path))


def _read_npz(path: Path, wavelengths_nm, wavelength_units, budget: int) -> SpectralCube:
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

        def load(name: str, stream: bool = False):
            lazy = _check_npz_member(path, archive.zip, name, budget, stream)
            if lazy is not None:
                return lazy
            try:
                return archive[name]
            except (ValueError, OSError, EOFError, zipfile.BadZipFile, zlib.error) as exc:
                raise SpectrumError(f"{path}: member {name!r} cannot be read ({exc})") from None

        values = load("values", stream=True)
        if wavelengths_nm is not None:
            wavelengths = _given_wavelengths(wavelengths_nm, path)
        elif "wavelengths_nm" in names:
            wavelengths = wavelengths_to_nm(load("wavelengths_nm"), "nm", str(path))
        elif "wavelengths_um" in names:
            wavelengths = wavelengths_to_nm(load("wavelengths_um"), "um", str(path))
        elif "wavelengths" in names:
            wavelengths = wavelengths_to_nm(load("wavelengths"), wavelength_units, str(path))
        else:
            raise SpectrumError(
                f"{path}: missing wavelengths: no array 'wavelengths_nm' (or 'wavelengths_um');"
                f" found {sorted(names)}"
            )
    return SpectralCube(values, wavelengths, str(path))


def _check_npz_member(path: Path, archive, name: str, budget: int, stream: bool = False):
    """Check the shape a member's .npy header claims before NumPy allocates it.

    The claim must fit in the member's uncompressed size, that size in its compressed size times
    :data:`~spectrocolor.budget.MAX_COMPRESSION_RATIO` (a 1 kB member cannot hold 4.5 GB), and
    -- where the member is read whole -- the array in the memory budget. With ``stream`` a
    member beyond the budget is not read: a stored (``np.savez``) member becomes a
    :class:`~spectrocolor.images.cube.MappedArray` of its bytes in the archive, a deflated one
    (``np.savez_compressed``, C order) a :class:`~spectrocolor.images.cube.ZipMemberArray`, read
    in blocks of rows; None is returned where the member is to be read whole.
    """
    import zipfile

    member = f"{name}.npy"
    try:
        info = archive.getinfo(member)
        with archive.open(member) as handle:
            version = np.lib.format.read_magic(handle)
            read_header = {(1, 0): np.lib.format.read_array_header_1_0,
                           (2, 0): np.lib.format.read_array_header_2_0}.get(version)
            if read_header is None:
                raise ValueError(f".npy format version {version} is not supported")
            shape, fortran_order, dtype = read_header(handle)
            offset = handle.tell()
    except (ValueError, OSError, EOFError, KeyError, zipfile.BadZipFile, zlib.error) as exc:
        raise SpectrumError(f"{path}: member {name!r} is not a readable .npy array ({exc})") from None
    what = f"member {name!r}: the header claims {_describe(shape, dtype)}"
    nbytes = claimed_bytes(shape, dtype.itemsize, f"{path}: member {name!r}: the header's shape")
    if offset + nbytes > info.file_size:
        raise SpectrumError(f"{path}: {what}: {format_size(nbytes)} of data, but the member holds "
                            f"{format_size(max(info.file_size - offset, 0))}; the archive is damaged")
    stored = info.compress_type == zipfile.ZIP_STORED
    if not stored:
        check_file_claim(path, info.file_size, what, compressed_bytes=info.compress_size)
    elif info.file_size > info.compress_size:
        raise SpectrumError(f"{path}: member {name!r} is stored uncompressed in "
                            f"{format_size(info.compress_size)} but claims {format_size(info.file_size)}")
    if stream and nbytes > budget and len(shape) == 3 and dtype.kind in "biuf":
        if stored:
            start = _zip_data_start(path, info) + offset
            check_file_claim(path, nbytes, what, offset=start)
            if fortran_order:
                return MappedArray(str(path), dtype.str, tuple(reversed(shape)), start, (2, 1, 0))
            return MappedArray(str(path), dtype.str, tuple(shape), start, (0, 1, 2))
        if not fortran_order:
            from .cube import ZipMemberArray

            return ZipMemberArray(str(path), member, dtype.str, tuple(shape), offset)
    check_bytes(nbytes, f"{path}: {what} (an .npz member is read whole where it is deflated in "
                "Fortran order, or small; a .npy file is streamed)", budget=budget)
    return None


def _zip_data_start(path: Path, info) -> int:
    """Where a stored ZIP member's bytes start in the archive (after its local header)."""
    with open(path, "rb") as handle:
        handle.seek(info.header_offset)
        local = handle.read(30)
    if len(local) != 30 or local[:4] != b"PK\x03\x04":
        raise SpectrumError(f"{path}: member {info.filename!r}: its local header is damaged")
    name_length, extra_length = struct.unpack("<HH", local[26:30])
    return info.header_offset + 30 + name_length + extra_length


# --- TIFF --------------------------------------------------------------------------------


def _read_tiff(path: Path, wavelengths_nm, wavelength_units, budget: int) -> SpectralCube:
    import tifffile

    try:
        tif = tifffile.TiffFile(path)
    except (tifffile.TiffFileError, struct.error) as exc:  # struct.error: cut right after the signature
        raise SpectrumError(f"{path}: not a readable TIFF file ({exc})") from None
    with tif:
        try:
            series = tif.series[0]
            shape, axes = tuple(series.shape), series.axes
            metadata = dict(tif.shaped_metadata[0]) if tif.shaped_metadata else {}
        except (IndexError, ValueError, KeyError, TypeError, tifffile.TiffFileError) as exc:
            raise SpectrumError(f"{path}: a damaged TIFF or one without image data ({exc!r:.80})") from None
        if len(shape) != 3:
            raise SpectrumError(
                f"{path}: a spectral TIFF must hold a 3-D stack (one page per band); got shape "
                f"{shape} (axes {axes!r})"
            )
        order = (0, 1, 2) if axes.endswith("S") else (1, 2, 0)
        offset = series.dataoffset
        dtype = np.dtype(series.dtype)
        claimed = claimed_bytes(shape, dtype.itemsize, f"{path}: the TIFF's shape")
        what = f"the TIFF claims pages of {_describe(shape, dtype)}"
        values: MappedArray | np.ndarray
        if offset is not None:  # contiguous and uncompressed: read lazily, streamed
            check_file_claim(path, claimed, what, offset=int(offset))
            values = MappedArray(str(path), dtype.newbyteorder(tif.byteorder).str, shape, int(offset), order)
        else:  # compressed or scattered: read whole
            check_file_claim(path, claimed, what, compressed_bytes=path.stat().st_size)
            check_bytes(claimed, f"{path}: {what} (compressed TIFFs are read whole; write it "
                        "uncompressed to stream it)", budget=budget)
            try:
                values = np.transpose(series.asarray(), order)
            except (ValueError, KeyError, TypeError, IndexError, tifffile.TiffFileError) as exc:
                raise SpectrumError(f"{path}: the TIFF's pages cannot be read ({exc!r:.80})") from None
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
#
# Why this reader is ours and not spectral.io.envi (issue 24; checked against spectral 0.25,
# the current release): spectral's ``envi.open`` checks neither the size the header claims
# against the file's length nor against the memory budget (its ``envi.py`` never looks at the
# file's size; a header claiming 100000 x 100000 x 31 over a 1 kB file opens, and its spectral
# libraries are read with ``np.fromfile`` of the claimed count before anything is checked), it
# parses ``bbl`` but does not drop the bad bands, leaves ``data ignore value`` unapplied (NaN
# only for spectral libraries) and applies ``reflectance scale factor`` only in some read
# paths. The fuzz suite (tests/fuzz/test_fuzz_resources.py, tests/images/test_images_io.py) demands all of
# these before allocation, so using spectral would mean parsing the header here first anyway,
# then opening the file a second time through it: this reader (header parse, checks, one
# memory map) stays.


def _envi_header_for(path: Path) -> Path | None:
    for candidate in (Path(str(path) + ".hdr"), path.with_suffix(".hdr")):
        if candidate.is_file() and candidate != path:
            return candidate
    return None


def read_envi_header(path) -> dict[str, str]:
    """The fields of an ENVI header file, lower-case keys, values as text.

    Multi-line ``{...}`` values are joined; ``;`` comment lines are skipped.

    Parameters
    ----------
    path : str or os.PathLike
        The ``.hdr`` file.

    Returns
    -------
    dict of str to str
        Field name (lower case) → value as written (braces kept).

    Raises
    ------
    SpectrumError
        The file does not start with the line ``ENVI``, or a ``{`` is never closed.

    References
    ----------
    L3Harris Geospatial, *ENVI Header Files* (file format description).

    Examples
    --------
    >>> import tempfile, pathlib
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     header = pathlib.Path(folder) / "cube.hdr"
    ...     _ = header.write_text("ENVI\\nsamples = 4\\nwavelength = {400,\\n 500}\\n; a comment\\n")
    ...     read_envi_header(header)
    {'samples': '4', 'wavelength': '{400, 500}'}
    """
    path = Path(path)
    lines = path.read_text(encoding="utf-8", errors="replace").splitlines()
    if not lines or lines[0].strip() != "ENVI":
        raise SpectrumError(f"{path}: not an ENVI header (the first line must be 'ENVI')")
    fields: dict[str, str] = {}
    key: str = ""  # the field whose '{...}' value is pending (set whenever pending is)
    pending: str | None = None
    for line in lines[1:]:
        if pending is not None:
            pending += " " + line.strip()
            if "}" in line:
                fields[key] = pending
                key, pending = "", None
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


def _read_envi(path: Path, wavelengths_nm, wavelength_units, raw: bool = False) -> SpectralCube:
    header, raw_file, fields = _envi_files(path)
    layout = _envi_layout(fields, header)
    _check_envi_size(raw_file, header, layout)  # before anything is read
    wavelengths = _envi_wavelengths(fields, header, layout.bands, wavelengths_nm, wavelength_units)
    values = MappedArray(str(raw_file), layout.dtype.str, layout.file_shape, layout.offset, layout.axes)
    corrections = _envi_corrections(fields, header, layout.bands, wavelength_units)
    if raw:
        return SpectralCube(values, wavelengths, str(header), corrections)
    return _envi_corrected(values, wavelengths, header, layout.bands, corrections)


def _envi_files(path: Path) -> tuple[Path, Path, dict[str, str]]:
    """The header, the raw data file and the header's fields, for a path to either file."""
    if path.suffix.lower() == ".hdr":
        header = path
        fields = read_envi_header(header)
        stem = path.with_suffix("")
        raw_file = next(
            (Path(str(stem) + s) for s in _ENVI_RAW_SUFFIXES if Path(str(stem) + s).is_file()),
            None,
        )
        if raw_file is None:
            raise SpectrumError(
                f"{header}: no raw data file beside the header (looked for {stem.name} with "
                f"suffixes {', '.join(repr(s) for s in _ENVI_RAW_SUFFIXES)})"
            )
    else:
        found = _envi_header_for(path)
        assert found is not None  # read_cube sends a raw file here only when its header exists
        raw_file, header = path, found
        fields = read_envi_header(header)
    return header, raw_file, fields


class _EnviLayout(NamedTuple):
    """How the header says the numbers are stored: sizes, header offset, dtype and interleave."""

    samples: int
    lines: int
    bands: int
    offset: int
    dtype: np.dtype
    file_shape: tuple[int, int, int]  # the array as stored
    axes: tuple[int, int, int]  # its axes in (rows, columns, bands) order


def _envi_layout(fields: dict, header: Path) -> _EnviLayout:
    """The storage layout from the header's fields, each checked (nothing is read yet)."""
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
    return _EnviLayout(samples, lines, bands, offset, dtype, file_shape, axes)


def _check_envi_size(raw_file: Path, header: Path, layout: _EnviLayout) -> None:
    """Refuse a raw file whose length, or whose bytes stored on disk, differ from the header's claim."""
    samples, lines, bands, offset, dtype = layout[:5]
    expected = offset + samples * lines * bands * dtype.itemsize
    size = raw_file.stat().st_size
    if size != expected:
        raise SpectrumError(
            f"{raw_file}: the file has {size} bytes but the header ({samples} samples x {lines} lines x"
            f" {bands} bands of {dtype.name} + {offset} header bytes) describes {expected}"
        )
    check_file_claim(raw_file, expected - offset, f"the header ({header.name}) claims "
                     f"{samples} x {lines} x {bands} {dtype.name}", offset=offset)


def _envi_wavelengths(fields: dict, header: Path, bands: int, wavelengths_nm, wavelength_units) -> np.ndarray:
    """The wavelengths, nm: those given, else the header's ``wavelength`` list in its units."""
    if wavelengths_nm is not None:
        return _given_wavelengths(wavelengths_nm, header)
    if "wavelength" not in fields:
        raise SpectrumError(
            f"{header}: missing wavelengths: the header has no 'wavelength' field; give them "
            "with wavelengths_nm=..."
        )
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
    return wavelengths_to_nm(numbers, units, str(header))


def _envi_corrected(values, wavelengths: np.ndarray, header: Path, bands: int, corrections: dict) -> SpectralCube:
    """The cube with the header's corrections (bad bands dropped, scale factor, ignore value) applied."""
    keep, divisor, ignore = corrections.get("bbl"), corrections.get("reflectance scale factor"), None
    ignore = corrections.get("data ignore value")
    applied = []
    metadata = {key: corrections[key] for key in ("fwhm_nm",) if key in corrections}
    if keep is not None and not all(keep):
        kept = tuple(int(i) for i in np.flatnonzero(keep))
        if not kept:
            raise SpectrumError(f"{header}: 'bbl' marks every band bad; nothing to read")
        wavelengths = wavelengths[list(kept)]
        if "fwhm_nm" in metadata:
            metadata["fwhm_nm"] = metadata["fwhm_nm"][list(kept)]
        applied.append(f"dropped {bands - len(kept)} bad band(s) listed in 'bbl'")
    else:
        kept = tuple(range(bands))
    if divisor is not None:
        applied.append(f"divided by the reflectance scale factor {divisor:g}")
    if ignore is not None:
        applied.append(f"values equal to the data ignore value {ignore:g} are NaN (masked)")
    if not applied:
        return SpectralCube(values, wavelengths, str(header), metadata)
    metadata["applied"] = tuple(applied)
    corrected = CorrectedArray(values, kept, 1.0 if divisor is None else divisor, ignore)
    return SpectralCube(corrected, wavelengths, str(header), metadata)


def _envi_corrections(fields: dict, header: Path, bands: int, wavelength_units) -> dict:
    """The header fields that say how to read the numbers, parsed and checked."""
    found: dict[str, object] = {}
    for key in ("reflectance scale factor", "data ignore value"):
        if key in fields:
            try:
                value = float(fields[key])
            except ValueError:
                raise SpectrumError(f"{header}: {key!r} must be a number; got {fields[key]!r}") from None
            if not np.isfinite(value) or (key == "reflectance scale factor" and value <= 0):
                raise SpectrumError(f"{header}: {key!r} must be a finite (positive) number; got {fields[key]!r}")
            found[key] = value
    for key in ("bbl", "fwhm"):
        if key not in fields:
            continue
        listed = _envi_list(fields[key])
        if len(listed) != bands:
            raise SpectrumError(f"{header}: {key!r} lists {len(listed)} values but 'bands' = {bands}; they must match")
        try:
            numbers = np.array([float(item) for item in listed])
        except ValueError:
            raise SpectrumError(f"{header}: {key!r} values must be numbers") from None
        if key == "bbl":
            if not np.all(np.isin(numbers, (0.0, 1.0))):
                raise SpectrumError(f"{header}: 'bbl' values must be 1 (good band) or 0 (bad band)")
            found["bbl"] = numbers.astype(bool)
        else:
            units = fields.get("wavelength units", wavelength_units)
            scale = wavelengths_to_nm([1.0], units, f"{header} ('fwhm', in the wavelength units)")[0]
            found["fwhm_nm"] = numbers * scale
    return found


@dataclass(frozen=True)
class CorrectedArray:
    """Stored cube values read with an ENVI header's corrections applied on every access.

    Bad bands (``bands`` lists those kept) are dropped, values are divided by ``divisor`` (the
    reflectance scale factor) and values equal to ``ignore`` (the data ignore value) become NaN.
    Reads return float32 (float64 when stored as float64). Like :class:`MappedArray`, it reads
    only what is indexed and pickles as its layout.
    """

    stored: Any  # a MappedArray or an ndarray, read by indexing
    bands: tuple[int, ...]
    divisor: float = 1.0
    ignore: float | None = None

    @property
    def dtype(self) -> np.dtype:
        return np.dtype(np.float64 if np.dtype(self.stored.dtype) == np.float64 else np.float32)

    @property
    def shape(self) -> tuple[int, int, int]:
        rows, columns, _ = self.stored.shape
        return (rows, columns, len(self.bands))

    @property
    def ndim(self) -> int:
        return 3

    def __len__(self) -> int:
        return self.shape[0]

    def __getitem__(self, key) -> np.ndarray:
        key = key if isinstance(key, tuple) else (key,)
        if any(k is Ellipsis for k in key) or len(key) > 3:
            return np.asarray(self)[key]
        block = np.asarray(self.stored[key[:2]])[..., list(self.bands)]
        out = block.astype(self.dtype)
        if self.divisor != 1.0:
            out /= self.divisor
        if self.ignore is not None:
            out[block == self.ignore] = np.nan
        return out[..., key[2]] if len(key) == 3 else out

    def __array__(self, dtype=None, copy=None) -> np.ndarray:
        values = self[:, :]
        return values if dtype is None else values.astype(dtype)


# --- MATLAB --------------------------------------------------------------------------------


@dataclass(frozen=True)
class MatlabH5Array:
    """A MATLAB v7.3 (HDF5) array read lazily in MATLAB's order (rows, columns, bands).

    MATLAB writes column-major arrays, so HDF5 sees the axes reversed: an (H, W, K) cube is
    stored as (K, W, H). Indexing reverses the key, reads only that part with h5py and
    transposes it back. It pickles as the path and the dataset name.
    """

    path: str
    name: str
    stored_shape: tuple[int, ...]
    stored_dtype: str

    @property
    def dtype(self) -> np.dtype:
        return np.dtype(self.stored_dtype)

    @property
    def shape(self) -> tuple[int, ...]:
        return tuple(reversed(self.stored_shape))

    @property
    def ndim(self) -> int:
        return len(self.stored_shape)

    def __len__(self) -> int:
        return self.shape[0]

    def __getitem__(self, key) -> np.ndarray:
        import h5py

        key = key if isinstance(key, tuple) else (key,)
        if any(k is Ellipsis for k in key) or len(key) > self.ndim:
            return np.asarray(self)[key]
        key = key + (slice(None),) * (self.ndim - len(key))
        try:
            with h5py.File(self.path, "r") as handle:
                block = np.asarray(handle[self.name][tuple(reversed(key))])
        except (TypeError, ValueError, IndexError):
            raise  # a bad index: the caller's error, not the file's
        except Exception as exc:  # a damaged file, as in _read_mat73
            reason = f"{type(exc).__name__}: {exc}"
            raise SpectrumError(f"{self.path}: variable {self.name!r} cannot be read ({reason})") from None
        return block.transpose(tuple(reversed(range(block.ndim))))

    def __array__(self, dtype=None, copy=None) -> np.ndarray:
        values = self[:, :, :]
        return values if dtype is None else values.astype(dtype)


def _read_mat(path: Path, wavelengths_nm, wavelength_units, variable, budget: int) -> SpectralCube:
    with open(path, "rb") as handle:
        head = handle.read(128)
    if head.startswith(b"MATLAB 7.3"):
        return _read_mat73(path, wavelengths_nm, wavelength_units, variable)
    return _read_mat5(path, wavelengths_nm, wavelength_units, variable, budget)


def _mat_choice(path: Path, shapes: dict[str, tuple], numeric: set[str], variable) -> str:
    """The cube variable: ``variable`` if given, else the only 3-D numeric one."""
    if variable is not None:
        if variable not in shapes:
            raise SpectrumError(f"{path}: no variable {variable!r}; variables: {sorted(shapes)}")
        if variable not in numeric or len(shapes[variable]) != 3:
            raise SpectrumError(f"{path}: variable {variable!r} is not a 3-D numeric array ({shapes[variable]})")
        return variable
    cubes = sorted(name for name, shape in shapes.items() if len(shape) == 3 and name in numeric)
    if len(cubes) != 1:
        found = "none" if not cubes else ", ".join(cubes)
        raise SpectrumError(
            f"{path}: expected one 3-D numeric variable (rows, columns, bands), found {found}; "
            f"choose one with variable=... (variables: {sorted(shapes)})"
        )
    return cubes[0]


def _mat_wavelengths(path: Path, load, shapes, bands: int, wavelengths_nm, wavelength_units) -> np.ndarray:
    if wavelengths_nm is not None:
        return _given_wavelengths(wavelengths_nm, path)
    for name in _MAT_WAVELENGTH_NAMES:
        if name in shapes and int(np.prod(shapes[name])) == bands:
            units = "nm" if name == "wavelengths_nm" else wavelength_units
            return wavelengths_to_nm(np.ravel(load(name)), units, f"{path} (variable {name!r})")
    raise SpectrumError(
        f"{path}: missing wavelengths: no variable {' / '.join(_MAT_WAVELENGTH_NAMES)} with {bands} "
        "values; give them with wavelengths_nm=... (--wavelengths on the command line)"
    )


def _read_mat5(path: Path, wavelengths_nm, wavelength_units, variable, budget: int) -> SpectralCube:
    """Read a MATLAB v4/v5 cube in a child process.

    scipy's MAT v5 parser is compiled code, and some damaged files crash the whole process
    inside it (a segmentation fault, found by ``tests/fuzz/test_fuzz_io.py``): no exception reaches
    Python. In a child process (forked from a forkserver, so a crash costs milliseconds) such a
    file becomes one clear error and the caller survives.
    """
    from concurrent.futures.process import BrokenProcessPool

    global _MAT5_WORKER
    if _MAT5_WORKER is None:
        import atexit
        import multiprocessing
        from concurrent.futures import ProcessPoolExecutor

        _MAT5_WORKER = ProcessPoolExecutor(max_workers=1, mp_context=multiprocessing.get_context("forkserver"))
        atexit.register(_MAT5_WORKER.shutdown, cancel_futures=True)  # before the interpreter tears down
    try:
        return _MAT5_WORKER.submit(_read_mat5_here, Path(path), wavelengths_nm, wavelength_units, variable,
                                   budget).result()
    except BrokenProcessPool:
        _MAT5_WORKER = None  # the worker died with the file: the next read starts a new one
        raise SpectrumError(
            f"{path}: a damaged MATLAB v5 file: the MAT reader stopped on it (re-save it, or as v7.3/ENVI)"
        ) from None


#: The child process that reads MATLAB v5 files (started on the first such read).
_MAT5_WORKER: ProcessPoolExecutor | None = None


def _read_mat5_here(path: Path, wavelengths_nm, wavelength_units, variable, budget: int) -> SpectralCube:
    import scipy.io

    # scipy's MAT parser meets damaged files with whatever its code hits (IndexError, KeyError,
    # struct.error, zlib.error, …): any of them means "this file cannot be read", said in one line.
    errors = (Exception,)
    try:
        listing = scipy.io.whosmat(str(path))
    except errors as exc:
        raise SpectrumError(f"{path}: not a MATLAB .mat file scipy can read (v4/v5) ({exc})") from None
    shapes = {name: tuple(shape) for name, shape, _ in listing}
    numeric = {name for name, _, kind in listing if kind in _MAT_CLASS_BYTES}
    name = _mat_choice(path, shapes, numeric, variable)
    kind = next(kind for n, _, kind in listing if n == name)
    claimed = claimed_bytes(shapes[name], _MAT_CLASS_BYTES[kind], f"{path}: variable {name!r}: shape")
    what = f"variable {name!r} claims shape {shapes[name]} of {kind}"
    check_file_claim(path, claimed, what, compressed_bytes=path.stat().st_size)  # v5 may be compressed
    check_bytes(claimed, f"{path}: {what} (MATLAB v5 files are read whole; save it as v7.3 or ENVI to "
                "stream it)", budget=budget)

    def load(variable_name):
        try:
            return scipy.io.loadmat(str(path), variable_names=[variable_name])[variable_name]
        except errors as exc:
            raise SpectrumError(f"{path}: variable {variable_name!r} cannot be read ({exc})") from None

    values = load(name)
    wavelengths = _mat_wavelengths(path, load, shapes, values.shape[2], wavelengths_nm, wavelength_units)
    return SpectralCube(np.ascontiguousarray(values), wavelengths, str(path), {"variable": name, "mat": "v5"})


def _read_mat73(path: Path, wavelengths_nm, wavelength_units, variable) -> SpectralCube:
    import h5py

    try:
        handle = h5py.File(path, "r")
    except OSError as exc:
        raise SpectrumError(f"{path}: says MATLAB 7.3 but is not a readable HDF5 file ({exc})") from None
    try:
        return _mat73_cube(path, handle, wavelengths_nm, wavelength_units, variable)
    except SpectrumError:
        raise
    except Exception as exc:  # h5py on a damaged file: KeyError, RuntimeError, OSError, … (see _read_mat5)
        raise SpectrumError(f"{path}: a damaged MATLAB 7.3 (HDF5) file ({type(exc).__name__}: {exc})") from None
    finally:
        handle.close()


def _mat73_cube(path: Path, handle, wavelengths_nm, wavelength_units, variable) -> SpectralCube:
    import h5py

    datasets = {name: item for name, item in handle.items() if isinstance(item, h5py.Dataset)}
    shapes = {name: tuple(reversed(item.shape)) for name, item in datasets.items()}
    numeric = {name for name, item in datasets.items() if item.dtype.kind in "biuf"}
    name = _mat_choice(path, shapes, numeric, variable)
    dataset = datasets[name]
    claimed = claimed_bytes(dataset.shape, dataset.dtype.itemsize, f"{path}: variable {name!r}: shape")
    what = f"variable {name!r} claims {_describe(shapes[name], dataset.dtype)}"
    if dataset.chunks is None:  # contiguous: its bytes must be in the file
        check_file_claim(path, claimed, what, offset=dataset.id.get_offset() or 0)
    else:  # chunked (and perhaps compressed): chunks never written read as the fill value
        check_file_claim(path, claimed, f"{what} in chunks (chunks never written read as the fill value)",
                         compressed_bytes=dataset.id.get_storage_size())
    values = MatlabH5Array(str(path), name, tuple(dataset.shape), dataset.dtype.str)

    def load(variable_name):
        return np.asarray(datasets[variable_name])

    wavelengths = _mat_wavelengths(path, load, shapes, values.shape[2], wavelengths_nm, wavelength_units)
    return SpectralCube(values, wavelengths, str(path), {"variable": name, "mat": "v7.3"})


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
                f"{path}: no variable {variable!r}; variables: {sorted(map(str, dataset.data_vars))}"
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
    _check_hdf5_storage(path, name)
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


def _check_hdf5_storage(path: Path, name: str) -> None:
    """The bytes an HDF5 variable claims against those stored (chunks never written are fill value)."""
    import h5py

    with h5py.File(path, "r") as handle:
        dataset = handle.get(name)
        if not isinstance(dataset, h5py.Dataset):
            return
        claimed = claimed_bytes(dataset.shape, dataset.dtype.itemsize, f"{path}: variable {name!r}: shape")
        what = f"variable {name!r} claims {_describe(dataset.shape, dataset.dtype)}"
        if dataset.chunks is None:
            check_file_claim(path, claimed, what, offset=dataset.id.get_offset() or 0)
        else:
            check_file_claim(path, claimed, f"{what} in chunks (chunks never written read as the fill value)",
                             compressed_bytes=dataset.id.get_storage_size())


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
    band = read_image(file)  # spectrocolor.imagefiles: PNG bit for bit, TIFF through tifffile
    if band.ndim != 2:
        raise SpectrumError(
            f"{file}: band images must have one channel; got shape {band.shape}"
        )
    return band


def _band_bytes(file: Path) -> int:
    """Bytes of one band image's samples, from its header (nothing is decoded)."""
    try:
        return image_header(file).nbytes
    except SpectrumError as exc:
        raise SpectrumError(f"{file}: cannot be read as a band image ({exc})") from None


def _read_folder(folder: Path, wavelength_units, budget: int) -> SpectralCube:
    files = sorted(f for f in folder.iterdir() if f.suffix.lower() in _FOLDER_SUFFIXES)
    if not files:
        raise SpectrumError(f"{folder}: no .png or .tif band images in the folder")
    wavelengths = np.array([_wavelength_from_name(f, wavelength_units) for f in files])
    # the bands and the stacked cube are held together
    check_bytes(2 * sum(_band_bytes(f) for f in files),
                f"{folder}: {len(files)} band images (a folder is read whole)", budget=budget)
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

