// Setting 4's photo: an uploaded picture as taken and relit under the setting's illuminant
// (POST /api/relight, the library's spectral upsampling). The photo stays in this page's memory
// only; every change of the illuminant, the observer, the bins or the gamut strategy relights it.
// Text from the server or the file's name always goes in as text nodes, never as HTML.

import {$, el, fill} from "./dom.js";
import {apiJSON} from "./api.js";
import {S} from "./state.js";
import {displayName} from "./view.js";

const P = {options: null, image: null, name: "", key: "", inflight: false, again: false, onError: null};

/** The photo panel: filled once from /api/relight/options; `onError(where, err)` shows failures. */
export async function setupPhoto(onError) {
  P.onError = onError;
  const o = P.options = await apiJSON("/api/relight/options");
  const option = ([v, label, help]) => el("option", {value: v, title: help || null}, label);
  fill($("photo-source"), o.sources.map((s) => option([s, s])));
  fill($("photo-adaptation"), o.adaptations.map(option));
  fill($("photo-exposure"), o.exposures.map(option));
  $("photo-exposure").value = o.defaults.exposure;
  $("photo-source").value = o.defaults.source;
  $("photo-adaptation").value = o.defaults.adaptation;
  const label = (list, v) => list.find(([k]) => k === v)[1];
  $("photo-default").textContent = `Defaults: adaptation ${label(o.adaptations, o.defaults.adaptation)}, `
    + `exposure ${label(o.exposures, o.defaults.exposure)}. `
    + `Photos are read as sRGB, up to ${(o.max_photo_bytes / 1e6).toFixed(1)} MB (larger ones are reduced here first) `
    + `and shown at most ${o.max_side_px} px wide or high.`;
  $("photo-choose").addEventListener("click", () => $("photo-file").click());
  $("photo-file").addEventListener("change", (e) => { if (e.target.files[0]) readPhoto(e.target.files[0]); e.target.value = ""; });
  for (const id of ["photo-source", "photo-adaptation", "photo-exposure"]) $(id).addEventListener("change", () => refreshPhoto());
}

/** Show or hide the panel with the setting; relight when anything the picture depends on changed. */
export function refreshPhoto() {
  const box = $("photo");
  box.hidden = S.setting !== 4 || !P.options;
  if (box.hidden || !P.image) return;
  const body = {image: P.image, illuminant: S.dists[4][0], step_nm: S.step, observer: S.observer,
    source: $("photo-source").value, adaptation: $("photo-adaptation").value, gamut: S.gamut,
    exposure: $("photo-exposure").value};
  const key = JSON.stringify([body.illuminant, body.step_nm, body.observer, body.source, body.adaptation, body.gamut,
    body.exposure, P.name]);
  if (key === P.key) return;
  if (P.inflight) { P.again = true; return; }
  P.key = key;
  relight(body, displayName(4, 0) || "the illuminant");
}

async function relight(body, lightName) {
  P.inflight = true;
  $("photo").setAttribute("aria-busy", "true");
  $("photo-status").textContent = "relighting…";
  try {
    const r = await apiJSON("/api/relight", body);
    show(r, body, lightName);
  } catch (err) {
    $("photo-status").textContent = "";
    P.key = "";
    P.onError("Could not relight the photo", err);
  }
  P.inflight = false;
  $("photo").removeAttribute("aria-busy");
  if (P.again) { P.again = false; refreshPhoto(); }
}

function show(r, body, lightName) {
  const adaptation = P.options.adaptations.find(([v]) => v === r.adaptation)[1];
  const size = `${r.width} × ${r.height} px`;
  // the pictures are made here (none exist before a photo is chosen); text goes in as text
  const picture = (id, png, alt, caption) => el("figure", {},
    el("img", {id, src: `data:image/png;base64,${png}`, alt, width: r.width, height: r.height}),
    el("figcaption", {id: `${id}-caption`}, caption));
  fill($("photo-figures"),
    picture("photo-taken", r.taken_png, `${P.name} as taken under ${r.source}, ${size}`, `As taken (under ${r.source})`),
    picture("photo-relit", r.relit_png, `${P.name} relit under ${lightName} (adaptation: ${adaptation}), ${size}`,
      `Under ${lightName}`));
  const n = (v) => v.toLocaleString("en-US");
  $("photo-status").textContent = `${n(r.pixels)} pixels (${size}`
    + `${r.downscaled ? `, reduced from ${r.photo_width} × ${r.photo_height}` : ""}): `
    + `${n(r.outside_solid)} outside the object-colour solid (${r.out_of_range}); `
    + `${n(r.out_of_gamut)} relit outside ${r.space} (${r.gamut}). Adaptation: ${adaptation}. `
    + `${r.exposure_factor < 1 ? `Exposure ×${r.exposure_factor.toFixed(2)}, so that the white under ${lightName} fits ${r.space}. ` : ""}`
    + `${n(r.colours)} colours relit in ${Math.round(r.relight_ms)} ms.`;
  $("photo-figures").hidden = false;
  S.photo = {status: $("photo-status").textContent, request: body, answer: r};  // for the browser tests
}

/** Read the file; one larger than the server takes is reduced here (canvas, JPEG) first. */
async function readPhoto(file) {
  try {
    let blob = file;
    if (file.size > P.options.max_photo_bytes) blob = await reduce(file, P.options.max_side_px);
    P.image = await base64(blob);
    P.name = file.name;
    $("photo-name").textContent = file.name + (blob === file ? "" : " (reduced in the browser)");
    P.key = "";
    refreshPhoto();
  } catch (err) { P.onError(`Read ${file.name}`, err); }
}

async function reduce(file, side) {
  const bitmap = await createImageBitmap(file);
  const scale = Math.min(1, side / Math.max(bitmap.width, bitmap.height));
  const canvas = el("canvas", {width: Math.max(1, Math.round(bitmap.width * scale)),
    height: Math.max(1, Math.round(bitmap.height * scale))});
  canvas.getContext("2d").drawImage(bitmap, 0, 0, canvas.width, canvas.height);
  return new Promise((resolve, reject) => canvas.toBlob(
    (b) => (b ? resolve(b) : reject(new Error("the browser could not reduce this picture"))), "image/jpeg", 0.92));
}

function base64(blob) {
  return new Promise((resolve, reject) => {
    const reader = new FileReader();
    reader.onload = () => resolve(String(reader.result).split(",", 2)[1] || "");
    reader.onerror = () => reject(new Error("the file could not be read"));
    reader.readAsDataURL(blob);
  });
}
