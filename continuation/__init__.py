"""Numerical continuation of curves ``F(u) = 0``: a generic pseudo-arclength engine.

The engine (the stepper :mod:`continuation.engine`, :mod:`continuation.events`, the problem
protocol :mod:`continuation.problem`, the dense output :mod:`continuation.dense`, and its
numerical building blocks, each written once for Python and numba: the corrector
:mod:`continuation.corrector`, the small dense solves and the bordered tangent
:mod:`continuation.linalg`, the cubic Hermite curve
:mod:`continuation.interpolation`, and their compiled faces :mod:`continuation.compiled`) knows
nothing about tops and imports nothing from :mod:`stability`. A problem may bring its own compiled corrector
(the ``compiled_step`` hook of :mod:`continuation.problem`, built from
:mod:`continuation.compiled`).

Its clients live in the application: the neutral and fold curves of the linear models are
``stability.neutral_curve`` and ``stability.fold_curve``
(:mod:`stability.linear.neutral_curves`, with their compiled step
:mod:`stability.linear.neutral_compiled`), the branch of tilted steady states is
``stability.steady_branch`` (:mod:`stability.steady.branch`). No module of this package, its
``__init__`` included, refers to :mod:`stability` (docs/architecture.md).

Every name is imported on first use (PEP 562), so that importing a building block
(``from continuation.linalg import lu_solve``) imports neither the engine nor scipy, and
nothing here imports numba until compiled code is wanted (:mod:`continuation.compiled`).
"""

from __future__ import annotations

import importlib
from typing import Any

#: public name -> the module that defines it (imported on first use)
_EXPORTS: dict[str, str] = {
    "dense": ".dense",
    "hermite_samples": ".dense",
    **dict.fromkeys(("Branch", "TraceOptions", "project", "tangent", "trace", "trace_both"), ".engine"),
    "ConvergenceError": ".errors",
    "locate": ".events",
    "hermite": ".interpolation",
    "ContinuationProblem": ".problem",
    "StepResult": ".problem",
    "finite_difference_jacobian": ".problem",
}

__all__ = sorted(_EXPORTS)  # noqa: PLE0605 - the names of _EXPORTS (one list of the public names)


def __getattr__(name: str) -> Any:
    if name in _EXPORTS:
        value = getattr(importlib.import_module(_EXPORTS[name], __name__), name)
        globals()[name] = value
        return value
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(_EXPORTS))
