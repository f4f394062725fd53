"""The one results file of the bench scripts: what was measured, where, and in which pass.

Every ``bench_*.py`` that feeds the README's speed table ends with ``record(task, label,
figures, script=...)``, which merges its figures into a JSON file:

* the path is ``$SPECTROCOLOR_BENCH_RESULTS``, else ``bench/results/latest.json`` (not committed);
  ``make bench`` writes ``bench/results.json``, which is committed, and the README's table is
  generated from it by ``tools/speed_table.py``;
* the pass is ``$SPECTROCOLOR_BENCH_RUN`` (``make bench`` runs every script twice: passes 1 and 2),
  else 1.

Layout::

    {"format": 1,
     "environment": {machine, CPU, threads, versions, git commit, date},
     "runs": {"1": {"started", "finished", "load_before", "load_after",
                    "scripts": {script: {"seconds", "returncode", "load_before", "load_after"}},
                    "tasks": {task: {"label", "script", "recorded", "load", "figures": [...]}}},
              "2": {...}}}
"""

from __future__ import annotations

import json
import os
import platform
import subprocess
import sys
from dataclasses import asdict, dataclass
from datetime import UTC, datetime
from importlib import metadata
from pathlib import Path

from timing import CLOCK_ENV, clock_name

ROOT = Path(__file__).resolve().parents[1]
RESULTS_ENV = "SPECTROCOLOR_BENCH_RESULTS"
RUN_ENV = "SPECTROCOLOR_BENCH_RUN"
DEFAULT_PATH = ROOT / "bench" / "results" / "latest.json"
COMMITTED_PATH = ROOT / "bench" / "results.json"
FORMAT = 1
COLUMNS = ("ours", "colour-science", "limit")
THREAD_VARIABLES = ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS", "NUMBA_NUM_THREADS",
                    "OPENBLAS_CORETYPE", "NPY_DISABLE_CPU_FEATURES", "SPECTROCOLOR_NUMBA", CLOCK_ENV)
PACKAGES = ("spectrocolor", "numpy", "scipy", "numba", "colour-science", "dask", "threadpoolctl")


@dataclass(frozen=True)
class Figure:
    """One number of a task, and how the README's table prints it.

    Parameters
    ----------
    name : str
        Stable key within the task (the two passes are matched by it).
    value : float
        The measured value (positive).
    column : str
        Which column of the table shows it: ``"ours"``, ``"colour-science"`` or ``"limit"``.
    text : str
        How it reads in the table; ``{}`` stands for the number (a range when the two passes
        differ, or "not reproduced (a vs b)").
    primary : bool
        True for ratios measured within one process (ours against colour-science or against a
        plain NumPy limit): the figures the table is about.
    """

    name: str
    value: float
    column: str
    text: str = "{}"
    primary: bool = False

    def __post_init__(self) -> None:
        if self.column not in COLUMNS:
            raise ValueError(f"column must be one of {COLUMNS}, got {self.column!r}")
        if "{}" not in self.text:
            raise ValueError(f"text must contain {{}} for the number: {self.text!r}")


def ratio(name: str, value: float, column: str, text: str) -> Figure:
    """A primary figure: the ratio of two best times measured alternately in one process."""
    return Figure(name, float(value), column, text, primary=True)


def figure(name: str, value: float, column: str, text: str = "{}") -> Figure:
    """A supporting figure: a time, a rate or a size measured in the same run."""
    return Figure(name, float(value), column, text)


def results_path(path: str | os.PathLike | None = None) -> Path:
    """The results file: ``path``, else ``$SPECTROCOLOR_BENCH_RESULTS``, else the default."""
    chosen = path or os.environ.get(RESULTS_ENV) or DEFAULT_PATH
    return Path(chosen)


def current_run(run: int | None = None) -> str:
    """The pass number as the file's key: ``run``, else ``$SPECTROCOLOR_BENCH_RUN``, else 1."""
    return str(run if run is not None else int(os.environ.get(RUN_ENV, "1")))


def load_average() -> list[float]:
    """The 1, 5 and 15 minute load averages, rounded to two decimals."""
    return [round(value, 2) for value in os.getloadavg()]


def now() -> str:
    """The current UTC time, ISO 8601 to the second."""
    return datetime.now(UTC).replace(microsecond=0).isoformat()


def _cpu_model() -> str:
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or platform.machine()


def _cpu_flags() -> list[str]:
    """The vector-instruction flags of the CPU that decide NumPy's and OpenBLAS's kernels."""
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("flags"):
                flags = line.split(":", 1)[1].split()
                return sorted(f for f in flags if f.startswith(("avx", "fma", "sse4")))
    except OSError:
        pass
    return []


def _memory_gib() -> float | None:
    try:
        for line in Path("/proc/meminfo").read_text().splitlines():
            if line.startswith("MemTotal:"):
                return round(int(line.split()[1]) / 2**20, 1)
    except OSError:
        pass
    return None


def _git(*arguments: str) -> str:
    try:
        done = subprocess.run(["git", *arguments], cwd=ROOT, capture_output=True, text=True, timeout=30)
    except (OSError, subprocess.SubprocessError):
        return ""
    return done.stdout.strip() if done.returncode == 0 else ""


def _versions() -> dict[str, str]:
    versions = {"python": platform.python_version()}
    for package in PACKAGES:
        try:
            versions[package] = metadata.version(package)
        except metadata.PackageNotFoundError:
            versions[package] = "not installed"
    return versions


def _openblas_runtime() -> list[dict]:
    """Each OpenBLAS loaded in this process: its library, thread count and the CPU kernel it chose
    (what threadpoolctl reports, read the same way: from the library's own functions)."""
    import ctypes

    try:
        paths = sorted({line.split()[-1] for line in Path("/proc/self/maps").read_text().splitlines()
                        if "openblas" in line.lower() and ".so" in line})
    except OSError:
        return []
    found = []
    for path in paths:
        try:
            library = ctypes.CDLL(path)
        except OSError:
            continue
        facts = {"library": path}
        for prefix, suffix in (("scipy_", "64_"), ("", "64_"), ("scipy_", ""), ("", "")):
            threads = getattr(library, f"{prefix}openblas_get_num_threads{suffix}", None)
            corename = getattr(library, f"{prefix}openblas_get_corename{suffix}", None)
            if threads is not None and corename is not None:
                corename.restype = ctypes.c_char_p
                facts.update(threads=threads(), corename=corename().decode())
                break
        found.append(facts)
    return found


def _threads() -> dict:
    """Thread settings: the environment, numba's pool, and the BLAS NumPy uses."""
    import numpy as np

    facts: dict = {"environment": {name: os.environ.get(name, "unset") for name in THREAD_VARIABLES}}
    try:
        import numba

        facts["numba"] = {"threads": numba.get_num_threads(), "layer": numba.config.THREADING_LAYER}
    except ImportError:
        facts["numba"] = "not installed"
    try:
        from threadpoolctl import threadpool_info

        facts["threadpoolctl"] = threadpool_info()
    except ImportError:
        facts["threadpoolctl"] = "not installed"
    facts["openblas_runtime"] = _openblas_runtime()
    config = np.show_config(mode="dicts")
    blas = config.get("Build Dependencies", {}).get("blas", {})
    facts["numpy_blas"] = {key: blas.get(key) for key in ("name", "version", "openblas configuration")}
    facts["numpy_simd"] = config.get("SIMD Extensions", {})
    return facts


def environment() -> dict:
    """Facts about this machine and this checkout, for the results file."""
    commit = _git("rev-parse", "HEAD")
    return {
        "date": now(),
        "machine": {
            "hostname": platform.node(),
            "platform": platform.platform(),
            "cpu_model": _cpu_model(),
            "cpu_flags": _cpu_flags(),
            "cpu_count": os.cpu_count(),
            "cpus_usable": len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count(),
            "memory_gib": _memory_gib(),
        },
        "clock": clock_name(),
        "threads": _threads(),
        "versions": _versions(),
        "python_executable": sys.executable,
        "git": {"commit": commit, "uncommitted_changes": bool(_git("status", "--porcelain"))},
    }


def read(path: str | os.PathLike | None = None) -> dict:
    """The results file's content, or an empty skeleton if there is none yet."""
    target = results_path(path)
    if target.exists():
        return json.loads(target.read_text())
    return {"format": FORMAT, "environment": {}, "runs": {}}


def write(results: dict, path: str | os.PathLike | None = None) -> Path:
    """Write the results atomically (a partial file is never left behind); return the path."""
    target = results_path(path)
    target.parent.mkdir(parents=True, exist_ok=True)
    temporary = target.with_suffix(target.suffix + ".tmp")
    temporary.write_text(json.dumps(results, indent=1, ensure_ascii=False) + "\n")
    os.replace(temporary, target)
    return target


def start(path: str | os.PathLike | None = None) -> Path:
    """Begin a fresh results file (the environment, no runs): what ``run_all.py`` does first."""
    return write({"format": FORMAT, "environment": environment(), "runs": {}}, path)


def run_section(results: dict, run: int | None = None) -> dict:
    """The section of one pass, created if missing."""
    return results["runs"].setdefault(current_run(run), {"started": now(), "load_before": load_average(),
                                                         "scripts": {}, "tasks": {}})


def begin_pass(run: int, path: str | os.PathLike | None = None) -> None:
    """Open the section of pass ``run`` now, so that its start time and load are the pass's."""
    results = read(path)
    results["runs"].pop(current_run(run), None)
    run_section(results, run)
    write(results, path)


def record(task: str, label: str, figures: list[Figure], *, script: str,
           path: str | os.PathLike | None = None, run: int | None = None) -> Path:
    """Merge one task's figures into the results file, in the current pass.

    Parameters
    ----------
    task : str
        Stable identifier of the task (one row of the README's table).
    label : str
        What the task is, as the table's first column says it.
    figures : list of Figure
        Its figures (see ``ratio`` and ``figure``).
    script : str
        The bench script's file name, for the table.
    path : path-like, optional
        The results file (default: see ``results_path``).
    run : int, optional
        The pass (default: see ``current_run``).

    Returns
    -------
    Path
        The results file written.
    """
    names = [f.name for f in figures]
    if len(set(names)) != len(names):
        raise ValueError(f"figure names repeat in task {task!r}: {names}")
    results = read(path)
    if not results.get("environment"):
        results["environment"] = environment()
    section = run_section(results, run)
    section["tasks"][task] = {"label": label, "script": script, "recorded": now(), "load": load_average(),
                              "figures": [asdict(f) for f in figures]}
    target = write(results, path)
    print(f"  recorded {task!r} (pass {current_run(run)}) in {target}")
    return target


def note_script(script: str, seconds: float, returncode: int, load_before: list[float],
                load_after: list[float], *, path: str | os.PathLike | None = None,
                run: int | None = None) -> None:
    """Record how one script of a pass went (``run_all.py`` calls this after each script)."""
    results = read(path)
    section = run_section(results, run)
    section["scripts"][script] = {"seconds": round(seconds, 1), "returncode": returncode,
                                  "load_before": load_before, "load_after": load_after}
    section["finished"] = now()
    section["load_after"] = load_after
    write(results, path)
