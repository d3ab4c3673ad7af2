"""The client's memory while two dask workers write an atlas into a Zarr store, as the atlas grows.

For each size (default 10^6 and 10^7 points: q N x fr_inv 100 x sigma 100, sliding, alpha_v 0.5,
masked; chunks of q=10, i.e. 10^5 points, 7.4 MB each), in one process with one LocalCluster
of two worker processes (one thread each):

* ``write_atlas(lazy_atlas, "<dir>/atlas_N.zarr", client=client)`` (the workers compute and
  write the regions; the client gets two flags per chunk back);
* the client's resident memory sampled every 20 ms (psutil, this process only; the workers
  are other processes) and its peak of traced allocations (tracemalloc: numpy included), both
  relative to just before the write; the workers' peak RSS; the wall time; the store's size.

Baseline in the same run (``--netcdf``): the same atlas written to netCDF from the same cluster,
where every chunk comes back to the client, which writes the file.

With ``--check`` the store of the smallest size is read back with ``stability.open_atlas`` and
compared with the in-memory atlas (``xarray.testing.assert_identical`` and the bytes of every
float variable): bit for bit.

    python benchmarks/atlas_zarr.py --dir /tmp/zarr_bench --sizes 1e6 1e7 --check
"""

from __future__ import annotations

import argparse
import contextlib
import shutil
import threading
import time
import tracemalloc
from pathlib import Path

import numpy as np
import psutil


def _grid(n: float) -> dict:
    nq = int(round(n / 1e4))
    return dict(q=np.linspace(-0.6, 0.6, nq), fr_inv=np.linspace(0, 3, 100), sigma=np.linspace(0.05, 1.95, 100))


class _Sampler:
    """Peak RSS of some processes, sampled every 20 ms in a thread."""

    def __init__(self, procs: list[psutil.Process]) -> None:
        self.procs, self.peak, self._stop = procs, [0] * len(procs), threading.Event()
        self._thread = threading.Thread(target=self._run, daemon=True)

    def _run(self) -> None:
        while not self._stop.is_set():
            for i, p in enumerate(self.procs):
                with contextlib.suppress(psutil.Error):
                    self.peak[i] = max(self.peak[i], p.memory_info().rss)
            time.sleep(0.02)

    def __enter__(self) -> _Sampler:  # noqa: PYI034
        self._thread.start()
        return self

    def __exit__(self, *exc: object) -> None:
        self._stop.set()
        self._thread.join()


def _size(path: Path) -> int:
    if path.is_file():
        return path.stat().st_size
    return sum(p.stat().st_size for p in path.rglob("*") if p.is_file())


def _measure(client, ds, path: Path) -> dict:
    from stability.grids.chunked import write_atlas

    me = psutil.Process()
    workers = [psutil.Process(pid) for pid in client.run(lambda: __import__("os").getpid()).values()]
    base = me.memory_info().rss
    tracemalloc.start()
    t0 = time.perf_counter()
    with _Sampler([me, *workers]) as s:
        write_atlas(ds, path, client=client, overwrite=True)
    wall = time.perf_counter() - t0
    traced = tracemalloc.get_traced_memory()[1]
    tracemalloc.stop()
    return {
        "wall": wall,
        "client_rss": (s.peak[0] - base) / 2**20,
        "client_traced": traced / 2**20,
        "workers_rss": sum(s.peak[1:]) / 2**20,
        "size": _size(path) / 1e9,
    }


def main() -> None:
    import stability
    from stability.grids.cluster import dask_client

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--dir", required=True, help="directory for the stores (removed at the end)")
    ap.add_argument("--sizes", nargs="+", type=float, default=[1e6, 1e7])
    ap.add_argument("--chunks", type=int, default=10, help="chunk size along q (x 10^4 points)")
    ap.add_argument("--netcdf", action="store_true", help="also write netCDF from the same cluster (baseline)")
    ap.add_argument("--check", action="store_true", help="compare the smallest store with the in-memory atlas")
    args = ap.parse_args()
    root = Path(args.dir)
    root.mkdir(parents=True, exist_ok=True)
    kw = dict(alpha_v=0.5, mask_unphysical=True)
    try:
        with dask_client(workers=2) as client:
            warm = stability.atlas("sliding", chunks={"q": 2}, **kw, **_grid(4e4))
            _measure(client, warm, root / "warm.zarr")  # imports, compiled kernels, first tasks
            for n in args.sizes:
                ds = stability.atlas("sliding", chunks={"q": args.chunks}, **kw, **_grid(n))
                kinds = [("zarr", ".zarr")] + ([("netcdf", ".nc")] if args.netcdf else [])
                for kind, suffix in kinds:
                    r = _measure(client, ds, root / f"atlas_{n:.0e}{suffix}")
                    print(
                        f"{kind:6s} {n:.0e} points, {len(ds.chunksizes['q'])} chunks: wall {r['wall']:.1f} s; "
                        f"client peak RSS +{r['client_rss']:.0f} MB, traced {r['client_traced']:.1f} MB; "
                        f"workers peak RSS {r['workers_rss']:.0f} MB; on disk {r['size']:.2f} GB"
                    )
        if args.check:
            import xarray as xr

            n = min(args.sizes)
            read = stability.open_atlas(root / f"atlas_{n:.0e}.zarr")
            ref = stability.atlas("sliding", **kw, **_grid(n))
            read.attrs.pop("history"), ref.attrs.pop("history")
            xr.testing.assert_identical(read, ref)
            for v in ("growth_rate", "frequency", "eigenvalue_error_bound", "max_growth_rate", "leading_growth_rate"):
                assert read[v].values.tobytes() == ref[v].values.tobytes(), v
            print(f"check: the {n:.0e}-point store equals the in-memory atlas bit for bit")
    finally:
        shutil.rmtree(root, ignore_errors=True)


if __name__ == "__main__":
    main()
