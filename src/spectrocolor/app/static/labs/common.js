// What every lab page shares: element lookup, the one error banner, the JSON API call (errors in
// the server's {"error": …} shape), canvases sized to their CSS box, and number formatting.

import { clientHeaders } from "../js/client.js";
import { showKernelStatus } from "../js/kernels.js";
import { busyFetch, Superseded } from "../js/busy.js";

export const $ = (id) => document.getElementById(id);

/** Show a message in the page's error banner (role=alert); it stays until dismissed. */
export function showError(message) {
  $("error-text").textContent = message;
  $("error").hidden = false;
}

/** GET (no body) or POST JSON; a non-2xx answer throws the server's error text. The "computing…"
 * note shows while it runs; a busy server's 429 is tried again (js/busy.js). A request that a newer
 * one to the same path replaced while it waited never settles: the newer one's answer is shown. */
export async function api(path, body) {
  const init = body === undefined ? { headers: clientHeaders() } : {
    method: "POST", headers: { "Content-Type": "application/json", ...clientHeaders() }, body: JSON.stringify(body),
  };
  let response;
  try {
    response = await busyFetch(path, init, path);
  } catch (error) {
    if (error instanceof Superseded) return new Promise(() => {});
    throw error;
  }
  const data = await response.json();
  if (!response.ok) throw new Error(data.error || `request failed (${response.status})`);
  showKernelStatus(response);
  return data;
}

/** A 2-D context in CSS pixels; the backing store follows the CSS size (reallocated only when it changes). */
export function context(canvas) {
  const ratio = window.devicePixelRatio || 1;
  const width = canvas.clientWidth, height = canvas.clientHeight;
  const w = Math.max(1, Math.round(width * ratio)), h = Math.max(1, Math.round(height * ratio));
  if (canvas.width !== w || canvas.height !== h) { canvas.width = w; canvas.height = h; }
  const ctx = canvas.getContext("2d");
  ctx.setTransform(ratio, 0, 0, ratio, 0, 0);
  ctx.clearRect(0, 0, width, height);
  return { ctx, width, height };
}

/** The page's palette (../theme.css) for a canvas: text, line, grid, muted, accent, bg, panel, bad,
 * warn, ok. Read from the element (custom properties inherit), so it also holds inside a notebook
 * widget's shadow root; a plot's ink then follows the theme, its sample colours stay as computed. */
export function theme(element = document.documentElement) {
  const style = getComputedStyle(element);
  const get = (name, fallback) => style.getPropertyValue(`--${name}`).trim() || fallback;
  return {
    text: get("text", "#e6e8ee"), line: get("line", "#4a505e"), grid: get("grid", "#2e333d"),
    muted: get("muted", "#aab1c0"), accent: get("accent", "#6aa9ff"), bg: get("bg", "#15171c"),
    panel: get("panel", "#1e2128"), bad: get("bad", "#ff7b7b"), warn: get("warn", "#ffb454"),
    ok: get("ok", "#7ad69b"),
  };
}

export const css = (rgb) => `rgb(${rgb[0]}, ${rgb[1]}, ${rgb[2]})`;
export const fmt = (v, digits) => (v === null || v === undefined ? "—" : Number(v).toFixed(digits));

/** Ctrl/Cmd+Z undoes, with Shift redoes; the banner's × dismisses it. */
export function wireCommon(undo, redo) {
  $("error-close").addEventListener("click", () => { $("error").hidden = true; });
  document.addEventListener("keydown", (e) => {
    if ((e.ctrlKey || e.metaKey) && e.key.toLowerCase() === "z") {
      e.preventDefault();
      if (e.shiftKey) redo(); else undo();
    }
  });
}

/** The square CIE xy plot (x 0–0.8, y 0–0.9) of a canvas: its box and the x, y → pixel maps. */
export function xyFrame(width, height) {
  const size = Math.min(width - 56, height - 44);
  const box = { x: 48, y: 8, w: size, h: size };
  return { box, X: (x) => box.x + (x / 0.8) * box.w, Y: (y) => box.y + box.h - (y / 0.9) * box.h };
}

/** The frame, tick values and axis label of an xy plot. */
export function drawXyAxes(ctx, { box, X, Y }) {
  const t = theme(ctx.canvas);
  ctx.strokeStyle = t.muted; ctx.fillStyle = t.text; ctx.lineWidth = 1; ctx.font = "11px system-ui, sans-serif";
  ctx.strokeRect(box.x, box.y, box.w, box.h);
  ctx.textAlign = "center";
  for (const v of [0, 0.2, 0.4, 0.6, 0.8]) ctx.fillText(v.toFixed(1), X(v), box.y + box.h + 15);
  ctx.fillText("x", box.x + box.w / 2, box.y + box.h + 30);
  ctx.textAlign = "right";
  for (const v of [0, 0.2, 0.4, 0.6, 0.8]) ctx.fillText(v.toFixed(1), box.x - 6, Y(v) + 4);
}

/** Stroke a polyline of chromaticities (closed on request) in the current style. */
export function xyPath(ctx, { X, Y }, points, close) {
  ctx.beginPath();
  points.forEach(([x, y], k) => (k ? ctx.lineTo(X(x), Y(y)) : ctx.moveTo(X(x), Y(y))));
  if (close) ctx.closePath();
  ctx.stroke();
}
