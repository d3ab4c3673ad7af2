"""Time until the axis of a launched top crosses a tilt, by event location on a nonlinear run.

The launch state (issue 23), in the units of :func:`stability.simulate` (length R, time
``1/Omega`` with ``Omega`` the launch spin): spun about its own axis, ``omega = k`` (spin 1),
the axis tilted by ``tilt`` degrees from the vertical in the x-z plane,
``k = (sin tilt, 0, cos tilt)``, the sphere's centre at rest (``V_O = 0``).

Event location: the run is integrated in chunks (:func:`stability.simulate`, compiled
Dormand-Prince 5(4) at the tolerance given) with output every ``dt`` time units; the first
output at or beyond the crossing tilt brackets the event between two outputs, and Brent's
method (:func:`scipy.optimize.brentq`, ``xtol = 1e-12`` time units) locates it on the run
restarted from the output before (each evaluation integrates from that state to the trial
time at the same tolerance, so the event is a root of the integrated solution, not of an
interpolant). The nondimensional core (:func:`run_launch`) is reused by
:func:`stability.launch`; :func:`flip_time` converts a top in SI units and a spin in any unit
of :data:`stability.top.SPIN_UNITS`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from .._version import package_version
from ..errors import DomainError, ParameterTypeError, RunError
from ..nonlinear.runs import run_in_chunks, simulate
from ..parameters import as_scalar, check_choice, check_interval, check_positive
from ..products import PRODUCT_ATTR
from ..top import Top, check_launch_spin

__all__ = ["FlipRun", "flip_time", "launch_parameters", "launch_state", "product_header", "run_launch"]

#: the models a launch can be asked of (the launch state has the centre at rest: sliding only)
MODELS = ("sliding",)
#: the paper's viscous friction parameter (Fig. 3, Sec. 3(ii)), used when neither the top's
#: mu_v nor an explicit alpha_v is given
DEFAULT_ALPHA_V = 0.5
#: tolerance of a launch run after its crossing (the settle time and the smallest normal force)
TAIL_RTOL = 1e-8
#: the settle time is when the tilt stays within this many degrees of its end
BAND = 1.0


def launch_state(tilt: float) -> dict[str, list[float]]:
    """``omega``, ``k``, ``velocity`` of the launch state (module docstring), tilt in degrees."""
    th = math.radians(tilt)
    k = [math.sin(th), 0.0, math.cos(th)]
    return {"omega": list(k), "k": k, "velocity": [0.0, 0.0]}


def product_header(product: str, title: str) -> dict[str, str]:
    """The global attributes that open every dataset of the launches (the product: docs/datasets.md)."""
    source = f"tippe-stability {package_version()}"
    return {"Conventions": "CF-1.10", PRODUCT_ATTR: product, "title": title, "source": source}


def launch_parameters(top: Top, spin: Any, unit: str, alpha_v: Any, model: str) -> tuple[float, dict[str, float], str]:
    """The launch spin in rad/s, the nondimensional set at it (``Omega`` = the launch spin) and
    where ``alpha_v`` came from: the top's ``mu_v`` by eq. (7) (``alpha_v = mu mu_v g / Omega``,
    :meth:`stability.Top.alpha_v`), the explicit argument, or the paper's 0.5 by default."""
    if not isinstance(top, Top):
        raise ParameterTypeError(f"top must be a stability.Top, got {type(top).__name__}")
    check_choice("model", model, MODELS)
    w = check_launch_spin(spin, unit)
    if top.mu_v is not None:  # an explicit alpha_v too is refused by Top.nondimensional
        source = f"eq. (7) from the top's mu_v = {top.mu_v:g} s/m: alpha_v = mu mu_v g / Omega"
    elif alpha_v is not None:
        source = "given (alpha_v argument)"
    else:
        alpha_v = DEFAULT_ALPHA_V
        source = f"default {DEFAULT_ALPHA_V:g} (the paper's; the top has no mu_v and no alpha_v was given)"
    return w, {k: float(v) for k, v in top.nondimensional(w, alpha_v=alpha_v).items()}, source


@dataclass(frozen=True)
class FlipRun:
    """A launch integrated until its tilt settles (nondimensional, :func:`run_launch`).

    Attributes
    ----------
    crossing_time : float or None
        First time the tilt reaches ``crossing`` degrees (units of ``1/Omega``), None if never.
    settle_time : float or None
        Time after which the tilt stays within :data:`BAND` degrees of ``end_tilt``; None if
        the run did not settle before ``t_max``.
    min_normal_force : float
        Smallest normal force along the run (units ``A0 Omega^2 / R``; equilibrium value
        ``mu fr_inv``).
    reason : str
        Why ``crossing_time`` or ``settle_time`` is None ("" when both are found).
    attrs : dict
        The last chunk's ``simulate`` attributes (``method``, ..., and ``event`` where the model
        reports contact events).
    """

    crossing_time: float | None
    settle_time: float | None
    min_normal_force: float
    reason: str
    attrs: dict


def run_launch(
    params: dict[str, float],
    *,
    tilt: float = 1.0,
    crossing: float = 90.0,
    stop_at_crossing: bool = False,
    t_max: float = 2e5,
    end_tilt: float | None = None,
    rtol: float = 1e-10,
    start: dict[str, Any] | None = None,
    stick_tilt: float | None = None,
) -> FlipRun:
    """Integrate the launch state (module docstring) of a sliding top with the nondimensional
    ``params`` (``q, fr_inv, sigma, mu, alpha_v`` [, ``alpha_k``]) and locate its events.

    The run goes in chunks of 500 time units (output every 0.25) until the tilt has moved by
    less than 1e-3 degree over a chunk, or ``t_max``, or (with ``stop_at_crossing``) the
    crossing, or (with ``end_tilt``) a whole chunk within half :data:`BAND` of ``end_tilt``;
    after the crossing at ``rtol`` no tighter than :data:`TAIL_RTOL`.
    ``end_tilt`` (the predicted end, e.g. from
    :func:`stability.final_state`) sets the band of the settle time; without it, the run's last
    tilt does. ``start`` (``omega``, ``k``, ``velocity`` as :func:`stability.simulate` takes
    them) replaces the launch state, e.g. the paper's printed states of Sec. 3(ii); ``tilt`` is
    then ignored. ``stick_tilt`` (degrees, :meth:`stability.Top.stick_contact`) stops the run where
    the stick touches the floor; a run also stops where the floor's normal force reaches zero
    (:mod:`stability.nonlinear.contact`): ``attrs`` then holds ``event``, ``event_time`` (time
    units from the launch) and ``event_tilt`` (degrees).
    """
    from scipy.optimize import brentq

    tilt = as_scalar("tilt", tilt)
    if not 0.0 < tilt < 180.0:
        raise DomainError(f"tilt = {tilt:g} degrees is outside the allowed range: 0 < tilt < 180")
    crossing = check_interval("crossing", crossing, 0.0, 180.0, closed="right")
    t_max = check_positive("t_max", t_max)
    state = launch_state(tilt)
    if start is not None:
        k0 = np.asarray(start["k"], dtype=float)
        tilt = float(np.degrees(np.arccos(np.clip(k0[2] / np.linalg.norm(k0), -1.0, 1.0))))
        state = {"omega": start["omega"], "k": start["k"], "velocity": start.get("velocity", [0.0, 0.0])}
    n_min, event_note, crossed, settled, attrs = math.inf, "", None, False, {}
    times, tilts = [np.array([0.0])], [np.array([tilt])]

    def tilt_minus(dt_: float, y: dict[str, Any], tilt0: float) -> float:  # the tilt dt_ after y, less crossing
        if dt_ <= 0.0:
            return tilt0 - crossing
        ds = simulate("sliding", t_end=dt_, t_eval=np.array([0.0, dt_]), **y, rtol=rtol, atol=1e-3 * rtol, **params)
        return float(ds.polar_angle[-1]) - crossing

    # after the crossing, the tail (settle time, normal force) at rtol 1e-8 at most: its
    # numbers are read to the 1-degree band and the output step, not to 1e-10
    steps = dict(
        chunk=500.0, t_max=t_max, samples=lambda length: max(2, math.ceil(length / 0.25)), stick_tilt=stick_tilt
    )
    tolerance = dict(rtol=lambda: rtol if crossed is None else max(rtol, TAIL_RTOL))
    for t, length, ds in run_in_chunks(state, params, **steps, **tolerance):
        attrs, pol, ts = dict(ds.attrs), ds.polar_angle.values, ds.time.values
        if not np.all(np.isfinite(pol)):
            raise RunError(f"the launch run failed at t = {t:.6g}: {ds.attrs.get('message', '')}")
        n_min = min(n_min, float(ds.normal_force.min()))
        tt = t + ts
        if crossed is None and (hit := np.nonzero(pol >= crossing)[0]).size and not (crossing <= tilt):
            # Brent's method on runs restarted from the output before the crossing (module docstring)
            i = int(hit[0])
            y = dict(omega=ds.omega.values[i - 1], k=ds.k.values[i - 1], velocity=ds.velocity.values[i - 1][:2])
            bracket = (0.0, float(ts[i] - ts[i - 1]))
            step = brentq(tilt_minus, *bracket, args=(y, float(pol[i - 1])), xtol=1e-12, rtol=8.9e-16, maxiter=200)
            crossed = float(t + ts[i - 1]) + float(step)
        times.append(tt[1:])
        tilts.append(pol[1:])
        t += length
        if attrs.get("event", "none") != "none":  # the model stops holding: contact lost or stick reached
            # omega . k at the event (units of Omega): the spin about the symmetry axis the top
            # carries onto its stick (the stick's sphere has axis -k: the same spin, reversed)
            attrs.update(event_time=float(tt[-1]), event_tilt=float(pol[-1]), event_spin=float(ds.spin.values[-1]))
            event_note = f"the run stops at t = {tt[-1]:.6g} time units: {attrs['event']} at tilt {pol[-1]:.6g} degrees"
            break
        if stop_at_crossing and crossed is not None:
            break
        # settled: the tilt moved less than settle_tolerance, or a whole chunk within half the band of the predicted end
        settled = float(np.max(pol) - np.min(pol)) < 1e-3 or (
            end_tilt is not None and float(np.max(np.abs(pol - end_tilt))) < 0.5 * BAND
        )
        if settled:
            break
    tt, pp = np.concatenate(times), np.concatenate(tilts)
    end = float(pp[-1]) if end_tilt is None else float(end_tilt)
    reasons = [event_note] if event_note else []
    if crossed is None:
        largest = f"largest tilt {float(np.max(pp)):.4g} degrees in {t:.6g} time units"
        reasons.append(f"the axis never reaches {crossing:g} degrees ({largest})")
    settle_t: float | None = None
    out = np.nonzero(np.abs(pp - end) > BAND)[0]
    if settled and out.size == 0:
        settle_t = 0.0
    elif settled and out[-1] + 1 < tt.size:  # linear interpolation of |tilt - end| = band between two outputs
        i = int(out[-1])
        a, b = abs(pp[i] - end) - BAND, abs(pp[i + 1] - end) - BAND
        settle_t = float(tt[i] + a / (a - b) * (tt[i + 1] - tt[i]))
    elif settled:
        reasons.append("the tilt is not yet within the band at the end of the run")
    elif not stop_at_crossing and not event_note:
        periods = f"{t_max / (2 * math.pi):.6g} spin periods"
        reasons.append(f"the tilt did not settle within t_max = {t_max:g} time units ({periods})")
    return FlipRun(crossed, settle_t, n_min, "; ".join(reasons), attrs)


def flip_time(
    top: Top,
    spin: Any,
    unit: str = "rad/s",
    tilt: float = 1.0,
    alpha_v: Any = None,
    model: str = "sliding",
    crossing: float = 90.0,
    *,
    t_max: float = 2e5,
    rtol: float = 1e-10,
) -> float | None:
    """Seconds until the axis of a launched top first crosses ``crossing`` degrees.

    Parameters
    ----------
    top : stability.Top
        The top, SI units.
    spin : float
        Launch spin, in ``unit`` (0.1 to 1e4 rev/s).
    unit : {"rad/s", "rev/s", "rpm", "Hz"}
    tilt : float, default 1.0
        Initial tilt of the axis, degrees (the launch state: module docstring).
    alpha_v : float, optional
        Viscous friction parameter (eq. 7) when the top has no ``mu_v``; default 0.5.
    model : {"sliding"}
    crossing : float, default 90.0
        The tilt whose first crossing is timed, degrees.
    t_max : float, default 2e5
        Longest run, units of ``1/Omega`` (one spin period is ``2 pi``).
    rtol : float, default 1e-10
        Integrator tolerance.

    Returns
    -------
    float or None
        Seconds (``t / Omega``); None if the axis does not reach ``crossing`` within ``t_max``
        (:func:`stability.launch` gives the reason).
    """
    w, params, _ = launch_parameters(top, spin, unit, alpha_v, model)
    run = run_launch(params, tilt=tilt, crossing=crossing, stop_at_crossing=True, t_max=t_max, rtol=rtol)
    return None if run.crossing_time is None else run.crossing_time / w
