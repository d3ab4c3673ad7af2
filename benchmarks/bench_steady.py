"""Benchmark: the final state by Jellett's integral against simulations, case by case.

A thin script: the measurement is :mod:`suites.steady` (the same code as
``python benchmarks/run.py --suite steady``); this prints its per-case table (the reference end tilt,
``t_0.01``, the cost and error of a simulation to it, the cost of the prediction) and the
branch and class-map numbers.

Run: ``python3 benchmarks/bench_steady.py [--repeat 3] [--quick]`` (about a minute).
"""

from __future__ import annotations

import argparse

from suites.steady import branch_measurements, class_map_measurements, final_state_cases, format_table


def main(argv: list[str] | None = None) -> None:
    """Print the tables of :mod:`suites.steady`."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=3, help="timed repeats (the best is kept)")
    parser.add_argument("--quick", action="store_true", help="three cases, two class-map sizes")
    args = parser.parse_args(argv)
    print(format_table(final_state_cases(repeat=args.repeat, quick=args.quick)))
    b = branch_measurements(repeat=max(args.repeat, 7))
    print(
        f"\nbranch of the paper's top, {b['points']} points with spectra and flags "
        "(time, largest relative error of lam vs the closed form):"
    )
    for key in ("compiled", "python", "brentq"):
        print(f"  {key:<9} {b[key][0] * 1e3:8.2f} ms  {b[key][1]:.1e}")
    c = class_map_measurements(repeat=args.repeat, quick=args.quick)
    print("\nclass map (stability.top_class, mask_unphysical=True):")
    for n, sec, mism in c["sizes"]:
        print(f"  {n:>9} tops {sec:8.3f} s  mismatches vs Hugenholtz {mism}")
    print(f"  per top (a loop of scalar calls): {c['per_top'] * 1e6:.1f} us")


if __name__ == "__main__":
    main()
