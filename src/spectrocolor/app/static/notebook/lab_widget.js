// A lab of the explorer as a notebook widget: anywidget's render(). Not a module of its own:
// spectrocolor.app.notebook_frontend.lab_widget_esm(name) puts it after the lab's modules (the lab's
// own, labs/common.js and the js/*.js they import, assembled into createExplorer), its page's markup
// and style (PAGE_MARKUP, PAGE_CSS) and its name (LAB), as one ES module.
//
// The lab runs unchanged in a shadow root of its own, as the explorer does in widget.js: its document
// is the shadow root, its address is the widget's own (/labs/<name> with the kernel's state as the
// hash; each change of the hash is sent to the kernel, which keeps it as widget.state, and a state
// assigned in Python reaches the page as a new hash), its storage is in memory, and its fetch asks
// the kernel, which answers with the server's lab computations.

const REQUEST_TIMEOUT_MS = 120000;

function memoryStorage() {
  const items = new Map();
  return {
    getItem: (k) => (items.has(String(k)) ? items.get(String(k)) : null),
    setItem: (k, v) => { items.set(String(k), String(v)); },
    removeItem: (k) => { items.delete(String(k)); },
  };
}

function render({model, el}) {
  const host = document.createElement("div");
  host.className = `spectrocolor-lab spectrocolor-lab-${LAB}`;
  host.setAttribute("data-lm-suppress-shortcuts", "true");  // JupyterLab: the lab's keys (Ctrl+Z) are its own
  el.append(host);
  const shadow = host.attachShadow({mode: "open"});
  const style = document.createElement("style");
  style.textContent = PAGE_CSS;
  const body = document.createElement("div");
  body.className = "sc-body";
  body.innerHTML = PAGE_MARKUP;  // the package's own static/labs/<name>.html, scripts removed
  shadow.append(style, body);
  const cleanups = [];
  host.addEventListener("keydown", (ev) => ev.stopPropagation());
  // a link to another page of the server (the explorer, another lab) has nowhere to go here
  shadow.addEventListener("click", (ev) => {
    const a = ev.target && ev.target.closest ? ev.target.closest("a[href]") : null;
    if (a && a.getAttribute("href").startsWith("/")) ev.preventDefault();
  });

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
    removeEventListener: (type, f, o) => shadow.removeEventListener(type, f, o),
    get activeElement() { return shadow.activeElement; },
    get body() { return body; },
    get title() { return ""; },
    set title(_) { /* the notebook keeps its own title */ },
    get cookie() { return ""; },  // no class role (js/classroom.js): a notebook is not in a class
    set cookie(_) { /* the notebook's cookies are not the lab's */ },
  };
  const popstate = new EventTarget();
  const win = {
    get devicePixelRatio() { return window.devicePixelRatio; },
    get innerWidth() { return window.innerWidth; },
    get innerHeight() { return window.innerHeight; },
    ResizeObserver: window.ResizeObserver,
    addEventListener(type, f, o) {
      if (type === "popstate") { popstate.addEventListener(type, f, o); return; }
      window.addEventListener(type, f, o);
      cleanups.push(() => window.removeEventListener(type, f, o));
    },
    dispatchEvent(ev) {
      return ev.type === "popstate" ? popstate.dispatchEvent(new Event("popstate")) : window.dispatchEvent(ev);
    },
  };
  const hashOf = (address) => (address ? `#${String(address).replace(/^#/, "")}` : "");
  const loc = {origin: "http://widget.invalid", pathname: `/labs/${LAB}`, search: "", hash: hashOf(model.get("address")),
    get href() { return `${this.origin}${this.pathname}${this.search}${this.hash}`; },
    assign() { /* another page of the server: there is none in a notebook */ }};
  const moved = (url) => {
    const u = new URL(String(url), `http://widget.invalid/labs/${LAB}${loc.hash}`);
    loc.search = u.search;
    loc.hash = u.hash;
    if (u.hash.slice(1) !== model.get("address")) model.send({kind: "state", address: u.hash.slice(1)});
  };
  const hist = {pushState: (_s, _t, url) => moved(url), replaceState: (_s, _t, url) => moved(url)};

  // the state was assigned in Python: the page reads it as a new address (as after Back)
  const fromKernel = () => {
    const address = model.get("address");
    if (address === loc.hash.slice(1)) return;
    loc.hash = hashOf(address);
    popstate.dispatchEvent(new Event("popstate"));
  };
  model.on("change:address", fromKernel);
  cleanups.push(() => model.off("change:address", fromKernel));

  const modules = createExplorer({document: doc, window: win, location: loc, history: hist,
    localStorage: memoryStorage(), sessionStorage: memoryStorage(), fetch: kernelFetch});
  host.__spectrocolor = {modules, location: loc, body};  // for the tests
  return () => { for (const f of cleanups) f(); };
}

export default {render};
