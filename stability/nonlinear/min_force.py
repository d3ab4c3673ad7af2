"""The smallest normal force of a run that is not stopped where it reaches zero.

``N_min = min over 0 <= t <= t_end of N(t)`` (``N`` the vertical component of eq. 1,
:func:`stability.nonlinear.integrators.normal_force_of`), on a run of the compiled
Dormand-Prince integrator with the contact unwatched (:func:`~stability.nonlinear.integrators.integrate`,
``watch_contact=False``), so that ``N_min`` keeps its sign where the contact would be lost: the
smallest sample of ``N`` on an output grid of step ``sample_step``, then the interior minimum
(``dN/dt = 0``) between its two neighbours by Brent's bounded minimisation, each trial time a
run restarted from the sample before (the minimum is one of the integrated solution, exact to
the integrator's tolerance: an error ``delta`` in its time moves the value by
``N'' delta^2 / 2`` only). At ``t = 0`` or ``t_end`` (no interior minimum) the sample is the
answer. ``N_min`` is a minimum over time: smooth in the initial state and the parameters where
one interior minimum is the smallest (envelope theorem), with kinks where two minima exchange.
"""

from __future__ import annotations

import math

import numpy as np

from ..errors import RunError
from . import get_nonlinear_model
from .integrators import integrate

__all__ = ["SAMPLE_STEP", "min_normal_force"]

#: output step (units of 1/Omega) of the first search: ~60 samples a nutation period (~2 pi / sigma)
SAMPLE_STEP = 0.1


def min_normal_force(
    model: str, y0: np.ndarray, p: np.ndarray, t_end: float, *, rtol: float = 1e-10, sample_step: float = SAMPLE_STEP
) -> tuple[float, float]:
    """``(N_min, t_min)`` of the run of ``model`` from ``y0`` (kernels' parameter vector ``p``)
    over ``[0, t_end]`` (module docstring), in the run's units (``N`` at rest ``mu fr_inv``).

    Raises
    ------
    stability.errors.RunError
        The integration failed.
    """
    from scipy.optimize import minimize_scalar

    m = get_nonlinear_model(model)
    n = max(2, int(math.ceil(t_end / sample_step)))
    t_eval = np.linspace(0.0, t_end, n + 1)
    sol = integrate(m.name, np.asarray(y0, float), t_eval, p, rtol=rtol, atol=1e-3 * rtol)
    if sol.status < 0:
        raise RunError(f"the run for the smallest normal force failed: {sol.message}")
    forces = m.contact_forces(np.ascontiguousarray(sol.y), p)[:, 2]
    i = int(np.argmin(forces))
    if i == 0 or i == n:
        return float(forces[i]), float(t_eval[i])
    start = sol.y[i - 1]

    def force(tau: float) -> float:
        if tau <= 0.0:
            return float(forces[i - 1])
        s = integrate(m.name, start, np.array([0.0, tau]), p, rtol=rtol, atol=1e-3 * rtol)
        return float(m.contact_forces(np.ascontiguousarray(s.y[-1:]), p)[0, 2])

    dt = float(t_eval[1] - t_eval[0])
    res = minimize_scalar(force, bounds=(0.0, 2.0 * dt), method="bounded", options={"xatol": 1e-9})
    if float(res.fun) < float(forces[i]):
        return float(res.fun), float(t_eval[i - 1]) + float(res.x)
    return float(forces[i]), float(t_eval[i])
