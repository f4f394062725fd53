"""Writes the encodings-and-dialects corpus: the same three samples as ``make_corpus.py``.

Run from the repository root (``python tests/data/io/make_dialects.py``); the files are committed,
so the tests never depend on this script. Each file is written from the public description of
what the software saves (none is a copied file):

* ``colorport_latin1.cgats``: CGATS.17 as X-Rite ColorPort writes it, in Latin-1 (ISO-8859-1),
  ``MEASUREMENT_SOURCE "Illumination=D50 ObserverAngle=2° …"``, CRLF.
* ``excel_cp1252.csv``: a wide table saved by Windows Excel as "CSV" (cp1252), with ``µ``, ``°``
  and the cp1252-only en dash ``–`` (0x96) in names and a remark column, CRLF.
* ``utf16le_bom.tsv``: a long table saved as "Unicode text" (UTF-16 LE with BOM, tabs, CRLF).
* ``utf8_bom.csv``: a long table saved as "CSV UTF-8" (with a BOM).
* ``semicolon_trailing.csv``: a wide ``;`` table with decimal commas, every line ending in ``;``.
* ``comma_trailing.csv``: a long table, every line ending in ``,`` (LibreOffice with an empty
  last column).
* ``cary_paired.csv``: Agilent Cary WinUV "Save as CSV": a row of sample names (one over each
  pair, then an empty cell), a row ``Wavelength (nm),%R,…``, wavelengths descending from 730 nm,
  percent, every line ending in ``,``, then a blank line and the method notes.
"""

from pathlib import Path

HERE = Path(__file__).parent
WAVELENGTHS = list(range(380, 740, 10))


def _counts(i: int, nm: int) -> int:  # the same integers of 1e-4 as make_corpus.py
    if i == 0:
        return 500 + int(8000 / (1 + 2.0 ** ((600 - nm) / 12)))
    if i == 1:
        return 400 + int(5000 * 2.0 ** (-(((nm - 530) / 40) ** 2)))
    return 1800 + (nm - 380) // 10


COUNTS = [[_counts(i, nm) for nm in WAVELENGTHS] for i in range(3)]
#: Names with the characters that differ between encodings (° µ – ü).
NAMES = ["Rot – glänzend", "Grün µ2", "Grau 10°"]
#: Latin-1 has no en dash.
LATIN1_NAMES = [name.replace("–", "-") for name in NAMES]


def frac(c: int) -> str:
    return f"{c / 10000:.4f}"


def pct(c: int) -> str:
    return f"{c / 100:.2f}"


def write(name: str, text: str, encoding: str, newline: str = "\n") -> None:
    (HERE / name).write_bytes(text.replace("\n", newline).encode(encoding))


def main() -> None:
    rows = [f'{i + 1} "{LATIN1_NAMES[i]}" ' + " ".join(frac(c) for c in COUNTS[i]) for i in range(3)]
    write("colorport_latin1.cgats", "\n".join([
        "CGATS.17",
        'ORIGINATOR "X-Rite ColorPort"',
        'CREATED "01.05.2024"',
        'INSTRUMENTATION "X-Rite i1Pro"',
        'MEASUREMENT_SOURCE "Illumination=D50  ObserverAngle=2°  WhiteBase=Abs  Filter=No"',
        'KEYWORD "SampleID"',
        "NUMBER_OF_FIELDS 38",
        "BEGIN_DATA_FORMAT",
        "SAMPLE_ID SAMPLE_NAME " + " ".join(f"SPECTRAL_NM{nm}" for nm in WAVELENGTHS),
        "END_DATA_FORMAT",
        "NUMBER_OF_SETS 3",
        "BEGIN_DATA",
        *rows,
        "END_DATA",
    ]) + "\n", "latin-1", "\r\n")

    header = "Sample Name,Remark," + ",".join(f"{nm} nm" for nm in WAVELENGTHS)
    rows = [f"{NAMES[i]},D65/10° – µm ok," + ",".join(frac(c) for c in COUNTS[i]) for i in range(3)]
    write("excel_cp1252.csv", "\n".join([header, *rows]) + "\n", "cp1252", "\r\n")

    def long(delimiter: str, end: str = "") -> str:
        lines = [delimiter.join(["wavelength_nm", *NAMES]) + end]
        lines += [delimiter.join([str(nm), *(frac(COUNTS[i][k]) for i in range(3))]) + end
                  for k, nm in enumerate(WAVELENGTHS)]
        return "\n".join(lines) + "\n"

    write("utf16le_bom.tsv", "\ufeff" + long("\t"), "utf-16-le", "\r\n")
    write("utf8_bom.csv", "\ufeff" + long(","), "utf-8")
    write("comma_trailing.csv", long(",", ","), "utf-8")

    header = "Probe;Datum;" + ";".join(str(nm) for nm in WAVELENGTHS) + ";"
    rows = [f"{NAMES[i]};01.05.2024;" + ";".join(frac(c).replace(".", ",") for c in COUNTS[i]) + ";"
            for i in range(3)]
    write("semicolon_trailing.csv", "\n".join([header, *rows]) + "\n", "utf-8")

    lines = ["".join(f"{name},," for name in NAMES)[:-1], "Wavelength (nm),%R," * 3]
    for k in reversed(range(len(WAVELENGTHS))):
        lines.append("".join(f"{WAVELENGTHS[k]:.1f},{pct(COUNTS[i][k])}," for i in range(3)))
    lines += ["", "Rot – glänzend", "Collection Time: 5/1/2024 10:12:13 AM", "Method: %R 380-730 nm,,",
              "Instrument,Cary 5000,", "SBW (nm),2.0,"]
    write("cary_paired.csv", "\n".join(lines) + "\n", "utf-8", "\r\n")


if __name__ == "__main__":
    main()
