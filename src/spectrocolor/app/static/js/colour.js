// The local fast path: the same arithmetic as the library's /api/evaluate, applied to the weights
// and display matrix that /api/model serves, so an edit repaints in the frame it happens in.
// tests/test_app_fastpath_browser.py compares every number here with the library (1e-9) for every
// display, gamut strategy, observer, bin width and normalisation the page offers, in every setting.

import {FULL} from "./state.js";

const CHANNELS = ["R", "G", "B"];

function rint(x) {  // NumPy's rint: round half to even
  const r = Math.round(x);
  return (Math.abs(x % 1) === 0.5) ? 2 * Math.round(x / 2) : r;
}

/** Linear 0–1 → encoded 0–1 with the display's transfer function (as the library's). */
export function encode(v, t) {
  if (t.kind === "srgb") return v <= t.threshold ? 12.92 * v : 1.055 * Math.pow(v, 1 / 2.4) - 0.055;
  if (t.kind === "power") return Math.pow(v, 1 / t.gamma);
  const L = t.levels;  // SPECTRA's excitation table: nearest level, ties to the lower (digit())
  let hi = 1;
  while (hi < L.length - 1 && L[hi] < v) hi++;
  const idx = (L[hi] - v) < (v - L[hi - 1]) ? hi : hi - 1;
  return idx / (L.length - 1);
}

/** Weights per level (K × 3) for reflectances under an illuminant given as levels 0–30:
 * the library's sc.weights(wl, observer, Spectrum(illuminant)), perfect white Y = 100,
 * derived from the equal-energy weights the model serves. */
function weightsUnder(illuminant, model) {
  const WE = model.weights;
  let yIll = 0;
  for (let k = 0; k < WE.length; k++) yIll += illuminant[k] * WE[k][1];
  const f = 100 / (yIll * FULL);
  return WE.map((w, k) => [illuminant[k] * w[0] * f, illuminant[k] * w[1] * f, illuminant[k] * w[2] * f]);
}

/** SPECTRA's alternative A divisor for weights per level: the largest channel any 0–30
 * distribution can drive (the library's max_object_rgb(...).max()). */
function fixedScale(W, M) {
  const top = [0, 0, 0];
  for (const w of W) {
    for (let c = 0; c < 3; c++) {
      const v = (M[c][0] * w[0] + M[c][1] * w[1] + M[c][2] * w[2]) * FULL;
      if (v > 0) top[c] += v;
    }
  }
  return Math.max(...top);
}

/** Weights per level and the normalisation divisor for one setting: under E (settings 1–3, 5)
 * or under setting 4's illuminant (levels), or null when the illuminant is dark everywhere. */
export function localWeights(model, normalise, illuminant) {
  if (!illuminant) return {W: model.weights, scale: model.fixed_scale};
  if (!illuminant.some((v) => v > 0)) return null;  // nothing lit: the server says why
  const W = weightsUnder(illuminant, model);
  // exact A depends on the weights (the brightest object colour under this illuminant);
  // SPECTRA's own A (from the display's matrix) and B do not
  return {W, scale: normalise === "fixed" ? fixedScale(W, model.matrix_from_XYZ) : model.fixed_scale};
}

const inside = (rgb) => rgb.every((c) => c >= 0 && c <= 1);
const clip01 = (c) => Math.min(1, Math.max(0, c));

/** The library's gamut strategies (display/gamut.py) on one snapped linear RGB triple. */
const STRATEGIES = {
  "flag": (rgb, ok) => ok ? rgb : [0, 0, 0],
  "clip": (rgb) => rgb.map(clip01),
  "preserve-luminance": (rgb, ok, yc) => {
    if (inside(rgb)) return rgb;
    const contrib = rgb.map((c, i) => c * yc[i]);
    const Y = contrib[0] + contrib[1] + contrib[2];
    const pos = contrib.reduce((s, v, i) => s + (rgb[i] > 0 ? v : 0), 0);
    const factor = (Y > 0 && pos > 0) ? Y / pos : 0;
    return rgb.map((c) => clip01(c > 0 ? c * factor : 0));
  },
  "desaturate": (rgb, ok, yc) => {
    if (inside(rgb)) return rgb;
    const g = (rgb[0] * yc[0] + rgb[1] * yc[1] + rgb[2] * yc[2]) / (yc[0] + yc[1] + yc[2]);
    let t = 0;
    for (const c of rgb) {
      if (c < 0) t = Math.max(t, -c / (g - c));
      if (c > 1) t = Math.max(t, (c - 1) / (c - g));
    }
    t = clip01(t);
    if (g <= 0) return [0, 0, 0];
    if (g >= 1) return [1, 1, 1];
    return rgb.map((c) => clip01((1 - t) * c + t * g));
  },
};

/** Whether a gamut strategy has a local fast path here; one registered only in the library is
 * drawn from the server's answer alone (a moment later, never wrong). */
export const hasFastPath = (gamut) => Object.hasOwn(STRATEGIES, gamut);

/**
 * One distribution's colour as /api/evaluate gives it (without λd and purity, which only the
 * server computes).
 * @param levels  K levels 0–30
 * @param model   /api/model's answer (matrix, transfer, tolerance, bit depth)
 * @param opts    {W: weights per level, scale: fixed divisor, normalise, gamut}
 */
export function localColour(levels, model, opts) {
  const {W, normalise, gamut} = opts;
  const M = model.matrix_from_XYZ, tol = model.tolerance;
  let X = 0, Y = 0, Z = 0;
  for (let k = 0; k < levels.length; k++) {
    const v = levels[k], w = W[k];
    X += v * w[0]; Y += v * w[1]; Z += v * w[2];
  }
  const sum = X + Y + Z;
  let rgb = M.map((row) => row[0] * X + row[1] * Y + row[2] * Z);
  let scale = opts.scale;
  if (normalise === "per-colour") { const top = Math.max(...rgb); scale = top > 0 ? top : 1; }
  rgb = rgb.map((c) => c / scale);
  const unmapped = rgb.slice();
  const negative = rgb.map((c) => c < -tol), over = rgb.map((c) => c > 1 + tol);
  const inGamut = !negative.some(Boolean) && !over.some(Boolean);
  const snapped = rgb.map((c) => (c < 0 && c >= -tol) ? 0 : (c > 1 && c <= 1 + tol) ? 1 : c);
  if (!STRATEGIES[gamut]) throw new Error(`gamut strategy ${gamut} has no local fast path`);
  const lin = STRATEGIES[gamut](snapped, inGamut, model.luminance_row);
  const enc = lin.map((c) => encode(c, model.transfer));
  const codes = model.transfer.kind === "levels" ? enc.map((e) => Math.round(e * (model.transfer.levels.length - 1)))
    : enc.map((e) => rint(e * (2 ** model.bit_depth - 1)));
  return {XYZ: [X, Y, Z], xy: sum > 0 ? [X / sum, Y / sum] : [null, null], rgb_unmapped: unmapped,
    rgb_linear: lin, rgb_encoded: enc, codes, in_gamut: inGamut, scale,
    negative: CHANNELS.filter((c, i) => negative[i]), over: CHANNELS.filter((c, i) => over[i])};
}

/** SPECTRA's step 4: the light the display emits for these codes, in levels (0–30 scale of the
 * page's distributions): C(λ) = scale · Σ γ(code)·primary(λ), as /api/evaluate's emitted_levels. */
export function emitted(colour, model) {
  const gamma = model.excitation.emission, P = model.emission.levels_per_drive;
  const drive = colour.codes.map((c) => gamma[c]);
  return P[0].map((_, k) => colour.scale * (drive[0] * P[0][k] + drive[1] * P[1][k] + drive[2] * P[2][k]));
}

/** Codes as a hex colour (#rrggbb on 8-bit displays; 6-bit codes are scaled to 0–255 first). */
export function hexOf(codes, model) {
  const top = model.transfer.kind === "levels" ? model.transfer.levels.length - 1 : 2 ** model.bit_depth - 1;
  return "#" + codes.map((c) => Math.round(c * 255 / top).toString(16).padStart(2, "0")).join("");
}

/** CIE 1976 L*a*b* relative to a white (the library's sc.lab: exact constants, δ = 6/29). */
export function lab(XYZ, white) {
  const d = 6 / 29;
  const f = XYZ.map((v, i) => {
    const r = v / white[i];
    return r > d ** 3 ? Math.cbrt(r) : r / (3 * d * d) + 4 / 29;
  });
  return [116 * f[1] - 16, 500 * (f[0] - f[1]), 200 * (f[1] - f[2])];
}

/** The white of a set of weights per level: XYZ of the full spectrum (all bins at 30). */
export function whiteOf(W) {
  const w = [0, 0, 0];
  for (const r of W) for (let c = 0; c < 3; c++) w[c] += FULL * r[c];
  return w;
}
