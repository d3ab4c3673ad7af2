"""Benchmark: the paper's Fr^-1 = 0.3 run (Sec. 3(ii)) by the compiled integrators, CPU time.

The run of the integrator suite's first panel (``python benchmarks/run.py --suite
integrators``): the sliding top at ``q = -0.1``, ``sigma = 1``, ``mu = 2.28``, ``alpha_v = 0.5``,
the printed initial conditions, 650 time units sampled every 0.05, by ``dopri5`` at
``simulate``'s default tolerances and by the paper's RK4 at ``h = 0.025``. Prints the best of
``--repeat`` calls in thread CPU time (less disturbed by other load than wall time), after one
warm-up call each (compilation or the disk cache). To compare two versions, run it with each on
``PYTHONPATH`` (e.g. a ``git archive`` of the old commit), one after the other::

    PYTHONPATH=/tmp/old python benchmarks/paper_run.py
    python benchmarks/paper_run.py
"""

from __future__ import annotations

import argparse
import time

from stability.nonlinear.runs import simulate
from stability.nonlinear.scene import INITIAL_CONDITIONS, PAPER

FR_INV = 0.3


def run(method: str, **kw: float) -> object:
    """The paper's run by ``method``."""
    return simulate(
        "sliding", t_end=650.0, dt=0.05, fr_inv=FR_INV, alpha_v=0.5, **PAPER, **INITIAL_CONDITIONS[FR_INV],
        method=method, rtol=1e-9, atol=1e-12, **kw,
    )  # fmt: skip


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--repeat", type=int, default=7, help="calls timed per method (default 7)")
    a = p.parse_args()
    for method, kw in (("dopri5", {}), ("rk4", {"step": 0.025})):
        run(method, **kw)
        best = float("inf")
        for _ in range(a.repeat):
            t = time.thread_time()
            ds = run(method, **kw)
            best = min(best, time.thread_time() - t)
        print(f"{method:8s} {best * 1e3:7.1f} ms CPU  nfev {ds.attrs['nfev']}")  # type: ignore[attr-defined]


if __name__ == "__main__":
    main()
