// The seed's defaults on keys 1–8 and as buttons (from /api/presets).

import {$, el, fill} from "./dom.js";
import {S, remember} from "./state.js";
import {setLevel} from "./editors.js";

const copy = (a) => a.slice();
/** Setting 5's defaults: filters in series, or (issue 28 item 7) two spotlights. */
const setting5List = (p) => (S.mode5 === "additive" ? p.setting5_additive : p.setting5);

/** Key `key` in the current setting: load that default (one undo step). */
export function applyPreset(key, update, say) {
  const p = S.presets, n = S.setting, d = S.dists[n], names = S.names[n], edited = S.edited[n];
  const find = (list) => list.find((q) => q.key === key);
  let first = true;
  const load = (i, levels, name) => {
    if (first) { remember(); first = false; }
    d[i] = copy(levels); names[i] = name; edited[i] = false;
  };
  if (n === 1) {
    const q = find(p.setting1); if (!q) return;
    if (q.cycle) { S.sunset = (S.sunset + 1) % q.cycle.length; load(0, q.cycle[S.sunset].levels, `${q.name} d = ${q.cycle[S.sunset].d}`); }
    else { S.sunset = -1; load(0, q.levels, q.name); }
  } else if (n === 2) {
    const i = S.active[2], side = i === 0 ? "left" : "right";
    const q = find(p.setting2[side]); if (!q) return;
    if (q.cycle) { S.level[side] = (S.level[side] + 1) % q.cycle.length; load(i, q.cycle[S.level[side]].levels, `level ${S.level[side]}`); }
    else load(i, q.levels, q.name);
  } else if (n === 4) {
    const qi = find(p.setting4.illuminants), qs = find(p.setting4.samples);
    if (qi) load(0, qi.levels, qi.name);
    if (qs) { load(1, qs.left, `${qs.name} 1`); load(2, qs.right, `${qs.name} 2`); }
    if (!qi && !qs) return;
  } else {
    const q = find(n === 3 ? p.setting3 : setting5List(p)); if (!q) return;
    const parts = q.name.split(":")[0].split(n === 3 ? " / " : " and ");
    load(0, q.left, parts[0].trim()); load(1, q.right, (parts[1] || parts[0]).trim());
  }
  const text = $("presets").querySelector(`button[data-key='${key}']`);
  say(text ? `default ${key}: ${text.dataset.name}` : "");
  update();
}

export function presetButtons(update, say) {
  const p = S.presets, n = S.setting;
  const btn = (group, q) => el("button", {type: "button", "data-group": group, "data-key": q.key, "data-name": q.name,
    title: `key ${q.key}${q.cycle ? " (press again for the next)" : ""}`}, el("kbd", {}, q.key), q.name);
  const group = (text) => el("span", {class: "group"}, text);
  let items;
  if (n === 1) items = p.setting1.map((q) => btn("s1", q));
  if (n === 2) items = [group("left"), ...p.setting2.left.map((q) => btn("left", q)), group("right"), ...p.setting2.right.map((q) => btn("right", q))];
  if (n === 3) items = p.setting3.map((q) => btn("pair", q));
  if (n === 4) items = [group("illuminant"), ...p.setting4.illuminants.map((q) => btn("ill", q)), group("samples"), ...p.setting4.samples.map((q) => btn("pair", q))];
  if (n === 5) items = setting5List(p).map((q) => btn("pair", q));
  fill($("presets"), items);
  $("presets").querySelectorAll("button").forEach((b) => b.addEventListener("click", () => {
    if (n === 2) S.active[2] = b.dataset.group === "left" ? 0 : 1;
    applyPreset(b.dataset.key, update, say);
  }));
}

/** Setting 3: load default `q` and make the seed's suggested transfers (`moves`: [bin, new left
 * level], e.g. Fig. 12's), each by the complementary rule — one undo step. */
export function applyMoves(q, update, say) {
  remember();
  S.dists[3] = [copy(q.left), copy(q.right)];
  S.names[3] = q.name.split(" / ").map((t) => t.trim());
  for (const [k, level] of q.moves) setLevel(0, k, level);
  const nm = q.moves.map(([k]) => S.wl[k]).join(", ");
  say(`default ${q.key} with the seed's transfers at ${nm} nm (from the left to the right)`);
  // The seed promises one hue on both sides; the library's answer says whether this reaches it.
  const moved = JSON.stringify(S.dists[3]);
  S.afterEvaluate = (r) => {
    if (S.setting === 3 && JSON.stringify(S.dists[3]) === moved) say(movesOutcome(q, nm, r));
  };
  update();
}

/** Hue angle h_ab (degrees) of a CIELAB triple. */
const hueAngle = ([, a, b]) => (Math.atan2(b, a) * 180 / Math.PI + 360) % 360;

/** What the seed's transfers reached: the same hue on both sides (λd within 1 nm), or why not. */
export function movesOutcome(q, nm, r) {
  const [left, right] = r.colours;
  const lead = `default ${q.key} with the seed's transfers at ${nm} nm`;
  if (left.dominant_nm === null || right.dominant_nm === null) return `${lead}: no dominant wavelength to compare`;
  const d = (c) => `${c.dominant_nm.toFixed(1)} nm`;
  if (Math.abs(left.dominant_nm - right.dominant_nm) <= 1) {
    return `${lead}: both sides have one hue, as the seed says (λd ${d(left)} and ${d(right)}); X shows them at full luminance`;
  }
  let dh = Math.abs(hueAngle(left.lab) - hueAngle(right.lab));
  dh = Math.min(dh, 360 - dh);
  const more = q.key === "2" ? "" : "; Fig. 12 (default 2) moves light at 560 and 590 nm as well and reaches one hue";
  return `${lead}: the seed says both sides now have the same hue, but computed they differ: λd ${d(left)} (left) `
    + `and ${d(right)} (right), hue angles ${dh.toFixed(0)}° apart. The right keeps only the moved band on a dark `
    + `neutral, a purer and ${right.dominant_nm > left.dominant_nm ? "more orange" : "greener"} light; the left, `
    + `without that band, shifts the other way${more}`;
}

/** Buttons for the defaults that come with the seed's transfers (setting 3). */
export function moveButtons(update, say) {
  if (S.setting !== 3) return [];
  return S.presets.setting3.filter((q) => q.moves && q.moves.length).map((q) => el("button", {type: "button",
    "data-moves": q.key, title: `Load default ${q.key} and move light at ${q.moves.map(([k]) => S.wl[k]).join(", ")} nm from the left to the right, as the seed suggests`,
    onclick: () => applyMoves(q, update, say)}, q.key === "2" ? "Fig. 12: move the light (default 2)" : `the seed's moves (default ${q.key})`));
}
