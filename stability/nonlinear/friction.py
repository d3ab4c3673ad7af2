"""The friction law (7) and its component-wise variant (16).

Nondimensional tangential force at the contact point (paper, eq. 7)::

    f = -(alpha_k e_v + alpha_v V_c),      e_v = V_c / |V_c|,

with the slip velocity ``V_c = V0 + K x omega`` (eq. 5), horizontal. The nondimensionalisation
of eq. (7) (``alpha_k = mu Fr^-1 mu_K``, ``alpha_v = mu Omega R Fr^-1 mu_v``) takes the normal
force at its equilibrium value ``mu fr_inv`` (the paper's law, the default here); with the
option ``normal="actual"`` the force is multiplied by ``N(t) / (mu fr_inv)``, which is
Coulomb's proportionality to the instantaneous normal reaction (eq. 6).

Two Coulomb laws, both regularised at slip speeds below ``slip_scale`` (``epsilon``):

* ``"isotropic"`` (default, eq. 7): ``e_v = V_c / sqrt(|V_c|^2 + epsilon^2)``, a force of
  magnitude ``alpha_k`` opposite to the slip whenever ``|V_c| >> epsilon``;
* ``"componentwise"`` (eq. 16): ``f_i = -alpha_k sgn(V_ci) - alpha_v V_ci`` with
  ``sgn(v) ~ v / sqrt(v^2 + epsilon^2)``; a different law (its magnitude ranges from
  ``alpha_k`` to ``sqrt(2) alpha_k`` with the slip direction).

The regularisation replaces the Coulomb term by a viscous one of coefficient
``alpha_k / epsilon`` for slips below ``epsilon``; its relative effect at slip ``|V_c|`` is
``epsilon^2 / (2 |V_c|^2)``. The default ``epsilon = 1e-4`` is two orders below the smallest
slip of the paper's runs (docs/nonlinear.md); it costs small steps, or the implicit path, only
when the slip actually comes near zero.
"""

from __future__ import annotations

import numpy as np

from stability.jit import njit

__all__ = ["DEFAULT_SLIP_SCALE", "FRICTION_LAWS", "NORMAL_FORCE", "traction"]

#: names of the Coulomb laws, in the code used by the compiled kernels
FRICTION_LAWS: dict[str, int] = {"isotropic": 0, "componentwise": 1}
#: which normal force scales the friction: the equilibrium value (paper) or N(t)
NORMAL_FORCE: dict[str, int] = {"equilibrium": 0, "actual": 1}
#: default regularisation scale epsilon of the Coulomb term (nondimensional slip speed)
DEFAULT_SLIP_SCALE: float = 1e-4


@njit(cache=True)
def traction(vc1, vc2, alpha_v: float, alpha_k: float, epsilon: float, law: float):
    """Friction force per unit normal-force factor, eq. (7) or eq. (16).

    Parameters
    ----------
    vc1, vc2 : float or complex
        Horizontal slip velocity components ``V_c`` (eq. 5 / 15).
    alpha_v, alpha_k : float
        Viscous and Coulomb parameters (eq. 7).
    epsilon : float
        Regularisation scale of the Coulomb term.
    law : float
        0 for the isotropic law (7), 1 for the component-wise law (16).

    Returns
    -------
    tuple
        ``(f1, f2)``, the traction for the equilibrium normal force.
    """
    if alpha_k == 0.0:
        return -alpha_v * vc1, -alpha_v * vc2
    if law == 0.0:
        r = np.sqrt(vc1 * vc1 + vc2 * vc2 + epsilon * epsilon)
        return -alpha_k * vc1 / r - alpha_v * vc1, -alpha_k * vc2 / r - alpha_v * vc2
    s1 = vc1 / np.sqrt(vc1 * vc1 + epsilon * epsilon)
    s2 = vc2 / np.sqrt(vc2 * vc2 + epsilon * epsilon)
    return -alpha_k * s1 - alpha_v * vc1, -alpha_k * s2 - alpha_v * vc2
