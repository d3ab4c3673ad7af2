"""Compiled dispatch from a model code to its right-hand side.

numba cannot cache a compiled function that receives another compiled function as an
argument, so the integrators take an integer model code instead and call :func:`rhs`, which
branches to the model's kernel (the branch costs nothing next to the 6 x 6 solve).
"""

from __future__ import annotations

from stability.jit import njit

from . import fixed_pivot, rolling, sliding

__all__ = ["CODES", "rhs"]

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
