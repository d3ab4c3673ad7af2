"""Work-precision benchmarks, written as charts (PNG) and JSON summaries: the one runner.

The suites live beside the package, not in it (as scipy keeps its benchmarks):
``benchmarks/suites/`` (:data:`suites.SUITES`). Run from the repository::

    python benchmarks/run.py                     # every suite, each in its own process -> atlases/
    python benchmarks/run.py --suite eigen       # one suite -> atlases/work_precision_eigen.*
    python benchmarks/run.py --suite eigen --quick   # seconds, not minutes -> a temporary folder

The suites are ``eigen`` (eigenvalue methods, 10^6 points), ``continuation`` (step settings
against the exact fold), ``integrators`` (the nonlinear runs) and ``steady`` (final state, branch,
class map). Each writes ``OUT_DIR/work_precision_NAME.png`` and ``.json`` (atomically) and prints
one line per measurement with its ratio to the baselines.

Where the files go: ``--out-dir DIR`` if given; otherwise the committed charts in the
repository's ``atlases/`` for a full run, and a new temporary folder (printed) for ``--quick``,
whose small configurations must never replace the committed charts (issue 20, item 16).

Exit status: 0, or 2 for a bad flag (one line on stderr), or the failing suite's status.
"""

from __future__ import annotations

import argparse
import inspect
import json
import math
import os
import platform
import subprocess
import sys
import tempfile
from pathlib import Path
from typing import Any

if __package__ in (None, ""):  # run as a script: its folder holds the suites
    sys.path.insert(0, str(Path(__file__).resolve().parent))

from suites import SUITES
from suites.records import WorkPrecision, peak_memory_mb

from stability.files import atomic_output, check_output_path

__all__ = ["ATLASES", "main", "parser", "run", "run_suite", "summary_lines"]

#: the committed charts: where a full run writes by default
ATLASES = Path(__file__).resolve().parent.parent / "atlases"


def parser() -> argparse.ArgumentParser:
    """The runner's flags."""
    p = argparse.ArgumentParser(
        prog="benchmarks/run.py",
        description="Work-precision benchmarks: the eigenvalue methods on a large batch of points over the "
        "physical domain against mpmath at 50 digits (eigen), the continuation's step settings "
        "against the exact fold of the neutral curve (continuation), the integrators of the "
        "nonlinear runs against a tight DOP853 reference (integrators), the steady states "
        "(steady). Writes a chart (PNG) and a JSON summary per suite and prints the speed "
        "ratios against the baselines.",
    )
    p.add_argument(
        "--suite", choices=[*SUITES, "all"], default="all", help="suite to run (default: all, each in its own process)"
    )
    p.add_argument("--quick", action="store_true", help=f"small configurations ({_quick_help()})")
    p.add_argument(
        "--points", type=float, default=None, metavar="N", help="eigen: batch size for the timings (default 1e6)"
    )
    p.add_argument("--reference-points", type=int, default=None, help="eigen: mpmath sample size (default 1000)")
    p.add_argument(
        "--loop-points", type=int, default=None, help="eigen: points timed for the per-point loop (default 20000)"
    )
    p.add_argument(
        "--repeat", type=int, default=None, help="timed repeats, the best kept (eigen 5, continuation 5, integrators 3)"
    )
    p.add_argument(
        "--out-dir",
        default=None,
        metavar="DIR",
        help="directory for the charts and the summaries (created if missing; default: atlases/ "
        "of the repository, or a new temporary folder with --quick)",
    )
    return p


def _quick_help() -> str:
    """What ``--quick`` runs, from each suite's :attr:`~suites.records.Suite.quick`."""

    def shown(k: str, v: Any) -> str:
        return "fewer settings" if k == "quick" else f"{k.replace('_', ' ')} {v:g}"

    return "; ".join(f"{s.name}: {', '.join(shown(k, v) for k, v in s.quick.items())}" for s in SUITES.values())


def _error(r: WorkPrecision, key: str) -> float:
    return r.error if key == "error" else float(r.extra.get(key, float("inf")))


def summary_lines(results: list[WorkPrecision], unit: str = "point", compare_at: tuple[str, ...] = ()) -> list[str]:
    """One line per measurement: time per unit of work, error, and speed ratios against the
    baselines of the same panel.

    Parameters
    ----------
    results : list of WorkPrecision
    unit : str
        Unit of work ("point", "curve", "run").
    compare_at : tuple of str
        Empty: the ratio against each baseline point. Otherwise, for each error named
        (``"error"`` or a key of ``extra``), the ratio at equal accuracy: against the fastest
        setting of each baseline series whose error is at most this point's ("none as
        accurate" if no setting is).

    Returns
    -------
    list of str
    """
    lines = []
    for r in results:
        series = {}
        for b in results:
            if b.baseline and b.panel == r.panel and (b.series or b.method) != (r.series or r.method):
                series.setdefault(b.series or b.method, []).append(b)
        parts = []
        for name, bs in series.items():
            if not compare_at:
                parts += [f"{b.seconds_per_point / r.seconds_per_point:.1f}x {name}" for b in bs]
                continue
            for key in compare_at:
                ok = [b for b in bs if _error(b, key) <= _error(r, key)]
                what = "" if key == "error" else f" ({key.replace('_', ' ')})"
                if ok:
                    b = min(ok, key=lambda b: b.seconds_per_point)
                    parts.append(f"{b.seconds_per_point / r.seconds_per_point:.1f}x {name} {b.setting}{what}")
                else:
                    parts.append(f"no {name} setting as accurate{what}")
        flag = " [default]" if r.default else ""
        t = r.seconds_per_point
        shown = f"{t * 1e9:10.1f} ns/{unit}" if t < 1e-3 else f"{t * 1e3:10.2f} ms/{unit}"
        label = f"{r.method} {r.setting}".strip()
        lines.append(f"{label:<44s} {shown}  error {r.error:8.1e}  {'; '.join(parts)}{flag}")
    return lines


def _options(args: argparse.Namespace, name: str) -> dict[str, Any]:
    """Keyword arguments for a suite's run function: the ones it names, from the flags (with
    ``--quick``, the suite's :attr:`~suites.records.Suite.quick` where no flag gives one)."""
    suite = SUITES[name]
    given = {
        "points": None if args.points is None else int(args.points),
        "reference_points": args.reference_points,
        "loop_points": args.loop_points,
        "repeat": args.repeat,
        "quick": None,
    }
    if args.quick:
        given = {k: suite.quick.get(k) if v is None else v for k, v in given.items()}
    accepted = inspect.signature(suite.run).parameters
    # every option the suite takes, with its default where no flag gave one (so that the chart
    # and the JSON record the configuration actually run)
    return {
        k: given[k] if given.get(k) is not None else p.default
        for k, p in accepted.items()
        if k in given and (given.get(k) is not None or p.default is not inspect.Parameter.empty)
    }


def run_suite(name: str, out_dir: Path, options: dict[str, Any]) -> list[WorkPrecision]:
    """Run one suite, write its chart and JSON summary (atomically), print its lines.

    Parameters
    ----------
    name : str
        A key of :data:`suites.SUITES`.
    out_dir : pathlib.Path
        Existing directory for ``work_precision_NAME.png`` and ``.json``.
    options : dict
        Keyword arguments for the suite's run function.

    Returns
    -------
    list of WorkPrecision
    """
    if name not in SUITES:
        raise ValueError(f"suite = {name!r} is not known; choose one of {', '.join(SUITES)}")
    suite = SUITES[name]
    png = check_output_path(out_dir / f"work_precision_{name}.png", overwrite=True)
    js = check_output_path(out_dir / f"work_precision_{name}.json", overwrite=True)
    results = suite.run(**options)
    peak = peak_memory_mb()
    from suites.charts import suite_figure, verdict

    from stability.plotting import save_figure, style

    cond = ", ".join(
        f"{k.replace('_', ' ')} {v:g}" if not isinstance(v, bool) else k for k, v in options.items() if v is not False
    )
    subtitle = f"{cond + '; ' if cond else ''}{os.cpu_count()} cores; peak memory {peak:.0f} MB"
    with style():
        fig, _ = suite_figure(suite, results, subtitle=subtitle)
    save_figure(fig, png)
    info = {
        "suite": name,
        **options,
        "cores": os.cpu_count(),
        "machine": platform.machine(),
        "python": platform.python_version(),
        "peak_memory_mb": peak,
        "verdict": [
            verdict([r for r in results if r.panel == p.select], p.target) for p in suite.panels if p.target is not None
        ],
        "results": [r.as_dict() for r in results],
    }
    with atomic_output(js, overwrite=True) as tmp:
        Path(tmp).write_text(json.dumps(info, indent=1))
    print(f"== {name}: {suite.title}")
    for line in summary_lines(results, suite.unit, suite.compare_at):
        print(line)
    for v in info["verdict"]:
        print(v)
    print(f"peak memory {peak:.0f} MB; wrote {png} and {js}")
    return results


def output_directory(args: argparse.Namespace) -> Path:
    """Where the charts go: ``--out-dir``, else :data:`ATLASES` (full run) or a new temporary
    folder (``--quick``: its small configurations never replace the committed charts)."""
    if args.out_dir is not None:
        return Path(args.out_dir)
    if args.quick:
        return Path(tempfile.mkdtemp(prefix="tippe-bench-"))
    return ATLASES


def run(args: argparse.Namespace, out_dir: Path) -> int:
    """Run the suites the flags name into the existing folder ``out_dir``; return the exit status."""
    names = list(SUITES) if args.suite == "all" else [args.suite]
    if len(names) == 1:
        run_suite(names[0], out_dir, _options(args, names[0]))
        return 0
    # one process per suite: the peak memory a chart reports (ru_maxrss, which never decreases)
    # is then that suite's own, not the largest of the suites run before it in the same process
    for name in names:
        cmd = [sys.executable, str(Path(__file__).resolve()), "--suite", name, "--out-dir", str(out_dir)]
        cmd += ["--quick"] * bool(args.quick)
        for flag in ("points", "reference_points", "loop_points", "repeat"):
            if getattr(args, flag) is not None:
                cmd += ["--" + flag.replace("_", "-"), repr(getattr(args, flag))]
        done = subprocess.run(cmd)
        if done.returncode != 0:
            print(
                f"benchmarks/run.py: suite {name} failed (exit {done.returncode}); the suites before it are written",
                file=sys.stderr,
            )
            return done.returncode
    return 0


def main(argv: list[str] | None = None) -> int:
    """Parse ``argv`` and run; a bad flag value is one line on stderr and exit status 2."""
    args = parser().parse_args(argv)
    try:  # the flags are checked before anything runs or is written
        _check_sizes(args)
        out_dir = output_directory(args)
        if out_dir.exists() and not out_dir.is_dir():
            raise FileExistsError(f"--out-dir {str(out_dir)!r} exists and is not a directory")
    except (ValueError, FileExistsError) as exc:
        print(f"benchmarks/run.py: error: {exc}", file=sys.stderr)
        return 2
    out_dir.mkdir(parents=True, exist_ok=True)
    return run(args, out_dir)


#: the sizes a flag may take (eigen: the batch must fit in memory, ~1.3 kB per point at 1e6)
SIZE_LIMITS = {"points": (100, 10**8), "reference_points": (10, 10**5), "loop_points": (10, 10**7), "repeat": (1, 1000)}


def _check_sizes(args: argparse.Namespace) -> None:
    """Each size flag is an integer in :data:`SIZE_LIMITS` (named with its value and range)."""
    for name, (lo, hi) in SIZE_LIMITS.items():
        value = getattr(args, name)
        if value is None:
            continue
        flag = "--" + name.replace("_", "-")
        if not (
            isinstance(value, (int, float)) and math.isfinite(value) and float(value).is_integer() and lo <= value <= hi
        ):
            raise ValueError(f"{flag} = {value!r} is outside the allowed range: an integer in [{lo}, {hi:g}]")


if __name__ == "__main__":
    sys.exit(main())
