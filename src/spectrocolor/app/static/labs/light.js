// The light-source lab. The page describes a light (a named one, Gaussian primaries, or a measured SPD
// uploaded from a file) and shows what the library computes for it (POST /api/lab/light): CCT, Duv,
// Ra, R1-R14, Rf, Rg, the TM-30 vector graphic and hue-bin charts (Rcs,hj, Rhs,hj, Rf,hj), LER,
// melanopic DER and the test samples under the light and the reference.
//
// An uploaded file is read by the server (POST /api/lab/light/upload: the explorer's Load reader,
// workers and budgets), which answers its SPD at the lab's 81 wavelengths (380-780 nm, 5 nm). The
// page keeps that SPD in the tab's sessionStorage (one light, about 1 kB), so a reload of the tab
// shows it again; the URL says only "kind=file", so a link opened elsewhere asks for the file.
//
// The explorer's own distribution (js/handoff.js: "Light → light lab" in setting 1) comes in the
// URL as kind=explorer&r=<step nm>:<level>,<level>,… (levels 0-30 over 400-700 nm) and &label=.
// The server answers it with None for every metric that needs 380-780 nm and the library's reason
// for each, which the page says in plain words (#reasons).

import { $, api, context, css, fmt, showError, theme, wireCommon } from "./common.js";

const DEFAULT_LEDS = [[450, 20, 1.0], [540, 60, 0.7], [620, 20, 0.8]];
const DEFAULTS = { kind: "named", name: "FL2", temperature: 3000, leds: DEFAULT_LEDS, display: "sRGB", file: null,
  explorer: null };  // explorer: {step, levels, label}, the explorer's distribution (400-700 nm)
const EXPLORER_STEPS = [1, 5, 10];
// the uploaded light in this tab's sessionStorage: {label, spd (81 values), note}
const STORED = "spectrocolor.lightLab.upload";
const GRID_SIZE = 81;  // 380-780 nm at 5 nm, the lab's grid (light_lab.WAVELENGTHS_NM)
const MAX_UPLOAD_BYTES = 1_000_000;  // the server's import_routes.MAX_IMPORT_BYTES
let notKept = "";  // said when the URL names an uploaded light this tab no longer holds
let badExplorer = "";  // said when the URL's explorer distribution cannot be read

let state = structuredClone(DEFAULTS);
// the kinds of light named by a temperature, from the server's registry: name -> {label, min_K, max_K}
let kinds = new Map();
let result = null;
let inflight = false;
let dirty = false;
const undoStack = [];
const redoStack = [];



// ---- state, URL, undo ----------------------------------------------------------------------
function encode(s) {
  const params = new URLSearchParams({ kind: s.kind, name: s.name, T: String(s.temperature), display: s.display });
  params.set("leds", s.leds.map((p) => p.join(":")).join(","));
  if (s.explorer) {
    params.set("r", `${s.explorer.step}:${s.explorer.levels.join(",")}`);
    params.set("label", s.explorer.label);
  }
  return "#" + params.toString();
}

/** The explorer's distribution from the address (`r=<step>:<levels>`), or null and a reason. */
function explorerFrom(params) {
  if (!params.has("r")) return [null, ""];
  const [stepText, list = ""] = params.get("r").split(":");
  const step = Number(stepText);
  const levels = list.split(",").map((v) => (v.trim() === "" ? NaN : Number(v)));
  const count = EXPLORER_STEPS.includes(step) ? 300 / step + 1 : -1;
  if (count < 0 || levels.length !== count || !levels.every((v) => Number.isFinite(v) && v >= 0 && v <= 30)
      || !levels.some((v) => v > 0)) {
    return [null, "The link's distribution from the explorer could not be read (r= must be a step of 1, 5 or 10 nm, "
      + "then the levels 0–30 at 400–700 nm, not all 0): showing a named light instead."];
  }
  return [{ step, levels, label: (params.get("label") || "the explorer's distribution").slice(0, 200) }, ""];
}

function storedUpload() {
  try {
    const light = JSON.parse(sessionStorage.getItem(STORED));
    const good = light && typeof light.label === "string" && Array.isArray(light.spd) && light.spd.length === GRID_SIZE
      && light.spd.every((v) => Number.isFinite(v) && v >= 0) && light.spd.some((v) => v > 0);
    return good ? { label: light.label, spd: light.spd, note: String(light.note || "") } : null;
  } catch { return null; }  // storage refused (privacy mode) or not JSON
}

function decode(hash) {
  const params = new URLSearchParams(hash.slice(1));
  const next = structuredClone(DEFAULTS);
  next.file = storedUpload();
  notKept = "";
  if (params.get("kind") === "leds" || params.get("kind") === "named") next.kind = params.get("kind");
  if (params.get("kind") === "file") {
    if (next.file) next.kind = "file";
    else notKept = "The link names an uploaded light that this tab does not hold (an upload is kept only in the tab "
      + "that read it): upload the file again. Showing a named light meanwhile.";
  }
  [next.explorer, badExplorer] = explorerFrom(params);
  if (params.get("kind") === "explorer" && next.explorer) next.kind = "explorer";
  if (params.has("name")) next.name = params.get("name");
  if (params.has("display")) next.display = params.get("display");
  const T = Number(params.get("T"));
  if (Number.isFinite(T) && T >= 1000 && T <= 20000) next.temperature = T;
  if (params.has("leds")) {
    const leds = params.get("leds").split(",").map((p) => p.split(":").map(Number));
    if (leds.length >= 1 && leds.length <= 4 && leds.every((p) => p.length === 3 && p.every(Number.isFinite))) next.leds = leds;
  }
  return next;
}

function source(s) {
  if (s.kind === "file" && s.file) return { kind: "spd", label: s.file.label, values: s.file.spd };
  if (s.kind === "explorer" && s.explorer) {
    return { kind: "explorer", label: s.explorer.label, step_nm: s.explorer.step, levels: s.explorer.levels };
  }
  if (s.kind === "leds") {
    return { kind: "leds", peaks_nm: s.leds.map((p) => p[0]), widths_nm: s.leds.map((p) => p[1]),
      powers: s.leds.map((p) => p[2]) };
  }
  const kind = kinds.get(s.name);
  if (kind) {
    return { kind: "temperature", light: s.name,
      temperature_K: Math.min(kind.max_K, Math.max(kind.min_K, s.temperature)) };
  }
  return { kind: "named", name: s.name };
}

function commit(change, replace = false) {
  const before = structuredClone(state);
  state = { ...state, ...structuredClone(change) };
  if (JSON.stringify(before) === JSON.stringify(state)) return;
  if (!replace) { undoStack.push(before); redoStack.length = 0; }
  history[replace ? "replaceState" : "pushState"](null, "", encode(state));
  render();
}

/** A state from the undo history, still holding the latest upload when it had none (undoing an upload
 * goes back to the light before it; the uploaded light stays one choice away under Light). */
const keepingUpload = (restored) => ({ ...restored, file: restored.file || storedUpload() });

function undo() {
  if (!undoStack.length) return;
  redoStack.push(structuredClone(state));
  state = keepingUpload(undoStack.pop());
  history.replaceState(null, "", encode(state));
  render();
}

function redo() {
  if (!redoStack.length) return;
  undoStack.push(structuredClone(state));
  state = keepingUpload(redoStack.pop());
  history.replaceState(null, "", encode(state));
  render();
}

// ---- controls ---------------------------------------------------------------------------
function slider(label, min, max, step, value, unit, onInput, onChange) {
  const wrap = document.createElement("label");
  wrap.className = "wide";
  wrap.append(document.createTextNode(label + " "));
  const input = document.createElement("input");
  Object.assign(input, { type: "range", min, max, step, value });
  const out = document.createElement("output");
  out.textContent = `${value}${unit}`;
  input.addEventListener("input", () => { out.textContent = `${input.value}${unit}`; onInput(Number(input.value)); });
  input.addEventListener("change", () => onChange(Number(input.value)));
  wrap.append(input, out);
  return wrap;
}

function buildPrimaries() {
  const box = $("primaries");
  box.replaceChildren(...state.leds.map((led, i) => {
    const set = document.createElement("fieldset");
    set.className = "primary";
    const legend = document.createElement("legend");
    legend.textContent = `Primary ${i + 1}`;
    const live = (k) => (v) => { state.leds[i][k] = v; request(); };
    const done = (k) => (v) => {
      const leds = structuredClone(state.leds);
      leds[i][k] = v;
      state.leds[i][k] = lastCommitted.leds[i] ? lastCommitted.leds[i][k] : v;
      commit({ leds });
    };
    set.append(legend,
      slider("Peak", 380, 780, 1, led[0], " nm", live(0), done(0)),
      slider("Width", 5, 200, 1, led[1], " nm", live(1), done(1)),
      slider("Power", 0, 1, 0.01, led[2], "", live(2), done(2)));
    return set;
  }));
  $("add").disabled = state.leds.length >= 4;
  $("remove").disabled = state.leds.length <= 1;
}

let lastCommitted = structuredClone(state);

function syncControls() {
  $("kind").querySelector("option[value=file]").disabled = !state.file;  // before the value: it may be "file"
  $("kind").querySelector("option[value=explorer]").disabled = !state.explorer;
  $("kind").value = state.kind;
  $("name").value = state.name;
  $("display").value = state.display;
  $("temperature").value = state.temperature;
  $("temperature-out").textContent = `${state.temperature} K`;
  $("named-box").hidden = state.kind !== "named";
  $("leds-box").hidden = state.kind !== "leds";
  if (notKept) $("file-note").textContent = notKept;
  else if (state.file) {
    $("file-note").textContent = `${state.kind === "file" ? "Showing" : "Uploaded"}: ${state.file.label} (${state.file.note}). `
      + "Kept in this tab until it closes; drop another file to replace it.";
  }
  $("temperature-box").hidden = !kinds.has(state.name);
  buildPrimaries();
  $("undo").disabled = !undoStack.length;
  $("redo").disabled = !redoStack.length;
}

function render() {
  lastCommitted = structuredClone(state);
  syncControls();
  request();
}

// Coalesce requests: at most one in flight; the latest state is sent when it returns.
async function request() {
  if (inflight) { dirty = true; return; }
  inflight = true;
  dirty = false;
  const asked = JSON.stringify(source(state));
  try {
    result = await api("/api/lab/light", { source: source(state), display: state.display });
    $("error").hidden = true;
    paint();
  } catch (error) {
    showError(`${error.message} — the numbers below are for the previous light.`);
  } finally {
    inflight = false;
    if (dirty || JSON.stringify(source(state)) !== asked) request();
    else document.body.dataset.ready = "true";
  }
}

// ---- upload ----------------------------------------------------------------------------
/** A file's bytes as base64 (the server decodes the text as the library's reader does). */
async function fileBase64(file) {
  const bytes = new Uint8Array(await file.arrayBuffer());
  let binary = "";
  for (let i = 0; i < bytes.length; i += 0x8000) binary += String.fromCharCode(...bytes.subarray(i, i + 0x8000));
  return btoa(binary);
}

async function upload(file) {
  if (!file) return;
  if (file.size === 0 || file.size > MAX_UPLOAD_BYTES) {
    showError(`${file.name}: the file must be 1 to ${MAX_UPLOAD_BYTES} bytes, got ${file.size}`);
    return;
  }
  $("file-note").textContent = `Reading ${file.name}…`;
  try {
    const light = await api("/api/lab/light/upload", { filename: file.name, content_base64: await fileBase64(file) });
    try { sessionStorage.setItem(STORED, JSON.stringify(light)); } catch { /* not kept: said below */ }
    notKept = "";
    $("error").hidden = true;
    commit({ kind: "file", file: light });
  } catch (error) {
    showError(error.message);
    notKept = "";
    syncControls();
    if (!state.file) $("file-note").textContent = "Or drop a measurement file on the page. It must cover 380–780 nm.";
  } finally {
    $("file").value = "";
  }
}

function wireUpload() {
  $("file").addEventListener("change", (e) => upload(e.target.files[0]));
  const files = (e) => e.dataTransfer && [...e.dataTransfer.types].includes("Files");
  document.addEventListener("dragover", (e) => {
    if (!files(e)) return;
    e.preventDefault();
    document.body.classList.add("dropping");
  });
  document.addEventListener("dragleave", (e) => { if (!e.relatedTarget) document.body.classList.remove("dropping"); });
  document.addEventListener("drop", (e) => {
    if (!files(e)) return;
    e.preventDefault();
    document.body.classList.remove("dropping");
    upload(e.dataTransfer.files[0]);
  });
}

// ---- drawing ----------------------------------------------------------------------------


function numbers() {
  const s = result.summary;
  const rows = [
    ["light", result.label],
    ["CCT", s.cct_K === null ? "— (no CCT)" : `${fmt(s.cct_K, 0)} K`],
    ["Duv", fmt(s.duv, 4)],
    ["Ra (CIE 13.3)", fmt(s.Ra, 1)], ["R9 (strong red)", fmt(s.R9, 1)],
    ["Rf (TM-30 / CIE 224)", fmt(s.Rf, 1)], ["Rg (gamut)", fmt(s.Rg, 1)],
    ["LER", `${fmt(s.LER_lm_per_W, 1)} lm/W`], ["melanopic DER", fmt(s.melanopic_DER, 3)],
  ];
  $("numbers").replaceChildren(...rows.flatMap(([term, value]) => {
    const dt = document.createElement("dt"); dt.textContent = term;
    const dd = document.createElement("dd"); dd.textContent = value;
    return [dt, dd];
  }));
  const reasons = result.reasons || [];
  $("note").textContent = reasons.length || s.cri_meaningful ? ""
    : "|Duv| > 0.0054: CIE 13.3 says the CRI is not meaningful for this light (it is not white enough).";
  // a light known over part of 380-780 nm (the explorer's 400-700 nm): what is not computed, and why
  const box = $("reasons");
  box.hidden = !reasons.length;
  if (reasons.length) {
    const [lo, hi] = result.range_nm;
    const head = document.createElement("p");
    head.textContent = `This light is known over ${lo}–${hi} nm only (the explorer's range); the lab never `
      + "extrapolates, so these numbers are not computed:";
    const list = document.createElement("ul");
    list.replaceChildren(...reasons.map(({ metrics, reason }) => {
      const li = document.createElement("li");
      const name = document.createElement("strong");
      name.textContent = `${metrics}: `;
      li.append(name, reason.replace(/^measured over less than the range: /, "").replace(/ \(not finite elsewhere\)/, ""));
      return li;
    }));
    box.replaceChildren(head, list);
  }
}

function drawSpd() {
  const { ctx, width, height } = context($("spd"));
  const box = { x: 40, y: 10, w: width - 52, h: height - 50 };
  const wl = result.wavelengths_nm;
  const X = (w) => box.x + ((w - 380) / 400) * box.w;
  const Y = (v) => box.y + box.h - v * box.h;
  const t = theme(ctx.canvas);
  ctx.strokeStyle = t.muted; ctx.fillStyle = t.text; ctx.font = "11px system-ui, sans-serif";
  ctx.strokeRect(box.x, box.y, box.w, box.h);
  ctx.textAlign = "center";
  for (let w = 400; w <= 750; w += 50) ctx.fillText(w, X(w), box.y + box.h + 15);
  ctx.fillText("wavelength (nm)", box.x + box.w / 2, box.y + box.h + 30);
  ctx.textAlign = "right";
  for (const v of [0, 0.5, 1]) ctx.fillText(v.toFixed(1), box.x - 6, Y(v) + 4);
  ctx.strokeStyle = t.text; ctx.lineWidth = 2;
  ctx.beginPath();
  let drawing = false;  // a light known over part of the range (null elsewhere) is drawn where known
  result.spd.forEach((v, k) => {
    if (v === null) { drawing = false; return; }
    if (drawing) ctx.lineTo(X(wl[k]), Y(v)); else ctx.moveTo(X(wl[k]), Y(v));
    drawing = true;
  });
  ctx.stroke();
}

function drawGraphic() {
  const { ctx, width, height } = context($("graphic"));
  const r = Math.min(width, height) / 2 / 1.32;
  const cx = width / 2, cy = height / 2;
  const bins = result.bin_rgb8;
  const t = theme(ctx.canvas);
  for (let j = 0; j < 16; j++) { // hue sectors in the bins' colours, faint
    ctx.fillStyle = css(bins[j]);
    ctx.globalAlpha = 0.45;
    ctx.beginPath(); ctx.moveTo(cx, cy);
    ctx.arc(cx, cy, r * 1.3, -(j + 1) * Math.PI / 8, -j * Math.PI / 8);
    ctx.closePath(); ctx.fill();
  }
  ctx.globalAlpha = 1;
  ctx.strokeStyle = t.text; ctx.lineWidth = 1.5;
  ctx.beginPath(); ctx.arc(cx, cy, r, 0, 2 * Math.PI); ctx.stroke();
  if (!result.graphic) { // no graphic for this light: say why (the server's note)
    ctx.fillStyle = t.text; ctx.font = "12px system-ui, sans-serif"; ctx.textAlign = "center";
    ctx.fillText("No vector graphic for this light", cx, cy);
    $("graphic").setAttribute("aria-label", `TM-30 colour vector graphic: ${result.graphic_note || "none"}`);
    return;
  }
  $("graphic").setAttribute("aria-label", "TM-30 colour vector graphic");
  const P = ([a, b]) => [cx + a * r, cy - b * r];
  ctx.strokeStyle = t.bad; ctx.lineWidth = 2.5;
  ctx.beginPath();
  result.graphic.test.forEach((p, j) => { const [x, y] = P(p); j ? ctx.lineTo(x, y) : ctx.moveTo(x, y); });
  ctx.closePath(); ctx.stroke();
  ctx.lineWidth = 1.5;
  result.graphic.test.forEach((p, j) => {
    const [x0, y0] = P(result.graphic.reference[j]); const [x1, y1] = P(p);
    ctx.beginPath(); ctx.moveTo(x0, y0); ctx.lineTo(x1, y1); ctx.stroke();
  });
  ctx.fillStyle = t.text; ctx.font = "12px system-ui, sans-serif"; ctx.textAlign = "left";
  ctx.fillText(`Rf ${fmt(result.summary.Rf, 0)}   Rg ${fmt(result.summary.Rg, 0)}`, 8, 16);
}

function samples() {
  const { names, under_light: light, under_reference: reference } = result.samples;
  const notes = [];  // said when the samples are not shown as the caption describes
  if (!result.samples.under_light_note.startsWith("adapted")) notes.push(`Under this light: ${result.samples.under_light_note}.`);
  if (!result.samples.under_reference_note.startsWith("adapted")) notes.push(`Under the reference: ${result.samples.under_reference_note}.`);
  if (result.graphic_note) notes.push(`${result.graphic_note[0].toUpperCase()}${result.graphic_note.slice(1)}.`);
  $("samples-note").textContent = notes.join(" ");
  $("samples").replaceChildren(...names.map((name, i) => {
    const item = document.createElement("div");
    item.className = "sample";
    const swatch = document.createElement("div");
    swatch.className = "swatch";
    swatch.setAttribute("role", "img");
    const top = document.createElement("div"); top.style.background = light ? css(light[i]) : "transparent";
    const bottom = document.createElement("div");
    bottom.style.background = reference ? css(reference[i]) : "transparent";
    swatch.append(top, bottom);
    swatch.setAttribute("aria-label", `${name}: under the light ${light ? css(light[i]) : "none"}, under the reference ${reference ? css(reference[i]) : "none"}`);
    const caption = document.createElement("span");
    caption.textContent = `${name.slice(0, 5)} R${i + 1} ${fmt(result.Ri[i], 0)}`;
    caption.title = name;
    item.append(swatch, caption);
    return item;
  }));
}

// ---- TM-30 hue bins ------------------------------------------------------------------------
const SVG = "http://www.w3.org/2000/svg";

function svgNode(name, attributes, text) {
  const node = document.createElementNS(SVG, name);
  for (const [k, v] of Object.entries(attributes)) node.setAttribute(k, String(v));
  if (text !== undefined) node.textContent = text;
  return node;
}

/** The smallest symmetric range ±k·step holding every value, at least ±least. */
const symmetric = (values, least, step) =>
  Math.max(least, Math.ceil(Math.max(0, ...values.filter((v) => v !== null).map(Math.abs)) / step - 1e-9) * step);

/** A 16-bar chart in an SVG: bars from 0 (or the range's bottom) in the bins' colours, ticks with
 * units, each bar titled with its value; `values` may hold null (a bin without samples). */
function barChart(svg, values, { lo, hi, ticks, tick, axis, show }) {
  const W = 420, H = 230, box = { x: 52, y: 10, w: W - 62, h: H - 58 };
  svg.setAttribute("viewBox", `0 0 ${W} ${H}`);
  const Y = (v) => box.y + box.h - ((v - lo) / (hi - lo)) * box.h;
  const slot = box.w / 16;
  const nodes = [];
  for (const t of ticks) {
    nodes.push(svgNode("line", { class: t === 0 ? "zero" : "grid", x1: box.x, x2: box.x + box.w, y1: Y(t), y2: Y(t) }));
    nodes.push(svgNode("text", { x: box.x - 6, y: Y(t) + 4, "text-anchor": "end" }, tick(t)));
  }
  const base = Y(Math.max(lo, Math.min(hi, 0)));
  values.forEach((v, j) => {
    const x = box.x + j * slot;
    nodes.push(svgNode("text", { x: x + slot / 2, y: box.y + box.h + 14, "text-anchor": "middle" }, String(j + 1)));
    if (v === null) {
      nodes.push(svgNode("text", { x: x + slot / 2, y: base - 4, "text-anchor": "middle" }, "–"));
      return;
    }
    const top = Y(Math.max(lo, Math.min(hi, v)));
    const bar = svgNode("rect", { class: "bar", x: x + slot * 0.12, width: slot * 0.76, y: Math.min(top, base),
      height: Math.max(0.5, Math.abs(base - top)), fill: css(result.bin_rgb8[j]) });
    bar.append(svgNode("title", {}, `bin ${j + 1}: ${show(v)}`));
    nodes.push(bar);
  });
  nodes.push(svgNode("rect", { class: "axis", x: box.x, y: box.y, width: box.w, height: box.h }));
  nodes.push(svgNode("text", { x: box.x + box.w / 2, y: H - 14, "text-anchor": "middle" }, "hue bin j (1 = red, 22.5° each)"));
  nodes.push(svgNode("text", { x: 12, y: box.y + box.h / 2, "text-anchor": "middle",
    transform: `rotate(-90 12 ${box.y + box.h / 2})` }, axis));
  svg.replaceChildren(...nodes);
}

function drawBins() {
  const { Rf_h: rf, Rcs_h: rcs, Rhs_h: rhs } = result.hue_bins;
  const percent = rcs.map((v) => (v === null ? null : v * 100));
  const cs = symmetric(percent, 40, 10);
  barChart($("chart-rcs"), percent, { lo: -cs, hi: cs, ticks: [-cs, -cs / 2, 0, cs / 2, cs],
    tick: (t) => `${t > 0 ? "+" : ""}${t.toFixed(0)}%`, axis: "Rcs,hj (%)", show: (v) => `Rcs ${v.toFixed(1)}%` });
  const hs = symmetric(rhs, 0.5, 0.1);
  barChart($("chart-rhs"), rhs, { lo: -hs, hi: hs, ticks: [-hs, -hs / 2, 0, hs / 2, hs],
    tick: (t) => t.toFixed(2), axis: "Rhs,hj (no unit)", show: (v) => `Rhs ${v.toFixed(3)}` });
  barChart($("chart-rf"), rf, { lo: 0, hi: 100, ticks: [0, 20, 40, 60, 80, 100],
    tick: (t) => t.toFixed(0), axis: "Rf,hj", show: (v) => `Rf ${v.toFixed(1)}` });
  const missing = rf.map((v, j) => (v === null ? j + 1 : null)).filter((j) => j !== null);
  $("bins-note").textContent = (result.reasons || []).length
    ? "Not computed for this light: TM-30 takes 380–780 nm (see above)."
    : missing.length ? `Bin${missing.length > 1 ? "s" : ""} ${missing.join(", ")} hold no sample this light shows with a hue: no value (–).` : "";
  const cell = (v, digits) => (v === null ? "—" : v.toFixed(digits));
  $("bin-table").tBodies[0].replaceChildren(...rf.map((_, j) => {
    const row = document.createElement("tr");
    const head = document.createElement("th");
    head.scope = "row"; head.textContent = String(j + 1);
    row.append(head, ...[`${(j * 22.5).toFixed(1)}–${((j + 1) * 22.5).toFixed(1)}`, cell(percent[j], 1),
      cell(rhs[j], 3), cell(rf[j], 1)].map((text) => Object.assign(document.createElement("td"), { textContent: text })));
    return row;
  }));
  const range = (values, digits, unit = "") => {
    const known = values.filter((v) => v !== null);
    return known.length ? `${Math.min(...known).toFixed(digits)}${unit} to ${Math.max(...known).toFixed(digits)}${unit}` : "none";
  };
  $("chart-rcs").setAttribute("aria-description", `16 bars, from ${range(percent, 1, "%")}; the values are in the table below.`);
  $("chart-rhs").setAttribute("aria-description", `16 bars, from ${range(rhs, 3)}; the values are in the table below.`);
  $("chart-rf").setAttribute("aria-description", `16 bars, from ${range(rf, 1)}; the values are in the table below.`);
}

function paint() {
  if (!result) return;
  numbers();
  drawSpd();
  drawGraphic();
  samples();
  drawBins();
}

async function start() {
  const options = await api("/api/lab/light/options");
  kinds = new Map(options.light_kinds.map((k) => [k.name, k]));
  const range = (k) => (k.min_K > 1000 ? `, ≥ ${k.min_K} K` : "");
  const names = [...options.lights.map((n) => [n, n, ""]),
    ...options.light_kinds.map((k) => [k.name, `${k.label} (temperature below${range(k)})`, k.help])];
  $("name").replaceChildren(...names.map(([value, label, title]) =>
    Object.assign(document.createElement("option"), { value, textContent: label, title })));
  $("display").replaceChildren(...options.displays.map((d) => Object.assign(document.createElement("option"), { value: d, textContent: d })));
  state = decode(location.hash);
  if (badExplorer) showError(badExplorer);
  $("kind").addEventListener("change", (e) => commit({ kind: e.target.value }));
  $("name").addEventListener("change", (e) => commit({ name: e.target.value }));
  $("display").addEventListener("change", (e) => commit({ display: e.target.value }));
  $("temperature").addEventListener("input", (e) => {
    state.temperature = Number(e.target.value);
    $("temperature-out").textContent = `${state.temperature} K`;
    request();
  });
  $("temperature").addEventListener("change", (e) => {
    const T = Number(e.target.value);
    state.temperature = lastCommitted.temperature;
    commit({ temperature: T });
  });
  $("add").addEventListener("click", () => commit({ leds: [...state.leds, [580, 30, 0.5]].slice(0, 4) }));
  $("remove").addEventListener("click", () => commit({ leds: state.leds.slice(0, -1) }));
  $("undo").addEventListener("click", undo);
  $("redo").addEventListener("click", redo);
  wireUpload();
  wireCommon(undo, redo);
  window.addEventListener("popstate", () => { state = decode(location.hash); render(); });
  window.addEventListener("resize", paint);
  history.replaceState(null, "", encode(state));
  render();
}

start().catch((error) => showError(error.message));
