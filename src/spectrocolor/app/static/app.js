// spectrocolor explorer: the page. Colour numbers come from the server (the spectrocolor
// library). For an instant repaint while dragging, `localColour` applies the weights W and the
// display matrix M that the server serves (XYZ = levels·W, RGB = M·XYZ, the same normalisation,
// flag/clip and transfer); tests/test_app_browser.py checks it equals the library to 1e-9.
"use strict";

const FULL = 30;
const SETTING_NAMES = {1: "Spectral distribution and colour", 2: "Matching two distributions",
  3: "Complementary distributions", 4: "Samples under illuminants", 5: "Subtractive mixing"};
const EDITORS = {1: ["distribution"], 2: ["left", "right"], 3: ["left", "right"],
  4: ["illuminant", "sample 1", "sample 2"], 5: ["filter 1", "filter 2"]};
const $ = (id) => document.getElementById(id);

const S = {
  setting: 1, step: 10, observer: "1931", display: "sRGB", gamut: "flag", normalise: "fixed",
  presets: null, model: null, wl: [],
  dists: {}, names: {}, cursor: {}, active: {1: 0, 2: 0, 3: 0, 4: 0, 5: 0},
  sunset: -1, level: {left: -1, right: -1}, sums: null,
  server: null, local: null, inflight: false, dirty: false, settled: false, seq: 0,
};
window.__spectra = S;  // for the browser tests and the latency bench

// ---------------------------------------------------------------- server
async function api(path, body) {
  const opts = body === undefined ? {} : {method: "POST", headers: {"Content-Type": "application/json"},
    body: JSON.stringify(body)};
  const res = await fetch(path, opts);
  if (!res.ok) {
    let msg = res.statusText;
    try { msg = (await res.json()).error || msg; } catch (e) { /* not JSON */ }
    throw new Error(msg);
  }
  return res;
}
const apiJSON = async (path, body) => (await api(path, body)).json();

function say(text) { $("message").textContent = text || ""; }

// ---------------------------------------------------------------- local colour (fast path)
function rint(x) {  // NumPy's rint: round half to even
  const r = Math.round(x);
  return (Math.abs(x % 1) === 0.5) ? 2 * Math.round(x / 2) : r;
}
function encode(v, t) {
  if (t.kind === "srgb") return v <= t.threshold ? 12.92 * v : 1.055 * Math.pow(v, 1 / 2.4) - 0.055;
  if (t.kind === "power") return Math.pow(v, 1 / t.gamma);
  const L = t.levels;  // nearest level, ties to the lower (SPECTRA's digit())
  let hi = 1; while (hi < L.length - 1 && L[hi] < v) hi++;
  const idx = (L[hi] - v) < (v - L[hi - 1]) ? hi : hi - 1;
  return idx / (L.length - 1);
}
function localColour(levels, m) {
  const W = m.weights, M = m.matrix_from_XYZ, tol = m.tolerance;
  let X = 0, Y = 0, Z = 0;
  for (let k = 0; k < levels.length; k++) { const v = levels[k], w = W[k]; X += v * w[0]; Y += v * w[1]; Z += v * w[2]; }
  const XYZ = [X, Y, Z], sum = X + Y + Z;
  let rgb = M.map((row) => row[0] * X + row[1] * Y + row[2] * Z);
  let scale = m.fixed_scale;
  if (S.normalise === "per-colour") { const top = Math.max(...rgb); scale = top > 0 ? top : 1; }
  rgb = rgb.map((c) => c / scale);
  const unmapped = rgb.slice();
  const negative = rgb.map((c) => c < -tol), over = rgb.map((c) => c > 1 + tol);
  const inGamut = !negative.some(Boolean) && !over.some(Boolean);
  let lin = rgb.map((c) => (c < 0 && c >= -tol) ? 0 : (c > 1 && c <= 1 + tol) ? 1 : c);
  const exact = S.gamut === "flag" || S.gamut === "clip" || inGamut;
  if (S.gamut === "flag") lin = inGamut ? lin : [0, 0, 0];
  else lin = lin.map((c) => Math.min(1, Math.max(0, c)));  // a preview until the server answers
  const enc = lin.map((c) => encode(c, m.transfer));
  const codes = m.transfer.kind === "levels" ? enc.map((e) => Math.round(e * (m.transfer.levels.length - 1)))
    : enc.map((e) => rint(e * (2 ** m.bit_depth - 1)));
  return {XYZ, xy: sum > 0 ? [X / sum, Y / sum] : [null, null], rgb_unmapped: unmapped, rgb_linear: lin,
    rgb_encoded: enc, codes, in_gamut: inGamut, negative: ["R", "G", "B"].filter((c, i) => negative[i]),
    over: ["R", "G", "B"].filter((c, i) => over[i]), exact};
}

// ---------------------------------------------------------------- what each setting evaluates
function evalSpec() {
  const d = S.dists[S.setting];
  switch (S.setting) {
    case 1: return {spectra: [d[0]], labels: [S.names[1][0]], pairs: []};
    case 2: case 3: return {spectra: [d[0], d[1]], labels: S.names[S.setting], pairs: [[0, 1]]};
    case 4: return {spectra: [Array(S.wl.length).fill(FULL), d[1], d[2]], illuminant: d[0],
      labels: ["illuminant (white)", S.names[4][1], S.names[4][2]], pairs: [[1, 2]]};
    case 5: return {spectra: [Array(S.wl.length).fill(FULL), d[0], d[1], product()],
      labels: ["initial (E)", S.names[5][0], S.names[5][1], "product"], pairs: []};
  }
}
function product() { const [a, b] = S.dists[5]; return a.map((v, k) => v * b[k] / FULL); }

function requestBody() {
  const e = evalSpec();
  const body = {step_nm: S.step, observer: S.observer, display: S.display, normalise: S.normalise,
    gamut: S.gamut, spectra: e.spectra, pairs: e.pairs};
  if (e.illuminant) body.illuminant = e.illuminant;
  return body;
}

function update() {
  S.settled = false;
  const e = evalSpec();
  if (S.model && !e.illuminant) {
    S.local = e.spectra.map((s) => localColour(s, S.model));
    paint(S.local, null);
  } else {
    drawEditors();
  }
  S.dirty = true;
  pump();
}
async function pump() {
  if (S.inflight || !S.dirty) return;
  S.inflight = true; S.dirty = false;
  const seq = ++S.seq;
  try {
    const r = await apiJSON("/api/evaluate", requestBody());
    if (!S.dirty && seq === S.seq) { S.server = r; paint(r.colours, r); S.settled = true; say(""); }
  } catch (err) { say(err.message); }
  S.inflight = false;
  if (S.dirty) pump();
}

// ---------------------------------------------------------------- painting
const fmt = (v, n) => (v === null || v === undefined || !isFinite(v)) ? "—" : v.toFixed(n);
function cssColour(c) {
  const [r, g, b] = c.rgb_encoded;
  if (S.display === "Display P3") return `color(display-p3 ${r} ${g} ${b})`;
  return `rgb(${(r * 255).toFixed(3)}, ${(g * 255).toFixed(3)}, ${(b * 255).toFixed(3)})`;
}
function statusOf(c) {
  if (!(c.XYZ[1] > 0)) return ["black", ""];
  if (!c.in_gamut) {
    const what = [];
    if (c.negative.length) what.push(`${c.negative.join(", ")} negative`);
    if (c.over.length) what.push(`${c.over.join(", ")} above 1`);
    return [`cannot be reproduced (${what.join("; ")})`, "bad"];
  }
  return S.normalise === "per-colour" ? ["Optimised!", "opt"] : ["", ""];
}

function paint(colours, server) {
  drawEditors();
  const e = evalSpec();
  const patches = $("patches");
  const box = (cls, inner) => `<div class="patchbox ${cls}">${inner}</div>`;
  const p = (i, tag, extra = "") => `<div class="patch ${extra}" data-i="${i}" style="background:${cssColour(colours[i])}"><span class="tag">${tag}</span></div>`;
  let html = "";
  if (S.setting === 1) html = box("", p(0, e.labels[0]));
  if (S.setting === 2 || S.setting === 3) {
    // SPECTRA: the border vanishes when the two displayed lights are the same (equal codes)
    const same = colours[0].in_gamut && colours[1].in_gamut && colours[0].codes.every((v, j) => v === colours[1].codes[j]);
    html = box(`split ${same ? "metameric" : ""}`, p(0, e.labels[0]) + p(1, e.labels[1]));
  }
  if (S.setting === 4) {
    html = `<div class="patchbox"><div class="patch" data-i="0" style="background:${cssColour(colours[0])}"><span class="tag">illuminant</span>` +
      `<div class="patch inner" data-i="1" style="left:14%;background:${cssColour(colours[1])}"><span class="tag">1</span></div>` +
      `<div class="patch inner" data-i="2" style="left:60%;background:${cssColour(colours[2])}"><span class="tag">2</span></div></div></div>`;
  }
  if (S.setting === 5) {
    html = `<div class="patchbox"><div class="patch" data-i="0" style="background:${cssColour(colours[0])}"><span class="tag">initial light (E)</span>` +
      `<div class="patch inner" data-i="3" style="left:37%;background:${cssColour(colours[3])}"><span class="tag">through both</span></div></div></div>` +
      `<div class="patchbox" style="flex:0.5">${p(1, "filter 1")}${p(2, "filter 2")}</div>`;
  }
  patches.innerHTML = html;
  // numbers
  const cards = colours.map((c, i) => {
    const [st, cls] = statusOf(c);
    const dom = server ? server.colours[i] : null;
    const domText = dom && dom.dominant_nm !== null ? `${dom.complementary ? "λc" : "λd"} ${fmt(dom.dominant_nm, 1)} nm${dom.complementary ? " (compl.)" : ""}` : "—";
    return `<div class="card" data-i="${i}"><h3><span class="sw" style="background:${cssColour(c)}"></span>${e.labels[i]}</h3>
      <table>
      <tr><td>X Y Z</td><td class="XYZ">${c.XYZ.map((v) => fmt(v, 2)).join("  ")}</td></tr>
      <tr><td>x y</td><td class="xy">${c.xy.map((v) => fmt(v, 4)).join("  ")}</td></tr>
      <tr><td>R G B</td><td class="rgb">${c.rgb_unmapped.map((v) => fmt(v, 3)).join("  ")}</td></tr>
      <tr><td>r g b</td><td class="codes">${c.codes.join("  ")}</td></tr>
      <tr><td>λ, purity</td><td class="dom">${domText}${dom && dom.dominant_nm !== null ? ", p " + fmt(dom.purity, 3) : ""}</td></tr>
      </table><div class="status ${cls}">${st}</div></div>`;
  });
  let extra = "";
  if (server && server.delta_e_2000.length) {
    // Under B each patch is scaled on its own, so the split patch compares the lights as shown;
    // the unscaled lights' difference is given beside it.
    const scaled = S.normalise === "per-colour";
    const de = scaled ? server.delta_e_2000_shown[0] : server.delta_e_2000[0];
    const note = scaled ? `as shown (B); unscaled lights ${fmt(server.delta_e_2000[0], 2)}` : "";
    extra = `<div class="card"><h3>ΔE00 between ${S.setting === 4 ? "the samples" : "the two"}: <span class="de">${fmt(de, 2)}</span></h3>
      <div class="status ${de < 0.5 ? "opt" : ""}">${[de < 0.5 ? "metameric" : "", note].filter(Boolean).join(" · ")}</div></div>`;
  }
  $("numbers").innerHTML = extra + cards.join("");
  drawPoints(colours, server);
}

// ---------------------------------------------------------------- editors (canvas)
function editorsFor(setting) { return EDITORS[setting]; }
function buildEditors() {
  const box = $("editors");
  const names = editorsFor(S.setting);
  const ro = S.setting === 5 ? ["product"] : [];
  box.className = names.length + ro.length === 3 ? "three" : names.length === 2 ? "two" : "";
  box.innerHTML = [...names, ...ro].map((n, i) => `<div class="editor ${i >= names.length ? "readonly" : ""}" data-e="${i}">
    <div class="head"><span><b>${n}</b> <span class="pname"></span></span><span class="cur"></span></div>
    <canvas aria-label="${n} distribution"></canvas></div>`).join("");
  box.querySelectorAll(".editor").forEach((el) => {
    const i = Number(el.dataset.e);
    if (i >= names.length) return;
    const cv = el.querySelector("canvas");
    let last = null;
    const at = (ev) => {
      const r = cv.getBoundingClientRect();
      const k = Math.min(S.wl.length - 1, Math.max(0, Math.floor((ev.clientX - r.left) / r.width * S.wl.length)));
      const pad = 14, h = r.height - pad - 16;
      let v = (1 - (ev.clientY - r.top - pad) / h) * FULL;
      v = Math.min(FULL, Math.max(0, v));
      return [k, S.step === 10 ? Math.round(v) : Math.round(v * 10) / 10];
    };
    cv.addEventListener("pointerdown", (ev) => {
      ev.preventDefault(); cv.setPointerCapture(ev.pointerId);
      S.active[S.setting] = i; const [k, v] = at(ev); last = [k, v];
      S.cursor[S.setting + ":" + i] = k; setLevel(i, k, v); update();
    });
    cv.addEventListener("pointermove", (ev) => {
      if (!last || !(ev.buttons & 1) && ev.pointerType === "mouse") return;
      const [k, v] = at(ev);
      const [k0, v0] = last, n = Math.abs(k - k0);
      for (let j = 1; j <= n; j++) { const kk = k0 + Math.sign(k - k0) * j; setLevel(i, kk, v0 + (v - v0) * j / n); }
      if (n === 0) setLevel(i, k, v);
      last = [k, v]; S.cursor[S.setting + ":" + i] = k; update();
    });
    const stop = () => { last = null; };
    cv.addEventListener("pointerup", stop); cv.addEventListener("pointercancel", stop);
  });
}
function setLevel(i, k, v) {
  v = S.step === 10 ? Math.round(v) : Math.round(v * 10) / 10;
  const d = S.dists[S.setting];
  if (S.setting === 3) {  // complementary: what one side loses the other gains
    const total = d[0][k] + d[1][k];
    v = Math.min(Math.min(FULL, total), Math.max(Math.max(0, total - FULL), v));
    d[i][k] = v; d[1 - i][k] = Math.round((total - v) * 1e9) / 1e9;
  } else {
    d[i][k] = Math.min(FULL, Math.max(0, v));
  }
}
function drawEditors() {
  const names = editorsFor(S.setting);
  const lists = [...S.dists[S.setting]];
  if (S.setting === 5) lists.push(product());
  document.querySelectorAll("#editors .editor").forEach((el, i) => {
    const cv = el.querySelector("canvas");
    const dpr = window.devicePixelRatio || 1;
    const w = cv.clientWidth, h = cv.clientHeight;
    if (cv.width !== Math.round(w * dpr)) { cv.width = Math.round(w * dpr); cv.height = Math.round(h * dpr); }
    const g = cv.getContext("2d"); g.setTransform(dpr, 0, 0, dpr, 0, 0); g.clearRect(0, 0, w, h);
    const levels = lists[i], K = levels.length, bw = w / K, pad = 14, hh = h - pad - 16;
    g.strokeStyle = "#2b2f38"; g.lineWidth = 1; g.fillStyle = "#8b93a5"; g.font = "10px system-ui, sans-serif";
    for (const L of [10, 20, 30]) { const y = pad + hh * (1 - L / FULL); g.beginPath(); g.moveTo(0, y); g.lineTo(w, y); g.stroke(); g.fillText(String(L), 2, y - 2); }
    const tints = S.model ? S.model.tints : null;
    for (let k = 0; k < K; k++) {
      const t = tints ? tints[k] : [0.6, 0.6, 0.6];
      g.fillStyle = `rgb(${t[0] * 255},${t[1] * 255},${t[2] * 255})`;
      const bh = hh * levels[k] / FULL;
      g.fillRect(k * bw + (K <= 61 ? 1 : 0), pad + hh - bh, Math.max(1, bw - (K <= 61 ? 2 : 0)), bh);
    }
    if (S.setting === 3 && i < 2) {  // the conserved total
      g.strokeStyle = "rgba(255,255,255,0.35)"; g.setLineDash([3, 3]); g.beginPath();
      for (let k = 0; k < K; k++) { const y = pad + hh * (1 - (S.dists[3][0][k] + S.dists[3][1][k]) / FULL); g.lineTo(k * bw, y); g.lineTo((k + 1) * bw, y); }
      g.stroke(); g.setLineDash([]);
    }
    g.fillStyle = "#8b93a5";
    for (const nm of [400, 500, 600, 700]) { const k = S.wl.indexOf(nm); if (k >= 0) g.fillText(String(nm), Math.min(w - 20, k * bw), h - 3); }
    const ed = el.classList;
    const active = i < names.length && S.active[S.setting] === i;
    ed.toggle("active", active && names.length > 1);
    if (i < names.length) {
      const k = S.cursor[S.setting + ":" + i] ?? Math.floor(K / 2);
      g.strokeStyle = active ? "#6aa9ff" : "#555b68"; g.lineWidth = 2; g.strokeRect(k * bw + 1, pad, bw - 2, hh);
      el.querySelector(".cur").textContent = `${S.wl[k]} nm: ${fmt(levels[k], S.step === 10 && Number.isInteger(levels[k]) ? 0 : 1)}`;
      el.querySelector(".pname").textContent = S.names[S.setting][i] || "";
    }
  });
}

// ---------------------------------------------------------------- chromaticity diagram
const DOT = ["#ffffff", "#ffd166", "#6aa9ff", "#ff8fab"];
function drawDiagram() {
  const m = S.model, svg = $("chroma");
  const P = (x, y) => `${x.toFixed(4)},${(-y).toFixed(4)}`;
  const loc = m.locus.xy.map(([x, y]) => P(x, y)).join(" ");
  let s = "";
  for (let v = 0; v <= 0.8; v += 0.1) s += `<line class="grid" x1="${v}" y1="0" x2="${v}" y2="-0.9"/><line class="grid" x1="0" y1="${-v}" x2="0.8" y2="${-v}"/>`;
  s += `<polygon class="locus" points="${loc}"/>`;
  s += `<polygon class="gamut" points="${m.primaries_xy.map(([x, y]) => P(x, y)).join(" ")}"/>`;
  m.locus.wavelengths_nm.forEach((w, i) => {
    if ([460, 480, 490, 500, 520, 540, 560, 580, 600, 620].includes(w)) {
      const [x, y] = m.locus.xy[i]; s += `<text x="${(x + (w < 520 ? -0.05 : 0.012)).toFixed(3)}" y="${(-y).toFixed(3)}">${w}</text>`;
    }
  });
  s += `<text x="0.62" y="-0.02">x</text><text x="0.005" y="-0.86">y</text>`;
  s += `<circle class="white" r="0.009" cx="${m.white_xy[0]}" cy="${-m.white_xy[1]}"/><g id="pts"></g>`;
  svg.innerHTML = s;
}
function drawPoints(colours, server) {
  const g = document.getElementById("pts"); if (!g) return;
  let s = "";
  const white = server ? server.white_xy : S.model.white_xy;
  const wc = document.querySelector("#chroma .white");
  if (wc) { wc.setAttribute("cx", white[0]); wc.setAttribute("cy", -white[1]); }
  colours.forEach((c, i) => {
    if (c.xy[0] === null) return;
    if ((S.setting === 4 || S.setting === 5) && i === 0) return;
    s += `<circle class="pt" r="0.012" cx="${c.xy[0]}" cy="${-c.xy[1]}" fill="${DOT[i % DOT.length]}"><title>${evalSpec().labels[i]}</title></circle>`;
  });
  g.innerHTML = s;
}

// ---------------------------------------------------------------- presets and keys
function presetButtons() {
  const box = $("presets"), p = S.presets;
  const btn = (group, key, name) => `<button data-group="${group}" data-key="${key}"><kbd>${key}</kbd>${name}</button>`;
  let html = "";
  if (S.setting === 1) html = p.setting1.map((q) => btn("s1", q.key, q.name)).join("");
  if (S.setting === 2) html = `<span class="group">left</span>` + p.setting2.left.map((q) => btn("left", q.key, q.name)).join("") +
    `<span class="group">right</span>` + p.setting2.right.map((q) => btn("right", q.key, q.name)).join("");
  if (S.setting === 3) html = p.setting3.map((q) => btn("pair", q.key, q.name)).join("");
  if (S.setting === 4) html = `<span class="group">illuminant</span>` + p.setting4.illuminants.map((q) => btn("ill", q.key, q.name)).join("") +
    `<span class="group">samples</span>` + p.setting4.samples.map((q) => btn("pair", q.key, q.name)).join("");
  if (S.setting === 5) html = p.setting5.map((q) => btn("pair", q.key, q.name)).join("");
  box.innerHTML = html;
  box.querySelectorAll("button").forEach((b) => b.addEventListener("click", () => {
    if (b.dataset.group === "left" || b.dataset.group === "right") S.active[2] = b.dataset.group === "left" ? 0 : 1;
    pressDigit(b.dataset.key); update();
  }));
  const act = $("actions");
  act.innerHTML = S.setting === 2 ? `<button id="metamer" title="Replace the right distribution by the smoothest metamer of the left">Make a metamer</button>` : "";
  if (S.setting === 2) $("metamer").addEventListener("click", makeMetamer);
}
const copy = (a) => a.slice();
function pressDigit(key) {
  const p = S.presets, d = S.dists[S.setting], names = S.names[S.setting];
  const find = (list) => list.find((q) => q.key === key);
  if (S.setting === 1) {
    const q = find(p.setting1); if (!q) return;
    if (q.cycle) { S.sunset = (S.sunset + 1) % q.cycle.length; d[0] = copy(q.cycle[S.sunset].levels); names[0] = `sunset d = ${q.cycle[S.sunset].d}`; }
    else { S.sunset = -1; d[0] = copy(q.levels); names[0] = q.name; }
  } else if (S.setting === 2) {
    const side = S.active[2] === 0 ? "left" : "right", i = S.active[2];
    const q = find(p.setting2[side]); if (!q) return;
    if (q.cycle) { S.level[side] = (S.level[side] + 1) % q.cycle.length; d[i] = copy(q.cycle[S.level[side]].levels); names[i] = `level ${S.level[side]}`; }
    else { d[i] = copy(q.levels); names[i] = q.name; }
  } else if (S.setting === 4) {
    const qi = find(p.setting4.illuminants), qs = find(p.setting4.samples);
    if (qi) { d[0] = copy(qi.levels); names[0] = qi.name; }
    if (qs) { d[1] = copy(qs.left); d[2] = copy(qs.right); names[1] = qs.name + " 1"; names[2] = qs.name + " 2"; }
  } else {
    const q = find(S.setting === 3 ? p.setting3 : p.setting5); if (!q) return;
    d[0] = copy(q.left); d[1] = copy(q.right);
    const head = q.name.split(":")[0], parts = head.split(S.setting === 3 ? " / " : " and ");
    names[0] = parts[0].trim(); names[1] = (parts[1] || parts[0]).trim();
  }
}
function storeKey(setting) { return `spectrocolor:setting${setting}:step${S.step}`; }
function saveSlot() {
  localStorage.setItem(storeKey(S.setting), JSON.stringify({dists: S.dists[S.setting], names: S.names[S.setting]}));
  say(`saved (key 0 recalls it${S.setting === 2 || S.setting === 3 ? "; key 9 in other settings loads it" : ""})`);
}
function recall(setting) {
  const raw = localStorage.getItem(storeKey(setting));
  if (!raw) { say(`nothing saved in setting ${setting} yet (press S there)`); return false; }
  const saved = JSON.parse(raw);
  const n = S.dists[S.setting].length;
  if (setting === S.setting) { S.dists[S.setting] = saved.dists.map(copy); S.names[S.setting] = saved.names.slice(); }
  else {  // key 9: a pair from setting 2 (or 3)
    const pair = saved.dists.slice(0, 2).map(copy);
    if (S.setting === 4) { S.dists[4][1] = pair[0]; S.dists[4][2] = pair[1]; S.names[4][1] = saved.names[0]; S.names[4][2] = saved.names[1]; }
    else { S.dists[S.setting] = pair.slice(0, n); S.names[S.setting] = saved.names.slice(0, n); }
  }
  return true;
}
function onKey(ev) {
  if (ev.target.closest && ev.target.closest("select, input, dialog[open]")) return;
  if (ev.ctrlKey || ev.metaKey || ev.altKey) return;
  const n = editorsFor(S.setting).length, a = S.active[S.setting];
  const ck = S.setting + ":" + a, K = S.wl.length;
  const cur = S.cursor[ck] ?? Math.floor(K / 2);
  let handled = true;
  switch (ev.key) {
    case "ArrowLeft": S.cursor[ck] = Math.max(0, cur - 1); drawEditors(); break;
    case "ArrowRight": S.cursor[ck] = Math.min(K - 1, cur + 1); drawEditors(); break;
    case "ArrowUp": case "ArrowDown": {
      const step = S.step === 10 ? 1 : (ev.shiftKey ? 0.1 : 1);
      S.cursor[ck] = cur;
      setLevel(a, cur, S.dists[S.setting][a][cur] + (ev.key === "ArrowUp" ? step : -step)); update(); break;
    }
    case " ": S.active[S.setting] = (a + 1) % n; drawEditors(); break;
    case "x": case "X": toggleNorm(); break;
    case "s": case "S": saveSlot(); break;
    case "0": if (recall(S.setting)) update(); break;
    case "9": if (S.setting !== 1 && recall(S.setting === 2 ? 3 : 2)) update(); break;
    default:
      if (/^[1-8]$/.test(ev.key)) { pressDigit(ev.key); update(); } else handled = false;
  }
  if (handled) ev.preventDefault();
}
function toggleNorm() {
  S.normalise = S.normalise === "fixed" ? "per-colour" : "fixed";
  const b = $("norm"); b.textContent = S.normalise === "fixed" ? "A · fixed" : "B · optimised"; b.classList.toggle("b", S.normalise !== "fixed");
  update();
}

// ---------------------------------------------------------------- metamer, files
async function makeMetamer() {
  try {
    const r = await apiJSON("/api/metamer", {step_nm: S.step, observer: S.observer, target: S.dists[2][0]});
    S.dists[2][1] = r.levels.map((v) => Math.min(FULL, Math.max(0, v))); S.names[2][1] = "smoothest metamer"; update();
  } catch (err) { say(err.message); }
}
async function saveFile(fmtSel) {
  const dists = S.setting === 4 ? S.dists[4] : S.dists[S.setting];
  const names = editorsFor(S.setting).map((n, i) => `${n} ${S.names[S.setting][i] || ""}`.trim().replace(/[^\w .,()+\-]/g, "_").slice(0, 60));
  try {
    const res = await api("/api/export", {format: fmtSel, step_nm: S.step, names, spectra: dists});
    const blob = await res.blob(), a = document.createElement("a");
    a.href = URL.createObjectURL(blob); a.download = `spectra-setting${S.setting}.${fmtSel}`; a.click();
    setTimeout(() => URL.revokeObjectURL(a.href), 1000);
  } catch (err) { say(err.message); }
}
async function loadFile(file) {
  const content = await file.text();
  const scale = $("upload-scale").value;
  try {
    const r = await apiJSON("/api/import", {filename: file.name, content, step_nm: S.step, method: "linear", scale});
    const a = S.active[S.setting], d = S.dists[S.setting];
    r.levels.slice(0, d.length - a).forEach((lv, j) => { d[a + j] = lv; S.names[S.setting][a + j] = r.names[j]; });
    say(r.note); update();
  } catch (err) { say(err.message); }
}

// ---------------------------------------------------------------- setup
async function loadModel() {
  S.model = await apiJSON("/api/model", {step_nm: S.step, observer: S.observer, display: S.display});
  S.wl = S.model.wavelengths_nm;
  drawDiagram();
}
function defaults() {
  const p = S.presets;
  S.dists = {1: [copy(p.setting1[0].levels)], 2: [copy(p.setting2.left[6].levels), copy(p.setting2.right[6].levels)],
    3: [copy(p.setting3[0].left), copy(p.setting3[0].right)],
    4: [copy(p.setting4.illuminants[1].levels), copy(p.setting4.samples[0].left), copy(p.setting4.samples[0].right)],
    5: [copy(p.setting5[0].left), copy(p.setting5[0].right)]};
  S.names = {1: [p.setting1[0].name], 2: ["D65", "three-band"], 3: ["yellow", "very dark neutral"],
    4: ["D65", "metameric grey 1", "metameric grey 2"], 5: ["straw", "light blue"]};
  S.sunset = -1; S.level = {left: -1, right: -1};
}
async function reloadGrid() {
  S.presets = await apiJSON(`/api/presets?step_nm=${S.step}`);
  await loadModel(); defaults(); buildEditors(); presetButtons(); update();
}
function selectSetting(n) {
  S.setting = n;
  document.querySelectorAll("#tabs button").forEach((b) => b.classList.toggle("on", Number(b.dataset.setting) === n));
  document.title = `spectrocolor · ${SETTING_NAMES[n]}`;
  buildEditors(); presetButtons(); update();
}
async function init() {
  const o = await apiJSON("/api/options");
  const fill = (sel, items, value) => { $(sel).innerHTML = items.map(([v, t]) => `<option value="${v}">${t}</option>`).join(""); $(sel).value = value; };
  fill("display", o.displays.map((d) => [d, d]), S.display);
  fill("observer", Object.entries(o.observers), S.observer);
  fill("gamut", o.gamuts.map((g) => [g, g]), S.gamut);
  $("display").addEventListener("change", async (e) => { S.display = e.target.value; await loadModel(); update(); });
  $("observer").addEventListener("change", async (e) => { S.observer = e.target.value; await loadModel(); update(); });
  $("gamut").addEventListener("change", (e) => { S.gamut = e.target.value; update(); });
  $("step").addEventListener("change", async (e) => { S.step = Number(e.target.value); await reloadGrid(); });
  $("norm").addEventListener("click", toggleNorm);
  $("save-csv").addEventListener("click", () => saveFile("csv"));
  $("save-json").addEventListener("click", () => saveFile("json"));
  $("load-file").addEventListener("click", () => $("file").click());
  $("file").addEventListener("change", (e) => { if (e.target.files[0]) loadFile(e.target.files[0]); e.target.value = ""; });
  $("about-open").addEventListener("click", () => $("about").showModal());
  document.querySelectorAll("#tabs button").forEach((b) => b.addEventListener("click", () => selectSetting(Number(b.dataset.setting))));
  document.addEventListener("keydown", onKey);
  window.addEventListener("resize", () => drawEditors());
  S.presets = await apiJSON(`/api/presets?step_nm=${S.step}`);
  await loadModel(); defaults();
  selectSetting(1);
}
init().catch((err) => say(err.message));
