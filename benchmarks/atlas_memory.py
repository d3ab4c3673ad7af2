"""Peak memory and time of a chunked atlas written to disk (default: 10^8 grid points).

Runs ``tippe atlas --chunks ...`` as a child process and samples the resident memory of it and
of its children (dask workers, if ``--workers`` is passed through) every 0.1 s with psutil;
prints the peak of the sum, the child's own ``ru_maxrss``, the wall time and the file size.

    python benchmarks/atlas_memory.py --output /tmp/atlas_1e8.nc [extra tippe atlas flags]

The grid: q 1000 x fr_inv 100 x sigma 100 x alpha_v 10 (sliding model, mu = 2.28, masked
outside the physical domain), in chunks of 20 x 100 x 100 x 10 = 2e6 points (CHUNKS).
"""

from __future__ import annotations

import argparse
import os
import resource
import subprocess
import sys
import time

import psutil

GRID = [
    "--model",
    "sliding",
    "--q",
    "-0.6:0.6:1000",
    "--fr-inv",
    "0:3:100",
    "--sigma",
    "0.05:1.95:100",
    "--alpha-v",
    "0.01:10:10",
    "--mask-unphysical",
]
CHUNKS = "q=20"


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--output", required=True)
    ap.add_argument("--chunks", default=CHUNKS)
    args, extra = ap.parse_known_args()
    cmd = [
        sys.executable,
        "-m",
        "stability",
        "atlas",
        *GRID,
        "--chunks",
        args.chunks,
        "-o",
        args.output,
        "--overwrite",
        "--no-progress",
        *extra,
    ]
    t0 = time.perf_counter()
    proc = subprocess.Popen(cmd)
    ps = psutil.Process(proc.pid)
    peak = 0
    while proc.poll() is None:
        try:
            rss = ps.memory_info().rss + sum(c.memory_info().rss for c in ps.children(recursive=True))
            peak = max(peak, rss)
        except psutil.Error:
            pass
        time.sleep(0.1)
    wall = time.perf_counter() - t0
    child_max = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss / 1024
    size = os.path.getsize(args.output) / 1e9 if os.path.exists(args.output) else float("nan")
    print(
        f"exit {proc.returncode}; wall {wall:.1f} s; peak RSS (sampled, process tree) {peak / 2**20:.0f} MB; "
        f"ru_maxrss of the child {child_max:.0f} MB; file {size:.2f} GB; points 1e8; chunks {args.chunks}"
    )
    return proc.returncode


if __name__ == "__main__":
    sys.exit(main())
