"""Heavy symmetric top on a fixed pivot at the sphere's bottom point: eqs. (8)-(9), h = 1 + q.

Eq. (8) with ``h = 1 + q`` (G lies ``(1 + q) R`` above the pivot), ``A_C = 1 + mu (1 + 2 q)``
the transverse moment about the pivot, ``sigma_hat = sigma / A_C`` and
``kappa = mu fr_inv (1 + q) / A_C`` (see :mod:`stability.models.second_order`).

First-principles check (docs/models.md): the angular momentum about the pivot is
``A_C omega + (C - A_C)(k . omega) k`` and the gravity torque ``-mu fr_inv (1 + q) k x K``;
linearised about ``omega = k = K`` with ``Phi' = i Phi - i omega`` (eq. 11, second line) this
gives ``A_C Phi'' - i sigma Phi' - mu fr_inv (1 + q) Phi = 0``: eq. (8) exactly.

Convention: every model's (:mod:`stability.models.base`) (eq. 8's ``lambda = -i s - 1``).
"""

from __future__ import annotations

from .second_order import SecondOrderTop

__all__ = ["FixedPivot"]


class FixedPivot(SecondOrderTop):
    """Fixed-pivot top, eqs. (8)-(9) with ``h = 1 + q``."""

    name = "fixed_pivot"
    equations = "(8)-(9)"
    description = "heavy top on a fixed pivot at the sphere's bottom point, eq. (8) with h = 1 + q"
    support_depth = 1.0  # h = 1 + q (eq. 9): G above the pivot
