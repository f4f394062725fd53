"""``spectrocolor image``: a spectral cube to a display image (PNG) or XYZ/CIELAB (float TIFF)."""

from __future__ import annotations

import argparse
import sys

import numpy as np

from ..illuminants import illuminant_label
from . import UserError
from .files import add_force, check_files
from .options import adapt_choices, add_gamut, add_illuminant, add_observer


def register(subparsers) -> None:
    """Add the ``image`` sub-command."""
    p = subparsers.add_parser(
        "image",
        help="convert a spectral cube (ENVI, TIFF, .npy/.npz, netCDF, band folder) to an image",
        description=(
            "Read a spectral cube, compute every pixel's colour in bounded-memory row blocks "
            "(or on a dask cluster with --scheduler) and write a PNG (display RGB, 8 or 16 bit) "
            "or a float TIFF (XYZ, CIELAB or linear RGB)."
        ),
    )
    p.add_argument("cube", metavar="CUBE",
                   help="cube file (.hdr/raw, .tif, .npy, .npz, .nc, .h5) or folder of band images")
    p.add_argument("--out", required=True, help="output: .png (display codes) or .tif (floats)")
    add_force(p)
    add_illuminant(p, lights=True, what="a reflectance cube ('none' for a radiance cube)")
    add_observer(p)
    p.add_argument("--method", choices=("sum", "1nm"), default="sum",
                   help="summation method (default sum)")
    p.add_argument("--quantity", choices=("rgb", "xyz", "lab"), default="rgb",
                   help="what to write (default rgb; xyz and lab need a .tif output)")
    p.add_argument("--wavelengths", default=None,
                   help="band wavelengths in nm: 'START:STOP:STEP' or a comma list (required "
                   "for .npy; replaces those in the file otherwise)")
    p.add_argument("--wavelength-units", default=None,
                   help="units of wavelengths the file gives without units (nm or um)")
    p.add_argument("--variable", default=None, help="netCDF/HDF5 variable to read")
    p.add_argument("--scale", type=float, default=None,
                   help="factor from the values read to reflectance (e.g. 0.0001; default 1); an ENVI "
                   "header's reflectance scale factor, data ignore value and bbl are applied on "
                   "reading, as read_cube does")
    p.add_argument("--space", default="sRGB", help="display RGB space (default sRGB)")
    add_gamut(p)
    p.add_argument("--exposure", type=float, default=1.0,
                   help="multiplier on XYZ before display (default 1)")
    p.add_argument("--adapt", choices=adapt_choices(), default="bradford",
                   help="adapt the illuminant's white to the display white (default bradford)")
    p.add_argument("--bit-depth", type=int, choices=(8, 16), default=8,
                   help="PNG bits per channel (default 8)")
    p.add_argument("--masked", default=None, metavar="WHAT",
                   help="what masked pixels (NaN values, the ENVI data ignore value) become with "
                   "--quantity rgb: 'black' (default: black codes in PNG, NaN in TIFF), "
                   "'transparent' (RGBA with alpha 0 there), or a colour '#RRGGBB' or 'R,G,B' "
                   "(codes for PNG, floats for TIFF)")
    p.add_argument("--chunks", default=None,
                   help="rows per block (NumPy path), or 'ROWS,COLS' dask chunks with "
                   "--scheduler (default: 64 MiB blocks; 512,512 on dask)")
    p.add_argument("--scheduler", default=None,
                   help="dask.distributed scheduler address (e.g. tcp://host:8786) to run on")
    p.add_argument("--progress", action="store_true", help="show a progress bar")
    p.set_defaults(handler=_image)


#: Most bands ``--wavelengths`` may describe (a 0.01 nm grid over 360-830 nm has 47 001).
MAX_BANDS = 100_000


def parse_wavelengths(text: str) -> np.ndarray:
    """'400:700:10' (inclusive) or '400,410,420' -> wavelengths in nm (at most MAX_BANDS)."""
    try:
        if ":" in text:
            start, stop, step = (float(part) for part in text.split(":"))
            if not (step > 0 and np.isfinite([start, stop, step]).all() and stop >= start):
                raise ValueError
            count = int(round((stop - start) / step)) + 1
            if count > MAX_BANDS:
                raise UserError(f"--wavelengths {text!r} gives {count:.3g} bands; at most "
                                f"{MAX_BANDS} are accepted")
            return start + step * np.arange(count)
        values = np.array([float(part) for part in text.split(",")[:MAX_BANDS + 1] if part.strip()])
        if values.size > MAX_BANDS or not np.isfinite(values).all():
            raise ValueError
        return values
    except ValueError as exc:
        raise UserError(
            f"--wavelengths: expected 'START:STOP:STEP' (finite nm, STOP >= START, STEP > 0) or a "
            f"comma list of at most {MAX_BANDS} finite nm; got {text[:60]!r}"
        ) from exc


def _chunks(text: str | None, dask: bool):
    if text is None:
        return (512, 512) if dask else None
    try:
        parts = [int(part) for part in text.split(",")]
    except ValueError as exc:
        raise UserError(f"--chunks: expected ROWS or ROWS,COLS (integers); got {text!r}") from exc
    if any(part < 1 for part in parts) or len(parts) > 2:
        raise UserError(f"--chunks: expected ROWS or ROWS,COLS (positive); got {text!r}")
    if dask:
        return (parts[0], parts[-1])
    if len(parts) != 1:
        raise UserError("--chunks ROWS,COLS needs --scheduler; without it give rows per block")
    return parts[0]


def parse_masked(text: str | None):
    """``--masked``: None (default), "transparent", "#RRGGBB" or three numbers "R,G,B"."""
    if text is None or text.strip().lower() == "black":
        return None
    if text.strip().lower() == "transparent":
        return "transparent"
    if text.strip().startswith("#"):
        return text.strip()
    try:
        parts = tuple(float(part) for part in text.split(","))
    except ValueError:
        parts = ()
    if len(parts) != 3:
        raise UserError(f"--masked: expected black, transparent, '#RRGGBB' or 'R,G,B'; got {text[:40]!r}")
    return parts


def _image(args: argparse.Namespace) -> int:
    from ..errors import ColorimetryError
    from ..images import plan_conversion, read_cube
    from ..images.convert import masked_fill, write_converted

    suffix = args.out.lower().rsplit(".", 1)[-1]
    if suffix not in ("png", "tif", "tiff"):
        raise UserError(f"--out must end in .png or .tif/.tiff; got {args.out!r}")
    if suffix == "png" and args.quantity != "rgb":
        raise UserError(f"--quantity {args.quantity} gives floats: write it to a .tif file")
    masked = parse_masked(args.masked)
    if masked is not None and args.quantity != "rgb":
        raise UserError(f"--masked applies to --quantity rgb; {args.quantity} keeps NaN for masked pixels")
    try:
        masked_fill(masked, "codes" if suffix == "png" else "rgb_linear", args.bit_depth)
    except ColorimetryError as exc:
        raise UserError(f"--{exc}") from None
    check_files(args, ("out",), ("cube",))
    if args.wavelength_units is not None:
        from ..images.cube import wavelengths_to_nm

        wavelengths_to_nm([1.0], args.wavelength_units, "--wavelength-units")  # known units only
    wavelengths = parse_wavelengths(args.wavelengths) if args.wavelengths else None
    cube = read_cube(args.cube, wavelengths_nm=wavelengths,
                     wavelength_units=args.wavelength_units, variable=args.variable)
    for note in cube.metadata.get("applied", ()):  # the header's reading fields (ENVI), as the API applies them
        print(f"{args.cube}: {note}", file=sys.stderr)
    scale = 1.0 if args.scale is None else args.scale
    illuminant = args.illuminant  # None for a radiance cube
    output = "codes" if suffix == "png" else "rgb_linear"
    plan = plan_conversion(
        args.quantity, cube.wavelengths_nm, illuminant=illuminant, observer=args.observer,
        method=args.method, scale=scale, space=args.space, gamut=args.gamut,
        exposure=args.exposure, adaptation=None if args.adapt == "none" else args.adapt,
        bit_depth=args.bit_depth, output=output, masked=masked,
    )
    metadata = None
    if suffix != "png":
        metadata = {"quantity": plan.quantity, "illuminant": illuminant_label(args.illuminant),
                    "observer": args.observer, "source": cube.source}
        if plan.white_XYZ is not None:
            metadata["white_XYZ"] = [float(v) for v in plan.white_XYZ]
        if plan.channels == 4:
            metadata["alpha"] = "0 where masked, 1 elsewhere"
    if args.scheduler:  # the cluster returns the whole result; write it as one block
        from ..imagefiles import write_png_blocks, write_tiff_blocks

        result = _on_cluster(cube, plan, args)
        if suffix == "png":
            height, width, channels = result.shape
            write_png_blocks(args.out, [result], height, width, channels, plan.dtype.itemsize * 8)
        else:
            write_tiff_blocks(args.out, [result], result.shape, result.shape[0], metadata)
    else:  # streamed: one block of rows in memory, written as it is made
        write_converted(args.out, cube.values, plan, rows_per_block=_chunks(args.chunks, False),
                        metadata=metadata, progress=args.progress)
    height, width = cube.values.shape[:2]
    print(f"wrote {args.out}: {width} x {height} pixels, {plan.quantity}, "
          f"{cube.wavelengths_nm.size} bands {cube.wavelengths_nm[0]:g}-"
          f"{cube.wavelengths_nm[-1]:g} nm, illuminant {illuminant_label(args.illuminant)}, observer "
          f"{args.observer}")
    return 0


def _on_cluster(cube, plan, args) -> np.ndarray:
    """Run the plan's block function over dask chunks on the scheduler at ``args.scheduler``."""
    import dask.array as da
    from distributed import Client

    chunks = _chunks(args.chunks, True)
    source = da.from_array(cube.values, chunks=(*chunks, -1))
    lazy = source.map_blocks(plan.function, **plan.keywords, dtype=plan.dtype,
                             chunks=(*source.chunks[:2], (plan.channels,)))
    try:
        client = Client(args.scheduler, timeout="10s")
    except (OSError, ValueError, TypeError) as exc:  # unreachable, or not an address at all
        raise UserError(f"--scheduler: cannot reach {args.scheduler!r} ({exc})") from exc
    with client:
        if args.progress:
            from distributed import progress

            future = client.compute(lazy)
            progress(future)
            return np.asarray(future.result())
        return np.asarray(client.compute(lazy).result())
