"""Writes the reader test corpus: the same three reflectance samples in every supported format.

Run from the repository root (``python tests/data/io/make_corpus.py``); the files are committed,
so the tests never depend on this script. Each file follows its format's published description:
CGATS.17 / ISO 28178 (i1Profiler and X-Rite field styles, CRLF), ArgyllCMS CTI3 and SPECT
(percent, SPECTRAL_NORM), IES TM-27-14 and TM-27-20 XML, CSV long/wide, ``;`` with decimal commas,
TSV and JSON. Reflectances are integers of 1e-4 (fractions to four decimals, percent to two).
"""

import json
from pathlib import Path

HERE = Path(__file__).parent
WAVELENGTHS = list(range(380, 740, 10))  # 380–730 nm, the i1Pro range
NAMES = ["red tile", "green tile", "grey card"]


def _counts(i: int, nm: int) -> int:
    if i == 0:
        return 500 + int(8000 / (1 + 2.0 ** ((600 - nm) / 12)))
    if i == 1:
        return 400 + int(5000 * 2.0 ** (-(((nm - 530) / 40) ** 2)))
    return 1800 + (nm - 380) // 10


COUNTS = [[_counts(i, nm) for nm in WAVELENGTHS] for i in range(3)]


def frac(c: int) -> str:
    return f"{c / 10000:.4f}"


def pct(c: int) -> str:
    return f"{c / 100:.2f}"


def write(name: str, text: str, newline: str = "\n") -> None:
    (HERE / name).write_bytes(text.replace("\n", newline).encode("utf-8"))


def main() -> None:
    lines = ["# three reflectance samples, fractions", "wavelength_nm," + ",".join(NAMES)]
    lines += [f"{nm}," + ",".join(frac(COUNTS[i][k]) for i in range(3)) for k, nm in enumerate(WAVELENGTHS)]
    write("long.csv", "\n".join(lines) + "\n")
    lines = ["nm\t" + "\t".join(NAMES)]
    lines += [f"{nm}\t" + "\t".join(frac(COUNTS[i][k]) for i in range(3)) for k, nm in enumerate(WAVELENGTHS)]
    write("long.tsv", "\n".join(lines) + "\n")
    lines = ["Sample," + ",".join(str(nm) for nm in WAVELENGTHS)]
    lines += [f"{NAMES[i]}," + ",".join(frac(c) for c in COUNTS[i]) for i in range(3)]
    write("wide.csv", "\n".join(lines) + "\n")
    lines = ["Sample Name,Date,Geometry," + ",".join(f"{nm}nm" for nm in WAVELENGTHS)]
    lines += [f'"{NAMES[i]}",2024-05-0{i + 1},45/0,' + ",".join(frac(c) for c in COUNTS[i]) for i in range(3)]
    write("wide_named_dated.csv", "\n".join(lines) + "\n", "\r\n")
    lines = ["Probe;Datum;" + ";".join(f"{nm} nm" for nm in WAVELENGTHS)]
    lines += [f"{NAMES[i]};0{i + 1}.05.2024;" + ";".join(pct(c).replace(".", ",") for c in COUNTS[i]) for i in range(3)]
    write("semicolon_decimal_comma_percent.csv", "\n".join(lines) + "\n", "\r\n")

    fields = ["SAMPLE_ID", "SAMPLE_NAME", *(f"SPECTRAL_NM{nm}" for nm in WAVELENGTHS), "LAB_L", "LAB_A", "LAB_B"]
    rows = [f'{i + 1} "{NAMES[i]}" ' + " ".join(frac(c) for c in COUNTS[i]) + " 50.00 10.00 -5.00" for i in range(3)]
    text = "\n".join(
        [
            "CGATS.17",
            'ORIGINATOR "i1Profiler"',
            'CREATED "May 01, 2024"',
            'INSTRUMENTATION "i1Pro 2"',
            'MEASUREMENT_SOURCE "Illumination=D50\tObserverAngle=2\tWhiteBase=Abs\tFilter=No"',
            'KEYWORD "MEASUREMENT_GEOMETRY"',
            'MEASUREMENT_GEOMETRY "45/0"',
            f"NUMBER_OF_FIELDS {len(fields)}",
            "BEGIN_DATA_FORMAT",
            "\t".join(fields),
            "END_DATA_FORMAT",
            "NUMBER_OF_SETS 3",
            "BEGIN_DATA",
            *rows,
            "END_DATA",
        ]
    )
    write("i1profiler.txt", text + "\n", "\r\n")

    fields = ["SampleID", "SAMPLE_NAME", *(f"SPECTRAL_NM_{nm}" for nm in WAVELENGTHS)]
    rows = [f'A{i + 1} "{NAMES[i]}" ' + " ".join(frac(c) for c in COUNTS[i]) for i in range(3)]
    text = "\n".join(
        [
            "CGATS.17",
            "# X-Rite style field names: SPECTRAL_NM_380",
            'ORIGINATOR "X-Rite"',
            'DESCRIPTOR "three tiles"',
            f"NUMBER_OF_FIELDS {len(fields)}",
            "BEGIN_DATA_FORMAT",
            " ".join(fields),
            "END_DATA_FORMAT",
            "NUMBER_OF_SETS 3",
            "BEGIN_DATA",
            *rows,
            "END_DATA",
        ]
    )
    write("xrite_underscore.cgats", text + "\n")

    fields = ["SAMPLE_ID", "RGB_R", "RGB_G", "RGB_B", "XYZ_X", "XYZ_Y", "XYZ_Z", *(f"SPEC_{nm}" for nm in WAVELENGTHS)]
    rows = [f"{i + 1} 100 50 25 30.0 25.0 20.0 " + " ".join(pct(c) for c in COUNTS[i]) for i in range(3)]
    text = "\n".join(
        [
            "CTI3",
            "",
            'DESCRIPTOR "Argyll Calibration Target chart information 3"',
            'ORIGINATOR "Argyll chartread"',
            'CREATED "Wed May  1 10:00:00 2024"',
            'DEVICE_CLASS "OUTPUT"',
            'COLOR_REP "RGB_XYZ"',
            'TARGET_INSTRUMENT "X-Rite i1 Pro 2"',
            "",
            'KEYWORD "SPECTRAL_BANDS"',
            f'SPECTRAL_BANDS "{len(WAVELENGTHS)}"',
            'KEYWORD "SPECTRAL_START_NM"',
            f'SPECTRAL_START_NM "{WAVELENGTHS[0]:.6f}"',
            'KEYWORD "SPECTRAL_END_NM"',
            f'SPECTRAL_END_NM "{WAVELENGTHS[-1]:.6f}"',
            "",
            f"NUMBER_OF_FIELDS {len(fields)}",
            "BEGIN_DATA_FORMAT",
            " ".join(fields),
            "END_DATA_FORMAT",
            "",
            "NUMBER_OF_SETS 3",
            "BEGIN_DATA",
            *rows,
            "END_DATA",
        ]
    )
    write("argyll.ti3", text + "\n")

    fields = [f"SPEC_{nm}" for nm in WAVELENGTHS]
    text = "\n".join(
        [
            "SPECT",
            "",
            'DESCRIPTOR "red tile"',
            'ORIGINATOR "Argyll spec2cie"',
            'CREATED "Wed May  1 10:00:00 2024"',
            'KEYWORD "SPECTRAL_BANDS"',
            f'SPECTRAL_BANDS "{len(WAVELENGTHS)}"',
            'KEYWORD "SPECTRAL_START_NM"',
            'SPECTRAL_START_NM "380.000000"',
            'KEYWORD "SPECTRAL_END_NM"',
            'SPECTRAL_END_NM "730.000000"',
            'KEYWORD "SPECTRAL_NORM"',
            'SPECTRAL_NORM "100.000000"',
            "",
            f"NUMBER_OF_FIELDS {len(fields)}",
            "BEGIN_DATA_FORMAT",
            " ".join(fields),
            "END_DATA_FORMAT",
            "",
            "NUMBER_OF_SETS 1",
            "BEGIN_DATA",
            " ".join(pct(c) for c in COUNTS[0]),
            "END_DATA",
        ]
    )
    write("argyll.sp", text + "\n")

    data = "\n".join(
        f'    <SpectralData wavelength="{nm}">{frac(COUNTS[0][k])}</SpectralData>' for k, nm in enumerate(WAVELENGTHS)
    )
    text = f"""<?xml version="1.0" encoding="UTF-8"?>
<IESTM2714 xmlns="http://www.ies.org/iestm2714" version="1.0">
  <Header>
    <Manufacturer>Tiles Inc.</Manufacturer>
    <CatalogNumber>R-1</CatalogNumber>
    <Description>red tile</Description>
    <DocumentCreator>spectrocolor test corpus</DocumentCreator>
    <MeasurementEquipment>i1Pro 2</MeasurementEquipment>
    <Laboratory>Lab</Laboratory>
    <ReportNumber>1</ReportNumber>
    <ReportDate>2024-05-01</ReportDate>
    <DocumentCreationDate>2024-05-01</DocumentCreationDate>
  </Header>
  <SpectralDistribution>
    <SpectralQuantity>reflectance</SpectralQuantity>
    <ReflectionGeometry>45/0</ReflectionGeometry>
    <BandwidthFWHM>10</BandwidthFWHM>
    <BandwidthCorrected>true</BandwidthCorrected>
{data}
  </SpectralDistribution>
</IESTM2714>
"""
    write("tm27_14.xml", text)
    distributions = "\n".join(
        "  <SpectralDistribution>\n    <SpectralQuantity>reflectance</SpectralQuantity>\n"
        + "\n".join(
            f'    <SpectralData wavelength="{nm}">{frac(COUNTS[i][k])}</SpectralData>'
            for k, nm in enumerate(WAVELENGTHS)
        )
        + "\n  </SpectralDistribution>"
        for i in range(3)
    )
    text = f"""<?xml version="1.0" encoding="UTF-8"?>
<tm:IESTM2714 xmlns:tm="iesna.org/tm2714" version="2.0">
  <tm:Header>
    <tm:Manufacturer>Tiles Inc.</tm:Manufacturer>
    <tm:Description>tiles</tm:Description>
    <tm:ReportDate>2024-05-01</tm:ReportDate>
  </tm:Header>
{distributions.replace("<", "<tm:").replace("<tm:/", "</tm:")}
</tm:IESTM2714>
"""
    write("tm27_20.spdx", text)
    spectra = {NAMES[i]: [COUNTS[i][k] / 10000 for k in range(len(WAVELENGTHS))] for i in range(3)}
    write("samples.json", json.dumps({"wavelengths_nm": WAVELENGTHS, "spectra": spectra}, indent=1) + "\n")


if __name__ == "__main__":
    main()
