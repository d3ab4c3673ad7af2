"""Stick and slip with Coulomb friction: a hybrid run of the sliding and the rolling sphere.

With the Coulomb term of eq. (6)/(7) (``alpha_k > 0``) the contact point can stop slipping in
finite time, and then stick: the sphere rolls. This is the switching model of Kane and Levinson
that the paper discusses (Sec. 1): *a switch to rolling occurs as the contact velocity vanishes;
a switch to sliding occurs when the friction required to maintain rolling exceeds mu_S N*.
:func:`stick_slip` integrates it as a hybrid run, phase by phase:

* **slip** -- the sliding model (:mod:`stability.nonlinear.sliding`, eqs. 1, 2, 4, 5) with the
  *unregularised* isotropic Coulomb-viscous law (7), ``f = -(alpha_k V_c / |V_c| + alpha_v
  V_c)`` (``slip_scale = 0``: no viscous substitute near zero slip). Terminal event: the slip
  speed ``|V_c|`` falls to ``slip_threshold`` (default 1e-10, in units of ``Omega R``). With the
  Coulomb term the slip speed reaches zero in finite time at a finite rate (about
  ``alpha_k (1/mu + ...)``), so the switch time found at the threshold lies within
  ``slip_threshold / rate`` (~1e-10) of the true zero; the event is located by scipy's event
  search on the dense output, to round-off;
* **stick** -- the rolling model (:mod:`stability.nonlinear.rolling`, ``V_c = 0``), the friction
  now the constraint force ``f`` that keeps the contact at rest. Terminal event: ``|f|``
  reaches the static limit ``alpha_s * n``, with ``n = 1`` (friction scaled by the equilibrium
  normal force, the paper's eq. 7, ``normal="equilibrium"``) or ``n = N(t) / (mu fr_inv)``
  (``normal="actual"``, Coulomb's eq. 6). ``alpha_s = mu fr_inv mu_S`` is the static
  coefficient in the units of ``alpha_k``; by default ``alpha_s = alpha_k`` (``mu_S = mu_K``).

At a slip -> stick switch the contact velocity (at most ``slip_threshold``) is set to zero
(``V0 = -K x omega``; the velocity jump is ``slip_threshold``). The stick is consistent only if
the friction that rolling needs there is within the static limit; if not, the slip passes
through zero (a ``"transit"``) and restarts. At a stick -> slip switch (or a transit) the
slip restarts in the direction ``e = -f / |f|`` opposite to the needed friction (the direction
along which the kinetic friction ``-alpha_k e`` continues the needed one), with a seed slip
``2 slip_threshold`` added to ``V0`` (an energy change of order ``mu |V_G| slip_threshold``).
Every run checks the contact: ``N > 0`` (a zero of ``N`` ends the run, ``event =
"contact_lost"``, as :func:`stability.simulate`; a start with ``N <= 0`` ends it at once,
``event_time = 0``, the run one sample long).

Only the isotropic law (eq. 7) is offered: its sticking cone is the disc ``|f| <= alpha_s n``;
the component-wise law (16) would stick in a square and is not built here.

The switches are the variables over the dimension ``switch`` of the run:
``switch_time``, ``switch_kind`` (``"stick"``, ``"slip"``, ``"transit"``), ``switch_tilt``
(degrees), ``switch_slip_speed`` (at the event: ``slip_threshold`` for a stick, 0 for a slip),
``switch_spin`` (``omega . k``) and ``switch_friction_ratio`` (``|f| / (alpha_s n)`` of the
friction rolling needs there: <= 1 at a stick, 1 at a slip); the variable ``phase`` (0 slip,
1 stick) along ``time``.

While sticking, the top is the rolling sphere: the contact point is at rest, so neither the
friction nor ``N`` does work and the energy is conserved, and Jellett's integral ``h_cg``
(eq. 10) too (paper, Sec. 3(i)). A Coulomb top that sticks and stays stuck therefore does not
settle: it rolls forever with the energy and ``J`` it had at its last stick
(:func:`stability.steady.coulomb.coulomb_end` says it in ``final_state``).
"""

from __future__ import annotations

import math
import warnings
from typing import Any

import numpy as np
import xarray as xr
from scipy.integrate import solve_ivp

from ..errors import InputError
from ..parameters import DEFAULT_MU, check_choice, check_integer, check_interval, check_positive
from . import get_nonlinear_model
from .friction import NORMAL_FORCE
from .integrators import CHATTERING, NOT_FINITE, SCIPY_METHODS, STEP_TOO_SMALL, Solution, check_tolerances
from .parameters import EPSILON, FR_INV, MU, NORMAL
from .runs import initial_state, model_parameter_vector, trajectory_dataset

__all__ = ["PHASES", "stick_slip"]

#: the phases of a hybrid run, as stored in its ``phase`` variable
PHASES = ("slip", "stick")
_SLIP, _STICK = 0, 1


def _rolling_state(y10: np.ndarray) -> np.ndarray:
    """The rolling model's state ``(omega, k, X0)`` of a sliding state (``V0`` dropped); of each
    row of an array of them."""
    return np.concatenate([y10[..., 0:6], y10[..., 8:10]], axis=-1)


def _sliding_state(y8: np.ndarray, seed: np.ndarray | None = None) -> np.ndarray:
    """The sliding model's state of a rolling state: ``V0 = -K x omega = (omega_2, -omega_1)``
    (eq. 5 with ``V_c = 0``), plus a seed slip if given; of each row of an array of them."""
    v0 = np.stack([y8[..., 1], -y8[..., 0]], axis=-1)
    if seed is not None:
        v0 = v0 + seed
    return np.concatenate([y8[..., 0:6], v0, y8[..., 6:8]], axis=-1)


def _tilt(y: np.ndarray) -> float:
    k = y[3:6]
    return math.degrees(math.acos(max(-1.0, min(1.0, float(k[2] / np.linalg.norm(k))))))


def stick_slip(
    *,
    t_end: float,
    omega: Any,
    k: Any,
    velocity: Any = None,
    q: Any,
    fr_inv: Any,
    sigma: Any,
    alpha_k: Any,
    alpha_v: Any = 0.0,
    alpha_s: Any = None,
    mu: Any = DEFAULT_MU,
    normal: str = "equilibrium",
    slip_threshold: float = 1e-10,
    method: str = "DOP853",
    rtol: float = 1e-10,
    atol: float = 1e-13,
    dt: float = 0.1,
    max_switches: int = 10_000,
) -> xr.Dataset:
    """A run of the sliding top with Coulomb friction that sticks and slips (module docstring).

    Parameters
    ----------
    t_end : float
        Final time (units of ``1/Omega``).
    omega, k, velocity : array_like
        Initial state, as :func:`stability.simulate` takes it (sliding).
    q, fr_inv, sigma, mu : float
        Parameters of the top (docs/conventions.md).
    alpha_k : float
        Kinetic Coulomb parameter of eq. (7), ``alpha_k = mu fr_inv mu_K > 0``.
    alpha_v : float, default 0
        Viscous parameter of eq. (7) (acts while slipping only).
    alpha_s : float, optional
        Static limit in the units of ``alpha_k`` (``mu fr_inv mu_S``), ``alpha_s >= alpha_k``;
        default ``alpha_k``.
    normal : {"equilibrium", "actual"}
        Friction limits scaled by the equilibrium normal force (eq. 7) or by ``N(t)`` (eq. 6).
    slip_threshold : float, default 1e-10
        Slip speed at which the slip phase ends (the switch's definition; module docstring).
    method : str, default "DOP853"
        A scipy ``solve_ivp`` method.
    rtol, atol : float
        Tolerances of every phase.
    dt : float, default 0.1
        Output interval; the switch instants are samples too (the last sample of each phase).
    max_switches : int
        A run that switches more often stops there (``attrs["status"]`` is
        :data:`~stability.nonlinear.integrators.CHATTERING`, -6); a failed phase gives scipy's
        failure as ``STEP_TOO_SMALL`` (-2) or ``NOT_FINITE`` (-3).

    Returns
    -------
    xarray.Dataset
        The run of :func:`stability.simulate` (sliding layout; ``velocity`` of O is the rolling
        one while sticking, ``friction`` the constraint force then), plus ``phase`` along
        ``time``, ``friction_limit`` (the static limit ``alpha_s n``) and the switch variables
        over ``switch`` (module docstring); attributes ``switching_model``, ``alpha_s``,
        ``slip_threshold``, ``n_switches``, ``final_phase``, ``event``, ``event_time``,
        ``status``.

    Raises
    ------
    stability.errors.InputError
        ``alpha_k <= 0`` (no Coulomb term: the slip never vanishes in finite time), ``alpha_s <
        alpha_k``, ``fr_inv = 0`` (no normal force to bound the friction), or a bad option; the
        physical domain of :func:`stability.simulate`.
    """
    top = dict(q=q, fr_inv=fr_inv, sigma=sigma, alpha_v=alpha_v, alpha_k=alpha_k, mu=mu)
    params, p_reg = model_parameter_vector("sliding", top, normal=normal)
    a_k = params["alpha_k"]
    if a_k <= 0.0:
        raise InputError(
            f"alpha_k = {a_k:g} is outside the allowed range of stick_slip: alpha_k > 0 "
            "(without the Coulomb term the slip never vanishes in finite time; use simulate)"
        )
    if params["fr_inv"] <= 0.0:
        raise InputError(
            "fr_inv = 0 is outside the allowed range of stick_slip: fr_inv > 0 (no gravity, no normal "
            "force to bound the static friction)"
        )
    # static friction is at least the kinetic one
    a_s = a_k if alpha_s is None else check_interval("alpha_s", alpha_s, a_k, math.inf, closed="left")
    t_end = check_positive("t_end", t_end)
    dt = check_positive("dt", dt)
    slip_threshold = check_interval("slip_threshold", slip_threshold, 0.0, 1e-3)
    rtol, atol = check_tolerances(rtol=rtol, atol=atol)
    max_switches = check_integer("max_switches", max_switches, minimum=1)
    method = check_choice("method", method, SCIPY_METHODS)
    sliding = get_nonlinear_model("sliding")
    rolling = get_nonlinear_model("rolling")
    # the exact law (7) while slipping: no regularisation (|V_c| >= slip_threshold > 0 there)
    p = p_reg.copy()
    p[EPSILON] = 0.0
    scaled = p[NORMAL] == NORMAL_FORCE["actual"]
    n_eq = p[MU] * p[FR_INV]

    def limit(n: float) -> float:
        return a_s * (n / n_eq if scaled else 1.0)

    def rolling_need(y8: np.ndarray) -> tuple[np.ndarray, float]:
        f = rolling.contact_forces(np.ascontiguousarray(y8[None, :]), p)[0]
        return f[:2], float(f[2])

    # every event ends its phase, on a downward crossing (solve_ivp passes p to them too)
    def ev_slip_stop(t, y, p):  # |V_c| - slip_threshold, V_c = V0 + K x omega (eq. 5)
        return math.hypot(y[6] - y[1], y[7] + y[0]) - slip_threshold

    def ev_slip_contact(t, y, p):
        return float(sliding.contact_forces(np.ascontiguousarray(y[None, :]), p)[0, 2])

    def ev_stick_break(t, y, p):
        f, n = rolling_need(y)
        return limit(n) - math.hypot(f[0], f[1])

    def ev_stick_contact(t, y, p):
        return rolling_need(y)[1]

    for ev in (ev_slip_stop, ev_slip_contact, ev_stick_break, ev_stick_contact):
        ev.terminal, ev.direction = True, -1

    def slip_along(y8: np.ndarray, f: np.ndarray) -> np.ndarray:
        """The slip restarting against the needed friction ``f``, seeded with ``2 slip_threshold``."""
        return _sliding_state(y8, -2.0 * slip_threshold * f / math.hypot(*f))

    y = initial_state("sliding", omega, k, velocity)
    grid = np.linspace(0.0, t_end, int(np.ceil(t_end / dt - 1e-9)) + 1)
    segments: list[tuple[np.ndarray, np.ndarray, int]] = []  # (times, sliding states, phase) of each phase
    switches: list[tuple] = []
    t = 0.0
    phase = _SLIP
    event, event_time, status, message = "none", math.nan, 0, "end of the time span reached"
    if ev_slip_stop(0.0, y, p) <= 0.0:  # starts without slip (|V_c| <= slip_threshold): stick if it can
        y8 = _rolling_state(y)
        f, n = rolling_need(y8)
        # rolling's N <= 0 at the start (its limit would be <= 0 with normal="actual"): no slip, the
        # sample shows rolling's forces
        if n <= 0.0 or math.hypot(*f) <= limit(n):
            phase, y = _STICK, y8
        else:
            y = slip_along(y8, f)
    n0 = ev_slip_contact(0.0, y, p) if phase == _SLIP else n
    if n0 <= 0.0:  # the events fire on a crossing only: a start without contact force is its own event
        event, event_time = "contact_lost", 0.0
        message = f"the normal force is N = {n0:.6g} <= 0 at the start (contact lost at once)"
    segments.append((np.array([0.0]), (y if phase == _SLIP else _sliding_state(y))[None, :], phase))
    while t < t_end and event == "none":
        inside = grid[(grid > t) & (grid < t_end)]
        t_eval = np.concatenate([inside, [t_end]])
        if phase == _SLIP:
            rhs, events = sliding.rhs, (ev_slip_stop, ev_slip_contact)
        else:
            rhs, events = rolling.rhs, (ev_stick_break, ev_stick_contact)
        sol = solve_ivp(rhs, (t, t_end), y, method, t_eval, events=events, rtol=rtol, atol=atol, args=(p,))
        if sol.status < 0:  # what was integrated is kept, then the loop ends (hit is empty)
            status = STEP_TOO_SMALL if "step size" in sol.message else NOT_FINITE  # as integrators.py maps scipy's
            message = f"integration failed in a {PHASES[phase]} phase at t = {sol.t[-1]:.6g}: {sol.message}"
        keep = sol.t
        out = sol.y.T
        hit = [i for i, te in enumerate(sol.t_events) if te.size] if sol.status >= 0 else []
        if hit:
            which = min(hit, key=lambda i: float(sol.t_events[i][0]))  # the earliest event
            t_ev = float(sol.t_events[which][0])
            y_ev = sol.y_events[which][0]
            sel = keep < t_ev
            keep = np.concatenate([keep[sel], [t_ev]])
            out = np.vstack([out[sel], y_ev[None, :]])
        segments.append((keep, out if phase == _SLIP else _sliding_state(out), phase))
        if not hit:
            break
        t = t_ev
        if which == 1:
            event, event_time = "contact_lost", t_ev
            message = f"the normal force reached zero at t = {t_ev:.9g} (contact lost)"
            break
        if len(switches) >= max_switches:
            status, message = CHATTERING, f"more than max_switches = {max_switches} stick/slip switches (chattering)"
            break
        # slipping: the slip reached the threshold, stick if rolling's friction is within the limit
        # (else a transit); sticking: the needed friction reached the static limit, slip along -f
        y8 = _rolling_state(y_ev) if phase == _SLIP else y_ev
        f, n = rolling_need(y8)
        ratio = math.hypot(*f) / limit(n)
        kind = "slip" if phase == _STICK else "stick" if ratio <= 1.0 else "transit"
        speed = slip_threshold if phase == _SLIP else 0.0
        switches.append((t_ev, kind, _tilt(y_ev), speed, float(y_ev[0:3] @ y_ev[3:6]), ratio))
        phase, y = (_STICK, y8) if kind == "stick" else (_SLIP, slip_along(y8, f))
    if status < 0:
        warnings.warn(f"stick_slip: {message}", RuntimeWarning, stacklevel=2)
    t_all = np.concatenate([times for times, _, _ in segments])
    y_all = np.vstack([states for _, states, _ in segments])
    ph = np.concatenate([np.full(times.size, phase, np.int8) for times, _, phase in segments])
    stuck = ph == _STICK
    # the contact forces (f_x, f_y, N): rolling's constraint force while sticking, the exact law (7)
    # while slipping (the run's p_reg is the regularised one)
    forces = np.empty((t_all.size, 3))
    if stuck.any():
        forces[stuck] = rolling.contact_forces(np.ascontiguousarray(_rolling_state(y_all[stuck])), p)
    if not stuck.all():
        forces[~stuck] = sliding.contact_forces(np.ascontiguousarray(y_all[~stuck]), p)
    ds = trajectory_dataset("sliding", Solution(t_all, y_all, 0, 0, 0, status, method), params, p_reg, forces)
    lim = a_s * ds.normal_force.values / n_eq if scaled else np.full(t_all.size, a_s)
    ds["friction"].attrs["comment"] = (
        "tangential contact force: the law (7) while slipping, the force needed to keep rolling while sticking"
    )
    phase_comment = "slip: sliding model with Coulomb friction (7); stick: rolling model (V_c = 0)"
    flags = {"flag_values": np.array([0, 1], np.int8), "flag_meanings": "slip stick", "comment": phase_comment}
    ds["phase"] = ("time", ph, {"long_name": "contact phase", **flags})
    limit_comment = "alpha_s n: the largest friction while sticking"
    ds["friction_limit"] = ("time", lim, {"long_name": "static friction limit", "units": "1", "comment": limit_comment})
    cols = list(zip(*switches)) if switches else [[]] * 6
    kinds = "stick (slip -> stick), slip (stick -> slip), transit"
    speed = {"long_name": "slip speed at the switch", "units": "Omega R", "comment": "slip_threshold at a stick"}
    switch_attrs = {  # name: (dtype, attributes), in the order of the switch tuples
        "switch_time": (float, {"long_name": "switch time", "units": "1/Omega"}),
        "switch_kind": ("<U7", {"long_name": "kind of switch", "comment": kinds}),
        "switch_tilt": (float, {"long_name": "tilt at the switch", "units": "degree"}),
        "switch_slip_speed": (float, speed),
        "switch_spin": (float, {"long_name": "spin omega . k at the switch", "units": "Omega"}),
        "switch_friction_ratio": (float, {"long_name": "needed friction / static limit at the switch", "units": "1"}),
    }
    variables = zip(switch_attrs.items(), cols)
    ds = ds.assign({name: ("switch", np.array(col, dtype), attrs) for (name, (dtype, attrs)), col in variables})
    ds.attrs["switching_model"] = (
        "hybrid (Kane and Levinson): slip phases with the unregularised law (7), stick phases with the rolling "
        "model; stick when |V_c| reaches slip_threshold and rolling's friction is within alpha_s n; slip when it "
        "reaches alpha_s n"
    )
    ds.attrs.update(alpha_s=a_s, slip_threshold=float(slip_threshold), n_switches=len(switches))
    ds.attrs.update(final_phase=PHASES[int(ph[-1])], event=event, event_time=event_time, status=status, message=message)
    ds.attrs.update(method=method, rtol=rtol, atol=atol, friction_law="isotropic", normal_force_scaling=normal)
    return ds
