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

That is all a model needs: spectra (every method), atlases, thresholds, neutral curves and
``tippe`` then work for it by name, through generic paths (the compiled kernel on the
coefficients the model returns, derivatives of the neutral condition by a finite-difference
stencil, the continuation engine's Python path).

5. *Optional capabilities* (fast paths). A model may also offer, as class attributes
   (``staticmethod``), the coefficients at one point as a formula the package can compile:

   ``point_coefficients(q, fr_inv, sigma, alpha_v, mu)``
       the ``n_modes + 1`` coefficients of :meth:`coefficients` at one point, returned as
       ``2 (n_modes + 1)`` reals ``(Re c_n, Im c_n, ..., Re c_0, Im c_0)``. The arguments are
       always the five linear parameters in the order of :data:`stability.parameters.PARAMETERS`
       (a model ignores those it does not take; the package passes ``0.0`` for them). It must be
       written in plain arithmetic (``+ - * /``, comparisons, ``math`` functions; no numpy
       calls) and registered with :func:`numba.extending.register_jitable`, so that one source
       runs on Python floats, on numpy arrays and compiled inside numba kernels, with the same
       floating-point operations in each. :meth:`coefficients` should be its numpy execution, so
       that the engines agree bit for bit.
   ``point_derivatives(q, fr_inv, sigma, alpha_v, mu, k)``
       the exact derivatives of ``point_coefficients`` by parameter ``k`` (the index into
       ``PARAMETERS``), in the same layout and under the same rules.

   With ``point_coefficients`` (degree ``n_modes <= 3``) :func:`stability.spectrum` computes
   the coefficients inside the compiled kernel, fused with the domain test
   (:mod:`stability.linear.kernel`); with both, the neutral condition uses the exact
   derivatives, and its crossing form (if the other modes' polynomial has degree <= 2) is
   compiled for the continuation engine (:mod:`stability.linear.neutrality`,
   :mod:`stability.linear.neutral_compiled`). Callers ask the model for these attributes
   (``None``: absent); they never test its class. :class:`stability.models.sliding.Sliding`
   offers both; the second-order models offer neither.

Convention (every model): ``x ~ exp(s t)``, ``t`` in units of ``1/Omega``, components in the
non-rotating frame ``F_a``; growth rate ``Re s`` and frequency ``Im s`` in units of the spin
rate. ``Im s > 0`` means the complex amplitude turns in the sense of the spin.
"""

from __future__ import annotations

from abc import ABC, abstractmethod
from collections.abc import Callable
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
    #: optional capability 5 (module docstring): the coefficients at one point, as reals, in
    #: plain arithmetic registered with numba's ``register_jitable``; None if not offered
    point_coefficients: ClassVar[Callable[..., tuple[float, ...]] | None] = None
    #: optional capability 5: their exact derivatives by parameter ``k``; None if not offered
    point_derivatives: ClassVar[Callable[..., tuple[float, ...]] | None] = None

    @abstractmethod
    def matrices(self, **params: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Return the batched complex matrices ``M`` and ``A``, shape (..., n, n)."""

    @abstractmethod
    def coefficients(self, **params: np.ndarray) -> np.ndarray:
        """Return the coefficients of ``det(s M - A)``, shape (..., n+1), highest power first."""

    def __repr__(self) -> str:
        return f"<linear model {self.name!r}: eqs. {self.equations}>"
