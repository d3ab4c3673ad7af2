"""The compiled step of the neutral curves (crossing form of a model with coefficient formulas).

:class:`stability.linear.neutral_curves.NeutralProblem` offers the engine this ``compiled_step``
(:mod:`continuation.problem`) when its neutral condition is the crossing form of a model that
offers its coefficients and their exact parameter derivatives as formulas (the optional
capabilities of :mod:`stability.models.base`; the sliding model, eq. 11), whose compiled twins
are built by :func:`stability.linear.neutrality.crossing_kernels`. One call does what the
engine's Python path does per step: Newton's method on the bordered system
``[F(v); t . (v - v_k) - h] = 0`` from the predicted point (polished to the rounding floor),
then the unit tangent oriented by ``t`` and ``det [J; t^T]`` at the solution: the engine's own
corrector compiled, :func:`continuation.compiled.step`. All in the
engine's scaled variables ``v = u / scale``.

The constraints of the problem (the physical domain's bounds and the requested ranges) are
evaluated by :func:`constraint_values`, the one source of
:func:`stability.linear.neutral_constraints.constraint_values` compiled, and the second test
function (the largest growth rate of the other modes) by the model's compiled twin, at the new
point.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Callable

import numpy as np

from continuation.compiled import step as corrector_step
from stability.jit import OPTIONS, njit

from .neutral_constraints import constraint_values as _constraint_values
from .neutrality import CrossingKernels

__all__ = ["constraint_values", "step_kernel"]

_JIT = dict(OPTIONS, cache=True)

#: the problem's constraints (:func:`stability.linear.neutral_constraints.constraint_values`), compiled
constraint_values = njit(**_JIT)(_constraint_values)


@functools.cache
def step_kernel(kernels: CrossingKernels) -> Callable[..., tuple]:
    """The compiled step for the crossing form compiled in ``kernels``
    (:func:`stability.linear.neutrality.crossing_kernels`), built once per model: a closure over
    the model's compiled residual and second test function (plain ``register_jitable``
    functions, so that numba caches it on disk; see :mod:`stability.linear.kernel`)."""
    residual_into, other_growth_of = kernels.residual_into, kernels.other_growth_of

    @njit(**_JIT)
    def step(point, free_index, ncoef, codes, index, a, guess, t_plane, anchor, h, scale, tol, max_iter, max_move):
        """Corrector and tangent of one continuation step (:func:`continuation.compiled.step`), and the problem's constraints and test functions at the new point
        (so that the engine's loop makes no further call for them).

        Arguments: the neutral condition ``(point, free_index, ncoef)``
        (:class:`~stability.linear.neutrality.CrossingKernels`); the constraint rows ``(codes,
        index, a)`` (:func:`constraint_values`); then those of
        :func:`continuation.compiled.step`.

        Returns ``(ok, iterations, n_residual_and_jacobian, n_residual, v, J, tangent_ok, t,
        det, g, tests)`` (:mod:`continuation.problem`): if ``ok``, the constraints ``g`` and the
        test functions ``[w, max Re(other modes)]`` (``-1`` if there is no other mode) at
        ``u = v * scale``, the operations of ``NeutralProblem.constraints`` and
        ``NeutralProblem.test_functions`` (which the engine would call with the same ``u``).
        """
        r = corrector_step(
            residual_into, (point, free_index, ncoef), guess, t_plane, anchor, h, scale, tol, max_iter, max_move
        )
        tests = np.empty(2)
        if not r[0]:
            return (*r, np.empty(0), tests)
        u = r[4] * scale
        g = constraint_values(point, free_index, u, codes, index, a)
        tests[0] = u[guess.shape[0] - 1]
        growth = other_growth_of(point, free_index, ncoef, u)
        tests[1] = growth if math.isfinite(growth) else -1.0
        return (*r, g, tests)

    return step
