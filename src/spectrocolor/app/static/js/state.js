// The page's state, its undo/redo history per setting, and its encoding in the URL (a link
// reproduces what is on screen) and in localStorage (a reload restores every setting).

export const FULL = 30;  // SPECTRA's top level: the full spectrum / 100 % reflectance
export const SETTING_NAMES = {1: "Spectral distribution and colour", 2: "Matching two distributions",
  3: "Complementary distributions", 4: "Samples under illuminants", 5: "Subtractive mixing"};
export const EDITORS = {1: ["distribution"], 2: ["left", "right"], 3: ["left", "right"],
  4: ["illuminant", "sample 1", "sample 2"], 5: ["filter 1", "filter 2"]};
const SETTINGS = [1, 2, 3, 4, 5];
const perSetting = (f) => Object.fromEntries(SETTINGS.map((n) => [n, f(n)]));

export const S = {
  setting: 1, step: 10, observer: "1931", display: "sRGB", gamut: "flag", normalise: "fixed",
  adaptation: null, filledLocus: false,
  mode5: "series",  // setting 5: "series" (filters in series, subtractive) or "additive" (two spotlights)
  presets: null, model: null, wl: [], options: null,
  dists: {}, names: {}, edited: {}, cursor: {}, active: perSetting(() => 0),
  undo: perSetting(() => []), redo: perSetting(() => []),
  sunset: -1, level: {left: -1, right: -1},
  editing: null,  // the editor a drag is changing (only it, and what follows it, is redrawn)
  server: null, local: null, inflight: false, dirty: false, settled: false, stale: false, seq: 0,
  afterEvaluate: null,  // once, with the library's answer for the state a demonstration made
};

// ---------------------------------------------------------------- undo / redo
const UNDO_DEPTH = 200;
const snapshot = (n) => ({dists: S.dists[n].map((d) => d.slice()), names: S.names[n].slice(),
  edited: S.edited[n].slice(), mode5: n === 5 ? S.mode5 : undefined});
function restore(n, snap) {
  S.dists[n] = snap.dists; S.names[n] = snap.names; S.edited[n] = snap.edited;
  if (n === 5 && snap.mode5) S.mode5 = snap.mode5;  // setting 5's mode switch is one undo step too
}

/** Call before an action changes setting n's distributions: it becomes one undo step. */
export function remember(n = S.setting) {
  const stack = S.undo[n];
  stack.push(snapshot(n));
  if (stack.length > UNDO_DEPTH) stack.shift();
  S.redo[n] = [];
}
export function undo(n = S.setting) {
  if (!S.undo[n].length) return false;
  S.redo[n].push(snapshot(n)); restore(n, S.undo[n].pop()); return true;
}
export function redo(n = S.setting) {
  if (!S.redo[n].length) return false;
  S.undo[n].push(snapshot(n)); restore(n, S.redo[n].pop()); return true;
}

// ---------------------------------------------------------------- levels and grids
export const quantise = (v, step) => step === 10 ? Math.round(v) : Math.round(v * 10) / 10;

/** Linear interpolation of levels from one 400–700 nm grid to another, quantised to the new
 * grid's level step (whole levels at 10 nm, tenths on the fine grids). */
export function resample(levels, fromWl, toWl, step) {
  return toWl.map((w) => {
    let j = 0;
    while (j < fromWl.length - 2 && fromWl[j + 1] < w) j++;
    const t = (w - fromWl[j]) / (fromWl[j + 1] - fromWl[j]);
    const v = levels[j] + (levels[j + 1] - levels[j]) * Math.min(1, Math.max(0, t));
    return Math.min(FULL, Math.max(0, quantise(v, step)));
  });
}

/** Every setting's distributions (and their undo history) moved onto a new grid. Setting 3
 * keeps its conserved total: the right side is what the total leaves of the left. */
export function resampleAll(fromWl, toWl, step) {
  const move = (n, dists) => {
    if (n !== 3) return dists.map((d) => resample(d, fromWl, toWl, step));
    const total = resample(dists[0].map((v, k) => v + dists[1][k]), fromWl, toWl, step);
    const left = resample(dists[0], fromWl, toWl, step).map((v, k) => Math.min(v, total[k]));
    return [left, left.map((v, k) => quantise(total[k] - v, step))];
  };
  for (const n of SETTINGS) {
    S.dists[n] = move(n, S.dists[n]);
    for (const stack of [S.undo[n], S.redo[n]]) stack.forEach((snap) => { snap.dists = move(n, snap.dists); });
  }
}

// ---------------------------------------------------------------- the URL
// ?s=setting&b=step&o=observer&d=display&g=gamut&n=normalisation&a=adaptation&l0=…&t0=name&e=edited flags
// &m=add: setting 5 as two spotlights (additive mixing); absent: filters in series
// Levels: "i" + one base-36 digit per bin (whole levels), "t" + two digits per bin (tenths),
// or "f" + comma-separated numbers (anything else, e.g. a CIE illuminant scaled to 30).
const DIGITS = "0123456789abcdefghijklmnopqrstuvwxyz";

export function encodeLevels(levels) {
  if (levels.every(Number.isInteger)) return "i" + levels.map((v) => DIGITS[v]).join("");
  const tenths = levels.map((v) => Math.round(v * 10));
  if (tenths.every((n, k) => Math.abs(n / 10 - levels[k]) < 1e-12)) {
    return "t" + tenths.map((n) => DIGITS[Math.floor(n / 36)] + DIGITS[n % 36]).join("");
  }
  return "f" + levels.map((v) => String(v)).join(",");
}

export function decodeLevels(text, bins) {
  const kind = text[0], body = text.slice(1);
  let out;
  if (kind === "i") out = [...body].map((c) => DIGITS.indexOf(c));
  else if (kind === "t") out = Array.from({length: body.length / 2}, (_, k) => (DIGITS.indexOf(body[2 * k]) * 36 + DIGITS.indexOf(body[2 * k + 1])) / 10);
  else if (kind === "f") out = body.split(",").map(Number);
  else return null;
  if (out.length !== bins || !out.every((v) => Number.isFinite(v) && v >= 0 && v <= FULL)) return null;
  return out;
}

export function stateURL() {
  const q = new URLSearchParams({s: S.setting, b: S.step, o: S.observer, d: S.display, g: S.gamut,
    n: S.normalise});
  if (S.adaptation) q.set("a", S.adaptation);
  if (S.setting === 5 && S.mode5 === "additive") q.set("m", "add");
  S.dists[S.setting].forEach((d, i) => {
    q.set(`l${i}`, encodeLevels(d));
    q.set(`t${i}`, S.names[S.setting][i] || "");
  });
  q.set("e", S.edited[S.setting].map((e) => (e ? "1" : "0")).join(""));
  return `${location.pathname}?${q}`;
}

/** The page options a URL asks for (values are checked against the server's lists by the caller). */
export function readURLOptions(search) {
  const q = new URLSearchParams(search);
  const setting = Number(q.get("s"));
  return {
    setting: SETTINGS.includes(setting) ? setting : null,
    step: q.has("b") ? Number(q.get("b")) : null,
    observer: q.get("o"), display: q.get("d"), gamut: q.get("g"), adaptation: q.get("a"),
    normalise: q.get("n"), mode5: q.get("m") === "add" ? "additive" : "series",
  };
}

/** Setting n's distributions from a URL, or null when the URL holds none that fit the grid. */
export function readURLDistributions(search, n, bins) {
  const q = new URLSearchParams(search);
  const count = EDITORS[n].length;
  const dists = [], names = [];
  for (let i = 0; i < count; i++) {
    const d = q.has(`l${i}`) ? decodeLevels(q.get(`l${i}`), bins) : null;
    if (!d) return null;
    dists.push(d); names.push((q.get(`t${i}`) || "").slice(0, 80));
  }
  const e = q.get("e") || "";
  return {dists, names, edited: names.map((_, i) => e[i] === "1")};
}

// ---------------------------------------------------------------- localStorage (reload)
const WORK_KEY = "spectrocolor:work";
export function persist() {
  try {
    localStorage.setItem(WORK_KEY, JSON.stringify({step: S.step, dists: S.dists, names: S.names, edited: S.edited, mode5: S.mode5}));
  } catch { /* storage full or disabled: the URL still holds the current setting */ }
}
/** The 400–700 nm grid of a bin width (nm). */
export const gridOf = (step) => Array.from({length: Math.round(300 / step) + 1}, (_, k) => 400 + k * step);

/** Restore the work saved by an earlier visit (moved onto the grid of `step` if it was saved on
 * another); false when there is none. */
export function readPersisted(step) {
  try {
    const w = JSON.parse(localStorage.getItem(WORK_KEY) || "null");
    if (!w || ![10, 5, 2, 1].includes(w.step)) return false;
    const bins = gridOf(w.step).length;
    const ok = SETTINGS.every((n) => Array.isArray(w.dists[n]) && w.dists[n].length === EDITORS[n].length
      && Array.isArray(w.names[n]) && Array.isArray(w.edited[n])
      && w.dists[n].every((d) => Array.isArray(d) && d.length === bins && d.every((v) => Number.isFinite(v) && v >= 0 && v <= FULL)));
    if (!ok) return false;
    S.dists = w.dists; S.names = w.names; S.edited = w.edited;
    S.mode5 = w.mode5 === "additive" ? "additive" : "series";
    if (w.step !== step) resampleAll(gridOf(w.step), gridOf(step), step);
    return true;
  } catch { return false; }
}
