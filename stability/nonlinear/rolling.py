"""Rolling sphere: eqs. (1), (2), (4) with the rolling constraint (5), ``V_c = 0``.

The centre's velocity is tied to the rotation, ``V0 = -K x omega = (omega2, -omega1, 0)``
(eq. 5), so ``V0' = -K x omega'``; the traction ``f`` is a constraint force and, with ``N``,
an unknown. With ``x = (omega'_1, omega'_2, omega'_3, f_1, f_2, N)`` eqs. (2) and (1) form a
6 x 6 linear system at each evaluation::

    I0 omega' + mu q (K x omega') x k + K x f = -(sigma-1)(k.omega)(omega x k) - mu q fr_inv k x K
    mu (-K x omega' + q omega' x k) - f - N K = -mu q omega x (omega x k) - mu fr_inv K

State vector (8 reals): ``omega (3), k (3), X0 horizontal (2)``.

Integrals (paper, Sec. 3(i)): the energy (the contact point does not move, so neither the
traction nor ``N`` does work) and ``h_cg`` of eq. (10), the angular momentum about G projected
on ``r_cg = q k + K`` (``h_cg = r_cg . I_G omega`` since the ``mu`` term of eq. 10 is normal to
``r_cg``).

First-principles linearisation about ``omega = k = K`` (derived in docs/nonlinear.md)::

    A_C Phi'' - i (sigma + mu (1 + q)) Phi' - mu fr_inv q Phi = 0,   A_C = 1 + mu (1 + 2 q),

which is the linear model ``"rolling"``; eq. (8) as printed (model ``"rolling_eq8"``)
has the gyroscopic coefficient ``sigma`` instead of ``sigma + mu (1 + q)``.
"""

from __future__ import annotations

import numpy as np

from continuation.compiled import solve_dense
from stability.jit import njit

from .parameters import MU, Q
from .sphere import normal_force_terms, sphere_rows
from .vectors import cross

__all__ = ["STATE", "contact_forces", "normal_force", "rhs"]

#: names of the state components
STATE = ("omega_1", "omega_2", "omega_3", "k_1", "k_2", "k_3", "X_1", "X_2")


@njit(cache=True)
def _solve(y, p):
    """``x = (omega', f_1, f_2, N)`` from the 6 x 6 system of the module docstring (the rows
    it shares with the sliding sphere: :func:`stability.nonlinear.sphere.sphere_rows`)."""
    mq, mu = p[MU] * p[Q], p[MU]
    k0, k1, k2 = y[3], y[4], y[5]
    a, b = sphere_rows(y, p)
    # - mu q V0' x k with V0' = (a1, -a0, 0): V0' x k = (-a0 k2, -a1 k2, a0 k0 + a1 k1)
    a[0, 0] += mq * k2
    a[1, 1] += mq * k2
    a[2, 0] -= mq * k0
    a[2, 1] -= mq * k1
    # + K x f = (-f2, f1, 0)
    a[0, 4] = -1.0
    a[1, 3] = 1.0
    # (1) horizontal: mu V0'_h = mu (omega'_2, -omega'_1), and - f_h
    a[3, 1] += mu
    a[3, 3] = -1.0
    a[4, 0] -= mu
    a[4, 4] = -1.0
    return solve_dense(a, b)


@njit(cache=True)
def rhs(t, y, p):
    """Right-hand side ``y'`` of the rolling sphere (state layout in :data:`STATE`).

    Parameters
    ----------
    t : float
        Time (autonomous system).
    y : numpy.ndarray, shape (8,)
        State, float or complex.
    p : numpy.ndarray
        Parameter vector (:func:`stability.nonlinear.parameters.pack`).
    """
    x = _solve(y, p)
    dy = np.empty_like(y)
    dy[0], dy[1], dy[2] = x[0], x[1], x[2]
    dy[3], dy[4], dy[5] = cross(y[0], y[1], y[2], y[3], y[4], y[5])
    dy[6], dy[7] = y[1], -y[0]
    return dy


@njit(cache=True)
def contact_forces(states, p):
    """``(f1, f2, N)`` along a trajectory (the traction needed to keep rolling), shape (n, 3)."""
    out = np.empty((states.shape[0], 3))
    for i in range(states.shape[0]):
        x = _solve(states[i], p)
        out[i, 0], out[i, 1], out[i, 2] = x[3], x[4], x[5]
    return out


@njit(cache=True, nogil=True)
def normal_force(y, p):
    """The normal force ``N`` in closed form, without the 6 x 6 solve: ``(N, scale)``.

    As :func:`stability.nonlinear.sliding.normal_force` (``u = k x K``,
    ``N = mu fr_inv + mu q (d_3 + omega' . u)``, ``d = omega x (omega x k)``), with the
    rolling sphere's reduced system (``benchmarks/suites/reference.py``: ``f`` eliminated by
    the horizontal part of eq. 1) ``M a = I0 a + mu q (K x a) x k + mu K x (-K x a + q a x k)``,
    ``R = -(sigma - 1)(k . omega)(omega x k) - mu q fr_inv k x K - mu q K x d``. ``u`` is an
    eigenvector of ``M^T`` for any ``k``: ``I0 u = u``; the second term's transpose
    ``-mu q [K]x [k]x`` gives ``mu q k_3 u`` (``[k]x u = k_3 k - |k|^2 K``, ``K x k = -u``); the
    third's, ``-mu [K]x [K]x - mu q [k]x [K]x``, gives ``mu u + mu q k_3 u``
    (``K x u = k_h``, ``K x k_h = -u``, ``k x k_h = -k_3 u``). So
    ``omega' . u = (u . R) / lambda``, ``lambda = 1 + mu + 2 mu q k_3`` (for a unit ``k``,
    ``A_G + mu |r|^2 > 0``, ``r`` from G to the contact point), and::

        u . R = -(sigma - 1)(k . omega)(u . (omega x k)) - mu q fr_inv |k_h|^2
                + mu q (k_1 d_1 + k_2 d_2).

    Equal to the kernel's 6 x 6 solution (:func:`contact_forces`) up to round-off; ``scale``
    the sum of the magnitudes of the terms; ``(nan, inf)`` where ``lambda`` is not safely
    positive.
    """
    q, mu = p[Q], p[MU]
    n0, s0, t_row, s_row, kd = normal_force_terms(y, p)
    mq = mu * q
    lam = 1.0 + mu + 2.0 * mq * y[5]
    if not lam > 1e-8:
        return np.nan, np.inf
    t_cen = mq * kd
    lever = mq / lam
    return n0 + lever * (t_row + t_cen), s0 + abs(lever) * (s_row + abs(t_cen))
