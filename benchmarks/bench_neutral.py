"""Benchmark: neutral curve by continuation vs a brentq per grid column.

Problem: the sliding model's neutral curve in the (q, sigma) plane at fr_inv = 0, alpha_v = 0.5,
mu = 2.28, over the whole physical domain. Reference (closed form, tests/test_neutral.py):
sigma = (1 - mu q^2)/(1 + q), fold at q* = -1 + sqrt(1 - 1/mu), sigma* = 2 (mu - sqrt(mu (mu - 1))).

* continuation: ``continuation.neutral_curve`` (start points from a 25 x 25 atlas, both
  directions, fold located exactly, domain edges located exactly);
* columns: for N columns q_j, ``scipy.optimize.brentq`` in sigma on [1e-9, 2 (1 - mu q_j^2)]
  on the leading growth rate (the largest Re s over the modes that are not structurally zero),
  with xtol = 1e-14 (the same pointwise accuracy); the fold is estimated by the largest sample
  and by a parabola through the three largest;
* turning back: the same curve seen by columns at fixed sigma (brentq in q over the domain):
  where a column crosses the curve twice, the leading growth rate has the same sign at both
  ends and the column finds nothing.

Run: ``python benchmarks/bench_neutral.py`` (prints a table; takes about a minute).
"""

from __future__ import annotations

import math
import time

import numpy as np
from scipy.optimize import brentq

import continuation
from stability import spectrum

MU, ALPHA_V = 2.28, 0.5
Q_STAR = -1 + math.sqrt(1 - 1 / MU)
S_STAR = 2 * (MU - math.sqrt(MU * (MU - 1)))


def sigma_ref(q):
    return (1 - MU * q * q) / (1 + q)


def leading(q: float, sigma: float) -> float:
    """Largest growth rate over the modes that are not structurally zero (fr_inv = 0)."""
    sp = spectrum("sliding", q=q, fr_inv=0.0, sigma=sigma, alpha_v=ALPHA_V, mu=MU)
    ev = sp.eigenvalues[~((sp.eigenvalues == 0))]
    return float(ev.real.max())


def columns_in_sigma(n: int):
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
        f = lambda q: leading(q, s)  # noqa: E731
        if f(-b) * f(b) < 0:
            brentq(f, -b, b, xtol=1e-14)
            found += 1
    return crossings, found


def best_time(fn, repeat=3):
    t = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        res = fn()
        t.append(time.perf_counter() - t0)
    return min(t), res


def main() -> None:
    print(f"sliding model, (q, sigma) plane, fr_inv = 0, alpha_v = {ALPHA_V}, mu = {MU}")
    t_c, ds = best_time(lambda: continuation.neutral_curve(
        "sliding", "q", "sigma", fixed=dict(fr_inv=0.0, alpha_v=ALPHA_V, mu=MU)))
    q, s = ds.q.values, ds.sigma.values
    fold = ds.where(ds.kind == "fold", drop=True)
    err_pts = np.max(np.abs(s - sigma_ref(q)))
    err_fold = max(abs(float(fold.q[0]) - Q_STAR), abs(float(fold.sigma[0]) - S_STAR))
    # chord error of the polyline (the curve between points), against the closed form
    qq = np.concatenate([np.linspace(a, b, 20) for a, b in zip(q[:-1], q[1:])])
    chord = np.max(np.abs(np.interp(qq, q[::-1], s[::-1]) - sigma_ref(qq))) if q[0] > q[-1] else np.nan
    print(f"continuation: {t_c * 1e3:8.1f} ms, {ds.sizes['point']} points, point error {err_pts:.1e}, "
          f"fold error {err_fold:.1e}, polyline chord error {chord:.1e}, "
          f"max |check growth rate| {np.max(np.abs(ds.check_growth_rate.values[(1 - MU * q * q) > 1e-6])):.1e}")
    print(f"{'columns':>8} {'time (ms)':>10} {'ratio':>7} {'point err':>10} {'fold err (max)':>15} "
          f"{'fold err (parabola)':>20} {'chord err':>10}")
    for n in (50, 100, 200, 1000, 4000):
        t_n, pts = best_time(lambda: columns_in_sigma(n), repeat=1 if n > 200 else 3)
        e = np.max(np.abs(pts[:, 1] - sigma_ref(pts[:, 0])))
        k = int(np.argmax(pts[:, 1]))
        fold_max = abs(pts[k, 1] - S_STAR)
        a, b_, c = np.polyfit(pts[k - 1:k + 2, 0], pts[k - 1:k + 2, 1], 2)
        fold_par = max(abs(-b_ / (2 * a) - Q_STAR), abs(c - b_ * b_ / (4 * a) - S_STAR))
        qq = np.linspace(pts[0, 0], pts[-1, 0], 20 * len(pts))
        ch = np.max(np.abs(np.interp(qq, pts[:, 0], pts[:, 1]) - sigma_ref(qq)))
        print(f"{n:>8} {t_n * 1e3:>10.1f} {t_n / t_c:>7.1f} {e:>10.1e} {fold_max:>15.1e} "
              f"{fold_par:>20.1e} {ch:>10.1e}")
    crossings, found = columns_in_q(200)
    upper = ds.where(ds.sigma > 0.86, drop=True)
    print(f"turning back: 200 columns at fixed sigma in [0.05, 1.95] cross the curve {crossings} times; "
          f"brentq per column finds {found} ({crossings - found} missed: the columns with two crossings, "
          f"0.86 < sigma < {S_STAR:.4f}); continuation traces that part with {upper.sizes['point']} points "
          "and the fold")


if __name__ == "__main__":
    main()
