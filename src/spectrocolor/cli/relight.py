"""``spectrocolor relight``: a photo (or a folder of photos) seen under another light.

Every pixel's colour is upsampled to the exact smoothest reflectance of an upsampling table
(:mod:`spectrocolor.upsampling`) built for the light the photo was taken under (``--from``),
seen under ``--to`` and shown on the display, optionally after chromatic adaptation to the
new light (``--adapt``). Photos are read, relit and written in blocks of rows sized by the
memory budget (:mod:`spectrocolor.cli.photos`, :func:`spectrocolor.imagefiles.write_png_blocks`):
memory stays bounded whatever the photo's size.
"""

from __future__ import annotations

import argparse
import sys
from collections.abc import Iterator
from pathlib import Path

import numpy as np

from ..upsampling.apply import OUT_OF_RANGE_STRATEGIES
from . import UserError
from .files import add_force, check_files
from .options import adapt_choices, add_gamut, illuminant_forms

#: NaN spectra cannot be displayed, so the command offers the strategies that give colours.
_OUT_OF_RANGE = tuple(name for name in OUT_OF_RANGE_STRATEGIES if name != "nan")
_INPUT_SUFFIXES = (".png", ".tif", ".tiff", ".jpg", ".jpeg")


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
                   help=f"the new light: {illuminant_forms('A, F11, D50, …')}")
    p.add_argument("--adapt", choices=adapt_choices(), default="none",
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
    """One clear error for a ``--resolution`` or ``--from`` no table can have, before any work.

    The memory the table takes to build (:func:`spectrocolor.upsampling.table.table_build_bytes`)
    is checked against the memory budget, naming ``--resolution``.
    """
    from ..budget import check_bytes, format_size, memory_budget
    from ..illuminants import canonical_illuminant
    from ..upsampling.table import DEFAULT_SAMPLES, table_build_bytes

    if not 2 <= args.resolution <= 65:
        raise UserError(f"--resolution must be from 2 to 65 nodes per axis; got {args.resolution}")
    if args.table is None:
        largest = max((n for n in range(2, 66) if table_build_bytes(n, DEFAULT_SAMPLES) <= memory_budget()),
                      default=None)
        check_bytes(table_build_bytes(args.resolution, DEFAULT_SAMPLES),
                    f"--resolution {args.resolution}: building the table",
                    raise_hint=f"choose --resolution {largest} or less, or raise the budget of "
                    f"{format_size(memory_budget())} with spectrocolor --memory-budget SIZE")
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


def relit_blocks(table, photo, args: argparse.Namespace, counts: dict) -> Iterator[np.ndarray]:
    """Relit display codes of ``photo`` (:class:`~spectrocolor.cli.photos.Photo`), block by block.

    ``counts`` gets ``inexact`` (pixels not reproduced exactly) and ``clipped`` (outside the
    display gamut) as the blocks go.
    """
    from ..display.render import render
    from ..upsampling import relight, rgb_linear_from_image

    adaptation = None if args.adapt == "none" else args.adapt
    dtype = np.uint8 if args.bit_depth == 8 else np.uint16
    counts.update(inexact=0, clipped=0)
    for block in photo.blocks(photo.rows_per_block()):
        relit = relight(table, rgb_linear_from_image(block, table.space), args.to_illuminant,
                        adaptation=adaptation, out_of_range=args.out_of_range)
        shown = render(relit.XYZ100, space=table.space, gamut=args.gamut,
                       bit_depth=args.bit_depth)
        counts["inexact"] += int(np.count_nonzero(~relit.exact))
        counts["clipped"] += int(np.count_nonzero(~shown.in_gamut))
        yield np.asarray(shown.codes, dtype=dtype)


def _relight(args: argparse.Namespace) -> int:
    from ..imagefiles import write_png_blocks
    from .photos import open_photo

    check_table_options(args)
    from ..illuminants import resolve_illuminant

    # resolved once (every form --illuminant takes), a clear error before any work
    args.to_illuminant = resolve_illuminant(args.to_illuminant, "--to")
    pairs = _pairs(args)
    table = None
    for photo_path, target in pairs:
        photo = open_photo(photo_path)  # its header checked before the table is built
        table = table_for(args) if table is None else table
        counts: dict = {}
        write_png_blocks(target, relit_blocks(table, photo, args, counts), photo.height,
                         photo.width, 3, args.bit_depth)
        pixels = photo.width * photo.height
        print(f"wrote {target}: {photo.width} x {photo.height} pixels, {table.space} under "
              f"{table.illuminant} -> {args.to_illuminant.label} (adaptation {args.adapt}); "
              f"{counts['inexact']} of {pixels} pixels not reproduced exactly ({args.out_of_range}), "
              f"{counts['clipped']} outside the display gamut ({args.gamut})", file=sys.stdout)
    return 0
