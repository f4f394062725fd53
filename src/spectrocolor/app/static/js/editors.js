// The bar editors: one canvas per distribution, each an ARIA slider for its selected bin
// ("550 nm, 18 of 30"), edited by mouse, finger or keys.

import {$, el, fill} from "./dom.js";
import {S, EDITORS, FULL, quantise, remember} from "./state.js";
import {displayName, product, additive, sum, setText, setAttr} from "./view.js";

const PAD_TOP = 14, PAD_BOTTOM = 16;
const OUTLINE = "#d7dbe4";  // bar outline: ≥ 3:1 against the panel (#1e2128) for every tint

export const editorCount = () => EDITORS[S.setting].length;
export const cursorOf = (i) => S.cursor[`${S.setting}:${i}`] ?? Math.floor(S.wl.length / 2);

/** Build the editors of the current setting; `onEdit` runs after every change of levels. */
export function buildEditors(onEdit) {
  const names = EDITORS[S.setting];
  const readonly = S.setting === 5 ? [additive() ? "sum (both lights)" : "product"] : [];
  const box = $("editors");
  box.className = names.length + readonly.length === 3 ? "three" : names.length === 2 ? "two" : "";
  fill(box, [...names, ...readonly].map((n, i) => {
    const ro = i >= names.length;
    const canvas = el("canvas", ro
      ? {role: "img", "aria-label": additive() ? "the sum of the two lights: where both spotlights overlap (scale 0–60)"
        : "the product of the two filters: light through both"}
      : {role: "slider", tabindex: 0, "aria-label": `${n}: level of the selected bin`,
        "aria-valuemin": 0, "aria-valuemax": FULL, "aria-orientation": "vertical"});
    return el("div", {class: `editor ${ro ? "readonly" : ""}`, "data-e": i},
      el("div", {class: "head"}, el("span", {}, el("b", {}, n), " ", el("span", {class: "pname"})),
        el("span", {class: "cur", "aria-hidden": "true"})),
      canvas);
  }));
  box.querySelectorAll(".editor").forEach((ed) => {
    const i = Number(ed.dataset.e);
    if (i >= names.length) return;
    const cv = ed.querySelector("canvas");
    cv.addEventListener("focus", () => { S.active[S.setting] = i; drawEditors(); });
    let last = null;
    const at = (ev) => {
      const r = cv.getBoundingClientRect();
      const k = Math.min(S.wl.length - 1, Math.max(0, Math.floor((ev.clientX - r.left) / r.width * S.wl.length)));
      const h = r.height - PAD_TOP - PAD_BOTTOM;
      const v = Math.min(FULL, Math.max(0, (1 - (ev.clientY - r.top - PAD_TOP) / h) * FULL));
      return [k, quantise(v, S.step)];
    };
    cv.addEventListener("pointerdown", (ev) => {
      ev.preventDefault(); cv.setPointerCapture(ev.pointerId); cv.focus({preventScroll: true});
      remember();
      S.active[S.setting] = i; const [k, v] = at(ev); last = [k, v];
      S.cursor[`${S.setting}:${i}`] = k; setLevel(i, k, v); onEdit();
    });
    cv.addEventListener("pointermove", (ev) => {
      if (!last || (!(ev.buttons & 1) && ev.pointerType === "mouse")) return;
      const [k, v] = at(ev);
      const [k0, v0] = last, n = Math.abs(k - k0);
      for (let j = 1; j <= n; j++) setLevel(i, k0 + Math.sign(k - k0) * j, v0 + (v - v0) * j / n);
      if (n === 0) setLevel(i, k, v);
      last = [k, v]; S.cursor[`${S.setting}:${i}`] = k; S.editing = i; onEdit(false);
    });
    const stop = () => { if (last) { last = null; onEdit(true); } };
    cv.addEventListener("pointerup", stop); cv.addEventListener("pointercancel", stop);
  });
}

/** Set bin k of editor i (setting 3: what one side loses, the other gains). */
export function setLevel(i, k, v) {
  v = quantise(v, S.step);
  const d = S.dists[S.setting];
  if (S.setting === 3) {
    const total = d[0][k] + d[1][k];
    v = Math.min(Math.min(FULL, total), Math.max(Math.max(0, total - FULL), v));
    d[i][k] = v; d[1 - i][k] = Math.round((total - v) * 1e9) / 1e9;
    S.edited[3][0] = S.edited[3][1] = true;
  } else {
    d[i][k] = Math.min(FULL, Math.max(0, v));
    S.edited[S.setting][i] = true;
  }
}

// ---- issue 28, glitch 5: each canvas's CSS size is kept from a ResizeObserver, so a redraw
// reads no layout (clientWidth after the patches' text changed forced a layout in the key press's
// handler); a canvas whose size changes is redrawn in that frame, before it is painted.
const sizes = new WeakMap(), redraws = new WeakMap();
const resized = new ResizeObserver((entries) => {
  const again = new Set();
  for (const entry of entries) {
    const box = entry.contentBoxSize && entry.contentBoxSize[0];
    const size = box ? [box.inlineSize, box.blockSize] : [entry.contentRect.width, entry.contentRect.height];
    const old = sizes.get(entry.target);
    sizes.set(entry.target, size);
    if (old && (old[0] !== size[0] || old[1] !== size[1]) && redraws.has(entry.target)) again.add(redraws.get(entry.target));
  }
  for (const redraw of again) redraw();
});
/** The CSS size [w, h] of canvas `cv`: observed, or read once (a canvas drawn before its first
 * observation, or while it was hidden). `redraw` draws it again when its size changes. */
function cssSize(cv, redraw) {
  let size = sizes.get(cv);
  if (!size || !size[0]) {
    size = [cv.clientWidth, cv.clientHeight];
    sizes.set(cv, size);
    resized.observe(cv);
  }
  redraws.set(cv, redraw);
  return size;
}
// ---- end of glitch 5's part

function plotArea(cv, redraw) {
  const dpr = window.devicePixelRatio || 1;
  const [w, h] = cssSize(cv, redraw);
  if (cv.width !== Math.round(w * dpr) || cv.height !== Math.round(h * dpr)) {
    cv.width = Math.round(w * dpr); cv.height = Math.round(h * dpr);
  }
  const g = cv.getContext("2d");
  g.setTransform(dpr, 0, 0, dpr, 0, 0); g.clearRect(0, 0, w, h);
  return [g, w, h];
}

function grid(g, w, hh, top = FULL) {
  g.strokeStyle = "#3a3f4b"; g.lineWidth = 1;
  for (const L of top > FULL ? [20, 40, 60] : [10, 20, 30]) {
    const y = PAD_TOP + hh * (1 - L / top);
    g.beginPath(); g.moveTo(0, y); g.lineTo(w, y); g.stroke();
  }
}

function labels(g, w, h, hh, top = FULL) {  // drawn over the bars, with a dark halo so they stay readable
  g.font = "10px system-ui, sans-serif"; g.lineWidth = 3; g.strokeStyle = "#15171c"; g.fillStyle = "#cfd4de";
  const text = (t, x, y) => { g.strokeText(t, x, y); g.fillText(t, x, y); };
  for (const L of top > FULL ? [20, 40, 60] : [10, 20, 30]) text(String(L), 2, PAD_TOP + hh * (1 - L / top) - 2);
  const K = S.wl.length, bw = w / K;
  for (const nm of [400, 500, 600, 700]) {
    const k = S.wl.indexOf(nm);
    if (k >= 0) text(nm === 700 ? "700 nm" : String(nm), Math.min(w - 34, k * bw), h - 3);
  }
}

const redrawEditors = () => drawEditors();

/** Redraw the bar editors: all of them, or (during a drag) only editor `only` and those that
 * follow it (setting 3's other side, setting 5's product). */
export function drawEditors(only = null) {
  const names = EDITORS[S.setting];
  const follows = (i) => only === null || i === only || S.setting === 3 || (S.setting === 5 && i === 2);
  const lists = [...S.dists[S.setting]];
  if (S.setting === 5) lists.push(additive() ? sum() : product());
  const tints = S.model ? S.model.tints : null;
  document.querySelectorAll("#editors .editor").forEach((ed, i) => {
    if (!follows(i)) return;
    const cv = ed.querySelector("canvas");
    const [g, w, h] = plotArea(cv, redrawEditors);
    const levels = lists[i], K = levels.length, bw = w / K, hh = h - PAD_TOP - PAD_BOTTOM;
    const top = S.setting === 5 && i === 2 && additive() ? 2 * FULL : FULL;  // the sum reaches 60
    grid(g, w, hh, top);
    const gap = K <= 61 ? 1 : 0;
    for (let k = 0; k < K; k++) {
      const t = tints ? tints[k] : [0.6, 0.6, 0.6];
      g.fillStyle = `rgb(${t[0] * 255},${t[1] * 255},${t[2] * 255})`;
      const bh = hh * levels[k] / top;
      g.fillRect(k * bw + gap, PAD_TOP + hh - bh, Math.max(1, bw - 2 * gap), bh);
    }
    // the outline of the distribution, in a colour that stands out from the panel and every bar
    g.strokeStyle = OUTLINE; g.lineWidth = 1.5; g.beginPath();
    for (let k = 0; k < K; k++) {
      const y = PAD_TOP + hh * (1 - levels[k] / top);
      if (k === 0) g.moveTo(0, y); else g.lineTo(k * bw, y);
      g.lineTo((k + 1) * bw, y);
    }
    g.stroke();
    if (S.setting === 3 && i < 2) {  // the conserved total
      g.strokeStyle = "rgba(255,255,255,0.55)"; g.setLineDash([3, 3]); g.beginPath();
      for (let k = 0; k < K; k++) { const y = PAD_TOP + hh * (1 - (S.dists[3][0][k] + S.dists[3][1][k]) / FULL); g.lineTo(k * bw, y); g.lineTo((k + 1) * bw, y); }
      g.stroke(); g.setLineDash([]);
    }
    labels(g, w, h, hh, top);
    const active = i < names.length && S.active[S.setting] === i;
    if (ed.classList.contains("active") !== (active && names.length > 1)) ed.classList.toggle("active", active && names.length > 1);
    if (i >= names.length) return;
    const k = cursorOf(i);
    g.strokeStyle = active ? "#6aa9ff" : "#8b93a5"; g.lineWidth = 2; g.strokeRect(k * bw + 1, PAD_TOP, Math.max(2, bw - 2), hh);
    const value = levels[k], digits = S.step === 10 && Number.isInteger(value) ? 0 : 1;
    setText(ed.querySelector(".cur"), `${S.wl[k]} nm: ${value.toFixed(digits)} of ${FULL}`);
    setText(ed.querySelector(".pname"), displayName(S.setting, i));
    setAttr(cv, "aria-valuenow", String(value));
    setAttr(cv, "aria-valuetext", `${S.wl[k]} nm, ${value.toFixed(digits)} of ${FULL}`);
  });
}

/** Step 4 of SPECTRA: the light the display emits for a colour, C(λ) = Σ γ(code)·primary(λ),
 * drawn with the distribution it matches, both in levels on one scale (the top of the graph is
 * the larger peak). */
export function drawEmitted(cv, emitted, target) {
  const [g, w, h] = plotArea(cv, () => drawEmitted(cv, emitted, target));
  const hh = h - PAD_TOP - PAD_BOTTOM;
  const top = Math.max(...emitted, ...target);
  g.font = "10px system-ui, sans-serif"; g.fillStyle = "#cfd4de";
  g.fillText(`peak ${top.toFixed(0)} levels`, 2, 10);
  g.fillText("400", 2, h - 3); g.fillText("700 nm", w - 38, h - 3);
  const line = (values, colour, dash) => {
    if (!(top > 0)) return;
    g.strokeStyle = colour; g.lineWidth = 1.5; g.setLineDash(dash); g.beginPath();
    values.forEach((v, k) => {
      const x = (k + 0.5) * w / values.length, y = PAD_TOP + hh * (1 - v / top);
      if (k === 0) g.moveTo(x, y); else g.lineTo(x, y);
    });
    g.stroke(); g.setLineDash([]);
  };
  line(target, "#8b93a5", [3, 3]);
  line(emitted, "#ffd166", []);
}
