"""Numerical continuation of curves ``F(u) = 0``: a generic pseudo-arclength engine.

The engine (the stepper :mod:`continuation.engine`, :mod:`continuation.events`, the problem
protocol :mod:`continuation.problem`, the dense output :mod:`continuation.dense`, and its
numerical building blocks, each written once for Python and numba: the small dense solves and
the bordered tangent :mod:`continuation.linalg`, the cubic Hermite curve
:mod:`continuation.interpolation`, and their compiled faces :mod:`continuation.compiled`) knows
nothing about tops and imports nothing from :mod:`stability`. A problem may bring its own compiled corrector
(the ``compiled_step`` hook of :mod:`continuation.problem`, built from
:mod:`continuation.compiled`).

Facade: the neutral curves of the linear models are a client of the engine and live in
:mod:`stability.linear.neutral_curves` (with their compiled step,
:mod:`stability.linear.neutral_compiled`). For convenience ``continuation.neutral_curve``,
``continuation.fold_curve`` and ``continuation.NeutralProblem`` re-export them, imported on
first use (module ``__getattr__``) so that the engine can be used without :mod:`stability`.
Likewise ``continuation.steady_branch`` re-exports :func:`stability.steady.branch.steady_branch`
(the family of tilted steady states of the sliding top against Jellett's integral, traced by
this engine). This ``__init__`` is the only module of the package that refers to
:mod:`stability` (docs/architecture.md).
"""

from __future__ import annotations

from typing import Any

from .dense import dense, hermite_samples
from .engine import Branch, correct, project, tangent, trace, trace_both
from .errors import ConvergenceError
from .events import fold_test, locate
from .interpolation import hermite
from .problem import ContinuationProblem, finite_difference_jacobian

__all__ = [
    "Branch", "ConvergenceError", "ContinuationProblem", "correct", "finite_difference_jacobian",
    "fold_test", "locate", "project", "tangent", "trace", "trace_both", "dense", "hermite",
    "hermite_samples",
    "neutral_curve", "fold_curve", "NeutralProblem", "steady_branch",
]

_LAZY = {"neutral_curve", "fold_curve", "NeutralProblem"}


def __getattr__(name: str) -> Any:
    if name in _LAZY:
        from stability.linear import neutral_curves

        return getattr(neutral_curves, name)
    if name == "steady_branch":
        from stability.steady.branch import steady_branch

        return steady_branch
    raise AttributeError(f"module 'continuation' has no attribute {name!r}")
