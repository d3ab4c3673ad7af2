"""Work-precision of the integrators of the nonlinear runs: a thin wrapper.

The measuring code is :mod:`suites.integrators` (one implementation, also behind
``python benchmarks/run.py --suite integrators``, which draws the chart ``atlases/work_precision_integrators.png``).
This script prints the measurements as a table.

Usage: python benchmarks/work_precision.py [--quick]
"""

from __future__ import annotations

import sys

from run import summary_lines
from suites.integrators import integrator_work_precision


def main(quick: bool = False) -> None:
    """Print one line per method and setting (time per run, error, ratios to the baselines)."""
    results = integrator_work_precision(quick=quick)
    for panel, title in (
        ("", "the paper's Fr^-1 = 0.3 run: 90-degree crossing time vs DOP853 rtol 1e-13"),
        ("stiff", "stiff slip mode (linear regime, 200 time units, rtol 1e-6): final tilt vs Radau rtol 1e-10"),
    ):
        print(title)
        rs = [r for r in results if r.panel == panel]
        for line, r in zip(summary_lines(rs, "run", ("error",)), rs):
            print(f"{line}  nfev {r.extra['nfev']}")


if __name__ == "__main__":
    main(quick="--quick" in sys.argv)
