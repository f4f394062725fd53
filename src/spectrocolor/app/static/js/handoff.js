// "Open in lab" (issue 28 item 6): the explorer hands what it shows to a lab, through the lab's own
// URL state (its fragment), so that Back returns here and a teacher can push the lab's page:
// * the shown colour (its x, y, Y from the library's last answer) to the smoothest-reflectance lab,
//   under E in settings 1-3 and 5 (a distribution read as a reflectance, level 30 = 1) and under
//   setting 4's illuminant when the lab has a light of that name;
// * setting 4's sample (the active one of the two; its levels 0-30 at the page's step, as
//   r=<step>:<levels>) to the object-colour-solid lab's metamer mismatch region;
// * to the light lab: setting 4's illuminant by name when it is one of the lab's named lights, else
//   (and setting 1's distribution always) its levels as kind=explorer&r=<step>:<levels>&label=<name>,
//   which the lab shows as a light known over 400-700 nm only, saying which metrics that leaves
//   out and why.
// Each lab checks what it reads (a bad address gives one message there, never a crash).

import {S} from "./state.js";
import {$, el} from "./dom.js";

const REFLECTANCE_LIGHTS = ["A", "B", "C", "D50", "D55", "D65", "D75", "E", "FL1", "FL2", "FL3", "FL4", "FL5", "FL6",
  "FL7", "FL8", "FL9", "FL10", "FL11", "FL12"];
const SOLID_LIGHTS = [...REFLECTANCE_LIGHTS, "LED-B1", "LED-B2", "LED-B3", "LED-B4", "LED-B5"];
const NAMED_LIGHTS = SOLID_LIGHTS.filter((name) => name !== "E");

const hash = (params) => "#" + new URLSearchParams(params).toString();
const level = (v) => String(Math.round(Math.min(30, Math.max(0, v)) * 100) / 100);

/** Which colour of the library's answer the active distribution is, or null. */
function shownColour() {
  const a = S.active[S.setting] || 0;
  const index = {1: 0, 2: a, 3: a, 4: a >= 1 ? a : 1, 5: a + 1}[S.setting];
  return S.server && S.server.colours ? S.server.colours[index] || null : null;
}

/** The reflectance lab's address for the colour shown, or a reason why there is none. */
export function reflectanceLink() {
  const colour = shownColour();
  let light = "E";
  if (S.setting === 4) {
    light = S.names[4][0];
    if (!REFLECTANCE_LIGHTS.includes(light)) return {why: `the reflectance lab has no light named "${light}"`};
  }
  if (!colour || !colour.xy || colour.xy[0] === null || !(colour.XYZ[1] > 0)) return {why: "this colour has no chromaticity"};
  const Y = Math.min(100, Math.round(colour.XYZ[1] * 100) / 100);
  return {href: "/labs/reflectance" + hash({light, step: "5", x: colour.xy[0].toFixed(4), y: colour.xy[1].toFixed(4),
    Y: String(Math.max(0.01, Y))})};
}

/** The solid lab's address for setting 4's active sample. */
export function solidLink() {
  if (S.setting !== 4) return {why: "choose setting 4 (its samples go to the solid lab)"};
  const a = S.active[4] >= 1 ? S.active[4] : 1;
  const name = S.names[4][0];
  const light = SOLID_LIGHTS.includes(name) ? name : "D65";
  const second = light === "A" ? "D65" : "A";
  return {href: "/labs/solid" + hash({light, second, sample: "0", mismatch: "1",
    r: `${S.step}:${S.dists[4][a].map(level).join(",")}`})};
}

/** The light lab's address for setting 1's distribution or setting 4's illuminant. */
export function lightLink() {
  if (S.setting !== 1 && S.setting !== 4) return {why: "choose setting 1 (its distribution) or 4 (its illuminant)"};
  const name = S.names[S.setting][0];
  if (S.setting === 4 && NAMED_LIGHTS.includes(name)) return {href: "/labs/light" + hash({kind: "named", name})};
  const levels = S.dists[S.setting][0];
  if (!levels.some((v) => v > 0)) return {why: "this distribution has no power"};
  return {href: "/labs/light" + hash({kind: "explorer", r: `${S.step}:${levels.map(level).join(",")}`,
    label: name || "the explorer's distribution"})};
}

function button(id, text, title, link) {
  return el("button", {type: "button", id, title, onclick: () => {
    const target = link();
    if (target.href) location.assign(target.href);
    else $("handoff-status").textContent = `Not here: ${target.why}.`;
  }}, text);
}

const group = $("handoff");
if (group) {
  group.append(
    "Open in lab: ",
    button("handoff-reflectance", "Colour → reflectance", "This colour (x, y, Y) in the smoothest-reflectance lab", reflectanceLink),
    button("handoff-solid", "Sample → solid", "Setting 4's sample: its metamer mismatch region in the object-colour-solid lab", solidLink),
    button("handoff-light", "Light → light lab", "Setting 1's distribution or setting 4's illuminant in the light lab (known over 400–700 nm: the lab says which metrics that leaves out)", lightLink),
    el("span", {id: "handoff-status", role: "status", class: "handoff-status"}));
  document.addEventListener("click", (e) => {
    if (!group.contains(e.target)) $("handoff-status").textContent = "";
  });
}
