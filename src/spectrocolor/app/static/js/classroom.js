// Classroom mode (issue 30; server side in spectrocolor/app/classroom.py). Only a page opened
// through a class's join or teacher address has the role cookie; every other page does nothing
// here. The teacher pushes this page's URL state to every student and sees the states students
// send back; a student follows the teacher (by default) and can send their own state. The
// events come over Server-Sent Events: the browser's EventSource reconnects by itself.

import {clientHeaders} from "./client.js";
import {$, el, fill} from "./dom.js";

const role = (document.cookie.match(/(?:^|;\s*)spectrocolor-role=(teacher|student)/) || [])[1];
const FOLLOW_KEY = "spectrocolor-follow";

/** This page's URL state: what a link to it holds (main.js keeps the URL up to date; a lab page
 * keeps its state in the fragment, so that goes too). */
const currentState = () => location.pathname + location.search + location.hash;

/** Whether `state` is a path of this server (never another origin, never a script URL). */
function sameOrigin(state) {
  if (typeof state !== "string" || !state.startsWith("/") || state.startsWith("//")) return false;
  try { return new URL(state, location.origin).origin === location.origin; } catch { return false; }
}

/** Show a URL state: another page (the explorer, a lab) is opened, and its own class panel keeps
 * the student in the class; on this page it is read as Back/Forward is (main.js and the labs
 * read the URL on popstate). */
function openState(state) {
  if (!sameOrigin(state)) return;
  const url = new URL(state, location.origin);
  const target = url.pathname + url.search + url.hash;
  if (url.pathname !== location.pathname) { location.assign(target); return; }
  if (url.search === location.search && url.hash === location.hash) return;
  history.pushState({}, "", target);
  window.dispatchEvent(new PopStateEvent("popstate", {state: {}}));
}

async function post(path, body) {
  const res = await fetch(path, {method: "POST", headers: {"Content-Type": "application/json",
    ...clientHeaders()}, body: JSON.stringify(body)});
  let data = {};
  try { data = await res.json(); } catch { /* not JSON */ }
  if (!res.ok) throw new Error(data.error || `${res.status} ${res.statusText}`);
  return data;
}

const say = (text) => fill($("class-status"), text);
const time = (at) => new Date(at * 1000).toLocaleTimeString();

/** The join address's QR code, from the server's SVG, added as nodes (no HTML parsing). */
function qrNode(svgText) {
  const doc = new DOMParser().parseFromString(svgText, "image/svg+xml");
  const svg = document.importNode(doc.documentElement, true);
  svg.setAttribute("role", "img");
  svg.setAttribute("aria-label", "QR code of the join address");
  svg.setAttribute("viewBox", `0 0 ${svg.getAttribute("width")} ${svg.getAttribute("height")}`);
  svg.removeAttribute("width"); svg.removeAttribute("height");
  return svg;
}

function receivedRow(entry) {
  return el("li", {}, el("span", {class: "who", text: entry.name}), " ",
    el("time", {text: time(entry.at)}), " ",
    el("button", {type: "button", title: "Show this student's state on this page",
      onclick: () => openState(entry.state)}, "Open"));
}

function showTeacher(view) {
  fill($("class-qr"), qrNode(view.qr_svg));
  const link = $("class-join");
  link.textContent = view.join_url; link.href = view.join_url;
  fill($("class-count"), String(view.students));
  fill($("class-exposure"), view.exposure);
}

async function teacher(panel) {
  panel.classList.add("teacher");
  fill(panel,
    el("div", {class: "class-qr", id: "class-qr"}),
    el("div", {class: "class-main"},
      el("h2", {}, "Class"),
      el("p", {}, "Students join at ", el("a", {id: "class-join", class: "join"}),
        " (or scan the code). Connected: ", el("strong", {id: "class-count"}, "0")),
      el("p", {class: "class-actions"},
        el("button", {type: "button", id: "class-push", title: "Show this page's state on every student's screen"}, "Push to class"),
        el("button", {type: "button", id: "class-renew", title: "A new join code: everyone is disconnected and must join again"}, "Renew code"),
        el("span", {id: "class-status", role: "status"})),
      el("p", {class: "class-exposure", id: "class-exposure"}),
      el("h3", {}, "Sent by students"),
      el("ol", {id: "class-received", class: "class-received"})));
  showTeacher(await (await fetch("/api/class/whoami", {headers: clientHeaders()})).json());
  const list = $("class-received");
  const received = await (await fetch("/api/class/received", {headers: clientHeaders()})).json();
  received.received.forEach((e) => list.append(receivedRow(e)));
  $("class-push").addEventListener("click", async () => {
    try { say(`pushed to ${(await post("/api/class/push", {state: currentState()})).students} students`); }
    catch (err) { say(`not pushed: ${err.message}`); }
  });
  $("class-renew").addEventListener("click", async () => {
    if (!confirm("Renew the join code? Every student is disconnected and must join again.")) return;
    try { showTeacher(await post("/api/class/renew", {})); say("new code: students must join again"); }
    catch (err) { say(`not renewed: ${err.message}`); }
  });
  const events = new EventSource("/api/class/events");
  events.addEventListener("count", (e) => fill($("class-count"), String(JSON.parse(e.data).students)));
  events.addEventListener("received", (e) => {
    list.append(receivedRow(JSON.parse(e.data)));
    while (list.children.length > 100) list.firstElementChild.remove();
  });
  events.addEventListener("error", () => say(events.readyState === EventSource.CLOSED
    ? "the class's server no longer answers" : "reconnecting…"));
  events.addEventListener("open", () => say(""));
}

function following() {
  try { return sessionStorage.getItem(FOLLOW_KEY) !== "0"; } catch { return true; }
}

function student(panel) {
  panel.classList.add("student");
  const follow = el("input", {type: "checkbox", id: "class-follow"});
  follow.checked = following();
  fill(panel,
    el("span", {class: "class-live", id: "class-live", text: "Class"}),
    el("label", {title: "Show what the teacher pushes as soon as it comes"}, follow, " Follow teacher"),
    el("label", {}, "Name ", el("input", {id: "class-name", maxlength: "40", size: "10",
      placeholder: "anonymous", autocomplete: "off"})),
    el("button", {type: "button", id: "class-send", title: "Send this page's state to the teacher"}, "Send to teacher"),
    el("span", {id: "class-status", role: "status"}));
  follow.addEventListener("change", () => {
    try { sessionStorage.setItem(FOLLOW_KEY, follow.checked ? "1" : "0"); } catch { /* storage off */ }
  });
  $("class-send").addEventListener("click", async () => {
    try {
      await post("/api/class/send", {state: currentState(), name: $("class-name").value.trim().slice(0, 40)});
      say(`sent at ${new Date().toLocaleTimeString()}`);
    } catch (err) { say(`not sent: ${err.message}`); }
  });
  let first = true;
  const events = new EventSource("/api/class/events");
  events.addEventListener("hello", (e) => {
    const data = JSON.parse(e.data);
    $("class-live").classList.add("on");
    say("connected");
    if (first && data.last_push && follow.checked) openState(data.last_push);
    first = false;
  });
  events.addEventListener("push", (e) => {
    const data = JSON.parse(e.data);
    window.__classPushes = (window.__classPushes || 0) + 1;  // for the browser tests
    if (follow.checked) { openState(data.state); say(`following the teacher (${time(data.at)})`); }
    else say(`the teacher pushed a state at ${time(data.at)} (not followed)`);
  });
  events.addEventListener("error", () => {
    $("class-live").classList.remove("on");
    say(events.readyState === EventSource.CLOSED
      ? "disconnected: the join code was renewed or the class ended; join again with the new code"
      : "reconnecting…");
  });
}

const panel = $("classroom");
if (role && panel) {
  panel.hidden = false;
  (role === "teacher" ? teacher(panel) : Promise.resolve(student(panel))).catch((err) => {
    fill(panel, el("span", {text: `The class panel could not start (${err.message}).`}));
  });
}
