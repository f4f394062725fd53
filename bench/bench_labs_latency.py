"""Latency of the explorer's labs, measured the way a user meets it: the real server, Debian's Chromium.

* Thin-film lab: thickness-slider input → repaint (patch, numbers, spectrum, strip, diagram and the
  draining film, all table lookups), per event: the handler's work with style and layout forced,
  and until the next animation frame. Target p95 < 16 ms.
* Thin-film lab: the draining-film animation at 1280×720 ("Full window"), frames per second over
  3 s of playing. Target ≥ 30 frames/s.
* Request round trips (Python client on loopback, server's own work included): the smoothest-
  reflectance lab's colour at 5 nm (target < 50 ms), the light-source lab's metrics of an LED
  mixture, the solid lab's section at a new Y.

Prints median, p95 and max per measurement. Timings vary with the machine's load; this script
never asserts them.

Run: .venv/bin/python bench/bench_labs_latency.py [--edits N]
"""

from __future__ import annotations

import argparse
import json
import re
import subprocess
import sys
import time
import urllib.request
from pathlib import Path

import numpy as np

ARGS = ["--headless", "--no-sandbox", "--disable-gpu", "--no-first-run", "--disable-background-networking"]

SLIDER = """async (n) => {
  const slider = document.querySelector('#thickness');
  const work = [], frame = [];
  for (let i = 0; i < n; i++) {
    const t0 = performance.now();
    slider.value = String(100 + (i * 7) % 1300);
    slider.dispatchEvent(new Event('input', {bubbles: true}));
    void document.body.offsetHeight;
    work.push(performance.now() - t0);
    await new Promise((res) => requestAnimationFrame(() => res()));
    frame.push(performance.now() - t0);
  }
  return [work, frame];
}"""

FPS = """async (seconds) => {
  document.querySelector('#full').click();
  document.querySelector('#play').click();
  let frames = 0;
  const start = performance.now();
  await new Promise((res) => {
    const tick = () => {
      frames++;
      if (performance.now() - start < seconds * 1000) requestAnimationFrame(tick); else res();
    };
    requestAnimationFrame(tick);
  });
  const canvas = document.querySelector('#drain');
  return [frames / ((performance.now() - start) / 1000), canvas.width, canvas.height];
}"""


def start_server() -> tuple[subprocess.Popen, str]:
    script = Path(sys.executable).with_name("spectrocolor")
    proc = subprocess.Popen([str(script), "app", "--port", "0", "--no-browser"], stdout=subprocess.PIPE, text=True)
    url = re.search(r"(http://127\.0\.0\.1:\d+/)", proc.stdout.readline()).group(1)
    for _ in range(200):
        try:
            urllib.request.urlopen(url + "api/options", timeout=2)  # noqa: S310 - loopback
            return proc, url
        except OSError:
            time.sleep(0.05)
    raise RuntimeError("the app did not start")


def post(url: str, body: dict) -> float:
    request = urllib.request.Request(url, data=json.dumps(body).encode(), headers={"Content-Type": "application/json"})
    start = time.perf_counter()
    with urllib.request.urlopen(request, timeout=60) as response:  # noqa: S310 - loopback
        response.read()
    return (time.perf_counter() - start) * 1000.0


def row(name: str, values_ms, target: str) -> None:
    v = np.asarray(values_ms, dtype=float)
    print(f"{name:<58} {np.median(v):8.2f} {np.percentile(v, 95):8.2f} {v.max():8.2f}   {target}")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--edits", type=int, default=200)
    args = parser.parse_args()
    from playwright.sync_api import sync_playwright

    proc, url = start_server()
    rng = np.random.default_rng(1)
    try:
        print(f"{'measurement':<58} {'median':>8} {'p95':>8} {'max':>8}   (ms)")
        with sync_playwright() as p:
            browser = p.chromium.launch(executable_path="/usr/bin/chromium", args=ARGS)
            page = browser.new_page(viewport={"width": 1280, "height": 720})
            page.goto(url + "labs/thinfilm")
            page.wait_for_selector("body[data-ready=true]")
            work, frame = page.evaluate(SLIDER, args.edits)
            row("thin film: thickness input -> repainted (handler+layout)", work, "p95 < 16 ms")
            row("thin film: thickness input -> next animation frame", frame, "")
            fps, width, height = page.evaluate(FPS, 3)
            print(f"thin film: draining film animation at {width}x{height}: {fps:.1f} frames/s (target >= 30)")
            browser.close()
        xyY = np.column_stack([rng.uniform(0.28, 0.45, 40), rng.uniform(0.3, 0.4, 40), rng.uniform(5, 40, 40)])
        colours = [{"x": float(x), "y": float(y), "Y": float(Y), "step_nm": "5"} for x, y, Y in xyY]
        reflectance = [post(url + "api/lab/reflectance", colour) for colour in colours]
        row("reflectance lab: one colour at 5 nm (3 solutions, limits)", reflectance[1:], "< 50 ms")
        light = [post(url + "api/lab/light", {"source": {"kind": "leds", "peaks_nm": [450, float(g), 620],
                                                          "widths_nm": [20, 60, 20], "powers": [1.0, 0.7, 0.8]}})
                 for g in rng.uniform(500, 580, 40)]
        row("light lab: an LED mixture (CCT, Ra, Rf/Rg, LER, DER, samples)", light[1:], "")
        section = [post(url + "api/lab/solid/section", {"Y": float(Y)}) for Y in rng.uniform(5, 95, 20)]
        row("solid lab: a section at a new Y (MacAdam limit, 180 hues)", section, "")
    finally:
        proc.terminate()
        proc.wait(10)


if __name__ == "__main__":
    main()
