"""The linear operators as python-control state-space systems (real 2n-dimensional form).

python-control works with real matrices only, so a complex system ``x' = A x + B u``,
``y = C x`` (with ``x = x_r + i x_i`` packing two real transverse components, as in eq. 11) is
handed over in its real form::

    d/dt [x_r]   [Re A  -Im A] [x_r]   [Re B  -Im B] [u_r]
         [x_i] = [Im A   Re A] [x_i] + [Im B   Re B] [u_i]

which is exactly the real linearisation in the components (omega_1, omega_2, l, m, ...). Its
eigenvalues are those of ``A`` together with their complex conjugates.

The sliding model's friction is a feedback loop (eq. 11 from eqs. 5 and 7): the frictionless
plant takes the traction ``f`` as input and gives the contact slip velocity ``V_c = V + i
omega`` as output; the viscous law ``f = -alpha_v V_c`` is negative feedback with the gain
``alpha_v * I`` (2 x 2). :func:`friction_loop` returns both and the closed loop.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np

from ..models import get_model
from ..parameters import DEFAULT_MU, check_domain
from .spectra import model_parameters

if TYPE_CHECKING:  # python-control takes ~1 s to import: loaded on first use
    import control

__all__ = ["friction_loop", "real_form", "state_space"]


def real_form(a: np.ndarray) -> np.ndarray:
    """Real ``(2p, 2q)`` form ``[[Re a, -Im a], [Im a, Re a]]`` of a complex ``(p, q)`` matrix."""
    a = np.asarray(a, dtype=complex)
    return np.block([[a.real, -a.imag], [a.imag, a.real]])


def _scalar_params(model, given: dict[str, Any]) -> dict[str, float]:
    p, _ = check_domain(scalar=True, **model_parameters(model, given))
    return {k: float(v) for k, v in p.items()}


def _state_names(state: tuple[str, ...]) -> list[str]:
    return [f"Re {s}" for s in state] + [f"Im {s}" for s in state]


def state_space(
    model: str, *, q: float, fr_inv: float, sigma: float, alpha_v: float | None = None, mu: float = DEFAULT_MU
) -> control.StateSpace:
    """The model's operator ``M^-1 A`` as a real python-control StateSpace (no inputs).

    Parameters
    ----------
    model : {"fixed_pivot", "rolling", "rolling_eq8", "sliding"}
    q, fr_inv, sigma, alpha_v, mu : float
        Scalars in the physical domain (``alpha_v`` for ``"sliding"`` only).

    Returns
    -------
    control.StateSpace
        ``2 n`` states (real parts, then imaginary parts of the complex state), all states as
        outputs; its poles are the model's eigenvalues and their conjugates.
    """
    m = get_model(model)
    p = _scalar_params(m, dict(q=q, fr_inv=fr_inv, sigma=sigma, alpha_v=alpha_v, mu=mu))
    M, A = m.matrices(**p)
    a = real_form(np.linalg.solve(M, A))
    n2 = a.shape[0]
    names = _state_names(m.state)
    import control

    return control.ss(a, np.zeros((n2, 0)), np.eye(n2), np.zeros((n2, 0)), states=names, outputs=names, name=m.name)


def friction_loop(
    *, q: float, fr_inv: float, sigma: float, alpha_v: float, mu: float = DEFAULT_MU
) -> tuple[control.StateSpace, np.ndarray, control.StateSpace]:
    """The sliding model's friction as feedback: plant, gain and closed loop.

    Parameters
    ----------
    q, fr_inv, sigma, alpha_v, mu : float
        Scalars in the physical domain.

    Returns
    -------
    plant : control.StateSpace
        Frictionless sliding top (eq. 11 with ``alpha_v = 0``), inputs the traction
        ``(f_1, f_2)``, outputs the slip ``(V_c1, V_c2)`` (eq. 15).
    gain : numpy.ndarray
        ``alpha_v * eye(2)``.
    closed : control.StateSpace
        ``control.feedback(plant, gain)`` (negative feedback, ``f = -alpha_v V_c``); its poles
        are the eigenvalues of eq. (11) and their conjugates.
    """
    m = get_model("sliding")
    p = _scalar_params(m, dict(q=q, fr_inv=fr_inv, sigma=sigma, alpha_v=alpha_v, mu=mu))
    M, A0, B, C = m.friction_plant(q=p["q"], fr_inv=p["fr_inv"], sigma=p["sigma"], mu=p["mu"])
    import control

    plant = control.ss(
        real_form(np.linalg.solve(M, A0)),
        real_form(np.linalg.solve(M, B)),
        real_form(C),
        np.zeros((2, 2)),
        states=_state_names(m.state),
        inputs=["f_1", "f_2"],
        outputs=["V_c1", "V_c2"],
        name="frictionless_sliding",
    )
    gain = p["alpha_v"] * np.eye(2)
    return plant, gain, control.feedback(plant, gain)
