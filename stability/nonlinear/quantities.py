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
"""

from __future__ import annotations

import numpy as np

__all__ = ["energy_parts", "h_cg", "centre_of_mass_velocity"]


def centre_of_mass_velocity(omega: np.ndarray, k: np.ndarray, v0: np.ndarray, arm: float) -> np.ndarray:
    """``V_G = V0 + arm omega x k`` (arm = q from O, 1 + q from the pivot), shape (n, 3)."""
    return v0 + arm * np.cross(omega, k)


def energy_parts(omega: np.ndarray, k: np.ndarray, v_g: np.ndarray, z_g: np.ndarray, *,
                 q: float, fr_inv: float, sigma: float, mu: float) -> dict[str, np.ndarray]:
    """Kinetic (translational, spin, transverse) and potential energy, and their sum.

    Parameters
    ----------
    omega, k, v_g : numpy.ndarray, shape (n, 3)
        Angular velocity, axis, velocity of G (fixed frame).
    z_g : numpy.ndarray, shape (n,)
        Height of G above the reference level of the potential.
    q, fr_inv, sigma, mu : float

    Returns
    -------
    dict of numpy.ndarray
        ``kinetic_translational``, ``kinetic_spin``, ``kinetic_transverse``, ``potential``,
        ``energy``.
    """
    a_g = 1.0 - mu * q * q
    wk = np.einsum("ij,ij->i", omega, k)
    parts = {
        "kinetic_translational": 0.5 * mu * np.einsum("ij,ij->i", v_g, v_g),
        "kinetic_spin": 0.5 * sigma * wk ** 2,
        "kinetic_transverse": 0.5 * a_g * (np.einsum("ij,ij->i", omega, omega) - wk ** 2),
        "potential": mu * fr_inv * z_g,
    }
    parts["energy"] = sum(parts.values())
    return parts


def h_cg(omega: np.ndarray, k: np.ndarray, *, q: float, sigma: float, mu: float) -> np.ndarray:
    """The integral of eq. (10), ``(q k + K) . I_G omega``, shape (n,)."""
    a_g = 1.0 - mu * q * q
    wk = np.einsum("ij,ij->i", omega, k)
    l_g = a_g * omega + (sigma - a_g) * wk[:, None] * k
    r = q * k
    r[:, 2] += 1.0
    return np.einsum("ij,ij->i", r, l_g)
