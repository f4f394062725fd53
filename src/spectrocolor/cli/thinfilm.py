"""``spectrocolor thinfilm``: interference colours of thin films (seed 000 and beyond).

Sub-commands:

* ``zawischa`` -- seed 000's strip exactly as specified (PNG/PPM, CSV, optional xy locus plot);
* ``strip`` -- colour against thickness for any film/stack, light, observer, angle;
* ``locus`` -- the film colours' xy locus in the chromaticity diagram with the sRGB triangle;
* ``map`` -- an image from a thickness map (wedge, draining film, bubble, or a user's file).
"""

from __future__ import annotations

import argparse
import csv
from pathlib import Path

import numpy as np

from ..safe_write import atomic_path
from ..thinfilm.colour import SEED_000_ILLUMINANT
from . import UserError
from .files import add_force, check_files, save_figure
from .options import add_gamut, add_illuminant, add_observer

#: Largest strip length / locus point count and image side accepted on the command line.
_MAX_COLUMNS = 100_000
_MAX_SIDE_PX = 16_384
#: Memory of one pixel of a thickness map while it is drawn (thickness, angle, table index,
#: codes): measured about 16 bytes (wedge) and 30 (bubble) at 4096 x 4096.
_MAP_PIXEL_BYTES = 40
#: Angles of the bubble's colour table (0-89 degrees in steps of 2).
_BUBBLE_ANGLES = 46
_PLOT_SUFFIXES = (".png", ".svg", ".pdf")


def _check_plot_path(path, option: str) -> None:
    if Path(path).suffix.lower() not in _PLOT_SUFFIXES:
        raise UserError(f"{option} must end in .png, .svg or .pdf, got {str(path)!r}")


def register(subparsers) -> None:
    parser = subparsers.add_parser(
        "thinfilm", help="interference colours of thin films (soap, oil, coatings)",
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    commands = parser.add_subparsers(dest="thinfilm_command", metavar="SUBCOMMAND")
    commands.required = True

    z = commands.add_parser("zawischa", help="seed 000's strip (two-beam, beta 0.95, 6504 K)")
    z.add_argument("--out", required=True, help="strip image, .png or .ppm")
    z.add_argument("--csv", help="write opd_nm,X,Y,Z,x,y,r8,g8,b8 (one row per column)")
    z.add_argument("--locus", help="also write the xy locus plot (.png/.svg/.pdf, matplotlib)")
    add_force(z)
    z.set_defaults(handler=_zawischa)

    s = commands.add_parser("strip", help="colour against film thickness")
    _film_options(s)
    _colour_options(s)
    s.add_argument("--max-thickness", type=float, default=1500.0, help="nm (default 1500)")
    s.add_argument("--columns", type=int, default=1000)
    s.add_argument("--tick-every", type=float, default=100.0, help="nm between ticks")
    s.add_argument("--out", required=True, help=".png or .ppm")
    s.add_argument("--csv", help="write thickness_nm,X,Y,Z,x,y,r8,g8,b8")
    add_force(s)
    s.set_defaults(handler=_strip)

    loc = commands.add_parser("locus", help="xy locus of the film colours (matplotlib)")
    _film_options(loc)
    _colour_options(loc)
    loc.add_argument("--max-thickness", type=float, default=1500.0, help="nm")
    loc.add_argument("--points", type=int, default=1000)
    loc.add_argument("--out", required=True, help=".png, .svg or .pdf")
    add_force(loc)
    loc.set_defaults(handler=_locus)

    m = commands.add_parser("map", help="image of a thickness map through a lookup table")
    _film_options(m)
    _colour_options(m)
    m.add_argument("--kind", choices=("wedge", "draining", "bubble", "file"), default="wedge")
    m.add_argument("--input", help="thickness map for --kind file (.npy in nm, or .png)")
    m.add_argument("--nm-per-count", type=float, help="PNG maps: nm per grey count")
    m.add_argument("--width", type=int, default=1920)
    m.add_argument("--height", type=int, default=1080)
    m.add_argument("--max-thickness", type=float, default=1500.0, help="wedge: nm")
    m.add_argument("--time", type=float, default=3000.0, help="draining: seconds")
    m.add_argument("--film-height", type=float, default=0.02, help="draining: metres")
    m.add_argument("--step", type=float, default=0.5, help="table thickness step, nm")
    m.add_argument("--out", required=True, help=".png or .ppm")
    add_force(m)
    m.set_defaults(handler=_map)


def _film_options(p) -> None:
    p.add_argument("--model", choices=("exact", "two-beam"), default="exact",
                   help="exact multiple-beam optics, or the two-beam model of seed 000")
    p.add_argument("--beta", type=float, default=0.95, help="two-beam model's beta")
    p.add_argument("--film", default="water",
                   help="film medium: water, oil, bk7, fused-silica, a number, or n,k CSV")
    p.add_argument("--ambient", default="air")
    p.add_argument("--substrate", default="air")
    p.add_argument("--under", default="",
                   help="fixed layers between film and substrate: 'medium:nm,medium:nm'")
    p.add_argument("--angle", type=float, default=0.0, help="angle of incidence, degrees")
    p.add_argument("--polarisation", choices=("s", "p", "unpolarised"), default="unpolarised")
    p.add_argument("--quantity", choices=("reflectance", "transmittance"), default="reflectance")


def _colour_options(p) -> None:
    add_illuminant(p, default=SEED_000_ILLUMINANT, what="the film (seed 000's 6504 K blackbody by default)")
    add_observer(p)
    p.add_argument("--exposure", choices=("global-max", "perfect-reflector"),
                   default="global-max")
    p.add_argument("--gain", type=float, default=1.0, help="with --exposure perfect-reflector")
    p.add_argument("--space", default="sRGB")
    add_gamut(p)


def _film_function(args):
    """A callable ``f(thickness_nm, wavelengths_nm, angle_deg=...) -> FilmOptics``."""
    from ..thinfilm import media
    from ..thinfilm.optics import FilmOptics, optical_path_difference, stack_optics, two_beam_reflectance

    film = media.medium(args.film)
    ambient, substrate = media.medium(args.ambient), media.medium(args.substrate)
    fixed = []
    for item in filter(None, (part.strip() for part in args.under.split(","))):
        name, sep, thickness = item.rpartition(":")
        try:
            fixed.append((media.medium(name), float(thickness)))
        except ValueError:
            raise UserError(f"--under: expected 'medium:nm', got {item!r}") from None
        if not sep:
            raise UserError(f"--under: expected 'medium:nm', got {item!r}")
        if not (np.isfinite(fixed[-1][1]) and fixed[-1][1] >= 0):
            raise UserError(f"--under: the thickness in {item!r} must be a finite number of nm >= 0")

    if args.model == "two-beam":
        if fixed or args.quantity != "reflectance":
            raise UserError("--model two-beam: a single film in reflection only")

        def two_beam(d, wl, angle_deg=0.0):
            n = float(np.real(film.refractive_index(np.array([589.3]))[0]))
            n0 = float(np.real(ambient.refractive_index(np.array([589.3]))[0]))
            opd = optical_path_difference(d, n, angle_deg, ambient_index=n0)
            factor = two_beam_reflectance(opd, wl, beta=args.beta)
            return FilmOptics(np.asarray(wl, float), factor, np.zeros_like(factor), "unpolarised")

        return two_beam

    def exact(d, wl, angle_deg=0.0):
        d = np.asarray(d, dtype=float)
        thicknesses = np.stack(
            np.broadcast_arrays(d, *[np.full(d.shape, t) for _, t in fixed]), axis=-1)
        return stack_optics(thicknesses, wl, [film] + [m for m, _ in fixed], ambient=ambient,
                            substrate=substrate, angle_deg=angle_deg,
                            polarisation=args.polarisation)

    return exact


def _colour_kwargs(args) -> dict:
    return dict(illuminant=args.illuminant, observer=args.observer, exposure=args.exposure,
                gain=args.gain, space=args.space, gamut=args.gamut)


def _series(args, count: int):
    from ..thinfilm.colour import film_colours

    film = _film_function(args)
    if count < 2 or not 0 < args.max_thickness < np.inf:
        raise UserError("need at least 2 columns/points and a positive, finite --max-thickness")
    if count > _MAX_COLUMNS:
        raise UserError(f"at most {_MAX_COLUMNS} columns/points, got {count}")
    d = np.linspace(0.0, args.max_thickness, count)
    wl = np.arange(380.0, 781.0, 5.0)
    optics = film(d, wl, angle_deg=args.angle)
    return d, film_colours(optics, quantity=args.quantity, **_colour_kwargs(args))


def _write_csv(path, first_name, first, colours) -> None:
    with atomic_path(path) as temporary, temporary.open("w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow([first_name, "X", "Y", "Z", "x", "y", "r8", "g8", "b8"])
        for value, XYZ, xy, rgb in zip(first, colours.XYZ100, colours.xy, colours.rgb8,
                                       strict=True):
            w.writerow([f"{value:g}", *(f"{v:.10g}" for v in XYZ), *(f"{v:.10g}" for v in xy),
                        *(int(c) for c in rgb)])


def _locus_plot(path, colours, label: str, title: str) -> None:
    import matplotlib

    matplotlib.use("Agg")

    from ..plot import chromaticity_diagram

    ax = chromaticity_diagram(curves=[colours.XYZ100], curve_labels=[label], title=title)
    ax.plot(*colours.xy[0], "o", color="k", ms=4)
    save_figure(ax.figure, path, dpi=150, bbox_inches="tight")


def _zawischa(args) -> int:
    from ..pictures import write_strip
    from ..thinfilm.zawischa import zawischa_strip

    if args.locus:
        _check_plot_path(args.locus, "--locus")
    check_files(args, ("out", "csv", "locus"))
    strip = zawischa_strip()
    write_strip(strip.colours.rgb8, args.out, height=80, ticks=strip.tick_columns,
                tick_height=10)
    if args.csv:
        _write_csv(args.csv, "opd_nm", strip.opd_nm, strip.colours)
    if args.locus:
        _locus_plot(args.locus, strip.colours, "soap film, two-beam, s = 5-5000 nm",
                    "Seed 000 (Zawischa): film colours, 6504 K blackbody")
    _report_written(args.out, args.csv, args.locus)
    return 0


def _strip(args) -> int:
    from ..pictures import write_strip

    check_files(args, ("out", "csv"))
    if not args.tick_every > 0 or args.max_thickness / args.tick_every > _MAX_COLUMNS:
        raise UserError(f"--tick-every must be positive and give at most {_MAX_COLUMNS} ticks "
                        f"over --max-thickness {args.max_thickness:g} nm; got {args.tick_every:g}")
    d, colours = _series(args, args.columns)
    marks = np.arange(args.tick_every, args.max_thickness + 1e-9, args.tick_every)
    ticks = np.unique(np.rint(marks / args.max_thickness * (args.columns - 1)).astype(int))
    write_strip(colours.rgb8, args.out, height=80, ticks=ticks, tick_height=10)
    if args.csv:
        _write_csv(args.csv, "thickness_nm", d, colours)
    _report_written(args.out, args.csv)
    return 0


def _locus(args) -> int:
    _check_plot_path(args.out, "--out")
    check_files(args, ("out",))
    _, colours = _series(args, args.points)
    _locus_plot(args.out, colours, f"{args.film} 0-{args.max_thickness:g} nm",
                f"Film colours, {colours.illuminant}, {args.angle:g}°")
    _report_written(args.out)
    return 0


def _map(args) -> int:
    from ..budget import check_bytes
    from ..pictures import save_image
    from ..thinfilm import maps

    if not (1 <= args.width <= _MAX_SIDE_PX and 1 <= args.height <= _MAX_SIDE_PX):
        raise UserError(f"--width and --height must be 1-{_MAX_SIDE_PX} pixels, got "
                        f"{args.width} x {args.height}")
    if not (np.isfinite(args.step) and args.step > 0):
        raise UserError(f"--step must be a positive, finite number of nm; got {args.step:g}")
    if args.kind != "file":
        check_bytes(args.width * args.height * _MAP_PIXEL_BYTES,
                    f"--width {args.width} --height {args.height}: a map of {args.width * args.height} pixels")
    check_files(args, ("out",), ("input",))
    film = _film_function(args)
    angle = None
    if args.kind == "wedge":
        thickness = maps.wedge(args.width, args.height, args.max_thickness)
    elif args.kind == "draining":
        thickness = maps.draining_film(args.width, args.height, time_s=args.time,
                                       film_height_m=args.film_height)
    elif args.kind == "bubble":
        thickness, angle = maps.bubble(min(args.width, args.height))
    else:
        if not args.input:
            raise UserError("--kind file needs --input PATH (.npy in nm or .png)")
        thickness = maps.read_thickness_map(args.input, args.nm_per_count)
    top = float(np.nanmax(thickness))
    entries = int(np.ceil(min(max(top, args.step) / args.step, 1e18) - 1e-9)) + 1
    check_bytes(entries * (1 if angle is None else _BUBBLE_ANGLES) * maps.TABLE_ENTRY_BYTES,
                f"--step {args.step:g} nm up to {top:g} nm"
                + (" (--max-thickness)" if args.kind == "wedge" else "")
                + f": a colour table of {entries} thicknesses")
    if args.angle and angle is None:
        angle_fn = film

        def film(d, wl, angle_deg=0.0):
            return angle_fn(d, wl, angle_deg=args.angle)  # the fixed --angle for every pixel

    table = maps.colour_table(film, max(top, args.step), thickness_step_nm=args.step,
                              max_angle_deg=None if angle is None else 89.0,
                              angle_step_deg=2.0, quantity=args.quantity,
                              **_colour_kwargs(args))
    save_image(maps.render_thickness_map(thickness, table, angle), args.out)
    _report_written(args.out)
    return 0


def _report_written(*paths) -> None:
    """Tell the user what was written (one line), as the other commands do."""
    print("wrote " + ", ".join(str(p) for p in paths if p))
