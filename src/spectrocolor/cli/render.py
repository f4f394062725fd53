"""``spectrocolor render`` (swatches of spectra on a display) and ``spectrocolor diagram``."""

from __future__ import annotations

import argparse

import numpy as np

from . import UserError
from .colorimetry import FILE_HELP
from .files import MAX_SPECTRAL_FILE_BYTES, add_force, check_files, save_figure
from .options import adapt_choices, add_encoding, add_gamut, add_illuminant, add_observer, normalise_choices

#: Largest swatch side in pixels (the image is about 8 swatches wide).
_MAX_SWATCH_PX = 1024
#: Reflectance samples with Y above this (white = 100) are almost surely percentages.
_PERCENT_SUSPICION_Y = 150.0


def register(subparsers) -> None:
    """Add the ``render`` and ``diagram`` sub-commands."""
    r = subparsers.add_parser(
        "render",
        help="render spectra as colour swatches on a display (PNG or PPM)",
        description=(
            "Compute each spectrum's colour, map it to the display (normalisation, gamut "
            "strategy, transfer function, 8-bit codes) and write swatches. Prints a table "
            "with the codes and whether each colour could be reproduced."
        ),
    )
    _common(r)
    r.add_argument("--space", default="sRGB", help="RGB space (default sRGB)")
    r.add_argument(
        "--normalise",
        choices=normalise_choices(),
        default=None,
        help="scale to the display: default 'none' for reflectances (perfect white = display "
        "white), 'global-max' for lights",
    )
    r.add_argument(
        "--scale",
        default=None,
        help="for --normalise fixed: a number, or 'object-max' (the largest channel any "
        "reflectance 0..1 can reach under the illuminant: SPECTRA's alternative A)",
    )
    add_gamut(r)
    r.add_argument(
        "--adapt",
        choices=adapt_choices(),
        default="bradford",
        help="reflectances: adapt the illuminant's white to the display white (default "
        "bradford); 'none' shows the scene as the light colours it (SPECTRA's choice)",
    )
    r.add_argument("--size", type=int, default=64, help="swatch size in pixels (default 64)")
    r.add_argument("--out", required=True, help="output image, .png or .ppm")
    add_force(r)
    r.set_defaults(handler=_render)

    d = subparsers.add_parser(
        "diagram",
        help="chromaticity diagram with a point for every spectrum",
        description="Plot every spectrum of FILE in the CIE 1931 xy or 1976 u'v' diagram.",
    )
    _common(d)
    d.add_argument("--kind", choices=("xy", "uv"), default="xy", help="diagram (default xy)")
    d.add_argument(
        "--space", action="append", default=None,
        help="gamut triangle to draw (repeatable; default sRGB)",
    )
    d.add_argument("--out", required=True, help="output image (.png, .svg, .pdf)")
    add_force(d)
    d.set_defaults(handler=_diagram)


def _common(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("file", metavar="FILE", help=FILE_HELP)
    add_encoding(parser)
    add_illuminant(parser, lights=True)
    add_observer(parser)


def _illuminant(args):
    return args.illuminant  # None for lights (--illuminant none)


def _tristimulus(args):
    from ..colorimetry import tristimulus, weights
    from ..spectrum_io import read_spectra

    spectra = read_spectra(args.file, encoding=args.encoding)
    illuminant = _illuminant(args)
    if illuminant is not None and np.min(spectra.values) < 0:
        raise UserError(
            f"{args.file}: negative reflectance {np.min(spectra.values):g}; reflectance factors are "
            "0-1 (use --illuminant none for lights)"
        )
    XYZ = tristimulus(spectra, observer=args.observer, illuminant=illuminant).reshape(-1, 3)
    W = weights(spectra.wavelengths_nm, observer=args.observer, illuminant=illuminant)
    n = XYZ.shape[0]
    names = list(spectra.names) if spectra.names else [f"spectrum {i + 1}" for i in range(n)]
    return XYZ, W, names, illuminant


def _render(args) -> int:
    from ..display import adaptation_matrix, max_object_rgb, render, rgb_space
    from ..display.explain import explain
    from ..pictures import write_swatches

    space = rgb_space(args.space)
    if not args.out.lower().endswith((".png", ".ppm")):
        raise UserError(f"--out must end in .png or .ppm, got {args.out!r}")
    check_files(args, ("out",), ("file",), MAX_SPECTRAL_FILE_BYTES)
    if not 1 <= args.size <= _MAX_SWATCH_PX:
        raise UserError(f"--size must be 1-{_MAX_SWATCH_PX} pixels, got {args.size}")
    XYZ, W, names, illuminant = _tristimulus(args)
    if illuminant is not None and np.max(XYZ[:, 1]) > _PERCENT_SUSPICION_Y:
        raise UserError(
            f"{args.file}: Y reaches {np.max(XYZ[:, 1]):.4g} under {illuminant} (the perfect white is "
            "100): are the reflectances percentages? Divide them by 100, or use --illuminant none "
            "for lights"
        )
    adapt_note = "no adaptation"
    if illuminant is not None and args.adapt != "none":
        A = adaptation_matrix(W.sum(axis=0), space.white_XYZ, args.adapt)
        XYZ, W = XYZ @ A.T, W @ A.T
        adapt_note = f"{args.adapt} adaptation of the {illuminant} white to the display white"
    normalise = args.normalise or ("none" if illuminant is not None else "global-max")
    scale = None
    if args.scale is not None:
        if normalise != "fixed":
            raise UserError("--scale is used only with --normalise fixed")
        if args.scale == "object-max":
            if illuminant is None:
                raise UserError("--scale object-max needs an illuminant (reflectances)")
            scale = float(max_object_rgb(space, W).max())
        else:
            try:
                scale = float(args.scale)
            except ValueError:
                raise UserError(
                    f"--scale must be a number or 'object-max', got {args.scale!r}"
                ) from None
    elif normalise == "fixed":
        raise UserError("--normalise fixed needs --scale (a number or 'object-max')")
    result = render(XYZ, space, normalise=normalise, gamut=args.gamut, scale=scale)
    depth = result.bit_depth
    codes8 = result.codes if depth == 8 else np.rint(result.rgb_encoded * 255).astype(int)
    write_swatches(codes8, args.out, size=args.size, crossed=~result.in_gamut)
    print(f"# space {space.name}; normalise {normalise}; gamut {args.gamut}; {adapt_note}")
    print(f"# {depth}-bit codes; out-of-gamut swatches are crossed; written to {args.out}")
    print("name\tX\tY\tZ\tcodes\tstatus")
    for i, (name, status) in enumerate(zip(names, explain(result), strict=True)):  # the library's words
        x, y, z = XYZ[i]
        code = " ".join(str(int(c)) for c in result.codes[i])
        print(f"{name}\t{x:.4f}\t{y:.4f}\t{z:.4f}\t{code}\t{status}")
    return 0


def _diagram(args) -> int:
    from ..plot import chromaticity_diagram

    check_files(args, ("out",), ("file",), MAX_SPECTRAL_FILE_BYTES)
    XYZ, W, names, illuminant = _tristimulus(args)
    if not np.all(XYZ.sum(axis=1) > 0):
        raise UserError("every spectrum must have X + Y + Z > 0 to have a chromaticity")
    whites = {} if illuminant is None else {illuminant: W.sum(axis=0)}
    ax = chromaticity_diagram(
        kind=args.kind,
        observer=args.observer,
        spaces=tuple(args.space or ("sRGB",)),
        whites=whites,
        points=XYZ,
        labels=names,
    )
    save_figure(ax.figure, args.out, dpi=150)
    print(f"wrote {args.out} ({len(names)} points, {args.kind} diagram)")
    return 0
