"""The one timer of the work-precision suites: the best (minimum) wall time per call.

Every suite of :data:`suites.SUITES` and ``benchmarks/bench_neutral.py`` time with
:func:`best_times`, so "time per point", "per curve" and "per run" mean the same statistic:
wall clock (``time.perf_counter``), the **minimum** over the timed samples, in the same
process. The minimum, not the mean or the median: the code timed is single-threaded, so a
sample's wall time is its CPU time plus what the machine's other jobs take from it, and those
only ever add time (the advice of :mod:`timeit`).

The options cover what the suites need:

* ``repeat`` rounds; in each round every function in turn runs one block (functions are
  interleaved, so that a change of the machine's load hits competitors alike, and a burst of
  other jobs cannot cover all the samples of one function);
* ``warmup``: untimed calls that pay compilation, caches and the first touch of memory:
  ``"first"`` one call of every function before the first round, ``"round"`` one call at the
  start of every block (caches warm again after the other functions ran), ``"none"`` none (the
  caller warmed up);
* ``number``: consecutive calls per timed sample (the sample's time is divided by it), for
  calls too short to time one by one;
* ``min_time``: seconds of timed samples per function, at least, spread over the rounds (each
  block keeps taking samples until it has at least one and ``min_time / repeat`` seconds): the
  same budget for every function, so a short call gets more samples of its floor;
* ``keep``: keep each function's last result (returned), or drop every result as soon as the
  call returns. The eigen suite's results are hundreds of MB at 10^6 points: kept, two of them
  would be alive during a call and the chart's peak memory would be the timer's, not the
  method's. Either way the previous result is freed inside the timed call, once per call.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable, Hashable, Mapping
from typing import Any

__all__ = ["WARMUPS", "best_times"]

#: the warm-up rules of :func:`best_times`
WARMUPS = ("first", "round", "none")


def best_times(
    fns: Mapping[Hashable, Callable[[], Any]],
    repeat: int,
    min_time: float = 0.0,
    *,
    number: int = 1,
    warmup: str = "round",
    keep: bool = True,
) -> tuple[dict[Hashable, float], dict[Hashable, Any]]:
    """Minimum wall time per call of each function, and its last result (module docstring).

    Parameters
    ----------
    fns : mapping of key to callable
        The functions timed (no arguments), in the order they run within a round.
    repeat : int
        Rounds, >= 1.
    min_time : float
        Seconds of timed samples per function, at least (>= 0; 0: one sample per round).
    number : int
        Consecutive calls per timed sample, >= 1.
    warmup : {"first", "round", "none"}
        Untimed calls: one per function before the first round, one at the start of every
        block, or none.
    keep : bool
        Keep and return each function's last result; False drops every result at once.

    Returns
    -------
    (dict, dict)
        Key -> the minimum seconds per call; key -> the last result of the function (empty if
        not ``keep``).

    Raises
    ------
    ValueError
        If ``repeat`` or ``number`` is not an integer >= 1, ``min_time`` is negative, or
        ``warmup`` is not one of :data:`WARMUPS`.
    """
    if not (isinstance(repeat, int) and not isinstance(repeat, bool) and repeat >= 1):
        raise ValueError(f"repeat = {repeat!r} must be an integer >= 1")
    if not (isinstance(number, int) and not isinstance(number, bool) and number >= 1):
        raise ValueError(f"number = {number!r} must be an integer >= 1")
    if not (isinstance(min_time, (int, float)) and min_time >= 0):
        raise ValueError(f"min_time = {min_time!r} must be a number >= 0 (seconds)")
    if not isinstance(keep, bool):
        raise TypeError(f"keep = {keep!r} must be True or False")
    if warmup not in WARMUPS:
        raise ValueError(f"warmup = {warmup!r} is not known; choose one of {', '.join(WARMUPS)}")
    best: dict[Hashable, float] = dict.fromkeys(fns, math.inf)
    out: dict[Hashable, Any] = {}
    if warmup == "first":
        for k, fn in fns.items():
            if keep:
                out[k] = fn()
            else:
                fn()
    block = min_time / repeat
    for _ in range(repeat):
        for k, fn in fns.items():
            if warmup == "round":
                if keep:
                    out[k] = fn()
                else:
                    fn()
            t_end = time.perf_counter() + block
            while True:
                t0 = time.perf_counter()
                if keep:
                    for _ in range(number):
                        out[k] = fn()
                else:
                    for _ in range(number):
                        fn()
                t1 = time.perf_counter()
                best[k] = min(best[k], (t1 - t0) / number)
                if t1 >= t_end:
                    break
    return best, out
