"""Reading measurement files: spectrocolor's readers vs colour-science and a plain NumPy limit.

Run: .venv/bin/python bench/bench_io.py
Writes 5 000 reflectance samples (380–730 nm, 10 nm) as long and wide CSV, CGATS.17 (i1Profiler style)
and IES TM-27 XML (one sample) into a temporary folder and prints best-of-5 wall times measured
in this one run: ``sc.read_spectra`` (format detected by content); colour-science's
``read_sds_from_csv_file`` (long CSV) and ``SpectralDistribution_IESTM2714.read`` (TM-27-14; it
has no CGATS or wide-CSV reader); and ``np.loadtxt`` on the numbers alone, the limit for a text parser in
NumPy.
"""

from __future__ import annotations

import tempfile
from pathlib import Path

import numpy as np

import spectrocolor as sc
from timing import best_of

SAMPLES = 5000


def main() -> None:
    import colour

    grid = np.arange(380.0, 731.0, 10.0)
    values = np.round(np.random.default_rng(0).random((SAMPLES, grid.size)), 4)
    names = [f"s{i}" for i in range(SAMPLES)]
    folder = Path(tempfile.mkdtemp())
    spectra = sc.Spectrum(grid, values, names)
    long_csv = sc.write_spectra(spectra, folder / "long.csv")
    cgats = sc.write_spectra(spectra, folder / "samples.cgats")
    wide_csv = folder / "wide.csv"  # one sample per row, as instrument software exports
    wide_csv.write_text(
        "name," + ",".join(f"{nm:g}" for nm in grid) + "\n"
        + "".join(f"{n}," + ",".join(f"{v:.4f}" for v in row) + "\n" for n, row in zip(names, values, strict=True))
    )
    numbers = folder / "numbers.txt"
    np.savetxt(numbers, values, fmt="%.4f")
    tm27 = folder / "lamp.xml"
    data = "".join(
        f'<SpectralData wavelength="{nm:g}">{v:.4f}</SpectralData>' for nm, v in zip(grid, values[0], strict=True)
    )
    tm27.write_text(
        '<IESTM2714 xmlns="http://www.ies.org/iestm2714" version="1.0"><Header><Description>x</Description>'
        "<DocumentCreator>bench</DocumentCreator></Header><SpectralDistribution><SpectralQuantity>relative"
        f"</SpectralQuantity>{data}</SpectralDistribution></IESTM2714>"
    )

    def colour_tm27():
        sd = colour.SpectralDistribution_IESTM2714(str(tm27))
        sd.read()

    rows = [
        (
            "long CSV, 5000 samples",
            best_of(lambda: sc.read_spectra(long_csv)),
            best_of(lambda: colour.read_sds_from_csv_file(str(long_csv))),
        ),
        ("wide CSV, 5000 samples", best_of(lambda: sc.read_spectra(wide_csv)), None),
        ("CGATS.17, 5000 samples", best_of(lambda: sc.read_spectra(cgats)), None),
        ("TM-27 XML, 1 sample", best_of(lambda: sc.read_spectra(tm27)), best_of(colour_tm27)),
    ]
    limit = best_of(lambda: np.loadtxt(numbers))
    print(f"np.loadtxt on the 5000 x {grid.size} numbers alone: {limit * 1e3:.1f} ms")
    print(f"{'file':28s} {'ours ms':>9s} {'colour ms':>10s} {'colour/ours':>12s} {'ours/loadtxt':>13s}")
    for label, ours, theirs in rows:
        theirs_text = f"{theirs * 1e3:10.1f} {theirs / ours:12.1f}" if theirs is not None else f"{'—':>10s} {'—':>12s}"
        ratio = f"{ours / limit:13.2f}" if "5000" in label else f"{'—':>13s}"
        print(f"{label:28s} {ours * 1e3:9.1f} {theirs_text} {ratio}")


if __name__ == "__main__":
    main()
