"""Heavy symmetric top on a fixed pivot at the sphere's bottom point (model of eqs. 8-9, h = 1 + q).

The pivot P is the body point ``O - R k`` held fixed at the origin; G lies ``(1 + q) R`` above
it along ``k``. About P (nondimensional)::

    d/dt (I_P omega) = -mu fr_inv (1 + q) k x K,       k' = omega x k              (2'), (4)

with ``I_P = A_C 1 + (sigma - A_C) k k^T``, ``A_C = 1 + mu (1 + 2 q)`` (transverse moment
about P), so ``I_P omega' = -(sigma - A_C)(k . omega)(omega x k) - mu fr_inv (1 + q) k x K``,
solved in closed form (Sherman-Morrison). The pivot reaction is
``F = mu (1 + q) k'' + mu fr_inv K``.

State vector (6 reals): ``omega (3), k (3)``. Integrals: energy, the spin ``omega . k``
(``sigma`` times it is the axial angular momentum) and the vertical angular momentum about P.
Linearisation: ``A_C Phi'' - i sigma Phi' - mu fr_inv (1 + q) Phi = 0``, eq. (8).
"""

from __future__ import annotations

import numpy as np

from stability.jit import njit

from .parameters import FR_INV, MU, SIGMA, Q
from .vectors import cross

__all__ = ["STATE", "contact_forces", "rhs"]

#: names of the state components
STATE = ("omega_1", "omega_2", "omega_3", "k_1", "k_2", "k_3")


@njit(cache=True)
def rhs(t, y, p):
    """Right-hand side ``y'`` of the top on a fixed pivot (state layout in :data:`STATE`)."""
    q, fr, sg, mu = p[Q], p[FR_INV], p[SIGMA], p[MU]
    ac = 1.0 + mu * (1.0 + 2.0 * q)
    c = sg - ac
    w0, w1, w2 = y[0], y[1], y[2]
    k0, k1, k2 = y[3], y[4], y[5]
    kw = k0 * w0 + k1 * w1 + k2 * w2
    c0, c1, c2 = cross(w0, w1, w2, k0, k1, k2)
    g = mu * fr * (1.0 + q)
    r0 = -c * kw * c0 - g * k1
    r1 = -c * kw * c1 + g * k0
    r2 = -c * kw * c2
    # (ac 1 + c k k^T)^-1 r = (r - c k (k.r) / (ac + c |k|^2)) / ac
    kr = (k0 * r0 + k1 * r1 + k2 * r2) * c / (ac + c * (k0 * k0 + k1 * k1 + k2 * k2))
    dy = np.empty_like(y)
    dy[0] = (r0 - k0 * kr) / ac
    dy[1] = (r1 - k1 * kr) / ac
    dy[2] = (r2 - k2 * kr) / ac
    dy[3], dy[4], dy[5] = c0, c1, c2
    return dy


@njit(cache=True)
def contact_forces(states, p):
    """``(F1, F2, F3)``, the pivot reaction ``mu (1 + q) k'' + mu fr_inv K``, shape (n, 3)."""
    q, fr, mu = p[Q], p[FR_INV], p[MU]
    out = np.empty((states.shape[0], 3))
    for i in range(states.shape[0]):
        y = states[i]
        dy = rhs(0.0, y, p)
        a0, a1, a2 = cross(dy[0], dy[1], dy[2], y[3], y[4], y[5])
        b0, b1, b2 = cross(y[0], y[1], y[2], dy[3], dy[4], dy[5])
        m = mu * (1.0 + q)
        out[i, 0] = m * (a0 + b0)
        out[i, 1] = m * (a1 + b1)
        out[i, 2] = m * (a2 + b2) + mu * fr
    return out
