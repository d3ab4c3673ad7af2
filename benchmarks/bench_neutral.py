"""Benchmark: neutral curve by continuation vs a brentq per grid column, at equal accuracy.

Problem: the sliding model's neutral curve in the (q, sigma) plane at fr_inv = 0, alpha_v = 0.5,
mu = 2.28, over the whole physical domain. Reference (closed form, tests/test_neutral.py):
sigma = (1 - mu q^2)/(1 + q), fold at q* = -1 + sqrt(1 - 1/mu), sigma* = 2 (mu - sqrt(mu (mu - 1))).

* continuation: the whole ``continuation.neutral_curve`` call (start points from a 25 x 25 atlas,
  both directions, fold and domain edges located exactly, the xarray dataset and the LAPACK
  check of every point included), at several step settings (``max_step``, ``max_angle``); the
  curve between points is its dense output ``continuation.dense`` (cubic Hermite with the
  stored tangents). The corrector is the compiled one (numba, continuation.neutral_compiled;
  compiled once per machine and cached on disk, loaded by the warm-up call below, so neither
  compiling nor loading is timed); the engine's Python path (``compiled=False``) is timed too
  at the default steps, for reference;
* columns: for N columns q_j, ``scipy.optimize.brentq`` in sigma on [1e-9, 2 (1 - mu q_j^2)] on
  the leading growth rate (the largest Re s over the modes that are not structurally zero),
  with xtol = 1e-14 (the same pointwise accuracy as the continuation's points); the curve
  between columns is a cubic spline through the column roots (not-a-knot; far better than
  linear interpolation, also reported); the fold is the spline's maximum. Two implementations
  of the leading growth rate: ``stability.spectrum`` with whichever of its methods is fastest
  for one point on this machine (picked at start-up), and ``numpy.roots`` on the model's
  coefficients (a hand-written shortcut, faster still);
* accuracy of a curve: the largest |sigma - sigma_ref(q)| over its dense samples (Hermite: 32
  per step over the whole curve; spline: 20 per column interval, over the columns' span only,
  which favours the columns: they miss the ends);
* equal accuracy: for each continuation setting, the smallest N (from the list below) whose
  spline error is at most the continuation's dense error, and the time ratio;
* turning back: the same curve seen by columns at fixed sigma (brentq in q over the domain):
  where a column crosses the curve twice the leading growth rate has the same sign at both
  ends and the column finds nothing.

Timings: CPU time of the process (``time.process_time``: on the shared machine wall-clock
times vary by 2-3x with the other jobs' load, CPU time far less); every configuration is run in
the same process, interleaved (continuation ``REPEAT`` times, columns 5 times), after a warm-up
call of each, and the median is reported. The column time is linear in N; the ratio is also given with the
least-squares line through all the column medians (``fit``), which a single noisy median
cannot move much.

Run: ``python benchmarks/bench_neutral.py`` (prints tables; takes about a minute).
"""

from __future__ import annotations

import math
import statistics
import time

import numpy as np
from scipy.interpolate import CubicSpline
from scipy.optimize import brentq

import continuation
from stability import spectrum
from stability.models import get_model

MU, ALPHA_V = 2.28, 0.5
Q_STAR = -1 + math.sqrt(1 - 1 / MU)
S_STAR = 2 * (MU - math.sqrt(MU * (MU - 1)))
REPEAT = 7
SETTINGS = [(0.05, 0.1), (0.1, 0.2), (0.2, 0.3), (0.4, 0.6)]  # (max_step, max_angle)
COLUMNS = [10, 15, 20, 25, 30, 40, 50, 60, 80, 100, 125, 150, 200, 300, 400]
SLIDING = get_model("sliding")


def sigma_ref(q):
    return (1 - MU * q * q) / (1 + q)


def _fastest_method() -> str:
    best = None
    for method in ("kernel", "polynomial", "lapack"):
        spectrum("sliding", q=0.1, fr_inv=0.0, sigma=0.5, alpha_v=ALPHA_V, mu=MU, method=method)
        t0 = time.process_time()
        for _ in range(50):
            spectrum("sliding", q=0.1, fr_inv=0.0, sigma=0.5, alpha_v=ALPHA_V, mu=MU, method=method)
        t = (time.process_time() - t0) / 50
        if best is None or t < best[1]:
            best = (method, t)
    return best[0]


METHOD = _fastest_method()


def leading_spectrum(q: float, sigma: float) -> float:
    """Largest growth rate over the modes that are not structurally zero (fr_inv = 0)."""
    ev = spectrum("sliding", q=q, fr_inv=0.0, sigma=sigma, alpha_v=ALPHA_V, mu=MU,
                  method=METHOD).eigenvalues
    # the structural zero eigenvalue (c0 = 0 at fr_inv = 0) is exactly 0 or, from LAPACK,
    # ~1e-17: drop the eigenvalue of smallest modulus (the others are O(1) away from 0 here)
    return float(np.delete(ev, np.argmin(np.abs(ev))).real.max())


def leading_roots(q: float, sigma: float) -> float:
    """The same from ``numpy.roots`` of eq. (11)'s coefficients (c0 = 0 at fr_inv = 0 dropped)."""
    c = SLIDING.coefficients(q=q, fr_inv=0.0, sigma=sigma, alpha_v=ALPHA_V, mu=MU)
    return float(np.roots(c[:3]).real.max())


def columns_in_sigma(n: int, leading):
    b = 1 / math.sqrt(MU)
    qs = np.linspace(-b, b, n + 2)[1:-1]
    out = []
    for q in qs:
        lo, hi = 1e-9, 2 * (1 - MU * q * q) * (1 - 1e-12)
        flo, fhi = leading(q, lo), leading(q, hi)
        if flo * fhi < 0:
            out.append((q, brentq(lambda s: leading(q, s), lo, hi, xtol=1e-14, rtol=1e-15)))
    return np.array(out)


def columns_in_q(n: int):
    """Columns at fixed sigma, brentq in q over |q| <= sqrt((1 - sigma/2)/mu)."""
    sig = np.linspace(0.05, 1.95, n)
    found, crossings = 0, 0
    for s in sig:
        b = math.sqrt((1 - s / 2) / MU) * (1 - 1e-12)
        # closed form: mu q^2 + sigma q + sigma - 1 = 0, roots inside the column
        r = np.roots([MU, s, s - 1])
        r = r[np.isreal(r)].real
        crossings += int(np.sum(np.abs(r) <= b))
        f = lambda q: leading_spectrum(q, s)  # noqa: E731
        if f(-b) * f(b) < 0:
            brentq(f, -b, b, xtol=1e-14)
            found += 1
    return crossings, found


def timed(fn):
    """``(CPU seconds of the process, result)``: ``time.process_time`` counts every thread of
    the process (nothing run on a thread pool is hidden) and, unlike the wall clock, not the
    time the process waits for the shared machine's other jobs."""
    t0 = time.process_time()
    res = fn()
    return time.process_time() - t0, res


def trace(max_step: float, max_angle: float, compiled: bool = True):
    return continuation.neutral_curve("sliding", "q", "sigma", fixed=dict(fr_inv=0.0, alpha_v=ALPHA_V, mu=MU),
                                      max_step=max_step, max_angle=max_angle, compiled=compiled)


def continuation_errors(ds) -> dict[str, float]:
    q, s = ds.q.values, ds.sigma.values
    fold = ds.where(ds.kind == "fold", drop=True)
    d = continuation.dense(ds, 32)
    qq = np.concatenate([np.linspace(a, b, 20) for a, b in zip(q[:-1], q[1:])])
    order = np.argsort(q)
    inner = (1 - MU * q * q) > 1e-6
    return {
        "points": ds.sizes["point"],
        "point": float(np.max(np.abs(s - sigma_ref(q)))),
        "fold": max(abs(float(fold.q[0]) - Q_STAR), abs(float(fold.sigma[0]) - S_STAR)),
        "polyline": float(np.max(np.abs(np.interp(qq, q[order], s[order]) - sigma_ref(qq)))),
        "dense": float(np.max(np.abs(d.sigma.values - sigma_ref(d.q.values)))),
        "check": float(np.max(np.abs(ds.check_growth_rate.values[inner]))),
    }


def column_errors(pts: np.ndarray) -> dict[str, float]:
    q, s = pts[:, 0], pts[:, 1]
    qq = np.linspace(q[0], q[-1], 20 * len(q))
    spline = CubicSpline(q, s)
    crit = spline.derivative().roots(extrapolate=False)
    k = int(np.argmax(spline(crit)))
    return {
        "point": float(np.max(np.abs(s - sigma_ref(q)))),
        "linear": float(np.max(np.abs(np.interp(qq, q, s) - sigma_ref(qq)))),
        "cubic": float(np.max(np.abs(spline(qq) - sigma_ref(qq)))),
        "fold": max(abs(crit[k] - Q_STAR), abs(float(spline(crit[k])) - S_STAR)),
    }


def main() -> None:
    print(f"sliding model, (q, sigma) plane, fr_inv = 0, alpha_v = {ALPHA_V}, mu = {MU}; CPU time "
          f"(process_time), median of {REPEAT} runs; columns' leading growth rate: stability.spectrum(method="
          f"{METHOD!r}) [A] or numpy.roots [B]")
    trace(*SETTINGS[0])  # warm-up (imports; numba's compiled code, from its cache or compiled)
    trace(*SETTINGS[0], compiled=False)
    columns_in_sigma(5, leading_spectrum)
    columns_in_sigma(5, leading_roots)
    times: dict = {}
    results: dict = {}
    for rep in range(REPEAT):
        for st in SETTINGS:
            t, ds = timed(lambda: trace(*st))
            times.setdefault(("cont", st), []).append(t)
            results[("cont", st)] = ds
        t, ds = timed(lambda: trace(*SETTINGS[0], compiled=False))
        times.setdefault(("python", SETTINGS[0]), []).append(t)
        results[("python", SETTINGS[0])] = ds
        if rep < 5:  # the columns are slow: 5 runs
            for n in COLUMNS:
                for name, fn in (("A", leading_spectrum), ("B", leading_roots)):
                    t, pts = timed(lambda: columns_in_sigma(n, fn))
                    times.setdefault((name, n), []).append(t)
                    results[(name, n)] = pts
    med = {k: statistics.median(v) for k, v in times.items()}

    print("\ncontinuation (whole neutral_curve call)")
    print(f"{'max_step':>8} {'max_angle':>9} {'points':>6} {'time ms':>8} {'point err':>9} {'fold err':>9} "
          f"{'polyline':>9} {'dense err':>9} {'|check|':>8}")
    cont = {}
    for st in SETTINGS:
        e = continuation_errors(results[("cont", st)])
        cont[st] = e
        print(f"{st[0]:>8} {st[1]:>9} {e['points']:>6} {med[('cont', st)] * 1e3:>8.1f} {e['point']:>9.1e} "
              f"{e['fold']:>9.1e} {e['polyline']:>9.1e} {e['dense']:>9.1e} {e['check']:>8.1e}")
    st = SETTINGS[0]
    e = continuation_errors(results[("python", st)])
    print(f"{st[0]:>8} {st[1]:>9} {e['points']:>6} {med[('python', st)] * 1e3:>8.1f} {e['point']:>9.1e} "
          f"{e['fold']:>9.1e} {e['polyline']:>9.1e} {e['dense']:>9.1e} {e['check']:>8.1e}  "
          "(Python path, compiled=False)")

    print("\ncolumns (brentq per column, xtol = 1e-14)")
    print(f"{'N':>5} {'found':>5} {'A ms':>8} {'B ms':>8} {'point err':>9} {'fold err':>9} "
          f"{'linear':>9} {'cubic':>9}")
    cols = {}
    for n in COLUMNS:
        e = column_errors(results[("A", n)])
        cols[n] = e
        print(f"{n:>5} {len(results[('A', n)]):>5} {med[('A', n)] * 1e3:>8.1f} {med[('B', n)] * 1e3:>8.1f} "
              f"{e['point']:>9.1e} {e['fold']:>9.1e} {e['linear']:>9.1e} {e['cubic']:>9.1e}")

    ns = np.array(COLUMNS, float)
    fit = {name: np.polyfit(ns, [med[(name, n)] for n in COLUMNS], 1) for name in ("A", "B")}
    print("\nequal accuracy of the whole curve (columns: cubic spline; continuation: dense output)")
    print(f"{'max_step':>8} {'dense err':>9} {'cont ms':>8} {'N':>5} {'A ms':>8} {'A/cont':>7} "
          f"{'fit':>5} {'B ms':>8} {'B/cont':>7} {'fit':>5}")
    for st in SETTINGS:
        target = cont[st]["dense"]
        ok = [n for n in COLUMNS if cols[n]["cubic"] <= target]
        tc = med[("cont", st)]
        if not ok:
            print(f"{st[0]:>8} {target:>9.1e} {tc * 1e3:>8.1f}   > {COLUMNS[-1]} columns needed")
            continue
        n = ok[0]
        fa, fb = np.polyval(fit["A"], n) / tc, np.polyval(fit["B"], n) / tc
        print(f"{st[0]:>8} {target:>9.1e} {tc * 1e3:>8.1f} {n:>5} {med[('A', n)] * 1e3:>8.1f} "
              f"{med[('A', n)] / tc:>7.1f} {fa:>5.1f} {med[('B', n)] * 1e3:>8.1f} "
              f"{med[('B', n)] / tc:>7.1f} {fb:>5.1f}")

    crossings, found = columns_in_q(200)
    ds = results[("cont", SETTINGS[0])]
    upper = ds.where(ds.sigma > 0.86, drop=True)
    print(f"\nturning back: 200 columns at fixed sigma in [0.05, 1.95] cross the curve {crossings} times; "
          f"brentq per column finds {found} ({crossings - found} missed: the columns with two crossings, "
          f"0.86 < sigma < {S_STAR:.4f}); continuation (default steps) traces that part with "
          f"{upper.sizes['point']} points and the fold")


if __name__ == "__main__":
    main()
