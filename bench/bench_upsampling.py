"""Spectral upsampling: table build, apply speed against a bare NumPy limit, and the comparison
with other upsampling methods. Run by hand:

    .venv/bin/python bench/bench_upsampling.py [--size 4096] [--compare] [--meng 12]

1. Build: ``upsampling_table`` for sRGB and Rec. 2020 (17 nodes per axis), with and without the
   measured roughness excess; the exact solver's colours/s beside it.
2. Apply to a SIZE x SIZE image of random linear sRGB, streamed in blocks of 65 536 pixels:
   (a) spectra (81 samples, float64) by ``upsample_spectra`` vs the bare gather-and-blend limit
   (the same four-node blend with indices and weights precomputed outside the timing);
   (b) colours under illuminant A (relighting) by ``colours_under`` vs the same bare limit on
   the 3-channel node table. Ratios are measured in this one run.
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
from spectrocolor.upsampling import (
    colours_under,
    lookup,
    texel_coefficients,
    upsample,
    upsample_spectra,
    upsampling_table,
)
from spectrocolor.upsampling.apply import _blend, node_colours
from timing import best_of

DOCS_IMAGES = Path(__file__).resolve().parents[1] / "docs" / "images"
BLOCK = 2**18


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


def apply_speed(table, size: int) -> None:
    from spectrocolor.upsampling.compiled import kernels

    pixels = size * size
    compiled = kernels() is not None
    threads = "no numba"
    if compiled:
        import numba

        threads = f"numba {numba.__version__}, {numba.get_num_threads()} threads"
    print(f"\n2. Apply to a {size}x{size} image ({pixels / 1e6:.1f} Mpixel), blocks of {BLOCK}; "
          f"{threads}; OPENBLAS_NUM_THREADS={os.environ.get('OPENBLAS_NUM_THREADS', 'unset')}")
    rng = np.random.default_rng(2)
    W_A = np.asarray(sc.weights(table.wavelengths_nm, illuminant="A"))
    nodes_A = node_colours(table, W_A)
    K = table.wavelengths_nm.size
    spectra = np.empty((BLOCK, K))
    relit = np.empty((BLOCK, 3))
    limit = _compiled_limit()
    engines = ("numpy", "numba") if compiled else ("numpy",)
    if limit is not None:  # compile outside the timing
        found = lookup(table, rng.random((8, 3)))
        limit(nodes_A, found.nodes, found.weights, relit[:8])
        for engine in engines:
            _engine(engine)
            upsample_spectra(table, rng.random((8, 3)))
            colours_under(table, rng.random((8, 3)), W_A)
            texel_coefficients(table, rng.random((8, 3)))
    timings: dict[str, float] = {}

    def timed(name, function, *arguments):
        start = time.perf_counter()
        function(*arguments)
        timings[name] = timings.get(name, 0.0) + time.perf_counter() - start

    done = 0
    while done < pixels:
        n = min(BLOCK, pixels - done)
        block = rng.random((n, 3))
        _engine("numpy")
        found = lookup(table, block)
        out, out3 = spectra[:n], relit[:n]
        for engine in engines:
            _engine(engine)
            timed(f"spectra {engine}", upsample_spectra, table, block, "toward-grey", out)
            timed(f"relight {engine}", colours_under, table, block, W_A)
            timed(f"coefficients {engine}", texel_coefficients, table, block)
        timed("spectra numpy limit", _blend, table.flat_reflectance, found, out)
        timed("relight numpy limit", _blend, nodes_A, found)
        if limit is not None:
            timed("spectra compiled limit", limit, table.flat_reflectance, found.nodes,
                  found.weights, out)
            timed("relight compiled limit", limit, nodes_A, found.nodes, found.weights, out3)
        done += n
    _engine("numba")

    def rate(name):
        return f"{pixels / timings[name]:10.3g}" if name in timings else "         -"

    print("   colours/s      |      numpy |      numba | NumPy limit | compiled limit | "
          "time: numpy/NumPy limit, numba/compiled limit")
    for what in ("spectra", "relight", "coefficients"):
        ratios = ""
        if f"{what} numba" in timings and f"{what} numpy limit" in timings:
            ratios = (f" | {timings[f'{what} numpy'] / timings[f'{what} numpy limit']:5.2f}x, "
                      f"{timings[f'{what} numba'] / timings[f'{what} compiled limit']:5.2f}x")
        print(f"   {what:14s} | {rate(what + ' numpy')} | {rate(what + ' numba')} | "
              f"{rate(what + ' numpy limit')}  | {rate(what + ' compiled limit')}     {ratios}")
    print("   (spectra: 81 float64 samples per colour; relight: colours under A, 3 channels; "
          "coefficients: 4 node indices + 4 weights)")
    colour_science_rates()


def colour_science_rates(count: int = 400) -> None:
    """colour-science's RGB -> reflectance functions (one colour per call) on random sRGB."""
    import colour
    from colour.recovery import RGB_to_sd_Mallett2019, RGB_to_sd_Smits1999

    rgb = np.random.default_rng(4).random((count, 3))
    for name, function in (("Mallett 2019", RGB_to_sd_Mallett2019),
                           ("Smits 1999", RGB_to_sd_Smits1999)):
        function(rgb[0])  # warm-up
        start = time.perf_counter()
        for colour_rgb in rgb:
            function(colour_rgb)
        print(f"   colour-science {colour.__version__} {name} (per colour, {count} colours): "
              f"{count / (time.perf_counter() - start):10.3g} colours/s")


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
    parser.add_argument("--size", type=int, default=4096)
    parser.add_argument("--compare", action="store_true")
    parser.add_argument("--meng", type=int, default=0)
    parser.add_argument("--apply-only", action="store_true",
                        help="skip the Rec. 2020 build and the measured excess (section 2 only)")
    parser.add_argument("--pictures", action="store_true",
                        help="only write the pictures of docs/upsampling.md")
    args = parser.parse_args()
    if args.pictures:
        pictures()
        return
    if args.apply_only:
        apply_speed(upsampling_table("sRGB", "D65", resolution=17, measure_excess=False),
                    args.size)
        return
    tables = build()
    apply_speed(tables["sRGB"], args.size)
    if args.compare:
        compare(tables, args.meng)


if __name__ == "__main__":
    main()
