"""Sliding sphere: the vector equations (1), (2), (4) with the contact constraint and friction (7).

Nondimensional (length R, time 1/Omega, inertia A0), fixed frame ``F_a`` with ``K`` up::

    mu (V0' + q k'') = N K + f - mu fr_inv K                                    (1)
    d/dt (I0 omega)  = mu q V0' x k - mu q fr_inv k x K - K x (N K + f)         (2)
    k'               = omega x k                                                (4)
    X0'              = V0

with ``I0 = 1 + (sigma - 1) k k^T``, hence ``d/dt (I0 omega) = I0 omega'
+ (sigma - 1)(k . omega)(omega x k)``, and ``k'' = omega' x k + omega x (omega x k)``.
Contact constraint: the centre O stays at height R, so ``V0 . K = 0`` and ``V0' . K = 0``;
the normal force ``N`` follows from the vertical component of (1). Slip velocity (5):
``V_c = V0 + K x omega = (V1 - omega2, V2 + omega1, 0)``; friction ``f`` from eq. (7) (see
:mod:`stability.nonlinear.friction`). Not the appendix's scalar equations (12)-(14), which
drop products of small quantities.

At every evaluation the unknowns ``x = (omega'_1, omega'_2, omega'_3, V0'_1, V0'_2, N)``
solve the 6 x 6 linear system made of (2) and the three components of (1); with friction
proportional to ``N(t)`` the friction columns enter the same system, so no iteration is
needed.

State vector (10 reals): ``omega (3), k (3), V0 horizontal (2), X0 horizontal (2)``.

Linearisation about ``omega = k = K`` (spin +1) is eq. (11) (``stability.models.sliding``);
:func:`stability.jacobian_eigenvalues` checks it from this right-hand side.
"""

from __future__ import annotations

import numpy as np

from continuation.compiled import solve_dense
from stability.jit import njit

from .friction import traction
from .parameters import ALPHA_K, ALPHA_V, EPSILON, FR_INV, LAW, MU, NORMAL, Q
from .sphere import normal_force_terms, sphere_rows
from .vectors import cross

__all__ = ["STATE", "contact_forces", "normal_force", "rhs"]

#: names of the state components
STATE = ("omega_1", "omega_2", "omega_3", "k_1", "k_2", "k_3", "V_1", "V_2", "X_1", "X_2")


@njit(cache=True)
def _solve(y, p):
    """Accelerations, normal force and friction: ``(x, f1, f2)``, ``x`` as in the docstring (the
    rows it shares with the rolling sphere: :func:`stability.nonlinear.sphere.sphere_rows`)."""
    q, fr, mu = p[Q], p[FR_INV], p[MU]
    w0, w1 = y[0], y[1]
    k0, k1, k2 = y[3], y[4], y[5]
    v0, v1 = y[6], y[7]
    g1, g2 = traction(v0 - w1, v1 + w0, p[ALPHA_V], p[ALPHA_K], p[EPSILON], p[LAW])
    a, b = sphere_rows(y, p)
    mq = mu * q
    # - mu q V0' x k,  V0' = (b1, b2, 0): V0' x k = (b2 k3, -b1 k3, b1 k2 - b2 k1)
    a[0, 4] = -mq * k2
    a[1, 3] = mq * k2
    a[2, 3] = -mq * k1
    a[2, 4] = mq * k0
    # (1), horizontal: mu V0'
    a[3, 3] = mu
    a[4, 4] = mu
    if p[NORMAL] == 0.0:
        # f = g known: K x f = (-g2, g1, 0) moves to the right of (2); f_h to the right of (1)
        b[0] += g2
        b[1] -= g1
        b[3] += g1
        b[4] += g2
    else:
        # f = N g / (mu fr_inv): columns of N
        r = 1.0 / (mu * fr)
        a[0, 5] = -g2 * r
        a[1, 5] = g1 * r
        a[3, 5] = -g1 * r
        a[4, 5] = -g2 * r
    x = solve_dense(a, b)
    if p[NORMAL] == 0.0:
        return x, g1, g2
    r = x[5] / (mu * fr)
    return x, g1 * r, g2 * r


@njit(cache=True)
def rhs(t, y, p):
    """Right-hand side ``y'`` of the sliding sphere (state layout in :data:`STATE`).

    Parameters
    ----------
    t : float
        Time (the system is autonomous).
    y : numpy.ndarray, shape (10,)
        State; float or complex (complex for the complex-step Jacobian).
    p : numpy.ndarray
        Parameter vector (:func:`stability.nonlinear.parameters.pack`).
    """
    x, f1, f2 = _solve(y, p)
    dy = np.empty_like(y)
    dy[0], dy[1], dy[2] = x[0], x[1], x[2]
    dy[3], dy[4], dy[5] = cross(y[0], y[1], y[2], y[3], y[4], y[5])
    dy[6], dy[7] = x[3], x[4]
    dy[8], dy[9] = y[6], y[7]
    return dy


@njit(cache=True)
def contact_forces(states, p):
    """Normal force and friction along a trajectory.

    Parameters
    ----------
    states : numpy.ndarray, shape (n, 10)
    p : numpy.ndarray
        Parameter vector.

    Returns
    -------
    numpy.ndarray, shape (n, 3)
        ``(f1, f2, N)`` at each sample.
    """
    out = np.empty((states.shape[0], 3))
    for i in range(states.shape[0]):
        x, f1, f2 = _solve(states[i], p)
        out[i, 0], out[i, 1], out[i, 2] = f1, f2, x[5]
    return out


@njit(cache=True, nogil=True)
def normal_force(y, p):
    """The normal force ``N`` in closed form, without the 6 x 6 solve: ``(N, scale)``.

    Derivation (eqs. 1, 2 about O, as the kernel's system; any ``k``, unit or not). With
    ``u = k x K = (k_2, -k_1, 0)``, the vertical component of (1) reads
    ``N = mu fr_inv + mu q (d_3 + omega' . u)``, ``d = omega x (omega x k)``, since
    ``(omega' x k)_3 = omega' . (k x K)``. Eliminating ``V0'`` from (2) by the horizontal part of
    (1) gives ``M omega' = R`` (``benchmarks/suites/reference.py``), ``M a = I0 a
    + mu q^2 (P (a x k)) x k = I0 a + mu q^2 [k]x P [k]x a``, symmetric. ``u`` is an
    eigenvector of ``M``: ``I0 u = u`` (``k . u = 0``), ``[k]x u = k_3 k - |k|^2 K``,
    ``P [k]x u = k_3 k_h``, ``[k]x (k_3 k_h) = -k_3^2 u``; so ``M u = (1 - mu q^2 k_3^2) u`` and
    ``omega' . u = (u . R) / (1 - mu q^2 k_3^2)``, with (the terms of ``R`` dotted with ``u``)::

        u . R = -(sigma - 1)(k . omega)(u . (omega x k)) - mu q fr_inv |k_h|^2
                + (1 + q k_3)(k_1 f_1 + k_2 f_2) - mu q^2 k_3 (k_1 d_1 + k_2 d_2).

    With the friction proportional to ``N`` (``normal = "actual"``, ``f = N g / (mu fr_inv)``)
    the friction term is ``N rho``, ``rho = (1 + q k_3)(k_1 g_1 + k_2 g_2) / (mu fr_inv)``, and
    ``N (1 - mu q rho / (1 - mu q^2 k_3^2))`` equals the rest. (For a unit ``k``,
    ``1 - mu q^2 k_3^2 = A_G + mu q^2 |k_h|^2 > 0``: the same as Euler's law about G.)

    The result equals the kernel's 6 x 6 solution (:func:`contact_forces`) up to round-off;
    ``scale`` is the sum of the magnitudes of its terms (round-off is a few ``eps * scale``).
    Where a denominator is not safely positive: ``(nan, inf)``. The integrators' scipy path
    uses it to screen the accepted steps (:func:`stability.nonlinear.kernels.normal_force_lower_bound`).
    """
    q, fr, mu = p[Q], p[FR_INV], p[MU]
    k0, k1, k2 = y[3], y[4], y[5]
    n0, s0, t_row, s_row, kd = normal_force_terms(y, p)
    g1, g2 = traction(y[6] - y[1], y[7] + y[0], p[ALPHA_V], p[ALPHA_K], p[EPSILON], p[LAW])
    mq = mu * q
    den = 1.0 - mq * q * k2 * k2
    if not den > 1e-8:
        return np.nan, np.inf
    t_cen = -mq * q * k2 * kd
    t_fric = (1.0 + q * k2) * (k0 * g1 + k1 * g2)
    lever = mq / den
    top = n0 + lever * (t_row + t_cen)
    scale = s0 + abs(lever) * (s_row + abs(t_cen))
    if p[NORMAL] == 0.0:
        return top + lever * t_fric, scale + abs(lever * t_fric)
    bottom = 1.0 - lever * t_fric / (mu * fr)
    if not bottom > 1e-8:
        return np.nan, np.inf
    return top / bottom, (scale + abs(lever * t_fric / (mu * fr)) * abs(top)) / bottom
