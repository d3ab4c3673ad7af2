"""Compiled dispatch from a model code to its right-hand side.

numba cannot cache a compiled function that receives another compiled *dispatcher* as an
argument (the dispatcher pickles with an identity that changes in every process), so the
integrators take an integer model code instead and call :func:`rhs`, which branches to the
model's kernel (the branch costs nothing next to the 6 x 6 solve). A ``register_jitable``
function can be passed and cached (:func:`continuation.compiled.newton` takes the problem's
residual that way); the model code is kept because the right-hand sides are dispatchers that
Python callers use too.
"""

from __future__ import annotations

import numpy as np

from stability.jit import njit

from . import fixed_pivot, rolling, sliding

__all__ = ["CODES", "NORMAL_FORCE_MARGIN", "normal_force_lower_bound", "rhs"]

#: model name -> code understood by :func:`rhs`
CODES: dict[str, int] = {"sliding": 0, "rolling": 1, "fixed_pivot": 2}


@njit(cache=True)
def rhs(code, t, y, p):
    """``y'`` of the model with the given code (see :data:`CODES`)."""
    if code == 0:
        return sliding.rhs(t, y, p)
    if code == 1:
        return rolling.rhs(t, y, p)
    return fixed_pivot.rhs(t, y, p)


#: relative margin of :func:`normal_force_lower_bound` over the closed form's round-off (a few
#: ``eps`` times its scale; measured <= 7e-14 against the 6 x 6 solve over random states)
NORMAL_FORCE_MARGIN = 1e-10


@njit(cache=True, nogil=True)
def normal_force_lower_bound(code, y, p):
    """A lower bound of the normal force at ``y`` without the model's 6 x 6 solve, or ``-inf``
    where the model has none (the fixed pivot) or its closed form is not defined there.

    The closed form (:func:`stability.nonlinear.sliding.normal_force`,
    :func:`stability.nonlinear.rolling.normal_force`) less :data:`NORMAL_FORCE_MARGIN` times
    its scale, so that a positive bound means ``N > 0`` for the 6 x 6 solution too (the two
    differ by round-off only)."""
    if code == 0:
        n, scale = sliding.normal_force(y, p)
    elif code == 1:
        n, scale = rolling.normal_force(y, p)
    else:
        return -np.inf
    if n == n:
        return n - NORMAL_FORCE_MARGIN * scale
    return -np.inf
