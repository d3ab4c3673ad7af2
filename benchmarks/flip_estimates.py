"""Flip-time estimates against the simulation, the cost of launch, and the flip-time map.

Usage: python benchmarks/flip_estimates.py [--map N_SPINS N_TILTS] [--skip-map] [--launch-only]

1. Error against cost (atlases/flip_estimates.png and .json): for the Table 1 top over launch
   spins and initial tilts, the time to 90 degrees by
   * the simulation at rtol 1e-12 (the reference: stability.launches.flip.run_launch, event
     location by Brent on restarted runs; checked against DOP853 on an independent rhs in
     tests/test_flip_time.py),
   * the simulation at rtol 1e-10 (stability.flip_time's default), 1e-8, 1e-6,
   * the e-folding estimates of eq. (11)'s leading growth rate, plain and projected on the
     growing mode (stability.launches.estimate.efold_flip_time),
   each timed warm (best of 3, time.perf_counter) per launch.
2. stability.launch warm for one top (Table 1, 7.15 rev/s): total and where the time goes.
3. The flip-time map (atlases/flip_time_toy.png, .nc): N_SPINS x N_TILTS launches (default
   80 x 5 = 400) of the Table 1 top, timed, with the paper's runs marked (Sec. 3(ii):
   about 78 and 41 spin periods at Fr^-1 = 0.3 and 0.1, i.e. 7.15 and 12.4 rev/s).
"""

from __future__ import annotations

import argparse
import json
import math
import time
from pathlib import Path

import numpy as np

import stability
from stability.launches.estimate import efold_flip_time, flip_time_map
from stability.launches.flip import run_launch
from stability.top import Top

ATLASES = Path(__file__).resolve().parent.parent / "atlases"
SPINS = (6.5, 7.15, 8.0, 9.0, 10.0, 12.0, 15.0, 20.0)  # rev/s; the upright top is unstable above 6.06
TILTS = (0.5, 1.0, 3.0, 10.0)  # degrees
RTOLS = (1e-10, 1e-8, 1e-6)


def best(fn, repeat=3):
    out, t = None, math.inf
    for _ in range(repeat):
        t0 = time.perf_counter()
        out = fn()
        t = min(t, time.perf_counter() - t0)
    return out, t


def error_cost():
    top = Top.table1()
    records = []
    for s in SPINS:
        params = top.nondimensional(s, "rev/s", alpha_v=0.5)
        for th in TILTS:
            ref = run_launch(params, tilt=th, stop_at_crossing=True, t_max=2e4, rtol=1e-12).crossing_time
            if ref is None:
                continue
            for rtol in RTOLS:
                run, sec = best(lambda: run_launch(params, tilt=th, stop_at_crossing=True, t_max=2e4, rtol=rtol))
                records.append(
                    dict(
                        method=f"simulation rtol {rtol:g}",
                        spin_rev_s=s,
                        tilt=th,
                        seconds=sec,
                        rel_error=abs(run.crossing_time - ref) / ref,
                    )
                )
            for name, how in (("e-folding (eq. 11)", "efold"), ("projected e-folding (eq. 11)", "projected")):
                est, sec = best(lambda: efold_flip_time(params, th, estimate=how), repeat=5)
                records.append(
                    dict(
                        method=name,
                        spin_rev_s=s,
                        tilt=th,
                        seconds=sec,
                        rel_error=abs(est - ref) / ref,
                        signed_error=(est - ref) / ref,
                    )
                )
    return records


def launch_cost():
    from stability.launches.result import inverts_above
    from stability.linear.critical import critical_spin
    from stability.steady.final import final_state

    top = Top.table1()
    stability.launch(top, 7.15, unit="rev/s")  # warm
    _, total = best(lambda: stability.launch(top, 7.15, unit="rev/s"))
    p = top.nondimensional(7.15, "rev/s", alpha_v=0.5)
    th = math.radians(1.0)
    k = [math.sin(th), 0.0, math.cos(th)]
    parts = {
        "critical_spin": best(lambda: critical_spin(top, "sliding", "upright", alpha_v=0.5))[1],
        "inverts_above (branch point)": best(lambda: inverts_above(top, 2 * math.pi * 7.15, 0.5))[1],
        "final_state": best(lambda: final_state(omega=k, k=k, velocity=[0.0, 0.0], **p))[1],
        "run to settle (flip, settle, normal force)": best(lambda: run_launch(p, tilt=1.0, end_tilt=163.7))[1],
        "the same run to the crossing only (flip_time)": best(lambda: run_launch(p, tilt=1.0, stop_at_crossing=True))[
            1
        ],
    }
    return total, parts


def the_map(n_spins, n_tilts):
    top = Top.table1()
    spins = np.linspace(6.2, 20.0, n_spins)
    tilts = np.array([0.5, 1.0, 2.0, 5.0, 10.0])[:n_tilts] if n_tilts <= 5 else np.geomspace(0.5, 10.0, n_tilts)
    t0 = time.perf_counter()
    ds = flip_time_map(top, spins, tilts, unit="rev/s", t_max=2e4)
    return ds, time.perf_counter() - t0


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--map", nargs=2, type=int, default=(80, 5), metavar=("N_SPINS", "N_TILTS"))
    ap.add_argument("--skip-map", action="store_true")
    ap.add_argument("--launch-only", action="store_true", help="only item 2 (the cost of stability.launch)")
    args = ap.parse_args()
    if args.launch_only:
        total, parts = launch_cost()
        print(f"stability.launch warm (Table 1, 7.15 rev/s): {total:.3f} s; parts:")
        for k, v in parts.items():
            print(f"  {k}: {v:.3f} s")
        return
    from stability.plotting import save_figure, style
    from stability.plotting.launch_plots import plot_flip_estimates, plot_flip_time

    stability.launch(Top.table1(), 7.15, unit="rev/s")  # compile once
    records = error_cost()
    summary = {}
    for m in dict.fromkeys(r["method"] for r in records):
        rs = [r for r in records if r["method"] == m]
        summary[m] = dict(
            max_rel_error=max(r["rel_error"] for r in rs),
            median_rel_error=float(np.median([r["rel_error"] for r in rs])),
            median_seconds=float(np.median([r["seconds"] for r in rs])),
        )
        print(
            f"{m:>24}: error max {summary[m]['max_rel_error']:.2e} median {summary[m]['median_rel_error']:.2e}, "
            f"median {summary[m]['median_seconds'] * 1e3:.3g} ms per launch"
        )
    total, parts = launch_cost()
    print(f"stability.launch warm (Table 1, 7.15 rev/s): {total:.3f} s; parts:")
    for k, v in parts.items():
        print(f"  {k}: {v:.3f} s")
    out = dict(
        spins_rev_s=SPINS,
        tilts_deg=TILTS,
        records=records,
        summary=summary,
        launch_seconds=total,
        launch_parts=parts,
        command="python benchmarks/flip_estimates.py",
    )
    with style():
        fig, ax = plot_flip_estimates(records)
        ax.set_title(
            "time to 90 deg, Table 1 top, 6.5-20 rev/s, tilts 0.5-10 deg; reference: simulation at rtol 1e-12",
            fontsize=8,
        )
        save_figure(fig, ATLASES / "flip_estimates.png")
    if not args.skip_map:
        ds, sec = the_map(*args.map)
        n = ds.flip_time.size
        print(f"flip-time map: {n} launches in {sec:.1f} s ({sec / n * 1e3:.0f} ms each)")
        out.update(map_launches=n, map_seconds=sec)
        top = Top.table1()
        marks = [
            (7.15, 78 / 7.15, "paper, Fr^-1 = 0.3: ~78 periods"),
            (
                float(top.spin_rate(0.1, "rev/s")),
                41 / float(top.spin_rate(0.1, "rev/s")),
                "paper, Fr^-1 = 0.1: ~41 periods",
            ),
        ]
        with style():
            fig, ax = plot_flip_time(ds, marks=marks)
            save_figure(fig, ATLASES / "flip_time_toy.png")
        ds.to_netcdf(ATLASES / "flip_time_toy.nc")
    (ATLASES / "flip_estimates.json").write_text(json.dumps(out, indent=1, default=float))


if __name__ == "__main__":
    main()
