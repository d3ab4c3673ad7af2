"""``tippe bench``: work-precision benchmarks, written as charts (PNG) and a JSON summary."""

from __future__ import annotations

import argparse
import json
import os
import platform
from pathlib import Path

from ..io import atomic_output, check_output_path
from ..performance import SUITES, WorkPrecision, peak_memory_mb

__all__ = ["register", "run", "summary_lines"]

#: required accuracy of the spectra (issue: largest relative error per eigenvalue)
EIGEN_TARGET = 1e-13


def register(sub: argparse._SubParsersAction) -> None:
    """Add the ``bench`` subcommand."""
    p = sub.add_parser(
        "bench", help="work-precision benchmarks -> charts under atlases/",
        description="Time the eigenvalue methods on a large batch of points spread over the physical "
                    "domain and measure their error against mpmath at 50 digits; write a work-precision "
                    "chart (PNG) and a JSON summary, and print the speed ratios against the baselines.")
    p.add_argument("--suite", choices=list(SUITES), default="eigen")
    p.add_argument("--points", type=float, default=1e6, help="batch size for the timings (default 1e6)")
    p.add_argument("--reference-points", type=int, default=1000, help="mpmath sample size (default 1000)")
    p.add_argument("--loop-points", type=int, default=20000, help="points timed for the per-point loop")
    p.add_argument("--repeat", type=int, default=3, help="timed repeats, best kept (default 3)")
    p.add_argument("--out-dir", default="atlases", help="directory for the chart and the summary")
    p.set_defaults(func=run)


def summary_lines(results: list[WorkPrecision]) -> list[str]:
    """One line per method: time per point, error, and ratios against each baseline."""
    baselines = [r for r in results if r.baseline]
    lines = []
    for r in results:
        ratios = ", ".join(f"{b.seconds_per_point / r.seconds_per_point:.1f}x {b.method}" for b in baselines
                           if b is not r)
        flag = " [default]" if r.default else ""
        lines.append(f"{r.method:<24s} {r.seconds_per_point * 1e9:10.1f} ns/point  error {r.error:8.1e}"
                     f"  {ratios}{flag}")
    return lines


def run(args: argparse.Namespace) -> int:
    """Run ``tippe bench``."""
    out_dir = Path(args.out_dir)
    if not out_dir.is_dir():
        raise FileNotFoundError(f"output directory {str(out_dir)!r} does not exist")
    png = check_output_path(out_dir / f"work_precision_{args.suite}.png", overwrite=True)
    js = check_output_path(out_dir / f"work_precision_{args.suite}.json", overwrite=True)
    points = int(args.points)
    results = SUITES[args.suite](points=points, reference_points=args.reference_points,
                                 loop_points=args.loop_points, repeat=args.repeat)
    peak = peak_memory_mb()
    lines = summary_lines(results)
    from ..plotting import save_figure, style
    from ..plotting.work_precision import work_precision_figure

    with style():
        fig, _ = work_precision_figure(
            results, target=EIGEN_TARGET,
            xlabel=f"largest relative error per eigenvalue vs mpmath, 50 digits ({args.reference_points} points)",
            title=f"sliding model, {points:.0e} points over the physical domain, {os.cpu_count()} cores; "
                  f"peak memory {peak:.0f} MB")
    save_figure(fig, png)
    info = {"suite": args.suite, "points": points, "reference_points": args.reference_points,
            "loop_points": args.loop_points, "repeat": args.repeat, "cores": os.cpu_count(),
            "machine": platform.machine(), "python": platform.python_version(),
            "peak_memory_mb": peak, "results": [r.as_dict() for r in results]}
    with atomic_output(js, overwrite=True) as tmp:
        Path(tmp).write_text(json.dumps(info, indent=1))
    for line in lines:
        print(line)
    print(f"peak memory {peak:.0f} MB; wrote {png} and {js}")
    return 0
