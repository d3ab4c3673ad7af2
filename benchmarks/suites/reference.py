"""Plain-numpy right-hand sides in vector form: a second, slower implementation of the sliding
and rolling spheres (:mod:`stability.nonlinear.sliding`, :mod:`stability.nonlinear.rolling`).

The tests' independent reference for the compiled kernels and the baseline of the integrator
suite (:mod:`suites.integrators`); beside the package, not installed. The elimination differs from the kernels': the centre's
acceleration is eliminated first and only a 3 x 3 system for ``omega'`` is solved.

Sliding (friction scaled by the equilibrium normal force), from (1) horizontal:
``V0' = P (f / mu - q k'')`` with ``P = 1 - K K^T`` and ``k'' = omega' x k + omega x (omega x k)``;
substituted in (2)::

    I0 omega' + mu q^2 (P (omega' x k)) x k
        = -(sigma-1)(k.omega) omega x k + q (P f) x k - mu q^2 (P (omega x (omega x k))) x k
          - mu q fr_inv k x K - K x f.

Rolling: ``V0' = -K x omega'`` and ``f_h = mu (V0' + q k'')_h`` (the ``K x`` in (2) ignores the
vertical part), so::

    I0 omega' + mu q (K x omega') x k + mu K x (-K x omega' + q omega' x k)
        = -(sigma-1)(k.omega) omega x k - mu q fr_inv k x K - mu q K x (omega x (omega x k)).
"""

from __future__ import annotations

import numpy as np

from stability.nonlinear.friction import traction

__all__ = ["rolling_rhs", "sliding_rhs"]

_K = np.array([0.0, 0.0, 1.0])
_P = np.diag([1.0, 1.0, 0.0])


def _linear_operator(fun) -> np.ndarray:
    """Matrix of a linear map of 3-vectors, column by column."""
    return np.column_stack([fun(e) for e in np.eye(3)])


def sliding_rhs(
    t: float,
    y: np.ndarray,
    q: float,
    fr_inv: float,
    sigma: float,
    mu: float,
    alpha_v: float,
    alpha_k: float = 0.0,
    epsilon: float = 1e-4,
    law: int = 0,
) -> np.ndarray:
    """``y'`` of the sliding sphere (state as :data:`stability.nonlinear.sliding.STATE`)."""
    w, k = y[0:3], y[3:6]
    v0 = np.array([y[6], y[7], 0.0])
    vc = v0 + np.cross(_K, w)
    f = np.array([*traction(vc[0], vc[1], alpha_v, alpha_k, epsilon, float(law)), 0.0])
    i0 = np.eye(3) + (sigma - 1.0) * np.outer(k, k)
    cen = np.cross(w, np.cross(w, k))
    L = _linear_operator(lambda a: i0 @ a + mu * q * q * np.cross(_P @ np.cross(a, k), k))
    rhs = (
        -(sigma - 1.0) * (k @ w) * np.cross(w, k)
        + q * np.cross(_P @ f, k)
        - mu * q * q * np.cross(_P @ cen, k)
        - mu * q * fr_inv * np.cross(k, _K)
        - np.cross(_K, f)
    )
    wd = np.linalg.solve(L, rhs)
    vd = _P @ (f / mu - q * (np.cross(wd, k) + cen))
    return np.concatenate([wd, np.cross(w, k), vd[:2], v0[:2]])


def rolling_rhs(t: float, y: np.ndarray, q: float, fr_inv: float, sigma: float, mu: float) -> np.ndarray:
    """``y'`` of the rolling sphere (state as :data:`stability.nonlinear.rolling.STATE`)."""
    w, k = y[0:3], y[3:6]
    i0 = np.eye(3) + (sigma - 1.0) * np.outer(k, k)
    cen = np.cross(w, np.cross(w, k))
    L = _linear_operator(
        lambda a: (
            i0 @ a + mu * q * np.cross(np.cross(_K, a), k) + mu * np.cross(_K, -np.cross(_K, a) + q * np.cross(a, k))
        )
    )
    rhs = -(sigma - 1.0) * (k @ w) * np.cross(w, k) - mu * q * fr_inv * np.cross(k, _K) - mu * q * np.cross(_K, cen)
    wd = np.linalg.solve(L, rhs)
    v0 = -np.cross(_K, w)
    return np.concatenate([wd, np.cross(w, k), v0[:2]])
