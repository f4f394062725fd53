"""Integer search for the explorer's presets (``src/spectrocolor/app/presets.py``).

Run by hand: ``.venv/bin/python tools/tune_presets.py FAMILY`` prints the levels found for one
family of presets (``s5-1`` … ``s5-7``, ``s3-2``, ``s3-5``, ``s4-yellow`` …). Every preset is a
vector of 31 integer levels 0-30 (SPECTRA's model). The search is a greedy coordinate descent
from the current preset: it moves one bin, or two neighbouring bins together, by ±1..±3 levels
and keeps a move when the objective falls, until no move helps.

The objectives are the seed's words (seed 002, settings 1-5) measured as the page shows the
colours by default, on sRGB and on SPECTRA's monitor: normalisation A (fixed), E adapted to the
display's white (Bradford), gamut strategy "desaturate". Each wish is a range for the shown
colour's dominant wavelength λd (relative to the display white; negative = complementary),
CIELAB chroma C*ab and lightness L* (relative to the display white), plus "in gamut" where the
seed says the colour can be shown; the objective is the sum of the distances outside the
ranges, with small penalties that keep the curves smooth and (where the seed says so)
monotonic. ``tests/app/test_app_demonstrations.py`` checks the same properties through the app's
own compute path.
"""

from __future__ import annotations

import sys

import numpy as np

import spectrocolor as sc
from spectrocolor.app import compute as C
from spectrocolor.app import presets as P
from spectrocolor.mixing import subtractive_mix

DISPLAYS = ("sRGB", "SPECTRA 7000K")


class View:
    """The page's default display chain for one display and reference illuminant."""

    def __init__(self, display, illuminant=None):
        self.chain = C.pipeline(10.0, "1931", display, "fixed", "bradford", illuminant)
        self.space = self.chain["space"]

    def measure(self, levels):
        """L*, C*ab, signed λd of the shown colour, and whether it is in gamut."""
        XYZ = np.asarray(levels, float) / 30 @ self.chain["W"]
        r = sc.render(XYZ @ self.chain["to_display"].T, self.space, normalise="fixed",
                      gamut="desaturate", scale=self.chain["scale"])
        shown = self.space.XYZ_from_rgb_linear(r.rgb_linear)
        lab = sc.lab(shown, self.space.white_XYZ)
        d = sc.dominant_wavelength(sc.xy(shown), self.space.white_xy)
        lam = float(np.where(d.complementary, -d.wavelength_nm, d.wavelength_nm))
        return float(lab[0]), float(np.hypot(lab[1], lab[2])), lam, bool(r.in_gamut)


def gamut_excess(view, levels):
    """How far the normalised linear RGB lies outside [0, 1] (0 when displayable)."""
    rgb = np.asarray(levels, float) / 30 @ view.chain["W"] @ view.chain["matrix"].T
    rgb = rgb / view.chain["scale"]
    return float(np.clip(-rgb, 0, None).sum() + np.clip(rgb - 1, 0, None).sum())


def outside(x, lo, hi):
    """0 inside [lo, hi], else the distance to the range."""
    if x != x:  # NaN: no dominant wavelength (a neutral)
        return 50.0
    return max(0.0, lo - x, x - hi)


def wish_penalty(view, levels, lam=None, chroma=None, lightness=None, in_gamut=False):
    L, Cab, d, ok = view.measure(levels)
    p = 0.0
    if lam is not None:
        p += outside(d, *lam)
    if chroma is not None:
        p += outside(Cab, *chroma)
    if lightness is not None:
        p += outside(L, *lightness)
    if in_gamut and not ok:
        p += 10.0
    return p


def shape_penalty(x, monotonic=0):
    """Roughness (second differences) and, for monotonic=±1, steps against the direction."""
    x = np.asarray(x, float)
    p = 0.02 * float(np.abs(np.diff(x, 2)).sum())
    if monotonic:
        p += float(np.clip(-monotonic * np.diff(x), 0, None).sum())
    return p


def search(parts, objective, max_rounds=40):
    """Coordinate descent over the concatenated integer vectors ``parts`` (each 31 levels)."""
    x = np.concatenate([np.asarray(p, int) for p in parts])
    n = len(parts)
    split = lambda v: [v[31 * i:31 * (i + 1)] for i in range(n)]  # noqa: E731
    best = objective(*split(x))
    for _ in range(max_rounds):
        improved = False
        for k in range(len(x)):
            for width in (1, 2):
                for step in (1, -1, 2, -2, 3, -3):
                    y = x.copy()
                    idx = [j for j in range(k, k + width) if j // 31 == k // 31]
                    y[idx] = np.clip(y[idx] + step, 0, 30)
                    if np.array_equal(x, y):
                        continue
                    v = objective(*split(y))
                    if v < best - 1e-9:
                        x, best, improved = y, v, True
        if not improved:
            break
    return split(x), best


def prod(a, b):
    return subtractive_mix(a, b, full=30)


FAMILIES = {}


def family(name):
    def register(f):
        FAMILIES[name] = f
        return f
    return register


@family("s5-1")
def straw_light_blue(views):
    def objective(straw, light_blue):
        p = shape_penalty(straw, +1) + shape_penalty(light_blue, -1)
        for v in views:
            p += wish_penalty(v, straw, (572, 590), (8, 30), (60, 100), True)
            p += wish_penalty(v, light_blue, (470, 495), (8, 30), (60, 100), True)
            p += wish_penalty(v, prod(straw, light_blue), (505, 560), (6, 25), None, True)
        return p
    return search([P.STRAW, P.LIGHT_BLUE], objective)


def delta_e(view, a, b):
    """CIEDE2000 between two distributions, CIELAB relative to the reference white (the API's)."""
    W = view.chain["W"]
    white = np.ones(31) @ W
    lab = sc.lab(np.array([a, b], float) / 30 @ W, white)
    return float(sc.delta_e_2000(lab[0], lab[1]))


def fig12_move(left, partial):
    """Seed 002, setting 3, default 2: all of 570 and 580 nm, part of 560 and 590 nm."""
    moved = np.zeros(31)
    moved[[17, 18]] = np.asarray(left)[[17, 18]]
    moved[[16, 19]] = np.minimum(np.asarray(partial)[[16, 19]], np.asarray(left)[[16, 19]])
    return moved


@family("s3-2")
def orange_yellow(views):
    """Setting 3, default 2: moving the yellow band to the dark neutral makes a metameric pair.

    The right is a dark neutral (level 2). The left is the neutral plus a block around 575 nm;
    580 and 570 nm are moved fully, 560 and 590 nm partly (at least 3 levels, not all), as the
    seed describes; the pair left then must match (CIEDE2000) and stay yellow/brown, and the
    left must start orange-yellow.
    """
    right = np.full(31, 2)

    def objective(left, partial):
        moved = fig12_move(left, partial)
        a, b = left - moved, right + moved
        p = shape_penalty(left) + 0.01 * float(np.abs(partial).sum())
        for k in (16, 19):  # partly: some but not all
            p += outside(moved[k], 3, left[k] - 3)
        p += 10 * delta_e(views[0], a, b)
        for v in views:
            p += wish_penalty(v, left, (578, 590), (30, 100), None, True)
            p += wish_penalty(v, a, (570, 592), (20, 100), None, True)
            p += wish_penalty(v, b, (570, 592), (20, 100), None, True)
        return p
    start = np.array([2] * 14 + [5, 10, 22, 27, 27, 22, 10, 5] + [2] * 9)
    partial = np.zeros(31, int)
    partial[[16, 19]] = 6
    return search([start, partial], objective)


def setting4_family(name, lam):
    """Setting 4: a pair metameric under D65, told apart under A and T65, displayable under all
    four illuminants on both displays, with the named hue under D65."""
    def run(views):
        wl = C.grid(10.0)
        ills = {"E": None, "D65": C.resolve("D65", wl), "T65": P.THREE_BAND,
                "A": C.resolve("A", wl)}
        lit = {k: [View(d, ill) for d in DISPLAYS] for k, ill in ills.items()}

        def objective(a, b):
            p = 5 * shape_penalty(a) + 0.2 * shape_penalty(b)  # the left is the smooth one
            p += 10 * max(0.0, delta_e(lit["D65"][0], a, b) - 0.25)
            p += max(0.0, 2.5 - delta_e(lit["A"][0], a, b))
            p += max(0.0, 2.5 - delta_e(lit["T65"][0], a, b))
            for vs in lit.values():
                for v in vs:
                    p += 1000 * (gamut_excess(v, a) + gamut_excess(v, b))
            for x in (a, b):
                for v in lit["D65"]:
                    p += wish_penalty(v, x, lam, (20, 100))
            return p
        return search(list(getattr(P, name)), objective, max_rounds=25)
    return run


FAMILIES["s4-yellow"] = setting4_family("S4_YELLOW", (566, 590))
FAMILIES["s4-green"] = setting4_family("S4_GREEN", (505, 560))
FAMILIES["s4-blue"] = setting4_family("S4_BLUE", (455, 490))


@family("s5-yellow")
def yellow_filters(views):
    """Setting 5, keys 2-4: one yellow filter with turquoise, blue and magenta ones."""
    def objective(y, t, b, m):
        p = shape_penalty(y, +1) + shape_penalty(t) + shape_penalty(b, -1) + shape_penalty(m)
        for v in views:
            p += wish_penalty(v, y, (565, 585), (30, 100), None, True)
            p += wish_penalty(v, t, (485, 500), (20, 100), None, True)
            p += wish_penalty(v, b, (455, 485), (30, 100), None, True)
            p += wish_penalty(v, m, (-560, -500), (40, 100), None, True)
            p += wish_penalty(v, prod(y, t), (515, 555), (30, 100), None, False)
            p += wish_penalty(v, prod(y, b), (510, 555), (20, 100), (0, 45), False)
            p += wish_penalty(v, prod(y, m), (605, 640), (40, 100), None, False)
        return p
    return search([P.YELLOW_FILTER, P.TURQUOISE, P.BLUE_FILTER, P.MAGENTA_FILTER], objective)


@family("s5-2")
def turquoise(views):
    def objective(t):
        p = shape_penalty(t)
        for v in views:
            p += wish_penalty(v, t, (485, 500), (15, 60), None, True)
            p += wish_penalty(v, prod(P.YELLOW, t), (510, 555), (25, 100), None, True)
        return p
    return search([P.TURQUOISE], objective)


@family("s5-3")
def blue_filter(views):
    def objective(b):
        p = shape_penalty(b)
        for v in views:
            p += wish_penalty(v, b, (455, 485), (30, 100), None, True)
            p += wish_penalty(v, prod(P.YELLOW, b), (505, 555), (15, 100), (0, 45), True)
        return p
    return search([P.BLUE_FILTER], objective)


@family("s5-4")
def magenta_filter(views):
    def objective(m):
        p = shape_penalty(m)
        for v in views:
            p += wish_penalty(v, m, (-565, -495), (30, 100), None, True)
            p += wish_penalty(v, prod(P.YELLOW, m), (605, 640), (35, 100), None, False)
        return p
    return search([P.MAGENTA_FILTER], objective)


@family("s5-5")
def green_magenta(views):
    def objective(g, m):
        p = shape_penalty(g) + shape_penalty(m)
        for v in views:
            p += wish_penalty(v, g, (510, 560), (25, 100), None, True)
            p += wish_penalty(v, m, (-565, -495), (25, 100), None, True)
            p += wish_penalty(v, prod(g, m), None, (0, 3), None, True)
        return p
    return search([P.GREEN, P.MAGENTA], objective)


@family("s5-7")
def moss_green(views):
    def objective(m):
        p = shape_penalty(m)
        for v in views:
            p += wish_penalty(v, m, (520, 570), (10, 100), None, True)
            p += wish_penalty(v, prod(m, m), (605, 700), (10, 100), (0, 35), False)
        return p
    return search([P.MOSS_GREEN], objective)


if __name__ == "__main__":
    found, value = FAMILIES[sys.argv[1]]([View(d) for d in DISPLAYS])
    print(f"objective {value:.4f}")
    for levels in found:
        print(np.asarray(levels).tolist())
