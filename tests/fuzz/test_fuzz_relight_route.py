"""Hostile input to ``POST /api/relight`` (setting 4's photo): damaged images, headers that claim
huge sizes, random bytes behind an image signature, and wrong JSON types in every field.

Every answer must be 200 or a 4xx with the server's one error shape ``{"error": "one line"}``;
never a 5xx, never a traceback, and the worker keeps answering afterwards.
"""

from __future__ import annotations

import base64
import io
import json
import struct
import zlib
from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("fastapi")
pytest.importorskip("PIL")
hypothesis = pytest.importorskip("hypothesis")
from fastapi.testclient import TestClient  # noqa: E402
from hypothesis import HealthCheck, given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402
from PIL import Image  # noqa: E402

from spectrocolor.app.server import create_app  # noqa: E402

CHART = (Path(__file__).parents[1] / "data" / "relight_chart.png").read_bytes()
FUZZ = settings(max_examples=40, deadline=None,
                suppress_health_check=[HealthCheck.function_scoped_fixture, HealthCheck.too_slow])


def _jpeg() -> bytes:
    buffer = io.BytesIO()
    Image.open(io.BytesIO(CHART)).convert("RGB").save(buffer, "JPEG", quality=90)
    return buffer.getvalue()


JPEG = _jpeg()


@pytest.fixture(scope="module")
def client():
    with TestClient(create_app(), base_url="http://127.0.0.1", raise_server_exceptions=False) as c:
        yield c


def post(client, body) -> int:
    # encoded here, not by the client: a hostile body may hold NaN or infinity, which Python writes
    # as the non-JSON words NaN/Infinity (the HTTP client refuses to send them at all)
    r = client.post("/api/relight", content=json.dumps(body), headers={"content-type": "application/json"})
    assert r.status_code in (200, 413, 422, 429), (r.status_code, r.text[:300])
    if r.status_code != 200:
        answer = r.json()
        assert list(answer) == ["error"] and isinstance(answer["error"], str)
        assert answer["error"] and "\n" not in answer["error"] and "Traceback" not in answer["error"]
    return r.status_code


def image_body(data: bytes, **kw) -> dict:
    return {"image": base64.b64encode(data).decode(), "illuminant": [30.0] * 31, **kw}


def still_answers(client) -> None:
    assert post(client, image_body(CHART)) == 200


@FUZZ
@given(source=st.sampled_from([CHART, JPEG]), edits=st.lists(
    st.tuples(st.floats(0, 1, exclude_max=True), st.integers(0, 255)), min_size=1, max_size=12),
    cut=st.floats(0.05, 1.0))
def test_damaged_images_get_one_error_or_a_picture(client, source, edits, cut):
    data = bytearray(source[:max(8, int(len(source) * cut))])
    for where, value in edits:
        data[int(where * len(data))] = value
    post(client, image_body(bytes(data)))


def _png_header(width: int, height: int, depth: int, colour_type: int) -> bytes:
    ihdr = struct.pack(">IIBBBBB", width, height, depth, colour_type, 0, 0, 0)
    chunk = struct.pack(">I", 13) + b"IHDR" + ihdr + struct.pack(">I", zlib.crc32(b"IHDR" + ihdr))
    idat = zlib.compress(b"\0" * 64)
    body = struct.pack(">I", len(idat)) + b"IDAT" + idat + struct.pack(">I", zlib.crc32(b"IDAT" + idat))
    end = struct.pack(">I", 0) + b"IEND" + struct.pack(">I", zlib.crc32(b"IEND"))
    return b"\x89PNG\r\n\x1a\n" + chunk + body + end


@FUZZ
@given(width=st.integers(1, 2**31 - 1), height=st.integers(1, 2**31 - 1),
       depth=st.sampled_from([1, 8, 16]), colour_type=st.sampled_from([0, 2, 3, 6]))
def test_headers_claiming_huge_sizes_are_refused_before_decoding(client, width, height, depth,
                                                                 colour_type):
    status = post(client, image_body(_png_header(width, height, depth, colour_type)))
    if width * height > 40_000_000:
        assert status == 422


def _jpeg_claiming(width: int, height: int) -> bytes:
    """The chart's JPEG with its frame header (SOF0) rewritten to claim width x height."""
    data = bytearray(JPEG)
    sof = data.index(b"\xff\xc0")
    data[sof + 5:sof + 9] = struct.pack(">HH", height, width)
    return bytes(data)


@FUZZ
@given(width=st.integers(1, 65535), height=st.integers(1, 65535))
def test_jpeg_frames_claiming_other_sizes(client, width, height):
    status = post(client, image_body(_jpeg_claiming(width, height)))
    if width * height > 40_000_000:
        assert status == 422


@FUZZ
@given(prefix=st.sampled_from([b"\x89PNG\r\n\x1a\n", b"\xff\xd8\xff", b"GIF89a", b""]),
       tail=st.binary(max_size=2000))
def test_random_bytes_behind_a_signature(client, prefix, tail):
    post(client, image_body(prefix + tail))


JUNK = st.one_of(st.none(), st.booleans(), st.integers(-10**12, 10**12),
                 st.floats(allow_nan=True, allow_infinity=True), st.text(max_size=40),
                 st.lists(st.integers(-5, 50), max_size=40), st.dictionaries(st.text(max_size=5),
                                                                             st.integers(), max_size=3))


@FUZZ
@given(field=st.sampled_from(["image", "illuminant", "step_nm", "observer", "source", "adaptation",
                              "gamut", "exposure", "extra"]), value=JUNK)
def test_wrong_types_in_any_field(client, field, value):
    body = image_body(CHART)
    body[field] = value
    post(client, body)


def test_the_worker_still_answers_after_the_fuzzing(client):
    still_answers(client)
    r = client.post("/api/relight", json=image_body(np.zeros(3).tobytes()))
    assert r.status_code == 422
