"""Work-precision of the integrators for the nonlinear sliding model, and the speed-up.

For each method and tolerance: wall time, right-hand-side evaluations, the error in the
90-degree crossing time of the paper's run (fr_inv = 0.3, Sec. 3(ii)) and the relative error
of the growth rate fitted by :func:`stability.validate` at (q, fr_inv, alpha_v) =
(-0.1, 0.3, 0.5); errors against a DOP853 reference at rtol = 1e-13. A second table runs the
linear-regime problem at large alpha_v (stiff slip mode) to show where explicit methods fail
(their step is bounded by stability, not accuracy). The last line compares the compiled
dopri5 with a plain scipy solve_ivp (RK45) calling the numpy right-hand side
(:mod:`stability.nonlinear.reference`), measured in the same run.

Usage: python benchmarks/work_precision.py [--quick]
"""

from __future__ import annotations

import sys
import time

import numpy as np
from scipy.integrate import solve_ivp

from stability.nonlinear.integrators import integrate
from stability.nonlinear.parameters import pack
from stability.nonlinear.reference import sliding_rhs
from stability.scene import INITIAL_CONDITIONS, PAPER, crossing_time
from stability.simulate import initial_state, simulate

FR = 0.3
IC = INITIAL_CONDITIONS[FR]


def crossing(method: str, rtol: float, step: float | None = None) -> tuple[float, float, int]:
    t0 = time.perf_counter()
    ds = simulate("sliding", t_end=650.0, dt=0.05, fr_inv=FR, alpha_v=0.5, **PAPER, **IC,
                  method=method, rtol=rtol, atol=rtol * 1e-3, step=step)
    return crossing_time(ds), time.perf_counter() - t0, int(ds.attrs["nfev"])


def stiff_run(method: str, alpha_v: float, rtol: float) -> tuple[float, int, float]:
    """Linear-regime run (tilt 1e-3) at large alpha_v: wall time, nfev, final tilt."""
    t0 = time.perf_counter()
    ds = simulate("sliding", t_end=200.0, dt=1.0, omega=[0.0, 0.0, 1.0], k=[1e-3, 0.0, 1.0],
                  q=-0.1, fr_inv=0.3, sigma=1.0, alpha_v=alpha_v, method=method, rtol=rtol,
                  atol=rtol * 1e-3, max_steps=2_000_000)
    tilt = float(np.hypot(*ds.k.values[-1, :2]))
    return time.perf_counter() - t0, int(ds.attrs["nfev"]), tilt


def main(quick: bool = False) -> None:
    crossing("dopri5", 1e-6)                                   # compile / load caches
    ref, _, _ = crossing("DOP853", 1e-13)
    print(f"reference crossing time (DOP853, rtol 1e-13): {ref:.9f} = {ref / 2 / np.pi:.6f} periods")
    print(f"{'method':8s} {'rtol/step':>10s} {'seconds':>9s} {'nfev':>10s} {'crossing error':>15s}")
    tols = (1e-5, 1e-7, 1e-9) if quick else (1e-4, 1e-6, 1e-8, 1e-10)
    for method in ("dopri5", "RK45", "DOP853", "LSODA", "Radau", "BDF"):
        for rtol in tols:
            if method in ("Radau", "BDF") and rtol < 1e-8 and quick:
                continue
            tc, sec, nfev = crossing(method, rtol)
            print(f"{method:8s} {rtol:10.0e} {sec:9.3f} {nfev:10d} {abs(tc - ref):15.3e}")
    for h in (0.4, 0.2, 0.1, 0.05):
        tc, sec, nfev = crossing("rk4", 1e-6, step=h)
        print(f"{'rk4':8s} {h:10.2f} {sec:9.3f} {nfev:10d} {abs(tc - ref):15.3e}")

    print("\nstiff slip mode: linear-regime run over 200 time units, rtol 1e-6")
    print(f"{'alpha_v':>8s} {'method':8s} {'seconds':>9s} {'nfev':>10s} {'final tilt':>12s}")
    for alpha_v in (5.0, 50.0, 500.0, 5000.0):
        for method in ("dopri5", "RK45", "LSODA", "Radau"):
            sec, nfev, tilt = stiff_run(method, alpha_v, 1e-6)
            print(f"{alpha_v:8.0f} {method:8s} {sec:9.3f} {nfev:10d} {tilt:12.6e}")

    p = pack(q=-0.1, fr_inv=FR, sigma=1.0, mu=2.28, alpha_v=0.5)
    y0 = initial_state("sliding", IC["omega"], IC["k"], IC["velocity"])
    t_eval = np.linspace(0, 1000, 10001)
    integrate("sliding", y0, t_eval[:3], p)
    t0 = time.perf_counter()
    integrate("sliding", y0, t_eval, p, method="dopri5", rtol=1e-9, atol=1e-12)
    fast = time.perf_counter() - t0
    t0 = time.perf_counter()
    r = solve_ivp(lambda t, y: sliding_rhs(t, y, 0.0 - 0.1, FR, 1.0, 2.28, 0.5), (0, 1000), y0,
                  method="RK45", t_eval=t_eval, rtol=1e-9, atol=1e-12)
    slow = time.perf_counter() - t0
    print(f"\n1000 time units, rtol 1e-9: compiled dopri5 {fast:.3f} s, scipy RK45 + numpy RHS "
          f"{slow:.2f} s ({r.nfev} evaluations): ratio {slow / fast:.0f}")


if __name__ == "__main__":
    main(quick="--quick" in sys.argv)
