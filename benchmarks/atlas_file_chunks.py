"""Time to write one chunk of the atlas to netCDF by file-chunk shape and compression level.

One grid chunk of ``benchmarks/atlas_memory.py`` (q values 490-509 of its 1000, fr_inv 100 x
sigma 100 x alpha_v 10: 2x10^6 points, inside the domain for the most part) is computed once;
then its seven variables (as ``write_atlas(float32=True)`` stores them, or in float64
uncompressed) are written into a new netCDF file with file (HDF5) chunks of ``qc`` values of q
(the other dimensions whole; ``qc = 20`` is one file chunk per grid chunk, 24 MB for a modal
variable in float32) and zstd at ``level`` with the byte shuffle. Wall time of the writes and
the close, best of ``--rounds`` interleaved rounds; bytes per point of the file.

    python benchmarks/atlas_file_chunks.py --rounds 3
"""

from __future__ import annotations

import argparse
import os
import time

import numpy as np

#: (float32, file chunk in values of q, zstd level or None: uncompressed)
SETTINGS = [
    (True, 20, 1),
    (True, 5, 1),
    (True, 2, 1),
    (True, 1, 1),
    (True, 2, -1),
    (True, 2, -3),
    (False, 20, None),
    (False, 2, None),
]


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--path", default="/tmp/atlas_file_chunks.nc")
    a = ap.parse_args()
    import netCDF4

    import stability
    from stability.grids.chunked import _as_float32
    from stability.grids.store import slice_block

    grid = dict(
        q=np.linspace(-0.6, 0.6, 1000)[490:510],
        fr_inv=np.linspace(0, 3, 100),
        sigma=np.linspace(0.05, 1.95, 100),
        alpha_v=np.linspace(0.01, 10, 10),
    )
    ds = stability.atlas("sliding", mask_unphysical=True, chunks={"q": 20}, **grid)
    dims = list(ds["stability"].dims)
    block = slice_block(ds.compute(), {})  # the arrays of one chunk: the whole grid
    n = int(np.prod([ds.sizes[d] for d in dims]))
    variants = {}
    for f32 in (True, False):
        c = {
            k: (_as_float32(k, v) if f32 and v.dtype.kind == "f" else np.ascontiguousarray(v)) for k, v in block.items()
        }
        c["max_growth_rate"] = np.ascontiguousarray(c["growth_rate"][..., 0])
        c["leading_growth_rate"] = c["max_growth_rate"].copy()
        variants[f32] = c
    best: dict = {}
    for _ in range(a.rounds):
        for f32, qc, level in SETTINGS:
            t = time.perf_counter()
            with netCDF4.Dataset(a.path, "w") as nc:
                for d in dims:
                    nc.createDimension(d, ds.sizes[d])
                nc.createDimension("mode", 3)
                for k, v in variants[f32].items():
                    kw = {} if level is None else dict(compression="zstd", complevel=level, shuffle=True)
                    var = nc.createVariable(
                        k, v.dtype, dims + (["mode"] if v.ndim == 5 else []), chunksizes=(qc, *v.shape[1:]), **kw
                    )
                    var[...] = v
            t = time.perf_counter() - t
            key = (f32, qc, level)
            best[key] = (min(best.get(key, (np.inf,))[0], t), os.path.getsize(a.path) / n)
    os.remove(a.path)
    print(f"{n:.0e} points, one grid chunk; best of {a.rounds}")
    for (_f32, qc, level), (t, b) in best.items():
        what = f"float32, zstd level {level}" if level is not None else "float64, uncompressed"
        print(f"{what:24s} file chunk q={qc:<3d} {t:6.3f} s  {b:6.2f} B/pt")


if __name__ == "__main__":
    main()
