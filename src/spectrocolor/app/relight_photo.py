"""Setting 4's photo: an uploaded picture seen under the setting's illuminant (issue 17).

A photo (PNG or JPEG, 8-bit sRGB codes) is taken to show surfaces under a declared *source*
light (default D65). Each pixel's colour gets the reflectance of a spectral upsampling table
(:func:`spectrocolor.upsampling.upsampling_table`: exact colour, ``0 ≤ ρ ≤ 1``), built once per
source light, observer and bin grid and kept (:func:`photo_table`), and is then seen under the
illuminant the setting shows -- its own bin levels, edited or not -- by
:func:`spectrocolor.upsampling.relight`, with the chosen chromatic adaptation. The relit colours
are shown on sRGB with the page's gamut strategy, by default after one exposure factor (1, or
less where the perfect white under the new light would leave sRGB, so that it just fits).

Photos are read and shown as sRGB, the space a browser shows an untagged PNG in; embedded ICC
profiles are not applied. A photo larger than :data:`MAX_SHOWN_SIDE_PX` on its long side is
downscaled (Lanczos, on the codes) before relighting; both pictures of the answer have the
shown size. Only the distinct colours of a photo are relit (a photo of a million pixels has far
fewer colours), then mapped back to the pixels.

This module is the worker side: :func:`relight_photo` runs in a worker process of
:mod:`spectrocolor.app.relight_routes`, and everything a hostile file makes it raise becomes one
:class:`~spectrocolor.errors.SpectrumError`.

References
----------
P. Sällström, *SPECTRA*, USIP Report 99-05 (1999), setting 4 (seed 002).
C. van Trigt, "Smoothest reflectance functions. I. Definition and main results", J. Opt. Soc.
Am. A 7, 1891–1904 (1990).
"""

from __future__ import annotations

import base64
import binascii
import hashlib
import io
import re
import time
from collections import OrderedDict
from dataclasses import dataclass
from functools import lru_cache

import numpy as np

from ..errors import ColorimetryError, SpectrumError

__all__ = ["SOURCES", "ADAPTATIONS", "DEFAULT_ADAPTATION", "EXPOSURES", "DEFAULT_EXPOSURE", "MAX_SHOWN_SIDE_PX",
           "MAX_PHOTO_PIXELS", "TABLE_RESOLUTION", "OUT_OF_RANGE", "photo_table", "prepare", "decode_photo",
           "relight_codes", "relight_photo"]

#: Lights a photo may be declared as taken under (the table's illuminant), the default first.
SOURCES = ("D65", "D50", "A", "F11")
#: How the viewer is adapted, the default first: [label, one-line explanation].
ADAPTATIONS = {
    "none": ("none (white balance of the photo kept)",
             "the viewer stays adapted to the photo's light, like a camera with fixed white "
             "balance: a white wall under A looks orange"),
    "von kries": ("von Kries (cone responses)",
                  "the viewer adapts to the new light, von Kries scaling of the "
                  "Hunt-Pointer-Estévez cone responses: what remains is colour inconstancy"),
    "bradford": ("Bradford",
                 "the viewer adapts to the new light, Bradford transform: the perfect white "
                 "looks white again, only colour inconstancy remains"),
}
DEFAULT_ADAPTATION = "none"
#: How bright the relit photo is shown, the default first: [label, one-line explanation].
EXPOSURES = {
    "fit white": ("fit the white",
                  "everything is scaled by one factor so that the perfect white under the new "
                  "light just fits the display (needed where it is seen unadapted, e.g. under A)"),
    "keep": ("keep the photo's",
             "the perfect white keeps Y = 100: under a light seen unadapted it leaves the display's "
             "gamut and the gamut strategy decides"),
}
DEFAULT_EXPOSURE = "fit white"
#: Longest side of the pictures shown, px; larger photos are downscaled before relighting.
MAX_SHOWN_SIDE_PX = 1024
#: Largest photo decoded, pixels (from the header, before any pixel is decoded).
MAX_PHOTO_PIXELS = 40_000_000
#: Nodes per axis of the upsampling table (the library's default).
TABLE_RESOLUTION = 17
#: The library's strategy for colours the table cannot reproduce exactly.
OUT_OF_RANGE = "toward-grey"
SPACE = "sRGB"

_PNG = b"\x89PNG\r\n\x1a\n"
_JPEG = b"\xff\xd8\xff"


@lru_cache(maxsize=8)
def photo_table(source: str, observer: str, step_nm: float):
    """The sRGB upsampling table under ``source`` on the explorer's grid, built once and kept.

    Parameters
    ----------
    source : str
        One of :data:`SOURCES`.
    observer : str
        Observer name as the explorer sends it (``"1931"``, ``"1964"``, ...).
    step_nm : float
        The explorer's bin width, nm (its grid is 400-700 nm).

    Returns
    -------
    spectrocolor.upsampling.UpsamplingTable

    Examples
    --------
    >>> table = photo_table("D65", "1931", 10.0)
    >>> table.space, table.illuminant, table.reflectance.shape
    ('sRGB', 'D65', (17, 17, 17, 31))
    >>> photo_table("D65", "1931", 10.0) is table   # kept, not rebuilt
    True
    """
    from ..upsampling import upsampling_table
    from . import compute

    return upsampling_table(SPACE, source, observer, (compute.START_NM, compute.STOP_NM, step_nm),
                            resolution=TABLE_RESOLUTION, measure_excess=False)


def prepare(source: str = SOURCES[0], observer: str = "1931", step_nm: float = 10.0) -> int:
    """Build (or find) the table and relight one colour, so that the first photo is answered quickly.

    The relight also compiles the library's optional numba kernels in this process.

    Parameters
    ----------
    source, observer, step_nm
        As for :func:`photo_table`.

    Returns
    -------
    int
        Nodes of the table.

    Examples
    --------
    >>> prepare()
    4913
    """
    table = photo_table(source, observer, float(step_nm))
    relight_codes(np.full((1, 1, 3), 128, np.uint8), table, "A", "none", "clip")
    return int(table.resolution ** 3)


def _bad(what: str) -> SpectrumError:
    return SpectrumError(f"image: {what}")


#: Bytes of one block of decoded rows while a PNG upload is pasted into its one RGB image.
_BLOCK_BYTES = 8 * 2**20


def _open_photo(data: bytes):
    """A Pillow image of the photo, the one full-size copy of its 8-bit codes that is held.

    A 16-bit PNG, and an 8-bit one that is not interlaced and has no palette, is decoded by the library's
    own reader (Pillow would cut 16 bits to 8 its own way, and would hold an RGBA or grey copy
    besides the RGB one) block by block of rows, each block rounded to the 8-bit RGB codes the
    page shows and pasted into one RGB image as it comes: a 40-megapixel photo never exists as
    16-bit or float values, nor twice. Other photos (JPEG, palette or interlaced PNG) are opened
    by Pillow, which decodes nothing yet."""
    from PIL import Image

    from ..imagefiles import CHANNELS

    streamed = data[:8] == _PNG and len(data) > 28 and (
        data[24] == 16 or (data[24] == 8 and data[25] in CHANNELS and data[28] == 0))
    if not streamed:
        return Image.open(io.BytesIO(data), formats=("PNG", "JPEG"))
    width, height = int.from_bytes(data[16:20], "big"), int.from_bytes(data[20:24], "big")
    if width * height > MAX_PHOTO_PIXELS:  # before any pixel is decoded
        raise _bad(f"{width} x {height} pixels; at most {MAX_PHOTO_PIXELS} are read")
    from ..imagefiles import iter_png_rows, png_header

    try:
        header = png_header(data, "the upload")
        image = Image.new("RGB", (header.width, header.height))
        row_bytes = header.width * header.channels * header.dtype.itemsize
        rows = max(1, _BLOCK_BYTES // row_bytes)  # small blocks: the image itself is the one copy
        for top, codes in iter_png_rows(data, rows_per_block=rows, name="the upload"):
            colour = codes[..., :1] if codes.shape[-1] < 3 else codes[..., :3]
            if header.bit_depth == 16:
                # round(c / 257) exactly, in integers: (c + 128) // 257 (c / 257 is never k + 1/2)
                colour = ((colour.astype(np.uint32) + 128) // 257).astype(np.uint8)
            if colour.shape[-1] == 1:
                colour = np.repeat(colour, 3, axis=-1)
            image.paste(Image.fromarray(np.ascontiguousarray(colour, np.uint8), "RGB"), (0, top))
    except SpectrumError as exc:
        message = str(exc).removeprefix("image: ")
        raise _bad(message if "cannot be read" in message else f"cannot be read as a PNG ({message})") from None
    return image


def decode_photo(data: bytes) -> tuple[np.ndarray, tuple[int, int]]:
    """8-bit RGB codes of a PNG or JPEG, downscaled to :data:`MAX_SHOWN_SIDE_PX` at most.

    Parameters
    ----------
    data : bytes
        The file's bytes.

    Returns
    -------
    codes : numpy.ndarray of uint8, shape (H, W, 3)
        ``rgb8`` codes (alpha dropped, grey repeated, palettes expanded).
    size : (int, int)
        The photo's own width and height, px.

    Raises
    ------
    SpectrumError
        For anything but a PNG (8 or 16 bits; 16-bit codes are rounded to 8 bits, the page's
        depth) or a JPEG, a damaged file, or more than :data:`MAX_PHOTO_PIXELS` pixels.

    Examples
    --------
    >>> import io
    >>> from PIL import Image
    >>> buffer = io.BytesIO()
    >>> Image.new("RGB", (2048, 512), (200, 10, 30)).save(buffer, "PNG")
    >>> codes, size = decode_photo(buffer.getvalue())
    >>> codes.shape, size, codes[0, 0].tolist()
    ((256, 1024, 3), (2048, 512), [200, 10, 30])
    """
    from PIL import Image

    if data[:8] != _PNG and data[:3] != _JPEG:
        raise _bad("not a PNG or JPEG file (accepted: .png, .jpg)")
    try:
        with _open_photo(data) as image:
            width, height = image.size
            if width * height > MAX_PHOTO_PIXELS:
                raise _bad(f"{width} x {height} pixels; at most {MAX_PHOTO_PIXELS} are read")
            scale = min(1.0, MAX_SHOWN_SIDE_PX / max(width, height, 1))
            shown = (max(1, round(width * scale)), max(1, round(height * scale)))
            if image.format == "JPEG":
                image.draft("RGB", shown)  # decode at a reduced scale where JPEG allows it
            rgb = image if image.mode == "RGB" else image.convert("RGB")  # no second copy
            if rgb.size != shown:
                rgb = rgb.resize(shown, Image.Resampling.LANCZOS)
            codes = np.asarray(rgb, dtype=np.uint8)
    except SpectrumError:
        raise
    except Image.DecompressionBombError:  # Pillow's own refusal, far beyond ours
        raise _bad(f"its header claims far more than {MAX_PHOTO_PIXELS} pixels; at most "
                   f"{MAX_PHOTO_PIXELS} are read") from None
    except Exception as exc:  # Pillow raises many types on damaged files: one error, one line
        detail = " ".join(re.sub(r"<[^>]*>", "the upload", str(exc)).split())[:120]
        raise _bad(f"cannot be read as a PNG or JPEG ({exc.__class__.__name__}: {detail})") from None
    return codes, (width, height)


def relight_codes(codes: np.ndarray, table, illuminant, adaptation: str, gamut: str,
                  exposure: str = DEFAULT_EXPOSURE) -> dict:
    """Relit ``rgb8`` codes of a photo and what was done to its pixels.

    Parameters
    ----------
    codes : numpy.ndarray of uint8, shape (H, W, 3)
        The photo's sRGB codes.
    table : spectrocolor.upsampling.UpsamplingTable
        sRGB table under the photo's light (:func:`photo_table`).
    illuminant : str or Spectrum
        The new light.
    adaptation : str
        A key of :data:`ADAPTATIONS`.
    gamut : str
        The display's gamut strategy for relit colours sRGB cannot show.
    exposure : str
        A key of :data:`EXPOSURES`.

    Returns
    -------
    dict
        ``codes`` (uint8, like the input), ``outside_solid`` (pixels the table could not
        reproduce exactly: colours outside the object-colour solid, moved by
        :data:`OUT_OF_RANGE`), ``out_of_gamut`` (relit pixels sRGB cannot show, handled by
        ``gamut``), ``colours`` (distinct colours relit), ``exposure_factor`` (applied to
        every relit colour: 1, or with ``exposure="fit white"`` less where the perfect white
        under the new light would leave sRGB -- a lamp's white seen unadapted -- so that it just
        fits, as a camera's exposure would).

    Examples
    --------
    >>> photo = np.array([[[255, 255, 255], [128, 128, 128]]], dtype=np.uint8)
    >>> same = relight_codes(photo, photo_table("D65", "1931", 10.0), "D65", "none", "clip")
    >>> same["codes"].tolist() == photo.tolist(), same["colours"]
    (True, 2)
    """
    return _relit(_Distinct.of(codes), table, illuminant, adaptation, gamut, exposure)


@dataclass(frozen=True)
class _Distinct:
    """A photo's distinct colours (``rgb8``, (N, 3)), each pixel's index into them, their counts."""

    shape: tuple
    colour_codes: np.ndarray
    where: np.ndarray
    counts: np.ndarray

    @classmethod
    def of(cls, codes: np.ndarray) -> _Distinct:
        packed = (codes[..., 0].astype(np.uint32) << 16) \
            | (codes[..., 1].astype(np.uint32) << 8) | codes[..., 2]
        distinct, where = np.unique(packed.ravel(), return_inverse=True)
        colour_codes = np.stack([(distinct >> 16) & 255, (distinct >> 8) & 255, distinct & 255],
                                axis=-1).astype(np.uint8)
        return cls(codes.shape, colour_codes, where, np.bincount(where, minlength=len(distinct)))


def _relit(photo: _Distinct, table, illuminant, adaptation: str, gamut: str,
           exposure: str) -> dict:
    from ..display.render import render
    from ..upsampling import relight, rgb_linear_from_image

    rgb_linear = np.concatenate([rgb_linear_from_image(photo.colour_codes, SPACE),
                                 np.ones((1, 3))])  # and the perfect white, last
    relit = relight(table, rgb_linear, illuminant,
                    adaptation=None if adaptation == "none" else adaptation,
                    out_of_range=OUT_OF_RANGE)
    white_max = float(relit.rgb_linear[-1].max())  # the perfect white (ρ = 1) under the light
    factor = 1.0 / white_max if exposure == "fit white" and white_max > 1.0 else 1.0
    shown = render(factor * relit.XYZ100[:-1], space=SPACE, gamut=gamut, bit_depth=8)
    return {"codes": shown.codes.astype(np.uint8)[photo.where].reshape(photo.shape),
            "outside_solid": int(photo.counts[~relit.exact[:-1]].sum()),
            "out_of_gamut": int(photo.counts[~shown.in_gamut].sum()),
            "colours": len(photo.colour_codes), "exposure_factor": factor}


def _png_base64(codes: np.ndarray) -> str:
    from PIL import Image

    buffer = io.BytesIO()
    Image.fromarray(codes, "RGB").save(buffer, "PNG", compress_level=1)
    return base64.b64encode(buffer.getvalue()).decode("ascii")


#: The last photos decoded (sha-256 of the file -> codes, size, distinct colours, PNG), so that
#: relighting the same photo under another light skips decoding, sorting and one PNG encoding.
_PHOTOS: OrderedDict[bytes, tuple] = OrderedDict()
_PHOTOS_KEPT = 2


def _photo(data: bytes) -> tuple:
    key = hashlib.sha256(data).digest()
    if key not in _PHOTOS:
        codes, size = decode_photo(data)
        _PHOTOS[key] = (codes, size, _Distinct.of(codes), _png_base64(codes))
        while len(_PHOTOS) > _PHOTOS_KEPT:
            _PHOTOS.popitem(last=False)
    _PHOTOS.move_to_end(key)
    return _PHOTOS[key]


def relight_photo(image_base64: str, illuminant_levels, step_nm: float, observer: str,
                  source: str = SOURCES[0], adaptation: str = DEFAULT_ADAPTATION,
                  gamut: str = "clip", exposure: str = DEFAULT_EXPOSURE) -> dict:
    """The API answer: a photo as taken and relit under setting 4's illuminant (PNG, base64).

    Parameters
    ----------
    image_base64 : str
        The PNG or JPEG file, base64-encoded.
    illuminant_levels : sequence of float
        The setting's illuminant, bin levels on the explorer's grid (400-700 nm at ``step_nm``).
    step_nm : float
        Bin width, nm.
    observer : str
        Observer (``"1931"``, ``"1964"``, ``"2015-2"``, ``"2015-10"``).
    source : str
        The light the photo was taken under, one of :data:`SOURCES`.
    adaptation : str
        A key of :data:`ADAPTATIONS` (default :data:`DEFAULT_ADAPTATION`).
    gamut : str
        Gamut strategy for relit colours outside sRGB.
    exposure : str
        A key of :data:`EXPOSURES`.

    Returns
    -------
    dict
        ``taken_png`` and ``relit_png`` (base64 PNG of the shown size), ``width``/``height``
        (shown), ``photo_width``/``photo_height`` (the file's), ``downscaled``, ``pixels``,
        ``outside_solid``, ``out_of_range`` (the strategy), ``out_of_gamut``, ``gamut``,
        ``exposure`` and ``exposure_factor`` (see :func:`relight_codes`), ``colours``,
        ``source``, ``adaptation``, ``space``, ``table`` (resolution, nodes, moved nodes) and
        ``relight_ms`` (the work after decoding, ms; a photo sent again is not decoded again).

    Raises
    ------
    SpectrumError
        For a damaged or unaccepted image, an unknown source or adaptation.
    ColorimetryError
        When the light's white cannot be adapted (a single spectral line: some cone response
        of its white is 0); ``adaptation="none"`` always works.

    Examples
    --------
    >>> import io
    >>> from PIL import Image
    >>> buffer = io.BytesIO()
    >>> Image.new("RGB", (4, 3), (255, 255, 255)).save(buffer, "PNG")
    >>> photo = base64.b64encode(buffer.getvalue()).decode()
    >>> answer = relight_photo(photo, [30.0] * 31, 10.0, "1931")   # white under E, unadapted
    >>> answer["pixels"], answer["outside_solid"], answer["out_of_range"]
    (12, 0, 'toward-grey')
    """
    from ..spectrum import Spectrum
    from . import compute

    if source not in SOURCES:
        raise SpectrumError(f"source: {source!r} is not one of {', '.join(SOURCES)}")
    if adaptation not in ADAPTATIONS:
        raise SpectrumError(f"adaptation: {adaptation!r} is not one of {', '.join(ADAPTATIONS)}")
    if exposure not in EXPOSURES:
        raise SpectrumError(f"exposure: {exposure!r} is not one of {', '.join(EXPOSURES)}")
    try:
        data = base64.b64decode(image_base64, validate=True)
    except (binascii.Error, ValueError):
        raise _bad("not valid base64 (send the file's bytes base64-encoded)") from None
    codes, (width, height), distinct, taken_png = _photo(data)
    start = time.perf_counter()
    table = photo_table(source, observer, float(step_nm))
    light = Spectrum(compute.grid(float(step_nm)), np.asarray(illuminant_levels, dtype=float))
    try:
        relit = _relit(distinct, table, light, adaptation, gamut, exposure)
    except ColorimetryError as exc:  # e.g. a single line: its white has no blue cone response
        raise ColorimetryError(f"adaptation {adaptation!r} under this illuminant: {exc}") from None
    answer = {
        "relit_png": _png_base64(relit["codes"]),
        "taken_png": taken_png,
        "width": int(codes.shape[1]), "height": int(codes.shape[0]),
        "photo_width": int(width), "photo_height": int(height),
        "downscaled": bool(codes.shape[1] != width or codes.shape[0] != height),
        "max_side_px": MAX_SHOWN_SIDE_PX,
        "pixels": int(codes.shape[0] * codes.shape[1]),
        "colours": relit["colours"],
        "outside_solid": relit["outside_solid"], "out_of_range": OUT_OF_RANGE,
        "out_of_gamut": relit["out_of_gamut"], "gamut": gamut, "exposure": exposure,
        "exposure_factor": relit["exposure_factor"],
        "source": source, "adaptation": adaptation, "space": SPACE,
        "table": {"resolution": table.resolution, "nodes": int(table.resolution ** 3),
                  "moved_nodes": int(np.count_nonzero(table.node_status))},
    }
    answer["relight_ms"] = round(1000 * (time.perf_counter() - start), 1)
    return answer
