// The object-colour solid lab. The library sends the solid (MacAdam limits in CIELAB with their
// colours, the display cube's edges), a section at Y and a sample's metamer mismatch region; the
// page only projects and draws them (a rotatable orthographic view on a 2-D canvas).
// It turns by mouse or finger (Pointer Events, captured; two fingers pinch to zoom), fits its canvas
// at any width (the view is scaled to the solid's largest radius, so no angle clips it), and a
// click or tap on a point of the solid (a MacAdam limit's point, the display cube's edge, the
// sample) shows its numbers; the Point controls pick the same points by keyboard.

import { $, api, context, css, showError, theme, wireCommon, drawXyAxes, xyFrame, xyPath } from "./common.js";

const DEFAULTS = { light: "D65", display: "sRGB", Y: 50, sample: 1, second: "A", yaw: 35, pitch: 20, mismatch: 0, r: "" };
// A sample handed over by the explorer (issue 28 item 6): r = "<step nm>:<level>,<level>,…", levels 0–30 on
// 400–700 nm (js/handoff.js writes it); sample 0 is that sample.
const HANDED_STEPS = [10, 5, 2, 1];
function handedSample(r) {
  const m = /^(10|5|2|1):([0-9.,]+)$/.exec(r || "");
  if (!m) return null;
  const step = Number(m[1]), levels = m[2].split(",").map(Number);
  if (!HANDED_STEPS.includes(step) || levels.length !== Math.round(300 / step) + 1) return null;
  if (!levels.every((v) => Number.isFinite(v) && v >= 0 && v <= 30)) return null;
  return { step, levels };
}
const HANDED_MESSAGE = "The sample in this address (r=…) is not levels 0–30 on 400–700 nm at 10, 5, 2 or 1 nm; "
  + "the CIE test-colour sample is shown instead.";

/** The state of an address, its hand-off checked: a bad one is said once and dropped. */
function checked(next) {
  if (next.r && !handedSample(next.r)) { showError(HANDED_MESSAGE); next.r = ""; }
  if (!next.r && next.sample === 0) next.sample = 1;
  if (next.r && !(next.sample >= 0 && next.sample <= 14)) next.sample = 0;
  return next;
}

function sampleOptions() {
  const values = Array.from({ length: 14 }, (_, i) => i + 1), labels = values.map((i) => `TCS${String(i).padStart(2, "0")}`);
  if (state.r) { values.unshift(0); labels.unshift("from the explorer"); }
  $("sample").replaceChildren(...values.map((v, i) =>
    Object.assign(document.createElement("option"), { value: String(v), textContent: labels[i] })));
}

let state = { ...DEFAULTS };
let solid = null;
let section = null;
let region = null;
const undoStack = [];
const redoStack = [];
let zoom = 1;  // the view's magnification (pinch, + and − buttons); not part of the URL
let picked = null;  // {kind: "level", i, h} | {kind: "cube", e, k} | {kind: "sample"}
window.__solid = { get state() { return state; }, get solid() { return solid; }, get region() { return region; },
  get picked() { return picked; }, get zoom() { return zoom; }, view: () => view(), pickAt: (x, y) => pickAt(x, y) };

function decode(hash) {
  const params = new URLSearchParams(hash.slice(1));
  const next = { ...DEFAULTS };
  for (const key of Object.keys(DEFAULTS)) {
    if (!params.has(key)) continue;
    next[key] = typeof DEFAULTS[key] === "number" ? Number(params.get(key)) : params.get(key);
    if (typeof DEFAULTS[key] === "number" && !Number.isFinite(next[key])) next[key] = DEFAULTS[key];
  }
  return next;
}

const encode = (s) => "#" + new URLSearchParams(Object.entries(s).map(([k, v]) => [k, String(v)])).toString();
function request(s) {
  const handed = s.sample === 0 ? handedSample(s.r) : null;
  const body = { illuminant: s.light, display: s.display, Y: s.Y, sample: handed ? 1 : s.sample, second_illuminant: s.second };
  return handed ? { ...body, levels: handed.levels, levels_step_nm: handed.step } : body;
}

function commit(change) {
  const before = { ...state };
  state = { ...state, ...change };
  if (JSON.stringify(before) === JSON.stringify(state)) return;
  undoStack.push(before);
  redoStack.length = 0;
  history.pushState(null, "", encode(state));
  load(before);
}

function restore(next) {
  const before = { ...state };
  state = next;
  history.replaceState(null, "", encode(state));
  load(before);
}

function undo() { if (undoStack.length) { redoStack.push({ ...state }); restore(undoStack.pop()); } }
function redo() { if (redoStack.length) { undoStack.push({ ...state }); restore(redoStack.pop()); } }

function syncControls() {
  for (const key of ["light", "display", "sample", "second"]) $(key).value = String(state[key]);
  $("Y").value = state.Y;
  $("Y-out").textContent = String(state.Y);
  $("undo").disabled = !undoStack.length;
  $("redo").disabled = !redoStack.length;
}

async function load(before = null) {
  syncControls();
  const changed = (keys) => !before || keys.some((k) => before[k] !== state[k]);
  try {
    if (!solid || changed(["light", "display"])) {
      $("status").textContent = "Computing the solid…";
      solid = await api("/api/lab/solid", request(state));
      fillPickLevels();
    }
    if (!section || changed(["light", "display", "Y"])) section = await api("/api/lab/solid/section", request(state));
    if (state.mismatch && (!region || changed(["light", "display", "sample", "second", "mismatch", "r"]))) {
      $("status").textContent = "Computing the metamer mismatch region (a few seconds)…";
      region = await api("/api/lab/solid/mismatch", request(state));
    }
    if (!state.mismatch) region = null;
    $("status").textContent = region
      ? `Sample ${region.sample}: matched under ${region.illuminant}, its metamers under ${region.second_illuminant} fill the purple region, up to ΔE*ab ${region.region_dEab_max.toFixed(1)} from the sample's own colour.`
      : "";
    $("error").hidden = true;
    if (picked && !pointData(picked)) picked = null;
    choosePoint(picked);
    paint();
    document.body.dataset.ready = "true";
  } catch (error) {
    $("status").textContent = "";
    showError(error.message);
  }
}

function fillPickLevels() {
  const select = $("pick-level"), keep = select.value;
  select.replaceChildren(...solid.levels.map((level, i) =>
    Object.assign(document.createElement("option"), { value: String(i), textContent: `Y = ${level.Y} %` })));
  $("pick-hue").max = String(solid.levels[0].lab.length - 1);
  if (keep) select.value = keep;
}

// ---- drawing ----------------------------------------------------------------------------


// The mismatch region is convex; its boundary points come in the order of their directions on a
// sphere, so a picture of it is the convex hull of their projections (Andrew's monotone chain).
export function hull(points) {
  const p = [...points].sort((a, b) => a[0] - b[0] || a[1] - b[1]);
  if (p.length < 3) return p;
  const cross = (o, a, b) => (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
  const half = (list) => {
    const out = [];
    for (const q of list) {
      while (out.length >= 2 && cross(out[out.length - 2], out[out.length - 1], q) <= 0) out.pop();
      out.push(q);
    }
    out.pop();
    return out;
  };
  return [...half(p), ...half(p.reverse())];
}

export function project([L, a, b], yawDeg, pitchDeg) {
  // orthographic view: yaw turns about the L* axis, pitch tilts it towards the viewer
  const yaw = (yawDeg * Math.PI) / 180, pitch = (pitchDeg * Math.PI) / 180;
  const x = a * Math.cos(yaw) - b * Math.sin(yaw);
  const depth = a * Math.sin(yaw) + b * Math.cos(yaw);
  const y = (L - 50) * Math.cos(pitch) - depth * Math.sin(pitch);
  return [x, y];
}

/** The solid's largest distance from the view's centre (L* 50, a* = b* = 0): a scale that fits
 * it fits every angle (an orthographic view never draws a point further out than this). */
function radius() {
  let r = 110 * 0.5 + 60;  // the L* axis (0 to 110) and its label
  const reach = ([L, a, b]) => { r = Math.max(r, Math.hypot(L - 50, a, b)); };
  for (const level of solid.levels) level.lab.forEach(reach);
  for (const edge of solid.cube_edges_lab) edge.forEach(reach);
  if (region) region.region_lab.forEach(reach);
  return r;
}

/** The view of the solid canvas in CSS pixels: its size and the map from L*a*b* to a pixel. */
function view() {
  const canvas = $("solid");
  const width = canvas.clientWidth, height = canvas.clientHeight;
  const scale = (zoom * (Math.min(width, height) / 2 - 14)) / radius();
  const P = (lab) => { const [x, y] = project(lab, state.yaw, state.pitch); return [width / 2 + x * scale, height / 2 - y * scale]; };
  return { width, height, scale, P };
}

/** Every point that can be picked, with what the page says about it. */
function pickables() {
  const out = [];
  solid.levels.forEach((level, i) => level.lab.forEach((lab, h) => out.push({ kind: "level", i, h, lab })));
  solid.cube_edges_lab.forEach((edge, e) => edge.forEach((lab, k) => out.push({ kind: "cube", e, k, lab })));
  if (region) out.push({ kind: "sample", lab: region.sample_lab });
  return out;
}

/** Pick the point nearest to (x, y) (CSS pixels in the canvas) within 18 px; null when none. */
function pickAt(x, y) {
  const { P } = view();
  let best = null, bestD = 18;
  for (const point of pickables()) {
    const [px, py] = P(point.lab);
    const d = Math.hypot(px - x, py - y);
    if (d < bestD) { best = point; bestD = d; }
  }
  choosePoint(best ? { kind: best.kind, i: best.i, h: best.h, e: best.e, k: best.k } : null);
  return picked;
}

function pointData(p) {
  if (!p || !solid) return null;
  if (p.kind === "level") {
    const level = solid.levels[p.i];
    return { lab: level.lab[p.h], rgb8: level.rgb8[p.h],
      text: `MacAdam limit at Y = ${level.Y} %, hue ${p.h + 1} of ${level.lab.length}` };
  }
  if (p.kind === "cube") {
    return { lab: solid.cube_edges_lab[p.e][p.k], rgb8: null, text: `edge ${p.e + 1} of the ${solid.display} cube` };
  }
  if (p.kind === "sample" && region) {
    return { lab: region.sample_lab, rgb8: region.rgb8_second, text: `sample ${region.sample} under ${region.second_illuminant}` };
  }
  return null;
}

/** Show (and mark) the picked point; the Point controls follow it. */
function choosePoint(p) {
  picked = p && pointData(p) ? p : null;
  const data = pointData(picked);
  $("pick-out").textContent = data
    ? `${data.text}: L* ${data.lab[0].toFixed(1)}, a* ${data.lab[1].toFixed(1)}, b* ${data.lab[2].toFixed(1)}`
      + (data.rgb8 ? `; shown as rgb(${data.rgb8.join(", ")})` : "")
    : "Click or tap a point of the solid, or choose one here.";
  $("pick-swatch").style.background = data && data.rgb8 ? css(data.rgb8) : "transparent";
  $("pick-swatch").hidden = !(data && data.rgb8);
  if (picked && picked.kind === "level") { $("pick-level").value = String(picked.i); $("pick-hue").value = String(picked.h); }
  if (solid) drawSolid();
}

/** The metamer mismatch region's purple: light enough to stand out on the theme's dark panel. */
const REGION = "#c58af9", REGION_FILL = "rgba(197, 138, 249, 0.25)";

function drawSolid() {
  const { ctx } = context($("solid"));
  const { P } = view();
  const t = theme(ctx.canvas);
  ctx.lineWidth = 1;
  ctx.strokeStyle = t.muted;
  for (const [from, to, label] of [[[0, -100, 0], [0, 100, 0], "a*"], [[0, 0, -100], [0, 0, 100], "b*"], [[0, 0, 0], [110, 0, 0], "L*"]]) {
    const p = P(from), q = P(to);
    ctx.beginPath(); ctx.moveTo(...p); ctx.lineTo(...q); ctx.stroke();
    ctx.fillStyle = t.text; ctx.font = "12px system-ui, sans-serif"; ctx.fillText(label, q[0] + 4, q[1]);
  }
  const levels = solid.levels;
  ctx.strokeStyle = t.line;
  for (let h = 0; h < levels[0].lab.length; h += 6) { // meridians
    ctx.beginPath();
    levels.forEach((level, i) => { const p = P(level.lab[h]); i ? ctx.lineTo(...p) : ctx.moveTo(...p); });
    ctx.stroke();
  }
  ctx.lineWidth = 2.5;
  for (const level of levels) {
    const n = level.lab.length;
    for (let k = 0; k < n; k++) {
      ctx.strokeStyle = css(level.rgb8[k]);
      ctx.beginPath(); ctx.moveTo(...P(level.lab[k])); ctx.lineTo(...P(level.lab[(k + 1) % n])); ctx.stroke();
    }
  }
  ctx.lineWidth = 1.5;
  ctx.strokeStyle = t.text;
  ctx.setLineDash([4, 3]);
  for (const edge of solid.cube_edges_lab) {
    ctx.beginPath();
    edge.forEach((lab, k) => (k ? ctx.lineTo(...P(lab)) : ctx.moveTo(...P(lab))));
    ctx.stroke();
  }
  ctx.setLineDash([]);
  if (region) {
    ctx.strokeStyle = REGION; ctx.lineWidth = 2; ctx.fillStyle = REGION_FILL;
    ctx.beginPath();
    hull(region.region_lab.map(P)).forEach((p, k) => (k ? ctx.lineTo(...p) : ctx.moveTo(...p)));
    ctx.closePath(); ctx.fill(); ctx.stroke();
    const [sx, sy] = P(region.sample_lab);
    ctx.fillStyle = REGION; ctx.beginPath(); ctx.arc(sx, sy, 4, 0, 2 * Math.PI); ctx.fill();
  }
  const mark = pointData(picked);
  if (mark) {  // the picked point: a ring, dark inside light, visible on any colour
    const [px, py] = P(mark.lab);
    for (const [colour, width, r] of [[t.bg, 5, 8], [t.text, 2, 8]]) {
      ctx.strokeStyle = colour; ctx.lineWidth = width; ctx.beginPath(); ctx.arc(px, py, r, 0, 2 * Math.PI); ctx.stroke();
    }
  }
}

function drawSection() {
  const { ctx, width, height } = context($("section"));
  const frame = xyFrame(width, height);
  const { box, X, Y } = frame;
  drawXyAxes(ctx, frame);
  const t = theme(ctx.canvas);
  const path = (points, close) => xyPath(ctx, frame, points, close);
  ctx.strokeStyle = t.muted; ctx.lineWidth = 1.5; path(section.locus_xy, true);
  ctx.strokeStyle = t.text; path(section.display_xy, true);
  ctx.strokeStyle = t.warn; ctx.lineWidth = 2.5; path(section.macadam_xy, true);
  const [wx, wy] = section.white_xy;
  ctx.strokeStyle = t.text; ctx.lineWidth = 1.5;
  ctx.beginPath(); ctx.moveTo(X(wx) - 5, Y(wy)); ctx.lineTo(X(wx) + 5, Y(wy)); ctx.moveTo(X(wx), Y(wy) - 5);
  ctx.lineTo(X(wx), Y(wy) + 5); ctx.stroke();
  if (region) {
    ctx.strokeStyle = REGION; ctx.lineWidth = 2; path(hull(region.region_xy), true);
    ctx.fillStyle = REGION; ctx.beginPath(); ctx.arc(X(region.sample_xy[0]), Y(region.sample_xy[1]), 4, 0, 2 * Math.PI); ctx.fill();
  }
  ctx.fillStyle = t.text; ctx.textAlign = "left"; ctx.font = "12px system-ui, sans-serif";
  ctx.fillText(`Y = ${section.Y}`, box.x + 8, box.y + 16);
}

function paint() {
  if (solid) drawSolid();
  if (section) drawSection();
}

/** Mouse, pen and finger on the solid (Pointer Events, captured: the drag goes on outside the
 * canvas): one pointer turns it, two pinch to zoom, a press that barely moves picks a point. */
function wirePointer(canvas) {
  const pointers = new Map();
  let drag = null, pinch = null;
  const local = (e) => { const r = canvas.getBoundingClientRect(); return [e.clientX - r.left, e.clientY - r.top]; };
  canvas.addEventListener("pointerdown", (e) => {
    if (!solid) return;
    e.preventDefault();
    canvas.setPointerCapture(e.pointerId);
    pointers.set(e.pointerId, [e.clientX, e.clientY]);
    if (pointers.size === 1) {
      drag = { x: e.clientX, y: e.clientY, yaw: state.yaw, pitch: state.pitch, before: { ...state }, moved: 0 };
    } else if (pointers.size === 2) {
      const [a, b] = [...pointers.values()];
      pinch = { d: Math.hypot(a[0] - b[0], a[1] - b[1]) || 1, zoom };
      if (drag) drag.moved = Infinity;  // two fingers never pick
    }
  });
  canvas.addEventListener("pointermove", (e) => {
    if (!pointers.has(e.pointerId)) return;
    pointers.set(e.pointerId, [e.clientX, e.clientY]);
    if (pinch && pointers.size >= 2) {
      const [a, b] = [...pointers.values()];
      zoom = Math.max(0.5, Math.min(4, pinch.zoom * Math.hypot(a[0] - b[0], a[1] - b[1]) / pinch.d));
      drawSolid();
      return;
    }
    if (!drag) return;
    drag.moved = Math.max(drag.moved, Math.hypot(e.clientX - drag.x, e.clientY - drag.y));
    state.yaw = (drag.yaw + (e.clientX - drag.x) * 0.5 + 360) % 360;
    state.pitch = Math.max(-80, Math.min(80, drag.pitch + (e.clientY - drag.y) * 0.5));
    drawSolid();
  });
  const end = (e) => {
    if (!pointers.delete(e.pointerId)) return;
    if (pointers.size < 2) pinch = null;
    if (!drag || pointers.size) return;
    const { yaw, pitch } = state;
    const tap = drag.moved < 6 && e.type === "pointerup";
    state = drag.before;
    drag = null;
    if (tap) { pickAt(...local(e)); return; }
    commit({ yaw: Math.round(yaw), pitch: Math.round(pitch) });
  };
  canvas.addEventListener("pointerup", end);
  canvas.addEventListener("pointercancel", end);
}

async function start() {
  const options = await api("/api/lab/solid/options");
  const fill = (select, values, labels = values) => select.replaceChildren(
    ...values.map((v, i) => Object.assign(document.createElement("option"), { value: String(v), textContent: labels[i] })));
  fill($("light"), options.illuminants);
  fill($("second"), options.illuminants);
  fill($("display"), options.displays);
  state = checked(decode(location.hash));
  sampleOptions();
  for (const [id, key] of [["light", "light"], ["display", "display"], ["second", "second"]]) {
    $(id).addEventListener("change", (e) => commit({ [key]: e.target.value }));
  }
  $("sample").addEventListener("change", (e) => commit({ sample: Number(e.target.value) }));
  $("Y").addEventListener("input", (e) => { $("Y-out").textContent = e.target.value; });
  $("Y").addEventListener("change", (e) => commit({ Y: Number(e.target.value) }));
  $("mismatch").addEventListener("click", () => commit({ mismatch: 1 }));
  for (const button of document.querySelectorAll("[data-turn]")) {
    button.addEventListener("click", () => {
      const [dy, dp] = button.dataset.turn.split(",").map(Number);
      commit({ yaw: (state.yaw + dy + 360) % 360, pitch: Math.max(-80, Math.min(80, state.pitch + dp)) });
    });
  }
  wirePointer($("solid"));
  const keyPick = () => choosePoint({ kind: "level", i: Number($("pick-level").value), h: Number($("pick-hue").value) });
  $("pick-level").addEventListener("change", keyPick);
  $("pick-hue").addEventListener("input", keyPick);
  for (const button of document.querySelectorAll("[data-zoom]")) {
    button.addEventListener("click", () => { zoom = Math.max(0.5, Math.min(4, zoom * Number(button.dataset.zoom))); drawSolid(); });
  }
  if (window.ResizeObserver) new ResizeObserver(() => paint()).observe($("solid"));
  $("undo").addEventListener("click", undo);
  $("redo").addEventListener("click", redo);
  wireCommon(undo, redo);
  window.addEventListener("popstate", () => { restore(checked(decode(location.hash))); sampleOptions(); syncControls(); });
  window.addEventListener("resize", paint);
  history.replaceState(null, "", encode(state));
  await load();
}

start().catch((error) => showError(error.message));
