"""``spectrocolor recover``: the smoothest reflectance (van Trigt) for colours."""

from __future__ import annotations

import csv
from pathlib import Path

import numpy as np

from . import UserError


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
    p.add_argument("--illuminant", default="D65")
    p.add_argument("--observer", default="1931")
    p.add_argument("--range", nargs=3, type=float, default=(380.0, 780.0, 5.0),
                   metavar=("START_NM", "STOP_NM", "STEP_NM"))
    p.add_argument("--bounds", choices=("unit", "nonnegative", "none"), default="unit")
    p.add_argument("--out", type=Path, required=True, help="output CSV of reflectances")
    p.add_argument("--plot", type=Path, help="also write a PNG of the recovered curves")
    p.set_defaults(handler=_run)


def _hex_to_xyz(codes: list[str], illuminant: str, observer: str, grid) -> np.ndarray:
    from .. import rgb_space, wavelength_grid, weights

    rgb8 = []
    for code in codes:
        text = code.lstrip("#")
        if len(text) != 6 or any(c not in "0123456789abcdefABCDEF" for c in text):
            raise UserError(f"--hex: {code!r} is not an RRGGBB colour")
        rgb8.append([int(text[i:i + 2], 16) for i in (0, 2, 4)])
    space = rgb_space("sRGB")
    rgb_linear = space.transfer.decode(np.array(rgb8) / 255.0)
    XYZ = rgb_linear @ np.asarray(space.matrix_to_XYZ).T * 100.0
    # the display's white is mapped to the perfect reflector under the chosen illuminant
    white = np.asarray(weights(wavelength_grid(*grid), observer, illuminant)).sum(axis=0)
    return XYZ * (white / (np.asarray(space.matrix_to_XYZ).sum(axis=1) * 100.0))


def _read_csv(path: Path) -> np.ndarray:
    with path.open(newline="") as handle:
        rows = [r for r in csv.reader(line for line in handle if not line.startswith("#")) if r]
    if not rows or [c.strip() for c in rows[0][:3]] != ["X", "Y", "Z"]:
        raise UserError(f"--csv: {path} must start with a header X,Y,Z")
    try:
        return np.array([[float(v) for v in r[:3]] for r in rows[1:]])
    except ValueError as exc:
        raise UserError(f"--csv: {path}: {exc}") from None


def _run(args) -> int:
    from ..recovery.smoothest import smoothest_reflectance
    from ..spectrum import Spectrum
    from ..spectrum_io import write_spectra

    grid = tuple(args.range)
    if args.xyz is not None:
        XYZ, names = np.array([args.xyz]), ["colour_1"]
    elif args.hex is not None:
        XYZ, names = _hex_to_xyz(args.hex, args.illuminant, args.observer, grid), [
            "#" + h.lstrip("#").lower() for h in args.hex]
    else:
        XYZ = _read_csv(args.csv)
        names = [f"colour_{i + 1}" for i in range(len(XYZ))]
    bounds = None if args.bounds == "none" else args.bounds
    result = smoothest_reflectance(XYZ, args.illuminant, args.observer, grid, bounds)
    for name, ok, dist in zip(names, result.feasible, result.distance_outside, strict=True):
        if not ok:
            print(f"{name}: outside the reachable colours (distance ≥ {dist:.4g} XYZ100); skipped")
    keep = np.flatnonzero(result.feasible)
    if keep.size == 0:
        raise UserError("no colour can be produced by a reflectance within the bounds")
    names = [names[i] for i in keep]
    spectrum = Spectrum(result.spectrum.wavelengths_nm, result.spectrum.values[keep], names)
    write_spectra(spectrum, args.out)
    print(f"wrote {len(names)} reflectance(s) to {args.out}")
    if args.plot is not None:
        from ..recovery.plots import reflectance_curves

        ax = reflectance_curves(spectrum, title=f"smoothest reflectance, {result.illuminant}, "
                                f"bounds={args.bounds}")
        ax.figure.savefig(args.plot, dpi=100)
        print(f"wrote {args.plot}")
    return 0 if keep.size == len(result.feasible) else 1
