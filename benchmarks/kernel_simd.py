"""Whether the kernel's block loops are packed: the SIMD instructions of the compiled model loop.

The model loops of :mod:`stability.linear.kernel` solve their points in blocks (structure of
arrays, loops with no branch on data, ``kernel._block_solve``) so that the compiler emits packed
arithmetic. This script compiles the sliding model's fused loop (serial) afresh, in a new numba
cache directory (numba's ``inspect_asm`` is disabled for code loaded from its cache), and counts
the arithmetic instructions of its machine code by kind: packed (``...pd`` on ``xmm``, ``ymm``
or ``zmm`` registers) and scalar (``...sd``). The divider's instructions (``vsqrtpd``,
``vdivpd``) are the ones that matter: every square root and division of a block's generic cubic
should appear packed (one of each kind per loop version the compiler writes)::

    python benchmarks/kernel_simd.py

Public numba API only (``NUMBA_CACHE_DIR``, ``Dispatcher.inspect_asm``); the kernel's private
helpers are this package's own.
"""

from __future__ import annotations

import collections
import os
import re
import sys
import tempfile


def main() -> None:
    os.environ["NUMBA_CACHE_DIR"] = tempfile.mkdtemp(prefix="kernel_simd_")  # before numba is imported
    import numpy as np

    from stability.jit import cached
    from stability.linear import kernel
    from stability.models import get_model

    rng = np.random.default_rng(0)
    mu = rng.uniform(0.5, 6.0, 1000)
    q = rng.uniform(-0.9, 0.9, 1000) / np.sqrt(mu)
    sigma = (1.0 - mu * q * q) * rng.uniform(0.1, 1.9, 1000)
    p = dict(q=q, fr_inv=rng.uniform(0, 3, 1000), sigma=sigma, alpha_v=np.full(1000, 0.3), mu=mu)
    kernel.checked_model_spectrum("sliding", p, parallel=False, engine="compiled")
    loop = cached(kernel._model_kernels(get_model("sliding")).checked)
    asm = loop.inspect_asm(loop.signatures[0])
    counts: collections.Counter = collections.Counter()
    for m in re.finditer(r"^\s+(v?(?:sqrt|div|mul|add|sub)(?:pd|sd))\s+[^\n]*?%([xyz]mm)\d+\s*$", asm, re.MULTILINE):
        op, reg = m.groups()
        counts[op, reg if op.endswith("pd") else "scalar"] += 1
    print(f"{'instruction':12s} {'registers':9s} {'count':>6s}   (the sliding model's fused loop, serial)")
    for (op, reg), c in sorted(counts.items()):
        print(f"{op:12s} {reg:9s} {c:6d}")
    packed = sum(c for (op, reg), c in counts.items() if op in ("vsqrtpd", "vdivpd"))
    print(f"packed square roots and divisions: {packed}")
    sys.exit(0 if packed else 1)


if __name__ == "__main__":
    main()
