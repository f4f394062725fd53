// Projector mode (issue 28, item 4): the current setting's patches, large and side by side, on a
// chosen surround (black, grey, white: the seed's piece of white cardboard with a hole), readable
// from the back of a room, the numbers hidden on request. Key P (or the Projector button) enters
// and leaves it, N hides/shows the numbers, B / G / W choose the surround, Escape leaves.
//
// The patches are not recomputed here: each one takes the colour the explorer's own patch has
// (view.js paint(), the same computation) and follows it while the mode is open, through a
// MutationObserver on the patches and the number cards. The explorer's state is never touched,
// so it is the same after leaving; the mode's own choices (numbers, surround) are kept in
// localStorage and come back on the next entry.

import {$, el, fill} from "./dom.js";
import {S} from "./state.js";

/** Which of a setting's patches are shown side by side (data-i of #patches .patch). */
const SHOWN = {1: [0], 2: [0, 1], 3: [0, 1], 4: [1, 2], 5: [1, 2, 3]};
/** Settings whose patches touch (the border vanishes when the two match, as in SPECTRA). */
const TOUCHING = new Set([2, 3, 4]);
export const SURROUNDS = {black: "black", grey: "mid grey", white: "white (the seed's cardboard)"};
const SURROUND_KEYS = {b: "black", g: "grey", w: "white"};
const STORE = "spectrocolor.projector.v1";
/** Explorer keys that still work in the mode (defaults 1–8, 0 recall, 9 pair, X normalisation). */
const FORWARDED = /^[0-9xX]$/;

const P = {numbers: true, surround: "black", opener: null};

function load() {
  try {
    const o = JSON.parse(localStorage.getItem(STORE) || "{}");
    if (typeof o.numbers === "boolean") P.numbers = o.numbers;
    if (o.surround in SURROUNDS) P.surround = o.surround;
  } catch { /* a damaged entry: the defaults */ }
}
function save() {
  try { localStorage.setItem(STORE, JSON.stringify({numbers: P.numbers, surround: P.surround})); } catch { /* private mode */ }
}

const dialog = () => $("projector");
export const projectorOpen = () => Boolean(dialog() && dialog().open);

function build() {
  const d = el("dialog", {id: "projector", class: "projector", "aria-labelledby": "projector-title"},
    el("div", {class: "pj-bar"},
      el("h2", {id: "projector-title"}, "Projector"),
      el("button", {type: "button", id: "pj-numbers", "aria-pressed": "true", title: "Show or hide the numbers (N)"},
        el("kbd", {}, "N"), " numbers"),
      el("span", {class: "pj-group", role: "group", "aria-label": "Surround"}, "Surround:",
        Object.entries(SURROUNDS).map(([k, label]) => el("button", {type: "button", "data-surround": k,
          "aria-pressed": "false", title: `Surround: ${label} (${k[0].toUpperCase()})`},
        el("kbd", {}, k[0].toUpperCase()), ` ${k}`))),
      el("span", {class: "pj-hint"}, "keys 1–8, X as in the explorer"),
      el("button", {type: "button", id: "pj-leave", title: "Leave the projector view (P or Escape)"}, "Leave ", el("kbd", {}, "Esc"))),
    el("div", {id: "pj-stage", class: "pj-stage"}),
    el("p", {id: "pj-de", class: "pj-de"}),
    el("p", {id: "pj-caption", class: "pj-caption"}));
  document.body.append(d);
  $("pj-numbers").addEventListener("click", () => setNumbers(!P.numbers));
  d.querySelectorAll("[data-surround]").forEach((b) => b.addEventListener("click", () => setSurround(b.dataset.surround)));
  $("pj-leave").addEventListener("click", () => leave());
  d.addEventListener("keydown", onKey);
  d.addEventListener("close", () => {
    document.body.classList.remove("projecting");
    const back = P.opener && P.opener.isConnected && P.opener !== document.body ? P.opener : null;
    if (back) back.focus();
  });
  return d;
}

function onKey(ev) {
  if (ev.ctrlKey || ev.metaKey || ev.altKey) return;
  const k = ev.key.length === 1 ? ev.key.toLowerCase() : ev.key;
  if (k === "p") leave();
  else if (k === "n") setNumbers(!P.numbers);
  else if (k in SURROUND_KEYS) setSurround(SURROUND_KEYS[k]);
  else if (FORWARDED.test(ev.key)) {  // to the explorer's own key handler, outside the dialog
    document.body.dispatchEvent(new KeyboardEvent("keydown", {key: ev.key, shiftKey: ev.shiftKey, bubbles: true}));
  } else return;  // Escape: the dialog's own cancel; Tab, Enter, space: the buttons
  ev.preventDefault(); ev.stopPropagation();
}

function setNumbers(on) {
  P.numbers = on; save();
  const d = dialog();
  if (!d) return;
  d.classList.toggle("pj-no-numbers", !on);
  $("pj-numbers").setAttribute("aria-pressed", String(on));
  $("pj-numbers").lastChild.textContent = on ? " numbers" : " numbers (hidden)";
  refresh();
}
function setSurround(name) {
  P.surround = name; save();
  const d = dialog();
  if (!d) return;
  for (const k of Object.keys(SURROUNDS)) d.classList.toggle(`pj-${k}`, k === name);
  d.querySelectorAll("[data-surround]").forEach((b) => b.setAttribute("aria-pressed", String(b.dataset.surround === name)));
  refresh();
}

const text = (sel) => { const n = document.querySelector(sel); return n ? n.textContent.trim() : ""; };

/** Copy the explorer's patches (colour, name) and numbers into the projector's. */
function refresh() {
  const d = dialog();
  if (!d || !d.open) return;
  const shown = SHOWN[S.setting] || [0];
  const stage = $("pj-stage");
  stage.classList.toggle("touching", TOUCHING.has(S.setting));
  if (stage.dataset.setting !== String(S.setting) || stage.children.length !== shown.length) {
    stage.dataset.setting = String(S.setting);
    fill(stage, shown.map((i) => el("figure", {class: "pj-item", "data-i": i},
      el("div", {class: "pj-patch", role: "img"}),
      el("figcaption", {}, el("span", {class: "pj-name"}),
        el("span", {class: "pj-num"}, el("span", {class: "pj-xy"}), el("span", {class: "pj-lab"}), el("span", {class: "pj-hex"}))))));
  }
  for (const fig of stage.children) {
    const i = fig.dataset.i, src = document.querySelector(`#patches .patch[data-i='${i}']`);
    if (!src) continue;
    const name = text(`#patches .patch[data-i='${i}'] > .tag`), hex = text(`#numbers .card[data-i='${i}'] td.hex`);
    const patch = fig.querySelector(".pj-patch");
    patch.style.background = src.style.background;  // the explorer's own colour, as painted
    patch.setAttribute("aria-label", P.numbers && hex ? `${name}: ${hex}` : name);
    fig.querySelector(".pj-name").textContent = name;
    fig.querySelector(".pj-xy").textContent = `x y ${text(`#numbers .card[data-i='${i}'] td.xy`)}`;
    fig.querySelector(".pj-lab").textContent = `L* a* b* ${text(`#numbers .card[data-i='${i}'] td.lab`)}`;
    fig.querySelector(".pj-hex").textContent = hex;
  }
  const de = text("#numbers .de-card .de");
  $("pj-de").textContent = de && (S.setting === 2 || S.setting === 3 || S.setting === 4)
    ? `ΔE00 ${de}${text("#numbers .de-card .de-status") ? ` (${text("#numbers .de-card .de-status")})` : ""}` : "";
  $("pj-caption").textContent = `Surround ${SURROUNDS[P.surround]}. P or Esc leaves; N hides the numbers; B, G, W choose the surround.`;
}

let queued = false;
function schedule() {
  if (queued || !projectorOpen()) return;
  queued = true;
  requestAnimationFrame(() => { queued = false; refresh(); });
}

export function enter() {
  const d = dialog() || build();
  if (d.open) return;
  P.opener = document.activeElement;
  setNumbers(P.numbers); setSurround(P.surround);
  document.body.classList.add("projecting");
  d.showModal();
  refresh();
  $("pj-leave").focus();
}
export function leave() {
  const d = dialog();
  if (d && d.open) d.close();
}
export const toggle = () => (projectorOpen() ? leave() : enter());

/** Wire key P and the Projector button; follow the explorer's repaints while the mode is open. */
export function setupProjector() {
  load();
  for (const id of ["projector-open", "projector-touch"]) {
    const button = $(id);
    if (button) button.addEventListener("click", () => enter());
  }
  document.addEventListener("keydown", (ev) => {
    if (ev.key !== "p" && ev.key !== "P") return;
    if (ev.ctrlKey || ev.metaKey || ev.altKey || ev.defaultPrevented) return;
    const t = ev.target;
    if (t.closest && t.closest("select, input, textarea, dialog[open]")) return;
    enter(); ev.preventDefault();
  });
  const watch = new MutationObserver(schedule);
  for (const id of ["patches", "numbers"]) {
    watch.observe($(id), {subtree: true, childList: true, attributes: true, characterData: true,
      attributeFilter: ["style", "data-i"]});
  }
}
