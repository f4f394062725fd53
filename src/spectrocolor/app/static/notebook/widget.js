// The SPECTRA explorer as a notebook widget: anywidget's render(). Not a module of its own:
// spectrocolor.app.notebook_widget.widget_esm() puts it after the explorer's modules (assembled into
// createExplorer) and the page's markup and style (PAGE_MARKUP, PAGE_CSS), as one ES module.
//
// The explorer runs unchanged in a shadow root of its own; what it takes for the page's globals is
// given to it here: its document is the shadow root, its address and history are the widget's own
// (setting 1 with the kernel's distribution; a change of them sends the edited distribution to the
// kernel), its storage is in memory, and its fetch asks the kernel, which answers with the server's
// computations (model.send / "msg:custom"; the kernel's answer becomes a real Response).

const REQUEST_TIMEOUT_MS = 120000;

function memoryStorage() {
  const items = new Map();
  return {
    getItem: (k) => (items.has(String(k)) ? items.get(String(k)) : null),
    setItem: (k, v) => { items.set(String(k), String(v)); },
    removeItem: (k) => { items.delete(String(k)); },
  };
}

/** The address of setting 1 showing `levels` on the grid of `step` (state.js reads it). */
function addressOf(levels, step, name) {
  const q = new URLSearchParams({s: "1", b: String(step), l0: "f" + levels.map(String).join(","),
    t0: name || "", e: "0"});
  return `?${q}`;
}

const sameLevels = (a, b) => Array.isArray(a) && Array.isArray(b) && a.length === b.length && a.every((v, k) => v === b[k]);

function render({model, el}) {
  const host = document.createElement("div");
  host.className = "spectrocolor-explorer";
  // JupyterLab: keys pressed in the widget are the explorer's (arrows, 1-8, S, 0, X), not the notebook's
  host.setAttribute("data-lm-suppress-shortcuts", "true");
  el.append(host);
  const shadow = host.attachShadow({mode: "open"});
  const style = document.createElement("style");
  style.textContent = PAGE_CSS;
  const body = document.createElement("div");
  body.className = "sc-body";
  body.innerHTML = PAGE_MARKUP;  // the package's own static/index.html, scripts removed
  shadow.append(style, body);
  const cleanups = [];
  const stopKeys = (ev) => ev.stopPropagation();  // handled by the explorer (its listener is on the shadow root)
  host.addEventListener("keydown", stopKeys);

  // ---------------------------------------------------------------- fetch through the kernel
  let next = 0;
  const waiting = new Map();
  const showError = (text) => {
    const box = shadow.getElementById("error"), line = shadow.getElementById("error-text");
    if (box && line) { line.textContent = text; box.hidden = false; }
  };
  const onMessage = (msg) => {
    if (!msg || typeof msg !== "object") return;
    if (msg.kind === "response" && waiting.has(msg.id)) {
      const {resolve, timer} = waiting.get(msg.id);
      waiting.delete(msg.id);
      clearTimeout(timer);
      resolve(new Response(msg.body, {status: msg.status,
        headers: {...(msg.headers || {}), "Content-Type": msg.media || "application/json"}}));
    } else if (msg.kind === "error") {
      showError(`The kernel refused a message: ${msg.message}`);
    }
  };
  model.on("msg:custom", onMessage);
  cleanups.push(() => model.off("msg:custom", onMessage));
  const kernelFetch = (path, opts = {}) => new Promise((resolve, reject) => {
    const id = ++next;
    const timer = setTimeout(() => {
      waiting.delete(id);
      reject(new Error("the kernel did not answer within 2 minutes (is it busy or stopped?)"));
    }, REQUEST_TIMEOUT_MS);
    waiting.set(id, {resolve, timer});
    model.send({kind: "request", id, method: opts.method || "GET", path: String(path),
      body: opts.body === undefined ? null : String(opts.body)});
  });

  // ---------------------------------------------------------------- the page's globals
  const doc = {
    getElementById: (id) => shadow.getElementById(id),
    querySelector: (s) => shadow.querySelector(s),
    querySelectorAll: (s) => shadow.querySelectorAll(s),
    createElement: (t) => document.createElement(t),
    createElementNS: (ns, t) => document.createElementNS(ns, t),
    createTextNode: (t) => document.createTextNode(t),
    addEventListener: (type, f, o) => shadow.addEventListener(type, f, o),
    get activeElement() { return shadow.activeElement; },
    get body() { return body; },
    get title() { return ""; },
    set title(_) { /* the notebook keeps its own title */ },
  };
  const popstate = new EventTarget();
  const win = {
    get devicePixelRatio() { return window.devicePixelRatio; },
    addEventListener(type, f, o) {
      if (type === "popstate") { popstate.addEventListener(type, f, o); return; }
      window.addEventListener(type, f, o);
      cleanups.push(() => window.removeEventListener(type, f, o));
    },
  };
  const loc = {pathname: "/", search: addressOf(model.get("levels"), model.get("step_nm"), model.get("name"))};
  let modules = null;
  const sendEdits = () => {
    const S = win.__spectra;
    if (!S || !S.dists || !S.dists[1]) return;
    const levels = S.dists[1][0];
    if (sameLevels(levels, model.get("levels")) && S.step === model.get("step_nm")) return;
    model.send({kind: "edited", levels: levels.slice(), step_nm: S.step});
  };
  const moved = (url) => {
    const u = new URL(String(url), "http://widget.invalid/");
    loc.search = u.search;
    sendEdits();
  };
  const hist = {pushState: (_s, _t, url) => moved(url), replaceState: (_s, _t, url) => moved(url)};

  // the kernel's distribution changed (assigned in Python): the page reads it as a new address
  const fromKernel = () => {
    const S = win.__spectra;
    const levels = model.get("levels"), step = model.get("step_nm");
    if (S && S.dists && S.dists[1] && sameLevels(S.dists[1][0], levels) && S.step === step) return;
    loc.search = addressOf(levels, step, model.get("name"));
    popstate.dispatchEvent(new Event("popstate"));
  };
  model.on("change:levels", fromKernel);
  model.on("change:step_nm", fromKernel);
  cleanups.push(() => { model.off("change:levels", fromKernel); model.off("change:step_nm", fromKernel); });

  modules = createExplorer({document: doc, window: win, location: loc, history: hist,
    localStorage: memoryStorage(), sessionStorage: memoryStorage(), fetch: kernelFetch});
  host.__spectrocolor = {modules, state: () => win.__spectra};  // for the tests
  return () => { for (const f of cleanups) f(); };
}

export default {render};
