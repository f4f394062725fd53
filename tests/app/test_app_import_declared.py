"""``POST /api/import`` decodes the file's bytes as the library does and reports its declared conditions.

Files of ``tests/data/io/make_declared.py``/``make_dialects.py``: a cp1252 X-Rite ColorPort-like
export declaring D65/10° and a Latin-1 one declaring D50/2°.
"""

from __future__ import annotations

import base64
from pathlib import Path

import numpy as np
import pytest
from fastapi.testclient import TestClient

import spectrocolor as sc
from spectrocolor.app import compute
from spectrocolor.app.import_routes import MAX_IMPORT_BYTES
from spectrocolor.app.server import create_app

CORPUS = Path(__file__).parents[1] / "data" / "io"


@pytest.fixture(scope="module")
def client():
    with TestClient(create_app(), base_url="http://127.0.0.1") as client:  # the Host a browser sends
        yield client


def _post(client, name: str, **extra):
    data = (CORPUS / name).read_bytes()
    return client.post("/api/import", json={"filename": name, "content_base64": base64.b64encode(data).decode(),
                                            "scale": "unit", **extra})


def test_a_cp1252_colorport_export_reads_with_its_encoding_and_declaration(client):
    r = _post(client, "colorport_d65_10_cp1252.cgats", observer="1931")
    assert r.status_code == 200, r.text
    answer = r.json()
    assert answer["names"] == ["Rot – glänzend", "Grün µ2", "Grau 10°"]  # decoded as cp1252, not garbled
    metadata = answer["metadata"]
    assert metadata["encoding"] == "cp1252" and metadata["declared_illuminant"] == "D65"
    assert metadata["declared_observer"] == "CIE 1964 10°"
    note = ("the file declares D65/10°; the page computes under its own light and the CIE 1931 2° observer, "
            "as chosen on the page")
    assert metadata["conditions_note"] == note and "encoding cp1252" in answer["note"] and note in answer["note"]
    # the levels are the library's reading of the same bytes, resampled as the page asks
    spectra = sc.read_spectra(CORPUS / "colorport_d65_10_cp1252.cgats")
    expected = spectra.resample(compute.grid(10.0), "linear").values * compute.FULL_LEVEL
    # one resampling and one product per value: a few ulps of 30
    np.testing.assert_allclose(answer["levels"], np.clip(expected, 0, compute.FULL_LEVEL), rtol=0, atol=1e-12)


def test_a_declared_d50_file_is_said(client):
    answer = _post(client, "colorport_latin1.cgats", observer="1964").json()
    assert answer["metadata"]["declared_illuminant"] == "D50"
    assert "the file declares D50/2°; the page computes under its own light and the CIE 1964 10° observer" \
        in answer["note"]


def test_text_content_still_works_and_has_no_note_without_a_declaration(client):
    text = (CORPUS / "wide.csv").read_text(encoding="utf-8")
    r = client.post("/api/import", json={"filename": "wide.csv", "content": text, "scale": "peak"})
    assert r.status_code == 200, r.text
    assert "declares" not in r.json()["note"] and "conditions_note" not in r.json()["metadata"]


@pytest.mark.parametrize(
    ("body", "needle"),
    [
        ({"filename": "x.csv"}, "one of them"),
        ({"filename": "x.csv", "content": "a", "content_base64": "YQ=="}, "one of them"),
        ({"filename": "x.csv", "content_base64": "not base64!"}, "x.csv: content_base64 is not base64"),
        ({"filename": "x.csv", "content_base64": "YQ==", "observer": "1999"}, "observer"),
        ({"filename": "x.csv", "content_base64": "A" * (4 * (MAX_IMPORT_BYTES // 3) + 8)}, "content_base64"),
    ],
)
def test_bad_bodies_get_one_clear_422(client, body, needle):
    r = client.post("/api/import", json=body)
    assert r.status_code == 422 and needle in r.json()["error"], r.text


@pytest.mark.parametrize("name", ["workbook.xlsx", "xrite.cxf", "datacolor.qtx"])
def test_the_page_imports_the_exchange_formats_as_the_library_reads_them(client, name):
    """A workbook (binary), a CxF3 document and a cp1252 QTX file through the page's Load (bytes)."""
    r = _post(client, name)
    assert r.status_code == 200, r.text
    spectra = sc.read_spectra(CORPUS / name)
    assert r.json()["names"] == list(spectra.names)[: len(r.json()["names"])]
    expected = spectra.resample(compute.grid(10.0), "linear").values * compute.FULL_LEVEL
    # one resampling and one product per value: a few ulps of 30
    np.testing.assert_allclose(r.json()["levels"], np.clip(expected, 0, compute.FULL_LEVEL)[: len(r.json()["levels"])],
                               rtol=0, atol=1e-12)


def test_the_page_offers_every_format_the_library_reads():
    page = (Path(sc.__file__).parent / "app" / "static" / "index.html").read_text(encoding="utf-8")
    accepted = page.split('id="file" type="file" accept="', 1)[1].split('"', 1)[0].split(",")
    for suffix in (".csv", ".txt", ".json", ".cgats", ".ti3", ".xml", ".cxf", ".qtx", ".xlsx"):
        assert suffix in accepted
