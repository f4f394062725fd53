// The patches and the number cards: built once per setting from DOM nodes, then updated in place
// on every repaint (cheap enough for the frame of a drag, and never parsing text as HTML).

import {$, el, fill} from "./dom.js";
import {S, FULL} from "./state.js";
import {hexOf, lab} from "./colour.js";

const fmt = (v, n) => (v === null || v === undefined || !Number.isFinite(v)) ? "—" : v.toFixed(n);

// ---- issue 28, glitch 5: a repaint writes only what changed. Setting textContent replaces the
// text node even when the text is the same, and every replaced node is laid out again (a key
// press re-laid out 137 of the page's 577 boxes, most of them unchanged labels); so each write
// below compares first (reading text or an attribute never forces a layout).
/** Set `node`'s text, unless it already reads `text`. */
export function setText(node, text) { if (node && node.textContent !== text) node.textContent = text; }
/** Set attribute `name` of `node`, unless it already has `value`. */
export function setAttr(node, name, value) { if (node && node.getAttribute(name) !== value) node.setAttribute(name, value); }
/** Set `node`'s background to the CSS colour `css`, unless it was last set to it here. */
export function setBackground(node, css) {
  if (node && node.__bg !== css) { node.style.background = css; node.__bg = css; }
}
// ---- end of glitch 5's part

/** The label of a choice, from the registries via /api/options (choices: [name, label, help] rows). */
const choiceRow = (kind, v) => (((S.options && S.options.choices) || {})[kind] || []).find(([n]) => n === v);
export const gamutLabel = (g) => (choiceRow("gamut", g) || [g, g])[1];
const gamutAction = (g) => ((S.options && S.options.gamut_actions) || {})[g] || "";

/** What each setting evaluates: the spectra sent to the library, their labels, the pairs. */
export function evalSpec() {
  const d = S.dists[S.setting], name = (i) => displayName(S.setting, i);
  switch (S.setting) {
    case 1: return {spectra: [d[0]], labels: [name(0)], pairs: []};
    case 2: case 3: return {spectra: [d[0], d[1]], labels: [name(0), name(1)], pairs: [[0, 1]]};
    case 4: return {spectra: [Array(S.wl.length).fill(FULL), d[1], d[2]], illuminant: d[0],
      labels: [`illuminant ${name(0)} (perfect white)`, name(1), name(2)], pairs: [[1, 2]]};
    case 5: {
      const E = Array(S.wl.length).fill(FULL);
      if (additive()) {  // issue 28 item 7: the server adds the two lights (mixing.additive_mix)
        return {spectra: [E, d[0], d[1], sum()], request: {spectra: [E, d[0], d[1]], additive: [[1, 2]]},
          labels: ["one spotlight, no filter (E)", `light 1: ${name(0)}`, `light 2: ${name(1)}`, "both lights (overlap)"], pairs: []};
      }
      return {spectra: [E, d[0], d[1], product()],
        labels: ["initial light (E)", name(0), name(1), "through both filters"], pairs: []};
    }
  }
}
export function product() { const [a, b] = S.dists[5]; return a.map((v, k) => v * b[k] / FULL); }
// ---- issue 28 item 7: setting 5 as two spotlights (additive mixing)
/** Setting 5 shows two spotlights, each through its filter, overlapping on a white screen. */
export const additive = () => S.setting === 5 && S.mode5 === "additive";
/** The overlap of the two spotlights: the sum of the lights, wavelength by wavelength (0–60). */
export function sum() { const [a, b] = S.dists[5]; return a.map((v, k) => v + b[k]); }

/** A distribution's name, "(edited)" once its bars were changed by hand. */
export function displayName(n, i) {
  const base = S.names[n][i] || "";
  return S.edited[n][i] ? `${base || "distribution"} (edited)` : base;
}

// ---------------------------------------------------------------- building
const patch = (i, extra = {}) => el("div", {class: `patch ${extra.cls || ""}`, "data-i": i, style: extra.style},
  el("span", {class: "tag"}), extra.inner);

function patchbox(cls, label, ...children) {
  return el("div", {class: `patchbox ${cls}`, role: "img", "aria-label": label}, ...children);
}

export function buildPatches() {
  let boxes;
  switch (S.setting) {
    case 1: boxes = [patchbox("", "", patch(0))]; break;
    case 2: case 3: boxes = [patchbox("split", "", patch(0), patch(1))]; break;
    case 4: boxes = [patchbox("", "", patch(0, {inner: [patch(1, {cls: "inner", style: "left:14%"}),
      patch(2, {cls: "inner", style: "left:60%"})]}))]; break;
    case 5: boxes = additive()
      ? [patchbox("spots", "", patch(1), patch(3, {cls: "overlap"}), patch(2)), patchbox("filters", "", patch(0))]
      : [patchbox("", "", patch(0, {inner: patch(3, {cls: "inner", style: "left:37%"})})),
        patchbox("filters", "", patch(1), patch(2))]; break;
  }
  fill($("patches"), boxes);
  PATCHES = [...$("patches").querySelectorAll(".patch")].map((p) => ({node: p, i: Number(p.dataset.i), tag: p.querySelector(".tag")}));
  BOXES = [...$("patches").querySelectorAll(".patchbox")].map((box) => ({node: box,
    members: [...box.querySelectorAll(".patch")].map((p) => Number(p.dataset.i))}));
}
/** The patches and their boxes as built (paint looks nothing up). */
let PATCHES = [], BOXES = [];

const ROWS = [
  ["XYZ", "X Y Z", "CIE tristimulus values; Y = 100 for the full spectrum (settings 1–3, 5) or the perfect white under the illuminant (4)."],
  ["lms", "L M S", "Cone responses: the distribution weighted by the CIE 2006 (Stockman–Sharpe) cone fundamentals of the observer's field (2° or 10°), in per cent of what the full spectrum (settings 1–3, 5) or the perfect white under the illuminant (4) gives each cone: that white is L = M = S = 100. The bars show the three on one scale (full width = 100)."],
  ["xy", "x y", "Chromaticity coordinates x = X/(X+Y+Z), y = Y/(X+Y+Z)."],
  ["lab", "L* a* b*", "CIELAB relative to the reference white (L* = 100 for it)."],
  ["rgb", "linear R G B", "Linear display RGB after normalisation, before gamut handling: 0–1 is what the display can show."],
  ["codes", "codes r g b", "The numbers sent to the display (8-bit 0–255; SPECTRA's monitor: 6-bit 0–63), and as hex."],
  ["dom", "λd, purity", "Dominant wavelength (λc: complementary, for purples) and excitation purity relative to the reference white: 0 = white, 1 = spectral colour."],
];

// The L M S bars: three thin horizontal bars (long-, medium-, short-wave cone), full width = 100.
const LMS_BARS = [["L", "#c0392b"], ["M", "#27ae60"], ["S", "#2e6fd8"]];
const lmsBar = ([name, colour]) => el("span", {class: "lms-bar", "data-cone": name, title: name,
  style: `display:block;height:4px;margin:1px 0;width:0;max-width:60px;background:${colour}`});

function paintLMS(cell, bars, dom, note) {
  const v = dom ? dom.LMS : null;
  setText(cell, !v ? "…" : v.map((x) => fmt(x, 2)).join("  "));
  setAttr(cell, "title", note || "");
  // while the server's answer is pending (a drag's local repaint) the bars keep their last
  // lengths, dimmed, rather than dropping to zero and jumping back
  bars.forEach((b, j) => {
    const opacity = v ? "1" : "0.35";
    if (b.style.opacity !== opacity) b.style.opacity = opacity;
    if (!v) return;
    const x = v[j] !== null && Number.isFinite(v[j]) ? Math.max(0, Math.min(v[j], 100)) : 0;
    const width = `${(0.6 * x).toFixed(1)}px`;
    if (b.__width !== width) { b.style.width = width; b.__width = width; }
  });
}

export function buildCards(count) {
  const cards = [];
  if (evalSpec().pairs.length) {
    cards.push(el("div", {class: "card de-card"},
      el("h3", {}, el("span", {class: "de-title"}), " ", el("span", {class: "de"})),
      el("div", {class: "status de-status"}),
      el("p", {class: "explain"}, `CIEDE2000 colour difference of the two ${S.setting === 4 ? "samples under the illuminant" : "lights"}; below about 1 it is hardly visible side by side.`)));
  }
  for (let i = 0; i < count; i++) {
    cards.push(el("div", {class: "card", "data-i": i},
      el("h3", {}, el("span", {class: "sw"}), el("span", {class: "cname"})),
      el("table", {}, el("tbody", {}, ROWS.map(([cls, head, help]) => el("tr", {},
        el("th", {scope: "row", title: help}, head), el("td", {class: cls}), cls === "codes" ? el("td", {class: "hex"})
          : cls === "lms" ? el("td", {class: "lms-bars", "aria-hidden": "true"}, ...LMS_BARS.map(lmsBar)) : null)))),
      el("div", {class: "status"}),
      el("div", {class: "badge", hidden: true}, el("span", {class: "badge-text"}),
        el("button", {class: "badge-switch", type: "button"}))));
  }
  fill($("numbers"), cards);
  CARDS = [];
  for (const card of $("numbers").querySelectorAll(".card[data-i]")) {
    const cells = Object.fromEntries(ROWS.map(([cls]) => [cls, card.querySelector(`td.${cls}`)]));
    cells.hex = card.querySelector("td.hex");
    cells.bars = [...card.querySelectorAll("td.lms-bars .lms-bar")];
    CARDS[Number(card.dataset.i)] = {sw: card.querySelector(".sw"), cname: card.querySelector(".cname"), cells,
      xyzHead: cells.XYZ.previousElementSibling, status: card.querySelector(".status"),
      badge: card.querySelector(".badge"), badgeText: card.querySelector(".badge-text"),
      badgeSwitch: card.querySelector(".badge-switch")};
  }
  const de = $("numbers").querySelector(".de-card");
  DE = de && {title: de.querySelector(".de-title"), value: de.querySelector(".de"), status: de.querySelector(".de-status")};
}
/** The number cards' cells as built, by colour (paint looks nothing up). */
let CARDS = [], DE = null;

// ---------------------------------------------------------------- updating
export function cssColour(c) {
  const [r, g, b] = c.rgb_encoded;
  if (S.display === "Display P3") return `color(display-p3 ${r} ${g} ${b})`;
  return `rgb(${(r * 255).toFixed(3)}, ${(g * 255).toFixed(3)}, ${(b * 255).toFixed(3)})`;
}

function statusOf(c, gamut) {
  if (!(c.XYZ[1] > 0)) return ["black: no light", ""];
  if (!c.in_gamut) {
    const what = [];
    if (c.negative.length) what.push(`${c.negative.join(", ")} negative`);
    if (c.over.length) what.push(`${c.over.join(", ")} above 1`);
    if (gamut === "flag") return [`cannot be reproduced (${what.join("; ")})`, "bad"];
    return [`outside the display (${what.join("; ")})`, "warn"];
  }
  return S.normalise === "per-colour" ? ["Optimised!", "opt"] : ["", ""];
}

/** Repaint patches and numbers from `colours` (local fast path, or the server's answer). Only
 * what changed is written (setText): a key press costs a frame otherwise (issue 28, glitch 5). */
export function paint(colours, server) {
  const e = evalSpec(), m = S.model;
  const gamut = server ? server.gamut : S.gamut;  // what was applied (local: what was asked)
  const local = S.localWhite;
  const css = colours.map(cssColour), hex = colours.map((c) => hexOf(c.codes, m));
  const statuses = colours.map((c) => statusOf(c, gamut));
  for (const p of PATCHES) {
    const i = p.i;
    setBackground(p.node, css[i]);
    setText(p.tag, e.labels[i]);
    setAttr(p.node, "title", `${e.labels[i]}: ${hex[i]}${statuses[i][0] ? ", " + statuses[i][0] : ""}`);
  }
  // SPECTRA's step 1 in "spectra-exact": one k per channel (model.channel_factors; 1 otherwise)
  const k = (m && m.channel_factors) || [1, 1, 1];
  const exact = S.normalise === "spectra-exact";
  colours.forEach((c, i) => {
    const card = CARDS[i];
    if (!card) return;
    const [status, cls] = statuses[i], cell = card.cells;
    setBackground(card.sw, css[i]);
    setText(card.cname, e.labels[i]);
    setText(cell.XYZ, c.XYZ.map((v, j) => fmt(v * k[j], 2)).join("  "));
    setAttr(cell.XYZ, "title", exact
      ? `SPECTRA's step 1: one k per channel, so the full spectrum shows X = Y = Z = 100 as in SPECTRA. CIE (one k for all three): ${c.XYZ.map((v) => fmt(v, 3)).join("  ")}. x y, L*a*b* and λd are CIE's.`
      : "");
    setText(card.xyzHead, exact ? "X Y Z (SPECTRA k)" : "X Y Z");
    setText(cell.xy, c.xy.map((v) => fmt(v, 4)).join("  "));
    const L = server ? server.colours[i].lab : lab(c.XYZ, local);
    setText(cell.lab, L.map((v) => fmt(v, 1)).join("  "));
    setAttr(cell.lab, "title", server && server.lab_note ? server.lab_note : "");
    setText(cell.rgb, c.rgb_unmapped.map((v) => fmt(v, 3)).join("  "));
    setText(cell.codes, c.codes.join("  "));
    setText(cell.hex, hex[i]);
    const dom = server ? server.colours[i] : null;
    setText(cell.dom, !dom ? "…" : dom.dominant_nm === null ? (dom.dominant_note ? "— (undefined: see the tooltip)" : "— (the white itself)")
      : `${dom.complementary ? "λc" : "λd"} ${fmt(dom.dominant_nm, 1)} nm${dom.complementary ? " (compl.)" : ""}, p ${fmt(dom.purity, 3)}`);
    setAttr(cell.dom, "title", dom && dom.dominant_note ? dom.dominant_note : "");
    paintLMS(cell.lms, cell.bars, dom, server ? server.lms_note : "");
    setText(card.status, status);
    setAttr(card.status, "class", `status ${cls}`);
    const badge = card.badge, hidden = c.in_gamut || !(c.XYZ[1] > 0);
    if (badge.hidden !== hidden) badge.hidden = hidden;
    if (!hidden) {
      const channels = [...c.negative.map((ch) => `${ch} negative`), ...c.over.map((ch) => `${ch} above 1`)].join(", ");
      const applied = dom ? dom.gamut_applied || gamut : gamut;
      setText(card.badgeText, `${channels}: ${gamutAction(applied) || gamutLabel(applied)}`);
      setAttr(badge, "title", dom && dom.explanation ? dom.explanation : `${gamutLabel(applied)}: ${gamutAction(applied)}`);
      const strict = gamut === "flag";
      setText(card.badgeSwitch, strict ? "show the nearest colour" : "strict: cannot be reproduced");
      const preferred = (S.options.defaults || {}).gamut;
      const to = strict ? (preferred && preferred !== "flag" ? preferred : "desaturate") : "flag";
      if (card.badgeSwitch.dataset.gamut !== to) card.badgeSwitch.dataset.gamut = to;
    }
  });
  for (const box of BOXES) {
    const shown = box.members.map((i) => `${e.labels[i]} ${hex[i]}${colours[i].in_gamut ? "" : " (outside the display)"}`);
    setAttr(box.node, "aria-label", `Colour patch: ${shown.join("; ")}`);
  }
  if (S.setting === 2 || S.setting === 3) {
    // SPECTRA: the border vanishes when the two displayed lights are the same (equal codes)
    const same = colours[0].in_gamut && colours[1].in_gamut && colours[0].codes.every((v, j) => v === colours[1].codes[j]);
    const split = BOXES.find((b) => b.node.classList.contains("split"));
    if (split && split.node.classList.contains("metameric") !== same) split.node.classList.toggle("metameric", same);
  }
  paintDeltaE(server);
}

function paintDeltaE(server) {
  if (!DE) return;
  setText(DE.title, `ΔE00 between ${S.setting === 4 ? "the samples" : "the two"}:`);
  if (!server || !server.delta_e_2000.length) { setText(DE.value, "…"); return; }
  // Under B each patch is scaled on its own, so the split patch compares the lights as shown;
  // the unscaled lights' difference is given beside it.
  const scaled = S.normalise === "per-colour";
  const de = scaled ? server.delta_e_2000_shown[0] : server.delta_e_2000[0];
  setText(DE.value, fmt(de, 2));
  if (de === null) {  // CIELAB undefined for this reference white (the server says why)
    setText(DE.status, server.lab_note || "undefined"); setAttr(DE.status, "class", "status de-status"); return;
  }
  setText(DE.status, [de < 0.5 ? "metameric" : "", scaled ? `as shown (B); unscaled lights ${fmt(server.delta_e_2000[0], 2)}` : ""]
    .filter(Boolean).join(" · "));
  setAttr(DE.status, "class", `status de-status ${de < 0.5 ? "opt" : ""}`);
}

/** Mark results that could not be recomputed (or clear the mark). */
export function markStale(reason) {
  S.stale = Boolean(reason);
  for (const id of ["patches", "numbers"]) {
    const node = $(id);
    if (node.classList.contains("stale") !== S.stale) node.classList.toggle("stale", S.stale);
  }
  const note = $("stale-note");
  if (note.hidden !== !S.stale) note.hidden = !S.stale;
  setText(note, S.stale ? `Not recomputed (${reason}): the colours and numbers shown belong to an earlier state, or are missing.` : "");
}
