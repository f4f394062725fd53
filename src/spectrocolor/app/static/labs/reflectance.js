// The smoothest-reflectance lab (seed 004). The page holds a colour (x, y, Y) and a light; the
// library answers with the three smoothest reflectances, the brightest object colour of the
// chromaticity and the domain of validity (POST /api/lab/reflectance), and the MacAdam limit at Y
// (POST /api/lab/reflectance/macadam). Nothing is computed here but the drawing.

import { $, api, context, css, fmt, showError, theme, wireCommon, drawXyAxes, xyFrame, xyPath } from "./common.js";

const DEFAULTS = { light: "D65", step: "5", x: 0.45, y: 0.4, Y: 30 };

let state = { ...DEFAULTS };
let result = null;
let macadam = null;
let inflight = false;
let dirty = false;
const undoStack = [];
const redoStack = [];



function decode(hash, steps) {
  const params = new URLSearchParams(hash.slice(1));
  const next = { ...DEFAULTS };
  if (params.has("light")) next.light = params.get("light");
  if (steps.includes(params.get("step"))) next.step = params.get("step");
  for (const key of ["x", "y", "Y"]) {
    const v = Number(params.get(key));
    if (params.has(key) && Number.isFinite(v)) next[key] = v;
  }
  return next;
}

const encode = (s) => "#" + new URLSearchParams(Object.entries(s).map(([k, v]) => [k, String(v)])).toString();
const body = (s) => ({ x: s.x, y: s.y, Y: s.Y, illuminant: s.light, step_nm: s.step });

function commit(change, replace = false) {
  const before = { ...state };
  state = { ...state, ...change };
  if (JSON.stringify(before) === JSON.stringify(state)) return;
  if (!replace) { undoStack.push(before); redoStack.length = 0; }
  history[replace ? "replaceState" : "pushState"](null, "", encode(state));
  render();
}

function undo() {
  if (!undoStack.length) return;
  redoStack.push({ ...state });
  state = undoStack.pop();
  history.replaceState(null, "", encode(state));
  render();
}

function redo() {
  if (!redoStack.length) return;
  undoStack.push({ ...state });
  state = redoStack.pop();
  history.replaceState(null, "", encode(state));
  render();
}

function syncControls() {
  $("light").value = state.light;
  $("step").value = state.step;
  $("x").value = state.x;
  $("y").value = state.y;
  $("Y").value = state.Y;
  $("Y-out").textContent = `${state.Y}`;
  $("undo").disabled = !undoStack.length;
  $("redo").disabled = !redoStack.length;
}

function render() {
  syncControls();
  request();
}

async function request() {
  if (inflight) { dirty = true; return; }
  inflight = true;
  dirty = false;
  const asked = JSON.stringify(body(state));
  try {
    const [next, limit] = await Promise.all([
      api("/api/lab/reflectance", body(state)),
      state.Y < 100 ? api("/api/lab/reflectance/macadam", body(state)) : Promise.resolve({ xy: [] }),
    ]);
    result = next;
    macadam = limit.xy;
    $("error").hidden = true;
    paint();
  } catch (error) {
    showError(`${error.message} — the pictures still show the previous colour.`);
  } finally {
    inflight = false;
    if (dirty || JSON.stringify(body(state)) !== asked) request();
    else document.body.dataset.ready = "true";
  }
}

// ---- drawing ----------------------------------------------------------------------------

const ranges = (runs) => runs.map(([a, b]) => (a === b ? `${a}` : `${a}–${b}`)).join(", ") + " nm";

function drawSpectrum() {
  const { ctx, width, height } = context($("spectrum"));
  const box = { x: 44, y: 10, w: width - 56, h: height - 50 };
  const wl = result.wavelengths_nm;
  const all = Object.values(result.solutions).filter((s) => s.feasible).flatMap((s) => [s.min, s.max]);
  const low = Math.min(-0.05, ...all), high = Math.max(1.05, ...all);
  const X = (w) => box.x + ((w - 380) / 400) * box.w;
  const Y = (v) => box.y + box.h - ((v - low) / (high - low)) * box.h;
  const t = theme(ctx.canvas);
  ctx.strokeStyle = t.muted; ctx.fillStyle = t.text; ctx.font = "11px system-ui, sans-serif"; ctx.lineWidth = 1;
  ctx.strokeRect(box.x, box.y, box.w, box.h);
  ctx.textAlign = "center";
  for (let w = 400; w <= 750; w += 50) ctx.fillText(w, X(w), box.y + box.h + 15);
  ctx.fillText("wavelength (nm)", box.x + box.w / 2, box.y + box.h + 30);
  ctx.textAlign = "right";
  for (const v of [0, 0.5, 1]) {
    ctx.fillText(v.toFixed(1), box.x - 6, Y(v) + 4);
    ctx.strokeStyle = t.line; ctx.beginPath(); ctx.moveTo(box.x, Y(v)); ctx.lineTo(box.x + box.w, Y(v)); ctx.stroke();
  }
  const styles = { unconstrained: [t.muted, [6, 4], 1.5], nonnegative: [t.accent, [], 2], unit: [t.text, [], 3] };
  for (const [name, [colour, dash, width_]] of Object.entries(styles)) {
    const s = result.solutions[name];
    if (!s.feasible) continue;
    ctx.strokeStyle = colour; ctx.setLineDash(dash); ctx.lineWidth = width_;
    ctx.beginPath();
    s.reflectance.forEach((v, k) => (k ? ctx.lineTo(X(wl[k]), Y(v)) : ctx.moveTo(X(wl[k]), Y(v))));
    ctx.stroke();
  }
  ctx.setLineDash([]);
}

function drawDiagram() {
  const canvas = $("diagram");
  const { ctx, width, height } = context(canvas);
  const frame = xyFrame(width, height);
  const { box, X, Y } = frame;
  canvas.dataset.box = JSON.stringify(box);
  const cells = result.valid_cells;
  const t = theme(canvas);
  ctx.fillStyle = "rgba(46, 160, 67, 0.45)";
  const cw = box.w / cells.size, ch = box.h / cells.size;
  for (const [i, j] of cells.cells) ctx.fillRect(box.x + i * cw, box.y + box.h - (j + 1) * ch, cw + 0.5, ch + 0.5);
  drawXyAxes(ctx, frame);
  const path = (points, close) => xyPath(ctx, frame, points, close);
  ctx.strokeStyle = t.muted; ctx.lineWidth = 1.5; path(result.locus_xy, true);
  ctx.setLineDash([5, 4]); ctx.strokeStyle = t.text; path(result.domain_xy, true); ctx.setLineDash([]);
  if (macadam && macadam.length) { ctx.strokeStyle = t.warn; ctx.lineWidth = 2; path(macadam, true); }
  const [wx, wy] = result.white_xy;
  ctx.strokeStyle = t.text; ctx.lineWidth = 1.5;
  ctx.beginPath(); ctx.moveTo(X(wx) - 5, Y(wy)); ctx.lineTo(X(wx) + 5, Y(wy));
  ctx.moveTo(X(wx), Y(wy) - 5); ctx.lineTo(X(wx), Y(wy) + 5); ctx.stroke();
  ctx.lineWidth = 3; ctx.strokeStyle = t.bg;
  ctx.beginPath(); ctx.arc(X(result.x), Y(result.y), 6, 0, 2 * Math.PI); ctx.stroke();
  ctx.lineWidth = 1.5; ctx.strokeStyle = t.text;
  ctx.beginPath(); ctx.arc(X(result.x), Y(result.y), 6, 0, 2 * Math.PI); ctx.stroke();
}

function numbers() {
  const rows = [["colour", `x ${fmt(result.x, 4)}, y ${fmt(result.y, 4)}, Y ${fmt(result.Y, 1)} under ${result.illuminant}`],
    ["brightest object colour", `Y = ${fmt(result.max_Y, 2)} at this chromaticity`],
    ["unconstrained is a reflectance", result.valid_up_to_Y === null ? "never (it goes below 0 somewhere)" : `up to Y = ${fmt(result.valid_up_to_Y, 2)}`]];
  const labels = { unconstrained: "unconstrained", nonnegative: "ρ ≥ 0", unit: "0 ≤ ρ ≤ 1" };
  for (const [name, label] of Object.entries(labels)) {
    const s = result.solutions[name];
    if (!s.feasible) { rows.push([label, `no solution: ${fmt(s.distance_outside, 3)} XYZ units outside`]); continue; }
    let text = `roughness ${fmt(s.roughness, 6)} nm⁻¹, ρ from ${fmt(s.min, 3)} to ${fmt(s.max, 3)}`;
    if (s.zero_nm.length) text += `; ρ = 0 on ${ranges(s.zero_nm)}`;
    if (s.one_nm.length) text += `; ρ = 1 on ${ranges(s.one_nm)}`;
    text += s.converged ? " (certified)" : " (NOT certified)";
    rows.push([label, text]);
  }
  $("numbers").replaceChildren(...rows.flatMap(([term, value]) => {
    const dt = document.createElement("dt"); dt.textContent = term;
    const dd = document.createElement("dd"); dd.textContent = value;
    return [dt, dd];
  }));
  const unit = result.solutions.unit;
  $("verdict").textContent = unit.feasible
    ? (result.valid_up_to_Y !== null && result.Y <= result.valid_up_to_Y
      ? "Inside the domain of validity: the unconstrained smoothest reflectance is already between 0 and 1, so all three coincide."
      : "Outside the domain of validity: the bounds change the answer; the bounded solution touches 0 or 1 where listed.")
    : `No object colour has this chromaticity at Y = ${fmt(result.Y, 1)}: the brightest has Y = ${fmt(result.max_Y, 2)}. `
      + "Lower Y, or move the chromaticity towards the white.";
  $("patch").style.background = css(result.srgb8);
  $("patch").setAttribute("aria-label", `The colour on sRGB: ${css(result.srgb8)}${result.srgb_in_gamut ? "" : " (outside sRGB: desaturated)"}`);
}

function paint() {
  if (!result) return;
  numbers();
  drawSpectrum();
  drawDiagram();
}

async function start() {
  const options = await api("/api/lab/reflectance/options");
  $("light").replaceChildren(...options.illuminants.map((n) => Object.assign(document.createElement("option"), { value: n, textContent: n })));
  $("step").replaceChildren(...options.steps.map(([v, label]) => Object.assign(document.createElement("option"), { value: v, textContent: label })));
  state = decode(location.hash, options.steps_nm);
  $("light").addEventListener("change", (e) => commit({ light: e.target.value }));
  $("step").addEventListener("change", (e) => commit({ step: e.target.value }));
  for (const key of ["x", "y"]) $(key).addEventListener("change", (e) => commit({ [key]: Number(e.target.value) }));
  $("Y").addEventListener("input", (e) => { state.Y = Number(e.target.value); $("Y-out").textContent = `${state.Y}`; request(); });
  let before = null;
  $("Y").addEventListener("pointerdown", () => { before = state.Y; });
  $("Y").addEventListener("change", (e) => {
    const Y = Number(e.target.value);
    if (before !== null) state.Y = before;
    before = null;
    commit({ Y });
  });
  $("diagram").addEventListener("click", (e) => {
    const box = JSON.parse($("diagram").dataset.box || "null");
    if (!box) return;
    const rect = $("diagram").getBoundingClientRect();
    const x = ((e.clientX - rect.left - box.x) / box.w) * 0.8;
    const y = ((box.y + box.h - (e.clientY - rect.top)) / box.h) * 0.9;
    if (x >= 0 && y > 0 && x + y <= 1) commit({ x: Number(x.toFixed(4)), y: Number(y.toFixed(4)) });
  });
  $("undo").addEventListener("click", undo);
  $("redo").addEventListener("click", redo);
  wireCommon(undo, redo);
  window.addEventListener("popstate", () => { state = decode(location.hash, options.steps_nm); render(); });
  window.addEventListener("resize", paint);
  history.replaceState(null, "", encode(state));
  render();
}

start().catch((error) => showError(error.message));
