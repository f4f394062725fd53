// Guided demonstrations (issue 28, item 2): the "Demos" panel of the explorer and of the labs.
// The demos are small JSON files (static/demos/, format in docs/demos.md), checked by the server
// and served by GET /api/demos. Choosing one loads its state (the explorer's URL state, or a lab's
// hash), says what to look at and asks a question; "Show me" loads the state after the suggested
// change, "Reveal the answer" shows what should be seen. Back returns to what was there before.
//
// The explorer mounts the panel from main.js (mountDemos with its loader); a lab page only loads
// this module, and the panel mounts itself with the lab's own hash state.

import {clientHeaders} from "./client.js";
import {S, encodeLevels} from "./state.js";

const LAB = location.pathname.startsWith("/labs/") ? location.pathname.split("/")[2] : null;
const LAB_NAMES = {thinfilm: "thin films", reflectance: "smoothest reflectance", solid: "object-colour solid",
  light: "light sources"};

const make = (tag, attrs = {}, ...children) => {
  const e = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs)) {
    if (k === "text") e.textContent = v; else if (v !== false && v !== null) e.setAttribute(k, v === true ? "" : v);
  }
  e.append(...children.filter((c) => c !== null && c !== undefined));
  return e;
};

async function getJSON(path) {
  const r = await fetch(path, {headers: clientHeaders()});
  const data = await r.json();
  if (!r.ok) throw new Error(data.error || `request failed (${r.status})`);
  return data;
}

// ---------------------------------------------------------------- the explorer's URL state
let presets10 = null;  // the defaults on SPECTRA's grid: demos are written on it (31 bins, 10 nm)

/** A default's levels and name for editor `i` of setting `n` (as the keys 1–8 load them). */
function presetOf(P, n, i, key, mode5 = "series") {
  const find = (list) => list.find((q) => q.key === key);
  const first = (q) => (q.cycle ? q.cycle[0].levels : q.levels);
  if (n === 1) { const q = find(P.setting1); return [first(q), q.name]; }
  if (n === 2) { const q = find(P.setting2[i === 0 ? "left" : "right"]); return [first(q), q.name]; }
  if (n === 4) {
    if (i === 0) { const q = find(P.setting4.illuminants); return [q.levels, q.name]; }
    const q = find(P.setting4.samples); return [i === 1 ? q.left : q.right, `${q.name} ${i}`];
  }
  const q = find(n === 3 ? P.setting3 : mode5 === "additive" ? P.setting5_additive : P.setting5);
  const parts = q.name.split(":")[0].split(n === 3 ? " / " : " and ");
  return [i === 0 ? q.left : q.right, (parts[i] || parts[0]).trim()];
}

/** The explorer's address (query) for a demo state: every option pinned (the page's defaults
 * unless the demo names one), so the demo shows the same wherever the page was. */
export async function explorerSearch(where, st) {
  const n = Number(where.slice("setting".length));
  presets10 = presets10 || await getJSON("/api/presets?step_nm=10");
  const d = (S.options && S.options.defaults) || {};
  const q = new URLSearchParams({s: n, b: 10, o: "1931", d: st.display || d.display || "sRGB",
    g: st.gamut || d.gamut || "desaturate", n: st.normalise || d.normalise || "fixed"});
  const a = st.adaptation || d.adaptation;
  if (a) q.set("a", a);
  if (n === 5 && st.mode === "additive") q.set("m", "add");  // setting 5 as two spotlights
  st.distributions.forEach((spec, i) => {
    let levels, name;
    if (spec.preset) [levels, name] = presetOf(presets10, n, i, spec.preset, st.mode);
    else if (spec.levels) [levels, name] = [spec.levels, ""];
    else [levels, name] = [Array(31).fill(spec.constant), `constant ${spec.constant}`];
    levels = levels.slice();
    for (const [nm, v] of Object.entries(spec.set || {})) levels[(Number(nm) - 400) / 10] = v;
    q.set(`l${i}`, encodeLevels(levels));
    q.set(`t${i}`, spec.name || name);
  });
  q.set("e", st.distributions.map(() => "0").join(""));
  return `?${q}`;
}

// ---------------------------------------------------------------- a lab's hash state
function labHost() {
  return {
    where: () => LAB,
    title: () => `Demos · ${LAB_NAMES[LAB] || LAB}`,
    load: async (st) => {
      const hash = "#" + new URLSearchParams(Object.entries(st).map(([k, v]) => [k, String(v)]));
      history.pushState(null, "", `${location.pathname}${location.search}${hash}`);
      window.dispatchEvent(new PopStateEvent("popstate"));
    },
    anchor: () => document.querySelector("header"),
  };
}

// ---------------------------------------------------------------- the panel
/** Mount the Demos button and panel. `host`: {where() → "setting1"…"setting5" or a lab, title(),
 * load(state) → Promise (the state is a demo's, or for the explorer its address), anchor()}. */
export function mountDemos(host) {
  const open = make("button", {id: "demos-open", type: "button", "aria-expanded": "false",
    "aria-controls": "demos-panel", title: "Guided demonstrations from SPECTRA's report: load one, look, answer, reveal"}, "Demos");
  const list = make("ul", {id: "demos-list", class: "demos-list"});
  const card = make("div", {id: "demo-card", class: "demo-card", hidden: true});
  const panel = make("aside", {id: "demos-panel", class: "demos-panel", "aria-labelledby": "demos-title", hidden: true},
    make("div", {class: "demos-head"}, make("h2", {id: "demos-title"}),
      make("button", {id: "demos-close", type: "button", "aria-label": "Close the demos", title: "Close"}, "×")),
    list, card);
  const anchor = host.anchor();
  if (anchor.tagName === "HEADER") anchor.append(open); else anchor.before(open);
  document.body.append(panel);

  let demos = [];
  let current = null;
  const setOpen = (on) => {
    panel.hidden = !on;
    open.setAttribute("aria-expanded", String(on));
    if (on) renderList();
  };
  open.addEventListener("click", () => setOpen(panel.hidden));
  panel.querySelector("#demos-close").addEventListener("click", () => { setOpen(false); open.focus(); });

  function renderList() {
    panel.querySelector("#demos-title").textContent = host.title();
    const mine = demos.filter((d) => d.where === host.where());
    list.replaceChildren(...(mine.length ? mine.map((d) => make("li", {}, make("button",
      {type: "button", "data-demo": d.id, "aria-current": current && current.id === d.id ? "true" : false},
      d.title))) : [make("li", {class: "demos-none", text: "No demos here yet (docs/demos.md says how to add one)."})]));
    list.querySelectorAll("button[data-demo]").forEach((b) => b.addEventListener("click", () => choose(b.dataset.demo)));
  }

  async function load(demo, phase) {
    document.body.dataset.demo = `${demo.id}:${phase}:loading`;
    const st = phase === "then" ? demo.then.state : demo.state;
    await host.load(host.explorer ? await explorerSearch(demo.where, st) : st);
    document.body.dataset.demo = `${demo.id}:${phase}`;
  }

  async function choose(id) {
    current = demos.find((d) => d.id === id);
    const d = current;
    card.hidden = false;
    card.replaceChildren(
      make("h3", {id: "demo-title", text: d.title}),
      d.seed ? make("p", {class: "demo-seed", text: d.seed}) : null,
      make("p", {}, make("strong", {text: "Look at: "}), make("span", {id: "demo-look", text: d.look})),
      make("p", {}, make("strong", {text: "Question: "}), make("span", {id: "demo-question", text: d.question})),
      make("div", {class: "demo-buttons"},
        d.then ? make("button", {id: "demo-show", type: "button", title: d.then.do}, "Show me") : null,
        make("button", {id: "demo-reveal", type: "button", "aria-expanded": "false", "aria-controls": "demo-answer"}, "Reveal the answer"),
        make("button", {id: "demo-restart", type: "button", title: "Load the demo's starting state again"}, "Start again")),
      make("p", {id: "demo-done", class: "demo-done", role: "status"}),
      make("p", {id: "demo-answer", class: "demo-answer", hidden: true}, make("strong", {text: "What to see: "}), d.answer));
    const done = card.querySelector("#demo-done");
    const reveal = card.querySelector("#demo-reveal");
    reveal.addEventListener("click", () => {
      const answer = card.querySelector("#demo-answer");
      answer.hidden = !answer.hidden;
      reveal.setAttribute("aria-expanded", String(!answer.hidden));
      reveal.textContent = answer.hidden ? "Reveal the answer" : "Hide the answer";
    });
    if (d.then) card.querySelector("#demo-show").addEventListener("click", async () => {
      await load(d, "then"); done.textContent = `Done: ${d.then.do}`;
    });
    card.querySelector("#demo-restart").addEventListener("click", async () => { await load(d, "state"); done.textContent = ""; });
    renderList();
    await load(d, "state");
    done.textContent = "";
    renderList();  // the explorer may have changed setting
  }

  // the explorer's setting changes the list (its title names the setting)
  // (a page without its own <title>, as the notebook widget's shadow root, has nothing to observe)
  const title = document.querySelector("title");
  if (title) new MutationObserver(() => { if (!panel.hidden) renderList(); }).observe(title, {childList: true});
  getJSON("/api/demos").then((r) => { demos = r.demos; if (!panel.hidden) renderList(); document.body.dataset.demos = "ready"; })
    .catch((err) => { list.replaceChildren(make("li", {class: "demos-none", text: `The demos could not be read: ${err.message}`})); });
}

if (LAB) mountDemos(labHost());
