"""The light lab's upload: a measurement file's SPD, evaluated like a named light, with TM-30's 16 hue bins
equal to the library's :func:`~spectrocolor.lighting.colour_fidelity` of the same light."""

from __future__ import annotations

import base64
from pathlib import Path

import numpy as np
import pytest

from spectrocolor import Spectrum, illuminant, read_spectra
from spectrocolor.app import light_lab as lab
from spectrocolor.lighting import colour_fidelity, summary

pytest.importorskip("fastapi")
from fastapi.testclient import TestClient  # noqa: E402

from spectrocolor.app.server import create_app  # noqa: E402

DATA = Path(__file__).parents[1] / "data" / "io"
WL = lab.WAVELENGTHS_NM
#: The lab's JSON rounds each index to 4 decimals (half a unit: 5e-5); the worker may run the
#: NumPy path while the kernels compile, which differs from the compiled one by ~1e-12.
ROUNDED_4 = 5e-5 + 1e-9
#: The upload rounds the SPD (peak 1) to 6 decimals: half a unit is 5e-7.
ROUNDED_6 = 5e-7 + 1e-12


@pytest.fixture(scope="module")
def client():
    return TestClient(create_app(), base_url="http://127.0.0.1")


def uploaded(client, name: str, content: bytes):
    return client.post("/api/lab/light/upload",
                       json={"filename": name, "content_base64": base64.b64encode(content).decode()})


def fl2_csv() -> bytes:
    """CIE FL2 (CIE 15:2018 Table 10, in the library) written as a plain two-column CSV at 5 nm."""
    spd = illuminant("FL2", WL).values
    return ("wavelength_nm,FL2 measured\n" + "".join(f"{w:g},{v:.4f}\n" for w, v in zip(WL, spd, strict=True))).encode()


@pytest.mark.parametrize("name", ["sekonic_c800.csv", "oceanview_flame.txt", "cl500a_memory.csv"])
def test_an_instrument_file_gives_the_readers_spectrum_on_the_labs_grid(client, name):
    path = DATA / name
    answer = uploaded(client, name, path.read_bytes())
    assert answer.status_code == 200, answer.text
    light = answer.json()
    s = read_spectra(path)  # the library's reader; the lab takes the first spectrum of a file
    expected = np.clip(s.resample(WL).values.reshape(-1, WL.size)[0], 0, None)
    np.testing.assert_allclose(light["spd"], expected / expected.max(), rtol=0, atol=ROUNDED_6)
    assert light["label"].startswith(name) and s.names[0] in light["label"]
    assert ("took the first" in light["note"]) == (s.values.ndim == 2)


@pytest.mark.parametrize(("name", "content"), [("sekonic_c800.csv", (DATA / "sekonic_c800.csv").read_bytes()),
                                               ("fl2.csv", fl2_csv())])
def test_the_route_returns_the_librarys_16_bins_for_the_uploaded_light(client, name, content):
    light = uploaded(client, name, content).json()
    out = client.post("/api/lab/light", json={"source": {"kind": "spd", "label": light["label"],
                                                         "values": light["spd"]}})
    assert out.status_code == 200, out.text
    out = out.json()
    spd = Spectrum(WL, np.asarray(light["spd"]))
    fidelity = colour_fidelity(spd)
    for key in ("Rf_h", "Rcs_h", "Rhs_h"):
        assert len(out["hue_bins"][key]) == 16
        np.testing.assert_allclose(out["hue_bins"][key], getattr(fidelity, key), rtol=0, atol=ROUNDED_4)
    expected = summary(spd)
    for key in ("cct_K", "Ra", "Rf", "Rg", "LER_lm_per_W"):
        assert out["summary"][key] == pytest.approx(expected[key], abs=ROUNDED_4), key
    assert out["label"] == light["label"]


def test_fl2_through_a_file_is_fl2():
    """CIE FL2 read back from a CSV at 4 decimals: its published Rf of 70 (the IES TM-30 calculator's F2) and a
    chroma loss in the reds (bin 1) that the lab's charts show."""
    folder = Path(__import__("tempfile").mkdtemp())
    (folder / "fl2.csv").write_bytes(fl2_csv())
    light = lab.light_from_file(folder / "fl2.csv")
    out = lab.light_lab({"kind": "spd", "label": light["label"], "values": light["spd"]})
    assert out["summary"]["Rf"] == pytest.approx(70, abs=0.5)
    assert out["hue_bins"]["Rcs_h"][0] < -0.05


@pytest.mark.parametrize(("name", "content", "message"), [
    ("argyll.sp", (DATA / "argyll.sp").read_bytes(), "argyll.sp: covers 380-730 nm; the light lab needs 380-780 nm"),
    ("notes.txt", b"hello, world\n", "notes.txt"),
    ("dark.csv", b"wavelength_nm,x\n" + b"".join(f"{w},0\n".encode() for w in range(380, 781, 5)),
     "dark.csv: its light has no power in 380-780 nm"),
    ("binary.csv", bytes(range(256)) * 8, "binary.csv"),
])
def test_a_bad_file_gets_one_clear_error_naming_it(client, name, content, message):
    answer = uploaded(client, name, content)
    assert answer.status_code == 422
    error = answer.json()["error"]
    assert error.startswith(name) and message in error and "\0" not in error and "\n" not in error


@pytest.mark.parametrize(("values", "status"), [([0.5] * 81, 200), ([0.0] * 81, 422), ([1.0] * 80, 422),
                                                ([1.0] * 80 + [-1e-3], 422), ([1.0] * 82, 422)])
def test_the_spd_source_is_checked(client, values, status):
    answer = client.post("/api/lab/light", json={"source": {"kind": "spd", "label": "x", "values": values}})
    assert answer.status_code == status and (status == 200 or isinstance(answer.json()["error"], str))


def test_measured_spd_refuses_what_the_route_would():
    for bad in ([np.nan] * 81, [-1.0] + [1.0] * 80, "81 values", [[1.0] * 81]):
        with pytest.raises(ValueError, match="give 81 finite, non-negative powers"):
            lab.measured_spd(bad)
