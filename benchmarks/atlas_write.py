"""Time and size of a chunked atlas written to netCDF, against the bare spectra, in one process.

The grid of ``benchmarks/atlas_memory.py`` with ``--q-points`` values of q (default 100: 10^7
points; 1000 gives its 10^8), chunks q=20, sliding model, masked outside the domain. In one
process, interleaved over ``--rounds``: for each layout the bare spectra (``stability.spectrum``
on each chunk, results dropped: what any atlas must compute) and right after them
:func:`stability.grids.chunked.write_atlas` of the lazy atlas in that layout (``--layouts``; e.g. ``all`` = every variable in float64,
uncompressed, the default file; ``map+zstd+f32`` = the leading growth rate and the flag, zstd,
float32). Reported per layout: min and median wall time, the ratio of each write to the bare spectra
measured just before it, and bytes per grid point on disk; the same for the CPU time of the
process (all its threads: what a loaded machine does not change much).

    python benchmarks/atlas_write.py --out-dir /tmp --rounds 2
    # the previous code, same machine, one after the other (A/B):
    python benchmarks/atlas_write.py --out-dir /tmp --rounds 2 --tree /tmp/base --layouts all

``--tree`` runs the measurement in a child process with that source tree on ``PYTHONPATH``
(a commit without ``variables=`` writes ``all`` only).
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import time

LAYOUTS = ("all", "all+zstd", "all+zstd+f32", "map", "map+zstd+f32", "map+zlib+f32")


def _kwargs(layout: str) -> dict:
    parts = layout.split("+")
    kw: dict = {}
    if parts[0] == "map":
        kw["variables"] = "map"
    for p in parts[1:]:
        if p in ("zlib", "zstd"):
            kw["compression"] = p
        elif p == "f32":
            kw["float32"] = True
    return kw


def measure(q_points: int, out_dir: str, layouts: list[str], rounds: int) -> dict:
    import numpy as np

    import stability
    from stability.grids.chunked import write_atlas

    grid = dict(
        q=np.linspace(-0.6, 0.6, q_points),
        fr_inv=np.linspace(0, 3, 100),
        sigma=np.linspace(0.05, 1.95, 100),
        alpha_v=np.linspace(0.01, 10, 10),
    )
    n = q_points * 100 * 100 * 10
    stability.spectrum("sliding", q=0.1, fr_inv=0.1, sigma=1.0, alpha_v=0.5)  # load the compiled loop

    def bare() -> None:
        for i in range(0, q_points, 20):
            part = dict(
                grid,
                q=grid["q"][i : i + 20].reshape(-1, 1, 1, 1),
                fr_inv=grid["fr_inv"].reshape(1, -1, 1, 1),
                sigma=grid["sigma"].reshape(1, 1, -1, 1),
                alpha_v=grid["alpha_v"].reshape(1, 1, 1, -1),
            )
            stability.spectrum("sliding", mask_unphysical=True, **part)

    times: dict[str, list[float]] = {"bare spectra": []}
    sizes: dict[str, int] = {}
    ratios: dict[str, list[float]] = {}
    cpu: dict[str, list[float]] = {"bare spectra": []}  # CPU seconds of the process (all threads)
    cpu_ratios: dict[str, list[float]] = {}
    for _ in range(rounds):
        for layout in layouts:
            t, c = time.perf_counter(), time.process_time()
            bare()
            tb, cb = time.perf_counter() - t, time.process_time() - c
            times["bare spectra"].append(tb)
            cpu["bare spectra"].append(cb)
            path = os.path.join(out_dir, f"atlas_write_{layout}.nc")
            ds = stability.atlas("sliding", mask_unphysical=True, chunks={"q": 20}, **grid)
            t, c = time.perf_counter(), time.process_time()
            write_atlas(ds, path, overwrite=True, **_kwargs(layout))
            tw, cw = time.perf_counter() - t, time.process_time() - c
            times.setdefault(layout, []).append(tw)
            ratios.setdefault(layout, []).append(tw / tb)
            cpu.setdefault(layout, []).append(cw)
            cpu_ratios.setdefault(layout, []).append(cw / cb)
            sizes[layout] = os.path.getsize(path)
            os.remove(path)
    return {
        "points": n,
        "times": times,
        "ratios": ratios,
        "cpu": cpu,
        "cpu_ratios": cpu_ratios,
        "bytes_per_point": {k: v / n for k, v in sizes.items()},
    }


def main(argv: list[str] | None = None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--q-points", type=int, default=100, help="values of q (x 10^5 points)")
    ap.add_argument("--out-dir", default="/tmp")
    ap.add_argument("--layouts", default=",".join(LAYOUTS))
    ap.add_argument("--rounds", type=int, default=2)
    ap.add_argument("--tree", help="run in a child process with this source tree on PYTHONPATH")
    ap.add_argument("--json", action="store_true", help="print the JSON only")
    a = ap.parse_args(argv)
    layouts = a.layouts.split(",")
    if a.tree:
        env = dict(os.environ, PYTHONPATH=os.path.abspath(a.tree))
        cmd = [
            sys.executable,
            os.path.abspath(__file__),
            "--q-points",
            str(a.q_points),
            "--out-dir",
            os.path.abspath(a.out_dir),
            "--layouts",
            a.layouts,
            "--rounds",
            str(a.rounds),
            "--json",
        ]
        res = json.loads(
            subprocess.run(cmd, env=env, cwd="/tmp", capture_output=True, text=True, check=True)
            .stdout.strip()
            .splitlines()[-1]
        )
    else:
        res = measure(a.q_points, a.out_dir, layouts, a.rounds)
    if a.json:
        print(json.dumps(res))
        return
    print(
        f"{res['points']:.0e} points; wall s (min / median over rounds), ratio to the bare spectra of the "
        "same round (min / median), bytes per point on disk"
    )
    for k, v in res["times"].items():
        r = res["ratios"].get(k)
        cr = res.get("cpu_ratios", {}).get(k)
        extra = (
            f"  x bare {min(r):.2f} / {statistics.median(r):.2f}  {res['bytes_per_point'][k]:6.2f} B/pt" if r else ""
        )
        if "cpu" in res:
            c = res["cpu"][k]
            extra += f"  CPU {min(c):7.2f} s" + (f" x bare {min(cr):.2f} / {statistics.median(cr):.2f}" if cr else "")
        print(f"{k:16s} {min(v):7.2f} / {statistics.median(v):7.2f} s{extra}")


if __name__ == "__main__":
    main()
