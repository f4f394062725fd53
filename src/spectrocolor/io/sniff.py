"""Binary files told by their first bytes, before any text decoding: read, or named and refused.

:func:`spectrocolor.io.read_spectra` and :func:`~spectrocolor.io.parse_spectra` call
:func:`binary_format` on the file's bytes first. An ``.xlsx`` workbook (a ZIP archive holding
``xl/workbook.xml``) is answered ``"xlsx"`` and read by :mod:`.xlsx`; a file in a format that is
recognised but not read gets one line naming it and saying what to do instead; anything else is
left to the text readers. The signatures ("magic numbers") are the ones each format's own
specification puts at the start of the file:

* ``PK\x03\x04`` (ZIP) holding ``xl/workbook.xml``: an Office Open XML workbook, read by
  :mod:`.xlsx`; other ZIP archives are named (``.xlsb``, ``.ods``, ``.docx``, ``.npz``, or the
  first member names) with what to do: save as ``.xlsx``/CSV, :func:`spectrocolor.read_cube`,
  or unpack;
* ``D0 CF 11 E0 A1 B1 1A E1``: an OLE2 compound file, a legacy ``.xls`` (or an encrypted
  ``.xlsx``): save it as ``.xlsx`` or CSV;
* ``%PDF-``: a PDF report: export the data instead;
* ``\x89PNG``, ``FF D8 FF``, ``II*\0``/``MM\0*``: PNG, JPEG, TIFF images: spectral images are
  read with :func:`spectrocolor.read_cube`;
* ``\x89HDF`` (HDF5, MATLAB v7.3), ``CDF\x01`` (netCDF), ``MATLAB 5.0 MAT-file``, ``\x93NUMPY``:
  :func:`spectrocolor.read_cube`;
* ``acsp`` at byte 36: an ICC profile (as ArgyllCMS writes), which holds no measurements;
* ``\x1f\x8b``, ``7z\xbc\xaf``, ``Rar!``: gzip, 7-Zip, RAR: unpack first.

References
----------
ECMA-376 / ISO/IEC 29500 (Office Open XML; package = ZIP, APPNOTE.TXT), Microsoft [MS-CFB]
(compound file header signature), ISO 32000 (PDF header), ISO/IEC 15948 (PNG signature), TIFF 6.0
(byte-order header), ICC.1:2010 (profile file signature ``acsp`` at offset 36), The HDF Group
(format signature), Unidata netCDF classic format, MathWorks MAT-file format, NumPy ``.npy``
format (NEP 1).
"""

from __future__ import annotations

import io
import zipfile
from pathlib import Path

from ..errors import SpectrumError
from .text import MAX_FILE_BYTES, codec_name

#: ``(signature, offset, name, advice)``: formats recognised by their first bytes but not read here.
_SIGNATURES = (
    (b"\xd0\xcf\x11\xe0\xa1\xb1\x1a\xe1", 0,
     "a legacy Excel .xls workbook (an OLE2 compound file; also a password-protected .xlsx)",
     "save it as .xlsx (Excel Workbook) or as CSV UTF-8 and read that"),
    (b"%PDF-", 0, "a PDF document",
     "spectra printed in a PDF cannot be read; export the measurements from the instrument software "
     "as CSV, CGATS, CxF3 or .xlsx"),
    (b"\x89PNG\r\n\x1a\n", 0, "a PNG image",
     "read_spectra reads measurement tables; spectral images (a folder of one-band PNG/TIFF images) "
     "are read with spectrocolor.read_cube"),
    (b"\xff\xd8\xff", 0, "a JPEG image",
     "read_spectra reads measurement tables; a JPEG holds RGB, not spectra (spectral images are "
     "read with spectrocolor.read_cube)"),
    (b"II*\x00", 0, "a TIFF image",
     "read_spectra reads measurement tables; a multi-band spectral TIFF is read with spectrocolor.read_cube"),
    (b"MM\x00*", 0, "a TIFF image",
     "read_spectra reads measurement tables; a multi-band spectral TIFF is read with spectrocolor.read_cube"),
    (b"\x89HDF\r\n\x1a\n", 0, "an HDF5 file (MATLAB v7.3, netCDF-4)",
     "spectral cubes in it are read with spectrocolor.read_cube"),
    (b"CDF\x01", 0, "a netCDF file", "spectral cubes in it are read with spectrocolor.read_cube"),
    (b"CDF\x02", 0, "a netCDF file", "spectral cubes in it are read with spectrocolor.read_cube"),
    (b"MATLAB 5.0 MAT-file", 0, "a MATLAB v5 .mat file",
     "spectral cubes in it are read with spectrocolor.read_cube; for one spectrum, save it from "
     "MATLAB with writematrix as CSV"),
    (b"\x93NUMPY", 0, "a NumPy .npy array",
     "read it with numpy.load and make a Spectrum, or read a cube with spectrocolor.read_cube"),
    (b"acsp", 36, "an ICC colour profile (as ArgyllCMS and colour-management software write)",
     "a profile holds no measurements; read the .ti3 or CGATS measurement file it was made from"),
    (b"\x1f\x8b", 0, "a gzip-compressed file", "decompress it and read the file inside"),
    (b"7z\xbc\xaf\x27\x1c", 0, "a 7-Zip archive", "unpack it and read the spectral file inside"),
    (b"Rar!\x1a\x07", 0, "a RAR archive", "unpack it and read the spectral file inside"),
)
#: ZIP local-file header, and the end record of an empty archive.
_ZIP = (b"PK\x03\x04", b"PK\x05\x06")


def binary_format(data: bytes, source: str) -> str | None:
    """``"xlsx"`` for a workbook, None for anything left to the text readers; refuse other known binaries.

    Parameters
    ----------
    data : bytes
        The file's bytes (only the first few are looked at, and a ZIP archive's member names).
    source : str
        The file name, for messages.

    Returns
    -------
    str or None
        ``"xlsx"`` for an Office Open XML workbook, None otherwise.

    Raises
    ------
    SpectrumError
        One line, ``"<source>: this is <format>; <what to do>"``, for a format recognised by its
        signature but not read by :func:`spectrocolor.io.read_spectra` (table in the module
        docstring).

    Examples
    --------
    >>> binary_format(b"wavelength_nm,a\\n400,0.5\\n", "a.csv") is None
    True
    >>> binary_format(b"%PDF-1.7 ...", "report.pdf")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    spectrocolor.errors.SpectrumError: report.pdf: this is a PDF document; spectra printed in a PDF ...
    """
    if data.startswith(_ZIP):
        return _zip_kind(data, source)
    for signature, offset, name, advice in _SIGNATURES:
        if offset and data[:1] != b"\x00":
            continue  # an ICC profile starts with its size (big-endian, under 16 MiB): a text never does
        if data[offset:offset + len(signature)] == signature:
            raise SpectrumError(f"{source}: this is {name}; {advice}")
    return None


def _zip_kind(data: bytes, source: str) -> str:
    try:
        with zipfile.ZipFile(io.BytesIO(data)) as archive:
            names = archive.namelist()
    except (zipfile.BadZipFile, zipfile.LargeZipFile, OSError, ValueError, EOFError, KeyError) as exc:
        raise SpectrumError(f"{source}: a ZIP archive (or an .xlsx workbook) that cannot be opened ({exc}); "
                            "the file is damaged or cut short") from None
    members = set(names)
    if "xl/workbook.xml" in members:
        return "xlsx"
    if "xl/workbook.bin" in members:
        found = "an Excel binary workbook (.xlsb)"
        advice = "save it as .xlsx (Excel Workbook) or as CSV UTF-8 and read that"
    elif "content.xml" in members and "mimetype" in members:
        found = "an OpenDocument file (.ods/.odt)"
        advice = "save it as .xlsx or as CSV UTF-8 and read that"
    elif "word/document.xml" in members or "ppt/presentation.xml" in members:
        found = "a Word or PowerPoint document"
        advice = "export the measurements from the instrument software as CSV, CGATS, CxF3 or .xlsx"
    elif names and all(name.endswith(".npy") for name in names):
        found = "a NumPy .npz archive"
        advice = "spectral cubes in it are read with spectrocolor.read_cube"
    else:
        shown = ", ".join(repr(name[:60]) for name in names[:4]) + (", …" if len(names) > 4 else "")
        found = f"a ZIP archive ({len(names)} members: {shown or 'none'})"
        advice = "unpack it and read the spectral file inside"
    raise SpectrumError(f"{source}: this is {found}; {advice}")


def read_checked(path: Path, encoding: str | None = None) -> bytes:
    """The file's bytes, the ``encoding`` name and the file's size checked first.

    Parameters
    ----------
    path : pathlib.Path
        The file.
    encoding : str or None, default None
        Checked to be a known text codec (an unknown name is the caller's error, reported
        before the file is read); the bytes are not decoded here.

    Returns
    -------
    bytes
        The whole file, for :func:`binary_format` and then the text decoder.

    Raises
    ------
    SpectrumError
        For an unknown encoding or a file larger than
        :data:`spectrocolor.io.text.MAX_FILE_BYTES`.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     path = pathlib.Path(folder) / "a.csv"
    ...     _ = path.write_bytes(b"nm,a")
    ...     read_checked(path)
    b'nm,a'
    """
    if encoding is not None:
        codec_name(encoding)
    size = path.stat().st_size
    if size > MAX_FILE_BYTES:
        raise SpectrumError(
            f"{path}: {size} bytes; spectral tables are read up to {MAX_FILE_BYTES} bytes "
            "(split the file, or read a spectral image with read_cube)"
        )
    return path.read_bytes()
