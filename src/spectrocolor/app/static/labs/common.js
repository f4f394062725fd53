// What every lab page shares: element lookup, the one error banner, the JSON API call (errors in
// the server's {"error": …} shape), canvases sized to their CSS box, and number formatting.

export const $ = (id) => document.getElementById(id);

/** Show a message in the page's error banner (role=alert); it stays until dismissed. */
export function showError(message) {
  $("error-text").textContent = message;
  $("error").hidden = false;
}

/** GET (no body) or POST JSON; a non-2xx answer throws the server's error text. */
export async function api(path, body) {
  const init = body === undefined ? {} : {
    method: "POST", headers: { "Content-Type": "application/json" }, body: JSON.stringify(body),
  };
  const response = await fetch(path, init);
  const data = await response.json();
  if (!response.ok) throw new Error(data.error || `request failed (${response.status})`);
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
