"""Viscous-sliding top: the linear set (11), ``M x' = A x`` with ``x = (omega, Phi, V)``.

State (complex, fixed frame): ``omega = omega_1 + i omega_2`` (transverse angular velocity),
``Phi = l + i m`` (tilt of the axis k), ``V = V_1 + i V_2`` (horizontal velocity of the
sphere's centre O). Parameters ``q, fr_inv, sigma, alpha_v, mu``; Coulomb friction
(``alpha_K``) is nonlinear and absent here, as in the paper.

Eq. (11)::

    omega' + i mu q V'  = i(-(sigma-1) + mu q fr_inv) Phi + (-alpha_v + i(sigma-1)) omega
                          + i alpha_v V
    Phi'                = i Phi - i omega
    V' - i q omega'     = q Phi - (q + i alpha_v/mu) omega - (alpha_v/mu) V

so ``M = [[1, 0, i mu q], [0, 1, 0], [-i q, 0, 1]]`` (``det M = 1 - mu q^2 = A_G``) and ``A``
is read off the right-hand sides.

Derivation from the vector equations (checked term by term; docs/models.md). Linearise
(1), (2), (4) about ``omega = k = K``, ``V0 = 0`` with ``omega_3 = n = 1``:

* transverse part of ``I0 omega = omega + (sigma - 1) k (k . omega)``: ``omega + (sigma-1) Phi``;
* ``mu q V0' x k -> -i mu q V'``; ``-mu q fr_inv k x K -> i mu q fr_inv Phi``;
  ``-K x F -> -i f`` with the traction ``f = f_1 + i f_2``;
* kinematics (4): ``Phi' = i Phi - i omega``, hence ``Phi'' = -Phi + omega - i omega'``;
* slip (5): ``V_c = V0 + K x omega -> V + i omega``; friction (7): ``f = -alpha_v (V + i omega)``;
* (2) then reads ``omega' + (sigma-1) Phi' + i mu q V' = i mu q fr_inv Phi - i f`` and, with
  ``Phi'`` substituted, gives the first line; (1) reads ``mu (V' + q Phi'') = f`` and gives
  the third. The appendix's scalar forms (12)-(14) reduce to the same set.

Characteristic polynomial (``mu det(s M - A)``; derived symbolically, tested against the
matrices)::

    c3 = mu (1 - mu q^2)
    c2 = alpha_v A_C - i mu sigma                          A_C = 1 + mu (1 + 2 q)
    c1 = -mu^2 q fr_inv - i alpha_v (sigma + mu (1 + q))
    c0 = -mu alpha_v q fr_inv

``c0 = 0`` exactly at ``fr_inv = 0``, ``q = 0`` or ``alpha_v = 0``: a structural zero eigenvalue
(a spin about a tilted axis is then an equilibrium). At ``alpha_v = 0`` the rest is the free
(frictionless) top ``A_G s^2 - i sigma s - mu q fr_inv``; as ``alpha_v -> infinity`` it tends
to the first-principles rolling top ``A_C s^2 - i (sigma + mu (1+q)) s - mu q fr_inv``.

Friction as feedback: with ``alpha_v = 0`` the plant ``M x' = A_0 x + B f``, slip output
``V_c = C x``, has ``B = (-i, 0, 1/mu)^T`` and ``C = (i, 0, 1)``; closing ``f = -alpha_v V_c``
gives ``A = A_0 - alpha_v B C``, eq. (11).

Convention: ``x ~ exp(s t)``, ``t`` in units of ``1/Omega``, fixed frame; growth rate
``Re s``, frequency ``Im s`` in units of the spin rate.
"""

from __future__ import annotations

import numpy as np

from .base import LinearModel
from .inertia import transverse_inertia_contact, transverse_inertia_g

__all__ = ["Sliding"]


class Sliding(LinearModel):
    """Viscous-sliding top, eq. (11)."""

    name = "sliding"
    equations = "(11)"
    parameters = ("q", "fr_inv", "sigma", "alpha_v", "mu")
    state = ("omega", "Phi", "V")
    n_modes = 3
    description = "top sliding on its sphere with viscous friction alpha_v, eq. (11)"

    def mass_matrix(self, *, q, mu) -> np.ndarray:
        """``M`` of eq. (11), shape (..., 3, 3)."""
        q, mu = np.broadcast_arrays(np.asarray(q, float), np.asarray(mu, float))
        M = np.zeros(q.shape + (3, 3), dtype=complex)
        M[..., 0, 0] = M[..., 1, 1] = M[..., 2, 2] = 1.0
        M[..., 0, 2] = 1j * mu * q
        M[..., 2, 0] = -1j * q
        return M

    def matrices(self, *, q, fr_inv, sigma, alpha_v, mu):
        """``M`` and ``A`` of eq. (11)."""
        q, fr_inv, sigma, alpha_v, mu = np.broadcast_arrays(
            *(np.asarray(v, float) for v in (q, fr_inv, sigma, alpha_v, mu)))
        A = np.zeros(q.shape + (3, 3), dtype=complex)
        A[..., 0, 0] = -alpha_v + 1j * (sigma - 1)
        A[..., 0, 1] = 1j * (-(sigma - 1) + mu * q * fr_inv)
        A[..., 0, 2] = 1j * alpha_v
        A[..., 1, 0] = -1j
        A[..., 1, 1] = 1j
        A[..., 2, 0] = -(q + 1j * alpha_v / mu)
        A[..., 2, 1] = q
        A[..., 2, 2] = -alpha_v / mu
        return self.mass_matrix(q=q, mu=mu), A

    def coefficients(self, *, q, fr_inv, sigma, alpha_v, mu):
        """``mu det(s M - A)``, highest power first (see module docstring)."""
        q, fr_inv, sigma, alpha_v, mu = np.broadcast_arrays(
            *(np.asarray(v, float) for v in (q, fr_inv, sigma, alpha_v, mu)))
        c = np.empty(q.shape + (4,), dtype=complex)
        c[..., 0] = mu * transverse_inertia_g(q, mu)
        c[..., 1] = alpha_v * transverse_inertia_contact(q, mu) - 1j * mu * sigma
        c[..., 2] = -mu * mu * q * fr_inv - 1j * alpha_v * (sigma + mu * (1.0 + q))
        c[..., 3] = -mu * alpha_v * q * fr_inv
        return c

    def friction_plant(self, *, q, fr_inv, sigma, mu):
        """Frictionless plant of the friction loop: ``(M, A_0, B, C)`` (complex, scalar params).

        ``M x' = A_0 x + B f``, slip velocity ``V_c = C x``; closing ``f = -alpha_v V_c``
        recovers eq. (11).
        """
        M, A0 = self.matrices(q=q, fr_inv=fr_inv, sigma=sigma, alpha_v=0.0, mu=mu)
        B = np.array([[-1j], [0.0], [1.0 / float(mu)]], dtype=complex)
        C = np.array([[1j, 0.0, 1.0]], dtype=complex)
        return M, A0, B, C
