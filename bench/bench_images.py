"""Spectral image conversion: throughput, bounded memory, dask scaling. Run by hand:

    .venv/bin/python bench/bench_images.py [--size 2048] [--big-gib 2.0]

1. XYZ of a SIZE x SIZE x 31 float32 cube, pixels/s: ``cube_to_xyz`` (row blocks) vs a bare
   NumPy matmul of the whole cube (the memory-bandwidth limit) vs colour-science's
   ``msds_to_XYZ`` (timed on a 512 x 512 crop: it needs several float64 copies of the cube);
   the three timed alternately, warm, best of N each.
2. A cube 2x larger than the address space the process may use (``RLIMIT_AS`` set in a
   subprocess after the imports) converts to an sRGB PNG; peak RSS is reported.
3. The same conversion on a dask LocalCluster with 1 and with 2 worker processes.
All ratios are measured in this one run; parts 1 and 2 are recorded in the results file
(bench/results.py) for the README's table.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

from results import figure, ratio, record
from timing import add_arguments, alternate_best, best_of, clock_name

WAVELENGTHS = np.arange(400.0, 701.0, 10.0)
CROP = 512
SCRIPT = Path(__file__).name


def _cube(size: int) -> np.ndarray:
    rng = np.random.default_rng(0)
    rows = [rng.random((size, WAVELENGTHS.size), dtype=np.float32) for _ in range(4)]
    return np.stack([rows[i % 4] for i in range(size)])  # cheap to make, same cost to convert


def throughput(size: int, repeats: int, burst: float) -> None:
    import colour

    import spectrocolor as sc
    from spectrocolor.images import cube_to_xyz

    cube = _cube(size)
    pixels = size * size
    W = np.asarray(sc.weights(WAVELENGTHS, observer="1931", illuminant="D65"))
    flat = cube.reshape(-1, WAVELENGTHS.size)
    W32 = W.astype(np.float32)
    crop = cube[:CROP, :CROP]  # colour-science needs several float64 copies of what it converts
    shape = colour.SpectralShape(400, 700, 10)
    cmfs = colour.MSDS_CMFS["CIE 1931 2 Degree Standard Observer"].copy().align(shape)
    illuminant = colour.SDS_ILLUMINANTS["D65"].copy().align(shape)
    best = alternate_best({
        "ours": lambda: cube_to_xyz(cube, WAVELENGTHS, illuminant="D65"),
        "colour-science": lambda: colour.msds_to_XYZ(crop, cmfs, illuminant, method="Integration",
                                                     shape=shape),
        "limit float32": lambda: flat @ W32,
        "limit float64": lambda: flat @ W,  # float32 @ float64 -> float64, one call
    }, repeats=repeats, burst=burst)
    rate_ours = pixels / best["ours"]
    rate_colour = crop.shape[0] * crop.shape[1] / best["colour-science"]
    rate_limit = pixels / best["limit float32"]
    print(f"\n1. XYZ of a {size}x{size}x31 float32 cube ({cube.nbytes / 2**20:.0f} MiB); warm, best of "
          f"{repeats}, timed alternately, {clock_name()}")
    print(f"   bare NumPy matmul, float32 @ float32 : {rate_limit / 1e6:8.1f} Mpixel/s")
    print(f"   bare NumPy matmul, float32 @ float64 : {pixels / best['limit float64'] / 1e6:8.1f} Mpixel/s")
    print(f"   spectrocolor cube_to_xyz (64 MiB rows): {rate_ours / 1e6:8.1f} Mpixel/s "
          f"= {best['ours'] / best['limit float32']:.2f} x the time of the float32 BLAS limit "
          f"(float32 cubes are summed in float32, like sc.tristimulus)")
    print(f"   colour-science msds_to_XYZ ({CROP}^2)   : {rate_colour / 1e6:8.1f} Mpixel/s "
          f"-> spectrocolor is {rate_ours / rate_colour:.1f} x faster")
    record("images_xyz", f"XYZ of a {size} × {size} × 31 float32 cube (colour-science on a {CROP}² crop)", [
        figure("ours_mpixel_s", rate_ours / 1e6, "ours", "{} Mpixel/s"),
        ratio("colour_over_ours", rate_ours / rate_colour, "colour-science", "{}× slower per pixel"),
        figure("colour_mpixel_s", rate_colour / 1e6, "colour-science", "{} Mpixel/s"),
        ratio("ours_over_limit", best["ours"] / best["limit float32"], "limit", "ours {}× its time"),
        figure("limit_mpixel_s", rate_limit / 1e6, "limit", "{} Mpixel/s (float32 BLAS matmul)"),
    ], script=SCRIPT)


_CHILD = r"""
import json, os, resource, sys, time
import numpy as np
from spectrocolor.images import read_cube, cube_to_rgb
from spectrocolor.pictures import write_image
status = dict(line.split(":", 1) for line in open("/proc/self/status") if ":" in line)
baseline = int(status["VmSize"].split()[0]) * 1024
limit = baseline + int(sys.argv[3])
resource.setrlimit(resource.RLIMIT_AS, (limit, limit))
start = time.perf_counter()
cube = read_cube(sys.argv[1])
codes = cube_to_rgb(cube, illuminant="D65", max_block_mib=32)
write_image(sys.argv[2], codes)
seconds = time.perf_counter() - start
status = dict(line.split(":", 1) for line in open("/proc/self/status") if ":" in line)
peak = int(status["VmHWM"].split()[0]) * 1024  # this process image's peak RSS
peak_vm = int(status["VmPeak"].split()[0]) * 1024
print(json.dumps({"limit": limit, "baseline_vm": baseline, "peak_rss": peak, "peak_vm": peak_vm,
                  "seconds": seconds, "shape": list(cube.shape)}))
"""


def _write_envi(folder: Path, lines: int, samples: int) -> Path:
    """A BSQ float32 ENVI cube written band by band (never whole in memory)."""
    raw = folder / "big.img"
    rng = np.random.default_rng(1)
    band = rng.random((lines, samples), dtype=np.float32)
    with open(raw, "wb") as handle:
        for k in range(WAVELENGTHS.size):
            (band * (0.5 + 0.5 * k / WAVELENGTHS.size)).tofile(handle)
    (folder / "big.hdr").write_text(
        f"ENVI\nsamples = {samples}\nlines = {lines}\nbands = {WAVELENGTHS.size}\n"
        "header offset = 0\ndata type = 4\ninterleave = bsq\nbyte order = 0\n"
        "wavelength units = nm\nwavelength = {"
        + ", ".join(f"{w:g}" for w in WAVELENGTHS) + "}\n")
    return folder / "big.hdr"


def bounded_memory(folder: Path, budget_mib: int) -> None:
    env = dict(os.environ, OPENBLAS_NUM_THREADS="1", OMP_NUM_THREADS="1", MALLOC_ARENA_MAX="2")
    probe = subprocess.run(
        [sys.executable, "-c", "import spectrocolor.images, numpy;"
         "print(open('/proc/self/status').read().split('VmSize:')[1].split()[0])"],
        capture_output=True, text=True, env=env, check=True)
    allowed = int(probe.stdout) * 1024 + budget_mib * 2**20
    samples = 2048
    lines = int(np.ceil(2 * allowed / (samples * WAVELENGTHS.size * 4)))
    hdr = _write_envi(folder, lines, samples)
    size = (folder / "big.img").stat().st_size
    result = subprocess.run(
        [sys.executable, "-c", _CHILD, str(hdr), str(folder / "big.png"),
         str(budget_mib * 2**20)], capture_output=True, text=True, env=env)
    print(f"\n2. Bounded memory: {lines}x{samples}x31 float32 ENVI cube of {size / 2**30:.2f} GiB")
    if result.returncode != 0:
        print("   FAILED:", result.stderr.strip().splitlines()[-1])
        return
    facts = json.loads(result.stdout)
    print(f"   address-space limit (RLIMIT_AS) {facts['limit'] / 2**30:.2f} GiB "
          f"(imports {facts['baseline_vm'] / 2**30:.2f} GiB + {budget_mib} MiB); cube = "
          f"{size / facts['limit']:.2f} x the limit")
    print(f"   converted to sRGB PNG in {facts['seconds']:.1f} s "
          f"({lines * samples / facts['seconds'] / 1e6:.1f} Mpixel/s)")
    print(f"   peak RSS (VmHWM) {facts['peak_rss'] / 2**20:.0f} MiB = "
          f"{facts['peak_rss'] / size:.2f} x the cube; peak address space "
          f"{facts['peak_vm'] / 2**20:.0f} MiB")
    record("images_bounded_memory", "a cube 2× larger than the address-space limit → sRGB PNG", [
        figure("peak_rss_mib", facts["peak_rss"] / 2**20, "ours", "peak RSS {} MiB"),
        figure("cube_gib", size / 2**30, "ours", "for a {} GiB cube"),
    ], script=SCRIPT)


def dask_scaling(folder: Path, size: int) -> None:
    import dask
    from distributed import Client, LocalCluster

    from spectrocolor.images import read_cube

    hdr = _write_envi(folder, size, size)
    cube = read_cube(hdr).to_xarray(chunks=(256, 256))
    lazy = cube.spectro.to_rgb(illuminant="D65")
    print(f"\n3. dask: sRGB of a {size}x{size}x31 ENVI cube, 256x256 chunks, process workers")
    times = {}
    for workers in (1, 2):
        with LocalCluster(n_workers=workers, threads_per_worker=1, processes=True,
                          dashboard_address=":0") as cluster, Client(cluster):
            dask.compute(lazy)  # warm the workers
            times[workers] = best_of(lambda: dask.compute(lazy), repeats=2, clock=time.perf_counter)  # work in workers
        print(f"   {workers} worker(s): {times[workers]:.2f} s "
              f"({size * size / times[workers] / 1e6:.1f} Mpixel/s)")
    print(f"   speed-up 2 vs 1 workers: {times[1] / times[2]:.2f} x "
          f"(machine has {os.cpu_count()} cores)")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--size", type=int, default=2048)
    parser.add_argument("--budget-mib", type=int, default=384,
                        help="address space allowed beyond the imports (part 2)")
    parser.add_argument("--dask-size", type=int, default=1024)
    parser.add_argument("--no-dask", action="store_true", help="skip part 3 (not in the README's table)")
    add_arguments(parser)
    args = parser.parse_args()
    throughput(args.size, args.repeats, args.burst)
    with tempfile.TemporaryDirectory() as folder:
        bounded_memory(Path(folder), args.budget_mib)
    if not args.no_dask:
        with tempfile.TemporaryDirectory() as folder:
            dask_scaling(Path(folder), args.dask_size)


if __name__ == "__main__":
    main()
