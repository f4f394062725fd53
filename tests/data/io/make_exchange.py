"""Writes the exchange-format corpus: the same three samples as ``make_dialects.py`` in CxF3, QTX and .xlsx.

Run from the repository root (``python tests/data/io/make_exchange.py``); the files are committed,
so the tests never depend on this script. Each file is written from the format's public
description (none is a copied file):

* ``exchange.cgats``: CGATS.17, fractions with four decimals, ``ILLUMINANT D50``: the reference
  the other files are compared with.
* ``xrite.cxf``: CxF3 (ISO 17972-1, namespace ``http://colorexchangeformat.com/CxF3-core``) as
  X-Rite software writes it: ``FileInformation``, three ``Object`` elements with a
  ``ReflectanceSpectrum`` (``StartWL="380"``, values 0–1 with four decimals) referring to the
  colour specification ``CS_D50_2`` (``Illuminant`` D50, ``Observer`` 2_Degree, ``Method``
  E308_Table5, ``MeasurementType`` Spectrum_Reflectance, ``SingleAngle`` 45/0 Annular,
  ``WavelengthRange StartWL="380" Increment="10"``), and a fourth object with ``ColorCIELab``
  only (not a spectrum: skipped by the reader).
* ``datacolor.qtx``: Datacolor QTX (public "QTX File Specification"): ``[STANDARD_DATA 0]`` with
  ``STD_NAME``, ``STD_DATETIME``, ``STD_REFLPOINTS=36``, ``STD_REFLINTERVAL=10``,
  ``STD_REFLLOW=380``, ``STD_R=`` percent with two decimals, then two ``[BATCH_DATA n]`` sections
  (``BATCH_NAME``, ``BATCH_STD_NAME`` …); cp1252 (Windows software, the en dash is 0x96), CRLF.
* ``workbook.xlsx``: an Office Open XML workbook (ECMA-376) written with :mod:`zipfile`: sheet
  "Spectra" (first) a wide table ``Sample, Date, 380 nm, …`` (text in shared strings, dates as
  serial numbers, reflectances as numbers), sheet "Notes" text only.
* ``workbook_long.xlsx``: one sheet, a long table starting at cell ``B3`` (column A and rows 1–2
  empty), header as inline strings, percent values.
"""

import zipfile
from pathlib import Path
from xml.sax.saxutils import escape, quoteattr

HERE = Path(__file__).parent
WAVELENGTHS = list(range(380, 740, 10))


def _counts(i: int, nm: int) -> int:  # the same integers of 1e-4 as make_dialects.py
    if i == 0:
        return 500 + int(8000 / (1 + 2.0 ** ((600 - nm) / 12)))
    if i == 1:
        return 400 + int(5000 * 2.0 ** (-(((nm - 530) / 40) ** 2)))
    return 1800 + (nm - 380) // 10


COUNTS = [[_counts(i, nm) for nm in WAVELENGTHS] for i in range(3)]
NAMES = ["Rot – glänzend", "Grün µ2", "Grau 10°"]


def frac(c: int) -> str:
    return f"{c / 10000:.4f}"


def pct(c: int) -> str:
    return f"{c / 100:.2f}"


def cgats() -> str:
    fields = " ".join(f"SPECTRAL_NM{nm}" for nm in WAVELENGTHS)
    rows = [f'{i + 1} "{NAMES[i]}" ' + " ".join(frac(c) for c in COUNTS[i]) for i in range(3)]
    return "\n".join(["CGATS.17", 'ORIGINATOR "spectrocolor test corpus"', 'ILLUMINANT "D50"',
                      f"NUMBER_OF_FIELDS {len(WAVELENGTHS) + 2}", "BEGIN_DATA_FORMAT",
                      f"SAMPLE_ID SAMPLE_NAME {fields}", "END_DATA_FORMAT", "NUMBER_OF_SETS 3", "BEGIN_DATA",
                      *rows, "END_DATA", ""])


def cxf() -> str:
    objects = []
    for i, name in enumerate(NAMES):
        values = " ".join(frac(c) for c in COUNTS[i])
        objects += [f'      <cc:Object ObjectType="Target" Name={quoteattr(name)} Id="{i + 1}">',
                    "        <cc:CreationDate>2024-05-01T10:00:00</cc:CreationDate>",
                    "        <cc:ColorValues>",
                    f'          <cc:ReflectanceSpectrum ColorSpecification="CS_D50_2" StartWL="380">{values}'
                    "</cc:ReflectanceSpectrum>",
                    "        </cc:ColorValues>",
                    "      </cc:Object>"]
    objects += ['      <cc:Object ObjectType="Standard" Name="Lab only" Id="4">',
                "        <cc:ColorValues>",
                '          <cc:ColorCIELab ColorSpecification="CS_D50_2"><cc:L>50</cc:L><cc:A>10</cc:A>'
                "<cc:B>-5</cc:B></cc:ColorCIELab>",
                "        </cc:ColorValues>",
                "      </cc:Object>"]
    return "\n".join([
        '<?xml version="1.0" encoding="UTF-8"?>',
        '<cc:CxF xmlns:cc="http://colorexchangeformat.com/CxF3-core">',
        "  <cc:FileInformation>",
        "    <cc:Creator>X-Rite ColorPort (written from the CxF3 description)</cc:Creator>",
        "    <cc:CreationDate>2024-05-01T10:00:00</cc:CreationDate>",
        "    <cc:Description>three tiles</cc:Description>",
        "  </cc:FileInformation>",
        "  <cc:Resources>",
        "    <cc:ObjectCollection>",
        *objects,
        "    </cc:ObjectCollection>",
        "    <cc:ColorSpecificationCollection>",
        '      <cc:ColorSpecification Id="CS_D50_2">',
        "        <cc:TristimulusSpec>",
        "          <cc:Illuminant>D50</cc:Illuminant>",
        "          <cc:Observer>2_Degree</cc:Observer>",
        "          <cc:Method>E308_Table5</cc:Method>",
        "        </cc:TristimulusSpec>",
        "        <cc:MeasurementSpec>",
        "          <cc:MeasurementType>Spectrum_Reflectance</cc:MeasurementType>",
        "          <cc:GeometryChoice>",
        "            <cc:SingleAngle>",
        "              <cc:SingleAngleConfiguration>Annular</cc:SingleAngleConfiguration>",
        "              <cc:IlluminationAngle>45</cc:IlluminationAngle>",
        "              <cc:MeasurementAngle>0</cc:MeasurementAngle>",
        "            </cc:SingleAngle>",
        "          </cc:GeometryChoice>",
        '          <cc:WavelengthRange StartWL="380" Increment="10"/>',
        "          <cc:Device><cc:Model>i1Pro 2</cc:Model></cc:Device>",
        "        </cc:MeasurementSpec>",
        "      </cc:ColorSpecification>",
        "    </cc:ColorSpecificationCollection>",
        "  </cc:Resources>",
        "</cc:CxF>",
        ""])


def qtx() -> str:
    def section(header, prefix, name, counts, extra):
        return [header, f"{prefix}_NAME={name}", *extra, "STD_DATETIME=2024-05-01 10:00:00" if prefix == "STD"
                else "BATCH_DATETIME=2024-05-02 09:30:00", f"{prefix}_REFLPOINTS={len(WAVELENGTHS)}",
                f"{prefix}_REFLINTERVAL=10", f"{prefix}_REFLLOW=380",
                f"{prefix}_R=" + ",".join(pct(c) for c in counts), f"{prefix}_INST_TYPE=SF600", ""]

    return "\n".join([
        *section("[STANDARD_DATA 0]", "STD", NAMES[0], COUNTS[0], ["STD_VIEWING=SCI"]),
        *section("[BATCH_DATA 0]", "BATCH", NAMES[1], COUNTS[1], [f"BATCH_STD_NAME={NAMES[0]}"]),
        *section("[BATCH_DATA 1]", "BATCH", NAMES[2], COUNTS[2], [f"BATCH_STD_NAME={NAMES[0]}"]),
    ])


MAIN = 'xmlns="http://schemas.openxmlformats.org/spreadsheetml/2006/main"'
RELS = "http://schemas.openxmlformats.org/officeDocument/2006/relationships"
PACKAGE_RELS = "http://schemas.openxmlformats.org/package/2006/relationships"


def column(index: int) -> str:
    letters = ""
    index += 1
    while index:
        index, rest = divmod(index - 1, 26)
        letters = chr(65 + rest) + letters
    return letters


def workbook(path: Path, sheets: list[tuple[str, list[list[object]], int, int]], shared: bool) -> None:
    """Sheets of ``(name, rows, first row, first column)``; str cells as shared or inline strings."""
    strings: list[str] = []
    parts = {}
    for s, (_, rows, top, left) in enumerate(sheets, start=1):
        xml_rows = []
        for r, row in enumerate(rows, start=top):
            cells = []
            for c, value in enumerate(row, start=left):
                ref = f"{column(c)}{r}"
                if isinstance(value, str) and shared:
                    if value not in strings:
                        strings.append(value)
                    cells.append(f'<c r="{ref}" t="s"><v>{strings.index(value)}</v></c>')
                elif isinstance(value, str):
                    cells.append(f'<c r="{ref}" t="inlineStr"><is><t>{escape(value)}</t></is></c>')
                else:
                    cells.append(f'<c r="{ref}"><v>{value}</v></c>')
            xml_rows.append(f'<row r="{r}">{"".join(cells)}</row>')
        parts[f"xl/worksheets/sheet{s}.xml"] = (f'<?xml version="1.0" encoding="UTF-8" standalone="yes"?>\n'
                                                f'<worksheet {MAIN}><sheetData>{"".join(xml_rows)}</sheetData>'
                                                "</worksheet>")
    sheet_list = "".join(f'<sheet name={quoteattr(name)} sheetId="{s}" r:id="rId{s}"/>'
                         for s, (name, _, _, _) in enumerate(sheets, start=1))
    parts["xl/workbook.xml"] = (f'<?xml version="1.0" encoding="UTF-8" standalone="yes"?>\n'
                                f'<workbook {MAIN} xmlns:r="{RELS}"><sheets>{sheet_list}</sheets></workbook>')
    relations = "".join(f'<Relationship Id="rId{s}" Type="{RELS}/worksheet" Target="worksheets/sheet{s}.xml"/>'
                        for s in range(1, len(sheets) + 1))
    overrides = "".join(f'<Override PartName="/xl/worksheets/sheet{s}.xml" ContentType="application/'
                        'vnd.openxmlformats-officedocument.spreadsheetml.worksheet+xml"/>'
                        for s in range(1, len(sheets) + 1))
    if strings:
        relations += (f'<Relationship Id="rId{len(sheets) + 1}" Type="{RELS}/sharedStrings" '
                      'Target="sharedStrings.xml"/>')
        items = "".join(f"<si><t>{escape(text)}</t></si>" for text in strings)
        parts["xl/sharedStrings.xml"] = (f'<?xml version="1.0" encoding="UTF-8" standalone="yes"?>\n<sst {MAIN} '
                                         f'count="{len(strings)}" uniqueCount="{len(strings)}">{items}</sst>')
        overrides += ('<Override PartName="/xl/sharedStrings.xml" ContentType="application/'
                      'vnd.openxmlformats-officedocument.spreadsheetml.sharedStrings+xml"/>')
    parts["xl/_rels/workbook.xml.rels"] = f'<Relationships xmlns="{PACKAGE_RELS}">{relations}</Relationships>'
    parts["_rels/.rels"] = (f'<Relationships xmlns="{PACKAGE_RELS}"><Relationship Id="rId1" '
                            f'Type="{RELS}/officeDocument" Target="xl/workbook.xml"/></Relationships>')
    parts["[Content_Types].xml"] = (
        '<Types xmlns="http://schemas.openxmlformats.org/package/2006/content-types">'
        '<Default Extension="rels" ContentType="application/vnd.openxmlformats-package.relationships+xml"/>'
        '<Default Extension="xml" ContentType="application/xml"/>'
        '<Override PartName="/xl/workbook.xml" ContentType="application/'
        f'vnd.openxmlformats-officedocument.spreadsheetml.sheet.main+xml"/>{overrides}</Types>')
    with zipfile.ZipFile(path, "w", zipfile.ZIP_DEFLATED) as archive:
        for name in ["[Content_Types].xml", "_rels/.rels", "xl/workbook.xml", "xl/_rels/workbook.xml.rels",
                     *sorted(n for n in parts if n.startswith("xl/worksheets") or n == "xl/sharedStrings.xml")]:
            info = zipfile.ZipInfo(name, date_time=(2024, 5, 1, 10, 0, 0))
            info.compress_type = zipfile.ZIP_DEFLATED
            archive.writestr(info, parts[name])


def main() -> None:
    (HERE / "exchange.cgats").write_text(cgats(), encoding="utf-8")
    (HERE / "xrite.cxf").write_text(cxf(), encoding="utf-8")
    (HERE / "datacolor.qtx").write_bytes(qtx().replace("\n", "\r\n").encode("cp1252"))
    wide = [["Sample", "Date", *[f"{nm} nm" for nm in WAVELENGTHS]]]
    wide += [[NAMES[i], 45413 + i, *[frac(c) for c in COUNTS[i]]] for i in range(3)]
    # numbers as written in <v>: the decimal text, not Python floats (str() would be the same here)
    wide = [row[:2] + [float(v) if isinstance(v, str) and r else v for v in row[2:]] for r, row in enumerate(wide)]
    notes = [["measured on an i1Pro 2, M0"], ["operator: test"]]
    workbook(HERE / "workbook.xlsx", [("Spectra", wide, 1, 0), ("Notes", notes, 1, 0)], shared=True)
    long = [["wavelength_nm", *NAMES]] + [[nm, *[float(pct(COUNTS[i][k])) for i in range(3)]]
                                          for k, nm in enumerate(WAVELENGTHS)]
    workbook(HERE / "workbook_long.xlsx", [("Messung", long, 3, 1)], shared=False)


if __name__ == "__main__":
    main()
