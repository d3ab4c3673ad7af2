"""Small dense linear algebra for compiled code: Gaussian elimination with partial pivoting.

:func:`solve_dense` solves a small system in place, written with scalar loops: LAPACK calls from
numba carry an overhead comparable to the work at this size. Its pieces :func:`swap_rows` and
:func:`back_substitute` also serve :func:`continuation.compiled.solve_det`. Users outside this
package: the compiled right-hand sides of the nonlinear models (:mod:`stability.nonlinear`),
whose sliding and rolling spheres solve a 6 x 6 system (three angular accelerations, two
horizontal unknowns, the normal force) at every evaluation.

The functions are generic in the dtype: called with complex arrays they are compiled for
complex128, which is what a complex-step Jacobian uses (the pivot choice uses ``abs`` and does
not break analyticity). Generic: nothing here knows about tops.
"""

from __future__ import annotations

import numpy as np
from numba import njit

__all__ = ["solve_dense", "swap_rows", "back_substitute"]


@njit(cache=True)
def swap_rows(a: np.ndarray, b: np.ndarray, i: int, j: int) -> None:
    """Exchange rows ``i`` and ``j`` of the system ``a x = b`` in place (a pivoting step; also
    used by :func:`continuation.compiled.solve_det`)."""
    for k in range(a.shape[1]):
        tmp = a[i, k]
        a[i, k] = a[j, k]
        a[j, k] = tmp
    tmp = b[i]
    b[i] = b[j]
    b[j] = tmp


@njit(cache=True)
def back_substitute(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Solve the upper-triangular system left in ``a`` by elimination, in place in ``b``
    (returned); also used by :func:`continuation.compiled.solve_det`."""
    n = b.shape[0]
    for c in range(n - 1, -1, -1):
        s = b[c]
        for j in range(c + 1, n):
            s -= a[c, j] * b[j]
        b[c] = s / a[c, c]
    return b


@njit(cache=True)
def solve_dense(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Solve ``a x = b`` in place by Gaussian elimination with partial pivoting.

    Parameters
    ----------
    a : numpy.ndarray, shape (n, n)
        Matrix; overwritten.
    b : numpy.ndarray, shape (n,)
        Right-hand side; overwritten with the solution, which is also returned.

    Returns
    -------
    numpy.ndarray
        The solution ``x`` (the array ``b``).
    """
    n = b.shape[0]
    for c in range(n):
        piv = c
        big = abs(a[c, c])
        for r in range(c + 1, n):
            v = abs(a[r, c])
            if v > big:
                big = v
                piv = r
        if piv != c:
            swap_rows(a, b, c, piv)
        inv = 1.0 / a[c, c]
        for r in range(c + 1, n):
            m = a[r, c] * inv
            if m != 0:
                for j in range(c + 1, n):
                    a[r, j] -= m * a[c, j]
                b[r] -= m * b[c]
    return back_substitute(a, b)
