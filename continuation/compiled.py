"""Compiled (numba) building blocks for a problem's compiled corrector.

A problem may give the engine a ``compiled_step`` (:mod:`continuation.problem`): the
corrector, the tangent and the branch-point test in one compiled call, with the same semantics
as the engine's Python path (:func:`continuation.engine.trace`). The engine cannot hand a
problem's compiled residual to a generic compiled loop as a run-time argument without losing
numba's on-disk cache (a dispatcher in a signature or a closure is pickled with a key that
differs in every process); the problem's own ``njit(cache=True)`` step calls :func:`newton`
here (a ``register_jitable`` function, compiled into the caller) with its residual, a
``register_jitable`` function too, as the first argument: the residual is then a compile-time
constant of the caller's type, the caller's cache key stays the same in every process, and the
call is inlined as if the loop were written out. Each is the engine's own building block compiled, not a copy of it:

* :func:`solve_det`: :func:`continuation.linalg.solve_det` (Gaussian elimination with partial
  pivoting, :func:`continuation.linalg.lu_solve`, and the determinant from the pivots);
* :func:`tangent_det`: :func:`continuation.linalg.tangent_det`, the unit tangent from the
  bordered system ``[J; t_ref^T] y = e`` and ``det [J; t^T]`` (``ok`` False on a singular
  bordered matrix: the engine then takes the tangent from the SVD, in Python);
* :func:`predict`: :func:`continuation.interpolation.predict`, the Hermite extrapolation of the
  last step, or the tangent;
* :func:`norm`: :func:`continuation.linalg.norm` (compiled: a loop);
* :func:`solve_dense`: ``continuation.linalg._solve_dense``, ``a x = b`` in place (float or
  complex; all NaN at a zero pivot), the compiled 6 x 6 solve of the nonlinear models'
  right-hand sides;
* :func:`corrector_update`: one step of the pseudo-arclength Newton iteration of
  ``engine._newton``, the convergence tests included;
* :func:`newton`: the whole corrector loop (``engine._newton`` with polishing) for a problem's
  residual passed as an argument, so that a problem's compiled step is its residual, its
  constraints and its test functions (see :mod:`stability.linear.neutral_compiled`).

All are ``numba.njit(cache=True)``: compiled once per machine and cached in ``__pycache__``.
Importing this module imports numba and registers the engine's building blocks with it, through
numba's public API only (:func:`register`: ``numba.extending.register_jitable`` for the
functions of :mod:`continuation.linalg` and :mod:`continuation.interpolation` that run in both
worlds, ``numba.extending.overload`` for the three whose compiled storage differs); the
engine's Python path never imports it.
"""

from __future__ import annotations

import math

from collections.abc import Callable

import numba
import numpy as np
from numba.extending import overload, register_jitable

from . import interpolation, linalg

__all__ = [
    "CONTINUE",
    "CONVERGED",
    "EPS",
    "FAILED",
    "FLOOR",
    "POLISH",
    "corrector_update",
    "newton",
    "norm",
    "predict",
    "solve_dense",
    "solve_det",
    "tangent_det",
]

_JIT = dict(cache=True, fastmath=False, nogil=True, error_model="numpy")

#: numba's njit (public API), for the callers of this package that compile its building blocks
njit = numba.njit


def register() -> None:
    """Register the building blocks of :mod:`continuation.linalg` and
    :mod:`continuation.interpolation` with numba (run once, when this module is imported)."""
    for fn in (
        linalg.lu_solve,
        linalg._lu_solve_loop,
        linalg._lu_solve3,
        linalg.tangent_det,
        interpolation.hermite_eval,
        interpolation.predict,
    ):
        register_jitable(fn)
    options = {k: _JIT[k] for k in ("fastmath", "nogil", "error_model")}
    for fn, impl in (
        (linalg.solve_det, linalg._solve_det_compiled),
        (linalg.bordered_solve, linalg._bordered_solve_compiled),
        (linalg.norm, linalg._norm_compiled),
    ):
        overload(fn, jit_options=options)(impl)


register()

EPS = float(np.finfo(float).eps)
#: a residual this small is at the rounding floor: no polishing step (``engine._FLOOR``)
FLOOR = 4.0 * EPS

#: actions of :func:`corrector_update`
CONTINUE, CONVERGED, POLISH, FAILED = 0, 1, 2, 3


@njit(**_JIT)
def norm(x: np.ndarray) -> float:
    """Euclidean norm of a short vector (:func:`continuation.linalg.norm`, compiled)."""
    return linalg.norm(x)


@njit(**_JIT)
def solve_det(G: np.ndarray, b: np.ndarray) -> tuple[bool, np.ndarray, float]:
    """Solve ``G x = b``: ``(ok, x, det G)``, ``ok`` False at a zero or NaN pivot
    (:func:`continuation.linalg.solve_det`, compiled)."""
    return linalg.solve_det(G, b)


#: ``(ok, t, det)``: the unit null vector ``t`` of ``J`` (n, n+1) with ``t . t_ref > 0`` and
#: ``det [J; t^T]`` (:func:`continuation.linalg.tangent_det`, compiled)
tangent_det = njit(**_JIT)(linalg.tangent_det)

#: the predictor of a step (:func:`continuation.interpolation.predict`, compiled)
predict = njit(**_JIT)(interpolation.predict)

#: ``a x = b`` in place by :func:`continuation.linalg.lu_solve` (``a`` overwritten, ``b`` holds
#: and is the solution; all NaN at a zero or NaN pivot), for float and complex arrays
solve_dense = njit(cache=True)(linalg._solve_dense)


@njit(**_JIT)
def corrector_update(
    it: int,
    max_iter: int,
    v: np.ndarray,
    start: np.ndarray,
    f: np.ndarray,
    J: np.ndarray,
    t_plane: np.ndarray,
    anchor: np.ndarray,
    h: float,
    tol: float,
    polish: bool,
) -> tuple[int, np.ndarray, float]:
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
    fn = linalg.norm(f)
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
    ok, x, _ = linalg.bordered_solve(J, t_plane, f, plane)
    if not ok:
        return (CONVERGED if converged else FAILED), f, fn
    dv = -x
    if converged:
        return POLISH, dv, fn
    return CONTINUE, dv, fn


@register_jitable
def newton(
    residual: Callable[..., None],
    args: tuple,
    guess: np.ndarray,
    t_plane: np.ndarray,
    anchor: np.ndarray,
    h: float,
    scale: np.ndarray,
    tol: float,
    max_iter: int,
    max_move: float,
) -> tuple[bool, int, int, int, np.ndarray, np.ndarray]:
    """The corrector of one step (``engine._newton`` with polishing), compiled.

    ``residual(*args, u, jacobian, F, J)`` writes ``F(u)`` into ``F`` (n,) and, if ``jacobian``,
    ``dF/du`` into ``J`` (n, n+1), at the problem's variables ``u = v * scale`` (the engine's
    ``_Scaled``); a ``register_jitable`` function (see the module docstring). Newton's method on
    the bordered system ``[F(v); t_plane . (v - anchor) - h] = 0`` from ``guess`` (scaled
    variables): accept at ``||F|| <= tol``, at most ``max_iter`` iterations, give up if an
    iterate moves farther than ``max_move`` from ``guess``; a converged point above the rounding
    floor is polished by one more step, kept if its residual is smaller.

    Returns ``(ok, iterations, n_residual_and_jacobian, n_residual, v, J)``: the point and the
    scaled Jacobian there (the one of the last Newton step when the polish step was kept, as
    the Python path).
    """
    m = guess.shape[0]
    n = m - 1
    F = np.empty(n)
    J = np.empty((n, m))
    F2 = np.empty(n)
    J2 = np.empty((n, m))
    v = guess.copy()
    n_rj = 0
    n_r = 0
    ok = False
    iterations = max_iter
    for it in range(max_iter + 1):
        residual(*args, v * scale, True, F, J)
        for i in range(n):
            for j in range(m):
                J[i, j] = J[i, j] * scale[j]
        n_rj += 1
        action, dv, fn = corrector_update(it, max_iter, v, guess, F, J, t_plane, anchor, h, tol, True)
        if action == FAILED:
            iterations = it
            break
        if action == CONVERGED:
            ok = True
            iterations = it
            break
        if action == POLISH:
            ok = True
            iterations = it
            if math.isfinite(norm(dv)):
                v2 = v + dv
                residual(*args, v2 * scale, False, F2, J2)
                n_r += 1
                if norm(F2) < fn:
                    v = v2
                    iterations = it + 1
            break
        v = v + dv  # CONTINUE
        moved = norm(v - guess)
        if not math.isfinite(moved) or moved > max_move:
            iterations = it + 1
            break
    return ok, iterations, n_rj, n_r, v, J
