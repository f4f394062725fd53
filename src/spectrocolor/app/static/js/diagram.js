// The CIE xy chromaticity diagram: spectral locus with wavelength labels, axes with tick values,
// the display's gamut triangle and white, the current colours as numbered markers filled with
// their patch colours, and a legend.

import {$, el, fill, svgEl} from "./dom.js";
import {S} from "./state.js";
import {cssColour} from "./view.js";

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
    svgEl("g", {id: "pts"}));
  fill(svg, parts);
  const dw = m.display_white_xy, cct = m.display_white ? m.display_white.cct_K : null;
  $("white-note").textContent = `${m.display}: white point x ${dw[0].toFixed(4)}, y ${dw[1].toFixed(4)}`
    + (cct ? `, CCT ${Math.round(cct)} K` : "") + ". Triangle: the colours this display can show.";
}

/** The markers of the current colours (numbered, in their patch colours) and their legend. */
export function drawPoints(colours, labels, server) {
  const g = $("pts");
  if (!g) return;
  const white = server ? server.white_xy : S.model.white_xy;
  const wc = document.querySelector("#chroma .white");
  wc.setAttribute("cx", white[0]); wc.setAttribute("cy", -white[1]);
  const marks = [], legend = [el("li", {}, el("span", {class: "key ring"}), "reference white")];
  let count = 0;
  colours.forEach((c, i) => {
    if ((S.setting === 4 || S.setting === 5) && i === 0) return;  // the white light itself
    const n = String(++count);
    legend.push(el("li", {}, el("span", {class: "key", style: `background:${cssColour(c)}`}, n), labels[i]));
    if (c.xy[0] === null) return;
    marks.push(svgEl("circle", {class: "pt", r: 0.016, cx: c.xy[0], cy: -c.xy[1], fill: cssColour(c)},
      svgEl("title", {}, labels[i])),
    svgEl("text", {class: "pt-n", x: c.xy[0], y: -c.xy[1] + 0.0075, "text-anchor": "middle"}, n));
  });
  fill(g, marks);
  fill($("legend"), legend);
}
