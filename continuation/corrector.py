"""The corrector of a continuation step, written once for the engine's Python path and for numba.

:func:`newton` is Newton's method on the bordered system ``[F(v); t_plane . (v - anchor) - h]
= 0`` (or, with ``t_plane`` None, minimum-norm Newton steps onto ``F = 0``: the projection of a
start point); :func:`step` adds the unit tangent and the branch-point test at the point found.
They are plain Python functions: the engine's Python path (:mod:`continuation.engine`) calls
them with its own residual, and :mod:`continuation.compiled` registers them with numba
(``numba.extending.register_jitable``) so that a problem's ``njit(cache=True)`` step calls them
with its compiled residual (:mod:`continuation.problem`, item ``compiled_step``; e.g.
:mod:`stability.linear.neutral_compiled`, :mod:`stability.steady.branch_compiled`). The
building blocks (:func:`continuation.linalg.norm`, :func:`~continuation.linalg.dot`,
:func:`~continuation.linalg.bordered_solve`, :func:`~continuation.linalg.tangent_det`) run as
Python from Python and compiled in compiled code, so each world gives the numbers it always gave.

The rules (:mod:`continuation.problem`): converged when ``||F||_2 <= tol`` and ``|t_plane . (v -
anchor) - h| <= 1e3 eps (1 + |h|)``; then one more Newton step, kept if it lowers ``||F||``
(skipped when ``||F|| <= 4 eps``, the rounding floor); failed after ``max_iter`` iterations, on a
value that is not finite, on a singular bordered matrix before convergence, or when an iterate
moves farther than ``max_move`` from ``guess``.
"""

from __future__ import annotations

import math

import numpy as np

from .linalg import bordered_solve, dot, least_squares, norm, tangent_det

__all__ = ["EPS", "FLOOR", "newton", "step"]

EPS = float(np.finfo(float).eps)
#: a residual this small is at the rounding floor: no polishing step
FLOOR = 4.0 * EPS


def newton(residual, args, guess, t_plane, anchor, h, scale, tol, max_iter, max_move):
    """The corrector of one step, in the scaled variables ``v = u / scale`` (module docstring).

    ``residual(*args, u, jacobian, F, J)`` writes ``F(u)`` into ``F`` (n,) and, if ``jacobian``,
    ``dF/du`` into ``J`` (n, n+1), at the problem's variables ``u = v * scale``; ``guess``,
    ``t_plane`` (None: minimum-norm steps, no plane), ``anchor`` and ``scale`` are float arrays of
    shape (n+1,), ``h``, ``tol`` and ``max_move`` floats, ``max_iter`` an int. Returns ``(ok,
    iterations, n_residual_and_jacobian, n_residual, v, J)``: the point and the scaled Jacobian
    there (the one of the last Newton step when the polishing step was kept).
    """
    n = guess.shape[0] - 1
    F, J = np.empty(n), np.empty((n, n + 1))
    v = guess  # never written: each iterate is a new array
    n_rj, n_r, ok, iterations = 0, 0, False, max_iter
    for it in range(max_iter + 1):
        residual(*args, v * scale, True, F, J)
        J *= scale
        n_rj += 1
        fn = norm(F)
        if not math.isfinite(fn):
            iterations = it
            break
        plane = 0.0 if t_plane is None else dot(t_plane, v - anchor) - h
        converged = fn <= tol and abs(plane) <= 1e3 * EPS * (1.0 + abs(h))
        ok, iterations = converged, it
        if (it == max_iter and not converged) or (converged and not fn > FLOOR):
            break
        if t_plane is None:
            solved, x = least_squares(J, F)
        else:
            solved, x, _ = bordered_solve(J, t_plane, F, plane)
        if not solved:
            break
        dv = -x
        if converged:  # polish: one more step, kept if it lowers ||F||
            if math.isfinite(norm(dv)):
                F2, J2 = np.empty(n), np.empty((n, n + 1))  # J stays the step's (a residual may fill J2)
                residual(*args, (v + dv) * scale, False, F2, J2)
                n_r += 1
                if norm(F2) < fn:
                    v, iterations = v + dv, it + 1
            break
        v = v + dv
        moved = norm(v - guess)
        if not math.isfinite(moved) or moved > max_move:
            iterations = it + 1
            break
    return ok, iterations, n_rj, n_r, v, J


def step(residual, args, guess, t_plane, anchor, h, scale, tol, max_iter, max_move):
    """:func:`newton`, then the unit tangent ``t`` (``t . t_plane > 0``) and ``det [J; t^T]`` at
    the point (:func:`continuation.linalg.tangent_det`): the first nine fields of a
    :class:`continuation.StepResult`, ``(ok, iterations, n_residual_and_jacobian, n_residual, v,
    J, tangent_ok, t, det)``."""
    ok, iterations, n_rj, n_r, v, J = newton(residual, args, guess, t_plane, anchor, h, scale, tol, max_iter, max_move)
    if not ok:
        return False, iterations, n_rj, n_r, v, J, False, t_plane, 0.0
    t_ok, t, det = tangent_det(J, t_plane)
    return True, iterations, n_rj, n_r, v, J, t_ok, t, det
