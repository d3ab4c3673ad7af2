"""The contract every linear model of the package fulfils.

A linear model is the linearisation of one of the tops about the upright spin
(``omega = K``, ``k = K``, ``V0 = 0``; paper, Sec. 2) written as ``M x' = A x`` with a complex
state ``x`` (transverse components packed as ``u1 + i u2``). To add a model:

1. subclass :class:`LinearModel` in a module of its own, with the equations it implements,
   by number, in the module docstring;
2. set ``name``, ``equations``, ``parameters`` (the names it takes, from
   :data:`stability.parameters.PARAMETERS`), ``state`` (names of the complex state
   variables) and ``n_modes``;
3. implement :meth:`LinearModel.matrices` (batched ``M`` and ``A``) and
   :meth:`LinearModel.coefficients` (``det(s M - A)``, highest power first), both from the
   same formulas, and tested against each other;
4. register an instance in :data:`stability.models.MODELS`.

Convention (every model): ``x ~ exp(s t)``, ``t`` in units of ``1/Omega``, components in the
non-rotating frame ``F_a``; growth rate ``Re s`` and frequency ``Im s`` in units of the spin
rate. ``Im s > 0`` means the complex amplitude turns in the sense of the spin.
"""

from __future__ import annotations

from abc import ABC, abstractmethod
from typing import ClassVar

import numpy as np

__all__ = ["LinearModel"]


class LinearModel(ABC):
    """A linear model ``M x' = A x`` of the top about the upright spin."""

    #: registry name, e.g. ``"sliding"``
    name: ClassVar[str]
    #: the paper's equation numbers the model implements
    equations: ClassVar[str]
    #: parameter names the model takes
    parameters: ClassVar[tuple[str, ...]]
    #: names of the complex state variables
    state: ClassVar[tuple[str, ...]]
    #: number of complex modes (= len(state))
    n_modes: ClassVar[int]
    #: one-line description
    description: ClassVar[str]

    @abstractmethod
    def matrices(self, **params: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Return the batched complex matrices ``M`` and ``A``, shape (..., n, n)."""

    @abstractmethod
    def coefficients(self, **params: np.ndarray) -> np.ndarray:
        """Return the coefficients of ``det(s M - A)``, shape (..., n+1), highest power first."""

    def __repr__(self) -> str:
        return f"<linear model {self.name!r}: eqs. {self.equations}>"
