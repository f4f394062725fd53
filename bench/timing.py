"""Timing helpers shared by the bench scripts (run as ``python bench/bench_x.py``).

Every figure the README prints is a best time, or a ratio of two best times, taken in one
process with the sides of a comparison timed alternately (``alternate_best``): a busy machine
slows both sides of a round alike, and the best of several rounds is the least disturbed one.
Within a round a quick function is called again and again for a short burst, each call timed on
its own, so that it gets as many chances at an undisturbed call as a slow one gets in its one
call.

The clock is the process's CPU time (``time.process_time``) unless ``SPECTROCOLOR_BENCH_CLOCK=wall``:
on a machine that runs more work than it has cores, no call of more than a few milliseconds
escapes the scheduler, and wall time measures the other work as much as ours, while CPU time
does not. With one thread (``OPENBLAS_NUM_THREADS=1`` and ``NUMBA_NUM_THREADS=1``, as
``run_all.py`` sets them) CPU time is the wall time of the call on an idle machine; with more
threads it is the work of all of them.
"""

from __future__ import annotations

import argparse
import os
import time
from collections.abc import Callable, Mapping

CLOCK_ENV = "SPECTROCOLOR_BENCH_CLOCK"
#: The clocks a bench may time with: name → (function, what the figures are).
CLOCKS = {"cpu": (time.process_time, "process CPU time"), "wall": (time.perf_counter, "wall time")}

#: Seconds each function is called for, call after call, in each round by default (at least once).
BURST = 0.2


def clock_choice() -> str:
    """The clock the bench times with: ``$SPECTROCOLOR_BENCH_CLOCK`` ("cpu" or "wall"), default "cpu"."""
    choice = os.environ.get(CLOCK_ENV, "cpu")
    if choice not in CLOCKS:
        raise ValueError(f"{CLOCK_ENV} must be one of {sorted(CLOCKS)}, got {choice!r}")
    return choice


def default_clock() -> Callable[[], float]:
    """The clock function of ``clock_choice``."""
    return CLOCKS[clock_choice()][0]


def clock_name() -> str:
    """What the figures measure, in words ("process CPU time" or "wall time")."""
    return CLOCKS[clock_choice()][1]


def add_arguments(parser: argparse.ArgumentParser, repeats: int = 5, burst: float = BURST) -> None:
    """Add the bench scripts' common ``--repeats`` and ``--burst`` options to ``parser``.

    Parameters
    ----------
    parser : argparse.ArgumentParser
        The script's parser.
    repeats : int
        Default number of alternating rounds.
    burst : float
        Default seconds per function per round.
    """
    parser.add_argument("--repeats", type=int, default=repeats,
                        help=f"number of alternating timed rounds, best of them (default {repeats})")
    parser.add_argument("--burst", type=float, default=burst,
                        help=f"seconds each function is called for in each round, at least once (default {burst})")


def best_of(function: Callable[[], object], repeats: int = 5,
            clock: Callable[[], float] | None = None) -> float:
    """Best time of ``repeats`` calls, in seconds (the least disturbed by a busy machine).

    Parameters
    ----------
    function : callable
        Called with no arguments.
    repeats : int
        Number of timed calls.
    clock : callable, optional
        Default ``default_clock()``; pass ``time.perf_counter`` for work done in other processes.

    Returns
    -------
    float
        The shortest of the timed calls, in seconds.
    """
    return alternate_best({"function": function}, repeats=repeats, warm=False, clock=clock)["function"]


def alternate_min(
    measures: Mapping[str, Callable[[], float]],
    repeats: int = 5,
    min_time: float = 0.0,
    *,
    max_repeats: int | None = None,
    clock: Callable[[], float] | None = None,
) -> dict[str, float]:
    """Smallest value each measure returns over rounds that call every measure once, in turn.

    Round after round, each measure is called in the order of ``measures``; a measure returns
    the seconds it measured (``alternate_best`` times plain functions with it; ``bench_import``
    uses it for times that fresh interpreters report).

    Parameters
    ----------
    measures : mapping of str to callable
        Name to a callable returning a duration in seconds.
    repeats : int
        Least number of rounds.
    min_time : float
        Rounds go on past ``repeats`` until this many seconds of ``clock`` have passed since the
        first round began.
    max_repeats : int, optional
        Most rounds, whatever ``min_time`` asks; default ``20 * repeats``.
    clock : callable, optional
        The clock that ``min_time`` is measured on (default ``default_clock()``).

    Returns
    -------
    dict of str to float
        Name to its smallest measured value, in the order of ``measures``.
    """
    if repeats < 1:
        raise ValueError(f"repeats must be at least 1, got {repeats}")
    clock = clock or default_clock()
    most = 20 * repeats if max_repeats is None else max(max_repeats, repeats)
    best = {name: float("inf") for name in measures}
    start = clock()
    rounds = 0
    while rounds < repeats or (clock() - start < min_time and rounds < most):
        for name, measure in measures.items():
            best[name] = min(best[name], measure())
        rounds += 1
    return best


def shortest_call(function: Callable[[], object], burst: float = 0.0,
                  clock: Callable[[], float] | None = None) -> float:
    """Shortest of calls of ``function``, each timed on its own, made until ``burst`` seconds
    of calls have passed (one call when ``burst`` is 0).

    Parameters
    ----------
    function : callable
        Called with no arguments.
    burst : float
        Seconds of calls.
    clock : callable, optional
        Clock in seconds (default ``default_clock()``).

    Returns
    -------
    float
        The shortest call, in seconds.
    """
    clock = clock or default_clock()
    shortest, spent = float("inf"), 0.0
    while True:
        begin = clock()
        function()
        took = clock() - begin
        shortest, spent = min(shortest, took), spent + took
        if spent >= burst:
            return shortest


def alternate_best(
    functions: Mapping[str, Callable[[], object]],
    repeats: int = 5,
    min_time: float = 0.0,
    *,
    burst: float = 0.0,
    warm: bool = True,
    max_repeats: int | None = None,
    clock: Callable[[], float] | None = None,
) -> dict[str, float]:
    """Best time of each function, the functions timed round-robin in one process.

    Each function is called once untimed first (``warm``: caches, compiled kernels, lazily built
    tables), then rounds call ``a, b, c, a, b, c, …`` (with ``burst``, each of them repeatedly for
    that many seconds, every call timed on its own); the result is each one's shortest call.
    Timing the sides of a comparison alternately makes their ratio robust to load that comes and
    goes: both see the same machine.

    Parameters
    ----------
    functions : mapping of str to callable
        Name to a function called with no arguments.
    repeats : int
        Least number of timed rounds.
    min_time : float
        Rounds go on until this many seconds have passed (see ``alternate_min``).
    burst : float
        Seconds each function is called for in each round, at least once (see ``shortest_call``).
    warm : bool
        Call each function once, untimed, before the rounds.
    max_repeats : int, optional
        Most rounds; default ``20 * repeats``.
    clock : callable, optional
        Clock in seconds (default ``default_clock()``: CPU time; tests pass a fake one).

    Returns
    -------
    dict of str to float
        Name to its best time in seconds, in the order of ``functions``.

    Examples
    --------
    >>> best = alternate_best({"ours": lambda: sum(range(100)), "theirs": lambda: sum(range(1000))})
    >>> sorted(best) == ["ours", "theirs"] and all(t > 0 for t in best.values())
    True
    """
    clock = clock or default_clock()
    if warm:
        for function in functions.values():
            function()
    measures = {name: (lambda function=function: shortest_call(function, burst, clock))
                for name, function in functions.items()}
    return alternate_min(measures, repeats, min_time, max_repeats=max_repeats, clock=clock)
