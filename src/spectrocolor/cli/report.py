"""``spectrocolor report``: a colour measurement report of reflectance samples (seed 001)."""

from __future__ import annotations

import argparse
from pathlib import Path

import numpy as np

from . import UserError


def register(subparsers) -> None:
    """Add the ``report`` sub-command."""
    p = subparsers.add_parser(
        "report",
        help="colour measurement report of reflectance samples (HTML, CSV or JSON)",
        description=(
            "For every reflectance sample in FILE: X, Y, Z, x, y, dominant or complementary "
            "wavelength, excitation purity, luminance factor, CIELAB and an sRGB swatch under "
            "the illuminant; the HTML adds a chromaticity diagram and the reflectance curves "
            "in one self-contained file."
        ),
    )
    p.add_argument("file", metavar="FILE", help="reflectance spectra as CSV or JSON (0-1)")
    p.add_argument("--illuminant", required=True, help="illuminant, e.g. C (seed 001), D65, A")
    p.add_argument("--observer", default="1931", help="observer (default 1931)")
    p.add_argument("--method", choices=("sum", "1nm"), default="sum",
                   help="summation method (default sum)")
    p.add_argument("--percent", action="store_true",
                   help="FILE holds reflectance in percent (0-100): divide by 100")
    p.add_argument("--out", required=True, help="output file (.html, .csv or .json)")
    p.add_argument("--format", choices=("html", "csv", "json"), default=None,
                   help="output format (default: from the --out suffix)")
    p.add_argument("--title", default=None, help="HTML title")
    p.add_argument("--page-rows", type=int, default=500,
                   help="HTML: list every sample up to this many, else list these and "
                   "summarise (default 500)")
    p.set_defaults(handler=_report)


def _report(args: argparse.Namespace) -> int:
    from ..report import measurement_report, write_report
    from ..spectrum import Spectrum
    from ..spectrum_io import read_spectra

    spectra = read_spectra(args.file)
    if args.percent:
        spectra = Spectrum(spectra.wavelengths_nm, spectra.values / 100.0, spectra.names)
    elif np.nanmax(spectra.values) > 2.0:
        raise UserError(
            f"{args.file}: reflectances reach {np.nanmax(spectra.values):g}; reflectance factors "
            "are 0-1 -- if the file is in percent, pass --percent"
        )
    if np.nanmin(spectra.values) < 0:
        raise UserError(
            f"{args.file}: negative reflectance {np.nanmin(spectra.values):g}; reflectance "
            "factors are 0-1"
        )
    if args.page_rows < 1:
        raise UserError(f"--page-rows must be at least 1; got {args.page_rows}")
    fmt = args.format or Path(args.out).suffix.lstrip(".").lower()
    if fmt not in ("html", "htm", "csv", "json"):
        raise UserError(f"--out {args.out!r}: give a .html, .csv or .json file, or --format")
    report = measurement_report(spectra, args.illuminant, args.observer, args.method)
    write_report(report, args.out, fmt, title=args.title, page_rows=args.page_rows)
    print(f"wrote {args.out}: {len(report)} samples, illuminant {report.illuminant}, observer "
          f"{report.observer}")
    return 0
