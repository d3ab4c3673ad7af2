"""The problem protocol of the continuation engine: what a client writes.

A *continuation problem* is a smooth map ``F: R^(n+1) -> R^n`` whose zero set near a regular
point is a curve; the continuation parameter is one of the ``n + 1`` unknowns (as in pacopy or
AUTO, with the parameter not singled out). A problem is any object with the attributes below:
the engine (:func:`continuation.trace`, :func:`continuation.trace_both`,
:func:`continuation.project`) looks the optional ones up by name
and knows nothing else about it. All arrays are float64 NumPy arrays in the problem's own
variables ``u``; the engine measures lengths in ``v = u / scale`` (``trace(..., scale=)``) and
does the scaling itself. A worked example: docs/continuation.md, "How to write a problem".

Required:

``residual(u) -> ndarray (n,)``
    ``F(u)``. Its size defines the accuracy of the traced points: the corrector iterates until
    ``||F(u)||_2 <= tol``, so a client should scale ``F`` to be ``O(1)`` (for instance a
    relative backward error).

Optional:

``jacobian(u) -> ndarray (n, n+1)``
    ``dF/du``. Accuracy of the Jacobian only affects the convergence rate of Newton's method
    and the tangent (hence where folds are located, see :mod:`continuation.events`); without
    it the engine uses central differences (:func:`finite_difference_jacobian`).
``residual_and_jacobian(u) -> (ndarray (n,), ndarray (n, n+1))``
    Both at once, when that is cheaper than two calls (the corrector asks for both at every
    Newton iterate); without it the engine calls the two methods.
``test_function_names`` (tuple of str) and ``test_functions(u, t) -> ndarray (len(names),)``
    Scalars whose sign changes along the curve mark special points; the engine locates each
    change exactly (:mod:`continuation.events`) and marks the point ``"test"`` with the
    function's name as detail. ``t`` is the unit tangent at ``u`` (problem variables), for
    tests that need it. Folds (turning points of a component of ``u``) need no test function:
    ask for them with ``trace(..., fold_components=(i, ...))``; branch points (``det [J; t^T]``
    changes sign) are found without one too.
``constraint_names`` (tuple of str) and ``constraints(u) -> ndarray (len(names),)``
    Values ``g_j(u)`` that must stay ``>= 0``; the branch ends exactly where the first one
    reaches zero (kind ``"boundary"``, the constraint's name as detail): bounds of a box,
    edges of a physical domain. A start point must satisfy them (to ``start_slack``).
``compiled_step(guess, t_plane, anchor, h, scale, tol, max_iter, max_move) -> tuple``
    A compiled corrector (numba), used by :func:`continuation.trace` for every step and for
    every corrector solve while locating special points; absent or None: the engine's Python
    path. In the engine's scaled variables ``v = u / scale`` (all arrays float64, shape
    ``(n+1,)``), it must do what the Python path does:

    1. Newton's method on ``[F(v * scale); t_plane . (v - anchor) - h] = 0`` from ``guess``
       (the bordered system ``[J; t_plane^T] dv = -[F; plane]``, ``J = dF/du * scale``);
       converged when ``||F||_2 <= tol`` and ``|t_plane . (v - anchor) - h| <= 1e3 eps (1 +
       |h|)``; then one more Newton step, kept if it lowers ``||F||`` (skipped when
       ``||F|| <= 4 eps``); failed after ``max_iter`` iterations, on a value that is not finite,
       on a singular bordered matrix before convergence, or when an iterate moves farther than
       ``max_move`` from ``guess``;
    2. at the point: the unit tangent ``t`` from ``[J; t_plane^T] y = e_(n+1)``, ``t = y /
       |y|`` (so ``t . t_plane > 0``), and the branch-point test ``det [J; t^T] = det [J;
       t_plane^T] |y|``.

    Returns a :class:`StepResult` (or a plain tuple of its 9 or 11 fields, which the engine
    turns into one), ``(ok, iterations, n_residual_and_jacobian, n_residual, v, jacobian,
    tangent_ok, tangent, det)``: the work counts feed :class:`continuation.Branch`; ``J`` is the scaled Jacobian
    the tangent came from (the one of the last Newton step if the polishing step was kept);
    ``tangent_ok`` False (singular bordered matrix) makes the engine take the tangent from
    the SVD of ``J``. Optionally two more values, ``(..., det, g, tests)``: the problem's
    ``constraints(u)`` and ``test_functions(u, t)`` at ``u = v * scale`` (when ``ok``; the
    same numbers the methods give), which the engine then does not ask for separately. It
    must solve the same equations as ``residual`` (which the engine still uses to project the
    start point and to end a branch on a constraint). The building blocks, the Python path's
    own functions compiled, are in :mod:`continuation.compiled`: the corrector loop
    :func:`~continuation.compiled.newton`, which a problem's own compiled step calls with its
    residual (a ``register_jitable`` function, so that numba caches the step on disk), the
    bordered tangent, the norm; e.g. ``HopfWithHook`` in tests/test_continuation_engine.py, or
    :mod:`stability.linear.neutral_compiled`.

Rules: the methods are functions of their arguments only. The engine calls them at points of
its choosing (predictions, Newton iterates, points inside a step while it locates special
points), as often and in whatever order it needs, and relies on the same ``u`` giving the same
numbers (the traced points are reproducible bit for bit). ``F``, its Jacobian, the test
functions, the constraints and ``compiled_step`` describe one and the same curve.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import NamedTuple, Protocol, runtime_checkable

import numpy as np

__all__ = ["ContinuationProblem", "StepResult", "finite_difference_jacobian", "problem_dimension"]


class StepResult(NamedTuple):
    """What a problem's ``compiled_step`` returns (module docstring, item ``compiled_step``):
    one corrector solve and the tangent at its point, in the engine's scaled variables."""

    #: Whether Newton's method converged.
    ok: bool
    #: Newton iterations taken.
    iterations: int
    #: Evaluations of the residual together with the Jacobian.
    n_residual_and_jacobian: int
    #: Evaluations of the residual alone.
    n_residual: int
    #: The point reached (scaled), shape (n+1,).
    v: np.ndarray
    #: The scaled Jacobian the tangent came from.
    jacobian: np.ndarray
    #: False: the bordered matrix was singular (the engine takes the tangent from the SVD).
    tangent_ok: bool
    #: The unit tangent at ``v``.
    tangent: np.ndarray
    #: The branch-point test ``det [J; t^T]``.
    det: float
    #: Optional: the problem's constraints at the point (then ``tests`` too).
    constraints: np.ndarray | None = None
    #: Optional: the problem's test functions at the point.
    tests: np.ndarray | None = None


@runtime_checkable
class ContinuationProblem(Protocol):
    """Minimal protocol: a residual ``F: R^(n+1) -> R^n``.

    The optional members (``jacobian``, ``residual_and_jacobian``, ``test_function_names`` and
    ``test_functions``, ``constraint_names`` and ``constraints``, ``compiled_step``) and the
    rules are in the docstring of :mod:`continuation.problem`.
    """

    def residual(self, u: np.ndarray) -> np.ndarray:
        """Return ``F(u)``, shape ``(n,)``."""


def finite_difference_jacobian(
    residual: Callable[[np.ndarray], np.ndarray], u: np.ndarray, f0: np.ndarray | None = None, rel_step: float = 6e-6
) -> np.ndarray:
    """Central-difference Jacobian of ``residual`` at ``u``.

    Parameters
    ----------
    residual : callable
        ``F(u) -> ndarray (n,)``.
    u : numpy.ndarray, shape (n+1,)
        Point.
    f0 : numpy.ndarray, optional
        Unused (kept so callers can pass ``F(u)`` when they have it).
    rel_step : float, default 6e-6
        Step ``h_i = rel_step * max(1, |u_i|)``; about ``u**(1/3)`` balances truncation
        (``O(h^2)``) and rounding (``O(u / h)``), relative error ``~1e-10``.

    Returns
    -------
    numpy.ndarray, shape (n, n+1)
    """
    u = np.asarray(u, dtype=float)
    cols = []
    for i in range(u.size):
        h = rel_step * max(1.0, abs(u[i]))
        e = np.zeros_like(u)
        e[i] = h
        cols.append((np.asarray(residual(u + e)) - np.asarray(residual(u - e))) / (2.0 * h))
    return np.stack(cols, axis=-1)


def problem_dimension(problem: ContinuationProblem, u: np.ndarray) -> int:
    """Number of equations ``n`` of ``problem`` (checked against ``u``, which has ``n + 1``)."""
    f = np.asarray(problem.residual(np.asarray(u, dtype=float)))
    if f.ndim != 1 or f.size + 1 != np.size(u):
        raise ValueError(
            f"the residual at a point of {np.size(u)} unknowns has shape {f.shape}; "
            f"a curve needs {np.size(u) - 1} equations"
        )
    return f.size
