"""Shared form of the two second-order models, eqs. (8)-(9).

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
"""

from __future__ import annotations

import numpy as np

from .base import LinearModel
from .inertia import transverse_inertia_contact

__all__ = ["SecondOrderTop", "contact_transverse_inertia", "gyroscopic_coefficients", "gyroscopic_state_form"]


#: transverse moment about the contact point, ``A_C = 1 + mu (1 + 2 q)`` (see stability.models.inertia)
contact_transverse_inertia = transverse_inertia_contact


def gyroscopic_state_form(gamma: np.ndarray, kappa: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """State form of ``Phi'' - i gamma Phi' - kappa Phi = 0`` with ``x = (Phi, Phi')``.

    Returns ``M = 1`` and ``A = [[0, 1], [kappa, i gamma]]`` (complex, batched over the shape of
    ``gamma`` and ``kappa`` broadcast together).
    """
    gamma, kappa = np.broadcast_arrays(np.asarray(gamma, float), np.asarray(kappa, float))
    A = np.zeros(kappa.shape + (2, 2), dtype=complex)
    A[..., 0, 1] = 1.0
    A[..., 1, 0] = kappa
    A[..., 1, 1] = 1j * gamma
    M = np.broadcast_to(np.eye(2, dtype=complex), A.shape).copy()
    return M, A


def gyroscopic_coefficients(gamma: np.ndarray, kappa: np.ndarray) -> np.ndarray:
    """``det(s 1 - A) = s^2 - i gamma s - kappa`` of :func:`gyroscopic_state_form`, highest power first."""
    gamma, kappa = np.broadcast_arrays(np.asarray(gamma, float), np.asarray(kappa, float))
    c = np.empty(kappa.shape + (3,), dtype=complex)
    c[..., 0] = 1.0
    c[..., 1] = -1j * gamma
    c[..., 2] = -kappa
    return c


class SecondOrderTop(LinearModel):
    """A top described by eq. (8): subclasses define ``h`` (eq. 9)."""

    parameters = ("q", "fr_inv", "sigma", "mu")
    state = ("Phi", "dPhi_dt")
    n_modes = 2
    #: the key of :meth:`derived` that is the coefficient ``gamma`` of ``i Phi'`` (here ``sigma_hat``)
    gyroscopic = "sigma_hat"

    #: depth of the support point below the sphere's centre, units of R: ``h = q + depth`` (eq. 9)
    support_depth: float = 0.0

    def h(self, q: np.ndarray) -> np.ndarray:
        """Height of G above the support point, eq. (9), in units of R: ``q + support_depth``."""
        q = np.asarray(q, dtype=float)
        return q + self.support_depth if self.support_depth else q

    def derived(self, *, q, fr_inv, sigma, mu) -> dict[str, np.ndarray]:
        """Derived quantities: ``A_C``, ``sigma_hat``, ``h`` and ``kappa`` (eqs. 8-9)."""
        a_c = contact_transverse_inertia(q, mu)
        h = self.h(q)
        return {"A_C": a_c, "sigma_hat": sigma / a_c, "h": h, "kappa": mu * fr_inv * h / a_c}

    def matrices(self, *, q, fr_inv, sigma, mu):
        """``M = 1`` and ``A = [[0, 1], [kappa, i gamma]]`` (state form of eq. 8; ``gamma`` is
        :attr:`gyroscopic`)."""
        d = self.derived(q=q, fr_inv=fr_inv, sigma=sigma, mu=mu)
        return gyroscopic_state_form(d[self.gyroscopic], d["kappa"])

    def coefficients(self, *, q, fr_inv, sigma, mu):
        """``s^2 - i gamma s - kappa``, highest power first (``gamma`` is :attr:`gyroscopic`)."""
        d = self.derived(q=q, fr_inv=fr_inv, sigma=sigma, mu=mu)
        return gyroscopic_coefficients(d[self.gyroscopic], d["kappa"])
