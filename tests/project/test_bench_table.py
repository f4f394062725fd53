"""The README's speed table is generated from the committed bench results, never typed.

No timing is asserted here: the README's block must equal what ``tools/speed_table.py`` makes
of ``bench/results.json``, the ±30 % rule and the number formats are checked on given values,
and the alternating timer's bookkeeping on a fake clock.
"""

from __future__ import annotations

import importlib.util
import json
import math
import sys
import time
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


def _load(name: str, path: Path):
    spec = importlib.util.spec_from_file_location(name, path)
    module = importlib.util.module_from_spec(spec)
    sys.modules[name] = module  # dataclasses look their module up there
    spec.loader.exec_module(module)
    return module


speed_table = _load("speed_table", ROOT / "tools" / "speed_table.py")
timing = _load("timing", ROOT / "bench" / "timing.py")  # the name bench/results.py imports it by
bench_results = _load("bench_results", ROOT / "bench" / "results.py")


# --- the README against the committed results file ------------------------------------------

def test_the_readme_speed_table_is_what_the_committed_results_file_gives():
    results = json.loads(speed_table.RESULTS.read_text())
    readme = speed_table.README.read_text()
    assert speed_table.BEGIN in readme and speed_table.END in readme
    assert speed_table.replace_block(readme, speed_table.render(results)) == readme, (
        "README.md's speed table differs from bench/results.json: run `make bench`, or "
        "`.venv/bin/python tools/speed_table.py` to regenerate it from the committed results")


def test_the_committed_results_hold_two_complete_passes_of_the_same_figures():
    results = json.loads(speed_table.RESULTS.read_text())
    first, second = (results["runs"][key]["tasks"] for key in ("1", "2"))
    assert first and list(first) == list(second)
    for task in first:
        names = [[f["name"] for f in run[task]["figures"]] for run in (first, second)]
        assert names[0] == names[1], task
    environment = results["environment"]
    for key in ("date", "machine", "threads", "versions", "git"):
        assert environment[key], key
    for key in ("1", "2"):
        section = results["runs"][key]
        assert len(section["load_before"]) == 3 and len(section["load_after"]) == 3


def test_the_speed_section_types_no_figure_outside_the_generated_block():
    readme = speed_table.README.read_text()
    section = readme.split("## Speed", 1)[1].split("\n## ", 1)[0]
    before = section.split(speed_table.BEGIN)[0]
    assert "×" not in before and "colours/s" not in before and " ms" not in before


# --- the ±30 % rule and how figures print ---------------------------------------------------

@pytest.mark.parametrize(("a", "b", "expected"), [
    (64.0, 66.0, True),
    (66.0, 64.0, True),
    (10.0, 13.0, True),  # exactly +30 %: still reproduced
    (10.0, 13.01, False),
    (64.0, 121.0, False),
    (1800.0, 5700.0, False),
    (None, 5.0, False),
    (5.0, None, False),
    (0.0, 0.0, False),
    (-2.0, -2.0, False),
    (math.nan, 1.0, False),
    (math.inf, math.inf, False),
])
def test_a_figure_is_reproduced_when_the_larger_pass_is_at_most_1_3_times_the_smaller(a, b, expected):
    assert speed_table.reproduced(a, b) is expected


def test_a_reproduced_figure_prints_as_one_number_or_a_range_and_the_rest_say_not_reproduced():
    assert speed_table.figure_text("{}× slower", 64.2, 65.9) == ("64–66× slower", True)
    assert speed_table.figure_text("{} ms", 10.01, 10.04) == ("10 ms", True)
    assert speed_table.figure_text("{}× slower", 64.0, 121.0) == ("not reproduced (64 vs 121× slower)", False)
    assert speed_table.figure_text("{} ms", 12.0, None) == ("not reproduced (12 vs missing ms)", False)


@pytest.mark.parametrize(("value", "text"), [
    (0.78, "0.78"), (1.0449, "1.04"), (9.99, "9.99"), (10.4, "10"), (236.6, "237"),
    (999.4, "999"), (1000.0, "1 000"), (163_682.0, "164 000"), (999_000.0, "999 000"),
    (2_016_085.0, "2.02 M"), (18_100_000.0, "18.1 M"),
])
def test_numbers_print_with_three_significant_digits(value, text):
    assert speed_table.format_number(value) == text


def _results(first: dict, second: dict) -> dict:
    def section(tasks):
        return {"started": "2026-01-01T10:00:00+00:00", "finished": "2026-01-01T10:05:00+00:00",
                "load_before": [1.0, 1.0, 1.0], "load_after": [2.0, 1.5, 1.0], "scripts": {},
                "tasks": {name: {"label": "a task", "script": "bench_x.py",
                                 "figures": [{"name": n, "value": v, "column": c, "text": t, "primary": True}
                                             for n, v, c, t in figures]}
                          for name, figures in tasks.items()}}

    return {"format": 1, "environment": {"date": "2026-01-01T10:00:00+00:00"},
            "runs": {"1": section(first), "2": section(second)}}


def test_rows_put_each_figure_in_its_column_and_count_what_was_not_reproduced():
    results = _results(
        {"x": [("ours_ms", 10.0, "ours", "{} ms"), ("ratio", 5.0, "colour-science", "{}× slower"),
               ("limit", 1.1, "limit", "{}× its time")],
         "only_first": [("ours_ms", 3.0, "ours", "{} ms")]},
        {"x": [("ours_ms", 11.0, "ours", "{} ms"), ("ratio", 9.0, "colour-science", "{}× slower"),
               ("limit", 1.1, "limit", "{}× its time")]},
    )
    table, shown, failed = speed_table.rows(results)
    assert table[0] == ["a task (`bench_x.py`)", "10–11 ms", "not reproduced (5 vs 9× slower)", "1.1× its time"]
    assert table[1] == ["a task (`bench_x.py`)", "not reproduced (3 vs missing ms)", "—", "—"]
    assert (shown, failed) == (2, 2)
    block = speed_table.render(results)
    assert "2 figures reproduced within ±30 %" in block and "2 did not" in block
    assert "load average 1.0 → 2.0" in block


def test_the_block_is_replaced_between_the_markers_only():
    text = f"before\n{speed_table.BEGIN}\nold\n{speed_table.END}\nafter\n"
    assert speed_table.replace_block(text, "new") == f"before\n{speed_table.BEGIN}\nnew\n{speed_table.END}\nafter\n"
    with pytest.raises(ValueError, match="no"):
        speed_table.replace_block("no markers", "new")


def test_check_mode_fails_on_a_stale_table_and_passes_on_a_fresh_one(tmp_path):
    results = _results({"x": [("ours_ms", 10.0, "ours", "{} ms")]}, {"x": [("ours_ms", 10.0, "ours", "{} ms")]})
    path = tmp_path / "results.json"
    path.write_text(json.dumps(results))
    readme = tmp_path / "README.md"
    readme.write_text(f"# x\n{speed_table.BEGIN}\nstale\n{speed_table.END}\n")
    assert speed_table.main(["--results", str(path), "--readme", str(readme), "--check"]) == 1
    assert speed_table.main(["--results", str(path), "--readme", str(readme)]) == 0
    assert speed_table.main(["--results", str(path), "--readme", str(readme), "--check"]) == 0
    assert "| a task (`bench_x.py`) | 10 ms | — | — |" in readme.read_text()


# --- the alternating timer, on a fake clock --------------------------------------------------

class FakeClock:
    """A clock that advances only when a fake function says how long it took."""

    def __init__(self):
        self.now = 0.0
        self.calls: list[str] = []

    def __call__(self) -> float:
        return self.now

    def function(self, name: str, durations: list[float]):
        """A function that logs its call and advances the clock by its next duration."""
        remaining = iter(durations)

        def run():
            self.calls.append(name)
            self.now += next(remaining)
        return run


def test_alternate_best_warms_each_function_once_then_times_them_round_robin():
    clock = FakeClock()
    functions = {"ours": clock.function("ours", [100.0, 3.0, 2.0, 4.0]),
                 "theirs": clock.function("theirs", [100.0, 30.0, 50.0, 20.0])}
    best = timing.alternate_best(functions, repeats=3, clock=clock)
    assert clock.calls == ["ours", "theirs"] + ["ours", "theirs"] * 3
    assert best == {"ours": 2.0, "theirs": 20.0}  # the warm-up calls (100) are not counted
    assert list(best) == ["ours", "theirs"]


def test_alternate_best_without_warm_up_counts_every_call():
    clock = FakeClock()
    best = timing.alternate_best({"a": clock.function("a", [1.0, 5.0])}, repeats=2, warm=False, clock=clock)
    assert clock.calls == ["a", "a"] and best == {"a": 1.0}


def test_rounds_go_on_until_min_time_has_passed_and_stop_at_max_repeats():
    clock = FakeClock()
    quick = {"a": clock.function("a", [1.0] * 100), "b": clock.function("b", [1.0] * 100)}
    timing.alternate_best(quick, repeats=2, min_time=9.0, warm=False, clock=clock)
    assert clock.calls == ["a", "b"] * 5  # 2 rounds are 4 s; rounds go on until 10 s >= 9 s
    clock.calls.clear()
    timing.alternate_best(quick, repeats=2, min_time=1e9, max_repeats=3, warm=False, clock=clock)
    assert clock.calls == ["a", "b"] * 3


def test_a_burst_calls_a_quick_function_again_within_its_turn_and_keeps_its_shortest_call():
    clock = FakeClock()
    functions = {"quick": clock.function("quick", [0.5, 0.375, 0.5, 0.25, 0.625, 0.125]),
                 "slow": clock.function("slow", [5.0, 4.0])}
    best = timing.alternate_best(functions, repeats=2, burst=1.0, warm=False, clock=clock)
    # each turn of "quick" lasts until 1 s of its calls have passed: 0.5 + 0.375 + 0.5, then 0.25 + 0.625 + 0.125
    assert clock.calls == ["quick"] * 3 + ["slow"] + ["quick"] * 3 + ["slow"]
    assert best == {"quick": 0.125, "slow": 4.0}  # exact: a fake clock of binary fractions
    # exact: the fake clock's own reading, returned unchanged
    assert timing.shortest_call(clock.function("once", [7.0]), burst=0.0, clock=clock) == 7.0


def test_the_clock_is_cpu_time_unless_the_environment_asks_for_wall_time(monkeypatch):
    monkeypatch.delenv(timing.CLOCK_ENV, raising=False)
    assert timing.default_clock() is time.process_time and timing.clock_name() == "process CPU time"
    monkeypatch.setenv(timing.CLOCK_ENV, "wall")
    assert timing.default_clock() is time.perf_counter and timing.clock_name() == "wall time"
    monkeypatch.setenv(timing.CLOCK_ENV, "sundial")
    with pytest.raises(ValueError, match="sundial"):
        timing.default_clock()


def test_alternate_min_keeps_the_smallest_reported_value_per_name():
    reported = {"x": iter([0.3, 0.1, 0.2]), "y": iter([0.5, 0.6, 0.4])}
    best = timing.alternate_min({name: (lambda name=name: next(reported[name])) for name in reported}, repeats=3)
    assert best == {"x": 0.1, "y": 0.4}
    with pytest.raises(ValueError):
        timing.alternate_min({}, repeats=0)


# --- the results file ------------------------------------------------------------------------

def test_record_merges_tasks_and_passes_into_one_file(tmp_path, monkeypatch):
    monkeypatch.setattr(bench_results, "environment", lambda: {"date": "now"})
    path = tmp_path / "results.json"
    ratio = bench_results.ratio("r", 5.0, "colour-science", "{}× slower")
    bench_results.record("a", "task a", [ratio], script="bench_a.py", path=path, run=1)
    bench_results.record("b", "task b", [bench_results.figure("t", 2.0, "ours", "{} ms")], script="bench_b.py",
                         path=path, run=1)
    bench_results.record("a", "task a", [ratio], script="bench_a.py", path=path, run=2)
    saved = json.loads(path.read_text())
    assert saved["environment"] == {"date": "now"}
    assert list(saved["runs"]) == ["1", "2"]
    assert list(saved["runs"]["1"]["tasks"]) == ["a", "b"] and list(saved["runs"]["2"]["tasks"]) == ["a"]
    assert saved["runs"]["1"]["tasks"]["a"]["figures"][0] == {
        "name": "r", "value": 5.0, "column": "colour-science", "text": "{}× slower", "primary": True}


def test_figures_name_a_known_column_and_a_place_for_the_number():
    with pytest.raises(ValueError, match="column"):
        bench_results.figure("x", 1.0, "theirs")
    with pytest.raises(ValueError, match="text"):
        bench_results.figure("x", 1.0, "ours", "no number")
    with pytest.raises(ValueError, match="repeat"):
        bench_results.record("t", "t", [bench_results.figure("x", 1.0, "ours")] * 2, script="s", path="/nonexistent")
