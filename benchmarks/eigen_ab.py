"""A/B of the kernel's speed: two versions of the package, interleaved, on a loaded machine.

``stability.eigenvalues`` (domain check, error bounds and decision included) on ``--points``
random sliding points (``benchmarks/suites/eigen.py`` ``domain_sample``, seed 0), against
``numpy.linalg.eigvals(numpy.linalg.solve(M, A))`` batched on the same points in the same
process (the eigen suite's baseline), best of ``--repeat`` calls each, interleaved in the
process. Also the pieces, to see where time goes: the fused loop alone
(:func:`stability.linear.kernel.checked_model_spectrum`), the loop without the domain test
(:func:`~stability.linear.kernel.model_spectrum` with a mask of every point), and the same on
one thread.

Each version runs in its own process (``PYTHONPATH``), ``--rounds`` times, alternating
A B A B ..., so that a burst of load from other users of the machine hits both alike; the
report gives per method the minimum and the median over rounds of each version and their
ratio (B/A of the time per point), and each version's ratio to numpy (numpy time / eigenvalues
time, from the same process)::

    git worktree add /tmp/base 2083ca0
    python benchmarks/eigen_ab.py --a /tmp/base --b . --points 1000000 --rounds 4

On a loaded machine, ``--clock thread`` times the one-thread methods and numpy (whose batched
call runs in the calling thread) by the CPU time of the calling thread (``time.thread_time``),
which does not count the time the thread waits for a core, and leaves out the parallel
methods: the ratios then survive a load that makes the wall-clock times meaningless.

Run one process only (``--child``) to print its JSON line.
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import time


def child(points: int, repeat: int, clock: str = "wall") -> dict:
    import numpy as np

    import stability

    try:  # the suites live beside the package now (benchmarks/suites); older trees installed them
        from stability.bench.eigen import domain_sample
    except ImportError:
        sys.path.insert(0, str(__import__("pathlib").Path(__file__).resolve().parent))
        from suites.eigen import domain_sample
    from stability.linear import kernel as K
    from stability.models import get_model

    p = domain_sample(points, seed=0)
    M, A = get_model("sliding").matrices(**p)
    every = np.ones(points, dtype=bool)  # the masked loop (model_spectrum without a mask runs the fused one at 1d78bea)
    fns = {
        "eigenvalues": lambda: stability.eigenvalues("sliding", **p),
        "fused loop": lambda: K.checked_model_spectrum("sliding", p),
        "no domain test": lambda: K.model_spectrum("sliding", p, every),
        "fused loop, 1 thread": lambda: K.checked_model_spectrum("sliding", p, parallel=False),
        "no domain test, 1 thread": lambda: K.model_spectrum("sliding", p, every, parallel=False),
        "numpy batched": lambda: np.linalg.eigvals(np.linalg.solve(M, A)),
    }
    now = time.perf_counter
    if clock == "thread":
        now = time.thread_time
        fns = {k: f for k, f in fns.items() if "1 thread" in k or "numpy" in k}
    for f in fns.values():
        f()
    best = dict.fromkeys(fns, float("inf"))
    for _ in range(repeat):
        for k, f in fns.items():
            t = now()
            f()
            best[k] = min(best[k], now() - t)
    ns = {k: v / points * 1e9 for k, v in best.items()}
    if clock == "thread":
        ns["x numpy, 1 thread"] = best["numpy batched"] / best["fused loop, 1 thread"]
    else:
        ns["x numpy"] = best["numpy batched"] / best["eigenvalues"]
    return ns


def main(argv: list[str] | None = None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--a", default=None, help="source tree of version A (PYTHONPATH), e.g. /tmp/base")
    ap.add_argument("--b", default=".", help="source tree of version B")
    ap.add_argument("--points", type=int, default=1_000_000)
    ap.add_argument("--repeat", type=int, default=3, help="calls per method and process (best kept)")
    ap.add_argument("--rounds", type=int, default=4, help="processes per version, interleaved")
    ap.add_argument("--clock", choices=("wall", "thread"), default="wall", help="see the module docstring")
    ap.add_argument("--child", action="store_true", help=argparse.SUPPRESS)
    a = ap.parse_args(argv)
    if a.child:
        print(json.dumps(child(a.points, a.repeat, a.clock)))
        return
    runs: dict[str, list[dict]] = {"A": [], "B": []}
    for r in range(a.rounds):
        for label, tree in (("A", a.a), ("B", a.b)):
            if tree is None:
                continue
            env = dict(os.environ, PYTHONPATH=os.path.abspath(tree))
            out = subprocess.run(
                [
                    sys.executable,
                    os.path.abspath(__file__),
                    "--child",
                    "--points",
                    str(a.points),
                    "--repeat",
                    str(a.repeat),
                    "--clock",
                    a.clock,
                ],
                env=env,
                capture_output=True,
                text=True,
                check=True,
                cwd="/tmp",
            )
            res = json.loads(out.stdout.strip().splitlines()[-1])
            runs[label].append(res)
            print(f"round {r} {label}: " + ", ".join(f"{k} {v:.1f}" for k, v in res.items()), flush=True)
    keys = list((runs["B"] or runs["A"])[0])
    print(
        f"\n{'method':28s} {'A min':>8s} {'A med':>8s} {'B min':>8s} {'B med':>8s} {'B/A min':>8s} {'B/A med':>8s}"
        "   (ns per point; 'x numpy': ratio)"
    )
    for k in keys:
        row = []
        for label in ("A", "B"):
            v = [r[k] for r in runs[label]]
            row += [min(v), statistics.median(v)] if v else [float("nan")] * 2
        mn = max if k.startswith("x numpy") else min
        ra = [r[k] for r in runs["A"]]
        rb = [r[k] for r in runs["B"]]
        if ra and rb:
            row[0], row[2] = mn(ra), mn(rb)
        print(f"{k:28s} " + " ".join(f"{x:8.1f}" for x in row) + f" {row[2] / row[0]:8.3f} {row[3] / row[1]:8.3f}")
    print("('x numpy': best = the largest ratio)")


if __name__ == "__main__":
    main()
