"""Generate the README's speed table from the bench results file; never type it by hand.

Run: .venv/bin/python tools/speed_table.py [--results bench/results.json] [--readme README.md] [--check]

``make bench`` runs every bench script twice (``bench/run_all.py``) into ``bench/results.json``
and then this script, which rewrites the README between ``<!-- speed-table:begin -->`` and
``<!-- speed-table:end -->``: a line naming the machine, CPU, threads, versions, commit, date and
load of the run, and one row per task. A cell prints a figure only if the two passes reproduce it
within ±30 % (the larger at most 1.3 times the smaller), as one number or the range of the two;
otherwise it reads "not reproduced (a vs b)". ``--check`` changes nothing and fails if the README
differs from what the results file gives (the test suite checks the same).
"""

from __future__ import annotations

import argparse
import json
import math
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
RESULTS = ROOT / "bench" / "results.json"
README = ROOT / "README.md"
BEGIN = "<!-- speed-table:begin -->"
END = "<!-- speed-table:end -->"
TOLERANCE = 0.30
PASSES = ("1", "2")
COLUMNS = ("ours", "colour-science", "limit")


def reproduced(a: float | None, b: float | None, tolerance: float = TOLERANCE) -> bool:
    """Whether two passes agree: both positive and finite, the larger ≤ (1 + tolerance) × the smaller.

    Parameters
    ----------
    a, b : float or None
        The figure in each pass (None where a pass lacks it).
    tolerance : float
        Allowed relative excess of the larger over the smaller (0.30: ±30 %).

    Returns
    -------
    bool

    Examples
    --------
    >>> reproduced(64.0, 66.0), reproduced(64.0, 121.0), reproduced(10.0, 13.0)
    (True, False, True)
    """
    if a is None or b is None or not (math.isfinite(a) and math.isfinite(b)) or min(a, b) <= 0:
        return False
    return max(a, b) <= (1.0 + tolerance) * min(a, b) * (1.0 + 1e-12)


def format_number(value: float) -> str:
    """A figure as the table prints it: 3 significant digits below 10, whole numbers up to 999,
    3 significant digits grouped by thousands up to a million, then millions ("2.02 M").

    Examples
    --------
    >>> [format_number(v) for v in (1.0449, 5.17, 64.4, 236.6, 163682.0, 2016085.0)]
    ['1.04', '5.17', '64', '237', '164 000', '2.02 M']
    """
    if not math.isfinite(value):
        return str(value)
    if value >= 999_500:
        return f"{value / 1e6:.3g} M"
    if value >= 999.5:
        digits = math.floor(math.log10(value)) + 1
        rounded = round(value, 3 - digits)
        return f"{rounded:,.0f}".replace(",", " ")
    if value >= 9.995:
        return f"{value:.0f}"
    return f"{value:.3g}"


def format_pair(a: float, b: float) -> str:
    """Two passes' values as one number when they print alike, else as a range "low–high".

    Examples
    --------
    >>> format_pair(64.2, 65.9), format_pair(1.04, 1.041), format_pair(2.1e6, 1.9e6)
    ('64–66', '1.04', '1.9–2.1 M')
    """
    low, high = sorted((a, b))
    low_text, high_text = format_number(low), format_number(high)
    if low_text == high_text:
        return low_text
    if low_text.endswith(" M") and high_text.endswith(" M"):
        return f"{low_text[:-2]}–{high_text}"
    return f"{low_text}–{high_text}"


def figure_text(template: str, a: float | None, b: float | None) -> tuple[str, bool]:
    """One figure's text in a cell, and whether it was reproduced."""
    if reproduced(a, b):
        return template.replace("{}", format_pair(a, b)), True
    shown = " vs ".join("missing" if v is None else format_number(v) for v in (a, b))
    return f"not reproduced ({template.replace('{}', shown)})", False


def _passes(results: dict) -> list[dict]:
    runs = results.get("runs", {})
    return [runs.get(key, {}).get("tasks", {}) for key in PASSES]


def rows(results: dict) -> tuple[list[list[str]], int, int]:
    """The table's rows (task, then one cell per column), and the counts of figures printed and
    not reproduced."""
    first, second = _passes(results)
    table, shown, failed = [], 0, 0
    for task in list(first) + [t for t in second if t not in first]:
        entries = [first.get(task), second.get(task)]
        base = entries[0] or entries[1]
        values = [{f["name"]: f["value"] for f in (entry or {}).get("figures", [])} for entry in entries]
        cells = {column: [] for column in COLUMNS}
        for spec in base["figures"]:
            text, ok = figure_text(spec["text"], values[0].get(spec["name"]), values[1].get(spec["name"]))
            cells[spec["column"]].append(text)
            shown += ok
            failed += not ok
        table.append([f"{base['label']} (`{base['script']}`)"]
                     + ["; ".join(cells[column]) or "—" for column in COLUMNS])
    return table, shown, failed


def _load(section: dict) -> str:
    before, after = section.get("load_before"), section.get("load_after")
    if not before or not after:
        return "load average unknown"
    return f"load average {before[0]:.1f} → {after[0]:.1f}"


def _time(stamp: str | None) -> str:
    return stamp[11:16] if stamp else "?"


def provenance(results: dict) -> list[str]:
    """Lines naming where, with what and when the figures were measured."""
    environment = results.get("environment", {})
    machine = environment.get("machine", {})
    versions = environment.get("versions", {})
    threads = environment.get("threads", {})
    blas = threads.get("numpy_blas", {})
    runtime = threads.get("openblas_runtime") or [{}]
    numba = threads.get("numba", {})
    git = environment.get("git", {})
    commit = (git.get("commit") or "unknown")[:7]
    if git.get("uncommitted_changes"):
        commit += " with uncommitted changes"
    openblas = threads.get("environment", {}).get("OPENBLAS_NUM_THREADS", "unset")
    numba_threads = f"numba {numba.get('threads')} thread(s)" if isinstance(numba, dict) else "no numba"
    passes = [f"pass {key} {_time(section.get('started'))}–{_time(section.get('finished'))} UTC "
              f"({_load(section)})"
              for key in PASSES if (section := results.get("runs", {}).get(key))]
    return [
        f"* Machine: {machine.get('cpu_model', '?')}, {machine.get('cpus_usable', '?')} of "
        f"{machine.get('cpu_count', '?')} CPUs usable, {machine.get('memory_gib', '?')} GiB, "
        f"{machine.get('platform', '?')}; OPENBLAS_NUM_THREADS={openblas} (OpenBLAS kernel "
        f"{runtime[0].get('corename', '?')}), {numba_threads}.",
        f"* Software: Python {versions.get('python', '?')}, NumPy {versions.get('numpy', '?')} "
        f"({blas.get('name', '?')} {blas.get('version', '?')}), numba {versions.get('numba', '?')}, "
        f"colour-science {versions.get('colour-science', '?')}; commit {commit}.",
        f"* Run: {environment.get('date', '?')[:10]}, " + ", ".join(passes) + f"; clock: "
        f"{environment.get('clock', 'wall time')}.",
    ]


def render(results: dict) -> str:
    """The README's block between the markers (without them)."""
    table, shown, failed = rows(results)
    colour = results.get("environment", {}).get("versions", {}).get("colour-science", "?")
    lines = [
        "<!-- generated by tools/speed_table.py from bench/results.json: do not edit by hand -->",
        *provenance(results),
        "",
        f"Each figure is warm and the best of several calls on each side, the sides timed alternately in one "
        f"process, on the clock named above; ratios (× slower, × its time) are the primary figures. Each cell "
        f"shows both passes of `make bench`: one number where they print alike, else the range. {shown} "
        f"figures reproduced within ±30 % between the two passes; {failed} did not and read "
        f"\"not reproduced (pass 1 vs pass 2)\" instead of a figure.",
        "",
        f"| task (script) | spectrocolor | colour-science {colour} | plain NumPy limit |",
        "| --- | --- | --- | --- |",
    ]
    lines += ["| " + " | ".join(row) + " |" for row in table]
    return "\n".join(lines)


def replace_block(text: str, block: str) -> str:
    """``text`` with everything between the markers replaced by ``block``."""
    start, end = text.find(BEGIN), text.find(END)
    if start < 0 or end < start:
        raise ValueError(f"the README has no {BEGIN} … {END} block")
    return text[: start + len(BEGIN)] + "\n" + block + "\n" + text[end:]


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--results", type=Path, default=RESULTS)
    parser.add_argument("--readme", type=Path, default=README)
    parser.add_argument("--check", action="store_true", help="fail if the README's table is not what the results give")
    args = parser.parse_args(argv)
    results = json.loads(args.results.read_text())
    text = args.readme.read_text()
    updated = replace_block(text, render(results))
    if args.check:
        if updated != text:
            print(f"{args.readme}: the speed table differs from {args.results}; run tools/speed_table.py",
                  file=sys.stderr)
            return 1
        print(f"{args.readme}: the speed table matches {args.results}")
        return 0
    if updated != text:
        args.readme.write_text(updated)
    _, shown, failed = rows(results)
    print(f"{args.readme}: speed table from {args.results} ({shown} figures reproduced, {failed} not)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
