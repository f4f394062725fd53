"""The explorer in class mode as a user starts it (``spectrocolor app --classroom``), for tests.

:func:`class_server` runs ``spectrocolor app --classroom --host 127.0.0.2 --port 0 --no-browser``
in its own process and yields what it printed: the class's origin, the students' join address
and the teacher's address (issue 30).
"""

from __future__ import annotations

import contextlib
import os
import re
import subprocess
import sys
import time

import httpx

HOST = "127.0.0.2"


@contextlib.contextmanager
def class_server(host: str = HOST):
    env = {**os.environ, "PYTHONUNBUFFERED": "1", "SPECTROCOLOR_NUMBA": "0"}
    proc = subprocess.Popen([sys.executable, "-m", "spectrocolor", "app", "--classroom", "--host",
                             host, "--port", "0", "--no-browser"], stdout=subprocess.PIPE,
                            stderr=subprocess.DEVNULL, text=True, env=env)
    try:
        lines: list[str] = []
        while not any("teacher's page" in line for line in lines):
            line = proc.stdout.readline()
            assert line, f"the server stopped: {lines}"
            lines.append(line)
        text = "".join(lines)
        origin = re.search(r"class open at (http://\S+?)/ ", text).group(1)
        join = re.search(r"students join at (\S+)", text).group(1)
        teacher = re.search(r"teacher's page \(keep this address to yourself\): (\S+)",
                            text).group(1)
        _warm(origin, teacher)
        yield {"origin": origin, "join": join, "teacher": teacher, "output": text}
    finally:
        proc.terminate()
        proc.wait(10)


def _warm(origin: str, teacher: str) -> None:
    """Wait until the lane's workers answer (they start with the server; slow on a busy machine)."""
    with httpx.Client(base_url=origin, timeout=120.0) as s:
        s.get(teacher)
        for _ in range(240):
            try:
                if s.post("/api/model", json={}).status_code == 200 and \
                        s.get("/api/presets?step_nm=10").status_code == 200:
                    return
            except httpx.HTTPError:
                pass
            time.sleep(0.5)
