"""``spectrocolor upsample``: a texture's per-texel coefficients for renderers (``.sctx``).

Every texel's colour is located in an upsampling table (:mod:`spectrocolor.upsampling`): four
node indices and four weights, written block by block of rows (memory bounded by the budget,
whatever the texture's size) by :func:`spectrocolor.upsampling.texels.write_texel_blocks`
(atomically) in the layout documented there and in ``docs/upsampling.md``. A renderer holding the
table evaluates each texel's reflectance at any wavelength; ``--save-table`` writes the table the
coefficients index.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from ..upsampling.apply import OUT_OF_RANGE_STRATEGIES
from . import UserError
from .files import add_force, check_files
from .relight import add_table_options, check_table_options, table_for

#: Strategies that give coefficients ("nan" gives none).
_OUT_OF_RANGE = tuple(name for name in OUT_OF_RANGE_STRATEGIES if name != "nan")


def register(subparsers) -> None:
    """Add the ``upsample`` sub-command."""
    p = subparsers.add_parser(
        "upsample",
        help="per-texel spectral upsampling coefficients of a texture, for renderers",
        description=(
            "Locate every texel of a texture in an upsampling table and write its four node "
            "indices and weights (.sctx; layout in docs/upsampling.md). A renderer holding the "
            "table (.scup, --save-table) evaluates each texel's reflectance at any wavelength."
        ),
    )
    p.add_argument("input", metavar="TEXTURE", help="texture (.png or .tif 8/16-bit, .jpg)")
    p.add_argument("--coefficients", required=True, help="output .sctx file")
    p.add_argument("--save-table", default=None,
                   help="also write the table the coefficients index (.scup)")
    add_table_options(p, taken="the table's illuminant", space="RGB space of the texture",
                      out_of_range=_OUT_OF_RANGE)
    add_force(p)
    p.set_defaults(handler=_upsample)


def _upsample(args: argparse.Namespace) -> int:
    from ..upsampling import rgb_linear_from_image, save_table
    from ..upsampling.texels import MAX_SIDE, write_texel_blocks
    from .photos import open_photo

    check_table_options(args)
    for option, value, suffix in (("--coefficients", args.coefficients, ".sctx"),
                                  ("--save-table", args.save_table, ".scup")):
        if value is not None and Path(value).suffix.lower() != suffix:
            raise UserError(f"{option} must end in {suffix}; got {value!r}")
    check_files(args, ("coefficients", "save_table"), ("input", "table"))
    if args.save_table is not None and args.table is not None:
        raise UserError("--save-table writes a table built here; with --table the table is "
                        "already saved")
    photo = open_photo(Path(args.input))
    if max(photo.width, photo.height) > MAX_SIDE:
        raise UserError(f"{args.input}: {photo.width} x {photo.height} texels; the "
                        f".sctx layout takes sides up to {MAX_SIDE}")
    table = table_for(args)
    blocks = (rgb_linear_from_image(codes, table.space)
              for codes in photo.blocks(photo.rows_per_block()))
    path, inexact = write_texel_blocks(args.coefficients, table, blocks, photo.width, photo.height,
                                       args.out_of_range)
    if args.save_table is not None:
        save_table(table, args.save_table)
    print(f"wrote {path}: {photo.width} x {photo.height} texels, {table.space} table under "
          f"{table.illuminant} (n = {table.resolution}); {inexact} texels not reproduced exactly "
          f"({args.out_of_range})" + (f"; table {args.save_table}" if args.save_table else ""),
          file=sys.stdout)
    return 0
