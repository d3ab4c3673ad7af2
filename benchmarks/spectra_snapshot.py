"""Every array of the kernel's spectra on a seeded set of points, to compare two versions bit for bit.

A change of the kernel that is meant to make it faster must not move an eigenvalue, an error
bound, a neutral flag or a stability flag. Run this script with each version (the old commit
from a ``git worktree`` on ``PYTHONPATH``) and compare::

    git worktree add /tmp/base 2083ca0
    (cd /tmp && PYTHONPATH=/tmp/base python /path/to/benchmarks/spectra_snapshot.py /tmp/old.npz)
    python benchmarks/spectra_snapshot.py /tmp/new.npz
    python benchmarks/spectra_snapshot.py --compare /tmp/old.npz /tmp/new.npz

The points: ``--points`` (default 10^5) of :func:`stability.bench.eigen.domain_sample` (seed 0),
and a boundary set with ``mask_unphysical=True``: q and sigma at the exact domain bounds
(``sigma_max``) and one and two ulp either side, points with ``mu q^2`` within a few ulp of 1,
and points beyond the bounds (flag -1, NaN). Saved: ``spectrum()``'s eigenvalues, error
bounds, neutral flags, stability flags and inside mask, for the default (compiled kernel) path
and the interpreted kernel on a subset.
"""

from __future__ import annotations

import argparse
import math
import sys

import numpy as np


def boundary_points(n: int = 2000, seed: int = 3) -> dict[str, np.ndarray]:
    from stability.parameters import sigma_max

    rng = np.random.default_rng(seed)
    mu = rng.uniform(0.5, 6.0, n)
    q = rng.uniform(-0.99, 0.99, n) / np.sqrt(mu)
    s = np.asarray(sigma_max(q, mu))
    k = rng.integers(-2, 3, n)
    sigma = s.copy()
    for j in range(n):
        for _ in range(abs(int(k[j]))):
            sigma[j] = math.nextafter(sigma[j], math.inf if k[j] > 0 else -math.inf)
    qb = 1.0 / np.sqrt(mu[: n // 4])
    qb = qb * (1.0 + rng.integers(-6, 7, qb.size) * 2.0**-52)
    q[: n // 4] = qb
    sigma[: n // 4] = 1e-3
    fr_inv = rng.uniform(0.0, 3.0, n)
    alpha_v = 10.0 ** rng.uniform(-2.0, 1.0, n)
    return {"q": q, "fr_inv": fr_inv, "sigma": sigma, "alpha_v": alpha_v, "mu": mu}


def snapshot(points: int) -> dict[str, np.ndarray]:
    try:  # the suites live beside the package now (benchmarks/suites); older trees installed them
        from stability.bench.eigen import domain_sample
    except ImportError:
        sys.path.insert(0, str(__import__("pathlib").Path(__file__).resolve().parent))
        from suites.eigen import domain_sample

    import stability

    out = {}
    for name, p, mask in (("sample", domain_sample(points, seed=0), False), ("boundary", boundary_points(), True)):
        sp = stability.spectrum("sliding", **p, mask_unphysical=mask)
        for field in ("eigenvalues", "error_bound", "neutral", "stability", "inside"):
            out[f"{name}/{field}"] = np.asarray(getattr(sp, field))
    from stability.linear.kernel import checked_model_spectrum

    small = domain_sample(2000, seed=7)
    sp = checked_model_spectrum("sliding", small, engine="python").spectrum
    for field, v in zip(("eigenvalues", "error_bound", "neutral", "stability"), sp):
        out[f"python/{field}"] = np.asarray(v)
    return out


def compare(a: str, b: str) -> int:
    x, y = np.load(a), np.load(b)
    bad = 0
    for k in sorted(set(x.files) | set(y.files)):
        if k not in x.files or k not in y.files:
            print(f"{k}: only in one file")
            bad += 1
            continue
        u, v = x[k], y[k]
        same = u.dtype == v.dtype and u.shape == v.shape and u.tobytes() == v.tobytes()
        print(f"{k:28s} {u.shape} {'identical' if same else 'DIFFERENT'}")
        bad += not same
    print(f"{len(x.files)} arrays, {bad} different")
    return 1 if bad else 0


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("out", nargs="?", help="the .npz to write")
    ap.add_argument("--points", type=int, default=100_000)
    ap.add_argument("--compare", nargs=2, metavar=("OLD", "NEW"))
    a = ap.parse_args(argv)
    if a.compare:
        return compare(*a.compare)
    np.savez(a.out, **snapshot(a.points))
    return 0


if __name__ == "__main__":
    sys.exit(main())
