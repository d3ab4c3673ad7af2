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
of :mod:`continuation.linalg`, never the grids, recipes, figures or command line. This ``__init__`` holds the
registry and imports no model module: :data:`NONLINEAR_MODELS` knows the names without them (the
command line lists them without importing numba) and imports a model's compiled module when its
kernels are first asked for; ``runs``, ``jacobian`` and ``validation`` import the registry from here
without a cycle.
"""

from __future__ import annotations

import importlib
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from functools import cached_property

from ..errors import InputError

__all__ = ["NONLINEAR_MODELS", "NonlinearModel", "get_nonlinear_model"]


@dataclass(frozen=True)
class NonlinearModel:
    """A nonlinear model: its compiled kernels and the layout of its state.

    The kernels and the state's names come from the model's compiled module (of the same name),
    imported when one of them is first asked for: the registry knows the names, equations and
    parameters without importing numba (the command line lists them).

    Attributes
    ----------
    name : str
    equations : str
        The paper's equation numbers.
    parameters : tuple of str
        Physical parameters the model takes.
    transverse : tuple of tuple of int
        Index pairs ``(re, im)`` of the complex transverse variables at the upright spin, in
        the order of the linear model's state (``omega, Phi[, V]``).
    rhs : callable
        Compiled ``rhs(t, y, p)``.
    contact_forces : callable
        Compiled ``contact_forces(states, p) -> (n, 3)``.
    state : tuple of str
        Names of the state components.
    linear_model : str
        Name of the registered linear model that is the first-principles linearisation (the
        linear model of the same name).
    """

    name: str
    equations: str
    parameters: tuple[str, ...]
    transverse: tuple[tuple[int, int], ...]

    @cached_property
    def rhs(self) -> Callable:
        return importlib.import_module(f"{__name__}.{self.name}").rhs

    @cached_property
    def contact_forces(self) -> Callable:
        return importlib.import_module(f"{__name__}.{self.name}").contact_forces

    @cached_property
    def state(self) -> tuple[str, ...]:
        return importlib.import_module(f"{__name__}.{self.name}").STATE

    @property
    def linear_model(self) -> str:
        return self.name

    @property
    def has_translation(self) -> bool:
        """True if the centre O moves (sliding and rolling)."""
        return "X_1" in self.state


#: the parameters of the tops without friction parameters (rolling, fixed pivot)
_CLASSICAL = ("q", "fr_inv", "sigma", "mu")

#: name -> :class:`NonlinearModel` (a model's compiled module is imported on first use of its kernels)
NONLINEAR_MODELS: Mapping[str, NonlinearModel] = {
    "sliding": NonlinearModel(
        "sliding",
        "(1), (2), (4), (5), (7)/(16)",
        ("q", "fr_inv", "sigma", "alpha_v", "alpha_k", "mu"),
        ((0, 1), (3, 4), (6, 7)),
    ),
    "rolling": NonlinearModel("rolling", "(1), (2), (4), (5) with V_c = 0", _CLASSICAL, ((0, 1), (3, 4))),
    "fixed_pivot": NonlinearModel(
        "fixed_pivot", "(2), (4) about the pivot; (8)-(9) with h = 1 + q", _CLASSICAL, ((0, 1), (3, 4))
    ),
}


def get_nonlinear_model(model: str) -> NonlinearModel:
    """Return the nonlinear model called ``model``.

    Raises
    ------
    ValueError
        If there is no such model; the message lists the names.
    """
    if not isinstance(model, str) or model not in NONLINEAR_MODELS:
        raise InputError(f"model = {model!r} is not a nonlinear model; choose one of {', '.join(NONLINEAR_MODELS)}")
    return NONLINEAR_MODELS[model]
