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

Every name is imported on first use (PEP 562), so that importing a building block
(``from continuation.jit import register_jitable``, which the formulas of :mod:`stability` do)
imports neither the engine nor scipy.
"""

from __future__ import annotations

import importlib
from typing import Any

#: public name -> the module that defines it (imported on first use)
_EXPORTS: dict[str, str] = {
    "dense": ".dense", "hermite_samples": ".dense",
    **dict.fromkeys(("Branch", "correct", "project", "tangent", "trace", "trace_both"), ".engine"),
    "ConvergenceError": ".errors",
    "fold_test": ".events", "locate": ".events",
    "hermite": ".interpolation",
    "ContinuationProblem": ".problem", "finite_difference_jacobian": ".problem",
    # the facade: the clients of the engine in stability
    **dict.fromkeys(("neutral_curve", "fold_curve", "NeutralProblem"), "stability.linear.neutral_curves"),
    "steady_branch": "stability.steady.branch",
}

__all__ = [
    "Branch", "ConvergenceError", "ContinuationProblem", "correct", "finite_difference_jacobian",
    "fold_test", "locate", "project", "tangent", "trace", "trace_both", "dense", "hermite",
    "hermite_samples",
    "neutral_curve", "fold_curve", "NeutralProblem", "steady_branch",
]


def __getattr__(name: str) -> Any:
    if name in _EXPORTS:
        value = getattr(importlib.import_module(_EXPORTS[name], __name__), name)
        if _EXPORTS[name].startswith("stability"):
            # the clients return datasets: give them ds.tippe (stability's facade does the same)
            importlib.import_module("stability.plotting.accessor")
        else:
            globals()[name] = value
        return value
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(_EXPORTS))
