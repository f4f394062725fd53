// The thin-film lab. Every number comes from the library: the server sends one table per film,
// model, angle, light and display (POST /api/lab/thinfilm: reflectance, XYZ, xy and display codes
// for thickness 0-1500 nm in 1 nm steps), and the page only looks values up in it, so dragging the
// thickness or animating a draining film repaints in the same frame.

import { $, api, context, css, showError, theme, wireCommon } from "./common.js";

const DEFAULTS = { film: "soap", model: "airy", light: "blackbody:6504", display: "sRGB", angle: 0, d: 350 };
// the library's draining_film(): h(x, t) = 2 sqrt(eta x / (rho g t)), x down from the top (m)
export const DRAIN = { heightM: 0.05, viscosityPaS: 1.0e-3, densityKgM3: 1000.0, g: 9.80665 };

let state = { ...DEFAULTS };
let table = null;
let request = 0;
const undoStack = [];
const redoStack = [];

export function drainThicknessNm(xM, timeS) {
  return 2.0 * Math.sqrt((DRAIN.viscosityPaS * xM) / (DRAIN.densityKgM3 * DRAIN.g * timeS)) * 1e9;
}



function fillSelect(select, options, value) {
  select.replaceChildren(...options.map((o) => {
    const option = document.createElement("option");
    option.value = o.name;
    option.textContent = o.name;
    option.title = o.description;
    return option;
  }));
  select.value = value;
}

function readHash() {
  const params = new URLSearchParams(location.hash.slice(1));
  const next = { ...DEFAULTS };
  for (const key of Object.keys(DEFAULTS)) {
    if (params.has(key)) next[key] = typeof DEFAULTS[key] === "number" ? Number(params.get(key)) : params.get(key);
  }
  if (!Number.isFinite(next.angle) || next.angle < 0 || next.angle > 80) next.angle = DEFAULTS.angle;
  if (!Number.isFinite(next.d) || next.d < 0 || next.d > 1500) next.d = DEFAULTS.d;
  return next;
}

function hashOf(s) {
  return "#" + new URLSearchParams(Object.entries(s).map(([k, v]) => [k, String(v)])).toString();
}

function syncControls() {
  for (const key of ["film", "model", "light", "display"]) $(key).value = state[key];
  $("angle").value = state.angle;
  $("angle-out").textContent = `${state.angle}°`;
  $("thickness").value = state.d;
  $("thickness-out").textContent = `${state.d} nm`;
  $("undo").disabled = undoStack.length === 0;
  $("redo").disabled = redoStack.length === 0;
}

// A change the user can undo: remember the state before it, put the new one in the URL.
function commit(change, push = true) {
  const before = { ...state };
  state = { ...state, ...change };
  if (JSON.stringify(before) === JSON.stringify(state)) return;
  undoStack.push(before);
  redoStack.length = 0;
  if (push) history.pushState(null, "", hashOf(state));
  else history.replaceState(null, "", hashOf(state));
  apply(before);
}

function apply(before) {
  syncControls();
  const needsTable = !table || ["film", "model", "light", "display", "angle"].some((k) => before[k] !== state[k]);
  if (needsTable) loadTable();
  else paint();
}

async function loadTable() {
  const mine = ++request;
  try {
    const next = await api("/api/lab/thinfilm", {
      film: state.film, model: state.model, angle_deg: state.angle, illuminant: state.light, display: state.display,
    });
    if (mine !== request) return; // a newer request is under way
    table = next;
    $("error").hidden = true;
    drawStatic();
    paint();
  } catch (error) {
    showError(`${error.message} — the pictures still show the previous film.`);
  }
}

// ---- drawing ----------------------------------------------------------------------------

// A layer drawn once per table and size (axes, curves), copied under each repaint's marker.
const layers = new Map();
function layer(name, canvas, draw) {
  const key = `${name}:${canvas.clientWidth}x${canvas.clientHeight}`;
  if (!layers.has(key)) {
    const off = document.createElement("canvas");
    off.style.width = `${canvas.clientWidth}px`;
    const ratio = window.devicePixelRatio || 1;
    off.width = Math.max(1, Math.round(canvas.clientWidth * ratio));
    off.height = Math.max(1, Math.round(canvas.clientHeight * ratio));
    const ctx = off.getContext("2d");
    ctx.setTransform(ratio, 0, 0, ratio, 0, 0);
    draw(ctx, canvas.clientWidth, canvas.clientHeight);
    layers.set(key, off);
  }
  return layers.get(key);
}

const hex = (rgb) => "#" + rgb.map((c) => c.toString(16).padStart(2, "0")).join("");

let stripImage = null;
let spectrumTop = 1;

function drawStatic() {
  const n = table.rgb8.length;
  stripImage = document.createElement("canvas");
  stripImage.width = n;
  stripImage.height = 1;
  const sctx = stripImage.getContext("2d");
  const pixels = sctx.createImageData(n, 1);
  table.rgb8.forEach((rgb, i) => pixels.data.set([rgb[0], rgb[1], rgb[2], 255], 4 * i));
  sctx.putImageData(pixels, 0, 0);
  spectrumTop = Math.max(1e-9, ...table.reflectance.map((row) => Math.max(...row)));
  layers.clear();
  const relative = table.model === "two-beam";
  $("spectrum-caption").textContent = relative
    ? "Two-beam factor 1 + β² − 2β cos(2πs/λ) against wavelength (nm): relative, not a reflectance."
    : "Reflectance (%) against wavelength (nm), unpolarised light.";
  const films = { soap: "a soap film in air", oil: "oil on water", mgf2: "MgF₂ on glass", tio2: "TiO₂ on glass" };
  $("model-note").textContent = `${films[table.film] || table.film}, ${table.model} model, ${table.illuminant}, `
    + `${table.display}; colours scaled so the brightest of 0–1500 nm is full white, luminance kept for colours outside the display (seed 000).`;
}

function axes(ctx, box, xTicks, yTicks, xLabel, yLabel) {
  const t = theme($("spectrum"));
  ctx.strokeStyle = t.muted;
  ctx.fillStyle = t.text;
  ctx.lineWidth = 1;
  ctx.font = "11px system-ui, sans-serif";
  ctx.strokeRect(box.x, box.y, box.w, box.h);
  ctx.textAlign = "center";
  for (const [value, position] of xTicks) {
    ctx.beginPath(); ctx.moveTo(position, box.y + box.h); ctx.lineTo(position, box.y + box.h + 4); ctx.stroke();
    ctx.fillText(value, position, box.y + box.h + 15);
  }
  ctx.textAlign = "right";
  for (const [value, position] of yTicks) {
    ctx.beginPath(); ctx.moveTo(box.x - 4, position); ctx.lineTo(box.x, position); ctx.stroke();
    ctx.fillText(value, box.x - 6, position + 4);
  }
  ctx.textAlign = "center";
  ctx.fillText(xLabel, box.x + box.w / 2, box.y + box.h + 30);
  ctx.save(); ctx.translate(12, box.y + box.h / 2); ctx.rotate(-Math.PI / 2); ctx.fillText(yLabel, 0, 0); ctx.restore();
}

function drawSpectrum(i) {
  const { ctx, width, height } = context($("spectrum"));
  const box = { x: 48, y: 10, w: width - 60, h: height - 50 };
  const wl = table.wavelengths_nm;
  const relative = table.model === "two-beam";
  const scale = relative ? 1 : 100;
  const top = spectrumTop * scale;
  const X = (w) => box.x + ((w - wl[0]) / (wl[wl.length - 1] - wl[0])) * box.w;
  const Y = (v) => box.y + box.h - (v / top) * box.h;
  const step = top > 20 ? 10 : top > 5 ? 2 : top > 2 ? 0.5 : top / 4;
  const yTicks = [];
  for (let v = 0; v <= top + 1e-9; v += step) yTicks.push([Number(v.toPrecision(3)).toString(), Y(v)]);
  axes(ctx, box, [400, 450, 500, 550, 600, 650, 700, 750].map((w) => [w, X(w)]), yTicks,
    "wavelength (nm)", relative ? "relative factor" : "reflectance (%)");
  ctx.strokeStyle = theme(ctx.canvas).text;
  ctx.lineWidth = 2;
  ctx.beginPath();
  table.reflectance[i].forEach((v, k) => (k ? ctx.lineTo(X(wl[k]), Y(v * scale)) : ctx.moveTo(X(wl[k]), Y(v * scale))));
  ctx.stroke();
}

function stripBox(width, height) { return { x: 8, y: 6, w: width - 16, h: height - 40 }; }

function drawStripLayer(ctx, width, height) {
  const box = stripBox(width, height);
  ctx.imageSmoothingEnabled = false;
  ctx.drawImage(stripImage, box.x, box.y, box.w, box.h);
  const t = theme($("strip"));
  ctx.fillStyle = t.text;
  ctx.strokeStyle = t.text;
  ctx.font = "11px system-ui, sans-serif";
  const max = table.thickness_nm[table.thickness_nm.length - 1];
  for (let d = 0; d <= max; d += 250) {
    const x = box.x + (d / max) * box.w;
    ctx.beginPath(); ctx.moveTo(x, box.y + box.h); ctx.lineTo(x, box.y + box.h + 4); ctx.stroke();
    ctx.textAlign = d === 0 ? "left" : d + 250 > max ? "right" : "center";
    ctx.fillText(d, x, box.y + box.h + 15);
  }
  ctx.textAlign = "center";
  ctx.fillText("thickness (nm)", box.x + box.w / 2, box.y + box.h + 30);
}

function drawStrip(i) {
  const canvas = $("strip");
  const { ctx, width, height } = context(canvas);
  ctx.drawImage(layer("strip", canvas, drawStripLayer), 0, 0, width, height);
  const box = stripBox(width, height);
  const max = table.thickness_nm[table.thickness_nm.length - 1];
  const x = box.x + (table.thickness_nm[i] / max) * box.w;
  ctx.lineWidth = 3;
  ctx.strokeStyle = "#ffffff";
  ctx.strokeRect(x - 3, box.y - 2, 6, box.h + 4);
  ctx.lineWidth = 1.5;
  ctx.strokeStyle = "#000000";
  ctx.strokeRect(x - 3, box.y - 2, 6, box.h + 4);
}

function diagramScale(width, height) {
  const size = Math.min(width - 56, height - 44);
  const box = { x: 48, y: 8, w: size, h: size };
  return { box, X: (x) => box.x + (x / 0.8) * box.w, Y: (y) => box.y + box.h - (y / 0.9) * box.h };
}

function drawDiagramLayer(ctx, width, height) {
  const { box, X, Y } = diagramScale(width, height);
  const ticks = (values, f) => values.map((v) => [v.toFixed(1), f(v)]);
  axes(ctx, box, ticks([0, 0.2, 0.4, 0.6, 0.8], X), ticks([0, 0.2, 0.4, 0.6, 0.8], Y), "x", "y");
  const t = theme($("diagram"));
  ctx.strokeStyle = t.muted;
  ctx.lineWidth = 1.5;
  ctx.beginPath();
  table.locus_xy.forEach(([x, y], k) => (k ? ctx.lineTo(X(x), Y(y)) : ctx.moveTo(X(x), Y(y))));
  ctx.closePath();
  ctx.stroke();
  let previous = null;
  table.xy.forEach(([x, y], k) => {
    if (x < 0) { previous = null; return; } // no chromaticity (black)
    if (previous) {
      ctx.strokeStyle = css(table.rgb8[k]);
      ctx.beginPath(); ctx.moveTo(X(previous[0]), Y(previous[1])); ctx.lineTo(X(x), Y(y)); ctx.stroke();
    }
    previous = [x, y];
  });
  const [wx, wy] = table.white_xy;
  ctx.strokeStyle = t.text;
  ctx.beginPath(); ctx.moveTo(X(wx) - 5, Y(wy)); ctx.lineTo(X(wx) + 5, Y(wy));
  ctx.moveTo(X(wx), Y(wy) - 5); ctx.lineTo(X(wx), Y(wy) + 5); ctx.stroke();
}

function drawDiagram(i) {
  const canvas = $("diagram");
  const { ctx, width, height } = context(canvas);
  ctx.drawImage(layer("diagram", canvas, drawDiagramLayer), 0, 0, width, height);
  const { X, Y } = diagramScale(width, height);
  const [x, y] = table.xy[i];
  if (x >= 0) {
    const t = theme(canvas);
    ctx.lineWidth = 3; ctx.strokeStyle = t.bg;
    ctx.beginPath(); ctx.arc(X(x), Y(y), 6, 0, 2 * Math.PI); ctx.stroke();
    ctx.lineWidth = 1.5; ctx.strokeStyle = t.text;
    ctx.beginPath(); ctx.arc(X(x), Y(y), 6, 0, 2 * Math.PI); ctx.stroke();
  }
}

function numbers(i) {
  const rgb = table.rgb8[i];
  const [X, Y, Z] = table.XYZ[i];
  const [x, y] = table.xy[i];
  const rows = [
    ["thickness", `${table.thickness_nm[i]} nm`],
    ["x, y", x < 0 ? "— (black: no chromaticity)" : `${x.toFixed(4)}, ${y.toFixed(4)}`],
    ["Y", `${Y.toFixed(2)} (perfect reflector = 100)`],
    ["X, Z", `${X.toFixed(2)}, ${Z.toFixed(2)}`],
    [`${table.display} codes`, `${rgb.join(", ")} (0–255)`],
    ["hex", hex(rgb)],
  ];
  $("numbers").replaceChildren(...rows.flatMap(([term, value]) => {
    const dt = document.createElement("dt");
    dt.textContent = term;
    const dd = document.createElement("dd");
    dd.textContent = value;
    return [dt, dd];
  }));
}

function paint() {
  if (!table) return;
  const i = Math.min(table.rgb8.length - 1, Math.max(0, Math.round(state.d)));
  const rgb = table.rgb8[i];
  $("patch").style.background = css(rgb);
  $("patch").setAttribute("aria-label", `Colour of a ${table.thickness_nm[i]} nm film: ${hex(rgb)}`);
  numbers(i);
  drawSpectrum(i);
  drawStrip(i);
  drawDiagram(i);
  drawDrain(lastDrainTime);
}

// ---- the draining film -------------------------------------------------------------------
const TIME_START_S = (() => { // the bottom edge is 1500 nm thick: the table's end
  const bottom = drainThicknessNm(DRAIN.heightM, 1);
  return (bottom / 1500) ** 2;
})();
const TIME_END_S = TIME_START_S * 400; // the top third has turned black by then
const LOOP_MS = 20000;
let lastDrainTime = TIME_START_S * 4;
let playing = false;
let startedAt = 0;

function drawDrain(timeS) {
  if (!table) return;
  const canvas = $("drain");
  const ratio = window.devicePixelRatio || 1;
  const width = Math.max(1, Math.round(canvas.clientWidth * ratio));
  const height = Math.max(1, Math.round(canvas.clientHeight * ratio));
  if (canvas.width !== width || canvas.height !== height) { canvas.width = width; canvas.height = height; }
  const ctx = canvas.getContext("2d");
  const rows = canvas.height; // one thickness per pixel row, at the screen's resolution
  for (let row = 0; row < rows; row++) {
    const d = drainThicknessNm(((row + 0.5) / rows) * DRAIN.heightM, timeS);
    const i = Math.min(table.rgb8.length - 1, Math.round(d));
    ctx.fillStyle = css(table.rgb8[i]);
    ctx.fillRect(0, row, canvas.width, 1);
  }
  const hours = timeS / 3600;
  $("drain-time").textContent = `t = ${hours < 10 ? hours.toFixed(1) : hours.toFixed(0)} h after the film was drawn`;
}

function frame(now) {
  if (!playing) return;
  const phase = ((now - startedAt) % LOOP_MS) / LOOP_MS;
  lastDrainTime = TIME_START_S * (TIME_END_S / TIME_START_S) ** phase;
  drawDrain(lastDrainTime);
  requestAnimationFrame(frame);
}

function toggleFullWindow(on = !$("drain").classList.contains("full-window")) {
  $("drain").classList.toggle("full-window", on);
  $("full").textContent = on ? "Exit full window (Esc)" : "Full window";
  $("full").classList.toggle("floating", on);
  drawDrain(lastDrainTime);
}

function togglePlay() {
  playing = !playing;
  $("play").textContent = playing ? "Pause" : "Play";
  $("play").setAttribute("aria-pressed", String(playing));
  if (playing) {
    const phase = Math.log(lastDrainTime / TIME_START_S) / Math.log(TIME_END_S / TIME_START_S);
    startedAt = performance.now() - Math.max(0, phase) * LOOP_MS;
    requestAnimationFrame(frame);
  }
}

// ---- wiring ------------------------------------------------------------------------------
function undo() {
  if (!undoStack.length) return;
  redoStack.push({ ...state });
  const before = { ...state };
  state = undoStack.pop();
  history.replaceState(null, "", hashOf(state));
  apply(before);
}

function redo() {
  if (!redoStack.length) return;
  undoStack.push({ ...state });
  const before = { ...state };
  state = redoStack.pop();
  history.replaceState(null, "", hashOf(state));
  apply(before);
}

async function start() {
  const options = await api("/api/lab/thinfilm/options");
  state = readHash();
  fillSelect($("film"), options.films, state.film);
  fillSelect($("model"), options.models, state.model);
  fillSelect($("light"), options.illuminants, state.light);
  fillSelect($("display"), options.displays, state.display);
  for (const key of ["film", "model", "light", "display"]) {
    $(key).addEventListener("change", (e) => commit({ [key]: e.target.value }));
  }
  $("angle").addEventListener("input", (e) => { $("angle-out").textContent = `${e.target.value}°`; });
  $("angle").addEventListener("change", (e) => commit({ angle: Number(e.target.value) }));
  let dragStart = null;
  $("thickness").addEventListener("input", (e) => {
    if (dragStart === null) dragStart = { ...state };
    state.d = Number(e.target.value); // live: a lookup, repainted in this frame
    $("thickness-out").textContent = `${state.d} nm`;
    paint();
  });
  $("thickness").addEventListener("change", (e) => {
    const before = dragStart || { ...state };
    dragStart = null;
    state = { ...before };
    commit({ d: Number(e.target.value) }, false);
  });
  $("undo").addEventListener("click", undo);
  $("redo").addEventListener("click", redo);
  $("play").addEventListener("click", togglePlay);
  $("full").addEventListener("click", () => toggleFullWindow());
  $("drain").addEventListener("click", togglePlay);
  document.addEventListener("keydown", (e) => { if (e.key === "Escape") toggleFullWindow(false); });
  wireCommon(undo, redo);
  window.addEventListener("popstate", () => { const before = { ...state }; state = readHash(); apply(before); });
  window.addEventListener("resize", () => paint());
  syncControls();
  history.replaceState(null, "", hashOf(state));
  await loadTable();
  document.body.dataset.ready = "true";
}

start().catch((error) => showError(error.message));
