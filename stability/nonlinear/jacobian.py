"""First-principles linearisation: eigenvalues of the nonlinear models' Jacobians.

:func:`jacobian_eigenvalues` differentiates the compiled right-hand side of a nonlinear model
(:mod:`stability.nonlinear`) at the upright spin ``omega = k = K`` (``V0 = 0``) by the complex
step, ``J e_j = Im f(y + i h e_j) / h`` with ``h = 1e-30`` (exact to rounding: no subtraction),
and never uses the linear operators of :mod:`stability.models`, so comparing the two is a
check of both.

The transverse block. The axial variables (``omega_3``, ``k_3``) and the position decouple
at first order (an upright spin at any rate is an equilibrium), so the transverse block of
the Jacobian, in the real variables ``(omega_1, k_1[, V_1])`` and ``(omega_2, k_2[, V_2])``,
is the linearisation. Rotational symmetry about ``K`` makes it complex-linear:
``J = [[Re A, -Im A], [Im A, Re A]]`` for a complex matrix ``A`` acting on
``omega_1 + i omega_2``, ``Phi = l + i m``, ``V_1 + i V_2``; the eigenvalues of ``A`` are the
``s`` of ``x ~ exp(s t)`` in the package's convention (those of ``J`` are ``s`` and
``conj(s)``).
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np

from ..parameters import DEFAULT_MU
from . import get_nonlinear_model

__all__ = ["jacobian_eigenvalues", "transverse_jacobian"]

_STEP = 1e-30


def transverse_jacobian(model: str, params: Mapping[str, Any]) -> tuple[np.ndarray, float]:
    """Complex transverse Jacobian ``A`` at the upright spin ``omega = k = K`` (centre at rest, at
    the origin), and its departure from C-linearity.

    Parameters
    ----------
    model : {"sliding", "rolling", "fixed_pivot"}
    params : mapping
        ``q, fr_inv, sigma`` and ``mu``, ``alpha_v`` (``"sliding"`` only), as
        :func:`stability.nonlinear.runs.model_parameter_vector` takes them.

    Returns
    -------
    A : numpy.ndarray of complex, shape (n, n)
        In the order ``omega, Phi[, V]``.
    asymmetry : float
        ``max |J - [[Re A, -Im A], [Im A, Re A]]|``: zero up to rounding when the real block
        is complex-linear.
    """
    from .runs import model_parameter_vector

    m = get_nonlinear_model(model)
    _, p = model_parameter_vector(m.name, params)
    y0 = np.zeros(len(m.state), complex)
    y0[2] = y0[5] = 1.0
    re = [i for i, _ in m.transverse]
    im = [j for _, j in m.transverse]
    idx = re + im
    n = len(re)
    J = np.empty((2 * n, 2 * n))
    for c, j in enumerate(idx):
        y = y0.copy()
        y[j] += 1j * _STEP
        J[:, c] = m.rhs(0.0, y, p)[idx].imag / _STEP
    A = J[:n, :n] + 1j * J[n:, :n]
    model_form = np.block([[A.real, -A.imag], [A.imag, A.real]])
    return A, float(np.max(np.abs(J - model_form)))


def jacobian_eigenvalues(
    model: str, *, q: Any, fr_inv: Any, sigma: Any, alpha_v: Any = None, mu: Any = DEFAULT_MU
) -> np.ndarray:
    """Eigenvalues of a nonlinear model's Jacobian at the upright spin (transverse variables).

    Parameters
    ----------
    model : {"sliding", "rolling", "fixed_pivot"}
        The nonlinear model (:mod:`stability.nonlinear`).
    q, fr_inv, sigma, mu : float
        Parameters (docs/conventions.md).
    alpha_v : float, optional
        Viscous friction; required for ``"sliding"``, refused otherwise.

    Returns
    -------
    numpy.ndarray of complex, shape (n_modes,)
        ``s`` with ``x ~ exp(s t)`` (fixed frame, time in ``1/Omega``), sorted by decreasing
        real part (ties by decreasing imaginary part). ``"sliding"`` agrees with eq. (11)
        (model ``"sliding"``), ``"fixed_pivot"`` with eq. (8), and ``"rolling"`` with
        the linear ``"rolling"`` (first principles), not with eq. (8) as printed
        (``"rolling_eq8"``, docs/nonlinear.md).

    Raises
    ------
    TypeError, ValueError
        For missing, foreign or out-of-domain parameters.

    Examples
    --------
    >>> import stability
    >>> s = stability.jacobian_eigenvalues("sliding", q=-0.1, fr_inv=0.3, sigma=1.0, alpha_v=0.5)
    >>> s.shape
    (3,)
    """
    A, _ = transverse_jacobian(model, dict(q=q, fr_inv=fr_inv, sigma=sigma, alpha_v=alpha_v, mu=mu))
    ev = np.linalg.eigvals(A)
    from ..linear.spectra import mode_order  # the spectra's sort convention (here: not imported with this module)

    ordered: np.ndarray = ev[mode_order(ev)]
    return ordered
