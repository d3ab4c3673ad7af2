"""Where the fused kernel's time goes: the sliding model's loop built up one piece at a time.

Each line is a serial compiled loop over ``--points`` random sliding points
(``benchmarks/suites/eigen.py`` ``domain_sample``, seed 0) that does one piece more than the
line before, from the kernel's own building blocks (:mod:`stability.linear.kernel`):

* ``coefficients``: the model's ``point_coefficients`` (eq. 11), one value written per point;
* ``+ Cardano``: Cardano's three estimates (:func:`~stability.linear.kernel._cardano`);
* ``+ cubic, no sweep``: the scale test and deflation of :func:`~stability.linear.kernel._cubic`
  with ``polish=0``;
* ``+ Weierstrass sweeps``: ``_cubic`` with ``polish=3`` (one sweep passes its test);
* ``+ error bounds``: :func:`~stability.linear.kernel._solve` (structural zeros, bounds);
* ``+ sort and decision``: :func:`~stability.linear.kernel._decide` writing the outputs, the whole
  loop of :func:`stability.linear.kernel.model_spectrum` without the mask test, one point per
  iteration;
* ``in blocks (the kernel)``: :func:`stability.linear.kernel.model_spectrum` itself (serial,
  compiled: the same work in blocks of points, structure of arrays, the loops packed into SIMD
  arithmetic, :func:`~stability.linear.kernel._block_solve`, plus the mask test and the
  driver's allocations); not a piece, so its difference to the line above is the gain of the
  blocks.

The differences between consecutive lines are the pieces' costs (ns per point of the calling
thread's CPU time, ``time.thread_time``, which does not count the time spent waiting for a core
on a loaded machine; best of ``--repeat`` calls, the lines interleaved ``--rounds`` times)::

    python benchmarks/kernel_pieces.py --points 400000 --rounds 3

The private helpers are this package's own (benchmarks of the kernel, not an API).
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import numpy as np


def main(argv: list[str] | None = None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--points", type=int, default=400_000)
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--rounds", type=int, default=3)
    a = ap.parse_args(argv)

    import stability.jit as jit

    jit.activate()
    import numba

    from stability.linear.kernel import _cardano, _cubic, _decide, _solve, model_spectrum
    from stability.models.sliding import coefficient_parts as formula

    sys.path.insert(0, str(Path(__file__).resolve().parent))
    from suites.eigen import domain_sample

    opts = dict(jit.OPTIONS)

    @numba.njit(**opts)
    def coefficients(q, f, s, al, m, ev):
        for i in range(len(q)):
            c = formula(q[i], f[i], s[i], al[i], m[i])
            ev[i, 0] = complex(c[0] + c[2] + c[4] + c[6], c[1] + c[3] + c[5] + c[7])

    @numba.njit(**opts)
    def cardano(q, f, s, al, m, ev):
        for i in range(len(q)):
            c = formula(q[i], f[i], s[i], al[i], m[i])
            r0, r1, r2 = _cardano(complex(c[0], c[1]), complex(c[2], c[3]), complex(c[4], c[5]), complex(c[6], c[7]))
            ev[i, 0] = r0
            ev[i, 1] = r1
            ev[i, 2] = r2

    @numba.njit(**opts)
    def cubic(q, f, s, al, m, ev, polish):
        for i in range(len(q)):
            c = formula(q[i], f[i], s[i], al[i], m[i])
            c3, c2, c1, c0 = complex(c[0], c[1]), complex(c[2], c[3]), complex(c[4], c[5]), complex(c[6], c[7])
            r0, r1, r2 = _cubic(c3, c2, c1, c0, polish)
            ev[i, 0] = r0
            ev[i, 1] = r1
            ev[i, 2] = r2

    @numba.njit(**opts)
    def solve(q, f, s, al, m, ev, bd):
        for i in range(len(q)):
            c = formula(q[i], f[i], s[i], al[i], m[i])
            c3, c2, c1, c0 = complex(c[0], c[1]), complex(c[2], c[3]), complex(c[4], c[5]), complex(c[6], c[7])
            r0, r1, r2, e0, e1, e2, x0, x1, x2 = _solve(c3, c2, c1, c0, 3, 3)
            ev[i, 0] = r0
            ev[i, 1] = r1
            ev[i, 2] = r2
            bd[i, 0] = e0
            bd[i, 1] = e1
            bd[i, 2] = e2

    @numba.njit(**opts)
    def whole(q, f, s, al, m, ev, bd, nt, st):
        for i in range(len(q)):
            c = formula(q[i], f[i], s[i], al[i], m[i])
            c3, c2, c1, c0 = complex(c[0], c[1]), complex(c[2], c[3]), complex(c[4], c[5]), complex(c[6], c[7])
            r0, r1, r2, e0, e1, e2, x0, x1, x2 = _solve(c3, c2, c1, c0, 3, 3)
            st[i] = _decide(3, r0, r1, r2, e0, e1, e2, x0, x1, x2, ev, bd, nt, i)

    n = a.points
    p = domain_sample(n, seed=0)
    args = [p[k] for k in ("q", "fr_inv", "sigma", "alpha_v", "mu")]
    ev = np.empty((n, 3), complex)
    bd = np.empty((n, 3))
    nt = np.empty((n, 3), np.bool_)
    st = np.empty(n, np.int8)
    lines = {
        "coefficients": lambda: coefficients(*args, ev),
        "+ Cardano": lambda: cardano(*args, ev),
        "+ cubic, no sweep": lambda: cubic(*args, ev, 0),
        "+ Weierstrass sweeps": lambda: cubic(*args, ev, 3),
        "+ error bounds": lambda: solve(*args, ev, bd),
        "+ sort and decision": lambda: whole(*args, ev, bd, nt, st),
        "in blocks (the kernel)": lambda: model_spectrum(
            "sliding", p, np.ones(n, bool), parallel=False, engine="compiled"
        ),
    }
    best = dict.fromkeys(lines, np.inf)
    for f in lines.values():
        f()  # compile
    for _ in range(a.rounds):
        for k, f in lines.items():
            for _ in range(a.repeat):
                t = time.thread_time()
                f()
                best[k] = min(best[k], time.thread_time() - t)
    prev = 0.0
    print(f"{'loop':24s} {'ns/point':>9s} {'piece':>7s}   ({n} points, one thread)")
    for k, v in best.items():
        ns = v / n * 1e9
        print(f"{k:24s} {ns:9.1f} {ns - prev:7.1f}")
        prev = ns


if __name__ == "__main__":
    main()
