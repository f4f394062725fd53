"""``spectrocolor light``: colour rendering, fidelity, photometry and α-opic report of light sources."""

from __future__ import annotations

import argparse
import math
from pathlib import Path

import numpy as np

from . import UserError
from .colorimetry import FILE_HELP
from .files import MAX_SPECTRAL_FILE_BYTES, add_force, check_files
from .options import add_encoding

_FORMATS = ("html", "csv", "json")
_RESAMPLE = ("linear", "sprague", "cubic")
#: Lights printed to the terminal as a table (beyond, only a count).
_PRINTED = 10
#: How to fix a grid the colour metrics refuse, said with this command's own option.
_RESAMPLE_HINT = ("add --resample sprague (or --resample linear / cubic) to interpolate the spectra to 1 nm "
                  "first (CIE 167 recommends sprague for uniform data)")
#: The same for an irregular grid (a spectrometer's pixel wavelengths), which Sprague cannot take.
_IRREGULAR_HINT = ("add --resample linear (or --resample cubic) to interpolate the irregular samples to 1 nm "
                   "first (sprague needs uniformly spaced data)")


def register(subparsers) -> None:
    """Add the ``light`` sub-command."""
    p = subparsers.add_parser(
        "light",
        help="light source report: CCT, Duv, CRI Ra/R9, TM-30 Rf/Rg and vector graphic, LER, melanopic DER",
        description=(
            "For every spectral power distribution in FILE: CCT and Duv, the CIE 13.3 colour "
            "rendering index (Ra, R1-R14), the CIE 224:2017 / ANSI/IES TM-30-20 fidelity and gamut "
            "indices with the 16 hue bins and the colour vector graphic, the luminous efficacy of "
            "radiation and the CIE S 026 alpha-opic quantities. The spectra must be at 1 or 5 nm "
            "and cover 380-780 nm (use --resample for other grids)."
        ),
    )
    p.add_argument("file", metavar="FILE", help=FILE_HELP)
    add_encoding(p)
    p.add_argument("--out", required=True, help="output file (.html, .csv or .json)")
    p.add_argument("--format", choices=_FORMATS, default=None, help="output format (default: from the --out suffix)")
    p.add_argument("--resample", choices=_RESAMPLE, default=None,
                   help="interpolate the spectra to 1 nm first (for grids other than 1 or 5 nm; "
                   "CIE 167 recommends sprague for uniform data)")
    p.add_argument("--graphic", default=None,
                   help="also write the colour vector graphic of the first light (.png or .svg)")
    p.add_argument("--title", default=None, help="HTML title")
    add_force(p)
    p.set_defaults(handler=_light)


def _output_format(args: argparse.Namespace) -> str:
    suffix = Path(args.out).suffix.lstrip(".").lower()
    suffix = {"htm": "html"}.get(suffix, suffix)
    fmt = args.format or suffix
    if fmt not in _FORMATS:
        raise UserError(f"--out {args.out!r}: give a .html, .csv or .json file, or --format")
    if args.format and suffix in _FORMATS and suffix != args.format:
        raise UserError(f"--format {args.format} would write {args.format.upper()} into {args.out!r}; make them agree")
    if args.graphic is not None and Path(args.graphic).suffix.lower() not in (".png", ".svg"):
        raise UserError(f"--graphic {args.graphic!r}: give a .png or .svg file")
    return fmt


def _resampled(spectra, method: str | None, source: str):
    from ..spectrum import wavelength_grid

    if method is None:
        return spectra
    grid = spectra.wavelengths_nm
    if method == "sprague" and not _uniform(grid):
        raise UserError(f"--resample sprague: FILE {source} has an irregular grid ({len(grid)} samples, "
                        f"{grid[0]:g}-{grid[-1]:g} nm, e.g. a spectrometer's pixels); {_IRREGULAR_HINT}")
    start, stop = math.ceil(grid[0] - 1e-9), math.floor(grid[-1] + 1e-9)
    if stop - start < 1:
        raise UserError(f"FILE {source}: {grid[0]:g}-{grid[-1]:g} nm is too short to resample to 1 nm")
    return spectra.resample(wavelength_grid(start, stop, 1), method)


def _uniform(grid: np.ndarray) -> bool:
    """Whether the wavelengths are evenly spaced (to 1e-6 of a step: a grid written with a few decimals)."""
    steps = np.diff(grid)
    return steps.size == 0 or bool(np.all(np.abs(steps - steps[0]) <= 1e-6 * abs(steps[0])))


def _print_table(report) -> None:
    headline = report.headline()
    print("name                      CCT/K      Duv     Ra     R9     Rf     Rg  LER lm/W  mel.DER")
    for i, name in enumerate(report.names[:_PRINTED]):
        v = {key: float(column[i]) for key, column in headline.items()}
        print(f"{name[:24]:24} {v['cct_K']:7.0f} {v['duv']:8.4f} {v['Ra']:6.1f} {v['R9']:6.1f} {v['Rf']:6.1f} "
              f"{v['Rg']:6.1f} {v['LER_lm_per_W']:9.1f} {v['melanopic_DER']:8.3f}")


def _light(args: argparse.Namespace) -> int:
    from ..lighting.report import write_light_report
    from ..lighting.summary import light_report
    from ..spectrum_io import read_spectra

    fmt = _output_format(args)
    check_files(args, ("out", "graphic"), ("file",), MAX_SPECTRAL_FILE_BYTES)
    spectra = _resampled(read_spectra(args.file, encoding=args.encoding), args.resample, args.file)
    hint = _RESAMPLE_HINT if _uniform(spectra.wavelengths_nm) else _IRREGULAR_HINT
    report = light_report(spectra, resample_hint=hint)
    write_light_report(report, args.out, fmt, title=args.title)
    if args.graphic is not None:
        from ..lighting.vector_graphic import write_vector_graphic

        write_vector_graphic(report.fidelity, args.graphic, 0, title=report.names[0])
    if len(report) <= _PRINTED:
        _print_table(report)
    reasons = report.reasons()
    refused = int(np.sum(reasons != ""))
    meaningless = int(np.sum(~report.cri.meaningful & (reasons == "")))
    note = f"; CIE 13.3: CCT not meaningful (|Duv| > 0.0054) for {meaningless}" if meaningless else ""
    if refused:
        first = int(np.flatnonzero(reasons != "")[0])
        note += f"; not computed for {refused} (e.g. {report.names[first]}: {reasons[first]})"
    print(f"wrote {args.out}: {len(report)} light(s){note}")
    return 0
