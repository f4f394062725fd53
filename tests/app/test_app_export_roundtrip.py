"""Issue 28, glitch 8: the explorer's exports carry their units, and a file saved then loaded gives
the same names and levels (it used to come back as "left left red paint", with no unit).

Through the real routes (/api/export, then /api/import as the page's Load calls it) and through
the library's reader, which must still read the unit line."""

from __future__ import annotations

import json

import numpy as np
import pytest
from fastapi.testclient import TestClient

import spectrocolor as sc
from spectrocolor.app import presets as P
from spectrocolor.app.compute import EXPORT_UNIT
from spectrocolor.app.server import create_app

# names the page gives its distributions: a preset's cycle ("sunset d = 0.15"), an edited one,
# a name with a colon and a percent sign, and one a spreadsheet would run ("=1+1")
NAMES = ["sunset d = 0.15", "D65 (edited)", "grey: 50 % reflectance", "=1+1"]


@pytest.fixture(scope="module")
def client():
    with TestClient(create_app(), base_url="http://127.0.0.1") as c:  # the Host a browser sends
        yield c


def spectra():
    wl = np.arange(400.0, 701.0, 10.0)
    return [P.STRAW, [15.0] * 31, (wl / 700 * 30).round(1).tolist(), [0.0] * 30 + [30.0]]


@pytest.mark.parametrize("fmt", ["csv", "json"])
def test_export_declares_its_units_and_the_library_reads_it(client, tmp_path, fmt):
    r = client.post("/api/export", json={"format": fmt, "names": NAMES, "spectra": spectra()})
    assert r.status_code == 200, r.text
    if fmt == "csv":
        first = r.text.splitlines()[0]
        assert first == f"# values: {EXPORT_UNIT}; wavelength_nm: nanometres"
        assert r.text.splitlines()[1].startswith("wavelength_nm,")
    else:
        assert json.loads(r.text)["units"] == {"wavelengths_nm": "nm", "values": EXPORT_UNIT}
    assert "levels 0-30" in EXPORT_UNIT
    path = tmp_path / f"spectra.{fmt}"
    path.write_bytes(r.content)
    back = sc.read_spectra(path)
    expected = [("'" + n if n.startswith("=") and fmt == "csv" else n) for n in NAMES]  # CSV guard
    assert list(back.names) == expected
    # 17 significant digits are written: the levels read back to the last bit
    np.testing.assert_array_equal(back.values, np.asarray(spectra()))  # exact: written with 17 digits


@pytest.mark.parametrize("fmt", ["csv", "json"])
def test_a_saved_file_loads_back_with_the_same_names_and_levels(client, fmt):
    r = client.post("/api/export", json={"format": fmt, "names": NAMES, "spectra": spectra()})
    got = client.post("/api/import", json={"filename": f"spectra.{fmt}", "content": r.text,
                                           "scale": "levels", "step_nm": 10})
    assert got.status_code == 200, got.text
    names = got.json()["names"]
    if fmt == "csv":  # the page undoes the spreadsheet guard's apostrophe (main.js importedName)
        assert names[3] == "'=1+1"
        names[3] = names[3][1:]
    assert names == NAMES
    # linear resampling onto the same grid returns the values; at most a rounding of the
    # interpolation weights (t = 0 or 1 exactly), so a few ulps of 30
    np.testing.assert_allclose(got.json()["levels"], spectra(), rtol=0, atol=1e-12)


@pytest.mark.parametrize("name", ["../x", "a/b", "back\\slash", 'say "hi"', "<b>", "line\nbreak", ""])
def test_export_still_refuses_paths_quotes_markup_and_line_breaks(client, name):
    r = client.post("/api/export", json={"format": "csv", "names": [name], "spectra": [[1.0] * 31]})
    assert r.status_code == 422 and "names" in r.json()["error"]
