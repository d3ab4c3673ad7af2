"""Compiled (numba) building blocks for a problem's compiled corrector.

A problem may give the engine a ``compiled_step`` (:mod:`continuation.problem`): the
corrector, the tangent and the branch-point test in one compiled call, with the same semantics
as the engine's Python path (:func:`continuation.engine.trace`). The engine cannot hand a
problem's compiled residual to a generic compiled loop without losing numba's on-disk cache
(a function passed as an argument makes the caller uncacheable, and costs microseconds of
dispatch per call), so the loop lives with the problem; the pieces that do not depend on the
problem live here, in the same floating-point operations as their Python twins in
:mod:`continuation.engine`:

* :func:`solve_det`: Gaussian elimination with partial pivoting and the determinant from the
  pivots (``engine._solve_det``);
* :func:`tangent_det`: the unit tangent from the bordered system ``[J; t_ref^T] y = e`` and
  ``det [J; t^T]`` (``engine._tangent_det``, without its SVD fallback: a singular bordered
  matrix is reported and the engine falls back to its Python path);
* :func:`predict`: the Hermite extrapolation of the last step, or the tangent
  (``engine.hermite`` and the predictor of ``engine.trace``);
* :func:`corrector_update`: one step of the pseudo-arclength Newton iteration of
  ``engine._newton``, the convergence tests included, so that a problem's loop is a few lines
  (see :mod:`stability.linear.neutral_compiled`).

All are ``numba.njit(cache=True)``: compiled once per machine and cached in ``__pycache__``.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from .linalg import back_substitute, swap_rows

__all__ = ["solve_det", "tangent_det", "predict", "corrector_update", "norm", "EPS", "FLOOR",
           "CONTINUE", "CONVERGED", "POLISH", "FAILED"]

_JIT = dict(cache=True, fastmath=False, nogil=True, error_model="numpy")

EPS = float(np.finfo(float).eps)
#: a residual this small is at the rounding floor: no polishing step (``engine._FLOOR``)
FLOOR = 4.0 * EPS

#: actions of :func:`corrector_update`
CONTINUE, CONVERGED, POLISH, FAILED = 0, 1, 2, 3


@njit(**_JIT)
def norm(x: np.ndarray) -> float:
    """Euclidean norm of a short vector."""
    s = 0.0
    for i in range(x.shape[0]):
        s += x[i] * x[i]
    return math.sqrt(s)


@njit(**_JIT)
def solve_det(G: np.ndarray, b: np.ndarray) -> tuple[bool, np.ndarray, float]:
    """Solve ``G x = b`` by partial pivoting; ``(ok, x, det G)``, ``ok`` False at a zero pivot.

    The pivot order and the operations of ``continuation.engine._solve_det`` (first largest
    pivot on ties; the determinant is the signed product of the pivots).
    """
    m = b.shape[0]
    A = G.copy()
    x = b.copy()
    det = 1.0
    for k in range(m):
        p = k
        big = abs(A[k, k])
        for i in range(k + 1, m):
            if abs(A[i, k]) > big:
                p = i
                big = abs(A[i, k])
        if big == 0.0 or big != big:
            return False, x, 0.0
        if p != k:
            swap_rows(A, x, k, p)
            det = -det
        piv = A[k, k]
        det *= piv
        for i in range(k + 1, m):
            f = A[i, k] / piv
            if f != 0.0:
                for j in range(k + 1, m):
                    A[i, j] -= f * A[k, j]
                x[i] -= f * x[k]
    return True, back_substitute(A, x), det


@njit(**_JIT)
def tangent_det(J: np.ndarray, t_ref: np.ndarray) -> tuple[bool, np.ndarray, float]:
    """Unit null vector ``t`` of ``J`` (n, n+1) with ``t . t_ref > 0`` and ``det [J; t^T]``.

    ``(ok, t, det)``; ``ok`` is False if the bordered matrix ``[J; t_ref^T]`` is singular
    (the engine then uses its SVD fallback).
    """
    n, m = J.shape
    G = np.empty((m, m))
    for i in range(n):
        for j in range(m):
            G[i, j] = J[i, j]
    for j in range(m):
        G[n, j] = t_ref[j]
    rhs = np.zeros(m)
    rhs[m - 1] = 1.0
    ok, y, det_ref = solve_det(G, rhs)
    if not ok:
        return False, y, 0.0
    ny = norm(y)
    if not math.isfinite(ny) or ny == 0.0:
        return False, y, 0.0
    return True, y / ny, det_ref * ny


@njit(**_JIT)
def predict(v: np.ndarray, t: np.ndarray, v_prev: np.ndarray, t_prev: np.ndarray,
            use_prev: bool, h: float) -> np.ndarray:
    """Predictor of a step of length ``h`` from ``(v, t)``: the cubic Hermite curve of the last
    step (``v_prev``, ``t_prev`` to ``v``, ``t``) extrapolated to ``tau = 1 + h / d`` if
    ``use_prev`` (and the step has length ``d > 0``), else the tangent ``v + h t``."""
    if use_prev:
        d = norm(v - v_prev)
        if d > 0:
            tau = 1.0 + h / d
            t2 = tau * tau
            t3 = t2 * tau
            a0 = 2 * t3 - 3 * t2 + 1
            b0 = (t3 - 2 * t2 + tau) * d
            a1 = 3 * t2 - 2 * t3
            b1 = (t3 - t2) * d
            out = np.empty_like(v)
            for i in range(v.shape[0]):
                out[i] = a0 * v_prev[i] + b0 * t_prev[i] + a1 * v[i] + b1 * t[i]
            return out
    return v + h * t


@njit(**_JIT)
def corrector_update(it: int, max_iter: int, v: np.ndarray, start: np.ndarray, f: np.ndarray,
                     J: np.ndarray, t_plane: np.ndarray, anchor: np.ndarray, h: float, tol: float,
                     polish: bool) -> tuple[int, np.ndarray, float]:
    """One iteration of ``engine._newton`` given ``f = F(v)`` and ``J = dF/dv`` (scaled).

    Returns ``(action, dv, ||f||)``:

    ``CONVERGED``
        ``v`` is the answer (``||f|| <= tol`` on the plane, at the rounding floor or without
        polishing);
    ``POLISH``
        converged; try ``v + dv`` and keep it if its residual is smaller;
    ``CONTINUE``
        not yet converged: ``v + dv`` is the next iterate (the caller checks ``max_move``);
    ``FAILED``
        not finite, or ``max_iter`` reached, or the bordered matrix is singular before
        convergence (a singular matrix after convergence gives ``CONVERGED``, as in the Python
        path).
    """
    fn = norm(f)
    if not math.isfinite(fn):
        return FAILED, f, fn
    plane = 0.0
    for i in range(v.shape[0]):
        plane += t_plane[i] * (v[i] - anchor[i])
    plane = plane - h
    converged = fn <= tol and abs(plane) <= 1e3 * EPS * (1.0 + abs(h))
    if it == max_iter and not converged:
        return FAILED, f, fn
    if converged and not (polish and fn > FLOOR):
        return CONVERGED, f, fn
    n, m = J.shape
    G = np.empty((m, m))
    rhs = np.empty(m)
    for i in range(n):
        for j in range(m):
            G[i, j] = J[i, j]
        rhs[i] = f[i]
    for j in range(m):
        G[n, j] = t_plane[j]
    rhs[n] = plane
    ok, x, _ = solve_det(G, rhs)
    if not ok:
        return (CONVERGED if converged else FAILED), f, fn
    dv = -x
    if converged:
        return POLISH, dv, fn
    return CONTINUE, dv, fn
