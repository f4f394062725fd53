"""``spectrocolor recover``: the smoothest reflectance (van Trigt) for colours."""

from __future__ import annotations

import argparse
import csv
from pathlib import Path

import numpy as np

from ..safe_write import atomic_path
from . import UserError
from .files import MAX_SPECTRAL_FILE_BYTES, add_force, check_files, save_figure
from .options import add_illuminant, add_observer


def register(subparsers) -> None:
    p = subparsers.add_parser(
        "recover",
        help="smoothest reflectance with given XYZ (van Trigt 1990), bounded 0..1 by default",
        description="Recover the smoothest reflectance for XYZ100 values (white Y = 100), "
        "for sRGB hex colours, or for a CSV of X,Y,Z columns.",
    )
    src = p.add_mutually_exclusive_group(required=True)
    src.add_argument("--xyz", nargs=3, type=float, metavar=("X", "Y", "Z"))
    src.add_argument("--hex", nargs="+", metavar="RRGGBB", help="sRGB hex colours")
    src.add_argument("--csv", type=Path, help="CSV with columns X,Y,Z (one colour per row)")
    p.add_argument("--xyz-scale", type=_scale, default=None, metavar="{1,100}",
                   help="the scale of --xyz and --csv colours: 100 (perfect white Y = 100, the default "
                   "scale) or 1 (white Y = 1: the values are multiplied by 100); --xyz with every value "
                   "at most 1 must say which")
    add_illuminant(p, what="the colours (their perfect white has Y = 100)")
    add_observer(p)
    p.add_argument("--range", nargs=3, type=float, default=(380.0, 780.0, 5.0),
                   metavar=("START_NM", "STOP_NM", "STEP_NM"),
                   help="wavelength grid of the recovered reflectance; XYZ must be on the scale "
                   "of this grid, whose perfect white has Y = 100 (default: 380 780 5)")
    p.add_argument("--bounds", choices=("unit", "nonnegative", "none"), default="unit",
                   help="unit: 0 <= R <= 1 (object colours); nonnegative: R >= 0; none: "
                   "unconstrained (default: %(default)s)")
    p.add_argument("--out", type=Path, required=True, help="output CSV of reflectances")
    p.add_argument("--plot", type=Path, help="also write a PNG of the recovered curves")
    add_force(p)
    p.set_defaults(handler=_run)


def _scale(text: str) -> float:
    try:
        value = float(text)
    except ValueError:
        value = None
    if value not in (1.0, 100.0):
        raise argparse.ArgumentTypeError(f"expected 1 (white Y = 1) or 100 (white Y = 100), got {text!r:.20}")
    return value


_scale.__name__ = "scale"


def _on_scale(XYZ: np.ndarray, scale: float | None, asked: bool) -> np.ndarray:
    """XYZ on the 100 scale: ``--xyz-scale 1`` multiplies by 100; an ``--xyz`` colour whose
    values are all at most 1 without ``--xyz-scale`` is refused (a 0–1 colour read as XYZ100 is a
    near-black reflectance)."""
    if scale is None and asked and np.all(np.abs(XYZ) <= 1.0):
        X, Y, Z = (f"{v:g}" for v in XYZ[0])
        raise UserError(
            f"--xyz {X} {Y} {Z}: every value is at most 1; is the colour on the 0–1 scale (white Y = 1)? "
            "Pass --xyz-scale 1 (it is multiplied by 100), or --xyz-scale 100 if it is this dark on the "
            "scale where white has Y = 100")
    return XYZ * 100.0 if scale == 1.0 else XYZ


def _hex_to_xyz(codes: list[str], illuminant: str, observer: str, grid) -> np.ndarray:
    from ..colorimetry import white_point
    from ..display.adaptation import adapt
    from ..display.spaces import rgb_space
    from ..spectrum import wavelength_grid

    rgb8 = []
    for code in codes:
        text = code.lstrip("#")
        if len(text) != 6 or any(c not in "0123456789abcdefABCDEF" for c in text):
            raise UserError(f"--hex: {code!r} is not an RRGGBB colour")
        rgb8.append([int(text[i:i + 2], 16) for i in (0, 2, 4)])
    space = rgb_space("sRGB")
    rgb_linear = space.transfer.decode(np.array(rgb8) / 255.0)
    XYZ100 = space.XYZ_from_rgb_linear(rgb_linear)  # the display's white has Y = 100
    # the display's white becomes the perfect reflector under the chosen illuminant by the same
    # Bradford adaptation that `describe` applies the other way, so recover → describe returns the hex
    white = white_point(illuminant, observer=observer, wavelengths_nm=wavelength_grid(*grid))
    return adapt(XYZ100, space.white_XYZ, white, method="bradford")


def _read_csv(path: Path) -> np.ndarray:
    try:
        with path.open(newline="") as handle:
            rows = [(n, r) for n, r in enumerate(csv.reader(handle), start=1)
                    if r and not r[0].lstrip().startswith("#")]
    except FileNotFoundError:
        raise UserError(f"--csv: {path}: no such file") from None
    except (OSError, UnicodeDecodeError) as exc:
        raise UserError(f"--csv: {path}: cannot be read ({exc.__class__.__name__})") from None
    if not rows or [c.strip() for c in rows[0][1][:3]] != ["X", "Y", "Z"]:
        raise UserError(f"--csv: {path} must start with a header X,Y,Z")
    values = []
    for line, row in rows[1:]:
        if len(row) < 3:
            raise UserError(f"--csv: {path}, line {line}: expected 3 values X,Y,Z, "
                            f"got {len(row)}")
        try:
            values.append([float(v) for v in row[:3]])
        except ValueError:
            raise UserError(f"--csv: {path}, line {line}: {row[:3]} are not all numbers") from None
    if not values:
        raise UserError(f"--csv: {path} has a header but no colours")
    return np.array(values)


def _run(args) -> int:
    from ..recovery.smoothest import smoothest_reflectance
    from ..spectrum import Spectrum
    from ..spectrum_io import write_spectra

    check_files(args, ("out", "plot"), ("csv",), MAX_SPECTRAL_FILE_BYTES)
    grid = tuple(args.range)
    if args.xyz_scale is not None and args.hex is not None:
        raise UserError("--xyz-scale applies to --xyz and --csv colours, not to --hex")
    if args.xyz is not None:
        XYZ, names = _on_scale(np.array([args.xyz]), args.xyz_scale, asked=True), ["colour_1"]
    elif args.hex is not None:
        XYZ, names = _hex_to_xyz(args.hex, args.illuminant, args.observer, grid), [
            "#" + h.lstrip("#").lower() for h in args.hex]
    else:
        XYZ = _on_scale(_read_csv(args.csv), args.xyz_scale, asked=False)
        names = [f"colour_{i + 1}" for i in range(len(XYZ))]
    bounds = None if args.bounds == "none" else args.bounds
    # one colour alone: the library's error (one line, with the white of this grid) says it all
    result = smoothest_reflectance(XYZ[0] if args.xyz is not None else XYZ, illuminant=args.illuminant,
                                   observer=args.observer, wavelengths=grid, bounds=bounds)
    feasible = np.atleast_1d(result.feasible)
    values = result.spectrum.values.reshape(len(feasible), -1)
    for name, ok, dist in zip(names, feasible, np.atleast_1d(result.distance_outside),
                              strict=True):
        if not ok:
            print(f"{name}: outside the reachable colours (distance ≥ {dist:.4g} XYZ100); skipped")
    keep = np.flatnonzero(feasible)
    if keep.size == 0:
        raise UserError("no colour can be produced by a reflectance within the bounds")
    names = [names[i] for i in keep]
    spectrum = Spectrum(result.spectrum.wavelengths_nm, values[keep], names)
    with atomic_path(args.out) as temporary:
        write_spectra(spectrum, temporary)
    print(f"wrote {len(names)} reflectance(s) to {args.out}")
    if args.plot is not None:
        from ..recovery.plots import reflectance_curves

        ax = reflectance_curves(spectrum, title=f"smoothest reflectance, {result.illuminant}, "
                                f"bounds={args.bounds}")
        save_figure(ax.figure, args.plot, "--plot", dpi=100)
        print(f"wrote {args.plot}")
    return 0 if keep.size == len(feasible) else 1
