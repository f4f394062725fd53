"""Each lab widget's front end (``sc.explore_lab``) evaluated in Chromium with a stand-in anywidget
model and no kernel: the joined modules (the lab's, labs/common.js and the js/*.js they import, and
the page's other module scripts) must evaluate and render without a page error, ask the model for
the lab's options (their fetch goes through the kernel, not HTTP), and show the kernel's refusal
in the page's one error banner. Fast (no JupyterLab); the real thing with a kernel is
tests/notebook/test_explore_jupyterlab_browser.py."""

from __future__ import annotations

import pytest

pytest.importorskip("fastapi")

from spectrocolor.app import notebook_frontend as front  # noqa: E402

pytestmark = pytest.mark.browser

RUN = """async (src) => {
const esm = await import(URL.createObjectURL(new Blob([src], {type: "text/javascript"})));
const handlers = {};
window.sent = [];
const model = {get: (k) => ({address: "x=1"})[k], on: (t, f) => { (handlers[t] ||= []).push(f); }, off() {},
  send: (m) => { window.sent.push(m); if (m.kind === "request") setTimeout(() =>
    handlers["msg:custom"].forEach((f) => f({kind: "response", id: m.id, status: 404,
      body: JSON.stringify({error: "no kernel here"}), media: "application/json"})), 0); }};
esm.default.render({model, el: document.getElementById("out")});
}"""


@pytest.mark.parametrize("lab", front.LABS)
def test_a_lab_widget_runs_its_page_and_asks_the_kernel(browser, lab):
    pg = browser.new_page()
    errors = []
    pg.on("pageerror", lambda e: errors.append(str(e)))
    try:
        pg.set_content("<div id=out></div>")
        pg.evaluate(RUN, front.lab_widget_esm(lab))
        pg.wait_for_function("() => document.querySelector('.spectrocolor-lab').shadowRoot"
                             ".getElementById('error-text').textContent !== ''", timeout=15000)
        assert not errors, errors
        sent = pg.evaluate("() => window.sent")
        requests = [m for m in sent if m["kind"] == "request"]
        assert requests[0]["path"] == f"/api/lab/{lab}/options" and requests[0]["method"] == "GET"
        assert pg.evaluate("() => document.querySelector('.spectrocolor-lab').shadowRoot"
                           ".getElementById('error-text').textContent") == "no kernel here"
        # the page's globals are the widget's: the address it reads is the kernel's, scoped to it
        assert pg.evaluate("() => document.querySelector('.spectrocolor-lab').__spectrocolor.location.pathname") \
            == f"/labs/{lab}"
        assert pg.evaluate("() => location.hash") == ""  # the notebook's own address is untouched
    finally:
        pg.close()
