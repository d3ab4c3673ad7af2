"""The rows of eqs. (1)-(2) that the sliding and the rolling sphere share.

With the unknowns ``x = (omega'_1, omega'_2, omega'_3, u_1, u_2, N)``, where ``u`` is a
model's own pair of horizontal unknowns (the sliding sphere's ``V0'_h``, the rolling sphere's
traction ``f_h``), both models solve a 6 x 6 system whose rows are eqs. (2) (rows 0-2) and (1)
(rows 3-5). :func:`sphere_rows` writes what does not depend on ``u``:

* rows 0-2: ``I0 omega'`` on the left, ``-(sigma-1)(k.omega)(omega x k) - mu q fr_inv k x K``
  on the right (``k x K = (k2, -k1, 0)``);
* rows 3-4 (eq. 1, horizontal): ``mu q (omega' x k)_h`` on the left,
  ``-mu q (omega x (omega x k))_h`` on the right;
* row 5 (eq. 1, vertical): ``mu q (omega' x k)_3 - N = -mu q (omega x (omega x k))_3 - mu fr_inv``.

The models add their ``u`` columns and their own ``omega'`` terms
(:mod:`stability.nonlinear.sliding`, :mod:`stability.nonlinear.rolling`).
"""

from __future__ import annotations

import numpy as np

from stability.jit import njit

from .parameters import FR_INV, MU, SIGMA, Q
from .vectors import cross

__all__ = ["normal_force_terms", "sphere_rows"]


@njit(cache=True)
def sphere_rows(y, p):
    """``(a, b)``: the 6 x 6 matrix and right-hand side with the shared rows of the module
    docstring filled in (the ``u`` columns zero), at the state ``y`` (``omega = y[0:3]``,
    ``k = y[3:6]``) and the parameters ``p``."""
    q, fr, sg, mu = p[Q], p[FR_INV], p[SIGMA], p[MU]
    w0, w1, w2 = y[0], y[1], y[2]
    k0, k1, k2 = y[3], y[4], y[5]
    kw = k0 * w0 + k1 * w1 + k2 * w2
    c0, c1, c2 = cross(w0, w1, w2, k0, k1, k2)  # omega x k = k'
    d0, d1, d2 = cross(w0, w1, w2, c0, c1, c2)  # omega x (omega x k)
    a = np.zeros((6, 6), y.dtype)
    b = np.zeros(6, y.dtype)
    s1 = sg - 1.0
    kk = (k0, k1, k2)
    for i in range(3):  # I0 omega'
        a[i, i] = 1.0
        for j in range(3):
            a[i, j] += s1 * kk[i] * kk[j]
    mq = mu * q
    b[0] = -s1 * kw * c0 - mq * fr * k1
    b[1] = -s1 * kw * c1 + mq * fr * k0
    b[2] = -s1 * kw * c2
    a[3, 1] = mq * k2
    a[3, 2] = -mq * k1
    a[4, 0] = -mq * k2
    a[4, 2] = mq * k0
    b[3] = -mq * d0
    b[4] = -mq * d1
    a[5, 0] = mq * k1
    a[5, 1] = -mq * k0
    a[5, 5] = -1.0
    b[5] = -mq * d2 - mu * fr
    return a, b


@njit(cache=True, nogil=True)
def normal_force_terms(y, p):
    """The pieces of the closed-form normal force the two spheres share
    (:func:`stability.nonlinear.sliding.normal_force`, :func:`stability.nonlinear.rolling.normal_force`).

    With ``u = k x K`` and ``d = omega x (omega x k)``: ``N = n0 + mu q (omega' . u)``,
    ``n0 = mu fr_inv + mu q d_3`` (row 5), and ``u`` dotted with the right-hand side of rows 0-2,
    ``t = -(sigma - 1)(k . omega)(u . (omega x k)) - mu q fr_inv |k_h|^2``.

    Returns
    -------
    tuple
        ``(n0, |mu fr_inv| + |mu q d_3|, t, sum of the magnitudes of t's two terms,
        k_1 d_1 + k_2 d_2)`` (the last for the models' own centripetal term).
    """
    q, fr, sg, mu = p[Q], p[FR_INV], p[SIGMA], p[MU]
    w0, w1, w2 = y[0], y[1], y[2]
    k0, k1, k2 = y[3], y[4], y[5]
    c0, c1, c2 = cross(w0, w1, w2, k0, k1, k2)  # omega x k
    d0, d1, d2 = cross(w0, w1, w2, c0, c1, c2)  # omega x (omega x k)
    mq = mu * q
    t_gyro = -(sg - 1.0) * (k0 * w0 + k1 * w1 + k2 * w2) * (k1 * c0 - k0 * c1)
    t_grav = -mq * fr * (k0 * k0 + k1 * k1)
    return mu * fr + mq * d2, abs(mu * fr) + abs(mq * d2), t_gyro + t_grav, abs(t_gyro) + abs(t_grav), k0 * d0 + k1 * d1
