"""Spectral upsampling: table build, apply speed against a bare NumPy limit, and the comparison
with other upsampling methods. Run by hand:

    .venv/bin/python bench/bench_upsampling.py [--size 1024] [--repeats 5] [--burst 0.2] [--apply-only]
                                                [--compare] [--meng 12]

1. Build: ``upsampling_table`` for sRGB and Rec. 2020 (17 nodes per axis), with and without the
   measured roughness excess; the exact solver's colours/s beside it.
2. Apply to a SIZE x SIZE image of random linear sRGB, streamed in blocks of 262 144 pixels:
   (a) spectra (81 samples, float64) by ``upsample_spectra`` vs the bare gather-and-blend limit
   (the same four-node blend with indices and weights precomputed outside the timing);
   (b) colours under illuminant A (relighting) by ``colours_under`` vs the same bare limit on
   the 3-channel node table; (c) texel coefficients; against colour-science's Mallett (2019) and
   Smits (1999), one colour per call, on 100 colours. All timed alternately in this one run,
   warm, best of N each (the NumPy path's spectra and their NumPy limit on one block), and
   recorded in the results file (bench/results.py).
2b. A Rec. 2020 image (SIZE x SIZE uniform random linear Rec. 2020, 17³ table, 694 nodes moved
   toward grey), exact wherever a reflectance exists (issue 27): spectra with the cells of moved
   nodes settled (``upsample_spectra``; their queries blended by the nodes' actual colours or
   solved by the certified solver), the same without settling (``settle_moved=False``, the
   plain blend: inexact there), relighting under A settled, the NumPy path (one block) and the
   bare NumPy gather-and-blend limit, and colour-science's Mallett (2019) and Smits (1999) on
   100 colours; all timed alternately, with the count of each path and the exactness over the
   image's colours. ``--rec2020-only`` runs this section alone.
3. ``--compare``: ΔE00 under D65 over random colours of the sRGB cube and of Rec. 2020 (wide
   gamut), roughness excess over the exact smoothest reflectance, values < 0 or > 1, and
   speed, for this table, an rgb2spec-style sigmoid-polynomial model (Jakob & Hanika 2019: the
   per-colour fit and a 17³ coefficient table), Smits (1999), and Meng (2015, colour-science;
   ``--meng`` colours only, it takes ~10 s each). Writes docs/images/upsampling_*.png.
"""

from __future__ import annotations

import argparse
import os
import sys
import time
from pathlib import Path

import numpy as np

import spectrocolor as sc
from results import figure, ratio, record
from spectrocolor.upsampling import (
    colours_under,
    lookup,
    texel_coefficients,
    upsample,
    upsample_spectra,
    upsampling_table,
)
from spectrocolor.upsampling.apply import _blend, node_colours
from timing import BURST, add_arguments, alternate_best, best_of, clock_name

DOCS_IMAGES = Path(__file__).resolve().parents[1] / "docs" / "images"
BLOCK = 2**18
COLOUR_SCIENCE_COLOURS = 100  # colour-science converts one colour per call (Smits 1999: ~450/s)
SCRIPT = Path(__file__).name


def build() -> dict:
    print("\n1. Table build (17 nodes per axis = 4913 nodes, 380-780 nm at 5 nm)")
    tables = {}
    for space in ("sRGB", "Rec. 2020"):
        start = time.perf_counter()
        tables[space] = upsampling_table(space, "D65", resolution=17, measure_excess=False)
        quick = time.perf_counter() - start
        start = time.perf_counter()
        tables[space] = upsampling_table(space, "D65", resolution=17)
        full = time.perf_counter() - start
        moved = int(np.count_nonzero(tables[space].node_status))
        print(f"   {space:10s}: {quick:6.2f} s (nodes only), {full:6.2f} s (with 24 576 measured "
              f"excess solves); {moved} nodes moved toward grey")
    table = tables["sRGB"]
    colours = np.random.default_rng(1).random((20000, 3)) @ table.matrix.T
    t = best_of(lambda: sc.smoothest_reflectance(colours), repeats=2)
    print(f"   exact solver (smoothest_reflectance, bounds=unit): {len(colours) / t:10.3g} "
          "colours/s")
    return tables


def _compiled_limit():
    """A compiled bare gather-and-blend (indices and weights precomputed), or None without numba."""
    try:
        import numba
    except ImportError:
        return None

    @numba.njit(parallel=True)
    def gather_blend(values, nodes, weights, out):
        for q in numba.prange(nodes.shape[0]):
            i0, i1, i2, i3 = nodes[q, 0], nodes[q, 1], nodes[q, 2], nodes[q, 3]
            w0, w1, w2, w3 = weights[q, 0], weights[q, 1], weights[q, 2], weights[q, 3]
            for k in range(values.shape[1]):
                out[q, k] = values[i0, k] * w0 + values[i1, k] * w1 + values[i2, k] * w2 \
                    + values[i3, k] * w3

    return gather_blend


def _engine(name: str) -> None:
    """Select the apply path: "numpy" (SPECTROCOLOR_NUMBA=0) or "numba" (the compiled kernel)."""
    os.environ["SPECTROCOLOR_NUMBA"] = "1" if name == "numba" else "0"


def _on(engine: str, function, blocks, *arguments):
    """A function of no arguments that calls ``function(block, *arguments)`` for every block, on ``engine``."""
    def run():
        _engine(engine)
        for block in blocks:
            function(block, *arguments)
    return run


def apply_speed(table, size: int, repeats: int, burst: float = BURST) -> None:
    """Colours/s of the apply functions, the bare limits and colour-science, timed alternately."""
    import colour
    from colour.recovery import RGB_to_sd_Mallett2019, RGB_to_sd_Smits1999

    from spectrocolor.upsampling.compiled import kernels

    pixels = size * size
    compiled = kernels() is not None
    threads = "no numba"
    if compiled:
        import numba

        threads = f"numba {numba.__version__}, {numba.get_num_threads()} threads"
    print(f"\n2. Apply to a {size}x{size} image ({pixels / 1e6:.1f} Mpixel), blocks of {BLOCK}; "
          f"{threads}; OPENBLAS_NUM_THREADS={os.environ.get('OPENBLAS_NUM_THREADS', 'unset')}; "
          f"warm, best of {repeats}, all timed alternately, {clock_name()}")
    rng = np.random.default_rng(2)
    W_A = np.asarray(sc.weights(table.wavelengths_nm, illuminant="A"))
    nodes_A = node_colours(table, W_A)
    K = table.wavelengths_nm.size
    blocks = [rng.random((min(BLOCK, pixels - start), 3)) for start in range(0, pixels, BLOCK)]
    few = blocks[:1]  # the NumPy path's spectra and their NumPy limit: one block is enough for a rate
    _engine("numpy")
    found = [lookup(table, block) for block in blocks]
    spectra = np.empty((BLOCK, K))
    relit = np.empty((BLOCK, 3))
    counts: dict[str, int] = {}
    functions = {}

    def add(name, run, over):
        functions[name] = run
        counts[name] = sum(len(block) for block in over)

    engines = ("numba", "numpy") if compiled else ("numpy",)
    for engine in engines:
        add(f"relight {engine}", _on(engine, lambda b: colours_under(table, b, W_A), blocks), blocks)
        add(f"coefficients {engine}", _on(engine, lambda b: texel_coefficients(table, b), blocks), blocks)
        over = blocks if engine == "numba" else few
        add(f"spectra {engine}", _on(engine, lambda b: upsample_spectra(table, b, "toward-grey", spectra[:len(b)]),
                                     over), over)
    add("relight numpy limit", _on("numpy", lambda f: _blend(nodes_A, f), found), blocks)
    add("spectra numpy limit", _on("numpy", lambda f: _blend(table.flat_reflectance, f, spectra[:len(f.nodes)]),
                                   found[:1]), few)
    limit = _compiled_limit()
    if limit is not None:
        add("relight compiled limit", _on("numba", lambda f: limit(nodes_A, f.nodes, f.weights,
                                                                   relit[:len(f.nodes)]), found), blocks)
        add("spectra compiled limit", _on("numba", lambda f: limit(table.flat_reflectance, f.nodes, f.weights,
                                                                   spectra[:len(f.nodes)]), found), blocks)
    sample = np.random.default_rng(4).random((COLOUR_SCIENCE_COLOURS, 3))
    for name, function in (("Mallett 2019", RGB_to_sd_Mallett2019), ("Smits 1999", RGB_to_sd_Smits1999)):
        functions[name] = lambda function=function: [function(rgb) for rgb in sample]
        counts[name] = len(sample)
    best = alternate_best(functions, repeats=repeats, burst=burst)
    _engine("numba")
    rates = {name: counts[name] / best[name] for name in best}

    def rate(name):
        return f"{rates[name]:10.3g}" if name in rates else "         -"

    print("   colours/s      |      numpy |      numba | NumPy limit | compiled limit | "
          "time: numpy/NumPy limit, numba/compiled limit")
    for what in ("spectra", "relight", "coefficients"):
        ratios = ""
        if f"{what} numba" in rates and f"{what} compiled limit" in rates:
            ratios = (f" | {rates[f'{what} numpy limit'] / rates[f'{what} numpy']:5.2f}x, "
                      f"{rates[f'{what} compiled limit'] / rates[f'{what} numba']:5.2f}x")
        print(f"   {what:14s} | {rate(what + ' numpy')} | {rate(what + ' numba')} | "
              f"{rate(what + ' numpy limit')}  | {rate(what + ' compiled limit')}     {ratios}")
    print("   (spectra: 81 float64 samples per colour; relight: colours under A, 3 channels; "
          "coefficients: 4 node indices + 4 weights)")
    for name in ("Mallett 2019", "Smits 1999"):
        print(f"   colour-science {colour.__version__} {name} (one colour per call, {len(sample)} colours): "
              f"{rates[name]:10.3g} colours/s")
    _record(rates, size, compiled)


def _record(rates: dict[str, float], size: int, compiled: bool) -> None:
    """The README's figures of the apply section, into the results file."""
    engine = "numba" if compiled else "numpy"
    figures = [
        figure("relight_per_s", rates[f"relight {engine}"], "ours", "relit under A {} colours/s"),
        figure("coefficients_per_s", rates[f"coefficients {engine}"], "ours", "texel coefficients {}/s"),
        figure("spectra_per_s", rates[f"spectra {engine}"], "ours", "81-sample spectra {}/s"),
    ]
    if compiled:
        figures += [figure(f"{what}_numpy_per_s", rates[f"{what} numpy"], "ours", f"{text} {{}}/s on the NumPy path")
                    for what, text in (("relight", "relit"), ("coefficients", "coefficients"), ("spectra", "spectra"))]
    figures += [
        ratio("spectra_over_mallett", rates[f"spectra {engine}"] / rates["Mallett 2019"], "colour-science",
              "spectra {}× slower by Mallett 2019"),
        ratio("relight_over_mallett", rates[f"relight {engine}"] / rates["Mallett 2019"], "colour-science",
              "relit colours {}× slower by Mallett 2019 (a spectrum per colour)"),
        ratio("spectra_over_smits", rates[f"spectra {engine}"] / rates["Smits 1999"], "colour-science",
              "spectra {}× slower by Smits 1999"),
        figure("mallett_per_s", rates["Mallett 2019"], "colour-science", "Mallett 2019 {} colours/s"),
        figure("smits_per_s", rates["Smits 1999"], "colour-science", "Smits 1999 {}"),
    ]
    limit = "compiled limit" if compiled else "numpy limit"
    figures += [
        ratio("relight_over_limit", rates[f"relight {limit}"] / rates[f"relight {engine}"], "limit",
              "relit: ours {}× its time"),
        ratio("spectra_over_limit", rates[f"spectra {limit}"] / rates[f"spectra {engine}"], "limit",
              "spectra: ours {}× its time"),
        figure("relight_limit_per_s", rates[f"relight {limit}"], "limit", "{} relit/s"),
        figure("spectra_limit_per_s", rates[f"spectra {limit}"], "limit",
               f"{{}} spectra/s (bare {'compiled' if compiled else 'NumPy'} gather and blend)"),
    ]
    record("upsampling_apply", f"spectral upsampling of a {size}² image through a 17³ sRGB table, "
           f"{'compiled kernel (extra `fast`)' if compiled else 'NumPy path'}", figures, script=SCRIPT)


def rec2020_speed(table, size: int, repeats: int, burst: float = BURST) -> None:
    """Section 2b: a Rec. 2020 image, every colour inside the solid exact; colours/s and ratios."""
    from colour.recovery import RGB_to_sd_Mallett2019, RGB_to_sd_Smits1999

    from spectrocolor.upsampling import PATHS
    from spectrocolor.upsampling.compiled import kernels

    pixels = size * size
    compiled = kernels() is not None
    engine = "numba" if compiled else "numpy"
    print(f"\n2b. A {size}x{size} Rec. 2020 image ({pixels / 1e6:.1f} Mpixel, uniform random linear "
          f"RGB), 17³ table with {int(np.count_nonzero(table.node_status))} moved nodes; blocks of "
          f"{BLOCK}; warm, best of {repeats}, timed alternately, {clock_name()}")
    rng = np.random.default_rng(27)
    blocks = [rng.random((min(BLOCK, pixels - start), 3)) for start in range(0, pixels, BLOCK)]
    few = blocks[:1]
    K = table.wavelengths_nm.size
    spectra = np.empty((BLOCK, K))
    W_A = np.asarray(sc.weights(table.wavelengths_nm, illuminant="A"))
    _engine("numpy")
    found = lookup(table, few[0])
    counts: dict[str, int] = {}
    functions = {}

    def add(name, run, over):
        functions[name] = run
        counts[name] = sum(len(block) for block in over)

    add(f"spectra exact {engine}", _on(engine, lambda b: upsample_spectra(table, b, "toward-grey", spectra[:len(b)]),
                                       blocks), blocks)
    add(f"spectra plain {engine}", _on(engine, lambda b: upsample_spectra(
        table, b, "toward-grey", spectra[:len(b)], settle_moved=False), blocks), blocks)
    add(f"relight exact {engine}", _on(engine, lambda b: colours_under(table, b, W_A), blocks), blocks)
    if compiled:
        add("spectra exact numpy", _on("numpy", lambda b: upsample_spectra(table, b, "toward-grey", spectra[:len(b)]),
                                       few), few)
    add("spectra numpy limit", _on("numpy", lambda f: _blend(table.flat_reflectance, f, spectra[:len(f.nodes)]),
                                   [found]), few)
    sample = np.random.default_rng(4).random((COLOUR_SCIENCE_COLOURS, 3))
    for name, function in (("Mallett 2019", RGB_to_sd_Mallett2019), ("Smits 1999", RGB_to_sd_Smits1999)):
        functions[name] = lambda function=function: [function(rgb) for rgb in sample]
        counts[name] = len(sample)
    best = alternate_best(functions, repeats=repeats, burst=burst)
    _engine("numba")
    rates = {name: counts[name] / best[name] for name in best}
    for name in functions:
        print(f"   {name:22s}: {rates[name]:10.3g} colours/s")
    ours = rates[f"spectra exact {engine}"]
    print(f"   exact spectra: {rates[f'spectra plain {engine}'] / ours:5.2f}x the time of the plain blend, "
          f"{ours / rates['spectra numpy limit']:5.2f}x the bare NumPy gather-and-blend's rate, "
          f"{ours / rates['Mallett 2019']:8.3g}x Mallett 2019's and {ours / rates['Smits 1999']:8.3g}x Smits 1999's")
    # how the image's colours went, and the exactness claim checked on the first block
    u = upsample(table, blocks[0])
    paths = {PATHS[k]: int(np.count_nonzero(u.path == k)) for k in PATHS}
    q = blocks[0] @ table.matrix.T
    error = np.abs(u.reflectance @ table.weights - q).max(axis=-1) / np.abs(q).max(axis=-1)
    print(f"   paths over the first block of {len(blocks[0])} colours: {paths}")
    print(f"   exact: {int(u.exact.sum())} colours, largest relative colour error {error[u.exact].max():.2g}, "
          f"reflectances in [{u.reflectance.min():.3g}, {u.reflectance.max():.3g}]")
    figures = [
        figure("rec2020_exact_spectra_per_s", ours, "ours", "Rec. 2020 image, exact spectra {}/s"),
        figure("rec2020_plain_spectra_per_s", rates[f"spectra plain {engine}"], "ours",
               "Rec. 2020 image, plain blend {}/s"),
        figure("rec2020_exact_relight_per_s", rates[f"relight exact {engine}"], "ours",
               "Rec. 2020 image, exact colours under A {}/s"),
        ratio("rec2020_exact_over_mallett", ours / rates["Mallett 2019"], "colour-science",
              "exact Rec. 2020 spectra {}× slower by Mallett 2019"),
        ratio("rec2020_exact_over_smits", ours / rates["Smits 1999"], "colour-science",
              "exact Rec. 2020 spectra {}× slower by Smits 1999"),
        ratio("rec2020_numpy_limit_over_exact", rates["spectra numpy limit"] / ours, "limit",
              "exact Rec. 2020 spectra: the bare NumPy blend {}× ours"),
    ]
    record("upsampling_rec2020", f"exact spectral upsampling of a {size}² Rec. 2020 image through a 17³ table",
           figures, script=SCRIPT)


def _metrics(name, rho, target_lab, W, white, optimum, seconds, count):
    finite = np.all(np.isfinite(rho), axis=-1)
    lab = sc.lab(np.where(finite[:, None], rho, 0.0) @ W, white)
    de = np.where(finite, sc.delta_e_2000(lab, target_lab), np.nan)
    step = 5.0
    rough = np.sum(np.diff(rho, axis=-1) ** 2, axis=-1) / step
    ok = finite & np.isfinite(optimum)
    excess = rough[ok] - optimum[ok]
    return {
        "method": name, "n": int(finite.sum()), "failed": int((~finite).sum()),
        "de_mean": float(np.nanmean(de)), "de_p99": float(np.nanpercentile(de, 99)),
        "de_max": float(np.nanmax(de)),
        "neg": float(np.mean(np.any(rho[finite] < 0, axis=-1))),
        "over": float(np.mean(np.any(rho[finite] > 1, axis=-1))),
        "excess_median": float(np.median(excess)) if excess.size else np.nan,
        "excess_p95": float(np.percentile(excess, 95)) if excess.size else np.nan,
        "rate": count / seconds,
    }


def compare(tables, meng_count: int) -> None:
    sys.path.insert(0, str(Path(__file__).parent))
    from upsampling_baselines import SigmoidPolynomial, meng, smits

    print("\n3. Comparison under D65 (CIE 1931, 380-780 nm at 5 nm)")
    rows = []
    rng = np.random.default_rng(3)
    for space, count in (("sRGB", 2000), ("Rec. 2020", 2000)):
        table = tables[space]
        W, white, grid = table.weights, table.weights.sum(0), table.wavelengths_nm
        rgb = sc.rgb_space(space).transfer.decode(rng.random((count, 3)))
        XYZ = rgb @ table.matrix.T
        target = sc.lab(XYZ, white)
        start = time.perf_counter()
        exact = sc.smoothest_reflectance(XYZ)
        exact_time = time.perf_counter() - start
        optimum = np.where(exact.feasible & exact.certificate.converged, exact.roughness, np.nan)
        print(f"   {space}: {int(np.isfinite(optimum).sum())} of {count} colours inside the "
              "object-colour solid")
        start = time.perf_counter()
        ours = upsample(table, rgb).reflectance
        rows.append((space, _metrics("this table (17³)", ours, target, W, white, optimum,
                                     time.perf_counter() - start, count)))
        rows.append((space, _metrics("exact solver", exact.spectrum.values, target, W, white,
                                     optimum, exact_time, count)))
        smits(rgb[:2], grid)  # warm-up: the first call imports colour-science for the basis
        start = time.perf_counter()
        rows.append((space, _metrics("Smits 1999", smits(rgb, grid), target, W, white,
                                     optimum, time.perf_counter() - start, count)))
        model = SigmoidPolynomial(W, grid, table.matrix)
        subset = rgb[:300]
        start = time.perf_counter()
        coefficients = model.fit(subset)
        fit_time = time.perf_counter() - start
        rows.append((space, _metrics("sigmoid polynomial, per-colour fit (300)",
                                     model.spectra(coefficients), target[:300], W, white,
                                     optimum[:300], fit_time, 300)))
        cache = Path("/tmp") / f"sigmoid_table_{space.replace(' ', '_')}.npy"
        if cache.exists():
            coefficient_table = np.load(cache)
        else:
            coefficient_table = model.table(17)
            np.save(cache, coefficient_table)
        start = time.perf_counter()
        from_table = model.spectra(model.from_table(coefficient_table, rgb))
        rows.append((space, _metrics("sigmoid polynomial, 17³ coefficient table", from_table,
                                     target, W, white, optimum, time.perf_counter() - start,
                                     count)))
        if meng_count:
            start = time.perf_counter()
            rho = meng(XYZ[:meng_count], grid)
            rows.append((space, _metrics(f"Meng 2015, colour-science ({meng_count})", rho,
                                         target[:meng_count], W, white, optimum[:meng_count],
                                         time.perf_counter() - start, meng_count)))
    print("\n| set | method | colours | ΔE00 mean | ΔE00 99th pct | ΔE00 max | any ρ<0 | any ρ>1 "
          "| roughness excess median / 95th pct (nm⁻¹) | colours/s |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for space, m in rows:
        failed = f" ({m['failed']} failed)" if m["failed"] else ""
        print(f"| {space} | {m['method']} | {m['n']}{failed} | {m['de_mean']:.3g} | "
              f"{m['de_p99']:.3g} | {m['de_max']:.3g} | {100 * m['neg']:.1f} % | "
              f"{100 * m['over']:.1f} % | {m['excess_median']:.2g} / {m['excess_p95']:.2g} | "
              f"{m['rate']:.3g} |")


def _chart(rgb_linear: np.ndarray, patch: int = 48) -> np.ndarray:
    """A 4 x 6 chart of 8-bit sRGB patches from linear RGB (24, 3), clipped to the gamut."""
    codes = sc.render(sc.rgb_space("sRGB").XYZ_from_rgb_linear(rgb_linear), gamut="clip").codes
    chart = codes.reshape(4, 6, 3).astype(np.uint8)
    return np.repeat(np.repeat(chart, patch, axis=0), patch, axis=1)


def pictures() -> None:
    """docs/images/upsampling_relit.png and upsampling_spectra.png (see docs/upsampling.md)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from spectrocolor.io import read_spectra
    from spectrocolor.pictures import save_image
    from spectrocolor.upsampling import relight, rgb_linear_from_image

    data = Path(sc.__file__).parent / "data" / "reflectances_colorchecker_babel.csv"
    checker = read_spectra(data)
    grid = checker.wavelengths_nm
    table = upsampling_table("sRGB", "D65", wavelengths=(grid[0], grid[-1], grid[1] - grid[0]),
                             resolution=17, measure_excess=False)
    truth = np.asarray(checker.values)
    photo = _chart(truth @ table.weights @ np.linalg.inv(table.matrix).T, patch=1)[..., :]
    rgb = rgb_linear_from_image(photo.reshape(24, 3))  # what the camera recorded, 8-bit
    W_A = np.asarray(sc.weights(grid, illuminant="A"))
    display = sc.rgb_space("sRGB")
    panels, report = [], []
    for adaptation in (None, "bradford"):
        relit = relight(table, rgb, "A", adaptation=adaptation)
        seen = table.weights.sum(0) if adaptation is None else W_A.sum(0)
        true_XYZ = sc.adapt(truth @ W_A, seen, display.white_XYZ)
        de = sc.delta_e_2000(sc.lab(relit.XYZ100, display.white_XYZ),
                             sc.lab(true_XYZ, display.white_XYZ))
        report.append((adaptation, de))
        panels.append((_chart(relit.rgb_linear), _chart(display.rgb_linear_from_XYZ(true_XYZ))))
    gap = np.full((4 * 48, 12, 3), 255, np.uint8)
    top = np.concatenate([_chart(rgb), gap, panels[0][0], gap, panels[0][1]], axis=1)
    bottom = np.concatenate([np.full_like(_chart(rgb), 255), gap, panels[1][0], gap,
                             panels[1][1]], axis=1)
    image = np.concatenate([top, np.full((12, top.shape[1], 3), 255, np.uint8), bottom])
    DOCS_IMAGES.mkdir(exist_ok=True)
    save_image(image, DOCS_IMAGES / "upsampling_relit.png")
    for adaptation, de in report:
        print(f"   ColorChecker under A ({adaptation or 'no'} adaptation): ΔE00 table-relit vs "
              f"measured spectra: mean {de.mean():.2f}, max {de.max():.2f} "
              f"(patch {checker.names[int(np.argmax(de))]})")

    sys.path.insert(0, str(Path(__file__).parent))
    from upsampling_baselines import SigmoidPolynomial, smits

    srgb = upsampling_table("sRGB", "D65", resolution=17, measure_excess=False)
    g = srgb.wavelengths_nm
    examples = {"red (0.8, 0.05, 0.05)": [0.8, 0.05, 0.05], "sky (0.2, 0.4, 0.8)": [0.2, 0.4, 0.8],
                "green (0.1, 0.6, 0.1)": [0.1, 0.6, 0.1], "skin (0.6, 0.4, 0.3)": [0.6, 0.4, 0.3]}
    rgb = np.array(list(examples.values()))
    model = SigmoidPolynomial(srgb.weights, g, srgb.matrix)
    curves = {"this table (17³)": upsample(srgb, rgb).reflectance,
              "exact smoothest": sc.smoothest_reflectance(rgb @ srgb.matrix.T).spectrum.values,
              "sigmoid polynomial (fit)": model.spectra(model.fit(rgb)),
              "Smits 1999": smits(rgb, g)}
    fig, axes = plt.subplots(1, 4, figsize=(13, 3.2), sharey=True)
    styles = {"this table (17³)": "-", "exact smoothest": ":", "sigmoid polynomial (fit)": "--",
              "Smits 1999": "-."}
    for i, (ax, title) in enumerate(zip(axes, examples, strict=True)):
        for name, values in curves.items():
            ax.plot(g, values[i], styles[name], label=name, lw=1.6)
        ax.set_title(f"linear sRGB {title.split(' ', 1)[1]}\n{title.split(' ')[0]}", fontsize=9)
        ax.set_xlabel("wavelength (nm)")
        ax.axhline(1.0, color="0.8", lw=0.8)
        ax.axhline(0.0, color="0.8", lw=0.8)
    axes[0].set_ylabel("reflectance")
    handles, labels = axes[0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="lower center", ncol=4, fontsize=8, frameon=False)
    fig.tight_layout(rect=(0, 0.07, 1, 1))
    fig.savefig(DOCS_IMAGES / "upsampling_spectra.png", dpi=110)
    plt.close(fig)
    print(f"   wrote {DOCS_IMAGES / 'upsampling_relit.png'} and upsampling_spectra.png")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--size", type=int, default=1024)
    add_arguments(parser)
    parser.add_argument("--compare", action="store_true")
    parser.add_argument("--meng", type=int, default=0)
    parser.add_argument("--apply-only", action="store_true",
                        help="skip the Rec. 2020 build and the measured excess (section 2 only)")
    parser.add_argument("--rec2020-only", action="store_true",
                        help="only section 2b: a Rec. 2020 image, exact wherever a reflectance exists")
    parser.add_argument("--pictures", action="store_true",
                        help="only write the pictures of docs/upsampling.md")
    args = parser.parse_args()
    if args.pictures:
        pictures()
        return
    if args.rec2020_only:
        rec2020_speed(upsampling_table("Rec. 2020", "D65", resolution=17, measure_excess=False),
                      args.size, args.repeats, args.burst)
        return
    if args.apply_only:
        apply_speed(upsampling_table("sRGB", "D65", resolution=17, measure_excess=False),
                    args.size, args.repeats, args.burst)
        return
    tables = build()
    apply_speed(tables["sRGB"], args.size, args.repeats, args.burst)
    rec2020_speed(tables["Rec. 2020"], args.size, args.repeats, args.burst)
    if args.compare:
        compare(tables, args.meng)


if __name__ == "__main__":
    main()
