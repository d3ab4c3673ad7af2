"""Compiled (numba) building blocks for a problem's compiled corrector.

A problem may give the engine a ``compiled_step`` (:mod:`continuation.problem`): the
corrector, the tangent and the branch-point test in one compiled call, with the same semantics
as the engine's Python path (:func:`continuation.engine.trace`). The engine cannot hand a
problem's compiled residual to a generic compiled loop as a run-time argument without losing
numba's on-disk cache (a dispatcher in a signature or a closure is pickled with a key that
differs in every process); the problem's own ``njit(cache=True)`` step calls :func:`step` (or
:func:`newton`) here, ``register_jitable`` functions compiled into the caller, with its
residual, a ``register_jitable`` function too, as the first argument: the residual is then a
compile-time constant of the caller's type, the caller's cache key stays the same in every
process, and the call is inlined as if the loop were written out. Each is the engine's own
building block compiled, not a copy of it:

* :func:`step` and :func:`newton`: :func:`continuation.corrector.step` (the corrector, then the
  tangent and ``det [J; t^T]``) and :func:`continuation.corrector.newton` (the corrector), the
  loop the engine's Python path runs too;
* :func:`tangent_det`: :func:`continuation.linalg.tangent_det`, the unit tangent from the
  bordered system ``[J; t_ref^T] y = e`` and ``det [J; t^T]`` (``ok`` False on a singular
  bordered matrix: the engine then takes the tangent from the SVD, in Python);
* :func:`predict`: :func:`continuation.interpolation.predict`, the Hermite extrapolation of the
  last step, or the tangent;
* :func:`norm`: :func:`continuation.linalg.norm` (compiled: a loop);
* :func:`solve_dense`: ``continuation.linalg._solve_dense``, ``a x = b`` in place (float or
  complex; all NaN at a zero pivot), the compiled 6 x 6 solve of the nonlinear models'
  right-hand sides.

The ``njit`` ones are ``numba.njit(cache=True)``: compiled once per machine and cached in
``__pycache__``. Importing this module imports numba and registers the engine's building blocks
with it, through numba's public API only (``numba.extending.register_jitable``
for the functions of :mod:`continuation.linalg`, :mod:`continuation.interpolation` and
:mod:`continuation.corrector` that run in both worlds, ``numba.extending.overload`` for those
whose compiled storage or summation differs); the engine's Python path never imports it.
"""

from __future__ import annotations

import numpy as np
from numba import njit
from numba.extending import overload, register_jitable

from . import corrector, interpolation, linalg

__all__ = ["newton", "norm", "predict", "solve_dense", "step", "tangent_det"]

_JIT = dict(cache=True, fastmath=False, nogil=True, error_model="numpy")


# the building blocks of continuation.linalg, continuation.interpolation and continuation.corrector,
# registered with numba once, when this module is imported
for fn in (linalg.lu_solve, linalg._lu_solve_array, linalg._lu_solve3, linalg.tangent_det):
    register_jitable(fn)
for fn in (interpolation.hermite_eval, interpolation.predict, corrector.newton, corrector.step):
    register_jitable(fn)
for fn, impl in (
    (linalg.bordered_solve, linalg._bordered_solve_compiled),
    (linalg.norm, linalg._norm_compiled),
    (linalg.dot, linalg._dot_compiled),
    (linalg.least_squares, linalg._least_squares_compiled),
):
    overload(fn, jit_options={k: _JIT[k] for k in ("fastmath", "nogil", "error_model")})(impl)

#: the corrector of a step, and the corrector with the tangent (:mod:`continuation.corrector`)
newton, step = corrector.newton, corrector.step


@njit(**_JIT)
def norm(x: np.ndarray) -> float:
    """Euclidean norm of a short vector (:func:`continuation.linalg.norm`, compiled)."""
    return linalg.norm(x)


#: ``(ok, t, det)``: the unit null vector ``t`` of ``J`` (n, n+1) with ``t . t_ref > 0`` and
#: ``det [J; t^T]`` (:func:`continuation.linalg.tangent_det`, compiled)
tangent_det = njit(**_JIT)(linalg.tangent_det)

#: the predictor of a step (:func:`continuation.interpolation.predict`, compiled)
predict = njit(**_JIT)(interpolation.predict)

#: ``a x = b`` in place by :func:`continuation.linalg.lu_solve` (``a`` overwritten, ``b`` holds
#: and is the solution; all NaN at a zero or NaN pivot), for float and complex arrays
solve_dense = njit(**_JIT)(linalg._solve_dense)
