"""Print the numbers of the tumbling runs of Sec. 3(ii) beside the paper's.

Usage: python benchmarks/scene_numbers.py
"""

from __future__ import annotations

import time
from typing import Any

import numpy as np

from stability.nonlinear.scene import crossing_time, friction_cases, run

#: the paper's numbers
PAPER_NUMBERS: dict[str, Any] = {"crossing_periods": {0.3: 78.0, 0.1: 41.0}, "peak_transverse_rate": 0.12}


def scene_numbers(fr_inv: float = 0.3, **kw: Any) -> dict[str, float]:
    """The numbers of Figs. 5-9 for one run of Sec. 3(ii) (the module docstring of :mod:`stability.nonlinear.scene`).

    Returns
    -------
    dict of float
        ``crossing_periods``, ``spin_start``, ``spin_end``, ``peak_transverse_rate``,
        ``transverse_rate_at_crossing``, ``min_slip_speed_before_crossing``,
        ``min_slip_speed``, energy parts at start and end, ``centre_excursion``,
        ``mean_friction_sliding`` and ``mean_friction_rolling`` (over the first
        ``crossing`` time units), ``seconds`` (wall time of the sliding run).
    """
    t0 = time.perf_counter()
    ds = run(fr_inv, **kw)
    wall = time.perf_counter() - t0
    tc = crossing_time(ds)
    out = {
        "crossing_periods": tc / (2 * np.pi),
        "crossing_time": tc,
        "spin_start": float(ds.spin[0]),
        "spin_end": float(ds.spin[-1]),
        "peak_transverse_rate": float(ds.transverse_rate.max()),
        "transverse_rate_at_crossing": float(ds.transverse_rate.interp(time=tc)),
        "min_slip_speed_before_crossing": float(ds.slip_speed.sel(time=slice(0, tc)).min()),
        "min_slip_speed": float(ds.slip_speed.min()),
        "centre_excursion": float(np.max(np.hypot(ds.position[:, 0], ds.position[:, 1]))),
        "seconds": wall,
    }
    for part in ("kinetic_translational", "kinetic_spin", "kinetic_transverse", "potential", "energy"):
        out[f"{part}_start"] = float(ds[part][0])
        out[f"{part}_end"] = float(ds[part][-1])
    roll = run(fr_inv, model="rolling", t_end=float(tc), dt=0.05)
    out["mean_friction_rolling"] = float(roll.friction_magnitude.mean())
    out["mean_friction_sliding"] = float(ds.friction_magnitude.sel(time=slice(0, tc)).mean())
    return out


def main() -> None:
    for fr in (0.3, 0.1):
        n = scene_numbers(fr)
        print(
            f"fr_inv = {fr}: crossing after {n['crossing_periods']:.2f} spin periods "
            f"(paper {PAPER_NUMBERS['crossing_periods'][fr]:.0f}); run took {n['seconds']:.3f} s"
        )
        for k, v in n.items():
            print(f"    {k:34s} {v: .6g}")
    for scheme in ("adaptive", "fixed_step"):
        ds = friction_cases(0.3, scheme=scheme)
        print(f"Fig. 9(b) friction cases, scheme = {scheme}")
        print(ds.to_dataframe().to_string())


if __name__ == "__main__":
    main()
