"""``spectrocolor relight``: a photo (or a folder of photos) seen under another light.

Every pixel's colour is upsampled to the exact smoothest reflectance of an upsampling table
(:mod:`spectrocolor.upsampling`) built for the light the photo was taken under (``--from``),
seen under ``--to`` and shown on the display, optionally after chromatic adaptation to the
new light (``--adapt``). Images are processed in row blocks of bounded memory.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import numpy as np

from ..display.adaptation import ADAPTATION_METHODS
from ..upsampling.apply import OUT_OF_RANGE_STRATEGIES
from . import UserError
from .files import add_force, check_files
from .options import add_gamut

_ADAPT_CHOICES = ("none", *ADAPTATION_METHODS)
#: NaN spectra cannot be displayed, so the command offers the strategies that give colours.
_OUT_OF_RANGE = tuple(name for name in OUT_OF_RANGE_STRATEGIES if name != "nan")
_INPUT_SUFFIXES = (".png", ".tif", ".tiff", ".jpg", ".jpeg")
#: Largest photo read, in pixels (a 24-megapixel photo is 2.4e7).
MAX_PIXELS = 2**28
#: Pixels relit per block (bounds the float64 temporaries to a few hundred MiB).
BLOCK_PIXELS = 2**20


def register(subparsers) -> None:
    """Add the ``relight`` sub-command."""
    p = subparsers.add_parser(
        "relight",
        help="show a photo (or every photo in a folder) under another light",
        description=(
            "Upsample every pixel to an exact smoothest reflectance under the original light "
            "(--from), see it under --to and write a display image. Without --adapt the viewer "
            "stays adapted to the original light (a camera with fixed white balance); with "
            "--adapt bradford (etc.) the viewer adapts to the new light."
        ),
    )
    p.add_argument("input", metavar="INPUT",
                   help="photo (.png or .tif 8/16-bit, .jpg) or a folder of them")
    p.add_argument("--out", required=True,
                   help="output .png (or an existing folder when INPUT is a folder)")
    p.add_argument("--to", required=True, dest="to_illuminant",
                   help="the new light, e.g. A, F11, D50")
    p.add_argument("--adapt", choices=_ADAPT_CHOICES, default="none",
                   help="chromatic adaptation to the new light (default none)")
    add_table_options(p, taken="the light the photo was taken under",
                      space="RGB space of the photo and the output", out_of_range=_OUT_OF_RANGE)
    add_gamut(p)
    p.add_argument("--bit-depth", type=int, choices=(8, 16), default=8,
                   help="PNG bits per channel (default 8)")
    add_force(p)
    p.set_defaults(handler=_relight)


def _pairs(args: argparse.Namespace) -> list[tuple[Path, Path]]:
    source, out = Path(args.input), Path(args.out)
    if not source.is_dir():
        if out.suffix.lower() != ".png":
            raise UserError(f"--out must end in .png; got {args.out!r}")
        check_files(args, ("out",), ("input",))
        return [(source, out)]
    if not out.is_dir():
        raise UserError(f"--out {out}: INPUT is a folder, so --out must be an existing folder")
    if out.resolve() == source.resolve():
        raise UserError(f"--out {out} is the input folder; choose another folder (inputs are "
                        "never written over)")
    photos = sorted(p for p in source.iterdir() if p.suffix.lower() in _INPUT_SUFFIXES
                    and p.is_file())
    if not photos:
        raise UserError(f"INPUT {source}: no {', '.join(_INPUT_SUFFIXES)} files in this folder")
    pairs = [(p, out / (p.stem + ".png")) for p in photos]
    stems = [target.name for _, target in pairs]
    if len(set(stems)) != len(stems):
        raise UserError(f"INPUT {source}: two photos share a name ({stems}); their outputs would "
                        "collide")
    for photo, target in pairs:
        check_files(argparse.Namespace(input=str(photo), out=str(target), force=args.force),
                    ("out",), ("input",))
    return pairs


def read_photo(path: Path) -> np.ndarray:
    """An (H, W, 3) uint8 or uint16 array of codes; alpha is dropped, grey is repeated.

    16-bit PNG is decoded by :func:`spectrocolor.upsampling.read_png` (all 16 bits); other PNG
    and JPEG by Pillow, TIFF by tifffile.
    """
    suffix = path.suffix.lower()
    try:
        if suffix in (".tif", ".tiff"):
            import tifffile

            codes = np.asarray(tifffile.imread(path))
        else:
            from PIL import Image

            with open(path, "rb") as handle:
                signature = handle.read(25)
            if signature[:8] == b"\x89PNG\r\n\x1a\n" and signature[24:25] == b"\x10":
                return _channels_to_rgb(path, _read_png16(path))  # Pillow would cut it to 8 bits
            with Image.open(path) as image:
                if image.width * image.height > MAX_PIXELS:
                    raise UserError(f"{path}: {image.width} x {image.height} pixels; at most "
                                    f"{MAX_PIXELS} are read")
                codes = np.asarray(image.convert("RGB"))
    except UserError:
        raise
    except Exception as exc:  # Pillow/tifffile raise many types for damaged files
        raise UserError(f"{path}: cannot be read as an image ({exc})") from None
    return _channels_to_rgb(path, codes)


def _read_png16(path: Path) -> np.ndarray:
    """A 16-bit PNG's codes (H, W, C) by :func:`spectrocolor.upsampling.read_png`."""
    from ..errors import SpectrumError
    from ..upsampling import read_png

    try:
        return read_png(path)
    except SpectrumError as exc:
        raise UserError(f"cannot be read as an image: {exc}") from None


def _channels_to_rgb(path: Path, codes: np.ndarray) -> np.ndarray:
    """(H, W, 3) codes: alpha dropped, grey repeated; other shapes and dtypes refused."""
    if codes.ndim == 3 and codes.shape[-1] in (1, 2):
        codes = codes[..., 0]
    if codes.ndim == 2:
        codes = np.repeat(codes[..., None], 3, axis=-1)
    if codes.ndim != 3 or codes.shape[-1] not in (3, 4) or codes.dtype not in (np.uint8,
                                                                                np.uint16):
        raise UserError(f"{path}: expected an RGB image of 8- or 16-bit codes; got "
                        f"{codes.dtype} {codes.shape}")
    if codes.shape[0] * codes.shape[1] > MAX_PIXELS:
        raise UserError(f"{path}: {codes.shape[1]} x {codes.shape[0]} pixels; at most "
                        f"{MAX_PIXELS} are read")
    return codes[..., :3]


def add_table_options(parser: argparse.ArgumentParser, *, taken: str, space: str,
                      out_of_range: tuple[str, ...]) -> None:
    """The options that choose or build the upsampling table (``relight`` and ``upsample``)."""
    parser.add_argument("--from", default=None, dest="from_illuminant",
                        help=f"{taken} (default D65, or the --table's)")
    parser.add_argument("--space", default=None, help=f"{space} (default sRGB, or the --table's)")
    parser.add_argument("--resolution", type=int, default=17,
                        help="nodes per axis of the table built on the fly (default 17)")
    parser.add_argument("--table", default=None, help="use a saved .scup upsampling table")
    parser.add_argument("--out-of-range", choices=out_of_range, default="toward-grey",
                        help="colours the table cannot reproduce exactly (default toward-grey): "
                        + OUT_OF_RANGE_STRATEGIES.help())


def check_table_options(args: argparse.Namespace) -> None:
    """One clear error for a ``--resolution`` or ``--from`` no table can have, before any work."""
    from ..illuminants import canonical_illuminant

    if not 2 <= args.resolution <= 65:
        raise UserError(f"--resolution must be from 2 to 65 nodes per axis; got {args.resolution}")
    if args.from_illuminant is not None:
        canonical_illuminant(args.from_illuminant, "--from")


def table_for(args: argparse.Namespace):
    """The ``--table`` (checked against ``--from``/``--space``), or one built for them."""
    from ..upsampling import load_table, upsampling_table

    if args.table is not None:
        table = load_table(args.table)
        for option, given, own in (("--from", args.from_illuminant, table.illuminant),
                                   ("--space", args.space, table.space)):
            if given is not None and given != own:
                raise UserError(f"{option} {given!r} differs from the --table's {own!r}; omit "
                                f"{option} or build a table for it")
        return table
    return upsampling_table(args.space or "sRGB", args.from_illuminant or "D65",
                            resolution=args.resolution, measure_excess=False)


def relight_codes(table, codes: np.ndarray, args: argparse.Namespace) -> tuple[np.ndarray, int, int]:
    """Relit display codes of one photo, in row blocks; also (inexact, out-of-gamut) counts."""
    from ..display.render import render
    from ..upsampling import relight, rgb_linear_from_image

    height, width = codes.shape[:2]
    rows = max(1, BLOCK_PIXELS // max(width, 1))
    out = np.empty(codes.shape, dtype=np.uint8 if args.bit_depth == 8 else np.uint16)
    inexact = clipped = 0
    adaptation = None if args.adapt == "none" else args.adapt
    for start in range(0, height, rows):
        block = codes[start:start + rows]
        relit = relight(table, rgb_linear_from_image(block, table.space), args.to_illuminant,
                        adaptation=adaptation, out_of_range=args.out_of_range)
        shown = render(relit.XYZ100, space=table.space, gamut=args.gamut,
                       bit_depth=args.bit_depth)
        out[start:start + rows] = shown.codes
        inexact += int(np.count_nonzero(~relit.exact))
        clipped += int(np.count_nonzero(~shown.in_gamut))
    return out, inexact, clipped


def _relight(args: argparse.Namespace) -> int:
    from ..pictures import write_image

    check_table_options(args)
    from ..illuminants import canonical_illuminant

    canonical_illuminant(args.to_illuminant, "--to")  # a clear error before any work
    pairs = _pairs(args)
    table = table_for(args)
    for photo, target in pairs:
        codes = read_photo(photo)
        out, inexact, clipped = relight_codes(table, codes, args)
        write_image(target, out)
        pixels = codes.shape[0] * codes.shape[1]
        print(f"wrote {target}: {codes.shape[1]} x {codes.shape[0]} pixels, {table.space} under "
              f"{table.illuminant} -> {args.to_illuminant} (adaptation {args.adapt}); "
              f"{inexact} of {pixels} pixels not reproduced exactly ({args.out_of_range}), "
              f"{clipped} outside the display gamut ({args.gamut})", file=sys.stdout)
    return 0
