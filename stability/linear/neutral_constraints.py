"""The constraints of a neutral-curve problem: the physical domain's bounds and the ranges.

The bounds of the table :data:`stability.parameters.DOMAIN` that involve a traced parameter
(through :func:`~stability.parameters.domain_sides`) and the ends of the requested ranges, as
rows ``(code, index, a)`` (:class:`Constraint`, :func:`constraints_of`), evaluated by one
function, :func:`constraint_values`, in both executions: interpreted on Python floats by
:class:`stability.linear.neutral_curves.NeutralProblem` and ``FoldProblem``, compiled in the
continuation's compiled step (:mod:`stability.linear.neutral_compiled`).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any, NamedTuple

import numpy as np

from ..jit import register_jitable
from ..models import LinearModel
from ..parameters import DOMAIN, PARAMETERS, domain_sides

__all__ = ["Constraint", "constraint_values", "constraints_of"]


class Constraint(NamedTuple):
    """One constraint ``g(params) >= 0`` of a neutral-curve problem.

    Attributes
    ----------
    name : str
        The bound as text (a domain bound's text of :data:`stability.parameters.DOMAIN`, or the
        end of a requested range); the ``detail`` of a point where a branch ends on it.
    kind : str
        ``"domain_edge"`` or ``"endpoint"``.
    code : int
        0 (``g`` = the margin ``upper - lower`` of row ``index`` of ``DOMAIN`` minus ``a``), 1
        (a lower end, ``p[index] - a``) or 2 (an upper end, ``a - p[index]``); ``index`` of a
        parameter counts in :data:`stability.parameters.PARAMETERS`.
    index : int
    a : float
    bound : (str, float) or None
        ``(parameter, value)`` if ``g`` is a simple bound on one parameter.
    """

    name: str
    kind: str
    code: int
    index: int
    a: float
    bound: tuple[str, float] | None


def constraints_of(
    model: LinearModel, free: Sequence[str], ranges: Mapping[str, tuple[float, float]], margin: float
) -> list[Constraint]:
    """The bounds of the domain table that involve a free parameter (and only parameters of the
    model), strict ones as ``>= margin``, then the requested ranges."""
    f = set(free)
    given = set(model.parameters)
    out: list[Constraint] = []
    for k, b in enumerate(DOMAIN):
        if set(b.involves) <= given and set(b.involves) & f:
            a = margin if b.strict else 0.0
            simple = (b.involves[0], a) if len(b.involves) == 1 else None
            out.append(Constraint(b.text, "domain_edge", 0, k, a, simple))
    for name, (lo, hi) in ranges.items():
        j = PARAMETERS.index(name)
        out.append(Constraint(f"{name} >= {lo:g} (end of {name}_range)", "endpoint", 1, j, lo, (name, lo)))
        out.append(Constraint(f"{name} <= {hi:g} (end of {name}_range)", "endpoint", 2, j, hi, (name, hi)))
    return out


@register_jitable
def constraint_values(point: Any, free_index: Any, u: Any, codes: Any, index: Any, a: Any) -> np.ndarray:
    """The problem's constraints at ``u`` (the free parameters' values), ``>= 0`` inside, from
    rows ``(code, index, a)`` (the fields of :class:`Constraint`); ``point``: the five parameters
    ``(q, fr_inv, sigma, alpha_v, mu)``, free ones at ``free_index``. One source for both
    executions: Python lists of floats on the Python path, arrays inside the compiled step
    (:mod:`stability.linear.neutral_compiled`)."""
    p = point.copy()
    for i in range(len(free_index)):
        p[free_index[i]] = u[i]
    sides = domain_sides(p[0], p[1], p[2], p[3], p[4], 0.0)
    out = np.empty(len(codes))
    for k in range(len(codes)):
        c = codes[k]
        j = index[k]
        if c == 0:
            out[k] = (sides[2 * j + 1] - sides[2 * j]) - a[k]
        elif c == 1:
            out[k] = p[j] - a[k]
        else:
            out[k] = a[k] - p[j]
    return out
