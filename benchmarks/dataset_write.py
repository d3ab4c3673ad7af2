"""Time of :func:`stability.grids.netcdf.write_dataset` against xarray's bare ``to_netcdf``.

In one process, interleaved over ``--rounds``: a dataset of ``--mbytes`` MB of float64 (one 2-D
variable, in memory) written by ``Dataset.to_netcdf`` (the baseline: no temporary file, no
interruption points) and right after it by ``write_dataset`` (a temporary file, slabs of 16 MiB
with an interruption point each, the commit). Reported: the median of each and their ratio.
The first round (imports, page cache) is dropped.

    python benchmarks/dataset_write.py --out-dir /tmp --rounds 5
    # the previous code, same machine (A/B): a source tree of it on PYTHONPATH
    python benchmarks/dataset_write.py --out-dir /tmp --rounds 5 --tree /tmp/base
"""

from __future__ import annotations

import argparse
import os
import statistics
import subprocess
import sys
import time


def measure(mbytes: float, out_dir: str, rounds: int) -> tuple[float, float]:
    import numpy as np
    import xarray as xr

    from stability.grids.netcdf import write_dataset

    rows = int(mbytes * 1e6 / 8 / 5000)
    ds = xr.Dataset({"g": (("a", "b"), np.random.default_rng(0).random((rows, 5000)))})
    bare, ours = [], []
    for _ in range(rounds + 1):
        for path in ("bare.nc", "ours.nc"):
            if os.path.exists(os.path.join(out_dir, path)):
                os.unlink(os.path.join(out_dir, path))
        t = time.perf_counter()
        ds.to_netcdf(os.path.join(out_dir, "bare.nc"))
        bare.append(time.perf_counter() - t)
        t = time.perf_counter()
        write_dataset(ds, os.path.join(out_dir, "ours.nc"))
        ours.append(time.perf_counter() - t)
    return statistics.median(bare[1:]), statistics.median(ours[1:])


def main() -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--out-dir", required=True)
    p.add_argument("--mbytes", type=float, default=400.0)
    p.add_argument("--rounds", type=int, default=5)
    p.add_argument("--tree", help="run with this source tree on PYTHONPATH (A/B against older code)")
    a = p.parse_args()
    if a.tree:
        env = dict(os.environ, PYTHONPATH=a.tree)
        argv = [sys.executable, __file__, "--out-dir", a.out_dir, "--mbytes", str(a.mbytes), "--rounds", str(a.rounds)]
        return subprocess.call(argv, env=env, cwd=a.tree)
    bare, ours = measure(a.mbytes, a.out_dir, a.rounds)
    print(f"{a.mbytes:g} MB: to_netcdf {bare:.3f} s, write_dataset {ours:.3f} s, ratio {ours / bare:.2f}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
