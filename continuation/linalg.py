"""Small dense linear algebra of the continuation engine, written once for Python and numba.

The engine's bordered systems are ``(n+1) x (n+1)`` with small ``n`` (3 x 3 for a curve in
``R^3``), where the call overhead of LAPACK, from Python or from numba, is larger than the work.
Each building block here is written once and runs in both worlds: plain Python functions, which
:mod:`continuation.compiled` registers with numba's public ``numba.extending.register_jitable``
(compiled into the caller when called from ``@njit`` code), or, where the two worlds need a
different storage or summation, a Python function with an implementation for compiled code
(``_*_compiled``, registered there with ``numba.extending.overload``), both calling the one
algorithm. This module never imports numba: the registrations are made when
:mod:`continuation.compiled` is imported, i.e. when compiled code is first wanted, so the
Python path never imports numba. Users:

* the engine's Python path (:mod:`continuation.engine`): corrector, tangent, branch-point test;
* the compiled corrector's building blocks (:mod:`continuation.compiled`, and through them a
  problem's ``compiled_step``, e.g. :mod:`stability.linear.neutral_compiled`);
* the compiled right-hand sides of the nonlinear models (:mod:`stability.nonlinear`), whose
  sliding and rolling spheres solve a 6 x 6 system at every evaluation
  (:func:`_solve_dense`, compiled as :func:`continuation.compiled.solve_dense`).

The algorithm (:func:`lu_solve`): Gaussian elimination with partial pivoting, the first largest
``|a_ik|`` of a column as pivot (ties go to the upper row), the multipliers ``a_ik / a_kk``, a
row skipped when its multiplier is exactly zero, back substitution, and the determinant as the
signed product of the pivots. It stops with ``ok = False`` at a pivot that is zero or NaN, before
dividing by it. Generic in the dtype: called from compiled code with complex arrays it is
compiled for complex128 (a complex-step Jacobian; the pivot choice uses ``abs`` and does not break
analyticity).

Storage (the operations, hence the numbers, are the same in both worlds): arrays indexed
``A[i, j]`` (:func:`_lu_solve_array`: numba would make a view object for every row ``A[i]``),
except the Python path's 3 x 3 systems, its most frequent, which the unrolled :func:`_lu_solve3`
solves on nested lists (indexing a list is several times faster than indexing an array from
Python), its 2 x 2 ones too, bordered by the identity (:func:`bordered_solve`); its 4 x 4 ones
(a fold curve's) cost about 3 us more on arrays. Two things differ by design between the worlds:
:func:`norm` (Python: one BLAS dot product; compiled: a loop, not bit-identical to BLAS, so a
problem's compiled step and the engine's Python path agree to rounding, not bit for bit); and
systems larger than :data:`PYTHON_LU_MAX` from Python, which go to LAPACK (an interpreted
elimination costs ``m^3 / 3`` Python operations).

numba keys its on-disk cache of a compiled function by that function's own source file only: after
editing this file or :mod:`continuation.corrector` in a development install, clear the numba
caches (``*.nbi``/``*.nbc`` under ``__pycache__``) of :mod:`continuation.compiled` and of the
compiled code that inlines them (the steps of :mod:`stability.linear.neutral_compiled` and
:mod:`stability.steady.branch_compiled`, the nonlinear right-hand sides; :mod:`stability.jit`).
"""

from __future__ import annotations

import math

import numpy as np

__all__ = [
    "PYTHON_LU_MAX",
    "bordered_det",
    "bordered_solve",
    "dot",
    "least_squares",
    "lu_solve",
    "norm",
    "tangent_det",
]

#: largest system that the Python faces solve with :func:`lu_solve`; larger ones go to LAPACK
PYTHON_LU_MAX = 4


# ------------------------------------------------------------------------------------------
# the elimination
# ------------------------------------------------------------------------------------------
def lu_solve(A, x):
    """Solve ``A y = x`` in place by Gaussian elimination with partial pivoting.

    Parameters
    ----------
    A : 2-D array (or, for m = 3, nested lists), size m x m
        Overwritten with the elimination.
    x : vector of size m
        Right-hand side; overwritten with the solution ``y``.

    Returns
    -------
    ok : bool
        False if a pivot is zero or NaN (``x`` is then not the solution).
    det : float or complex
        ``det A``, the signed product of the pivots; if not ``ok``, the offending pivot's
        magnitude: 0.0 (the matrix is singular, its determinant 0 to rounding) or NaN.

    Notes
    -----
    For m = 3 the same steps run unrolled (:func:`_lu_solve3`; 3 x 3 is the engine's most
    frequent system, and the loop :func:`_lu_solve_array` costs the Python path about three
    times as much, docs/continuation.md); the two agree bit for bit
    (tests/test_continuation_engine.py).
    """
    if len(x) == 3:
        return _lu_solve3(A, x)
    return _lu_solve_array(A, x)


def _lu_solve_array(A, x):
    """:func:`lu_solve` for any size, in loops, on a 2-D array indexed ``A[i, j]`` (Python, and
    compiled code, where a row ``A[i]`` would be a reference-counted view object: 2.4x slower
    for a 6 x 6 solve, docs/performance.md, "The 6 x 6 solve of the nonlinear runs")."""
    m = len(x)
    det = 1.0
    for k in range(m):
        p = k
        big = abs(A[k, k])
        for i in range(k + 1, m):
            if abs(A[i, k]) > big:
                p = i
                big = abs(A[i, k])
        if big == 0.0 or big != big:
            return False, big
        if p != k:
            for j in range(k, m):
                tmp = A[k, j]
                A[k, j] = A[p, j]
                A[p, j] = tmp
            tmp = x[k]
            x[k] = x[p]
            x[p] = tmp
            det = -det
        piv = A[k, k]
        det *= piv
        for i in range(k + 1, m):
            f = A[i, k] / piv
            if f != 0.0:
                for j in range(k + 1, m):
                    A[i, j] -= f * A[k, j]
                x[i] -= f * x[k]
    for k in range(m - 1, -1, -1):
        acc = x[k]
        for j in range(k + 1, m):
            acc -= A[k, j] * x[j]
        x[k] = acc / A[k, k]
    return True, det


def _lu_solve3(A, x):
    """:func:`lu_solve` for m = 3: the operations of :func:`_lu_solve_array` in the same order,
    unrolled (``A`` is read, not written)."""
    a00, a01, a02 = A[0]
    a10, a11, a12 = A[1]
    a20, a21, a22 = A[2]
    b0, b1, b2 = x
    det = 1.0
    # column 0
    big = abs(a00)
    p = 0
    if abs(a10) > big:
        big = abs(a10)
        p = 1
    if abs(a20) > big:
        big = abs(a20)
        p = 2
    if big == 0.0 or big != big:
        return False, big
    if p == 1:
        a00, a01, a02, b0, a10, a11, a12, b1 = a10, a11, a12, b1, a00, a01, a02, b0
        det = -det
    elif p == 2:
        a00, a01, a02, b0, a20, a21, a22, b2 = a20, a21, a22, b2, a00, a01, a02, b0
        det = -det
    det *= a00
    f = a10 / a00
    if f != 0.0:
        a11 -= f * a01
        a12 -= f * a02
        b1 -= f * b0
    f = a20 / a00
    if f != 0.0:
        a21 -= f * a01
        a22 -= f * a02
        b2 -= f * b0
    # column 1
    big = abs(a11)
    if abs(a21) > big:
        big = abs(a21)
        a11, a12, b1, a21, a22, b2 = a21, a22, b2, a11, a12, b1
        det = -det
    if big == 0.0 or big != big:
        return False, big
    det *= a11
    f = a21 / a11
    if f != 0.0:
        a22 -= f * a12
        b2 -= f * b1
    # column 2
    big = abs(a22)
    if big == 0.0 or big != big:
        return False, big
    det *= a22
    # back substitution
    y2 = b2 / a22
    y1 = (b1 - a12 * y2) / a11
    y0 = (b0 - a01 * y1 - a02 * y2) / a00
    x[0] = y0
    x[1] = y1
    x[2] = y2
    return True, det


# ------------------------------------------------------------------------------------------
# the bordered faces: arrays in, new arrays out (Python: nested lists inside; compiled: copies)
# ------------------------------------------------------------------------------------------
def bordered_solve(J: np.ndarray, c: np.ndarray, f: np.ndarray, r: float) -> tuple[bool, np.ndarray, float]:
    """Solve the bordered system ``[J; c^T] x = [f; r]`` (:func:`lu_solve`): ``(ok, x, det)``.

    The engine's systems: the corrector's Newton step (``c`` the tangent, ``r`` the distance
    from the plane), the tangent (``f = 0``, ``r = 1``), the location of a boundary (``c`` the
    constraint's gradient). ``J`` has shape (n, n+1), ``c`` (n+1,), ``f`` (n,); ``det`` is
    ``det [J; c^T]``; ``ok`` False at a zero or NaN pivot. From Python, a system larger than
    :data:`PYTHON_LU_MAX` goes to LAPACK.

    From Python a 2 x 2 system ``G x = b`` is solved as the 3 x 3 system ``[G 0; 0 1] [x; y] =
    [b; 0]`` by the unrolled :func:`_lu_solve3`, with the same numbers as the 2 x 2 elimination:
    the zero entries never win a pivot (``0 > |a|`` is false, also for NaN), their multipliers
    ``0 / a_kk`` are zero and skip the row, and ``a_k2 y = 0``, ``y = 0 / 1``, ``det`` times
    ``1`` are exact; faster than the loop on lists, and checked bit for bit against the 2 x 2
    codings in tests/test_continuation_engine.py.
    """
    m = J.shape[0] + 1
    if 2 <= m <= 3:  # nested lists: Python indexes them faster than arrays (module docstring)
        A, x = J.tolist() + [c.tolist()], f.tolist() + [r]
        if m == 2:  # bordered by the identity: the numbers of the 2 x 2 elimination (docstring)
            A, x = [A[0] + [0.0], A[1] + [0.0], [0.0, 0.0, 1.0]], x + [0.0]
        ok, d = _lu_solve3(A, x)
        return ok, np.array(x[:m]), d
    dtype = np.result_type(J, c, f, r, np.float64)  # never the caller's int or float32
    G, y = np.vstack([J, c], dtype=dtype), np.append(f, r).astype(dtype, copy=False)  # new arrays, once
    if y.size > PYTHON_LU_MAX:  # LAPACK (ok False if it reports a singular matrix)
        try:
            return True, np.linalg.solve(G, y), float(np.linalg.det(G))
        except np.linalg.LinAlgError:
            return False, y, 0.0
    with np.errstate(all="ignore"):  # numpy scalars warn where Python floats overflow silently
        ok, d = _lu_solve_array(G, y)
    return ok, y, d


def _bordered_solve_compiled(J, c, f, r):
    def impl(J, c, f, r):
        n = J.shape[0]
        G, x = np.empty((n + 1, n + 1)), np.empty(n + 1)
        G[:n], G[n], x[:n], x[n] = J, c, f, r
        ok, d = lu_solve(G, x)
        return ok, x, d

    return impl


def bordered_det(J: np.ndarray, c: np.ndarray) -> float:
    """``det [J; c^T]`` by :func:`bordered_solve` (the pivots of :func:`lu_solve`; 0.0 at a zero
    pivot), from Python; LAPACK above :data:`PYTHON_LU_MAX`."""
    return bordered_solve(J, c, np.zeros(J.shape[0]), 0.0)[2]


def norm(x: np.ndarray) -> float:
    """Euclidean norm of a short vector: ``sqrt(x . x)`` (cheaper than ``numpy.linalg.norm``
    for a few entries). Compiled: a loop (its own summation, so the two worlds agree to
    rounding)."""
    return math.sqrt(float(x @ x))


def dot(a: np.ndarray, b: np.ndarray) -> float:
    """``a . b`` of two short vectors (Python: one BLAS dot product; compiled: a loop, summed in
    order, as :func:`norm`)."""
    return float(a @ b)


def _dot_compiled(a, b):
    def impl(a, b):
        s = 0.0
        for i in range(a.shape[0]):
            s += a[i] * b[i]
        return s

    return impl


def least_squares(J: np.ndarray, f: np.ndarray) -> tuple[bool, np.ndarray]:
    """The minimum-norm solution of ``J x = f`` (``numpy.linalg.lstsq``; Python only): ``(ok,
    x)``, ``ok`` False if the SVD fails."""
    try:
        return True, np.linalg.lstsq(J, f, rcond=None)[0]
    except np.linalg.LinAlgError:
        return False, f


def _least_squares_compiled(J, f):
    def impl(J, f):  # no compiled caller projects (a projection is Python's): a failed solve
        return False, f

    return impl


def _norm_compiled(x):
    def impl(x):
        s = 0.0
        for i in range(x.shape[0]):
            s += x[i] * x[i]
        return math.sqrt(s)

    return impl


# ------------------------------------------------------------------------------------------
# the bordered tangent and the branch-point test
# ------------------------------------------------------------------------------------------
def tangent_det(J, t_ref):
    """Unit null vector ``t`` of ``J`` (n, n+1), oriented by ``t_ref``, and ``det [J; t^T]``.

    The bordered solve ``[J; t_ref^T] y = e_(n+1)`` gives ``J y = 0`` and ``t_ref . y = 1``, so
    ``t = y / |y|`` has ``t . t_ref > 0``. The branch-point test costs nothing more: ``det [J;
    c^T]`` is linear in ``c``, ``c . g`` with ``g`` the vector of cofactors, and ``J g = 0`` (a
    repeated row), so ``g = det [J; t^T] t``; the pivots of the solve give ``det [J; t_ref^T] =
    t_ref . g = det [J; t^T] / |y|``. ``det [J; t^T]`` changes sign at a simple branch point
    (Allgower & Georg, *Introduction to Numerical Continuation Methods*, ch. 8).

    Returns
    -------
    ok : bool
        False if the bordered matrix is singular (``t_ref`` orthogonal to the null space, or
        ``J`` rank-deficient); the caller then needs another way (the engine: the SVD).
    t : numpy.ndarray, shape (n+1,)
    det : float
        ``det [J; t^T]`` (0.0 if not ``ok``).
    """
    ok, y, det_ref = bordered_solve(J, t_ref, np.zeros(J.shape[0]), 1.0)
    if not ok:
        return False, y, 0.0
    ny = norm(y)
    if not math.isfinite(ny) or ny == 0.0:
        return False, y, 0.0
    return True, y / ny, det_ref * ny


# ------------------------------------------------------------------------------------------
# in place, for compiled code (the nonlinear models' right-hand sides)
# ------------------------------------------------------------------------------------------
def _solve_dense(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Solve ``a x = b`` in place by :func:`lu_solve` (compiled; float or complex).

    Parameters
    ----------
    a : numpy.ndarray, shape (n, n)
        Matrix; overwritten.
    b : numpy.ndarray, shape (n,)
        Right-hand side; overwritten with the solution, which is also returned.

    Returns
    -------
    numpy.ndarray
        The solution ``x`` (the array ``b``); all NaN if a pivot is zero or NaN (an integrator
        sees a non-finite derivative and rejects the step).
    """
    ok, _ = lu_solve(a, b)
    if not ok:
        b[:] = np.nan
    return b
