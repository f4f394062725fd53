"""Latency of setting 4's photo: ``POST /api/relight`` for a 1-megapixel photo, over HTTP.

Starts the explorer as a user starts it (``spectrocolor app --port 0 --no-browser``), posts a
1000 x 1000 JPEG (a smooth gradient with noise: many distinct colours, like a photo) with the
A illuminant at 31 bins, and times the answer end to end (base64, JSON, worker process, decode,
relight, two PNG encodes): the first answer (worker start and table build included) and the
median / max of the warm ones. Beside it, in the same run and the same process:

* the **plain NumPy limit** of the same job without spectra: decode the JPEG, codes -> linear
  through a 256-entry table, one 3 x 3 matrix per pixel (a von Kries relight), linear -> codes,
  encode one PNG;
* the worker's steps timed in this process (decode, distinct colours, the library's relight of
  them, rendering, PNG encoding);
* **colour-science**: the same von Kries-type relight with its functions (``cctf_decoding``,
  ``chromatic_adaptation`` Bradford, ``cctf_encoding``) on the decoded photo.

Run: .venv/bin/python bench/bench_relight_latency.py [--size 1000] [--repeat 5]
"""

from __future__ import annotations

import argparse
import base64
import io
import json
import re
import subprocess
import sys
import time
import urllib.request

import numpy as np


def photo(size: int) -> bytes:
    rng = np.random.default_rng(17)
    y, x = np.mgrid[0:size, 0:size] / size
    rgb = np.stack([x, y, 1 - 0.5 * (x + y)], -1) * 235 + rng.normal(0, 6, (size, size, 3)) + 10
    from PIL import Image

    buffer = io.BytesIO()
    Image.fromarray(np.clip(rgb, 0, 255).astype(np.uint8), "RGB").save(buffer, "JPEG", quality=90)
    return buffer.getvalue()


def a_levels() -> list[float]:
    import spectrocolor as sc

    values = np.asarray(sc.illuminant("A").resample(np.arange(400.0, 701.0, 10.0)).values)
    return (30 * values / values.max()).tolist()


def post(url: str, body: bytes) -> tuple[float, dict]:
    request = urllib.request.Request(url + "api/relight", data=body,
                                     headers={"Content-Type": "application/json"})
    start = time.perf_counter()
    with urllib.request.urlopen(request, timeout=120) as r:
        answer = json.loads(r.read())
    return time.perf_counter() - start, answer


def numpy_limit(data: bytes) -> float:
    from PIL import Image

    start = time.perf_counter()
    codes = np.asarray(Image.open(io.BytesIO(data)).convert("RGB"))
    lut = np.where(np.arange(256) / 255 <= 0.04045, np.arange(256) / 255 / 12.92,
                   ((np.arange(256) / 255 + 0.055) / 1.055) ** 2.4)
    linear = lut[codes] @ np.diag([1.2, 0.9, 0.4]).T
    encoded = np.where(linear <= 0.0031308, 12.92 * linear, 1.055 * np.clip(linear, 0, 1) ** (1 / 2.4) - 0.055)
    out = np.round(255 * np.clip(encoded, 0, 1)).astype(np.uint8)
    Image.fromarray(out, "RGB").save(io.BytesIO(), "PNG", compress_level=1)
    return time.perf_counter() - start


def colour_science(data: bytes) -> float:
    import colour
    from PIL import Image

    start = time.perf_counter()
    codes = np.asarray(Image.open(io.BytesIO(data)).convert("RGB"))
    linear = colour.cctf_decoding(codes / 255, "sRGB")
    XYZ = colour.sRGB_to_XYZ(codes / 255)
    adapted = colour.chromatic_adaptation(XYZ, colour.xy_to_XYZ([0.3127, 0.329]),
                                          colour.xy_to_XYZ([0.4476, 0.4074]), method="Von Kries",
                                          transform="Bradford")
    out = colour.XYZ_to_sRGB(adapted)
    codes_out = np.round(255 * np.clip(out, 0, 1)).astype(np.uint8)
    Image.fromarray(codes_out, "RGB").save(io.BytesIO(), "PNG", compress_level=1)
    del linear
    return time.perf_counter() - start


def in_process(data: bytes) -> dict:
    """The worker's steps timed in this process (warm: tables built, kernels compiled)."""
    import spectrocolor as sc
    from spectrocolor.app import relight_photo as rp
    from spectrocolor.display.render import render
    from spectrocolor.upsampling import relight, rgb_linear_from_image

    light = sc.Spectrum(np.arange(400.0, 701.0, 10.0), a_levels())
    table = rp.photo_table("D65", "1931", 10.0)
    rp.prepare()
    steps = {}
    start = time.perf_counter()
    codes, _ = rp.decode_photo(data)
    steps["decode"] = time.perf_counter() - start
    packed = codes.reshape(-1, 3).astype(np.uint32)
    start = time.perf_counter()
    distinct = np.unique((packed[:, 0] << 16) | (packed[:, 1] << 8) | packed[:, 2])
    steps["distinct colours (np.unique)"] = time.perf_counter() - start
    colours = np.stack([(distinct >> 16) & 255, (distinct >> 8) & 255, distinct & 255], -1).astype(np.uint8)
    linear = rgb_linear_from_image(colours)
    start = time.perf_counter()
    relit = relight(table, linear, light)
    steps["library relight of the distinct colours"] = time.perf_counter() - start
    start = time.perf_counter()
    render(relit.XYZ100, space="sRGB", gamut="clip", bit_depth=8)
    steps["render (gamut clip, encode)"] = time.perf_counter() - start
    start = time.perf_counter()
    out = rp.relight_codes(codes, table, light, "none", "clip")
    steps["relight_codes, all of it"] = time.perf_counter() - start
    start = time.perf_counter()
    rp._png_base64(out["codes"])
    steps["PNG + base64 of the relit picture"] = time.perf_counter() - start
    return steps


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--size", type=int, default=1000, help="photo side, px (default 1000)")
    parser.add_argument("--repeat", type=int, default=5, help="warm requests (default 5)")
    args = parser.parse_args()

    data = photo(args.size)
    body = json.dumps({"image": base64.b64encode(data).decode(), "illuminant": a_levels()}).encode()
    print(f"photo: {args.size} x {args.size} px, JPEG {len(data) / 1e6:.2f} MB, body {len(body) / 1e6:.2f} MB")
    proc = subprocess.Popen([sys.executable, "-m", "spectrocolor", "app", "--port", "0", "--no-browser"],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        url = re.search(r"http://127\.0\.0\.1:\d+/", proc.stdout.readline()).group(0)
        time.sleep(1.0)
        first, answer = post(url, body)
        warm = []
        for _ in range(args.repeat):
            seconds, answer = post(url, body)
            warm.append(seconds)
    finally:
        proc.terminate()
        proc.wait(timeout=20)
    steps = in_process(data)
    limit = min(numpy_limit(data) for _ in range(3))
    cs = min(colour_science(data) for _ in range(3))
    median = float(np.median(warm))
    print(f"distinct colours: {answer['colours']}, pixels {answer['pixels']}, "
          f"shown {answer['width']} x {answer['height']}")
    print(f"POST /api/relight, first (worker start + table build): {first * 1e3:.0f} ms")
    print(f"POST /api/relight, warm (same photo, decoded once): median {median * 1e3:.0f} ms, "
          f"max {max(warm) * 1e3:.0f} ms "
          f"(server's relight_ms {answer['relight_ms']:.0f} ms)")
    for name, seconds in steps.items():
        print(f"  in process: {name}: {seconds * 1e3:.0f} ms")
    print(f"plain NumPy limit (decode, 3x3 von Kries, encode 1 PNG): {limit * 1e3:.0f} ms "
          f"-> ours / limit {median / limit:.2f}x")
    print(f"colour-science von Kries relight (Bradford), decode + encode: {cs * 1e3:.0f} ms "
          f"-> ours / colour-science {median / cs:.2f}x")


if __name__ == "__main__":
    main()
