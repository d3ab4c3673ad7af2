"""Nonlinear models of the Tippe top: one module per model, compiled right-hand sides.

============== ============================================ =========================================
name           module                                       equations
============== ============================================ =========================================
``sliding``    :mod:`stability.nonlinear.sliding`           (1), (2), (4), contact, friction (7)/(16)
``rolling``    :mod:`stability.nonlinear.rolling`           (1), (2), (4) with ``V_c = 0`` (5)
``fixed_pivot`` :mod:`stability.nonlinear.fixed_pivot`      heavy top about the bottom point (8)-(9)
============== ============================================ =========================================

Shared pieces: the friction law (:mod:`~stability.nonlinear.friction`), the integrators
(:mod:`~stability.nonlinear.integrators`), the parameter vector
(:mod:`~stability.nonlinear.parameters`) and the energy and integrals
(:mod:`~stability.nonlinear.quantities`). Built on them: the runs
(:mod:`~stability.nonlinear.runs`, :func:`stability.simulate`), the first-principles
linearisation (:mod:`~stability.nonlinear.jacobian`, :func:`stability.jacobian_eigenvalues`),
the validation of the linear predictions (:mod:`~stability.nonlinear.validation`,
:func:`stability.validate`) and the scene of Sec. 3(ii) (:mod:`~stability.nonlinear.scene`).

Layer 3 (docs/architecture.md): imports the models, the linear layer and the small dense solves
of :mod:`continuation.linalg`, never the grids, recipes, figures or command line. This ``__init__`` imports only the three model modules, so
that ``runs``, ``jacobian`` and ``validation`` can import the registry from it without a cycle.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

from . import fixed_pivot, rolling, sliding

__all__ = ["NonlinearModel", "NONLINEAR_MODELS", "get_nonlinear_model"]


@dataclass(frozen=True)
class NonlinearModel:
    """A nonlinear model: its compiled kernels and the layout of its state.

    Attributes
    ----------
    name : str
    equations : str
        The paper's equation numbers.
    rhs : callable
        Compiled ``rhs(t, y, p)``.
    contact_forces : callable
        Compiled ``contact_forces(states, p) -> (n, 3)``.
    state : tuple of str
        Names of the state components.
    parameters : tuple of str
        Physical parameters the model takes.
    transverse : tuple of tuple of int
        Index pairs ``(re, im)`` of the complex transverse variables at the upright spin, in
        the order of the linear model's state (``omega, Phi[, V]``).
    linear_model : str
        Name of the registered linear model that is the first-principles linearisation.
    """

    name: str
    equations: str
    rhs: Callable
    contact_forces: Callable
    state: tuple[str, ...]
    parameters: tuple[str, ...]
    transverse: tuple[tuple[int, int], ...]
    linear_model: str

    @property
    def has_translation(self) -> bool:
        """True if the centre O moves (sliding and rolling)."""
        return "X_1" in self.state


NONLINEAR_MODELS: dict[str, NonlinearModel] = {
    "sliding": NonlinearModel(
        "sliding", "(1), (2), (4), (5), (7)/(16)", sliding.rhs, sliding.contact_forces,
        sliding.STATE, ("q", "fr_inv", "sigma", "alpha_v", "alpha_k", "mu"),
        ((0, 1), (3, 4), (6, 7)), "sliding"),
    "rolling": NonlinearModel(
        "rolling", "(1), (2), (4), (5) with V_c = 0", rolling.rhs, rolling.contact_forces,
        rolling.STATE, ("q", "fr_inv", "sigma", "mu"), ((0, 1), (3, 4)),
        "rolling"),
    "fixed_pivot": NonlinearModel(
        "fixed_pivot", "(2), (4) about the pivot; (8)-(9) with h = 1 + q", fixed_pivot.rhs,
        fixed_pivot.contact_forces, fixed_pivot.STATE, ("q", "fr_inv", "sigma", "mu"),
        ((0, 1), (3, 4)), "fixed_pivot"),
}


def get_nonlinear_model(model: str) -> NonlinearModel:
    """Return the nonlinear model called ``model``.

    Raises
    ------
    ValueError
        If there is no such model; the message lists the names.
    """
    if not isinstance(model, str) or model not in NONLINEAR_MODELS:
        raise ValueError(f"model = {model!r} is not a nonlinear model; choose one of "
                         f"{', '.join(NONLINEAR_MODELS)}")
    return NONLINEAR_MODELS[model]
