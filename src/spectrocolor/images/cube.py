"""The spectral cube: a (rows, columns, bands) array and its wavelengths in nanometres.

A cube's values may live in memory (``ndarray``), or stay on disk as a :class:`MappedArray`
that opens the file on each access, so a cube larger than memory is read block by block
and can be shipped to dask workers as a few bytes (a path and a layout), not as data. A
deflate-compressed ``.npz`` member larger than the memory budget is a :class:`ZipMemberArray`:
its rows are inflated as they are asked for, top to bottom.
"""

from __future__ import annotations

import os
import re
import threading
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..errors import SpectrumError

__all__ = ["SpectralCube", "MappedArray", "ZipMemberArray", "wavelengths_to_nm"]

# accepted spellings of wavelength units (lower case, spaces removed) -> nanometres per unit
_UNITS_TO_NM = {
    "nm": 1.0,
    "nanometer": 1.0,
    "nanometers": 1.0,
    "nanometre": 1.0,
    "nanometres": 1.0,
    "um": 1000.0,
    "µm": 1000.0,
    "μm": 1000.0,  # Greek mu as well as the micro sign
    "micron": 1000.0,
    "microns": 1000.0,
    "micrometer": 1000.0,
    "micrometers": 1000.0,
    "micrometre": 1000.0,
    "micrometres": 1000.0,
}


def wavelengths_to_nm(values, units: str | None, source: str) -> np.ndarray:
    """Wavelengths given in ``units`` converted to nanometres, checked strictly increasing.

    Parameters
    ----------
    values : array_like, shape (K,)
        Wavelengths in ``units``.
    units : str or None
        "nm" (nanometres) or "um" / "µm" / "micrometers" (converted by × 1000); other
        spellings of these are accepted case-insensitively. None or anything else is an error:
        no unit is guessed.
    source : str
        Where the wavelengths came from, for error messages (a file name).

    Returns
    -------
    ndarray, shape (K,), float64
        Wavelengths in nm.

    Raises
    ------
    SpectrumError
        For missing or unknown units, non-numbers, an empty list, non-finite values or
        wavelengths that are not strictly increasing.

    Examples
    --------
    >>> wavelengths_to_nm([0.4, 0.5], "µm", "cube.tif").tolist()
    [400.0, 500.0]
    """
    if units is None:
        raise SpectrumError(
            f"{source}: the wavelength units are not given; say them (e.g. wavelength_units='nm'"
            " or 'um'); units are never guessed"
        )
    key = re.sub(r"\s+", "", str(units)).lower()
    if key not in _UNITS_TO_NM:
        raise SpectrumError(
            f"{source}: unknown wavelength units {units!r}; accepted: nanometers (nm) or "
            "micrometers (um, µm, microns)"
        )
    try:
        nm = np.asarray(values, dtype=np.float64).reshape(-1) * _UNITS_TO_NM[key]
    except (TypeError, ValueError) as exc:
        raise SpectrumError(f"{source}: wavelengths must be numbers; got {values!r:.80}") from exc
    if nm.size == 0:
        raise SpectrumError(f"{source}: the wavelength list is empty")
    if not np.all(np.isfinite(nm)):
        raise SpectrumError(f"{source}: wavelengths must be finite; got {nm}")
    if nm.size > 1 and not np.all(np.diff(nm) > 0):
        raise SpectrumError(
            f"{source}: wavelengths must be strictly increasing; got {np.array2string(nm)}"
        )
    return nm


@dataclass(frozen=True)
class MappedArray:
    """A read-only array stored in a raw binary file, opened with ``np.memmap`` on each access.

    Indexing returns an in-memory ``ndarray`` of the selected part; nothing else is read.
    It pickles as its path and layout, so dask workers open the file themselves.

    Parameters
    ----------
    path : str
        The raw file.
    stored_dtype : str
        NumPy dtype string with byte order (e.g. ">f4").
    file_shape : tuple of int
        Shape of the array as stored (C order), e.g. (bands, lines, samples) for ENVI BSQ.
    offset : int
        Bytes to skip at the start of the file (a header).
    axes : tuple of int
        Transposition from the stored order to (rows, columns, bands).

    Examples
    --------
    >>> import tempfile, pathlib
    >>> import numpy as np
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     raw = pathlib.Path(folder) / "cube.raw"
    ...     np.arange(24, dtype="<f4").tofile(raw)  # 2 bands of 3 x 4 pixels, band-sequential
    ...     cube = MappedArray(str(raw), "<f4", (2, 3, 4), 0, (1, 2, 0))
    ...     print(cube.shape, cube[0, 0].tolist())
    (3, 4, 2) [0.0, 12.0]
    """

    path: str
    stored_dtype: str
    file_shape: tuple[int, ...]
    offset: int = 0
    axes: tuple[int, ...] = (0, 1, 2)

    def _open(self) -> np.ndarray:
        stored = np.memmap(
            self.path, dtype=np.dtype(self.stored_dtype), mode="r", offset=self.offset,
            shape=self.file_shape,
        )
        return stored.transpose(self.axes)

    @property
    def dtype(self) -> np.dtype:
        """The dtype of what reads return: the stored type in native byte order."""
        return np.dtype(self.stored_dtype).newbyteorder("=")

    @property
    def shape(self) -> tuple[int, ...]:
        return tuple(self.file_shape[axis] for axis in self.axes)

    @property
    def ndim(self) -> int:
        return len(self.file_shape)

    @property
    def nbytes(self) -> int:
        return int(np.prod(self.file_shape)) * np.dtype(self.stored_dtype).itemsize

    def __getitem__(self, key) -> np.ndarray:
        rows, rest = _split_row_key(key, self.shape[0])
        if rows is not None and self.axes[0] in (0, 1):
            return self._read_rows(*rows)[rest]
        return np.asarray(self._open()[key], dtype=self.dtype)

    def _read_rows(self, start: int, stop: int) -> np.ndarray:
        """Rows start:stop as (rows, columns, bands), read with plain file reads (no mapping).

        Mapping the whole file would count the file against the address-space limit of the
        process; reading only the rows keeps memory (and address space) bounded by the block.
        """
        dtype = np.dtype(self.stored_dtype)
        first, second, third = self.file_shape
        with open(self.path, "rb") as handle:
            if self.axes[0] == 0:  # rows are the stored outer axis: one contiguous read
                count = (stop - start) * second * third
                handle.seek(self.offset + start * second * third * dtype.itemsize)
                block = np.fromfile(handle, dtype=dtype, count=count)
                block = block.reshape(stop - start, second, third)
            else:  # rows are the middle axis (e.g. ENVI BSQ): one read per outer index
                block = np.empty((first, stop - start, third), dtype=dtype)
                for index in range(first):
                    handle.seek(self.offset + (index * second + start) * third * dtype.itemsize)
                    block[index] = np.fromfile(
                        handle, dtype=dtype, count=(stop - start) * third
                    ).reshape(stop - start, third)
        # block is stored-order with the row axis cut; apply the same transposition
        return block.transpose(self.axes).astype(self.dtype, copy=False)

    def __array__(self, dtype=None, copy=None) -> np.ndarray:
        return np.asarray(self._open(), dtype=self.dtype if dtype is None else dtype)

    def __len__(self) -> int:
        return self.shape[0]


class ZipMemberArray:
    """A read-only C-order array in a deflate-compressed ZIP member (an ``.npz`` array), read by rows.

    Rows are inflated as they are asked for: reading top to bottom (as the streamed
    conversions do) inflates the member once, holding one block of rows and zlib's window; a
    read above the last one starts the member again from its beginning. Indexing with
    anything but a range of rows reads the whole array. It pickles as its path and layout.

    Parameters
    ----------
    path : str
        The ZIP archive.
    member : str
        The member's name (e.g. ``"values.npy"``).
    stored_dtype : str
        NumPy dtype string with byte order (e.g. ``"<f4"``).
    shape : tuple of int
        The array's shape (rows first).
    data_offset : int
        Bytes of the member before the array's data (the ``.npy`` header).

    Examples
    --------
    >>> import tempfile, pathlib, zipfile
    >>> import numpy as np
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     path = pathlib.Path(folder) / "cube.npz"
    ...     np.savez_compressed(path, values=np.arange(24, dtype="<f4").reshape(4, 3, 2))
    ...     cube = ZipMemberArray(str(path), "values.npy", "<f4", (4, 3, 2), 128)
    ...     print(cube.shape, cube[1:3, 0].tolist(), cube[0:1, 2].tolist())
    (4, 3, 2) [[6.0, 7.0], [12.0, 13.0]] [[4.0, 5.0]]
    """

    def __init__(self, path: str, member: str, stored_dtype: str, shape: tuple[int, ...],
                 data_offset: int) -> None:
        self.path, self.member, self.stored_dtype = path, member, stored_dtype
        self.shape = tuple(int(n) for n in shape)
        self.data_offset = int(data_offset)
        self._stream: Any = None
        self._archive: Any = None
        self._row = 0
        self._lock = threading.Lock()  # one reader at a time (dask's threads share the stream)

    def __getstate__(self) -> dict:
        return {**self.__dict__, "_stream": None, "_archive": None, "_row": 0, "_lock": None}

    def __setstate__(self, state: dict) -> None:
        self.__dict__.update(state, _lock=threading.Lock())

    def __repr__(self) -> str:
        return f"ZipMemberArray({self.path!r}, {self.member!r}, {self.stored_dtype!r}, {self.shape})"

    @property
    def dtype(self) -> np.dtype:
        """The dtype of what reads return: the stored type in native byte order."""
        return np.dtype(self.stored_dtype).newbyteorder("=")

    @property
    def ndim(self) -> int:
        return len(self.shape)

    @property
    def nbytes(self) -> int:
        return int(np.prod(self.shape, dtype=np.int64)) * np.dtype(self.stored_dtype).itemsize

    def __len__(self) -> int:
        return self.shape[0]

    def _row_bytes(self) -> int:
        return int(np.prod(self.shape[1:], dtype=np.int64)) * np.dtype(self.stored_dtype).itemsize

    def _rewind(self) -> None:
        import zipfile

        self.close()
        archive = zipfile.ZipFile(self.path)
        stream = archive.open(self.member)
        stream.read(self.data_offset)
        self._stream, self._archive, self._row = stream, archive, 0

    def close(self) -> None:
        """Close the member (the next read opens it again)."""
        if self._stream is not None:
            self._stream.close()
            self._archive.close()
        self._stream, self._archive, self._row = None, None, 0

    def _read(self, start: int, stop: int) -> np.ndarray:
        if self._stream is None or start < self._row:
            self._rewind()
        row_bytes = self._row_bytes()
        while self._row < start:  # skip forward, a block of rows at a time
            skip = min(start - self._row, max(1, 2**24 // max(row_bytes, 1)))
            if len(self._stream.read(skip * row_bytes)) != skip * row_bytes:
                raise SpectrumError(f"{self.path}: member {self.member!r} ends before row {start}")
            self._row += skip
        data = self._stream.read((stop - start) * row_bytes)
        if len(data) != (stop - start) * row_bytes:
            raise SpectrumError(f"{self.path}: member {self.member!r} ends before row {stop}")
        self._row = stop
        block = np.frombuffer(data, np.dtype(self.stored_dtype)).reshape((stop - start, *self.shape[1:]))
        return block.astype(self.dtype, copy=False)

    def __getitem__(self, key) -> np.ndarray:
        rows, rest = _split_row_key(key, self.shape[0])
        if rows is not None:
            with self._lock:
                return self._checked_read(*rows)[rest]
        return np.asarray(self)[key]

    def _checked_read(self, start: int, stop: int) -> np.ndarray:
        """``_read``, with a damaged member (bad deflate data, CRC-32) named in one error."""
        import zipfile
        import zlib

        try:
            return self._read(start, stop)
        except (zipfile.BadZipFile, zlib.error, EOFError, OSError) as exc:
            self.close()
            raise SpectrumError(f"{self.path}: member {self.member!r} cannot be read ({exc})") from None

    def __array__(self, dtype=None, copy=None) -> np.ndarray:
        with self._lock:
            whole = self._checked_read(0, self.shape[0]) if self.shape[0] else np.empty(self.shape, self.dtype)
        return np.asarray(whole, dtype=self.dtype if dtype is None else dtype)


@dataclass(frozen=True)
class SpectralCube:
    """A spectral image: values (rows, columns, bands) and the band wavelengths in nm.

    Attributes
    ----------
    values : ndarray or MappedArray or array-like, shape (H, W, K)
        Spectral values as stored in the file (no scaling applied: a reflectance stored as
        integer codes stays integer codes; pass ``scale=`` to the conversions).
    wavelengths_nm : ndarray, shape (K,)
        Band centre wavelengths in nanometres, strictly increasing.
    source : str
        The file or folder the cube was read from ("" for an in-memory cube).
    metadata : dict
        Other header fields worth keeping (e.g. ENVI "reflectance scale factor").

    Raises
    ------
    SpectrumError
        For values that are not (H, W, K) numbers, or wavelengths that do not match the bands
        or are not strictly increasing.

    Examples
    --------
    >>> import numpy as np
    >>> cube = SpectralCube(np.full((2, 3, 31), 0.5), np.arange(400, 701, 10))
    >>> cube.shape, cube.wavelengths_nm[[0, -1]].tolist()
    ((2, 3, 31), [400.0, 700.0])
    """

    values: Any  # an ndarray, a MappedArray or another array-like read by indexing (dask, h5py)
    wavelengths_nm: np.ndarray
    source: str = ""
    metadata: dict = field(default_factory=dict)

    def __post_init__(self) -> None:
        shape = tuple(self.values.shape)
        name = self.source or "cube"
        if len(shape) != 3:
            raise SpectrumError(
                f"{name}: a spectral cube must have shape (rows, columns, bands); got {shape}"
            )
        dtype = getattr(self.values, "dtype", None)
        if dtype is not None and np.dtype(dtype).kind not in "biuf":
            raise SpectrumError(f"{name}: values must be numbers; the cube holds dtype {dtype}")
        wavelengths = np.asarray(self.wavelengths_nm, dtype=np.float64)
        if wavelengths.ndim != 1 or wavelengths.size != shape[2]:
            raise SpectrumError(
                f"{name}: {wavelengths.size} wavelengths for {shape[2]} bands; the band count and"
                " the wavelength count must match"
            )
        if wavelengths.size > 1 and not np.all(np.diff(wavelengths) > 0):
            raise SpectrumError(f"{name}: wavelengths_nm must be strictly increasing")
        object.__setattr__(self, "wavelengths_nm", wavelengths)

    @property
    def shape(self) -> tuple[int, int, int]:
        return tuple(self.values.shape)

    def to_numpy(self) -> np.ndarray:
        """All values in memory as an ndarray (H, W, K) of the stored dtype.

        Returns
        -------
        numpy.ndarray, shape (H, W, K)
            The stored values, unscaled (a memory-mapped cube is read whole).

        Examples
        --------
        >>> import numpy as np
        >>> cube = SpectralCube(np.zeros((2, 3, 4), dtype=np.uint16), [400, 500, 600, 700])
        >>> cube.to_numpy().dtype.name
        'uint16'
        """
        return np.asarray(self.values)

    def to_xarray(self, chunks=None):
        """The cube as an ``xarray.DataArray`` with dims ("y", "x", "wavelength").

        Parameters
        ----------
        chunks : None, int, tuple or dict, optional
            None: values as they are (in memory, or read on access). Otherwise a dask-backed
            array with these chunks (the wavelength axis is always one whole chunk).

        Returns
        -------
        xarray.DataArray
            Dims ``("y", "x", "wavelength")``, the ``wavelength`` coordinate in nm; ready for
            the ``.spectro`` accessor (registered by ``import spectrocolor.images``).

        Examples
        --------
        >>> import numpy as np
        >>> import spectrocolor.images  # registers DataArray.spectro
        >>> array = SpectralCube(np.full((2, 3, 31), 0.5), np.arange(400, 701, 10)).to_xarray(chunks=1)
        >>> array.dims, array.spectro.to_rgb(illuminant="D65").compute().values[0, 0].tolist()
        (('y', 'x', 'wavelength'), [188, 188, 188])
        """
        import xarray as xr

        values = self.values
        if chunks is not None:
            import dask.array as da

            if isinstance(chunks, dict):
                chunks = (chunks.get("y", "auto"), chunks.get("x", "auto"), -1)
            elif isinstance(chunks, int):
                chunks = (chunks, chunks, -1)
            else:
                chunks = (*tuple(chunks)[:2], -1)
            values = da.from_array(values, chunks=chunks, name=f"cube-{_token(self)}")
        elif not isinstance(values, np.ndarray):
            values = np.asarray(values)
        return xr.DataArray(
            values,
            dims=("y", "x", "wavelength"),
            coords={"wavelength": ("wavelength", self.wavelengths_nm, {"units": "nm"})},
            name="spectral_values",
            attrs={"source": self.source},
        )


def _split_row_key(key, n_rows: int):
    """(start, stop) and the remaining key when ``key`` selects a contiguous row range."""
    first, rest = (key[0], (slice(None), *key[1:])) if isinstance(key, tuple) else (key, ())
    if not isinstance(first, slice) or first.step not in (None, 1):
        return None, None
    start, stop, _ = first.indices(n_rows)
    if stop <= start:
        return None, None
    return (start, stop), (rest if rest else slice(None))


def _token(cube: SpectralCube) -> str:
    """A deterministic dask name for a cube (stable across pickling)."""
    import dask.base

    if isinstance(cube.values, MappedArray):
        stat = os.stat(cube.values.path)
        return dask.base.tokenize(cube.values, stat.st_mtime_ns, stat.st_size)
    return dask.base.tokenize(cube.values)
