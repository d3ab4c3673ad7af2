"""Cubic Hermite interpolation of a curve between two of its points, written once.

Between ``p0`` (unit tangent ``t0``) and ``p1`` (``t1``) the curve is approximated by the cubic
Hermite curve parametrised by ``tau`` in [0, 1] with the chord length ``d = |p1 - p0|`` as the
length of the arc::

    H(tau) = h00(tau) p0 + h10(tau) d t0 + h01(tau) p1 + h11(tau) d t1,
    h00 = 2 tau^3 - 3 tau^2 + 1,  h10 = tau^3 - 2 tau^2 + tau,  h01 = 3 tau^2 - 2 tau^3,
    h11 = tau^3 - tau^2.

Its distance from a smooth curve through the two points with those tangents is ``O(d^4)``
(the chord-length parametrisation moves points along the curve by ``O(d^3)``, off it only by
``O(d^4)``; on a circle of curvature ``kappa``: ``kappa^3 d^4 / 128`` at the middle,
tests/test_continuation_engine.py). Values of ``tau`` outside [0, 1] extrapolate.

Users: the engine's predictor (:func:`predict`: the curve of the last step extrapolated; in
the Python path and, compiled, in :func:`continuation.compiled.predict`), its predictor of the
corrector solves that locate special points (:func:`hermite`), and the dense output
(:func:`continuation.dense.hermite_samples`). :func:`hermite_eval` and :func:`predict` are plain
Python from Python, and compiled into ``@njit`` callers once :mod:`continuation.compiled` has
registered them (``numba.extending.register_jitable``).
"""

from __future__ import annotations

from typing import Any

import numpy as np

from .linalg import norm

__all__ = ["hermite", "hermite_eval", "predict"]


def hermite_eval(p0: Any, t0: Any, p1: Any, t1: Any, tau: Any, d: Any) -> Any:
    """``H(tau)`` (module docstring) for a given chord length ``d``.

    Scalars or arrays that broadcast (numpy rules; compiled: scalars ``tau`` and ``d``): e.g.
    ``tau`` of shape ``(k, 1)`` and points of shape ``(dim,)`` give ``(k, dim)``. The operations,
    in this order, are the ones every user relies on: ``h10`` and ``h11`` are multiplied by
    ``d`` first, then by the tangent.
    """
    t2 = tau * tau
    t3 = t2 * tau
    return (2 * t3 - 3 * t2 + 1) * p0 + ((t3 - 2 * t2 + tau) * d) * t0 + (3 * t2 - 2 * t3) * p1 + ((t3 - t2) * d) * t1


def hermite(p0: np.ndarray, t0: np.ndarray, p1: np.ndarray, t1: np.ndarray, tau: np.ndarray | float) -> np.ndarray:
    """Cubic Hermite curve through ``p0`` (unit tangent ``t0``) and ``p1`` (``t1``).

    Parametrised by ``tau`` in [0, 1] (values outside extrapolate) with the chord length
    ``d = |p1 - p0|`` as the length of the arc: ``H(tau) = h00 p0 + h10 d t0 + h01 p1 +
    h11 d t1`` (:mod:`continuation.interpolation`). Its distance from a smooth curve through the
    two points with those tangents is ``O(d^4)``.

    Parameters
    ----------
    p0, t0, p1, t1 : numpy.ndarray, shape (dim,)
    tau : float or numpy.ndarray, shape (k,)

    Returns
    -------
    numpy.ndarray, shape (dim,) or (k, dim)
    """
    d = norm(p1 - p0)
    if isinstance(tau, float):  # one point: the basis in Python floats (4 vector operations)
        return hermite_eval(p0, t0, p1, t1, tau, d)
    return hermite_eval(p0, t0, p1, t1, np.asarray(tau, dtype=float)[..., None], d)


def predict(v, t, v_prev, t_prev, use_prev, h):
    """Predictor of a continuation step of length ``h`` from ``(v, t)``.

    The cubic Hermite curve of the last step (from ``v_prev``, ``t_prev`` to ``v``, ``t``),
    extrapolated to ``tau = 1 + h / d`` (error ``O(h^3)`` to ``O(h^4)`` instead of the tangent's
    ``O(h^2)``) if ``use_prev`` and the last step has a length ``d > 0``; else the tangent
    predictor ``v + h t``.
    """
    if use_prev:
        d = norm(v - v_prev)
        if d > 0:
            return hermite_eval(v_prev, t_prev, v, t, 1.0 + h / d, d)
    return v + h * t
