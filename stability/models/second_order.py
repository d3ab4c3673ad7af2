"""The two second-order models of eqs. (8)-(9), the fixed pivot and the rolling top as printed
(:class:`FixedPivot`, :class:`RollingEq8`), and their shared form.

Both classical tops reduce to one complex equation for the tilt ``Phi = l + i m``,

    Phi'' - i sigma_hat Phi' - kappa Phi = 0,                                   (*)

whose state form, with ``x = (Phi, Phi')``, is ``x' = A x`` with
``A = [[0, 1], [kappa, i sigma_hat]]`` and ``det(s 1 - A) = s^2 - i sigma_hat s - kappa``.

Relation to eq. (8). The paper writes ``exp(i lambda t)`` and
``lambda = (sigma_hat/2 - 1) +- (sigma_hat^2/4 - kappa)^(1/2)``. With ``s = i nu`` the roots
of (*) are ``nu = sigma_hat/2 +- (sigma_hat^2/4 - kappa)^(1/2)``, so ``lambda = nu - 1``:
eq. (8) measures the frequency in the frame turning with the spin (a complex amplitude
``Phi e^{-i t}``). In this package ``s = i (lambda + 1)``: growth rate ``-Im lambda``,
fixed-frame frequency ``Re lambda + 1``.

The paper's ``mu Fr^-1 h`` is a torque divided by the transverse moment that appears in (*):
``kappa = mu fr_inv h / A_C`` with ``A_C = 1 + mu (1 + 2 q)``, the transverse moment about
the contact point (``A_G + mu (1 + q)^2`` with ``A_G = 1 - mu q^2``), in units of ``A0``;
``sigma_hat = sigma / A_C``. The stability condition ``1 > 4 kappa / sigma_hat^2`` is the
sign of the discriminant.

Convention: every model's (:mod:`stability.models.base`) (eq. 8's ``lambda = -i s - 1``).
"""

from __future__ import annotations

import numpy as np

from .base import LinearModel
from .inertia import transverse_inertia_contact

__all__ = ["FixedPivot", "RollingEq8", "SecondOrderTop"]


class SecondOrderTop(LinearModel):
    """A top described by eq. (8): subclasses define ``h`` (eq. 9) by their :attr:`support_depth`.

    Its state form, with ``x = (Phi, Phi')``, is ``M = 1`` and ``A = [[0, 1], [kappa, i gamma]]``,
    ``det(s 1 - A) = s^2 - i gamma s - kappa`` (module docstring), with ``gamma`` the
    :attr:`gyroscopic` entry of :meth:`derived`.
    """

    parameters = ("q", "fr_inv", "sigma", "mu")
    state = ("Phi", "dPhi_dt")
    n_modes = 2
    #: the key of :meth:`derived` that is the coefficient ``gamma`` of ``i Phi'`` (here ``sigma_hat``)
    gyroscopic = "sigma_hat"

    #: depth of the support point below the sphere's centre, units of R: ``h = q + depth`` (eq. 9)
    support_depth: float = 0.0

    def derived(self, *, q: np.ndarray, fr_inv: np.ndarray, sigma: np.ndarray, mu: np.ndarray) -> dict[str, np.ndarray]:
        """Derived quantities: ``A_C``, ``sigma_hat``, ``h = q + support_depth`` and ``kappa`` (eqs. 8-9)."""
        a_c = transverse_inertia_contact(q, mu)
        q = np.asarray(q, dtype=float)
        h = q + self.support_depth if self.support_depth else q
        return {"A_C": a_c, "sigma_hat": sigma / a_c, "h": h, "kappa": mu * fr_inv * h / a_c}

    def _gamma_kappa(self, **params: np.ndarray) -> tuple[np.ndarray, ...]:
        """``gamma`` (:attr:`gyroscopic`) and ``kappa`` of :meth:`derived`, broadcast together."""
        d = self.derived(**params)
        return np.broadcast_arrays(np.asarray(d[self.gyroscopic], float), np.asarray(d["kappa"], float))

    def matrices(self, **params: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """``M = 1`` and ``A = [[0, 1], [kappa, i gamma]]`` (state form of eq. 8), batched; the
        parameters those of :meth:`derived`."""
        gamma, kappa = self._gamma_kappa(**params)
        A = np.zeros(kappa.shape + (2, 2), dtype=complex)
        A[..., 0, 1] = 1.0
        A[..., 1, 0] = kappa
        A[..., 1, 1] = 1j * gamma
        return np.broadcast_to(np.eye(2, dtype=complex), A.shape).copy(), A

    def coefficients(self, **params: np.ndarray) -> np.ndarray:
        """``s^2 - i gamma s - kappa``, highest power first (the parameters of :meth:`derived`)."""
        gamma, kappa = self._gamma_kappa(**params)
        c = np.empty(kappa.shape + (3,), dtype=complex)
        c[..., 0] = 1.0
        c[..., 1] = -1j * gamma
        c[..., 2] = -kappa
        return c


class FixedPivot(SecondOrderTop):
    """Heavy symmetric top on a fixed pivot at the sphere's bottom point: eqs. (8)-(9), h = 1 + q.

    Eq. (8) with ``h = 1 + q`` (G lies ``(1 + q) R`` above the pivot), ``A_C = 1 + mu (1 + 2 q)``
    the transverse moment about the pivot, ``sigma_hat = sigma / A_C`` and
    ``kappa = mu fr_inv (1 + q) / A_C`` (the module docstring).

    First-principles check (docs/models.md): the angular momentum about the pivot is
    ``A_C omega + (C - A_C)(k . omega) k`` and the gravity torque ``-mu fr_inv (1 + q) k x K``;
    linearised about ``omega = k = K`` with ``Phi' = i Phi - i omega`` (eq. 11, second line) this
    gives ``A_C Phi'' - i sigma Phi' - mu fr_inv (1 + q) Phi = 0``: eq. (8) exactly.
    """

    name = "fixed_pivot"
    equations = "(8)-(9)"
    description = "heavy top on a fixed pivot at the sphere's bottom point, eq. (8) with h = 1 + q"
    support_depth = 1.0  # h = 1 + q (eq. 9): G above the pivot


class RollingEq8(SecondOrderTop):
    """Rolling top, eqs. (8)-(9) as printed: h = q (model ``"rolling_eq8"``).

    Eq. (8) with ``h = q``, ``sigma_hat = sigma / A_C`` (the axial to transverse moment ratio about
    the contact point, as the paper defines it), ``A_C = 1 + mu (1 + 2 q)`` and
    ``kappa = mu fr_inv q / A_C``.

    Known difference from first principles (docs/models.md). Linearising the rolling sphere
    (eqs. 1, 2, 4 with ``V_c = 0`` of eq. 5 and the traction eliminated) gives
    ``A_C Phi'' - i (sigma + mu (1 + q)) Phi' - mu fr_inv q Phi = 0``: the gyroscopic
    coefficient gains ``mu (1 + q)`` from the rolling constraint (the translation of O is tied
    to the rotation); that is the model ``"rolling"``
    (:mod:`stability.models.rolling`). This class keeps the paper's operator as
    printed, under the name ``"rolling_eq8"`` (it was ``"rolling"`` in tippe-stability 0.1.0); the two agree on the
    stiffness ``kappa`` and on stability for ``q < 0`` (both always neutrally stable there), and
    differ in the frequencies and in the inverted (``q > 0``) threshold. A check: for a uniform
    ball (``q = 0``, ``sigma = 1``) the rolling frequencies are 0 and 1 from first principles,
    and ``0`` and ``1 / (1 + mu)`` here. The first-principles polynomial is also the
    ``alpha_v -> infinity`` limit of the sliding model's (divide eq. 11's ``det(s M - A)`` by
    ``alpha_v``).
    """

    name = "rolling_eq8"
    equations = "(8)-(9) as printed"
    description = "top rolling on its sphere, eq. (8)-(9) as printed, h = q, sigma_hat = sigma/A_C"
    # support_depth: the class's 0 (h = q, eq. 9: G above the sphere's centre)
