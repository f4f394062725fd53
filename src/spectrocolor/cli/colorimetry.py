"""``spectrocolor xyz`` and ``spectrocolor describe``: colorimetry of the spectra in a file."""

from __future__ import annotations

import argparse
import csv
import io
import json
import sys
from contextlib import contextmanager

import numpy as np

from ..errors import ColorimetryError, SpectrumError
from ..illuminants import illuminant_label
from ..io.conditions import PERCENT_SUSPICION  # reflectance factors above this are almost surely percentages
from ..spectrum import Spectrum
from . import UserError
from .options import add_encoding, add_illuminant, add_observer

#: What the spectral file argument accepts (every format :func:`spectrocolor.read_spectra` detects).
FILE_HELP = (
    "spectral file: CSV/TSV (long or wide, ';' with decimal commas), CGATS.17/i1Profiler, "
    "Argyll .ti3/.sp, IES TM-27 XML or JSON (told by content)"
)
#: The --percent help, one wording for every command.
PERCENT_HELP = (
    "the file's values are percentages (0-100); files that declare their scale (Argyll .ti3/.sp, "
    "SPECTRAL_NORM, SPECTRAL_PCT) are read as declared without it"
)


def add_spectral_options(parser: argparse.ArgumentParser, *, lights: bool) -> None:
    """Options shared by commands that compute colour from a spectral file (``lights``: the file
    may hold lights, written ``--illuminant none``)."""
    from ..colorimetry import SUMMATION_METHODS

    parser.add_argument("file", help=FILE_HELP)
    add_encoding(parser)
    add_illuminant(parser, lights=lights, what="the reflectance/transmittance samples (seed 001's examples use C)",
                   declared=True)
    add_observer(parser, declared=True)
    parser.add_argument(
        "--interval",
        type=float,
        help="sum only at multiples of this interval in nm (e.g. 10 or 20; the file must hold those samples)",
    )
    parser.add_argument(
        "--method",
        choices=SUMMATION_METHODS.names(),
        default="sum",
        help="summation: sum at the file's samples, 1nm (linear to 1 nm), astm-e308 (ASTM E308/E2022 "
        "Table 5 weights; 1, 5, 10 or 20 nm data), astm-e308-table6 (E308 Table 6: 10 or 20 nm data not corrected "
        "for a bandpass equal to the interval) (default %(default)s)",
    )
    parser.add_argument("--range", nargs=2, type=float, metavar=("START", "STOP"), help="use only START–STOP nm")
    parser.add_argument("--percent", action="store_true", help=PERCENT_HELP)
    parser.add_argument(
        "--format",
        choices=("table", "csv", "json", "cgats"),
        default="table",
        help="output: aligned table, CSV, JSON or CGATS.17 (for i1Profiler, ArgyllCMS …) (default %(default)s)",
    )


def load_samples(args: argparse.Namespace) -> Spectrum:
    """Read ``args.file`` and apply --range, --interval and --percent, checking reflectances."""
    from .files import MAX_SPECTRAL_FILE_BYTES, check_files

    check_files(args, (), ("file",), MAX_SPECTRAL_FILE_BYTES)  # a regular file, bounded: never /dev/zero

    spectra = read_measurements(args)
    args.illuminant, args.observer = declared_conditions_of(spectra, args)  # before --interval drops metadata
    if spectra.names is None:
        spectra = Spectrum(spectra.wavelengths_nm, spectra.values, ("spectrum_1",))
    if args.range:
        spectra = spectra.restrict(*args.range)
    if args.interval is not None:
        if not (np.isfinite(args.interval) and args.interval > 0):
            raise UserError(f"--interval: must be a positive number of nm, got {args.interval:g}")
        grid = spectra.wavelengths_nm
        on_step = np.isclose(np.mod(grid + 1e-9, args.interval), 0, atol=1e-6)
        if on_step.sum() < 2:
            raise UserError(f"--interval: the file holds fewer than two samples at multiples of {args.interval:g} nm")
        step = np.diff(grid[on_step])
        if not np.allclose(step, args.interval):
            raise UserError(
                f"--interval: the file's samples ({spectra.interval_nm or 'irregular'} nm) do not include every "
                f"multiple of {args.interval:g} nm in its range; summation needs the samples themselves "
                "(use --method 1nm to integrate at 1 nm instead)"
            )
        spectra = Spectrum(grid[on_step], spectra.values[..., on_step], spectra.names)
    if args.illuminant is None:  # lights
        return spectra
    return reflectance_factors(spectra, args.file)


def read_measurements(args: argparse.Namespace) -> Spectrum:
    """``args.file`` read with ``--percent`` and ``--encoding``; a reader's warning (``--percent``
    on values that never exceed 1) is one ``warning:`` line on stderr."""
    import warnings

    from ..spectrum_io import read_spectra

    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        spectra = read_spectra(args.file, percent=True if args.percent else None, encoding=args.encoding)
    for warning in caught:
        text = str(warning.message).replace("percent was asked", "--percent was given")
        print(f"spectrocolor {args.command}: warning: {text.replace('leave percent unset', 'leave out --percent')}",
              file=sys.stderr)
    return spectra


def declared_conditions_of(spectra: Spectrum, args: argparse.Namespace):
    """``(illuminant, observer)`` to compute under: ``declared`` replaced by what the file declares
    (else D65, CIE 1931 2°); where the user's choice differs from the declaration, one line on
    stderr says so."""
    from ..io.conditions import choose_conditions

    with command_line_hints():
        illuminant, observer, note = choose_conditions(spectra, args.illuminant, args.observer)
    if note:
        print(f"spectrocolor {args.command}: {args.file}: {note}", file=sys.stderr)
    return illuminant, observer


def reflectance_factors(spectra: Spectrum, source: str) -> Spectrum:
    """The spectra, checked as reflectance factors on the 0–1 scale (read with ``--percent`` where
    the file holds undeclared percentages): negative values and values that look like percentages
    (above 1.5) are refused with a message saying what to pass."""
    values = np.atleast_2d(spectra.values)
    if np.any(values < 0):
        row, k = np.argwhere(values < 0)[0]
        name = spectra.names[row] if spectra.names else f"spectrum {row + 1}"
        raise UserError(
            f"{source}: negative reflectance {values[row, k]:g} in {name!r} at {spectra.wavelengths_nm[k]:g} nm; "
            "reflectance factors are 0–1 (for lights give --illuminant none)"
        )
    if values.max() > PERCENT_SUSPICION:
        raise UserError(
            f"{source}: reflectance values reach {values.max():g}; if they are percentages pass --percent, "
            "if they are lights give --illuminant none"
        )
    return spectra


@contextmanager
def command_line_hints():
    """Re-raise library errors as user errors, translating API advice into command-line options."""
    try:
        yield
    except (SpectrumError, ColorimetryError) as exc:
        hint = " (on the command line: --range START STOP)" if "Spectrum.restrict" in str(exc) else ""
        raise UserError(f"{exc}{hint}") from None


def compute_XYZ(spectra: Spectrum, args: argparse.Namespace) -> np.ndarray:
    from ..colorimetry import tristimulus

    illuminant = args.illuminant
    with command_line_hints():
        return np.atleast_2d(tristimulus(spectra, observer=args.observer, illuminant=illuminant, method=args.method))


def conditions(args: argparse.Namespace) -> dict[str, str]:
    """CGATS keywords saying how the rows were computed (file, illuminant, observer, method)."""
    return {
        "DESCRIPTOR": f"spectrocolor {args.command} of {args.file}",
        "ILLUMINANT": illuminant_label(args.illuminant),
        "OBSERVER": str(args.observer),
        "SUMMATION_METHOD": str(args.method),
    }


def emit(rows: list[dict], fmt: str, stream=None, keywords: dict[str, str] | None = None) -> None:
    """Print rows as an aligned table, CSV, JSON or CGATS.17 (with ``keywords``)."""
    stream = stream or sys.stdout
    if fmt == "cgats":
        from ..io.writers import table_to_cgats

        stream.write(table_to_cgats(rows, keywords).replace("\r\n", "\n"))
        return
    if fmt == "json":
        json.dump(rows, stream, indent=1)
        stream.write("\n")
        return
    columns = list(rows[0])
    if fmt == "csv":
        from ..spreadsheet import neutralise_cell  # names a spreadsheet would run become text

        writer = csv.DictWriter(stream, columns, lineterminator="\n")
        writer.writeheader()
        writer.writerows({k: neutralise_cell(v) if isinstance(v, str) else v for k, v in row.items()}
                         for row in rows)
        return
    cells = [[_cell(row[c]) for c in columns] for row in rows]
    widths = [max(len(c), *(len(r[i]) for r in cells)) for i, c in enumerate(columns)]
    numeric = [all(_numeric(r[i]) or not r[i] for r in cells) for i in range(len(columns))]
    buffer = io.StringIO()
    header = (c.rjust(w) if n else c.ljust(w) for c, w, n in zip(columns, widths, numeric, strict=True))
    buffer.write("  ".join(header).rstrip() + "\n")
    for r in cells:
        buffer.write(
            "  ".join(v.rjust(w) if _numeric(v) else v.ljust(w) for v, w in zip(r, widths, strict=True)).rstrip() + "\n"
        )
    stream.write(buffer.getvalue())


def _cell(value) -> str:
    if isinstance(value, float):
        return "" if np.isnan(value) else f"{value:.4f}"
    return str(value)


def _numeric(text: str) -> bool:
    try:
        float(text)
    except ValueError:
        return False
    return True


def _xyz_command(args: argparse.Namespace) -> int:
    from ..colorimetry import white_point
    from ..coordinates import lab, xy

    spectra = load_samples(args)
    XYZ = compute_XYZ(spectra, args)
    chromaticity = xy(XYZ)
    assert spectra.names is not None  # load_samples names every sample
    rows = [
        {"name": name, "X": float(X[0]), "Y": float(X[1]), "Z": float(X[2]), "x": float(c[0]), "y": float(c[1])}
        for name, X, c in zip(spectra.names, XYZ, chromaticity, strict=True)
    ]
    if args.illuminant is not None:  # reflectances: CIELAB relative to the perfect white summed the same way
        with command_line_hints():
            white = white_point(
                args.illuminant, observer=args.observer, wavelengths_nm=spectra.wavelengths_nm, method=args.method
            )
        for row, values in zip(rows, lab(XYZ, white), strict=True):
            row.update({"L*": float(values[0]), "a*": float(values[1]), "b*": float(values[2])})
    emit(rows, args.format, keywords=conditions(args))
    return 0


def describe_rows(spectra: Spectrum, illuminant: str, observer: str, method: str = "sum") -> list[dict]:
    """One dict per sample: XYZ, xy, dominant/complementary wavelength, purity, Y %, sRGB hex.

    The same computation as ``spectrocolor report`` (:func:`spectrocolor.report.measurement_report`):
    the white for dominant wavelength and purity is the perfect reflector summed the same way on the
    spectra's grid; swatches are Bradford-adapted to sRGB's white and desaturated if out of gamut.
    """
    from ..report import measurement_report

    report = measurement_report(spectra, illuminant=illuminant, observer=observer, method=method)
    rows = []
    for i, name in enumerate(report.names):
        wavelength = float(report.dominant_wavelength_nm[i])
        rows.append(
            {
                "name": name,
                "X": float(report.XYZ[i, 0]),
                "Y": float(report.XYZ[i, 1]),
                "Z": float(report.XYZ[i, 2]),
                "x": float(report.xy[i, 0]),
                "y": float(report.xy[i, 1]),
                "L*": float(report.lab[i, 0]),
                "a*": float(report.lab[i, 1]),
                "b*": float(report.lab[i, 2]),
                "wavelength_nm": wavelength,
                "kind": "neutral"
                if np.isnan(wavelength)
                else ("complementary" if report.complementary[i] else "dominant"),
                "purity": float(report.excitation_purity[i]),
                "luminance_factor_percent": float(report.luminance_factor[i]),
                "srgb": str(report.srgb_hex[i]),
                "in_srgb_gamut": bool(report.in_gamut[i]),
            }
        )
    return rows


def _describe_command(args: argparse.Namespace) -> int:
    spectra = load_samples(args)
    with command_line_hints():
        rows = describe_rows(spectra, args.illuminant, args.observer, args.method)
    emit(rows, args.format, keywords=conditions(args))
    return 0


def register(subparsers) -> None:
    xyz = subparsers.add_parser(
        "xyz",
        help="CIE XYZ and xy of each spectrum in a file",
        description="Tristimulus values (perfect white Y = 100) and chromaticity of each spectrum.",
    )
    add_spectral_options(xyz, lights=True)
    xyz.set_defaults(handler=_xyz_command)

    describe = subparsers.add_parser(
        "describe",
        help="XYZ, xy, dominant wavelength, purity, luminance factor and an sRGB swatch per sample",
        description=(
            "Describe surface colours as in a measurement report (seed 001): dominant or complementary "
            "wavelength and excitation purity relative to the illuminant's white, luminance factor Y in %, "
            "and an sRGB hex swatch (Bradford-adapted to D65, desaturated at constant Y if out of gamut)."
        ),
    )
    add_spectral_options(describe, lights=False)
    describe.set_defaults(handler=_describe_command)
