// Pictures for slides and worksheets (issue 28, item 5): the current view (patches with their
// names and numbers, the distributions' graphs, the chromaticity diagram) as an SVG file built from
// the page's own data, not a screenshot, and as a PNG drawn from that SVG on a canvas at a chosen
// scale. Every graph names its quantity and unit (wavelength λ in nm, level 0–30 and what it means
// in the setting, CIE x and y); names are text nodes, so the serializer escapes them; the PNG also
// carries the names and units as an iTXt "Description" chunk.
//
// The patch colours are the explorer's own: each rectangle takes the colour the page's patch is
// painted with (view.js paint(), from the library's answer), and the diagram's markers theirs.

import {$} from "./dom.js";
import {S, EDITORS, FULL, SETTING_NAMES} from "./state.js";
import {displayName, product, additive, sum} from "./view.js";

const NS = "http://www.w3.org/2000/svg";
const INK = "#1b1d22", MUTED = "#4d5463", GRID = "#d5d8de", FONT = "system-ui, -apple-system, 'Segoe UI', Roboto, Arial, sans-serif";
const W = 1200;

/** Characters XML 1.0 cannot hold (a name from a file may carry them): replaced, never emitted. */
const xmlSafe = (t) => String(t).replace(/[\x00-\x08\x0b\x0c\x0e-\x1f\ufffe\uffff]/g, "\ufffd");

function node(tag, attrs = {}, ...children) {
  const n = document.createElementNS(NS, tag);
  for (const [k, v] of Object.entries(attrs)) if (v !== undefined && v !== null) n.setAttribute(k, String(v));
  for (const c of children.flat()) if (c !== null && c !== undefined) n.append(typeof c === "string" ? xmlSafe(c) : c);
  return n;
}
const txt = (x, y, s, attrs = {}) => node("text", {x: x.toFixed(1), y: y.toFixed(1), "font-size": 13, fill: INK, ...attrs}, s);
const cellText = (i, cls) => { const c = document.querySelector(`#numbers .card[data-i='${i}'] td.${cls}`); return c ? c.textContent.trim() : ""; };

/** What each level means in the current setting, per editor (the graph's y quantity and unit). */
function quantity(setting, i) {
  if (setting === 4) return i === 0 ? "relative spectral power (level 0–30)" : "reflectance (level 0–30 = 0–100 %)";
  if (setting === 5) return "transmittance (level 0–30 = 0–100 %)";
  return "spectral power (level 0–30; 30 = the full spectrum)";
}
function optionsLine() {
  const o = S.options || {}, obs = (o.observers || {})[S.observer] || S.observer;
  const label = (kind, v) => ((((o.choices || {})[kind]) || []).find(([n]) => n === v) || [v, v])[1];
  return [`display ${S.display}`, `observer ${obs}`, `normalisation ${label("normalise", S.normalise)}`,
    `out of gamut: ${label("gamut", S.gamut)}`, `bins ${S.step} nm (${S.wl.length})`,
    S.adaptation ? `white: ${S.adaptation}` : null].filter(Boolean).join(" · ");
}

/** The page's patches: [{i, name, fill}] in the order of #patches (the colour as painted). */
function patches() {
  return [...document.querySelectorAll("#patches .patch")].map((p) => ({
    i: Number(p.dataset.i), name: p.querySelector(":scope > .tag").textContent,
    fill: getComputedStyle(p).backgroundColor}));
}

function patchRow(g, y0) {
  const list = patches(), n = list.length, gap = 16, w = Math.min(260, (W - 40 - gap * (n - 1)) / n), h = 110;
  list.forEach((p, k) => {
    const x = 20 + k * (w + gap);
    g.append(node("rect", {x, y: y0, width: w.toFixed(1), height: h, fill: p.fill, stroke: "#888", "stroke-width": 1,
      class: "patch", "data-i": p.i}, node("title", {}, p.name)));
    const lines = [[p.name, {"font-weight": 700, "font-size": 14}],
      [`x y ${cellText(p.i, "xy")}`, {}], [`L* a* b* ${cellText(p.i, "lab")}`, {}],
      [`codes ${cellText(p.i, "codes")}  ${cellText(p.i, "hex")}`, {fill: MUTED}]];
    lines.forEach(([s, a], j) => g.append(txt(x, y0 + h + 18 + 17 * j, s, a)));
  });
  let y = y0 + h + 18 + 17 * 4;
  const de = document.querySelector("#numbers .de-card .de");
  if (de) {
    const status = document.querySelector("#numbers .de-card .de-status").textContent.trim();
    g.append(txt(20, y + 6, `ΔE00 (CIEDE2000) ${S.setting === 4 ? "between the samples" : "between the two"}: ${de.textContent.trim()}${status ? ` (${status})` : ""}`, {"font-size": 14}));
    y += 24;
  }
  return y;
}

/** One distribution's bars with axes: x wavelength λ / nm, y its level and meaning. */
function graph(x0, y0, w, h, levels, title, yLabel) {
  const g = node("g", {class: "graph"});
  const L = 46, B = 34, pw = w - L - 8, ph = h - B - 40, top = y0 + 40, wl = S.wl, K = levels.length;
  const X = (nm) => x0 + L + pw * (nm - 395) / 310, Y = (v) => top + ph * (1 - v / FULL);
  g.append(txt(x0 + L, y0 + 14, title, {"font-weight": 700}),
    txt(x0 + L, y0 + 30, yLabel, {"font-size": 12, fill: MUTED, class: "quantity"}));
  for (const v of [0, 10, 20, 30]) {
    g.append(node("line", {x1: X(395), x2: X(705), y1: Y(v), y2: Y(v), stroke: GRID}),
      txt(x0 + L - 6, Y(v) + 4, String(v), {"text-anchor": "end", "font-size": 11, fill: MUTED}));
  }
  const tints = S.model && S.model.tints, half = (S.step || 10) / 2;
  for (let k = 0; k < K; k++) {
    const t = tints ? tints[k] : [0.6, 0.6, 0.6];
    g.append(node("rect", {x: X(wl[k] - half).toFixed(2), y: Y(levels[k]).toFixed(2), width: (X(wl[k] + half) - X(wl[k] - half)).toFixed(2),
      height: (Y(0) - Y(levels[k])).toFixed(2), fill: `rgb(${t.map((c) => Math.round(c * 255)).join(",")})`}));
  }
  g.append(node("polyline", {fill: "none", stroke: INK, "stroke-width": 1.2,
    points: levels.map((v, k) => `${X(wl[k] - half).toFixed(1)},${Y(v).toFixed(1)} ${X(wl[k] + half).toFixed(1)},${Y(v).toFixed(1)}`).join(" ")}));
  g.append(node("line", {x1: X(395), x2: X(705), y1: Y(0), y2: Y(0), stroke: INK}),
    node("line", {x1: X(395), x2: X(395), y1: Y(0), y2: Y(FULL), stroke: INK}));
  for (const nm of [400, 450, 500, 550, 600, 650, 700]) {
    g.append(node("line", {x1: X(nm), x2: X(nm), y1: Y(0), y2: Y(0) + 4, stroke: INK}),
      txt(X(nm), Y(0) + 16, String(nm), {"text-anchor": "middle", "font-size": 11}));
  }
  g.append(txt(x0 + L + pw / 2, Y(0) + 30, "wavelength λ (nm)", {"text-anchor": "middle", "font-size": 12, class: "axis-label"}));
  const yl = txt(x0 + 12, top + ph / 2, "level (0–30)", {"text-anchor": "middle", "font-size": 11, class: "axis-label",
    transform: `rotate(-90 ${(x0 + 12).toFixed(1)} ${(top + ph / 2).toFixed(1)})`});
  g.append(yl);
  return g;
}

/** The CIE xy diagram from the display model and the page's markers. */
function diagram(x0, y0, size) {
  const m = S.model, g = node("g", {class: "diagram"}), s = size - 60;
  const X = (x) => x0 + 50 + s * x / 0.8, Y = (y) => y0 + 20 + s * (0.9 - y) / 0.9;
  const obs = ((S.options || {}).observers || {})[S.observer] || S.observer;
  g.append(txt(x0 + 50, y0 + 10, `CIE xy chromaticity diagram (${obs})`, {"font-weight": 700}));
  for (let i = 0; i <= 8; i++) {
    const v = i / 10;
    g.append(node("line", {x1: X(v), x2: X(v), y1: Y(0), y2: Y(0.9), stroke: GRID}),
      node("line", {x1: X(0), x2: X(0.8), y1: Y(v), y2: Y(v), stroke: GRID}),
      txt(X(v), Y(0) + 15, v.toFixed(1), {"text-anchor": "middle", "font-size": 11}),
      txt(X(0) - 6, Y(v) + 4, v.toFixed(1), {"text-anchor": "end", "font-size": 11}));
  }
  const poly = (pts) => pts.map(([x, y]) => `${X(x).toFixed(1)},${Y(y).toFixed(1)}`).join(" ");
  g.append(node("polygon", {points: poly(m.locus.xy), fill: "none", stroke: INK, "stroke-width": 1.3}),
    node("polygon", {points: poly(m.primaries_xy), fill: "none", stroke: "#1f5fbf", "stroke-width": 1.3}));
  m.locus.wavelengths_nm.forEach((w, i) => {
    if (![460, 480, 490, 500, 520, 540, 560, 580, 600, 620, 700].includes(w)) return;
    const [x, y] = m.locus.xy[i];
    g.append(node("circle", {cx: X(x).toFixed(1), cy: Y(y).toFixed(1), r: 2, fill: INK}),
      // below 490 nm outside the locus (left), from 490 to 510 nm inside it (clear of the y ticks)
      txt(X(x) + (w < 490 ? -6 : 6), Y(y) + 4, `${w} nm`, {"text-anchor": w < 490 ? "end" : "start", "font-size": 10}));
  });
  g.append(txt(X(0.4), Y(0) + 32, "CIE x (chromaticity, unitless)", {"text-anchor": "middle", "font-size": 12, class: "axis-label"}),
    txt(x0 + 12, Y(0.45), "CIE y (chromaticity, unitless)", {"text-anchor": "middle", "font-size": 12, class: "axis-label",
      transform: `rotate(-90 ${(x0 + 12).toFixed(1)} ${Y(0.45).toFixed(1)})`}));
  const white = document.querySelector("#chroma .white");
  const wx = white ? Number(white.getAttribute("cx")) : m.white_xy[0], wy = white ? -Number(white.getAttribute("cy")) : m.white_xy[1];
  g.append(node("circle", {cx: X(wx).toFixed(1), cy: Y(wy).toFixed(1), r: 6, fill: "none", stroke: INK, "stroke-width": 1.5},
    node("title", {}, "reference white")));
  const legend = [["reference white (ring)", null]];
  document.querySelectorAll("#pts .mark").forEach((mk, n) => {
    const dot = mk.querySelector("circle");
    const name = (dot.querySelector("title") || {}).textContent || "";
    legend.push([`${n + 1} ${name}`, dot.getAttribute("fill")]);
    if (mk.style.display === "none" || dot.getAttribute("cx") === null) return;
    const cx = X(Number(dot.getAttribute("cx"))), cy = Y(-Number(dot.getAttribute("cy")));
    g.append(node("circle", {cx: cx.toFixed(1), cy: cy.toFixed(1), r: 9, fill: dot.getAttribute("fill"), stroke: INK, "stroke-width": 1.5},
      node("title", {}, name)),
    txt(cx, cy + 4, String(n + 1), {"text-anchor": "middle", "font-size": 11, "font-weight": 700, fill: "#fff",
      stroke: "#000", "stroke-width": 2.5, "paint-order": "stroke"}));
  });
  legend.forEach(([t, fill], j) => {
    const ly = y0 + size + 8 + 17 * j;
    g.append(fill ? node("rect", {x: x0 + 50, y: ly - 10, width: 12, height: 12, fill, stroke: INK}) :
      node("circle", {cx: x0 + 56, cy: ly - 4, r: 5, fill: "none", stroke: INK}), txt(x0 + 68, ly, t, {"font-size": 12}));
  });
  return [g, y0 + size + 8 + 17 * legend.length];
}

/** The current view as an SVG element (width 1200 px, height as needed). */
export function buildSVG() {
  const svg = node("svg", {xmlns: NS, width: W, "font-family": FONT});
  const body = node("g");
  const when = new Date().toISOString().slice(0, 16).replace("T", " ");
  body.append(txt(20, 30, `SPECTRA explorer · setting ${S.setting}: ${SETTING_NAMES[S.setting]}`, {"font-size": 20, "font-weight": 700}),
    txt(20, 52, optionsLine(), {fill: MUTED}));
  const afterPatches = patchRow(body, 70);
  // graphs (left) and the diagram (right)
  const roles = EDITORS[S.setting], lists = S.dists[S.setting].map((d, i) => [d, `${roles[i]}: ${displayName(S.setting, i)}`, quantity(S.setting, i)]);
  if (S.setting === 5) {
    lists.push(additive() ? [sum(), "both lights (sum, the spotlights' overlap)", "level 0–60 (two full spotlights)"]
      : [product(), "through both filters (product)", "transmittance (level 0–30 = 0–100 %)"]);
  }
  const gw = 700, gh = 250;
  let y = afterPatches + 16;
  lists.forEach(([levels, title, yl]) => { body.append(graph(20, y, gw, gh, levels, title, yl)); y += gh + 10; });
  const [dg, dEnd] = diagram(W - 460, afterPatches + 16, 440);
  body.append(dg);
  const end = Math.max(y, dEnd) + 10;
  body.append(txt(20, end + 10, `Levels 0–30 per bin (30 = the full, equal-energy spectrum or 100 %); colours for ${S.display} as the explorer shows them. spectrocolor, ${when} UTC.`,
    {"font-size": 11, fill: MUTED}));
  const H = Math.ceil(end + 24);
  svg.setAttribute("height", H); svg.setAttribute("viewBox", `0 0 ${W} ${H}`);
  svg.append(node("title", {}, `SPECTRA explorer, setting ${S.setting}: ${SETTING_NAMES[S.setting]}`),
    node("desc", {}, describe()), node("rect", {x: 0, y: 0, width: W, height: H, fill: "#fff"}), body);
  return svg;
}

/** Names and units in words (the SVG's desc, the PNG's Description). */
function describe() {
  const names = patches().map((p) => p.name).join("; ");
  return `Setting ${S.setting} (${SETTING_NAMES[S.setting]}). Colours: ${names}. ${optionsLine()}. `
    + "Graphs: level 0-30 per wavelength bin, wavelength λ in nm; diagram: CIE x, y chromaticity.";
}

export const svgText = () => `<?xml version="1.0" encoding="UTF-8"?>\n${new XMLSerializer().serializeToString(buildSVG())}\n`;

// ---------------------------------------------------------------- PNG
const CRC = (() => {
  const t = new Uint32Array(256);
  for (let n = 0; n < 256; n++) { let c = n; for (let k = 0; k < 8; k++) c = c & 1 ? 0xedb88320 ^ (c >>> 1) : c >>> 1; t[n] = c >>> 0; }
  return t;
})();
function crc32(bytes) {
  let c = 0xffffffff;
  for (const b of bytes) c = CRC[(c ^ b) & 0xff] ^ (c >>> 8);
  return (c ^ 0xffffffff) >>> 0;
}
/** The PNG `png` with an iTXt chunk (keyword, UTF-8 text) after its IHDR (PNG spec §11.3.4.5). */
export function withText(png, keyword, text) {
  const enc = new TextEncoder(), data = [...enc.encode(keyword), 0, 0, 0, 0, 0, ...enc.encode(text)];
  const chunk = new Uint8Array(12 + data.length), view = new DataView(chunk.buffer);
  view.setUint32(0, data.length);
  chunk.set(enc.encode("iTXt"), 4); chunk.set(data, 8);
  view.setUint32(8 + data.length, crc32(chunk.subarray(4, 8 + data.length)));
  const at = 8 + 25;  // signature, then IHDR (length 4 + type 4 + 13 data + CRC 4)
  const out = new Uint8Array(png.length + chunk.length);
  out.set(png.subarray(0, at)); out.set(chunk, at); out.set(png.subarray(at), at + chunk.length);
  return out;
}

/** The SVG drawn on a canvas at `scale` (device pixels per SVG pixel), as PNG bytes. */
export async function pngBytes(svg, scale) {
  const w = Number(svg.getAttribute("width")), h = Number(svg.getAttribute("height"));
  const url = URL.createObjectURL(new Blob([new XMLSerializer().serializeToString(svg)], {type: "image/svg+xml"}));
  try {
    const img = new Image();
    img.decoding = "sync";
    await new Promise((ok, no) => { img.onload = ok; img.onerror = () => no(new Error("the picture could not be drawn")); img.src = url; });
    const cv = document.createElement("canvas");
    cv.width = Math.round(w * scale); cv.height = Math.round(h * scale);
    const g = cv.getContext("2d");
    g.drawImage(img, 0, 0, cv.width, cv.height);
    const blob = await new Promise((ok) => cv.toBlob(ok, "image/png"));
    if (!blob) throw new Error(`a ${cv.width} × ${cv.height} picture is too large for this browser`);
    return new Uint8Array(await blob.arrayBuffer());
  } finally { URL.revokeObjectURL(url); }
}

function download(blob, name) {
  const a = document.createElement("a");
  a.href = URL.createObjectURL(blob); a.download = name;
  document.body.append(a); a.click(); a.remove();
  setTimeout(() => URL.revokeObjectURL(a.href), 1000);
}
const baseName = () => `spectra-setting${S.setting}`;
export const SCALES = [1, 2, 3];

/** Wire the SVG and PNG buttons; `say` reports, `fail` shows an error. */
export function setupSnapshot({say, fail}) {
  $("save-svg").addEventListener("click", () => {
    try {
      download(new Blob([svgText()], {type: "image/svg+xml"}), `${baseName()}.svg`);
      say("picture saved as SVG");
    } catch (err) { fail("Save SVG", err, "picture"); }
  });
  $("save-png").addEventListener("click", async () => {
    const scale = Number($("png-scale").value) || 2;
    try {
      const svg = buildSVG();
      const png = withText(await pngBytes(svg, scale), "Description", describe());
      download(new Blob([png], {type: "image/png"}), `${baseName()}${scale === 1 ? "" : `@${scale}x`}.png`);
      say(`picture saved as PNG (${scale}×)`);
    } catch (err) { fail("Save PNG", err, "picture"); }
  });
}
