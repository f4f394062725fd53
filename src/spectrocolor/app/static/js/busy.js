// The "computing…" state of every slow request (issue 28 item 6, issue 30 item 3), shared by the
// explorer (js/api.js) and the labs (labs/common.js). A request still unanswered after SHOW_AFTER_MS
// shows a small note in a corner (position: fixed, so nothing on the page moves; role=status, so a
// screen reader hears it). When the server answers 429 or 503 -- its worker pools are all busy --
// the request is not an error: the note says "busy — queued, retrying…" and the same request is
// sent again after the server's Retry-After (or a doubling back-off), a bounded number of times.
// A request sent again with the same key while an older one waits for its retry supersedes it:
// the older one stops (latest request wins).

const NOTE_ID = "busy-status";
export const SHOW_AFTER_MS = 150;
export const COMPUTING_TEXT = "computing…";
export const QUEUED_TEXT = "busy — queued, retrying…";
/** Tries of one request in all, and the longest wait between two, ms. */
export const MAX_TRIES = 8;
const FIRST_WAIT_MS = 400, MAX_WAIT_MS = 8000;

/** Thrown by busyFetch for a request that a newer one with the same key replaced while it waited. */
export class Superseded extends Error {
  constructor() { super("superseded by a newer request"); this.name = "Superseded"; }
}

let running = 0, queued = 0, timer = null;
const latest = new Map(); // key -> the newest request's number
let counter = 0;

function note() {
  let node = document.getElementById(NOTE_ID);
  if (!node) {
    node = document.createElement("p");
    node.id = NOTE_ID;
    node.className = "busy-status";
    node.setAttribute("role", "status");
    node.setAttribute("aria-live", "polite");
    node.hidden = true;
    document.body.append(node);
  }
  return node;
}

function show() {
  const node = note();
  const text = queued ? QUEUED_TEXT : COMPUTING_TEXT;
  if (node.textContent !== text) node.textContent = text;
  node.dataset.state = queued ? "queued" : "computing";
  node.hidden = false;
}

function update() {
  if (!running) {
    clearTimeout(timer); timer = null;
    const node = document.getElementById(NOTE_ID);
    if (node) { node.hidden = true; node.textContent = ""; delete node.dataset.state; }
    return;
  }
  if (queued) { clearTimeout(timer); timer = null; show(); return; }
  const node = document.getElementById(NOTE_ID);
  if (node && !node.hidden) { show(); return; } // already shown: say "computing…" again
  if (!timer) timer = setTimeout(() => { timer = null; if (running) show(); }, SHOW_AFTER_MS);
}

/** The wait before try `tries + 1`, ms: the server's Retry-After (seconds) when it gives one. */
export function retryDelay(retryAfter, tries) {
  const seconds = Number(retryAfter);
  if (retryAfter !== null && retryAfter !== "" && Number.isFinite(seconds) && seconds >= 0) {
    return Math.min(MAX_WAIT_MS, Math.max(100, seconds * 1000));
  }
  return Math.min(MAX_WAIT_MS, FIRST_WAIT_MS * 2 ** (tries - 1));
}

const sleep = (ms) => new Promise((resolve) => setTimeout(resolve, ms));

/**
 * fetch(path, init), with the busy note shown while it runs and 429/503 answers tried again.
 * `key` (optional): a newer request with the same key supersedes this one while it waits.
 * Returns the last Response (a 429 after MAX_TRIES tries comes back as it is: the caller shows
 * the server's message); a network failure throws as fetch does; a superseded request throws
 * Superseded.
 */
export async function busyFetch(path, init, key) {
  const mine = ++counter;
  if (key !== undefined) latest.set(key, mine);
  running += 1;
  update();
  let waiting = false;
  try {
    for (let tries = 1; ; tries += 1) {
      const response = await fetch(path, init);
      if ((response.status !== 429 && response.status !== 503) || tries >= MAX_TRIES) return response;
      waiting = true; queued += 1; update();
      await sleep(retryDelay(response.headers.get("Retry-After"), tries));
      waiting = false; queued -= 1;
      if (key !== undefined && latest.get(key) !== mine) throw new Superseded();
      update();
    }
  } finally {
    if (waiting) queued -= 1;
    running -= 1;
    if (key !== undefined && latest.get(key) === mine) latest.delete(key);
    update();
  }
}
