"""The gallery in docs/notebooks runs: each notebook executes clean, offline, on a local kernel.

Notebooks are stored without outputs (small diffs, nothing stale): this test executes each one
with nbclient on an ipykernel of this very interpreter (never a kernel spec found elsewhere),
talking over local sockets (no TCP port),
with a first cell, added here and not stored, that refuses every network connection except to
the loopback, a time limit per cell, and failure on any error. The outputs must include the
records' own notebook reprs, and no output may hold a script or a network reference. ``make
docs`` executes the same notebooks again (myst-nb) to render them into the docs site.
"""

from __future__ import annotations

import json
from pathlib import Path

import pytest

nbformat = pytest.importorskip("nbformat")
nbclient = pytest.importorskip("nbclient")
pytest.importorskip("ipykernel")

from jupyter_client.kernelspec import KernelSpecManager  # noqa: E402
from jupyter_client.manager import KernelManager  # noqa: E402

GALLERY = Path(__file__).resolve().parents[2] / "docs" / "notebooks"
NOTEBOOKS = sorted(GALLERY.glob("*.ipynb"))
#: Seconds any one cell may take (the slowest builds a small upsampling table).
CELL_TIMEOUT_S = 240

#: Run first in the kernel, not stored in the notebook: only loopback and local sockets connect.
OFFLINE = """
import socket as _socket

_connect = _socket.socket.connect


def _loopback_only(self, address):
    host = address[0] if isinstance(address, tuple) else None
    if host is not None and host not in ("127.0.0.1", "::1", "localhost"):
        raise OSError(f"the gallery runs offline: no connection to {host!r}")
    return _connect(self, address)


_socket.socket.connect = _loopback_only
"""


def test_the_gallery_has_the_seeds_first_then_each_capability():
    names = [p.stem for p in NOTEBOOKS]
    assert names[:5] == ["01_wyszecki_stiles_example", "02_visser_alloys", "03_spectra_demonstrations",
                         "04_zawischa_soap_film", "05_van_trigt_smoothest_reflectance"]
    assert {"06_light_sources", "07_measurement_files", "08_upsampling", "09_images_at_scale"} <= set(names)


@pytest.mark.parametrize("path", NOTEBOOKS, ids=[p.stem for p in NOTEBOOKS])
def test_notebooks_are_stored_without_outputs_and_with_a_title(path):
    notebook = nbformat.read(path, as_version=4)
    nbformat.validate(notebook)
    code = [cell for cell in notebook.cells if cell.cell_type == "code"]
    assert code and all(cell.outputs == [] and cell.execution_count is None for cell in code)
    assert notebook.cells[0].cell_type == "markdown" and notebook.cells[0].source.startswith("# ")
    assert notebook.metadata["kernelspec"]["name"] == "python3"


def _outputs(notebook) -> list[dict]:
    return [output for cell in notebook.cells if cell.cell_type == "code" for output in cell.outputs]


@pytest.mark.slow
@pytest.mark.parametrize("path", NOTEBOOKS, ids=[p.stem for p in NOTEBOOKS])
def test_notebook_runs_clean_offline(path, tmp_path):
    notebook = nbformat.read(path, as_version=4)
    notebook.cells.insert(0, nbformat.v4.new_code_cell(OFFLINE))
    # this interpreter's own ipykernel, over local sockets in the test's folder (no TCP port)
    manager = KernelManager(kernel_name="python3", kernel_spec_manager=KernelSpecManager(kernel_dirs=[]),
                            transport="ipc", ip=str(tmp_path / "kernel"))
    client = nbclient.NotebookClient(notebook, km=manager, timeout=CELL_TIMEOUT_S, startup_timeout=120,
                                     allow_errors=False, resources={"metadata": {"path": str(tmp_path)}})
    client.execute()  # raises CellExecutionError on the first failing cell
    outputs = _outputs(notebook)
    assert not [o for o in outputs if o.get("output_type") == "error"]
    assert not [o for o in outputs if o.get("name") == "stderr" and "Traceback" in o.get("text", "")]
    html = [o["data"]["text/html"] for o in outputs if "text/html" in o.get("data", {})]
    assert any('class="spectrocolor-repr' in h for h in html), "no record showed itself"
    for h in html:
        lowered = h.lower()
        assert "<script" not in lowered and "http:" not in lowered and "https:" not in lowered
    serialised = json.dumps([o.get("data", {}) for o in outputs])
    assert "matplotlib" not in serialised
