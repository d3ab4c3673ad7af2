"""Three-vector algebra for the compiled right-hand sides of the nonlinear models."""

from __future__ import annotations

from stability.jit import njit

__all__ = ["cross"]


@njit(cache=True)
def cross(u0, u1, u2, v0, v1, v2):
    """Components of ``u x v`` (scalars in, a 3-tuple out)."""
    return u1 * v2 - u2 * v1, u2 * v0 - u0 * v2, u0 * v1 - u1 * v0
