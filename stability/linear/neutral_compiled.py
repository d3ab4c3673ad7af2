"""The compiled step of the sliding model's neutral curves (crossing form of eq. 11).

:class:`stability.linear.neutral_curves.NeutralProblem` offers the engine this ``compiled_step``
(:mod:`continuation.problem`) when its neutral condition is the crossing form of the sliding
model, whose coefficients and exact parameter derivatives have compiled twins in
:mod:`stability.linear.neutrality` (:func:`~stability.linear.neutrality.sliding_crossing_residual`). One call
does what the engine's Python path does per step: Newton's method on the bordered system
``[F(v); t . (v - v_k) - h] = 0`` from the predicted point (polished to the rounding floor,
:func:`continuation.compiled.corrector_update`), then the unit tangent oriented by ``t`` and
``det [J; t^T]`` at the solution (:func:`continuation.compiled.tangent_det`). All in the
engine's scaled variables ``v = u / scale``.

The constraints and the second test function of the problem (the largest growth rate of the
other modes) have compiled twins here too (:func:`constraint_values`,
:func:`~stability.linear.neutrality.sliding_crossing_other_growth`).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from continuation.compiled import CONVERGED, FAILED, POLISH, corrector_update, norm, tangent_det

from .neutrality import sliding_crossing_other_growth, sliding_crossing_residual

__all__ = ["sliding_step", "residual_and_jacobian", "constraint_values", "CONSTRAINT_CODES"]

_JIT = dict(cache=True, fastmath=False, nogil=True, error_model="numpy")

#: kinds of constraint rows ``(code, index, a)`` for :func:`constraint_values` (parameters
#: ``p`` indexed as ``(q, fr_inv, sigma, alpha_v, mu)``): ``1 - mu q^2 - a``, ``p[i] - a``,
#: ``a - p[i]``, ``2 (1 - mu q^2) - sigma``
CONSTRAINT_CODES = {"inside": 0, "lower": 1, "upper": 2, "sigma_max": 3}


@njit(**_JIT)
def _scaled_residual(point: np.ndarray, free_index: np.ndarray, ncoef: int, v: np.ndarray,
                     scale: np.ndarray, jacobian: bool, F: np.ndarray, J: np.ndarray) -> None:
    """``F(v * scale)`` and ``dF/dv = dF/du * scale`` (the engine's ``_Scaled``)."""
    sliding_crossing_residual(point, free_index, ncoef, v * scale, jacobian, F, J)
    if jacobian:
        for i in range(J.shape[0]):
            for j in range(J.shape[1]):
                J[i, j] = J[i, j] * scale[j]


@njit(**_JIT)
def residual_and_jacobian(point: np.ndarray, free_index: np.ndarray, ncoef: int, u: np.ndarray,
                          jacobian: bool) -> tuple[np.ndarray, np.ndarray]:
    """``F`` (2,) and ``dF/du`` (2, k + 1) at ``u`` (problem variables), as new arrays
    (:func:`stability.linear.neutrality.sliding_crossing_residual`; ``J`` is not filled unless
    ``jacobian``)."""
    m = u.shape[0]
    F = np.empty(2)
    J = np.empty((2, m))
    sliding_crossing_residual(point, free_index, ncoef, u, jacobian, F, J)
    return F, J


@njit(**_JIT)
def sliding_step(point: np.ndarray, free_index: np.ndarray, ncoef: int, codes: np.ndarray,
                 index: np.ndarray, a: np.ndarray, guess: np.ndarray, t_plane: np.ndarray,
                 anchor: np.ndarray, h: float, scale: np.ndarray, tol: float, max_iter: int,
                 max_move: float) -> tuple:
    """Corrector and tangent of one continuation step (the engine's ``_newton`` with polishing,
    then ``_tangent_det``), compiled, and the problem's constraints and test functions at the
    new point (so that the engine's loop makes no further call for them).

    Parameters
    ----------
    point, free_index, ncoef
        The neutral condition (:func:`stability.linear.neutrality.sliding_crossing_residual`).
    codes, index, a
        The constraint rows (:func:`constraint_values`).
    guess : numpy.ndarray, shape (m,)
        Predicted point (scaled variables).
    t_plane, anchor : numpy.ndarray, shape (m,)
        The plane ``t_plane . (v - anchor) = h`` (the last tangent and point).
    h : float
        Step length.
    scale : numpy.ndarray, shape (m,)
        ``u = v * scale``.
    tol : float
        Accept at ``||F|| <= tol``.
    max_iter : int
        Newton iterations.
    max_move : float
        Give up if an iterate moves farther than this from ``guess``.

    Returns
    -------
    tuple
        ``(ok, iterations, n_residual_and_jacobian, n_residual, v, J, tangent_ok, t, det,
        g, tests)``: the point, the scaled Jacobian there (the one of the last Newton step when
        the polish step was kept, as the Python path), and if ``tangent_ok`` the unit tangent
        oriented by ``t_plane`` and ``det [J; t^T]``; if ``ok``, the constraints ``g`` and the
        test functions ``[w, max Re(other modes)]`` (``-1`` if there is no other mode) at
        ``u = v * scale``, the operations of ``NeutralProblem.constraints`` and
        ``NeutralProblem.test_functions`` (which the engine would call with the same ``u``).
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
        _scaled_residual(point, free_index, ncoef, v, scale, True, F, J)
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
                _scaled_residual(point, free_index, ncoef, v2, scale, False, F2, J2)
                n_r += 1
                if norm(F2) < fn:
                    v = v2
                    iterations = it + 1
            break
        # CONTINUE
        v = v + dv
        moved = norm(v - guess)
        if not math.isfinite(moved) or moved > max_move:
            iterations = it + 1
            break
    tests = np.empty(2)
    if not ok:
        return False, iterations, n_rj, n_r, v, J, False, t_plane, 0.0, np.empty(0), tests
    t_ok, t_new, det = tangent_det(J, t_plane)
    u = v * scale
    g = constraint_values(point, free_index, u, codes, index, a)
    tests[0] = u[m - 1]
    growth = sliding_crossing_other_growth(point, free_index, ncoef, u)
    tests[1] = growth if math.isfinite(growth) else -1.0
    return True, iterations, n_rj, n_r, v, J, t_ok, t_new, det, g, tests


@njit(**_JIT)
def constraint_values(point: np.ndarray, free_index: np.ndarray, u: np.ndarray,
                      codes: np.ndarray, index: np.ndarray, a: np.ndarray) -> np.ndarray:
    """The problem's constraints at ``u`` (problem variables), from rows ``(code, index, a)``
    (:data:`CONSTRAINT_CODES`), in the operations of their Python twins in
    :mod:`stability.linear.neutral_curves`."""
    p = point.copy()
    for i in range(free_index.shape[0]):
        p[free_index[i]] = u[i]
    q, sigma, mu = p[0], p[2], p[4]
    out = np.empty(codes.shape[0])
    for k in range(codes.shape[0]):
        c = codes[k]
        if c == 0:
            out[k] = 1.0 - mu * (q * q) - a[k]
        elif c == 1:
            out[k] = p[index[k]] - a[k]
        elif c == 2:
            out[k] = a[k] - p[index[k]]
        else:
            out[k] = 2.0 * (1.0 - mu * (q * q)) - sigma
    return out
