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

Exact derivatives of the coefficients (they are polynomials in the parameters; with
``A_C = 1 + mu (1 + 2 q)``, ``dA_G/dq = -2 mu q``, ``dA_C/dq = 2 mu``, ``dA_G/dmu = -q^2``,
``dA_C/dmu = 1 + 2 q``)::

    d/dq       : c3' = -2 mu^2 q,      c2' = 2 mu alpha_v,                 c1' = -mu^2 fr_inv - i alpha_v mu,
                 c0' = -mu alpha_v fr_inv
    d/dfr_inv  : c3' = 0,  c2' = 0,    c1' = -mu^2 q,                      c0' = -mu alpha_v q
    d/dsigma   : c3' = 0,  c2' = -i mu, c1' = -i alpha_v,                  c0' = 0
    d/dalpha_v : c3' = 0,  c2' = A_C,  c1' = -i (sigma + mu (1 + q)),      c0' = -mu q fr_inv
    d/dmu      : c3' = 1 - 2 mu q^2,   c2' = alpha_v (1 + 2 q) - i sigma,
                 c1' = -2 mu q fr_inv - i alpha_v (1 + q),                  c0' = -alpha_v q fr_inv

One home, three engines. :func:`coefficient_parts` and :func:`derivative_parts` are the only
place these formulas are written. They are plain arithmetic, registered with
:func:`numba.extending.register_jitable`, and return real and imaginary parts as separate
reals (the caller assembles ``complex(re, im)`` or fills ``.real``/``.imag``), so that the same
source runs on Python floats (the neutral condition's scalar path), on numpy arrays
(:meth:`Sliding.coefficients`) and compiled into numba kernels (the spectral kernel, the
compiled neutral condition), with the same floating-point operations and hence the same bits
in every engine. :class:`Sliding` offers them to the rest of the package as its optional
capabilities ``point_coefficients`` and ``point_derivatives`` (:mod:`stability.models.base`).

Convention: every model's (:mod:`stability.models.base`).
"""

from __future__ import annotations

import numpy as np

from stability.jit import register_jitable

from .base import LinearModel
from .inertia import inertia_contact, inertia_g

__all__ = ["Sliding", "coefficient_parts", "derivative_parts"]

#: the parameters of eq. (11), in the order of :data:`stability.parameters.PARAMETERS` (the
#: index ``k`` of :func:`derivative_parts`)
PARAMETER_ORDER = ("q", "fr_inv", "sigma", "alpha_v", "mu")


@register_jitable
def coefficient_parts(q, fr_inv, sigma, alpha_v, mu):
    """``mu det(s M - A)`` of eq. (11) as real and imaginary parts, highest power first.

    Returns ``(Re c3, Im c3, Re c2, Im c2, Re c1, Im c1, Re c0, Im c0)`` with ``c3 = mu A_G``,
    ``c2 = alpha_v A_C - i mu sigma``, ``c1 = -mu^2 q fr_inv - i alpha_v (sigma + mu (1 + q))``,
    ``c0 = -mu alpha_v q fr_inv`` (``A_G`` compensated, :func:`stability.models.inertia.inertia_g`).
    Plain arithmetic: floats, numpy arrays (broadcast together) or numba.
    """
    a_g = inertia_g(q, mu)
    a_c = inertia_contact(q, mu, a_g)
    return (
        mu * a_g,
        0.0,
        alpha_v * a_c,
        -(mu * sigma),
        -mu * mu * q * fr_inv,
        -(alpha_v * (sigma + mu * (1.0 + q))),
        -mu * alpha_v * q * fr_inv,
        0.0,
    )


@register_jitable
def derivative_parts(q, fr_inv, sigma, alpha_v, mu, k):
    """Exact derivatives of :func:`coefficient_parts` by parameter ``k`` (0 ``q``, 1 ``fr_inv``,
    2 ``sigma``, 3 ``alpha_v``, 4 ``mu``; module docstring), in the same layout."""
    if k == 0:
        return (
            -2.0 * mu * mu * q,
            0.0,
            2.0 * mu * alpha_v,
            0.0,
            -mu * mu * fr_inv,
            -alpha_v * mu,
            -mu * alpha_v * fr_inv,
            0.0,
        )
    if k == 1:
        return (0.0, 0.0, 0.0, 0.0, -mu * mu * q, 0.0, -mu * alpha_v * q, 0.0)
    if k == 2:
        return (0.0, 0.0, 0.0, -mu, 0.0, -alpha_v, 0.0, 0.0)
    if k == 3:
        return (
            0.0,
            0.0,
            inertia_contact(q, mu, inertia_g(q, mu)),
            0.0,
            0.0,
            -(sigma + mu * (1.0 + q)),
            -mu * q * fr_inv,
            0.0,
        )
    return (
        1.0 - 2.0 * mu * q * q,
        0.0,
        alpha_v * (1.0 + 2.0 * q),
        -sigma,
        -2.0 * mu * q * fr_inv,
        -alpha_v * (1.0 + q),
        -alpha_v * q * fr_inv,
        0.0,
    )


class Sliding(LinearModel):
    """Viscous-sliding top, eq. (11)."""

    name = "sliding"
    equations = "(11)"
    parameters = PARAMETER_ORDER
    state = ("omega", "Phi", "V")
    n_modes = 3
    description = "top sliding on its sphere with viscous friction alpha_v, eq. (11)"
    # the optional capabilities of the contract (stability.models.base): one point's
    # coefficients and their exact derivatives, for every engine
    point_coefficients = staticmethod(coefficient_parts)
    point_derivatives = staticmethod(derivative_parts)

    def matrices(self, *, q, fr_inv, sigma, alpha_v, mu):
        """``M`` and ``A`` of eq. (11), shape (..., 3, 3)."""
        q, fr_inv, sigma, alpha_v, mu = np.broadcast_arrays(
            *map(np.asarray, (q, fr_inv, sigma, alpha_v, mu), [float] * 5)
        )
        M = np.zeros(q.shape + (3, 3), dtype=complex)
        M[..., 0, 0] = M[..., 1, 1] = M[..., 2, 2] = 1.0
        M[..., 0, 2] = 1j * mu * q
        M[..., 2, 0] = -1j * q
        A = np.zeros(q.shape + (3, 3), dtype=complex)
        A[..., 0, 0] = -alpha_v + 1j * (sigma - 1)
        A[..., 0, 1] = 1j * (-(sigma - 1) + mu * q * fr_inv)
        A[..., 0, 2] = 1j * alpha_v
        A[..., 1, 0] = -1j
        A[..., 1, 1] = 1j
        A[..., 2, 0] = -(q + 1j * alpha_v / mu)
        A[..., 2, 1] = q
        A[..., 2, 2] = -alpha_v / mu
        return M, A

    def coefficients(self, *, q, fr_inv, sigma, alpha_v, mu):
        """``mu det(s M - A)``, highest power first (:func:`coefficient_parts` on arrays)."""
        q, fr_inv, sigma, alpha_v, mu = np.broadcast_arrays(
            *map(np.asarray, (q, fr_inv, sigma, alpha_v, mu), [float] * 5)
        )
        parts = coefficient_parts(q, fr_inv, sigma, alpha_v, mu)
        c = np.empty(q.shape + (4,), dtype=complex)
        for j in range(4):
            c.real[..., j], c.imag[..., j] = parts[2 * j], parts[2 * j + 1]
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
