"""``spectrocolor report``: a colour measurement report of reflectance samples (seed 001)."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from . import UserError
from .colorimetry import FILE_HELP, PERCENT_HELP, command_line_hints, read_measurements, reflectance_factors
from .files import MAX_SPECTRAL_FILE_BYTES, add_force, check_files
from .options import add_encoding, add_illuminant, add_observer


def register(subparsers) -> None:
    """Add the ``report`` sub-command."""
    p = subparsers.add_parser(
        "report",
        help="colour measurement report of reflectance samples (HTML, CSV, JSON or CGATS.17)",
        description=(
            "For every reflectance sample in FILE: X, Y, Z, x, y, dominant or complementary "
            "wavelength, excitation purity, luminance factor, CIELAB and an sRGB swatch under "
            "the illuminant (Bradford-adapted to D65, desaturated toward the white at constant Y "
            "where out of gamut); the HTML adds a chromaticity diagram and the reflectance curves "
            "in one self-contained file."
        ),
    )
    p.add_argument("file", metavar="FILE", help=FILE_HELP)
    add_encoding(p)
    add_illuminant(p, what="the reflectance samples (seed 001 uses C)", declared=True)
    add_observer(p, declared=True)
    p.add_argument("--method", choices=_methods(), default="sum",
                   help="summation method: sum, 1nm or astm-e308 (default sum)")
    p.add_argument("--percent", action="store_true", help=PERCENT_HELP)
    p.add_argument("--out", required=True, help="output file (.html, .csv, .json, .cgats or .cxf)")
    add_force(p)
    p.add_argument("--format", choices=_FORMATS, default=None,
                   help="output format (default: from the --out suffix)")
    p.add_argument("--title", default=None, help="HTML title")
    p.add_argument("--page-rows", type=int, default=500,
                   help="HTML: list every sample up to this many, else list these and "
                   "summarise (default 500)")
    p.set_defaults(handler=_report)


_FORMATS = ("html", "csv", "json", "cgats", "cxf")


def _methods() -> tuple[str, ...]:
    from ..colorimetry import SUMMATION_METHODS

    return SUMMATION_METHODS.names()


def _report(args: argparse.Namespace) -> int:
    from ..report import measurement_report, write_report

    check_files(args, ("out",), ("file",), MAX_SPECTRAL_FILE_BYTES)
    spectra = reflectance_factors(read_measurements(args), args.file)
    if args.page_rows < 1:
        raise UserError(f"--page-rows must be at least 1; got {args.page_rows}")
    suffix = Path(args.out).suffix.lstrip(".").lower()
    suffix = {"htm": "html"}.get(suffix, suffix)
    fmt = args.format or suffix
    if fmt not in _FORMATS:
        raise UserError(f"--out {args.out!r}: give a .html, .csv, .json, .cgats or .cxf file, or --format")
    if args.format and suffix in _FORMATS and suffix != args.format:
        raise UserError(f"--format {args.format} would write {args.format.upper()} into {args.out!r}; make them agree")
    with command_line_hints():
        report = measurement_report(spectra, illuminant=args.illuminant, observer=args.observer, method=args.method)
    if report.conditions_note:  # the user's conditions differ from the file's: said here and in the report
        print(f"spectrocolor report: {args.file}: {report.conditions_note}", file=sys.stderr)
    if fmt == "cgats":
        from ..io.writers import table_to_cgats
        from ..safe_write import write_text

        keywords = {"DESCRIPTOR": f"spectrocolor report of {args.file}", "ILLUMINANT": report.illuminant,
                    "OBSERVER": report.observer, "SUMMATION_METHOD": report.method}
        write_text(args.out, table_to_cgats(report.records(), keywords))
    elif fmt == "cxf":  # the spectra with their XYZ and L*a*b*, under the report's illuminant and observer
        from ..io.cxf import report_to_cxf
        from ..safe_write import write_text

        write_text(args.out, report_to_cxf(spectra, report))
    else:
        write_report(report, args.out, fmt, title=args.title, page_rows=args.page_rows)
    print(f"wrote {args.out}: {len(report)} samples, illuminant {report.illuminant}, observer "
          f"{report.observer}")
    return 0
