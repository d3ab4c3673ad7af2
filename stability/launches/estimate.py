"""Cheap estimates of the flip time, and the flip-time map of a top (issue 23).

The e-folding estimate. Near the upright state the tilt of the sliding top grows as
``exp(g t)`` with ``g`` the leading growth rate of eq. (11) (:func:`stability.eigenvalues`, the
sliding model at the launch spin, units of ``Omega``). Taking the tilt to follow that growth all
the way, the time from ``theta0`` to ``theta_c`` is

    t_efold = ln(tan(theta_c / 2) / tan(theta0 / 2)) / g                              (*)

(``tan(theta/2)`` is the stereographic coordinate of the axis, which equals ``theta/2`` to
third order and makes (*) exact in the linear regime while keeping it finite at 90 degrees).
It ignores (i) the projection of the launch state on the growing mode (the launch state
excites the growing and the decaying precession modes alike, which delays the growth by a
transient of a few ``1/g``), and (ii) the nonlinear slowing of the growth as the centre of mass
rises.

The projected estimate removes (i). In eq. (11)'s variables (fixed frame, complex:
``omega = omega_1 + i omega_2``, ``Phi = l + i m`` the tilt of k, ``V`` the centre's velocity),
the launch state is ``x0 = theta0 (1, 1, 0)`` to first order (``omega = k``, centre at rest).
With ``M x' = A x`` (:meth:`stability.models.sliding.Sliding.matrices`),
``M^-1 A = W diag(s) W^-1``, the growing mode's share of the tilt is
``a0 = |(W^-1 x0)_lead W_{Phi, lead}|``, and the tilt follows ``a0 e^{g t}`` once the other
modes have decayed, so

    t_projected = t_efold + ln(theta0 / a0) / g                                          (**)

(``theta0 / a0`` does not depend on ``theta0``: the model is linear). Its error against the
simulation is charted by ``benchmarks/flip_estimates.py`` (docs/launch.md): a few per cent well
above the critical spin, tens of per cent near it, where (ii) dominates;
:func:`stability.flip_time` (the simulation) is the answer :func:`stability.launch` gives.
"""

from __future__ import annotations

import math
import time
from typing import Any

import numpy as np
import xarray as xr

from ..linear.spectra import eigenvalues
from ..top import Top, from_rad_per_s
from .flip import launch_parameters, product_header, run_launch

__all__ = ["efold_flip_time", "flip_time_map"]

#: the cheap estimates, by name (module docstring: (*) and (**))
ESTIMATES = ("efold", "projected")

#: the product attribute of :func:`flip_time_map` (docs/datasets.md)
MAP_PRODUCT = "flip_time_map"


def efold_flip_time(
    params: dict[str, float], tilt: float, crossing: float = 90.0, *, estimate: str = "projected"
) -> float | None:
    """The e-folding estimate, ``"efold"`` (*) or ``"projected"`` (**) of the module docstring,
    in units of ``1/Omega``; None where the upright state does not grow (leading growth rate
    <= 0)."""
    from ..models import get_model
    from ..parameters import check_choice

    check_choice("estimate", estimate, ESTIMATES)
    nd = {k: params[k] for k in ("q", "fr_inv", "sigma", "alpha_v", "mu")}
    ev = eigenvalues("sliding", **nd)
    g = float(np.max(ev.real))
    if not g > 0.0:
        return None
    t = math.log(math.tan(math.radians(crossing) / 2) / math.tan(math.radians(tilt) / 2)) / g
    if estimate == "efold":
        return t
    m, a = get_model("sliding").matrices(**nd)
    s, w = np.linalg.eig(np.linalg.solve(m, a))
    lead = int(np.argmax(s.real))
    a0 = abs(np.linalg.solve(w, np.array([1.0, 1.0, 0.0], dtype=complex))[lead] * w[1, lead])
    return t + math.log(1.0 / a0) / g


def flip_time_map(
    top: Top,
    spins: Any,
    tilts: Any,
    *,
    unit: str = "rev/s",
    alpha_v: Any = None,
    crossing: float = 90.0,
    t_max: float = 2e4,
    estimate: bool = True,
) -> xr.Dataset:
    """Time to ``crossing`` degrees (s) of launches of ``top`` over ``spins`` (in ``unit``) and
    initial ``tilts`` (degrees): :func:`stability.launches.flip.run_launch` per point (NaN where
    the axis does not reach it within ``t_max`` time units), and the e-folding estimate.

    Returns
    -------
    xarray.Dataset
        ``flip_time`` (s), ``flip_periods`` (spin periods) and, with ``estimate``,
        ``flip_time_efold`` (s) over ``(tilt, spin)``; ``spin`` in ``unit``; attributes the
        top's ``q, mu, sigma``, ``alpha_v`` source, the wall time (``seconds``); product
        ``flip_time_map``.
    """
    spins = np.atleast_1d(np.asarray(spins, dtype=float))
    tilts = np.atleast_1d(np.asarray(tilts, dtype=float))
    t_flip, t_est, periods = (np.full((tilts.size, spins.size), np.nan) for _ in range(3))
    source = ""
    t0 = time.perf_counter()
    for j, s in enumerate(spins):
        w, params, source = launch_parameters(top, float(s), unit, alpha_v, "sliding")
        for i, th in enumerate(tilts):
            run = run_launch(params, tilt=float(th), crossing=crossing, stop_at_crossing=True, t_max=t_max)
            if run.crossing_time is not None:
                t_flip[i, j] = run.crossing_time / w
                periods[i, j] = run.crossing_time / (2 * math.pi)
            if estimate:
                e = efold_flip_time(params, float(th), crossing, estimate="projected")
                if e is not None:
                    t_est[i, j] = e / w
    seconds = time.perf_counter() - t0
    dims, crosses = ("tilt", "spin"), f"until the axis crosses {crossing:g} degrees"
    data = {
        "flip_time": (dims, t_flip, {"long_name": f"time {crosses}", "units": "s"}),
        "flip_periods": (dims, periods, {"long_name": f"spin periods {crosses}", "units": "1"}),
    }
    if estimate:
        efold = {"long_name": "projected e-folding estimate of the flip time", "units": "s"}
        data["flip_time_efold"] = (dims, t_est, efold)
    units = {"rad/s": "rad s-1", "rev/s": "s-1", "Hz": "Hz", "rpm": "min-1"}[unit]
    coords = {
        "spin": ("spin", spins, {"long_name": "launch spin", "units": units, "spin_unit": unit}),
        "tilt": ("tilt", tilts, {"long_name": "initial tilt of the axis", "units": "degree"}),
    }
    attrs = product_header(MAP_PRODUCT, "flip time of launches of a real top")
    attrs.update(q=top.q, mu=top.mu, sigma=top.sigma, radius_m=top.radius, mass_kg=top.mass, alpha_v_source=source)
    per_unit = float(from_rad_per_s(1.0, "rev/s") / from_rad_per_s(1.0, unit))
    attrs.update(crossing_deg=crossing, t_max=t_max, seconds=seconds, spin_unit=unit, spin_rev_s_per_unit=per_unit)
    return xr.Dataset(data, coords=coords, attrs=attrs)
