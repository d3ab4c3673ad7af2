"""What the hybrid stick-slip run costs against simulate's regularised run of the same launch.

A (``stability.stick_slip``): the Kane-Levinson hybrid, DOP853 through scipy at rtol 1e-10,
exact switches (docs/contact.md). B (``stability.simulate``, ``method="auto"``: LSODA, the
regularised Coulomb law, rtol 1e-9): the baseline, which never truly sticks (its slip stays at
~3e-5, the regularisation scale's order). Same launch (the figure's: wobbling top, alpha_k =
0.02, alpha_s = 0.022 for A), 150 time units, output every 0.05; best of 3 after a warm-up run
of each (numba caches loaded). Accuracy of A: switch times agree with the independent hybrid of
tests/test_stickslip.py to 4e-12 relative.

Usage: python benchmarks/stick_slip.py
"""

from __future__ import annotations

import math
import time

import stability

TH = math.radians(30.0)
LAUNCH = dict(
    t_end=150.0,
    q=-0.1,
    sigma=1.0,
    mu=2.28,
    fr_inv=0.3,
    alpha_k=0.02,
    omega=[1.0, 0.0, 0.5],
    k=[math.sin(TH), 0.0, math.cos(TH)],
    velocity=[0.3, 0.0],
    dt=0.05,
)


def _best(fn, repeat=3):
    fn()
    best = math.inf
    for _ in range(repeat):
        t0 = time.perf_counter()
        out = fn()
        best = min(best, time.perf_counter() - t0)
    return best, out


def main() -> None:
    a, ds = _best(lambda: stability.stick_slip(alpha_s=0.022, **LAUNCH))
    b, reg = _best(lambda: stability.simulate("sliding", alpha_v=0.0, **LAUNCH))
    print(f"stick_slip: {a:.3f} s ({ds.attrs['n_switches']} switches, final phase {ds.attrs['final_phase']})")
    print(f"simulate (regularised, {reg.attrs['method']}): {b:.3f} s (final slip {float(reg.slip_speed[-1]):.2g})")
    print(f"ratio stick_slip / simulate: {a / b:.2f}")


if __name__ == "__main__":
    main()
