"""Rolling top, eqs. (8)-(9) as printed: h = q (model ``"rolling_eq8"``).

Eq. (8) with ``h = q``, ``sigma_hat = sigma / A_C`` (the axial to transverse moment ratio about
the contact point, as the paper defines it), ``A_C = 1 + mu (1 + 2 q)`` and
``kappa = mu fr_inv q / A_C``.

Known difference from first principles (docs/models.md). Linearising the rolling sphere
(eqs. 1, 2, 4 with ``V_c = 0`` of eq. 5 and the traction eliminated) gives
``A_C Phi'' - i (sigma + mu (1 + q)) Phi' - mu fr_inv q Phi = 0``: the gyroscopic
coefficient gains ``mu (1 + q)`` from the rolling constraint (the translation of O is tied
to the rotation); that is the model ``"rolling"``
(:mod:`stability.models.rolling`). This module keeps the paper's operator as
printed, under the name ``"rolling_eq8"`` (it was ``"rolling"`` in tippe-stability 0.1.0); the two agree on the
stiffness ``kappa`` and on stability for ``q < 0`` (both always neutrally stable there), and
differ in the frequencies and in the inverted (``q > 0``) threshold. A check: for a uniform
ball (``q = 0``, ``sigma = 1``) the rolling frequencies are 0 and 1 from first principles,
and ``0`` and ``1 / (1 + mu)`` here. The first-principles polynomial is also the
``alpha_v -> infinity`` limit of the sliding model's (divide eq. 11's ``det(s M - A)`` by
``alpha_v``).

Convention: every model's (:mod:`stability.models.base`) (eq. 8's ``lambda = -i s - 1``).
"""

from __future__ import annotations

from .second_order import SecondOrderTop

__all__ = ["RollingEq8"]


class RollingEq8(SecondOrderTop):
    """Rolling top, eqs. (8)-(9) with ``h = q``, as printed in the paper."""

    name = "rolling_eq8"
    equations = "(8)-(9) as printed"
    description = "top rolling on its sphere, eq. (8)-(9) as printed, h = q, sigma_hat = sigma/A_C"
    support_depth = 0.0  # h = q (eq. 9): G above the sphere's centre
