"""Rolling top from first principles: the linearised rolling sphere (model ``"rolling"``).

Registered as ``"rolling"`` (it was ``"rolling_first_principles"`` in tippe-stability 0.1.0;
that name still works for one release, with a DeprecationWarning).

Linearising eqs. (1), (2), (4) with the rolling constraint ``V_c = 0`` (eq. 5) about the
upright spin ``omega = k = K`` (spin +1) gives, with ``Phi = l + i m``
(derivation in docs/nonlinear.md)::

    A_C Phi'' - i (sigma + mu (1 + q)) Phi' - mu fr_inv q Phi = 0,   A_C = 1 + mu (1 + 2 q).

Sketch: the constraint ties the centre's velocity to the rotation, ``V = -i omega``
(``V0 = -K x omega``), and makes the traction ``f = mu (V' + q Phi'')`` from (1); inserted
in the transverse part of (2) with ``Phi' = i Phi - i omega`` (eq. 11, second line) the
``mu (1 + q)`` terms that are not moments of inertia add to the gyroscopic coefficient.

It differs from eq. (8) as printed (model ``"rolling_eq8"``, ``sigma_hat = sigma / A_C``) by the
gyroscopic term ``mu (1 + q) Phi'``; it is the ``alpha_v -> infinity`` limit of the sliding
polynomial (eq. 11 divided by ``alpha_v``) and the linearisation of the nonlinear rolling
model (:func:`stability.jacobian_eigenvalues`). Monic state form, ``x = (Phi, Phi')``::

    x' = [[0, 1], [kappa, i gamma]] x,  gamma = (sigma + mu (1 + q)) / A_C,
    kappa = mu fr_inv q / A_C,  det(s 1 - A) = s^2 - i gamma s - kappa.

Convention: every model's (:mod:`stability.models.base`).
"""

from __future__ import annotations

import numpy as np

from .inertia import transverse_inertia_contact
from .second_order import SecondOrderTop

__all__ = ["Rolling"]


class Rolling(SecondOrderTop):
    """Linearised rolling sphere: ``A_C Phi'' - i (sigma + mu (1+q)) Phi' - mu fr_inv q Phi = 0``."""

    name = "rolling"
    equations = "(1), (2), (4), (5) linearised"
    gyroscopic = "gamma"
    description = "top rolling on its sphere, linearised from the vector equations (1), (2), (4), (5)"

    def derived(self, *, q, fr_inv, sigma, mu) -> dict[str, np.ndarray]:
        """``A_C``, the gyroscopic coefficient ``gamma`` and the stiffness ``kappa``."""
        q, fr_inv, sigma, mu = np.broadcast_arrays(*(np.asarray(v, float) for v in (q, fr_inv, sigma, mu)))
        a_c = transverse_inertia_contact(q, mu)
        return {"A_C": a_c, "gamma": (sigma + mu * (1.0 + q)) / a_c, "kappa": mu * fr_inv * q / a_c}
