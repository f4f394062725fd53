// The object-colour solid lab. The library sends the solid (MacAdam limits in CIELAB with their
// colours, the display cube's edges), a section at Y and a sample's metamer mismatch region; the
// page only projects and draws them (a rotatable orthographic view on a 2-D canvas).

import { $, api, context, css, showError, wireCommon, drawXyAxes, xyFrame, xyPath } from "./common.js";

const DEFAULTS = { light: "D65", display: "sRGB", Y: 50, sample: 1, second: "A", yaw: 35, pitch: 20, mismatch: 0 };

let state = { ...DEFAULTS };
let solid = null;
let section = null;
let region = null;
const undoStack = [];
const redoStack = [];



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
const request = (s) => ({ illuminant: s.light, display: s.display, Y: s.Y, sample: s.sample, second_illuminant: s.second });

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
    }
    if (!section || changed(["light", "display", "Y"])) section = await api("/api/lab/solid/section", request(state));
    if (state.mismatch && (!region || changed(["light", "display", "sample", "second", "mismatch"]))) {
      $("status").textContent = "Computing the metamer mismatch region (a few seconds)…";
      region = await api("/api/lab/solid/mismatch", request(state));
    }
    if (!state.mismatch) region = null;
    $("status").textContent = region
      ? `Sample ${region.sample}: matched under ${region.illuminant}, its metamers under ${region.second_illuminant} fill the purple region.`
      : "";
    $("error").hidden = true;
    paint();
    document.body.dataset.ready = "true";
  } catch (error) {
    $("status").textContent = "";
    showError(error.message);
  }
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

function drawSolid() {
  const { ctx, width, height } = context($("solid"));
  const scale = Math.min(width, height) / 260;
  const P = (lab) => { const [x, y] = project(lab, state.yaw, state.pitch); return [width / 2 + x * scale, height / 2 - y * scale]; };
  ctx.lineWidth = 1;
  ctx.strokeStyle = "#9a9aa5";
  for (const [from, to, label] of [[[0, -100, 0], [0, 100, 0], "a*"], [[0, 0, -100], [0, 0, 100], "b*"], [[0, 0, 0], [110, 0, 0], "L*"]]) {
    const p = P(from), q = P(to);
    ctx.beginPath(); ctx.moveTo(...p); ctx.lineTo(...q); ctx.stroke();
    ctx.fillStyle = "#1b1b1f"; ctx.font = "12px system-ui, sans-serif"; ctx.fillText(label, q[0] + 4, q[1]);
  }
  const levels = solid.levels;
  ctx.strokeStyle = "rgba(60, 60, 70, 0.35)";
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
  ctx.strokeStyle = "#000000";
  ctx.setLineDash([4, 3]);
  for (const edge of solid.cube_edges_lab) {
    ctx.beginPath();
    edge.forEach((lab, k) => (k ? ctx.lineTo(...P(lab)) : ctx.moveTo(...P(lab))));
    ctx.stroke();
  }
  ctx.setLineDash([]);
  if (region) {
    ctx.strokeStyle = "#6a1b9a"; ctx.lineWidth = 2; ctx.fillStyle = "rgba(106, 27, 154, 0.25)";
    ctx.beginPath();
    hull(region.region_lab.map(P)).forEach((p, k) => (k ? ctx.lineTo(...p) : ctx.moveTo(...p)));
    ctx.closePath(); ctx.fill(); ctx.stroke();
    const [sx, sy] = P(region.sample_lab);
    ctx.fillStyle = "#6a1b9a"; ctx.beginPath(); ctx.arc(sx, sy, 4, 0, 2 * Math.PI); ctx.fill();
  }
}

function drawSection() {
  const { ctx, width, height } = context($("section"));
  const frame = xyFrame(width, height);
  const { box, X, Y } = frame;
  drawXyAxes(ctx, frame);
  const path = (points, close) => xyPath(ctx, frame, points, close);
  ctx.strokeStyle = "#5b5b66"; ctx.lineWidth = 1.5; path(section.locus_xy, true);
  ctx.strokeStyle = "#000000"; path(section.display_xy, true);
  ctx.strokeStyle = "#c05600"; ctx.lineWidth = 2.5; path(section.macadam_xy, true);
  const [wx, wy] = section.white_xy;
  ctx.strokeStyle = "#1b1b1f"; ctx.lineWidth = 1.5;
  ctx.beginPath(); ctx.moveTo(X(wx) - 5, Y(wy)); ctx.lineTo(X(wx) + 5, Y(wy)); ctx.moveTo(X(wx), Y(wy) - 5);
  ctx.lineTo(X(wx), Y(wy) + 5); ctx.stroke();
  if (region) {
    ctx.strokeStyle = "#6a1b9a"; ctx.lineWidth = 2; path(hull(region.region_xy), true);
    ctx.fillStyle = "#6a1b9a"; ctx.beginPath(); ctx.arc(X(region.sample_xy[0]), Y(region.sample_xy[1]), 4, 0, 2 * Math.PI); ctx.fill();
  }
  ctx.fillStyle = "#1b1b1f"; ctx.textAlign = "left"; ctx.font = "12px system-ui, sans-serif";
  ctx.fillText(`Y = ${section.Y}`, box.x + 8, box.y + 16);
}

function paint() {
  if (solid) drawSolid();
  if (section) drawSection();
}

async function start() {
  const options = await api("/api/lab/solid/options");
  const fill = (select, values, labels = values) => select.replaceChildren(
    ...values.map((v, i) => Object.assign(document.createElement("option"), { value: String(v), textContent: labels[i] })));
  fill($("light"), options.illuminants);
  fill($("second"), options.illuminants);
  fill($("display"), options.displays);
  fill($("sample"), Array.from({ length: 14 }, (_, i) => i + 1), Array.from({ length: 14 }, (_, i) => `TCS${String(i + 1).padStart(2, "0")}`));
  state = decode(location.hash);
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
  let drag = null;
  $("solid").addEventListener("pointerdown", (e) => { drag = { x: e.clientX, y: e.clientY, yaw: state.yaw, pitch: state.pitch, before: { ...state } }; $("solid").setPointerCapture(e.pointerId); });
  $("solid").addEventListener("pointermove", (e) => {
    if (!drag) return;
    state.yaw = (drag.yaw + (e.clientX - drag.x) * 0.5 + 360) % 360;
    state.pitch = Math.max(-80, Math.min(80, drag.pitch + (e.clientY - drag.y) * 0.5));
    drawSolid();
  });
  $("solid").addEventListener("pointerup", () => {
    if (!drag) return;
    const { yaw, pitch } = state;
    state = drag.before;
    drag = null;
    commit({ yaw: Math.round(yaw), pitch: Math.round(pitch) });
  });
  $("undo").addEventListener("click", undo);
  $("redo").addEventListener("click", redo);
  wireCommon(undo, redo);
  window.addEventListener("popstate", () => restore(decode(location.hash)));
  window.addEventListener("resize", paint);
  history.replaceState(null, "", encode(state));
  await load();
}

start().catch((error) => showError(error.message));
