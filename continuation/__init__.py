"""Numerical continuation of curves ``F(u) = 0`` and the neutral curves of the linear models.

The engine (:mod:`continuation.engine`, :mod:`continuation.events`,
:mod:`continuation.problem`, and the dense output :mod:`continuation.dense`) is generic and knows nothing about tops. The neutral-curve problem
of the linear models (:mod:`continuation.neutral`) is one of its clients; it is imported on
first use so that the engine can be used without :mod:`stability`. A problem may bring its own
compiled corrector (the ``compiled_step`` hook of :mod:`continuation.problem`, built from
:mod:`continuation.compiled`; :mod:`continuation.neutral_compiled` for the sliding model).
"""

from __future__ import annotations

from typing import Any

from .dense import dense, hermite_samples
from .engine import Branch, ConvergenceError, correct, hermite, project, tangent, trace, trace_both
from .events import fold_test, locate
from .problem import ContinuationProblem, finite_difference_jacobian

__all__ = [
    "Branch", "ConvergenceError", "ContinuationProblem", "correct", "finite_difference_jacobian",
    "fold_test", "locate", "project", "tangent", "trace", "trace_both", "dense", "hermite",
    "hermite_samples",
    "neutral_curve", "fold_curve", "NeutralProblem",
]

_LAZY = {"neutral_curve", "fold_curve", "NeutralProblem"}


def __getattr__(name: str) -> Any:
    if name in _LAZY:
        from . import neutral

        return getattr(neutral, name)
    raise AttributeError(f"module 'continuation' has no attribute {name!r}")
