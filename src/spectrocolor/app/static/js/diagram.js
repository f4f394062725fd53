// The CIE xy chromaticity diagram: spectral locus with wavelength labels, axes with tick values,
// the display's gamut triangle and white, the current colours as numbered markers filled with
// their patch colours, and a legend.

import {$, el, fill, svgEl} from "./dom.js";
import {S} from "./state.js";
import {cssColour, additive, setText, setAttr, setBackground} from "./view.js";

const P = (x, y) => `${x.toFixed(4)},${(-y).toFixed(4)}`;
const LABELLED_NM = [460, 480, 490, 500, 520, 540, 560, 580, 600, 620, 700];

export function drawDiagram() {
  const m = S.model, svg = $("chroma");
  const parts = [];
  for (let i = 0; i <= 8; i++) {
    const v = i / 10;
    parts.push(svgEl("line", {class: "grid", x1: v, y1: 0, x2: v, y2: -0.9}),
      svgEl("line", {class: "grid", x1: 0, y1: -v, x2: 0.8, y2: -v}),
      svgEl("text", {class: "tick", x: v, y: 0.032, "text-anchor": "middle"}, v.toFixed(1)),
      svgEl("text", {class: "tick", x: -0.012, y: -v + 0.008, "text-anchor": "end"}, v.toFixed(1)));
  }
  parts.push(svgEl("line", {class: "axis", x1: 0, y1: 0, x2: 0.8, y2: 0}),
    svgEl("line", {class: "axis", x1: 0, y1: 0, x2: 0, y2: -0.9}));
  const locus = m.locus.xy.map(([x, y]) => P(x, y)).join(" ");
  parts.push(svgEl("polygon", {class: `locus ${S.filledLocus ? "filled" : ""}`, points: locus}));
  if (S.filledLocus) parts.push(svgEl("polygon", {class: "gamut-fill", points: m.primaries_xy.map(([x, y]) => P(x, y)).join(" ")}));
  parts.push(svgEl("polygon", {class: "gamut", points: m.primaries_xy.map(([x, y]) => P(x, y)).join(" ")}));
  m.locus.wavelengths_nm.forEach((w, i) => {
    if (!LABELLED_NM.includes(w)) return;
    const [x, y] = m.locus.xy[i];
    parts.push(svgEl("circle", {class: "nm-dot", r: 0.004, cx: x, cy: -y}),
      svgEl("text", {x: (x + (w < 520 ? -0.012 : 0.012)).toFixed(3), y: (-y + 0.008).toFixed(3),
        "text-anchor": w < 520 ? "end" : "start"}, String(w)));
  });
  parts.push(svgEl("text", {class: "axis-name", x: 0.74, y: -0.02}, "x"),
    svgEl("text", {class: "axis-name", x: 0.012, y: -0.86}, "y"),
    svgEl("circle", {class: "white", r: 0.009, cx: m.white_xy[0], cy: -m.white_xy[1]}),
    $("pts") || svgEl("g", {id: "pts"}));  // the markers survive a redraw of the diagram
  fill(svg, parts);
  const dw = m.display_white_xy, cct = m.display_white ? m.display_white.cct_K : null;
  $("white-note").textContent = `${m.display}: white point x ${dw[0].toFixed(4)}, y ${dw[1].toFixed(4)}`
    + (cct ? `, CCT ${Math.round(cct)} K` : "") + ". Triangle: the colours this display can show.";
}

/** The markers and legend entries of the current setting's colours, built once per setting. */
export function buildPoints(count) {
  const shown = [...Array(count).keys()].filter((i) => !((S.setting === 4 || S.setting === 5) && i === 0));
  fill($("pts"), shown.map((i, n) => svgEl("g", {class: "mark", "data-i": i},
    svgEl("circle", {class: "pt", r: 0.016}, svgEl("title")),
    svgEl("text", {class: "pt-n", "text-anchor": "middle"}, String(n + 1)))));
  fill($("legend"), el("li", {}, el("span", {class: "key ring"}), "reference white"),
    shown.map((i, n) => el("li", {"data-i": i}, el("span", {class: "key"}, String(n + 1)), el("span", {class: "name"}))));
}

/** Move the markers (numbered, in their patch colours) and update the legend. The white light
 * of settings 4 and 5 is the reference white itself (the ring). Only what changed is written
 * (issue 28, glitch 5). */
export function drawPoints(colours, labels, server) {
  const white = server ? server.white_xy : S.model.white_xy;
  const wc = document.querySelector("#chroma .white");
  setAttr(wc, "cx", String(white[0])); setAttr(wc, "cy", String(-white[1]));
  for (const g of $("pts").children) {
    const i = Number(g.dataset.i), c = colours[i];
    const display = c.xy[0] === null ? "none" : "";
    if (g.style.display !== display) g.style.display = display;
    if (c.xy[0] === null) continue;
    const dot = g.firstChild, n = g.lastChild;
    setAttr(dot, "cx", String(c.xy[0])); setAttr(dot, "cy", String(-c.xy[1])); setAttr(dot, "fill", cssColour(c));
    setText(dot.firstChild, labels[i]);
    setAttr(n, "x", String(c.xy[0])); setAttr(n, "y", String(-c.xy[1] + 0.0075));
  }
  mixLine(colours);
  for (const li of $("legend").children) {
    if (li.dataset.i === undefined) continue;
    const i = Number(li.dataset.i);
    setBackground(li.firstChild, cssColour(colours[i]));
    setText(li.lastChild, labels[i]);
  }
}

/** Setting 5 as two spotlights (issue 28 item 7): the segment joining the two lights, on which
 * their overlap lies (weighted by luminance); hidden otherwise. */
function mixLine(colours) {
  let line = $("mix-line");
  if (!line) {
    line = svgEl("line", {id: "mix-line", class: "mix-line"}, svgEl("title", {}, "additive mixtures of light 1 and light 2 lie on this line"));
    $("chroma").insertBefore(line, $("pts"));
  }
  const [a, b] = [colours[1], colours[2]];
  const shown = additive() && a && b && a.xy[0] !== null && b.xy[0] !== null;
  const display = shown ? "" : "none";
  if (line.style.display !== display) line.style.display = display;
  if (!shown) return;
  setAttr(line, "x1", String(a.xy[0])); setAttr(line, "y1", String(-a.xy[1]));
  setAttr(line, "x2", String(b.xy[0])); setAttr(line, "y2", String(-b.xy[1]));
}

function curve(g, w, h, values, top, colour, dash = []) {
  g.strokeStyle = colour; g.lineWidth = 1.5; g.setLineDash(dash); g.beginPath();
  values.forEach((v, k) => {
    const x = 4 + (w - 8) * k / (values.length - 1), y = h - 14 - (h - 24) * v / top;
    if (k === 0) g.moveTo(x, y); else g.lineTo(x, y);
  });
  g.stroke(); g.setLineDash([]);
}

function canvasOf(id) {
  const cv = $(id), dpr = window.devicePixelRatio || 1, w = cv.clientWidth, h = cv.clientHeight;
  cv.width = Math.round(w * dpr); cv.height = Math.round(h * dpr);
  const g = cv.getContext("2d");
  g.setTransform(dpr, 0, 0, dpr, 0, 0); g.clearRect(0, 0, w, h);
  g.font = "10px system-ui, sans-serif"; g.fillStyle = "#cfd4de";
  return [g, w, h];
}

/** SPECTRA's Figs. 9 and 10 for the current display, from /api/model: the primaries' emission
 * spectra (with ȳ) and the excitation function. Drawn while the panel is open. */
export function drawDisplayLight() {
  const m = S.model;
  if (!$("display-light").open || !m.emission) return;
  const P = m.emission.levels_per_drive;
  let [g, w, h] = canvasOf("primaries");
  const top = Math.max(...P.flat());
  ["#ff6b6b", "#7ad69b", "#6aa9ff"].forEach((c, i) => curve(g, w, h, P[i], top, c));
  curve(g, w, h, m.emission.ybar, Math.max(...m.emission.ybar), "#cfd4de", [3, 3]);
  g.fillText("400", 2, h - 2); g.fillText("700 nm", w - 40, h - 2); g.fillText(`peak ${top.toFixed(0)} levels`, 4, 10);
  fill($("primary-sources"), [...new Set(m.emission.sources)].join("; "));
  [g, w, h] = canvasOf("excitation");
  curve(g, w, h, m.excitation.emission, 1, "#ffd166");
  const codes = m.excitation.codes;
  g.fillText("0", 2, h - 2); g.fillText(`code ${codes[codes.length - 1]}`, w - 56, h - 2); g.fillText("γ = 1", 4, 10);
}
