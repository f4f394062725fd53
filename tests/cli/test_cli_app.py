"""``spectrocolor app`` started as a user starts it: the console script, a free port, no browser.

The page it serves must load with every asset it references (scripts, style sheets), all from
the package itself — nothing from a CDN.
"""

from __future__ import annotations

import re
import subprocess
import sys
import time
import urllib.request
from pathlib import Path

import pytest

pytest.importorskip("fastapi")
pytest.importorskip("uvicorn")

SCRIPT = Path(sys.executable).with_name("spectrocolor")


def fetch(url: str) -> tuple[int, str, str]:
    with urllib.request.urlopen(url, timeout=10) as response:  # noqa: S310 - loopback only
        return response.status, response.headers.get("content-type", ""), response.read().decode("utf-8")


@pytest.fixture
def running_app():
    if not SCRIPT.exists():
        pytest.skip(f"the console script is not installed next to {sys.executable}")
    proc = subprocess.Popen([str(SCRIPT), "app", "--port", "0", "--no-browser"],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        line = proc.stdout.readline()
        match = re.search(r"(http://127\.0\.0\.1:\d+/)", line)
        assert match, f"the app printed no URL: {line!r}"
        url = match.group(1)
        deadline = time.monotonic() + 20
        while True:
            try:
                fetch(url + "api/options")
                break
            except OSError:
                assert time.monotonic() < deadline, "the app did not answer within 20 s"
                time.sleep(0.1)
        yield url
    finally:
        proc.terminate()
        proc.wait(10)


def test_the_page_and_every_asset_it_references_load(running_app):
    status, content_type, page = fetch(running_app)
    assert status == 200 and content_type.startswith("text/html")
    assert "SPECTRA" in page
    assets = [a for a in re.findall(r'(?:src|href)="([^"#]+)"', page) if not a.startswith("data:")]
    assert assets, "the page references no script or style sheet"
    for asset in assets:
        assert not asset.startswith(("http:", "https:", "//")), f"external asset {asset}"
        status, _, body = fetch(running_app + asset.lstrip("/"))
        assert status == 200 and body, asset


def test_the_announced_address_already_accepts_connections():
    """The 'serving at' line (and the browser opened with it) comes after the socket listens: a
    connection made the moment the line is read waits for an answer instead of being refused."""
    import socket

    process = subprocess.Popen([sys.executable, "-m", "spectrocolor", "app", "--port", "0", "--no-browser"],
                               stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    try:
        line = process.stdout.readline()
        port = int(re.search(r"http://127\.0\.0\.1:(\d+)/", line).group(1))
        with socket.create_connection(("127.0.0.1", port), timeout=60) as connection:
            connection.sendall(f"GET / HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\nConnection: close\r\n\r\n".encode())
            assert connection.recv(12) == b"HTTP/1.1 200"
    finally:
        process.terminate()
        process.wait(30)
