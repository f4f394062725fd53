// spectrocolor explorer: wiring. Colour numbers come from the server (the library); while an
// edit is in progress the page repaints from the local fast path (colour.js) in the same frame,
// and the server's answer replaces it as soon as it arrives.

import {$, el, fill} from "./dom.js";
import {apiJSON, api} from "./api.js";
import {S, FULL, EDITORS, SETTING_NAMES, remember, undo, redo, resampleAll, stateURL, readURLOptions,
  readURLDistributions, persist, readPersisted} from "./state.js";
import {hasFastPath, localColour, localWeights, whiteOf, emitted} from "./colour.js";
import {buildPatches, buildCards, paint, evalSpec, markStale, displayName, setText} from "./view.js";
import {buildEditors, drawEditors, drawEmitted, setLevel, editorCount, cursorOf} from "./editors.js";
import {drawDiagram, buildPoints, drawPoints, drawDisplayLight} from "./diagram.js";
import {applyPreset, presetButtons, moveButtons} from "./presets.js";
import {setupPhoto, refreshPhoto} from "./relight.js";
import {setupProjector} from "./projector.js";  // issue 28 item 4
import {setupSnapshot} from "./snapshot.js";  // issue 28 item 5
import {mountDemos} from "./demos.js";  // issue 28: guided demonstrations

window.__spectra = S;  // for the browser tests and the latency bench

// ---------------------------------------------------------------- messages
/** A note next to the actions (saved, file read, …): replaced by the next one. */
function say(text) { $("note").textContent = text || ""; }

/** An error, laid over the page (it never moves what is under the pointer), until dismissed or
 * until a later request of the same `kind` succeeds. `where` names the action that failed. */
let errorKind = null;
function fail(where, err, kind = where) {
  $("error-text").textContent = `${where}: ${err.message || err}`;
  $("error").hidden = false;
  errorKind = kind;
}
function dismissError() { $("error").hidden = true; $("error-text").textContent = ""; errorKind = null; }
/** A request of `kind` succeeded: an earlier failure of that kind no longer describes the page. */
function succeeded(kind) { if (errorKind === kind) dismissError(); }

// ---------------------------------------------------------------- evaluation
function requestBody() {
  const e = evalSpec();
  const body = {step_nm: S.step, observer: S.observer, display: S.display, normalise: S.normalise,
    gamut: S.gamut, spectra: e.request ? e.request.spectra : e.spectra, pairs: e.pairs};
  if (e.request && e.request.additive) body.additive = e.request.additive;  // setting 5's spotlights
  if (S.adaptation) body.adaptation = S.adaptation;
  if (e.illuminant) body.illuminant = e.illuminant;
  return body;
}

/** Repaint now from the local fast path, then ask the server. `final`: an edit has ended (the
 * address and storage are written after the frame either way: see queueSave). */
function update(final = true) {
  S.settled = false;
  const e = evalSpec();
  const lw = localWeights(S.model, S.normalise, e.illuminant);
  drawEditors(S.editing);
  S.editing = null;
  if (lw && hasFastPath(S.gamut)) {
    S.localWhite = whiteOf(lw.W);
    S.local = e.spectra.map((s) => localColour(s, S.model, {W: lw.W, scale: lw.scale, normalise: S.normalise, gamut: S.gamut}));
    paint(S.local, null);
    drawPoints(S.local, e.labels, null);
    if (S.setting === 1 && S.model.emission) drawEmittedLight(emitted(S.local[0], S.model));
  }
  S.dirty = true;
  pump();
  queueSave();
  undoButtons();
}
async function pump() {
  if (S.inflight || !S.dirty) return;
  S.inflight = true; S.dirty = false;
  const seq = ++S.seq;
  try {
    const r = await apiJSON("/api/evaluate", requestBody());
    if (!S.dirty && seq === S.seq) {
      S.server = r; S.localWhite = r.white_XYZ;
      paint(r.colours, r); drawPoints(r.colours, evalSpec().labels, r); drawEmittedLight(r.colours[0].emitted_levels);
      showLightMetrics(r.light_metrics);
      refreshPhoto();
      markStale(null);
      succeeded("evaluate");
      if (S.afterEvaluate) { const after = S.afterEvaluate; S.afterEvaluate = null; after(r); }
      S.settled = settledUnlessSaving(optionsWaiting === 0);
    }
  } catch (err) {
    if (!S.dirty && seq === S.seq) {
      markStale("the library refused the last change");
      fail("Could not compute the colours", err, "evaluate");
      S.settled = settledUnlessSaving(optionsWaiting === 0);
    }
  }
  S.inflight = false;
  if (S.dirty) pump();
}

/** Setting 4: how well the illuminant renders colours (the library's lighting metrics). */
function showLightMetrics(m) {
  const box = $("light-metrics"), hidden = S.setting !== 4 || !m;
  if (box.hidden !== hidden) box.hidden = hidden;
  if (hidden) return;
  const f = (v, d) => (v === null || v === undefined ? "—" : Number(v).toFixed(d));
  const text = m.Ra === undefined ? m.note
    : `The illuminant: CCT ${f(m.cct_K, 0)} K, Duv ${f(m.duv, 4)} · CRI Ra ${f(m.Ra, 1)}, R9 ${f(m.R9, 1)}`
      + `${m.cri_meaningful ? "" : " (not meaningful: |Duv| > 0.0054)"} · TM-30 Rf ${f(m.Rf, 1)}, Rg ${f(m.Rg, 1)} · `
      + `${f(m.LER_lm_per_W, 0)} lm/W · melanopic DER ${f(m.melanopic_DER, 2)}. `;
  const shown = `${text}\n${m.Ra === undefined ? "" : m.note}`;
  if (box.__shown === shown) return;  // the same answer: nothing to rebuild (issue 28, glitch 5)
  box.__shown = shown;
  box.replaceChildren();
  box.append(document.createTextNode(text));
  if (m.Ra !== undefined) {
    const link = document.createElement("a");
    link.href = "/labs/light";
    link.textContent = "More in the light-source lab";
    box.append(link);
    box.title = m.note;
  }
}

/** Setting 1: the light the screen emits for the colour (SPECTRA's step 4) beside the bars. */
function drawEmittedLight(levels) {
  const box = $("emitted-box"), hidden = S.setting !== 1 || !levels;
  if (box.hidden !== hidden) box.hidden = hidden;
  if (hidden) return;
  const target = S.dists[1][0];
  // the server's answer repeats what the fast path drew (to rounding): drawn once (glitch 5)
  if (!(emittedDrawn && near(emittedDrawn[0], levels) && near(emittedDrawn[1], target))) {
    drawEmitted($("emitted"), levels, target);
    emittedDrawn = [levels.slice(), target.slice()];
  }
  setText($("emitted-caption"), emittedCaption());
}
/** The levels last drawn in the emitted-light graph, [emitted, distribution]. */
let emittedDrawn = null;
/** Equal to a millionth of a level (far below a pixel of the graph), bin for bin. */
const near = (a, b) => a.length === b.length && a.every((v, k) => Math.abs(v - b[k]) <= 1e-6);
/** What the emitted light matches, truthfully: the codes are those of the colour as shown, i.e.
 * adapted to the display's white when an adaptation is chosen, so the screen's light is then no
 * metamer of the distribution (it matches the adapted colour). */
function emittedCaption() {
  if (S.adaptation && S.adaptation !== "none") {
    return "The display's light (solid) matches the colour as adapted to the display's white, not the distribution (dashed) itself: no metamer.";
  }
  return "The display's light (solid), unadapted: inside the gamut it has the distribution's (dashed) chromaticity, a metamer up to brightness.";
}

// ---------------------------------------------------------------- history and the URL
// ---- issue 28, glitch 5: the address and storage are written once the edits pause: SAVE_QUIET_MS
// after the last edit, or SAVE_MAX_WAIT_MS after the first unwritten one while they go on, never
// in the frame of an edit (a held arrow key repeats 30 times a second: writing both on every press
// cost a frame on up to 39 % of presses, replaceState alone 1-4 ms, and Chromium ignores an address
// changed more than 200 times in 10 s). The last state is always written: when the edits pause,
// when the page is hidden or left (pagehide), and before the address is pushed or read (settings,
// Back). The page counts as settled only once it is written.
const SAVE_QUIET_MS = 250, SAVE_MAX_WAIT_MS = 1000;
let saveQueued = false, firstUnsaved = 0, lastEdit = 0, saveTimer = null, settleAfterSave = false;
function queueSave() {
  lastEdit = performance.now();
  if (saveQueued) return;
  saveQueued = true;
  firstUnsaved = lastEdit;
  requestAnimationFrame(() => {  // the frame of this edit is painted first
    clearTimeout(saveTimer);
    saveTimer = setTimeout(saveWhenQuiet, SAVE_QUIET_MS);
  });
}
/** Write the queued state if the edits have paused (or waited long enough), else wait on. */
function saveWhenQuiet() {
  if (!saveQueued) return;
  const now = performance.now(), due = Math.min(lastEdit + SAVE_QUIET_MS, firstUnsaved + SAVE_MAX_WAIT_MS);
  if (now >= due - 1) flushSave();
  else saveTimer = setTimeout(saveWhenQuiet, due - now);
}
function flushSave() {
  clearTimeout(saveTimer);
  if (!saveQueued) return;
  saveQueued = false;
  saveState();
  if (settleAfterSave) {
    settleAfterSave = false;
    if (!S.dirty && !S.inflight && optionsWaiting === 0) S.settled = true;
  }
}
/** `settled` as the page would set it, held back (until flushSave) while a write is queued. */
function settledUnlessSaving(settled) {
  settleAfterSave = settled && saveQueued;
  return settled && !saveQueued;
}
/** Back/Forward moved to another address: a write still queued would overwrite it. */
function dropSave() { clearTimeout(saveTimer); saveQueued = false; }
window.addEventListener("pagehide", flushSave);
document.addEventListener("visibilitychange", () => { if (document.hidden) flushSave(); });
// ---- end of glitch 5's part

function saveState() {
  persist();
  const url = stateURL();
  if (url !== location.pathname + location.search) history.replaceState({setting: S.setting}, "", url);
}

function undoButtons() {
  const u = $("undo"), r = $("redo");
  if (u.disabled !== !S.undo[S.setting].length) u.disabled = !S.undo[S.setting].length;
  if (r.disabled !== !S.redo[S.setting].length) r.disabled = !S.redo[S.setting].length;
}

function doUndo(back) {
  const mode = S.mode5;
  if (!(back ? undo() : redo())) { say(back ? "nothing to undo in this setting" : "nothing to redo"); return; }
  if (S.mode5 !== mode) selectSetting(S.setting, false);  // setting 5's mode came back: its view too
  else update();
}

// ---- issue 28 item 7: setting 5 as filters in series (subtractive) or two spotlights (additive)
function showMode5() {
  $("mode5").hidden = S.setting !== 5;
  for (const r of document.querySelectorAll("#mode5 input")) r.checked = r.value === S.mode5;
}
/** Switch setting 5's mode (one undo step); the two filters stay as they are. */
function setMode5(mode) {
  if (S.setting !== 5 || mode === S.mode5) return;
  remember();
  S.mode5 = mode;
  selectSetting(5, false);
  say(mode === "additive"
    ? "two spotlights, one filter each, on a white screen: where they overlap the lights add (on the diagram, on the dashed line)"
    : "one light through both filters: the transmittances multiply");
}
function setupMode5() {
  document.querySelectorAll("#mode5 input").forEach((r) => r.addEventListener("change", () => {
    if (r.checked) { setMode5(r.value); focusBars(); }  // the keys go back to the bars, as after an option
  }));
}
// ---- end of item 7's part

// ---------------------------------------------------------------- settings and options
function selectSetting(n, push = true) {
  if (push) flushSave();  // the setting left keeps its last edit in its history entry
  S.setting = n;
  document.querySelectorAll("#tabs [role=tab]").forEach((b) => {
    const on = Number(b.dataset.setting) === n;
    b.classList.toggle("on", on); b.setAttribute("aria-selected", String(on)); b.tabIndex = on ? 0 : -1;
  });
  $("stage").setAttribute("aria-labelledby", `tab-${n}`);
  document.title = `spectrocolor · ${SETTING_NAMES[n]}`;
  const count = evalSpec().spectra.length;
  buildEditors(update); buildPatches(); buildCards(count); buildPoints(count);
  presetButtons(update, say); actionButtons(); say("");
  showMode5();
  $("emitted-box").hidden = true;
  refreshPhoto();
  if (push) history.pushState({setting: n}, "", stateURL());
  update();
}

function actionButtons() {
  fill($("actions"), S.setting === 2 ? el("button", {id: "metamer", type: "button", onclick: makeMetamer,
    title: "Replace the right distribution by the smoothest one with the same colour as the left (van Trigt)"}, "Make a metamer") : null,
  moveButtons(update, say));
}

/** The display model for the page's options with `over` changed ({step, observer, display,
 * normalise, adaptation}); S is left as it is. */
function fetchModel(over = {}) {
  const o = {step: S.step, observer: S.observer, display: S.display, normalise: S.normalise,
    adaptation: S.adaptation, ...over};
  const body = {step_nm: o.step, observer: o.observer, display: o.display, normalise: o.normalise};
  if (o.adaptation) body.adaptation = o.adaptation;
  return apiJSON("/api/model", body);
}
function setModel(model) {
  S.model = model;
  S.wl = model.wavelengths_nm;
  drawDiagram();
  drawDisplayLight();
}

// Option changes (bins, display, observer, white, normalisation, gamut, Back) run one at a time in
// the order chosen. Each asks the server first and changes the page's state only once every answer
// is in, all at once, so the page never holds options, a grid and distributions that disagree
// (three quick choices used to interleave: 61 bins on a 10 nm page, every edit refused).
let optionQueue = Promise.resolve();
let optionsWaiting = 0;
function queueOption(where, task) {
  optionsWaiting++;
  S.settled = false;
  const run = async () => {
    let failed = false;
    try { await task(); succeeded("options"); } catch (err) { failed = true; fail(where, err, "options"); }
    optionsWaiting--;
    if (optionsWaiting === 0) syncControls();  // the controls show the state the page holds
    if (failed) update();  // the page as it was (settles again)
    else if (optionsWaiting === 0 && !S.dirty && !S.inflight) S.settled = settledUnlessSaving(true);
  };
  optionQueue = optionQueue.then(run);
  return optionQueue;
}

/** A chosen option: reload what depends on it, then give the keyboard back to the bars. */
function option(name, value) {
  return queueOption(`Could not switch ${name}`, async () => {
    if (name !== "gamut") setModel(await fetchModel({[name]: value}));
    S[name] = value;
    if (name === "normalise" && value !== "per-colour") S.normaliseA = value;
    update();
  }).then(focusBars);
}
function focusBars() {
  const cv = document.querySelector(`#editors .editor[data-e='${S.active[S.setting]}'] canvas`);
  if (cv) cv.focus({preventScroll: true});
}

function changeStep(step) {
  return queueOption("Could not change the bins", async () => {
    if (step === S.step) return;
    const [presets, model] = await Promise.all([apiJSON(`/api/presets?step_nm=${step}`), fetchModel({step})]);
    commitStep(step, presets, model);
  }).then(focusBars);
}
/** Move the page onto the grid of `step` (synchronously: nothing runs in between). */
function commitStep(step, presets, model) {
  const fromWl = S.wl;
  S.step = step; S.presets = presets;
  setModel(model);
  resampleAll(fromWl, S.wl, step);
  for (const key of Object.keys(S.cursor)) {  // keep each cursor on the same wavelength
    const nm = fromWl[S.cursor[key]];
    S.cursor[key] = S.wl.reduce((best, w, k) => Math.abs(w - nm) < Math.abs(S.wl[best] - nm) ? k : best, 0);
  }
  selectSetting(S.setting, false);
  say(`resampled every distribution to ${S.wl.length} bins (linear interpolation${step === 10 ? ", whole levels" : ", levels in tenths"})`);
}

/** Key X: SPECTRA's switch between alternative A (in the variant last chosen) and B. */
function toggleNorm() {
  return queueOption("Could not switch the normalisation", async () => {
    const value = S.normalise === "per-colour" ? S.normaliseA : "per-colour";
    setModel(await fetchModel({normalise: value}));
    S.normalise = value;
    $("normalise").value = value;
    update();
  });
}

// ---------------------------------------------------------------- save, recall, pair
const storeKey = (n) => `spectrocolor:setting${n}:step${S.step}`;
function saveSlot() {
  localStorage.setItem(storeKey(S.setting), JSON.stringify({dists: S.dists[S.setting], names: S.names[S.setting], edited: S.edited[S.setting]}));
  say(`saved (0 recalls it${S.setting === 2 || S.setting === 3 ? "; 9 in other settings loads this pair" : ""})`);
}
function recall(from) {
  const raw = localStorage.getItem(storeKey(from));
  if (!raw) { say(`nothing saved in setting ${from} yet (press S there)`); return; }
  const saved = JSON.parse(raw);
  remember();
  const n = S.setting, copy = (a) => a.slice();
  if (from === n) {
    S.dists[n] = saved.dists.map(copy); S.names[n] = saved.names.slice(); S.edited[n] = (saved.edited || saved.names.map(() => false)).slice();
  } else if (n === 4) {  // key 9: the pair from setting 2 as the two samples
    for (const j of [0, 1]) { S.dists[4][j + 1] = copy(saved.dists[j]); S.names[4][j + 1] = saved.names[j]; S.edited[4][j + 1] = false; }
  } else {
    const count = S.dists[n].length;
    S.dists[n] = saved.dists.slice(0, count).map(copy); S.names[n] = saved.names.slice(0, count); S.edited[n] = S.names[n].map(() => false);
  }
  say(from === n ? "recalled the saved distributions" : `loaded the pair saved in setting ${from}`);
  update();
}
const pairSource = () => (S.setting === 2 ? 3 : 2);

// ---------------------------------------------------------------- keys and touch buttons
function moveCursor(delta) {
  const a = S.active[S.setting];
  S.cursor[`${S.setting}:${a}`] = Math.min(S.wl.length - 1, Math.max(0, cursorOf(a) + delta));
  drawEditors(a);
}
function stepLevel(delta) {
  const a = S.active[S.setting], k = cursorOf(a);
  S.cursor[`${S.setting}:${a}`] = k;
  remember();
  setLevel(a, k, S.dists[S.setting][a][k] + delta);
  S.editing = a;  // only its bars (and those that follow them) change: redraw just those
  update();
}
function nextDistribution() {
  S.active[S.setting] = (S.active[S.setting] + 1) % editorCount();
  drawEditors();
  if (document.activeElement && document.activeElement.closest("#editors")) focusBars();
}
/** One level on SPECTRA's grid; on the fine grids one level, or a tenth with Shift. */
const levelStep = (fine) => (S.step === 10 ? 1 : fine ? 0.1 : 1);

const COMMANDS = {
  left: () => moveCursor(-1), right: () => moveCursor(1),
  up: () => stepLevel(levelStep(false)), down: () => stepLevel(-levelStep(false)),
  next: nextDistribution, save: saveSlot, recall: () => recall(S.setting),
  pair: () => (S.setting === 1 ? say("key 9 loads a pair: use it in settings 2–5") : recall(pairSource())),
};

function onKey(ev) {
  const t = ev.target;
  if (t.closest && t.closest("select, input, textarea, dialog[open]")) return;
  const mod = ev.ctrlKey || ev.metaKey;
  if (mod && !ev.altKey && (ev.key === "z" || ev.key === "Z")) { doUndo(!ev.shiftKey); ev.preventDefault(); return; }
  if (mod && !ev.altKey && (ev.key === "y" || ev.key === "Y")) { doUndo(false); ev.preventDefault(); return; }
  if (ev.ctrlKey || ev.metaKey || ev.altKey) return;
  if (t.getAttribute && t.getAttribute("role") === "tab" && (ev.key === "ArrowLeft" || ev.key === "ArrowRight")) {
    const n = ((S.setting - 1 + (ev.key === "ArrowRight" ? 1 : 4)) % 5) + 1;  // tabs: arrows move between them
    selectSetting(n); $(`tab-${n}`).focus(); ev.preventDefault(); return;
  }
  const onButton = t.closest && t.closest("button, a, summary");
  let handled = true;
  switch (ev.key) {
    case "ArrowLeft": moveCursor(-1); break;
    case "ArrowRight": moveCursor(1); break;
    case "ArrowUp": stepLevel(levelStep(ev.shiftKey)); break;
    case "ArrowDown": stepLevel(-levelStep(ev.shiftKey)); break;
    case " ": if (onButton) handled = false; else nextDistribution(); break;
    case "x": case "X": toggleNorm(); break;
    case "s": case "S": saveSlot(); break;
    case "0": recall(S.setting); break;
    case "9": COMMANDS.pair(); break;
    case "m": case "M": if (S.setting === 5) setMode5(S.mode5 === "additive" ? "series" : "additive"); else handled = false; break;
    default:
      if (/^[1-8]$/.test(ev.key)) applyPreset(ev.key, update, say); else handled = false;
  }
  if (handled) ev.preventDefault();
}

// ---------------------------------------------------------------- metamer, files
async function makeMetamer() {
  try {
    const r = await apiJSON("/api/metamer", {step_nm: S.step, observer: S.observer, target: S.dists[2][0]});
    remember();
    S.dists[2][1] = r.levels.map((v) => Math.min(FULL, Math.max(0, v)));
    S.names[2][1] = "smoothest metamer"; S.edited[2][1] = false;
    update();
  } catch (err) { fail("Make a metamer", err); }
}
/** The names a file gets: as the page shows them ("(edited)" included), so Load gives them back
 * unchanged; the editor's role only where a name is empty or taken twice (a file's names differ). */
function exportNames(shown, roles) {
  const clean = (t) => t.replace(/[\x00-\x1f\x7f-\x9f\u2028\u2029/\\"<>]/g, "_").trim().slice(0, 60);
  const out = [];
  shown.forEach((t, i) => {
    let name = clean(t || "");
    if (!name || out.includes(name)) name = clean(`${roles[i]} ${name}`);
    out.push(name);
  });
  return out;
}
async function saveFile(format) {
  const names = exportNames(S.names[S.setting].map((_, i) => displayName(S.setting, i)), EDITORS[S.setting]);
  try {
    const res = await api("/api/export", {format, step_nm: S.step, names, spectra: S.dists[S.setting]});
    const blob = await res.blob(), a = el("a", {href: URL.createObjectURL(blob), download: `spectra-setting${S.setting}.${format}`});
    a.click();
    setTimeout(() => URL.revokeObjectURL(a.href), 1000);
    succeeded("save");
  } catch (err) { fail(`Save ${format.toUpperCase()}`, err, "save"); }
}
/** A name read from a file: a spreadsheet guard's apostrophe (CSV) and "(edited)" undone. */
function importedName(name) {
  const plain = /^'[=+\-@]/.test(name) ? name.slice(1) : name;
  const m = /^(.*) \(edited\)$/.exec(plain);
  return m ? {name: m[1], edited: true} : {name: plain, edited: false};
}
/** The unit an exported file declares (compute.EXPORT_UNIT): such a file is read as levels. */
const DECLARES_LEVELS = "SPECTRA levels 0-30";
/** A file's bytes as base64: the server decodes the text as the library does (BOM, UTF-8, else cp1252). */
async function fileBase64(file) {
  const bytes = new Uint8Array(await file.arrayBuffer());
  let binary = "";
  for (let i = 0; i < bytes.length; i += 0x8000) binary += String.fromCharCode(...bytes.subarray(i, i + 0x8000));
  return btoa(binary);
}
async function loadFile(file) {
  try {
    const head = new TextDecoder().decode(new Uint8Array(await file.slice(0, 4096).arrayBuffer()));
    const levels = head.includes(DECLARES_LEVELS);
    const r = await apiJSON("/api/import", {filename: file.name, content_base64: await fileBase64(file),
      step_nm: S.step, method: "linear", scale: levels ? "levels" : $("upload-scale").value, observer: S.observer});
    if (levels) r.note += ` (the file declares ${DECLARES_LEVELS}: read as levels)`;
    const named = r.names.map(importedName);
    const slots = editorCount() - (S.setting === 3 ? 1 : 0);
    const place = (picks) => {
      remember();
      const a = S.active[S.setting];
      picks.forEach((j, n) => {
        const i = S.setting === 3 ? a : (a + n) % editorCount();
        if (S.setting === 3) {  // a complementary pair: the other side is what the full spectrum leaves
          S.dists[3][i] = r.levels[j].slice(); S.dists[3][1 - i] = r.levels[j].map((v) => FULL - v);
          S.names[3][i] = named[j].name; S.names[3][1 - i] = `complement of ${named[j].name}`; S.edited[3] = [named[j].edited, named[j].edited];
        } else {
          S.dists[S.setting][i] = r.levels[j].slice(); S.names[S.setting][i] = named[j].name; S.edited[S.setting][i] = named[j].edited;
        }
      });
      say(r.note); succeeded("load"); update();
    };
    if (r.levels.length <= slots) place(r.levels.map((_, j) => j));
    else chooseSpectra(r.names, Math.min(slots, r.levels.length), place);
  } catch (err) { fail(`Load ${file.name}`, err, "load"); }
}

/** The file holds more spectra than this setting has editors: let the user pick which. */
function chooseSpectra(names, count, place) {
  const dlg = $("choose"), targets = EDITORS[S.setting];
  const a = S.active[S.setting];
  const selects = Array.from({length: count}, (_, n) => el("select", {id: `pick-${n}`},
    names.map((name, j) => el("option", {value: j, selected: j === n}, `${j + 1}. ${name}`))));
  fill($("choose-rows"), selects.map((sel, n) => el("p", {},
    el("label", {for: sel.id}, `${targets[S.setting === 3 ? a : (a + n) % targets.length]}: `), sel)));
  $("choose-count").textContent = `The file holds ${names.length} spectra; this setting shows ${count} at a time.`;
  dlg.onclose = () => { if (dlg.returnValue === "ok") place(selects.map((s) => Number(s.value))); focusBars(); };
  dlg.returnValue = "";
  dlg.showModal();
}

// ---------------------------------------------------------------- setup
function defaults() {
  const p = S.presets, copy = (a) => a.slice();
  S.dists = {1: [copy(p.setting1[0].levels)], 2: [copy(p.setting2.left[6].levels), copy(p.setting2.right[6].levels)],
    3: [copy(p.setting3[0].left), copy(p.setting3[0].right)],
    4: [copy(p.setting4.illuminants[1].levels), copy(p.setting4.samples[0].left), copy(p.setting4.samples[0].right)],
    5: [copy(p.setting5[0].left), copy(p.setting5[0].right)]};
  S.names = {1: [p.setting1[0].name], 2: [p.setting2.left[6].name, p.setting2.right[6].name],
    3: p.setting3[0].name.split(" / ").map((s) => s.trim()),
    4: [p.setting4.illuminants[1].name, `${p.setting4.samples[0].name} 1`, `${p.setting4.samples[0].name} 2`],
    5: p.setting5[0].name.split(":")[0].split(" and ").map((s) => s.trim())};
  S.edited = Object.fromEntries(Object.entries(S.dists).map(([n, d]) => [n, d.map(() => false)]));
}

function fillSelect(id, items, value) {
  fill($(id), items.map(([v, text, help]) => el("option", {value: v, title: help}, text)));
  $(id).value = value;
}

/** The options a URL asks for, written into `T` (options the server does not offer are ignored). */
function fromURL(search, T = S) {
  const o = readURLOptions(search), opts = S.options;
  if (o.step && opts.steps_nm.includes(o.step)) T.step = o.step;
  if (o.observer && o.observer in opts.observers) T.observer = o.observer;
  if (o.display && opts.displays.includes(o.display)) T.display = o.display;
  if (o.gamut && opts.gamuts.includes(o.gamut)) T.gamut = o.gamut;
  if (o.adaptation && (opts.adaptations || []).some(([v]) => v === o.adaptation)) T.adaptation = o.adaptation;
  if (o.normalise && opts.normalisations.includes(o.normalise)) T.normalise = o.normalise;
  if (T.normalise !== "per-colour") T.normaliseA = T.normalise;
  return o.setting;
}
function syncControls() {
  $("display").value = S.display; $("observer").value = S.observer; $("gamut").value = S.gamut;
  $("step").value = String(S.step); $("normalise").value = S.normalise;
  if (S.adaptation) $("adaptation").value = S.adaptation;
}

/** Back/Forward: the options and distributions of the address, queued like any option change
 * (`demo`: a demonstration's address, whose levels are one undo step of their setting). */
function onPopState(_event, demo = false) {
  dropSave();
  return queueOption("Could not go back", async () => {
    const keys = ["step", "display", "observer", "adaptation", "normalise"];
    const T = Object.fromEntries([...keys, "gamut", "normaliseA"].map((k) => [k, S[k]]));
    const setting = fromURL(location.search, T) || 1;
    const newStep = T.step !== S.step;
    const presets = newStep ? await apiJSON(`/api/presets?step_nm=${T.step}`) : S.presets;
    const model = keys.some((k) => T[k] !== S[k]) ? await fetchModel(T) : null;
    Object.assign(S, T);  // every answer is in: change the page at once
    S.presets = presets;
    if (model) setModel(model);
    if (newStep) defaults();
    showURLState(setting, demo);
  });
}
/** A demonstration's address (demos.js): pushed, so Back returns to what was there, then shown
 * as Back/Forward show an address (queued like any option change). */
function loadState(search) {
  flushSave();  // the entry Back returns to holds the page as it is (a press still queued included)
  history.pushState({}, "", `${location.pathname}${search}`);
  return onPopState(null, true);
}
function showURLState(setting, demo = false) {
  if (demo) remember(setting);  // Ctrl+Z after a demo gives back the setting as it was
  if (setting === 5) S.mode5 = readURLOptions(location.search).mode5;  // &m=add: two spotlights
  const d = readURLDistributions(location.search, setting, S.wl.length);
  if (d) { S.dists[setting] = d.dists; S.names[setting] = d.names; S.edited[setting] = d.edited; }
  syncControls();
  selectSetting(setting, false);
}

async function init() {
  const o = S.options = await apiJSON("/api/options");
  const defaults_ = o.defaults || {};
  S.gamut = defaults_.gamut || o.gamuts[0];
  S.normalise = S.normaliseA = defaults_.normalise || "fixed";
  S.display = defaults_.display || o.displays[0];
  if (o.adaptations) S.adaptation = defaults_.adaptation || o.adaptations[0][0];
  const setting = fromURL(location.search) || 1;
  // every list and label comes from the library's registries through /api/options
  fillSelect("step", o.steps, String(S.step));
  fillSelect("display", o.displays.map((d) => [d, d]), S.display);
  fillSelect("observer", Object.entries(o.observers), S.observer);
  fillSelect("gamut", o.choices.gamut, S.gamut);
  fillSelect("normalise", o.choices.normalise, S.normalise);
  fillSelect("upload-scale", o.choices.scale.map(([v, text]) => [v, text]), o.choices.scale[0][0]);
  if (o.adaptations) {
    fillSelect("adaptation", o.adaptations, S.adaptation);
    $("adaptation-label").hidden = false;
  }
  for (const name of ["display", "observer", "gamut", "adaptation", "normalise"]) {
    $(name).addEventListener("change", (e) => option(name, e.target.value));
  }
  $("step").addEventListener("change", (e) => changeStep(Number(e.target.value)));
  $("save-csv").addEventListener("click", () => saveFile("csv"));
  $("save-json").addEventListener("click", () => saveFile("json"));
  $("load-file").addEventListener("click", () => $("file").click());
  $("file").addEventListener("change", (e) => { if (e.target.files[0]) loadFile(e.target.files[0]); e.target.value = ""; });
  $("about-open").addEventListener("click", () => $("about").showModal());
  $("error-close").addEventListener("click", dismissError);
  $("display-light").addEventListener("toggle", drawDisplayLight);
  $("locus-fill").addEventListener("change", (e) => { S.filledLocus = e.target.checked; drawDiagram(); });
  $("menu").addEventListener("click", () => {
    const open = document.body.classList.toggle("tools-open");
    $("menu").setAttribute("aria-expanded", String(open));
  });
  document.querySelectorAll("#tabs [role=tab]").forEach((b) => b.addEventListener("click", (ev) => {
    if (Number(b.dataset.setting) !== S.setting) selectSetting(Number(b.dataset.setting));
    if (ev.detail > 0) focusBars();  // a mouse or finger choice gives the keys back to the bars
  }));
  document.querySelectorAll("#touch [data-command]").forEach((b) => b.addEventListener("click", () => COMMANDS[b.dataset.command]()));
  $("undo").addEventListener("click", () => doUndo(true));
  $("redo").addEventListener("click", () => doUndo(false));
  $("numbers").addEventListener("click", (ev) => {
    const b = ev.target.closest(".badge-switch");
    if (b) { $("gamut").value = b.dataset.gamut; option("gamut", b.dataset.gamut); }
  });
  document.addEventListener("keydown", onKey);
  document.addEventListener("click", (ev) => {  // after a mouse or finger press, space and arrows go to the bars again
    if (ev.detail > 0 && ev.target.closest("#presets button, #touch button, #actions button")) focusBars();
  });
  window.addEventListener("resize", () => drawEditors());
  window.addEventListener("popstate", onPopState);
  setupMode5();  // setting 5's mode switch (issue 28 item 7)
  setupProjector();  // key P, the Projector button (issue 28 item 4)
  setupSnapshot({say, fail});  // Picture SVG / PNG (issue 28 item 5)
  mountDemos({explorer: true, where: () => `setting${S.setting}`, title: () => `Demos · setting ${S.setting}`,
    load: loadState, anchor: () => $("about-open")});

  setupPhoto(fail).then(refreshPhoto).catch((err) => fail("The photo panel could not start", err));
  const start = (async () => {  // option changes chosen meanwhile wait for it (queueOption)
    const [presets, model] = await Promise.all([apiJSON(`/api/presets?step_nm=${S.step}`), fetchModel()]);
    S.presets = presets;
    setModel(model);
    defaults();
    readPersisted(S.step);  // the other settings as they were left
    showURLState(setting);
    history.replaceState({setting}, "", stateURL());
  })();
  optionQueue = start.catch(() => {});
  await start;
}
init().catch((err) => fail("The explorer could not start", err));
