"""Energy, momenta and the integral h_cg along a trajectory (vectorised over samples).

Nondimensional (energy in units of ``A0 Omega^2``). With ``G = O + q k`` and ``I_G = A_G 1 +
(sigma - A_G) k k^T``, ``A_G = 1 - mu q^2``:

* translational kinetic energy ``mu |V_G|^2 / 2``, ``V_G = V0 + q omega x k`` (for the fixed
  pivot ``V_G = (1 + q) omega x k``);
* rotational energy about G split into spin ``sigma (omega . k)^2 / 2`` and transverse
  ``A_G (|omega|^2 - (omega . k)^2) / 2`` parts;
* potential ``mu fr_inv z_G`` with ``z_G`` the height of G above the plane, ``1 + q k_3``
  (above the pivot, ``(1 + q) k_3``, for the fixed pivot);
* ``h_cg = r_cg . I_G omega`` with ``r_cg = q k + K`` (eq. 10; the ``mu`` term of eq. 10 is
  normal to ``r_cg``). ``dh_cg/dt = q (omega x k) . I_G omega = 0`` for any force acting at the
  contact point, so ``h_cg`` is conserved by the rolling sphere and also by the sliding sphere
  with any friction law (Jellett's integral).

``A_G`` is :func:`stability.models.inertia.inertia_g` (compensated: accurate near the domain
edge), its one home. The formulas are written once, by components, as plain arithmetic
registered with numba (:func:`centre_velocity`, :func:`energy_terms`) or compiled
(:func:`jellett_integral`): the array functions apply them to columns, and compiled callers
(the steady layer's integrals of one state, the branch's complex steps) call them directly.
"""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np

from stability.jit import njit, register_jitable

from ..execution import pick
from ..models.inertia import inertia_g

__all__ = [
    "ENERGY_PARTS",
    "centre_velocity",
    "energy_parts",
    "energy_terms",
    "h_cg",
    "jellett_integral",
]

#: the names of :func:`energy_parts` (the order of :func:`energy_terms`)
ENERGY_PARTS = ("kinetic_translational", "kinetic_spin", "kinetic_transverse", "potential", "energy")


@register_jitable
def centre_velocity(w0, w1, w2, k0, k1, k2, v0, v1, v2, arm):
    """``V_G = V0 + arm omega x k`` by components (arm = q from O, 1 + q from the pivot).

    Plain arithmetic registered with numba (floats, numpy arrays elementwise, compiled callers)."""
    return (v0 + arm * (w1 * k2 - w2 * k1), v1 + arm * (w2 * k0 - w0 * k2), v2 + arm * (w0 * k1 - w1 * k0))


@register_jitable
def energy_terms(w0, w1, w2, k0, k1, k2, g0, g1, g2, z_g, q, fr_inv, sigma, mu):
    """The parts of the energy and their sum, by components (the order of :data:`ENERGY_PARTS`).

    ``omega = (w0, w1, w2)``, ``k = (k0, k1, k2)``, ``V_G = (g0, g1, g2)``, ``z_G`` the height of
    G; ``A_G`` is :func:`stability.models.inertia.inertia_g`. Plain arithmetic registered with
    numba: floats, numpy arrays (elementwise), compiled callers."""
    a_g = inertia_g(q, mu)
    wk = w0 * k0 + w1 * k1 + w2 * k2
    translational = 0.5 * mu * (g0 * g0 + g1 * g1 + g2 * g2)
    spin = 0.5 * sigma * (wk * wk)
    transverse = 0.5 * a_g * ((w0 * w0 + w1 * w1 + w2 * w2) - wk * wk)
    potential = mu * fr_inv * z_g
    return translational, spin, transverse, potential, ((translational + spin) + transverse) + potential


def energy_parts(
    omega: np.ndarray, k: np.ndarray, v_g: np.ndarray, z_g: np.ndarray, params: Mapping[str, float]
) -> dict[str, np.ndarray]:
    """Kinetic (translational, spin, transverse) and potential energy, and their sum.

    Parameters
    ----------
    omega, k, v_g : numpy.ndarray, shape (n, 3)
        Angular velocity, axis, velocity of G (fixed frame).
    z_g : numpy.ndarray, shape (n,)
        Height of G above the reference level of the potential.
    params : mapping
        ``q, fr_inv, sigma, mu`` (floats; others are ignored).

    Returns
    -------
    dict of numpy.ndarray
        ``kinetic_translational``, ``kinetic_spin``, ``kinetic_transverse``, ``potential``,
        ``energy``.
    """
    w, kk, g = np.asarray(omega), np.asarray(k), np.asarray(v_g)
    top = (params["q"], params["fr_inv"], params["sigma"], params["mu"])
    return dict(zip(ENERGY_PARTS, energy_terms(*w.T, *kk.T, *g.T, np.asarray(z_g), *top)))


@njit(cache=True)
def jellett_integral(w0, w1, w2, k0, k1, k2, q, sigma, mu):
    """The integral of eq. (10) at one state, ``(q k + K) . I_G omega`` (Jellett's integral).

    ``I_G omega = A_G omega + (sigma - A_G) (omega . k) k`` with ``A_G = 1 - mu q^2``
    (:func:`stability.models.inertia.inertia_g`, compiled in). Compiled; the components may be
    real or complex (complex-step derivatives). :func:`h_cg` is the same formula over many states."""
    a_g = inertia_g(q, mu)
    wk = w0 * k0 + w1 * k1 + w2 * k2
    b = (sigma - a_g) * wk
    return (q * k0) * (a_g * w0 + b * k0) + (q * k1) * (a_g * w1 + b * k1) + (1.0 + q * k2) * (a_g * w2 + b * k2)


@njit(cache=True)
def _h_cg_rows(omega, k, q, sigma, mu):
    out = np.empty(omega.shape[0], dtype=omega.dtype)
    for i in range(omega.shape[0]):
        out[i] = jellett_integral(omega[i, 0], omega[i, 1], omega[i, 2], k[i, 0], k[i, 1], k[i, 2], q, sigma, mu)
    return out


def h_cg(omega: np.ndarray, k: np.ndarray, *, q: float, sigma: float, mu: float) -> np.ndarray:
    """The integral of eq. (10), ``(q k + K) . I_G omega``, shape (n,) (:func:`jellett_integral`
    at each row; real or complex input)."""
    omega = np.asarray(omega)
    k = np.asarray(k)
    dtype = np.result_type(omega, k, float)
    return pick(_h_cg_rows, omega.shape[0])(
        np.ascontiguousarray(omega, dtype=dtype),
        np.ascontiguousarray(k, dtype=dtype),
        float(q),
        float(sigma),
        float(mu),
    )
