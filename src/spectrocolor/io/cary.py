"""Agilent Cary WinUV CSV exports, told from other paired wavelength/value tables.

Cary WinUV's "Save as CSV" writes a row of sample names over ``Wavelength (nm),%R`` pairs (read
by :mod:`.delimited`, paired layout) and, after the data, its method block: the sample's name,
``Collection Time: …``, ``Operator Name``, ``Scan Software Version``, ``Instrument,Cary 60``,
``Start (nm)``, ``Y Mode`` …. Either the two-row header or the block says Cary; the result then
names the software and the instrument model (``metadata["format"]`` ends ``(Agilent Cary
WinUV)``, ``["instrument"]``, ``["date"]`` from the first ``Collection Time``).

References
----------
The layout as public material shows it: the Cary 300 export quoted in ComPlat's
chemotion_saurus converter profiles (``Collection Time:``, ``Scan Software Version:``,
``Instrument Cary 300`` after descending paired data) and the description this project's
``tests/data/io/make_dialects.py`` was written from.
"""

from __future__ import annotations

import re

_CARY_NOTE = re.compile(r"Collection Time|Scan Software Version|\bCary\b|Method Log|Baseline", re.IGNORECASE)


def recognise(metadata: dict, two_rows: bool) -> dict:
    """``format``/``instrument``/``date`` for an Agilent Cary WinUV export, else nothing.

    Parameters
    ----------
    metadata : dict
        A paired table's metadata (``format``, ``notes_after_data``).
    two_rows : bool
        Whether sample names stood over the row of pairs (Cary's own header).

    Returns
    -------
    dict
        ``format``, ``instrument`` and ``date`` to add; empty for a table that is not Cary's.

    Examples
    --------
    >>> recognise({"format": "CSV, paired", "notes_after_data": ("Instrument,Cary 60",)}, False)["instrument"]
    'Agilent Cary 60'
    >>> recognise({"format": "CSV, paired"}, False)
    {}
    """
    notes = metadata.get("notes_after_data", ())
    if not (two_rows or any(_CARY_NOTE.search(note) for note in notes)):
        return {}
    found: dict = {"format": f"{metadata['format']} (Agilent Cary WinUV)", "instrument": "Agilent Cary (WinUV)"}
    for note in notes:
        model = re.search(r"\bCary[ ,:]*([0-9A-Za-z]+(?: ?[A-Za-z]+)?)", note)
        if model and "instrument" in note.lower():
            found["instrument"] = f"Agilent Cary {model[1]}"
        stamp = re.match(r"Collection Time\s*:?\s*,?\s*(.+)", note)
        if stamp and "date" not in found:
            found["date"] = stamp[1].strip(" ,")
    return found
