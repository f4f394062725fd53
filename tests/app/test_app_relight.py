"""Setting 4's photo: ``POST /api/relight`` and ``GET /api/relight/options`` (issue 17).

Golden behaviour: a photo relit under the light it was taken under comes back with identical
8-bit codes; a neutral stays neutral when the viewer adapts (the smoothest reflectance of a
neutral is flat, and the Freudenthal split keeps the grey axis an edge of every tetrahedron, so
the blend of flat node spectra is flat); the perfect white under A, seen unadapted, has A's
colour, cross-checked with colour-science from the CIE tables.
"""

from __future__ import annotations

import base64
import io
import struct
import threading
import time
import zlib
from pathlib import Path

import colour
import numpy as np
import pytest
from fastapi.testclient import TestClient
from PIL import Image

import spectrocolor as sc
from spectrocolor.app import relight_photo, relight_routes
from spectrocolor.app.server import MAX_BODY_BYTES, create_app

CHART = Path(__file__).parents[1] / "data" / "relight_chart.png"
WL = np.arange(400.0, 701.0, 10.0)
CMFS = colour.MSDS_CMFS["CIE 1931 2 Degree Standard Observer"]


@pytest.fixture(scope="module")
def client():
    with TestClient(create_app(), base_url="http://127.0.0.1") as c:  # shutdown stops the worker
        yield c


def levels(name: str) -> list[float]:
    """A CIE illuminant (colour-science's table) at the explorer's 31 bins, peak 30."""
    s = np.array([colour.SDS_ILLUMINANTS[name][w] for w in WL])
    return (30 * s / s.max()).tolist()


def png(codes: np.ndarray, **save) -> str:
    buffer = io.BytesIO()
    Image.fromarray(np.asarray(codes, np.uint8), "RGB").save(buffer, "PNG", **save)
    return base64.b64encode(buffer.getvalue()).decode()


def decoded(b64: str) -> np.ndarray:
    return np.asarray(Image.open(io.BytesIO(base64.b64decode(b64))).convert("RGB"))


def relight(client, image: str, illuminant, **kw) -> dict:
    r = client.post("/api/relight", json={"image": image, "illuminant": illuminant, **kw})
    assert r.status_code == 200, r.text
    return r.json()


def chart() -> tuple[np.ndarray, str]:
    data = CHART.read_bytes()
    return np.asarray(Image.open(io.BytesIO(data)).convert("RGB")), base64.b64encode(data).decode()


@pytest.mark.parametrize("exposure", ["fit white", "keep"])
@pytest.mark.parametrize("adaptation", ["none", "von kries", "bradford"])
def test_relit_under_its_own_light_is_the_photo(client, adaptation, exposure):
    codes, image = chart()
    answer = relight(client, image, levels("D65"), adaptation=adaptation, exposure=exposure)
    # exact: 8-bit codes, decoded from lossless PNGs
    assert np.array_equal(decoded(answer["taken_png"]), codes)
    assert np.array_equal(decoded(answer["relit_png"]), codes)  # exact: 8-bit codes
    assert (answer["width"], answer["height"], answer["downscaled"]) == (244, 164, False)
    assert answer["pixels"] == 244 * 164 and answer["colours"] == 25  # 24 patches + the frame
    assert answer["outside_solid"] == 0 and answer["out_of_range"] == "toward-grey"
    assert answer["out_of_gamut"] == 0


@pytest.mark.parametrize("adaptation", ["von kries", "bradford"])
def test_grey_card_stays_grey_under_a_when_the_viewer_adapts(client, adaptation):
    greys = np.array([[[v, v, v] for v in (30, 60, 128, 200, 255)]], np.uint8)
    answer = relight(client, png(greys), levels("A"), adaptation=adaptation)
    relit = decoded(answer["relit_png"])[0]
    assert np.all(relit == relit[:, :1]), relit  # R = G = B, exactly
    # the lightness is kept: the white stays 255 and the greys within one code of the input
    assert np.abs(relit[:, 0].astype(int) - greys[0, :, 0]).max() <= 1


def _srgb_codes_of_a_white(exposure: str) -> np.ndarray:
    """Independent: illuminant A's white on the explorer's bins, seen by a viewer adapted to D65
    (Bradford, D65 on the same bins -> sRGB's white), in sRGB (colour-science)."""
    xbar = np.array([CMFS[w] for w in WL])
    white = {}
    for name in ("A", "D65"):
        s = np.array([colour.SDS_ILLUMINANTS[name][w] for w in WL])
        white[name] = 100 * (s @ xbar) / (s @ xbar[:, 1])
    srgb = colour.RGB_COLOURSPACES["sRGB"]
    target = 100 * colour.xy_to_XYZ(srgb.whitepoint)
    seen = colour.adaptation.chromatic_adaptation_VonKries(white["A"], white["D65"], target,
                                                           transform="Bradford")
    rgb = colour.algebra.vecmul(srgb.matrix_XYZ_to_RGB, seen / 100)
    if exposure == "fit white":
        rgb = rgb / rgb.max()
    return np.round(255 * colour.cctf_encoding(np.clip(rgb, 0, 1), "sRGB")).astype(int)


@pytest.mark.parametrize("exposure", ["fit white", "keep"])
def test_white_under_a_without_adaptation_turns_warm(client, exposure):
    white = np.full((2, 3, 3), 255, np.uint8)
    answer = relight(client, png(white), levels("A"), adaptation="none", exposure=exposure,
                     gamut="clip")
    relit = decoded(answer["relit_png"])[0, 0].astype(int)
    # colour-science's sRGB matrix is rounded differently from the library's (4 digits): one code
    np.testing.assert_allclose(relit, _srgb_codes_of_a_white(exposure), atol=1)
    if exposure == "fit white":  # A's chromaticity itself, inside sRGB: an orange of hue ~60°
        L, C, h = colour.Lab_to_LCHab(colour.XYZ_to_Lab(colour.sRGB_to_XYZ(relit / 255)))
        assert 40 < h < 90 and C > 30, (L, C, h)
        assert relit[0] == 255 and 0.4 < answer["exposure_factor"] < 0.7
    else:  # Y = 100 kept: red leaves sRGB and is clipped; still R > G > B
        assert relit[0] == 255 > relit[1] > relit[2], relit
        # exact: "keep" sets the factor to 1 without arithmetic
        assert answer["exposure_factor"] == 1.0 and answer["out_of_gamut"] == 6


def test_an_edited_illuminant_is_the_one_used(client):
    """The setting's own levels, not a named light: only 600-700 nm lit makes the white red."""
    red = [30.0 if w >= 600 else 0.0 for w in WL]
    codes, image = chart()
    answer = relight(client, image, red, adaptation="none", gamut="clip", exposure="keep")
    table = relight_photo.photo_table("D65", "1931", 10.0)
    expected = relight_photo.relight_codes(codes, table, sc.Spectrum(WL, red), "none", "clip",
                                           "keep")
    relit = decoded(answer["relit_png"])
    assert np.array_equal(relit, expected["codes"])  # exact: 8-bit codes from the same function on the same CPU
    assert answer["out_of_gamut"] == expected["out_of_gamut"] > 0
    white = relit[4 + 3 * 40 + 10, 4 + 10].astype(int)  # patch 19
    assert white[0] > 3 * max(white[1], white[2]), white


@pytest.mark.parametrize("adaptation", ["von kries", "bradford"])
def test_a_line_light_that_cannot_be_adapted_to_is_one_error(client, adaptation):
    """A single line at 700 nm: its white has Z = 0, no adaptation transform can reach it."""
    line = [30.0 if w == 700 else 0.0 for w in WL]
    image = png(np.full((2, 2, 3), 200))
    r = client.post("/api/relight", json={"image": image, "illuminant": line,
                                          "adaptation": adaptation})
    assert r.status_code == 422 and r.json()["error"].startswith(f"adaptation '{adaptation}'")
    relit = decoded(relight(client, image, line, adaptation="none")["relit_png"])[0, 0]
    assert relit[0] > 0 and relit[1] == relit[2] == 0  # unadapted: pure deep red


def test_a_large_photo_is_shown_downscaled(client):
    rows = np.linspace(0, 255, 1536).astype(np.uint8)
    photo = np.stack(np.broadcast_arrays(rows[:, None], 128, 255 - rows[:, None]), -1)
    photo = np.broadcast_to(photo, (1536, 2048, 3))
    answer = relight(client, png(photo, compress_level=9), levels("D65"))
    assert (answer["photo_width"], answer["photo_height"]) == (2048, 1536)
    assert (answer["width"], answer["height"], answer["downscaled"]) == (1024, 768, True)
    assert decoded(answer["relit_png"]).shape == (768, 1024, 3)
    assert answer["max_side_px"] == relight_photo.MAX_SHOWN_SIDE_PX == 1024


def test_a_jpeg_is_read_as_pillow_decodes_it(client):
    codes, _ = chart()
    buffer = io.BytesIO()
    Image.fromarray(codes).save(buffer, "JPEG", quality=95)
    answer = relight(client, base64.b64encode(buffer.getvalue()).decode(), levels("D65"))
    expected = np.asarray(Image.open(io.BytesIO(buffer.getvalue())).convert("RGB"))
    # exact: 8-bit codes, decoded from lossless PNGs
    assert np.array_equal(decoded(answer["taken_png"]), expected)
    assert np.array_equal(decoded(answer["relit_png"]), expected)  # exact: 8-bit codes


def test_options_name_the_choices_and_defaults(client):
    o = client.get("/api/relight/options").json()
    assert o["sources"][0] == o["defaults"]["source"] == "D65"
    assert [a[0] for a in o["adaptations"]] == ["none", "von kries", "bradford"]
    assert o["defaults"]["adaptation"] == "none" and o["defaults"]["exposure"] == "fit white"
    assert all(len(a) == 3 and a[2] for a in o["adaptations"] + o["exposures"])
    # a photo file of max_photo_bytes, base64-encoded in JSON, passes the server's body limit
    assert 4 * o["max_photo_bytes"] / 3 + 10_000 < MAX_BODY_BYTES


def _png_header_only(width: int, height: int) -> str:
    """A PNG signature, an IHDR chunk (valid CRC) claiming width x height and IEND: no pixels."""
    ihdr = struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)
    chunk = struct.pack(">I", 13) + b"IHDR" + ihdr + struct.pack(">I", zlib.crc32(b"IHDR" + ihdr))
    end = struct.pack(">I", 0) + b"IEND" + struct.pack(">I", zlib.crc32(b"IEND"))
    return base64.b64encode(b"\x89PNG\r\n\x1a\n" + chunk + end).decode()


def test_a_16_bit_png_is_read_whole_and_rounded_to_the_pages_8_bits(tmp_path):
    """Pillow would cut 16-bit RGB to 8 bits by dropping the low byte; the photo reader decodes
    all 16 bits and rounds (c / 257), so 0x8100 (128.498 × 257) becomes 128, not 0x81 = 129."""
    from spectrocolor.pictures import write_image

    codes16 = np.array([[[0x8100, 0x0000, 0xFFFF], [0x0101 * 200, 0x807F, 0x0081]]], np.uint16)
    data = write_image(tmp_path / "photo16.png", codes16).read_bytes()
    assert data[24] == 16
    codes, size = relight_photo.decode_photo(data)
    assert size == (2, 1)
    assert codes.tolist() == [[[128, 0, 255], [200, 128, 1]]]
    grey = io.BytesIO()
    Image.fromarray(np.full((2, 2), 0x8100, np.uint16)).save(grey, "PNG")  # grey, 16 bits
    assert relight_photo.decode_photo(grey.getvalue())[0].tolist() == [[[128] * 3] * 2] * 2


def _png16_header_only(width: int, height: int) -> str:
    header = struct.pack(">IIBBBBB", width, height, 16, 2, 0, 0, 0)
    ihdr = b"IHDR" + header
    raw = b"\x89PNG\r\n\x1a\n" + struct.pack(">I", 13) + ihdr + struct.pack(">I", zlib.crc32(ihdr))
    return base64.b64encode(raw).decode()


@pytest.mark.parametrize(("body", "status", "words"), [
    ({"image": base64.b64encode(b"GIF89a....").decode()}, 422, "not a PNG or JPEG"),
    ({"image": "@@@@"}, 422, "base64"),
    ({"image": _png_header_only(100_000, 100_000)}, 422, "at most 40000000"),
    ({"image": _png_header_only(8000, 6000)}, 422, "at most 40000000"),
    ({"image": _png_header_only(64, 64)}, 422, "cannot be read"),
    ({"image": _png16_header_only(100_000, 100_000)}, 422, "at most 40000000"),
    ({"image": _png16_header_only(64, 64)}, 422, "the upload"),
    ({"illuminant": [30.0] * 30}, 422, "31"),
    ({"illuminant": [0.0] * 31}, 422, "dark everywhere"),
    ({"illuminant": [31.0] * 31}, 422, "illuminant"),
    ({"source": "D75"}, 422, "source"),
    ({"adaptation": "cat16"}, 422, "adaptation"),
    ({"exposure": "auto"}, 422, "exposure"),
    ({"step_nm": True}, 422, "boolean"),
    ({"file": "/etc/passwd"}, 422, "file"),
    ({"image": 12}, 422, "image"),
])
def test_bad_requests_get_one_error_line(client, body, status, words):
    full = {"image": png(np.zeros((2, 2, 3))), "illuminant": [30.0] * 31, **body}
    r = client.post("/api/relight", json=full)
    assert r.status_code == status, r.text
    error = r.json()["error"]
    assert list(r.json()) == ["error"] and "\n" not in error and words in error


def test_a_file_over_the_body_limit_is_refused_before_reading(client):
    r = client.post("/api/relight", json={"image": "A" * MAX_BODY_BYTES, "illuminant": [30] * 31})
    assert r.status_code == 413 and "larger than" in r.json()["error"]


@pytest.mark.slow
def test_busy_worker_answers_429(client, monkeypatch):
    pool = relight_routes._workers
    monkeypatch.setattr(pool, "wait_s", 0.05)  # the pool reads its wait, not the module constant
    # fill every worker with a real job (a sleep in the worker process), then ask for one more
    holders = [threading.Thread(target=pool.run, args=(time.sleep, 6.0), kwargs={"client": ("holder", i)})
               for i in range(relight_routes.RELIGHT_WORKERS)]
    for holder in holders:
        holder.start()
    try:
        deadline = time.monotonic() + 60.0
        while pool.running < relight_routes.RELIGHT_WORKERS and time.monotonic() < deadline:
            time.sleep(0.01)
        assert pool.running == relight_routes.RELIGHT_WORKERS
        r = client.post("/api/relight", json={"image": png(np.zeros((2, 2, 3))), "illuminant": [30.0] * 31})
    finally:
        for holder in holders:
            holder.join()
    assert r.status_code == 429 and "busy" in r.json()["error"]
