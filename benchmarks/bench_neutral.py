"""Benchmark: neutral curve by continuation vs a brentq per grid column, at equal accuracy.

A thin script: the measurement (problem, baselines, error definitions, timing) is
:mod:`suites.continuation`, the same code as ``python benchmarks/run.py --suite continuation``;
this prints its tables (continuation settings, column counts, equal accuracy, turning back).

Run: ``python3 benchmarks/bench_neutral.py [--repeat 7] [--min-time 0.5]`` (about a minute;
run it on a quiet machine: the timing is the minimum wall time, see the module).
"""

from __future__ import annotations

import argparse

from suites.continuation import format_tables, neutral_benchmark

COLUMNS = (10, 15, 20, 25, 30, 40, 50, 60, 80, 100, 125, 150, 200, 300, 400)


def main(argv: list[str] | None = None) -> None:
    """Run :func:`suites.continuation.neutral_benchmark` and print its tables."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument(
        "--repeat",
        type=int,
        default=7,
        help="rounds over all configurations (the minimum over all timed calls is kept)",
    )
    parser.add_argument(
        "--min-time", type=float, default=0.5, help="seconds of timed calls per configuration, at least"
    )
    args = parser.parse_args(argv)
    print(format_tables(neutral_benchmark(repeat=args.repeat, columns=COLUMNS, min_time=args.min_time)))


if __name__ == "__main__":
    main()
