"""Writes the declared-conditions corpus: the same three samples as ``make_corpus.py``/``make_dialects.py``.

Run from the repository root (``python tests/data/io/make_declared.py``); the files are committed,
so the tests never depend on this script. Each file is written from the public description of
the keywords (ANSI CGATS.17 / ISO 28178; X-Rite's ``MEASUREMENT_SOURCE`` line), none is a copied file:

* ``colorport_d65_10_cp1252.cgats``: CGATS.17 as X-Rite ColorPort writes it on Windows (cp1252:
  the en dash ``–`` is 0x96, which Latin-1 does not have; ``°`` is 0xB0), declaring
  ``MEASUREMENT_SOURCE "Illumination=D65 ObserverAngle=10° WhiteBase=Abs Filter=No"``, CRLF.
* ``eci_weighting_d50_2.cgats``: CGATS.17 with the standard's ``WEIGHTING_FUNCTION`` keyword
  written twice (``"ILLUMINANT, D50"`` and ``"OBSERVER, 2 degree"``) and
  ``MEASUREMENT_GEOMETRY "45/0"``, the way ECI/FOGRA characterisation data state D50/2°; UTF-8.
"""

from make_dialects import COUNTS, NAMES, WAVELENGTHS, frac, write


def _cgats(keywords: list[str], names: list[str]) -> str:
    rows = [f'{i + 1} "{names[i]}" ' + " ".join(frac(c) for c in COUNTS[i]) for i in range(3)]
    return "\n".join([
        "CGATS.17",
        *keywords,
        f"NUMBER_OF_FIELDS {2 + len(WAVELENGTHS)}",
        "BEGIN_DATA_FORMAT",
        "SAMPLE_ID SAMPLE_NAME " + " ".join(f"SPECTRAL_NM{nm}" for nm in WAVELENGTHS),
        "END_DATA_FORMAT",
        "NUMBER_OF_SETS 3",
        "BEGIN_DATA",
        *rows,
        "END_DATA",
    ]) + "\n"


def main() -> None:
    write("colorport_d65_10_cp1252.cgats", _cgats([
        'ORIGINATOR "X-Rite ColorPort"',
        'CREATED "01.05.2024"',
        'INSTRUMENTATION "X-Rite i1Pro"',
        'MEASUREMENT_SOURCE "Illumination=D65  ObserverAngle=10°  WhiteBase=Abs  Filter=No"',
        'KEYWORD "SampleID"',
    ], NAMES), "cp1252", "\r\n")
    write("eci_weighting_d50_2.cgats", _cgats([
        'ORIGINATOR "characterisation data, written after ISO 28178"',
        'CREATED "2024-05-01"',
        'MEASUREMENT_GEOMETRY "45/0"',
        'WEIGHTING_FUNCTION "ILLUMINANT, D50"',
        'WEIGHTING_FUNCTION "OBSERVER, 2 degree"',
    ], NAMES), "utf-8")


if __name__ == "__main__":
    main()
