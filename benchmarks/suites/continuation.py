"""Continuation against a brentq per grid column: the one measurement of both.

Used by ``python benchmarks/run.py --suite continuation`` (:data:`suites.SUITES`, through
:func:`continuation_work_precision`) and by ``benchmarks/bench_neutral.py`` (the tables,
:func:`neutral_benchmark` and :func:`format_tables`): one implementation, one timing method.

Problem (the sliding model, eq. 11): the neutral curve in the ``(q, sigma)`` plane at
``fr_inv = 0``, ``alpha_v = 0.5``, ``mu = 2.28``, over the whole physical domain. There the
neutral condition has a closed form (tests/test_neutral.py): the curve is
``sigma = (1 - mu q^2) / (1 + q)`` and its fold (the largest sigma on it, the paper's
``sigma ~ 1.14`` of Figs. 3c-d) is at ``q* = -1 + sqrt(1 - 1/mu)``,
``sigma* = 2 (mu - sqrt(mu (mu - 1)))``.

* continuation: the whole :func:`continuation.neutral_curve` call (start points from a
  25 x 25 atlas, both directions, fold and domain edges located, the dataset and its LAPACK
  check) at several ``(max_step, max_angle)`` settings (the default ``(0.05, 0.1)`` first);
  the curve between the points is its dense output (:func:`continuation.dense`, cubic Hermite,
  32 samples per step over the whole curve);
* columns (the baseline): ``N`` columns ``q_j`` evenly spaced inside ``|q| < 1/sqrt(mu)``,
  ``scipy.optimize.brentq`` in sigma on ``[1e-9, 2 (1 - mu q_j^2)]`` on the leading growth
  rate (the largest ``Re s`` over the modes that are not structurally zero), ``xtol = 1e-14``;
  the curve a cubic spline through the column roots (not-a-knot; its error over 20 samples per
  column interval, over the columns' span only, which favours the columns), the fold the
  spline's maximum. Leading growth rate [A]: :func:`stability.spectrum` with its fastest method
  for one point (picked by timing, :func:`fastest_method`; a one-point call runs the compiled
  kernel serially, ``stability.linear.kernel.SERIAL_BELOW``); [B]: ``numpy.roots`` on the model's
  coefficients (a hand-written shortcut);
* equal accuracy: the smallest column count whose spline error is at most the continuation's
  dense error (:func:`columns_for_accuracy`, searched over every ``N``, not a list), timed;
* turning back: columns at fixed sigma (brentq in q) see nothing where they cross the curve
  twice (:func:`columns_in_q`).

Timing (:func:`suites.timing.best_times`, warm-up ``"round"``): wall clock
(``time.perf_counter``), the **minimum** over all timed calls of a configuration: ``repeat``
rounds, in each a block of consecutive calls of every configuration in turn (one untimed
warm-up call, then at least ``min_time / repeat`` seconds), in the same process. Everything
timed is single-threaded, so the wall time of a run is its CPU time plus what the machine's
other jobs take from it; those only ever add time, and the minimum is the least disturbed
estimate (the advice of :mod:`timeit`). The same rule for the continuation and the baselines.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Callable, Hashable
from typing import Any

import numpy as np

from stability import execution

from .records import Panel, Suite, WorkPrecision
from .timing import best_times

__all__ = [
    "ALPHA_V",
    "COLUMNS",
    "FOLD_TARGET",
    "MU",
    "Q_STAR",
    "SETTINGS",
    "SIGMA_STAR",
    "SUITE",
    "column_errors",
    "columns_for_accuracy",
    "columns_in_q",
    "columns_in_sigma",
    "continuation_errors",
    "continuation_work_precision",
    "fastest_method",
    "format_tables",
    "leading_growth_rate",
    "leading_growth_rate_roots",
    "neutral_benchmark",
    "sigma_ref",
    "trace",
]

#: required accuracy of the fold's coordinates (q*, sigma*) (the issue)
FOLD_TARGET = 1e-10

#: the problem: scaled mass and viscous friction (Fig. 3), fr_inv = 0
MU, ALPHA_V = 2.28, 0.5
#: the fold of the neutral curve, closed form
Q_STAR = -1.0 + math.sqrt(1.0 - 1.0 / MU)
SIGMA_STAR = 2.0 * (MU - math.sqrt(MU * (MU - 1.0)))
#: (max_step, max_angle) settings; the first is the engine's default
SETTINGS: tuple[tuple[float, float], ...] = ((0.05, 0.1), (0.1, 0.2), (0.2, 0.3), (0.4, 0.6))
#: column counts of the baseline's work-precision line
COLUMNS: tuple[int, ...] = (10, 15, 25, 50, 100, 200, 400)
DEFAULT_SETTING = (0.05, 0.1)
#: brentq tolerances of the columns (the continuation's points sit at the rounding floor)
XTOL, RTOL = 1e-14, 1e-15


def sigma_ref(q: np.ndarray) -> np.ndarray:
    """The neutral curve at ``fr_inv = 0``, ``sigma = (1 - mu q^2) / (1 + q)`` (closed form)."""
    q = np.asarray(q, dtype=float)
    return (1.0 - MU * q * q) / (1.0 + q)


def _check_setting(max_step: float, max_angle: float) -> None:
    if not (isinstance(max_step, (int, float)) and 0 < max_step <= 1):
        raise ValueError(f"max_step = {max_step!r} must lie in (0, 1] (arclength in the scaled ranges)")
    if not (isinstance(max_angle, (int, float)) and 0 < max_angle < math.pi / 2):
        raise ValueError(f"max_angle = {max_angle!r} must lie in (0, pi/2) radians")


def trace(max_step: float, max_angle: float, compiled: bool = True) -> Any:
    """The whole ``continuation.neutral_curve`` call for the problem at one step setting.

    Parameters
    ----------
    max_step : float
        Largest continuation step, in (0, 1] (arclength in the ranges scaled to 1).
    max_angle : float
        Largest turn of the tangent per step, in (0, pi/2) radians.
    compiled : bool
        False forces the engine's Python path.

    Returns
    -------
    xarray.Dataset
        The traced curve (:func:`continuation.neutral_curve`).
    """
    from stability.linear.neutral_curves import neutral_curve

    _check_setting(max_step, max_angle)
    return neutral_curve(
        "sliding",
        "q",
        "sigma",
        fixed=dict(fr_inv=0.0, alpha_v=ALPHA_V, mu=MU),
        max_step=max_step,
        max_angle=max_angle,
        compiled=compiled,
    )


def continuation_errors(ds: Any, samples: int = 32) -> dict[str, float]:
    """Errors of a traced curve against the closed form.

    Parameters
    ----------
    ds : xarray.Dataset
        From :func:`trace`.
    samples : int
        Dense-output samples per step.

    Returns
    -------
    dict
        ``points``; ``point``: largest ``|sigma - sigma_ref(q)|`` at the traced points;
        ``fold``: ``max(|q - q*|, |sigma - sigma*|)`` of the located fold (inf if none);
        ``polyline``: the chords' error (20 samples per step); ``dense``: the largest
        ``|sigma - sigma_ref(q)|`` over the dense output; ``check``: the largest LAPACK growth
        rate of the neutral mode (away from the corner ``1 - mu q^2 <= 1e-6``); ``upper``: the
        points above ``sigma = 0.86``, where columns at fixed sigma cross the curve twice.
    """
    from continuation.dense import dense

    q, s = ds.q.values, ds.sigma.values
    kinds = ds.kind.values
    folds = np.nonzero(kinds == "fold")[0]
    fold = max(abs(float(q[folds[0]]) - Q_STAR), abs(float(s[folds[0]]) - SIGMA_STAR)) if folds.size else math.inf
    d = dense(ds, samples)
    qq = np.concatenate([np.linspace(a, b, 20) for a, b in itertools.pairwise(q)])
    order = np.argsort(q)
    inner = (1.0 - MU * q * q) > 1e-6
    return {
        "points": int(ds.sizes["point"]),
        "point": float(np.max(np.abs(s - sigma_ref(q)))),
        "fold": fold,
        "polyline": float(np.max(np.abs(np.interp(qq, q[order], s[order]) - sigma_ref(qq)))),
        "dense": float(np.max(np.abs(d.sigma.values - sigma_ref(d.q.values)))),
        "check": float(np.max(np.abs(ds.check_growth_rate.values[inner]))),
        "upper": int(np.count_nonzero(s > 0.86)),
    }


def fastest_method() -> str:
    """The fastest :func:`stability.spectrum` method for one point of the problem, by timing
    (the baseline [A] gets the best the package offers): each method's mean over a block of 50
    consecutive calls after one warm-up call (:func:`~suites.timing.best_times`, one
    sample of ``number = 50``), the methods one after the other."""
    from stability.linear.spectra import spectrum

    times, _ = best_times(
        {
            m: lambda m=m: spectrum("sliding", q=0.1, fr_inv=0.0, sigma=0.5, alpha_v=ALPHA_V, mu=MU, method=m)
            for m in ("kernel", "polynomial", "lapack")
        },
        1,
        number=50,
        warmup="round",
        keep=False,
    )
    return min(times, key=times.get)


def leading_growth_rate(q: float, sigma: float, method: str = "kernel") -> float:
    """[A]: the largest ``Re s`` of the sliding model at ``fr_inv = 0`` over the modes that are
    not structurally zero, from :func:`stability.spectrum` (the structural zero eigenvalue,
    exactly 0 from the kernel or ~1e-17 from LAPACK, is the one of smallest modulus: dropped)."""
    from stability.linear.spectra import spectrum

    ev = spectrum("sliding", q=q, fr_inv=0.0, sigma=sigma, alpha_v=ALPHA_V, mu=MU, method=method).eigenvalues
    return float(np.delete(ev, np.argmin(np.abs(ev))).real.max())


def leading_growth_rate_roots(q: float, sigma: float) -> float:
    """[B]: the same from ``numpy.roots`` of eq. (11)'s coefficients (``c0 = 0`` at
    ``fr_inv = 0`` dropped)."""
    from stability.models import get_model

    c = get_model("sliding").coefficients(q=q, fr_inv=0.0, sigma=sigma, alpha_v=ALPHA_V, mu=MU)
    return float(np.roots(c[:3]).real.max())


def columns_in_sigma(n: int, leading: Callable[[float, float], float] = leading_growth_rate) -> np.ndarray:
    """The brentq-per-column baseline: ``(q_j, sigma_j)`` on the curve for ``n`` columns.

    Parameters
    ----------
    n : int
        Columns ``q_j``, evenly spaced inside ``|q| < 1/sqrt(mu)`` (at least 4, for the spline).
    leading : callable
        ``leading(q, sigma)``, the leading growth rate ([A] or [B]).

    Returns
    -------
    numpy.ndarray, shape (m, 2)
        The columns where the leading growth rate changes sign, with the root in sigma.
    """
    from scipy.optimize import brentq

    if not (isinstance(n, (int, np.integer)) and n >= 4):
        raise ValueError(f"n = {n!r} columns: need an integer >= 4 (a cubic spline through them)")
    b = 1.0 / math.sqrt(MU)
    out = []
    for q in np.linspace(-b, b, n + 2)[1:-1]:
        q = float(q)
        lo, hi = 1e-9, 2.0 * (1.0 - MU * q * q) * (1.0 - 1e-12)
        if leading(q, lo) * leading(q, hi) < 0:
            out.append((q, brentq(lambda s: leading(q, s), lo, hi, xtol=XTOL, rtol=RTOL)))
    return np.array(out)


def columns_in_q(n: int, leading: Callable[[float, float], float] = leading_growth_rate) -> tuple[int, int]:
    """Columns at fixed sigma in ``[0.05, 1.95]``, brentq in q over ``|q| <= sqrt((1 - sigma/2)/mu)``.

    Returns
    -------
    tuple of int
        ``(crossings, found)``: how often the ``n`` columns cross the curve (closed form,
        ``mu q^2 + sigma q + sigma - 1 = 0``) and how many roots brentq finds (one per column
        whose ends differ in sign; a column crossing twice has the same sign at both ends).
    """
    from scipy.optimize import brentq

    found, crossings = 0, 0
    for s in np.linspace(0.05, 1.95, n):
        s = float(s)
        b = math.sqrt((1.0 - s / 2.0) / MU) * (1.0 - 1e-12)
        r = np.roots([MU, s, s - 1.0])
        r = r[np.isreal(r)].real
        crossings += int(np.sum(np.abs(r) <= b))
        if leading(-b, s) * leading(b, s) < 0:
            brentq(lambda q: leading(q, s), -b, b, xtol=XTOL)
            found += 1
    return crossings, found


def column_errors(pts: np.ndarray) -> dict[str, float]:
    """Errors of the columns' curve (cubic spline) and fold (the spline's maximum).

    Returns
    -------
    dict
        ``point`` (at the column roots), ``linear`` (the polyline), ``cubic`` (the spline;
        both 20 samples per interval) and ``fold`` (``max(|q - q*|, |sigma - sigma*|)``).
    """
    from scipy.interpolate import CubicSpline

    q, s = pts[:, 0], pts[:, 1]
    qq = np.linspace(q[0], q[-1], 20 * len(q))
    spline = CubicSpline(q, s)
    crit = spline.derivative().roots(extrapolate=False)
    k = int(np.argmax(spline(crit)))
    return {
        "point": float(np.max(np.abs(s - sigma_ref(q)))),
        "linear": float(np.max(np.abs(np.interp(qq, q, s) - sigma_ref(qq)))),
        "cubic": float(np.max(np.abs(spline(qq) - sigma_ref(qq)))),
        "fold": max(abs(float(crit[k]) - Q_STAR), abs(float(spline(crit[k])) - SIGMA_STAR)),
    }


def columns_for_accuracy(
    target: float, leading: Callable[[float, float], float] = leading_growth_rate_roots, n_max: int = 2000
) -> int:
    """The smallest column count whose spline error is at most ``target``.

    Bisection for the first ``N`` with ``cubic <= target`` (the error falls like ``N^-4``),
    then a downward scan while smaller counts also qualify (the error is not exactly monotone
    in ``N``). The column roots of [A] and [B] agree to rounding, so the cheaper [B] decides.

    Raises
    ------
    ValueError
        If even ``n_max`` columns do not reach ``target``.
    """
    err: dict[int, float] = {}

    def e(n: int) -> float:
        if n not in err:
            err[n] = column_errors(columns_in_sigma(n, leading))["cubic"]
        return err[n]

    if e(n_max) > target:
        raise ValueError(f"{n_max} columns do not reach the curve error {target:.2g}")
    lo, hi = 4, n_max
    while hi - lo > 1:
        mid = (lo + hi) // 2
        lo, hi = (lo, mid) if e(mid) <= target else (mid, hi)
    n = hi
    while n > 4 and e(n - 1) <= target:
        n -= 1
    return n


@execution.using("compiled")  # the compiled paths are measured (docs/performance.md)
def neutral_benchmark(
    repeat: int = 7,
    settings: tuple[tuple[float, float], ...] = SETTINGS,
    columns: tuple[int, ...] = COLUMNS,
    python_path: bool = True,
    equal_accuracy: bool = True,
    turning_back: int = 200,
    method: str | None = None,
    min_time: float = 0.5,
) -> dict[str, Any]:
    """The whole comparison in one run.

    Parameters
    ----------
    repeat : int
        Timed runs per configuration (the minimum is kept), after one warm-up call each.
    settings : tuple of (max_step, max_angle)
        Continuation settings.
    columns : tuple of int
        Column counts of the baselines' work-precision line.
    python_path : bool
        Also time the engine's Python path (``compiled=False``) at the first setting.
    equal_accuracy : bool
        For each setting, find and time the smallest column count of equal curve accuracy.
    turning_back : int
        Columns at fixed sigma for the turning-back count (0: skip).
    method : str, optional
        :func:`stability.spectrum` method of [A] (default: :func:`fastest_method`).
    min_time : float
        Seconds of timed runs per configuration, at least
        (:func:`~suites.timing.best_times`).

    Returns
    -------
    dict
        ``method``, ``repeat``; ``continuation``: ``{setting: errors + time}``; ``python``:
        the same for the Python path (or None); ``columns``: ``{N: errors + time_A, time_B}``;
        ``equal``: ``{setting: errors + {"N", "time_A", "time_B", "found"}}``; ``turning_back``:
        ``(crossings, found)`` or None.
    """
    for st in settings:
        _check_setting(*st)
    method = fastest_method() if method is None else method

    def lead_a(q: float, s: float) -> float:
        return leading_growth_rate(q, s, method)

    fns: dict[Hashable, Callable[[], Any]] = {}
    for st in settings:
        fns[("cont", st)] = lambda st=st: trace(*st)
    if python_path:
        fns[("python", settings[0])] = lambda: trace(*settings[0], compiled=False)
    for n in columns:
        fns[("A", n)] = lambda n=n: columns_in_sigma(n, lead_a)
        fns[("B", n)] = lambda n=n: columns_in_sigma(n, leading_growth_rate_roots)
    equal_n: dict[tuple[float, float], int] = {}
    if equal_accuracy:
        # the accuracy of a setting does not depend on timing: one untimed call decides N
        for st in settings:
            target = continuation_errors(trace(*st))["dense"]
            try:
                equal_n[st] = n = columns_for_accuracy(target)
            except ValueError:
                continue
            fns.setdefault(("A", n), lambda n=n: columns_in_sigma(n, lead_a))
            fns.setdefault(("B", n), lambda n=n: columns_in_sigma(n, leading_growth_rate_roots))
    best, res = best_times(fns, repeat, min_time)

    out: dict[str, Any] = {
        "method": method,
        "repeat": repeat,
        "min_time": min_time,
        "continuation": {},
        "python": None,
        "columns": {},
        "equal": {},
        "turning_back": None,
    }
    for st in settings:
        out["continuation"][st] = dict(continuation_errors(res[("cont", st)]), time=best[("cont", st)])
    if python_path:
        out["python"] = dict(continuation_errors(res[("python", settings[0])]), time=best[("python", settings[0])])
    for n in columns:
        out["columns"][n] = dict(
            column_errors(res[("A", n)]), time_A=best[("A", n)], time_B=best[("B", n)], found=len(res[("A", n)])
        )
    for st, n in equal_n.items():
        out["equal"][st] = dict(
            column_errors(res[("A", n)]), N=n, time_A=best[("A", n)], time_B=best[("B", n)], found=len(res[("A", n)])
        )
    if turning_back:
        out["turning_back"] = columns_in_q(turning_back, lead_a)
    return out


def format_tables(b: dict[str, Any]) -> str:
    """The tables of :func:`neutral_benchmark`: continuation, columns, equal accuracy, turning back."""
    ms = 1e3
    lines = [
        f"sliding model, (q, sigma) plane, fr_inv = 0, alpha_v = {ALPHA_V}, mu = {MU}",
        f"wall time: minimum over {b['repeat']} rounds of consecutive calls, >= {b['min_time']:g} s per "
        "configuration, each block after a warm-up call",
        f"[A]: stability.spectrum(method={b['method']!r}), [B]: numpy.roots",
        "",
        "continuation (whole neutral_curve call)",
        f"{'max_step':>8} {'max_angle':>9} {'points':>6} {'time ms':>8} {'point err':>9} {'fold err':>9} "
        f"{'polyline':>9} {'dense err':>9} {'|check|':>8}",
    ]

    def row(st: tuple[float, float], e: dict[str, float], note: str = "") -> str:
        return (
            f"{st[0]:>8} {st[1]:>9} {e['points']:>6} {e['time'] * ms:>8.2f} {e['point']:>9.1e} "
            f"{e['fold']:>9.1e} {e['polyline']:>9.1e} {e['dense']:>9.1e} {e['check']:>8.1e}{note}"
        )

    for st, e in b["continuation"].items():
        lines.append(row(st, e))
    if b["python"] is not None:
        lines.append(row(next(iter(b["continuation"])), b["python"], "  (Python path, compiled=False)"))
    lines += [
        "",
        f"columns (brentq per column, xtol = {XTOL:g})",
        f"{'N':>5} {'found':>5} {'A ms':>8} {'B ms':>8} {'point err':>9} {'fold err':>9} {'linear':>9} {'cubic':>9}",
    ]
    for n, e in b["columns"].items():
        lines.append(
            f"{n:>5} {e['found']:>5} {e['time_A'] * ms:>8.1f} {e['time_B'] * ms:>8.1f} "
            f"{e['point']:>9.1e} {e['fold']:>9.1e} {e['linear']:>9.1e} {e['cubic']:>9.1e}"
        )
    if b["equal"]:
        lines += [
            "",
            "equal accuracy of the whole curve (N: the smallest column count whose cubic spline is "
            "as accurate as the continuation's dense output)",
            f"{'max_step':>8} {'dense err':>9} {'cont ms':>8} {'N':>5} {'spline':>9} {'A ms':>8} "
            f"{'A/cont':>7} {'B ms':>8} {'B/cont':>7}",
        ]
        for st, q in b["equal"].items():
            c = b["continuation"][st]
            lines.append(
                f"{st[0]:>8} {c['dense']:>9.1e} {c['time'] * ms:>8.2f} {q['N']:>5} {q['cubic']:>9.1e} "
                f"{q['time_A'] * ms:>8.1f} {q['time_A'] / c['time']:>7.1f} {q['time_B'] * ms:>8.1f} "
                f"{q['time_B'] / c['time']:>7.1f}"
            )
    if b["turning_back"] is not None:
        crossings, found = b["turning_back"]
        c = next(iter(b["continuation"].values()))
        lines += [
            "",
            f"turning back: columns at fixed sigma in [0.05, 1.95] cross the curve {crossings} times; "
            f"brentq per column finds {found} ({crossings - found} missed: the columns with two crossings, "
            f"0.86 < sigma < {SIGMA_STAR:.4f}); continuation (first setting) traces that part with "
            f"{c['upper']} points and the fold",
        ]
    return "\n".join(lines)


@execution.using("compiled")  # the compiled paths are measured (docs/performance.md)
def continuation_work_precision(
    repeat: int = 5,
    quick: bool = False,
    settings: tuple[tuple[float, float], ...] = SETTINGS,
    columns: tuple[int, ...] = COLUMNS,
    min_time: float = 0.5,
    equal_accuracy: bool = True,
) -> list[WorkPrecision]:
    """Work-precision points of the continuation settings and of the brentq baseline [A]
    (:func:`neutral_benchmark`, without the Python path and the turning-back count).

    With ``equal_accuracy`` the baseline also has, for each setting, the smallest column count
    as accurate as that setting's dense output, so that the ratio at equal curve accuracy
    ``python benchmarks/run.py`` prints is the one of ``benchmarks/bench_neutral.py`` (the same N, the same
    timing), not the one of the next coarser or finer listed count.

    Parameters
    ----------
    repeat : int
        Timed runs per configuration (the minimum is kept), after one warm-up.
    quick : bool
        Fewer repeats (at most 2), a shorter time budget and columns only up to 100.
    settings : tuple of (max_step, max_angle)
        Continuation settings.
    columns : tuple of int
        Column counts of the baseline.
    min_time : float
        Seconds of timed runs per configuration, at least
        (:func:`~suites.timing.best_times`; quick: at most 0.1).
    equal_accuracy : bool
        Add the equal-accuracy column counts (not when ``quick``).

    Returns
    -------
    list of WorkPrecision
        ``error``: the fold error; ``extra["curve_error"]``: the curve's error (dense output
        or spline); ``extra["points"]``: traced points or columns found.
    """
    if quick:
        repeat = min(repeat, 2)
        min_time = min(min_time, 0.1)
        columns = tuple(n for n in columns if n <= 100)
    b = neutral_benchmark(
        repeat,
        settings,
        columns,
        python_path=False,
        equal_accuracy=equal_accuracy and not quick,
        turning_back=0,
        min_time=min_time,
    )
    results = []
    for st, e in b["continuation"].items():
        results.append(
            WorkPrecision(
                "continuation",
                e["time"],
                e["fold"],
                1,
                default=st == DEFAULT_SETTING,
                series="continuation",
                setting=f"max_step {st[0]:g}, max_angle {st[1]:g}",
                note="continuation.neutral_curve, the whole call (start, both directions, fold, edges)",
                extra={
                    "curve_error": e["dense"],
                    "points": e["points"],
                    "point_error": e["point"],
                    "max_step": st[0],
                    "max_angle": st[1],
                },
            )
        )
    cols = dict(b["columns"])
    for e in b["equal"].values():
        cols.setdefault(e["N"], e)
    for n, e in sorted(cols.items()):
        results.append(
            WorkPrecision(
                "brentq per column",
                e["time_A"],
                e["fold"],
                1,
                baseline=True,
                series="brentq per column",
                setting=f"N = {n}",
                note=f"scipy.optimize.brentq in sigma per column q_j (xtol 1e-14) on stability.spectrum "
                f"(method {b['method']!r}), cubic spline, fold its maximum",
                extra={"curve_error": e["cubic"], "points": e["found"], "point_error": e["point"], "columns": n},
            )
        )
    return results


#: the suite: ``python benchmarks/run.py --suite continuation``
SUITE = Suite(
    "continuation",
    continuation_work_precision,
    "neutral curve of the sliding model in (q, sigma), fr_inv = 0, alpha_v = 0.5, mu = 2.28: "
    "continuation vs brentq per column",
    (
        Panel(
            "error of the located fold (q*, sigma*) vs closed form",
            "wall time per traced curve [s]",
            target=FOLD_TARGET,
        ),
        Panel(
            "largest error of the curve (dense output / spline) vs closed form",
            "wall time per traced curve [s]",
            x="curve_error",
            title="the curve between the points: Hermite dense output vs cubic spline",
        ),
    ),
    unit="curve",
    compare_at=("error", "curve_error"),
    quick={"quick": True},
)
