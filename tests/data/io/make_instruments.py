"""Writes the instrument-export corpus: the same light through each spectrometer's and light meter's format.

Run from the repository root (``python tests/data/io/make_instruments.py``); the files are
committed, so the tests never depend on this script. Each file is written from the public
description of what the software saves (see the readers' module docstrings); none is a copied file.

**The light is CIE standard illuminant A**, computed here from its defining formula (CIE 015:2018
§4.1: S_A(λ) = 100 (560/λ)⁵ (e^(1.435×10⁷/(2848×560)) − 1) / (e^(1.435×10⁷/(2848 λ)) − 1)), as
spectral irradiance E(λ) = S_A(λ) mW·m⁻²·nm⁻¹ (0.1 W·m⁻²·nm⁻¹ at 560 nm), rounded to whole
µW·m⁻²·nm⁻¹ (six decimals in W). Every file states what the meter would: the published CCT of A,
2856 K, its published chromaticity x = 0.4476, y = 0.4074 (CIE 015:2018 Table 11.3, rounded as
meters print them) and an illuminance ``683 Σ E(λ) ȳ(λ) Δλ`` summed here in plain Python from the
CIE 1931 ȳ table (``src/spectrocolor/data/cmf_cie1931_2deg.csv``, CIE 015:2018 Table 1), not with
the library. One Sekonic file holds CIE D65 (the CIE's 5 nm table, published CCT 6504 K,
x = 0.3127, y = 0.3290) in mW·m⁻²·nm⁻¹, the unit written in its row labels.

Files:

* ``uprtek_mk350.xls``: UPRtek uSpectrum "save as .xls" (tab-separated text, CRLF, ASCII): items,
  then ``380nm<TAB>…`` in mW·m⁻²·nm⁻¹.
* ``sekonic_c800.csv``: Sekonic C-800 CSV (UTF-8 with BOM: ``⊿uv``, ``°``, ``⁻²``): items, a 5 nm
  block and a 1 nm block ``Spectral Data 380[nm],…`` in W·m⁻²·nm⁻¹.
* ``sekonic_c7000_d65.csv``: Sekonic C-7000 CSV with D65 at 5 nm, ``Spectral Data 380nm [mW/m²nm]``.
* ``cl500a_memory.csv``: Konica Minolta CL-500A memory CSV (ASCII): one measurement per row,
  ``Date, Time, Illuminance, …, Tcp, delta uv, …, Spectrum[0] … Spectrum[420]`` (360–780 nm),
  two measurements (A at full and at half level).
* ``cl_s10w_utf16.txt``: a CL-S10w export saved as Unicode text (UTF-16 LE with BOM, tabs):
  ``Ev [lx]``, ``Tcp [K]``, ``Δuv`` … then ``360nm<TAB>…`` rows.
* ``oceanview_flame.txt``: OceanView "AbsoluteIrradiance" node, 2048 pixels on a quadratic
  calibration (178.2 + 0.3795 p − 1.56×10⁻⁵ p² nm), values in µW·cm⁻²·nm⁻¹ (A at
  10 µW·cm⁻²·nm⁻¹ = 0.1 W·m⁻²·nm⁻¹ at 560 nm, the same light), tab-separated, LF.
* ``spectrasuite_usb2000.txt``: SpectraSuite "Processed Spectral Data", 2048 pixels, cp1252
  (``User: Müller``), CRLF, with its End marker.
* ``cary_winuv_cp1252.csv``: Cary WinUV CSV (cp1252): two %T samples, pairs, trailing commas,
  then the method block (``Collection Time``, ``Instrument,Cary 60``, ``Operator Name,Müller`` …).
"""

import math
from pathlib import Path

HERE = Path(__file__).parent
CMF = HERE.parents[2] / "src" / "spectrocolor" / "data" / "cmf_cie1931_2deg.csv"
D65 = HERE.parents[2] / "src" / "spectrocolor" / "data" / "illuminants" / "D65.csv"


def illuminant_a(nm: float) -> float:
    """CIE illuminant A relative spectral power (CIE 015:2018 §4.1), 100 at 560 nm."""
    c = 1.435e7
    return 100 * (560 / nm) ** 5 * (math.exp(c / (2848 * 560)) - 1) / (math.exp(c / (2848 * nm)) - 1)


#: E(λ) of the corpus light, integers of 1 µW·m⁻²·nm⁻¹ at 360–780 nm.
MICRO = {nm: round(illuminant_a(nm) * 1000) for nm in range(360, 781)}


def _ybar() -> dict[int, float]:
    table = {}
    for line in CMF.read_text(encoding="utf-8").splitlines():
        cells = line.split(",")
        if cells[0].isdigit():
            table[int(cells[0])] = float(cells[2])
    return table


def lux(micro: dict[int, int], scale: float = 1.0) -> float:
    """683 Σ E ȳ Δλ (Δλ = 1 nm) in plain Python, E in W·m⁻²·nm⁻¹."""
    ybar = _ybar()
    return 683 * sum(scale * value / 1e6 * ybar[nm] for nm, value in micro.items())


def w(value_micro: float) -> str:
    return f"{value_micro / 1e6:.6f}"


def write(name: str, text: str, encoding: str, newline: str = "\n") -> None:
    (HERE / name).write_bytes(text.replace("\n", newline).encode(encoding))


def uprtek() -> None:
    visible = {nm: v for nm, v in MICRO.items() if nm >= 380}
    lines = ["Model Name\tMK350N Premium", "Serial Number\t21A00123", "Time\t2024/05/01_10:12:13", "Memo\tlamp A",
             f"LUX\t{lux(visible):.6f}", f"fc\t{lux(visible) / 10.7639:.6f}", "CCT\t2856.000000", "Duv\t0.000000",
             "I-Time\t12000.000000", "x\t0.447600", "y\t0.407400", "LambdaP\t780.000000",
             f"LambdaPValue\t{visible[780] / 1000:.6f}", "CRI\t99.900000", "R9\t99.800000",
             f"IRR\t{sum(visible.values()) / 1e6:.6f}"]
    lines += [f"{nm}nm\t{value / 1000:.6f}" for nm, value in visible.items()]
    write("uprtek_mk350.xls", "\n".join(lines) + "\n", "ascii", "\r\n")


def sekonic() -> None:
    visible = {nm: v for nm, v in MICRO.items() if nm >= 380}
    head = ["Date Saved,01/05/2024 10:12:13", "Title,Lamp A 2°", "", "Measuring Mode,Ambient",
            "Viewing Angle [°],2", "Tcp [K],2856", "⊿uv,0.0000", f"Illuminance [lx],{lux(visible):.1f}",
            f"Illuminance [fc],{lux(visible) / 10.7639:.2f}", "Peak Wavelength [nm],780",
            "CIE1931 x,0.4476", "CIE1931 y,0.4074", "PPFD [umolm⁻²s⁻¹],21.5", "CRI Ra,99.9", "TLMF,---", ""]
    five = [f"Spectral Data {nm}[nm],{w(visible[nm])}" for nm in range(380, 781, 5)]
    one = [f"Spectral Data {nm}[nm],{w(value)}" for nm, value in visible.items()]
    write("sekonic_c800.csv", "\ufeff" + "\n".join(head + five + [""] + one) + "\n", "utf-8", "\r\n")

    d65 = {}
    for line in D65.read_text(encoding="utf-8").splitlines():
        cells = line.split(",")
        if cells[0].isdigit() and 380 <= int(cells[0]) <= 780:
            d65[int(cells[0])] = cells[1]
    head = ["Date Saved,02/05/2024 09:00:00", "Title,D65 simulator", "Measuring Mode,Ambient",
            "Tcp [K],6504", "⊿uv,0.0032", "CIE1931 x,0.3127", "CIE1931 y,0.3290", ""]
    rows = [f"Spectral Data {nm}nm [mW/m²nm],{value}" for nm, value in d65.items()]
    write("sekonic_c7000_d65.csv", "\n".join(head + rows) + "\n", "utf-8", "\r\n")


def konica_minolta() -> None:
    items = ["Date", " Time", " Illuminance", " x chromaticity", " y chromaticity", " u chromaticity",
             " v chromaticity", " Tcp", " delta uv", "Dom. Wavelength", " Excit Purity", "Peak Wave"]
    header = ",".join(items + [f"Spectrum[{i}]" for i in range(421)] + ["Scotopic Lux", "S/P Ratio"])
    rows = []
    for scale, time in ((1.0, "10:12:13"), (0.5, "10:12:15")):
        values = [w(MICRO[nm] * scale) for nm in range(360, 781)]
        rows.append(",".join(["2024/5/1", time, f"{lux(MICRO, scale):.6f}", "0.447600", "0.407400", "0.255900",
                              "0.349500", "2856.000000", "0.000000", "583.000000", "58.000000", "780.000000",
                              *values, "0.000000", "1.400000"]))
    write("cl500a_memory.csv", "\n".join([header, *rows]) + "\n", "ascii", "\r\n")

    lines = ["Data Name\tLamp A", "Date\t2024/05/01 10:12:13", "Instrument\tCL-500A", "Observer\t2°",
             f"Ev [lx]\t{lux(MICRO):.2f}", "Tcp [K]\t2856", "Δuv\t0.0000", "x\t0.4476", "y\t0.4074",
             "Ra\t99.9"]
    lines += [f"{nm}nm\t{w(value)}" for nm, value in MICRO.items()]
    write("cl_s10w_utf16.txt", "\ufeff" + "\n".join(lines) + "\n", "utf-16-le", "\r\n")


def pixel_nm(p: int) -> float:
    return 178.2 + 0.3795 * p - 1.56e-5 * p * p


def oceanview() -> None:
    rows = [f"{pixel_nm(p):.3f}\t{illuminant_a(round(pixel_nm(p), 3)) / 10:.4f}" for p in range(2048)]
    head = ["Data from AbsoluteIrradiance_10-12-13-456.txt Node", "Date: Wed May 01 10:12:13 CEST 2024",
            "User: lab", "Spectrometer: FLMS01234", "Trigger mode: 0", "Integration Time (sec): 1.000000E-1",
            "Scans to average: 10", "Electric dark correction enabled: true",
            "Nonlinearity correction enabled: true", "Boxcar width: 2", "XAxis mode: Wavelengths",
            "Number of Pixels in Spectrum: 2048", ">>>>>Begin Spectral Data<<<<<"]
    write("oceanview_flame.txt", "\n".join(head + rows) + "\n", "ascii")

    grid = [339.4 + 0.3662 * p - 1.4e-5 * p * p for p in range(2048)]
    rows = [f"{nm:.2f}\t{1000 + 3000 * math.exp(-(((nm - 550) / 80) ** 2)):.2f}" for nm in grid]
    head = ["SpectraSuite Data File", "++++++++++++++++++++++++++++++++++++", "Date: Wed May 01 10:12:13 CEST 2024",
            "User: Müller", "Dark Spectrum Present: Yes", "Reference Spectrum Present: No",
            "Number of Sampled Component Spectra: 1", "Spectrometers: USB2G12345",
            "Integration Time (usec): 100000 (USB2G12345)", "Spectra Averaged: 5 (USB2G12345)",
            "Boxcar Smoothing: 0 (USB2G12345)", "Correct for Electrical Dark: Yes (USB2G12345)",
            "Number of Pixels in Processed Spectrum: 2048", ">>>>>Begin Processed Spectral Data<<<<<"]
    write("spectrasuite_usb2000.txt", "\n".join(head + rows + [">>>>>End Processed Spectral Data<<<<<"]) + "\n",
          "cp1252", "\r\n")


def cary() -> None:
    grid = list(range(800, 379, -10))
    lines = ["Filter BG38,,Filter OG550,", "Wavelength (nm),%T,Wavelength (nm),%T,"]
    for nm in grid:
        blue = 90 * math.exp(-(((nm - 480) / 90) ** 2))
        orange = 90 / (1 + math.exp((550 - nm) / 8))
        lines.append(f"{nm:.1f},{blue:.4f},{nm:.1f},{orange:.4f},")
    lines += ["", "Filter BG38", "Collection Time: 01.05.2024 10:12:13", "Operator Name,Müller",
              "Scan Software Version,4.20(468)", "Parameter List :", "Instrument,Cary 60", "Instrument Version,2.00",
              "Start (nm),800.00", "Stop (nm),380.00", "X Mode,Nanometers", "Y Mode,%T",
              "UV-Vis Scan Rate (nm/min),600", "Beam Mode,Dual Beam", "Comment,Temperatur 23 °C", "", "Filter OG550",
              "Collection Time: 01.05.2024 10:14:02"]
    write("cary_winuv_cp1252.csv", "\n".join(lines) + "\n", "cp1252", "\r\n")


def main() -> None:
    uprtek()
    sekonic()
    konica_minolta()
    oceanview()
    cary()


if __name__ == "__main__":
    main()
