"""After the contact is lost: the free flight of the top and its landing (``on_contact_loss="continue"``).

Units of :mod:`stability.nonlinear.runs` (length R, time ``1/Omega``, inertia ``A0``, mass
``mu = m R^2 / A0``); gravity is ``-fr_inv K`` per unit mass (the potential ``mu fr_inv z_G``).

Flight (closed form)
--------------------
Off the floor only gravity acts, through G. So ``G`` falls on a parabola,

    x_G(t) = x_G0 + v_G0 t - (fr_inv / 2) t^2 K,

and the angular momentum about G, ``L = I_G omega``, ``I_G = A_G 1 + (sigma - A_G) k k^T``
(``A_G = 1 - mu q^2``, :func:`stability.models.inertia.inertia_g`), is constant. For the
axisymmetric top Euler's torque-free motion is closed-form: ``L . k = sigma (omega . k)`` and
``omega = (L - (sigma - A_G) n k) / A_G`` with the spin ``n = omega . k``; then
``k' = omega x k = (L x k) / A_G`` (``k x k = 0``), so ``k`` turns rigidly about ``e = L / |L|``
at the rate ``Omega_p = |L| / A_G`` (``L . k`` and so ``n`` are constant:
``(L . k)' = L . (L x k) / A_G = 0``). Rodrigues' formula with ``phi = Omega_p t``:

    k(t) = k0 cos(phi) + (e x k0) sin(phi) + e (e . k0)(1 - cos(phi)),
    omega(t) = (L - (sigma - A_G) n k(t)) / A_G.

The sphere's centre is ``O = G - q k`` and its lowest point is at height ``h = z_O - 1``. At
the take-off ``h = 0`` with ``h' = 0`` (O moved horizontally) and ``h'' = 0`` (``N = 0``).

Landing
-------
The landing is the first zero of ``h`` after the take-off (:func:`landing_time`): ``h`` is
sampled on a grid fine against the precession (``2 pi / Omega_p / 64``) and the fall, from the
first sample where the sphere has risen, and the first sign change is refined by Brent's
method to round-off. The flight cannot last longer than ``T_max``, the positive root of
``z_G0 + |q| - 1 + v_Gz t - fr_inv t^2 / 2`` (since ``h <= z_G + |q| - 1``), which bounds the
grid.

Which runs fly
--------------
Only the sliding model with friction proportional to the normal force (``normal="actual"``,
Coulomb's proportionality, eq. 6): its friction vanishes with ``N`` at the take-off, so the
free motion starts where the constrained one ends (``h'' = 0``) and the sphere rises,
``h ~ c tau^3``. The paper's law (7) at the equilibrium normal force keeps its full traction
as ``N`` reaches 0, and so does the rolling constraint: dropping it at the take-off turns the
top into the floor at once (``h''(0+) < 0``; docs/contact.md, "Which runs", gives a measured
value); such runs refuse ``"continue"`` (:func:`stability.nonlinear.runs.simulate`).

Impact law (perfectly plastic, ``e = 0``, frictionless)
-------------------------------------------------------
At the landing an impulse ``P`` acts at the contact point C (``r = C - G = -K - q k``):
``Delta v_G = P / mu``, ``I_G Delta omega = r x P``, and C's velocity after the impact is
``v_C+ = v_C- + W P`` with the Delassus matrix ``W = 1/mu - [r]_x I_G^-1 [r]_x``
(Glocker, *Set-Valued Force Laws*, Springer 2001, ch. 7; Brogliato, *Nonsmooth Mechanics*,
3rd ed., Springer 2016, ch. 4; Pfeiffer and Glocker, *Multibody Dynamics with Unilateral
Contacts*, Wiley 1996, for the plastic Newton law ``v_C+ . K = 0``). Frictionless,
``P = Lambda K`` with ``v_C+ . K = 0``:

    Lambda = -(v_C- . K) / (1/mu + (r x K) . I_G^-1 (r x K)).

The friction impulse of the landing is neglected (the law proportional to ``N`` would give a
tangential impulse ``-(alpha_v v_C,h + alpha_k e_v) Lambda / (mu fr_inv)`` integrated through
the impact, a Darboux-Keller problem not built here). The frictionless impact conserves the
horizontal momentum, ``L_G . K``, the angular momentum about C, and Jellett's integral
``(K + q k) . L_G`` (eq. 10; ``Delta L_G = r x P`` is normal to ``r``), and dissipates the
energy ``Lambda^2 / (2 (1/mu + (r x K) . I_G^-1 (r x K)))`` (reported per landing).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np

from ..errors import InputError
from ..models.inertia import inertia_g
from .integrators import GRAZE, TOO_MANY_FLIGHTS, Solution

__all__ = [
    "IMPACT_LAWS",
    "Flight",
    "Landing",
    "body_state",
    "flight_motion",
    "floor_centre",
    "impact",
    "landing_height",
    "landing_time",
    "model_state",
]

#: the impact law of each model (the text of a run's attribute ``impact_law``)
IMPACT_LAWS = {
    "sliding": "perfectly plastic (e = 0), frictionless: a vertical impulse at the contact point",
}

_K = np.array([0.0, 0.0, 1.0])


@dataclass(frozen=True)
class Flight:
    """The free motion after a take-off (module docstring): the data of the closed form.

    Attributes
    ----------
    x_g, v_g : numpy.ndarray, shape (3,)
        Position and velocity of G at the take-off.
    k : numpy.ndarray, shape (3,)
        The axis at the take-off.
    l_g : numpy.ndarray, shape (3,)
        Angular momentum about G (constant).
    spin : float
        ``n = omega . k`` (constant).
    q, fr_inv, sigma, mu : float
    """

    x_g: np.ndarray
    v_g: np.ndarray
    k: np.ndarray
    l_g: np.ndarray
    spin: float
    q: float
    fr_inv: float
    sigma: float
    mu: float

    @property
    def a_g(self) -> float:
        """``A_G = 1 - mu q^2``."""
        return float(inertia_g(self.q, self.mu))


@dataclass(frozen=True)
class Landing:
    """One landing: its time and the impact (module docstring).

    Attributes
    ----------
    time : float
        The landing time (the run's time).
    impulse : numpy.ndarray, shape (3,)
        The impulse ``P`` at the contact point.
    contact_velocity_before, contact_velocity_after : numpy.ndarray, shape (3,)
        The contact point's velocity just before and after the impact.
    energy_loss : float
        Kinetic energy dissipated (``A0 Omega^2``), >= 0.
    """

    time: float
    impulse: np.ndarray
    contact_velocity_before: np.ndarray
    contact_velocity_after: np.ndarray
    energy_loss: float


def _inertia(k: np.ndarray, a_g: float, sigma: float) -> np.ndarray:
    return a_g * np.eye(3) + (sigma - a_g) * np.outer(k, k)


def body_state(model: str, y: np.ndarray, *, q: float, fr_inv: float, sigma: float, mu: float) -> Flight:
    """The flight that starts from the model state ``y`` (sliding: ``omega, k, V_h, X_h``;
    rolling: ``omega, k, X_h``) with O at height 1 (the take-off)."""
    w, k = np.array(y[0:3], float), np.array(y[3:6], float)
    v_o, x_o = (a[0] for a in floor_centre(model, np.asarray(y, float)[None, :]))
    a_g = float(inertia_g(q, mu))
    l_g = _inertia(k, a_g, sigma) @ w
    return Flight(x_o + q * k, v_o + q * np.cross(w, k), k, l_g, float(w @ k), q, fr_inv, sigma, mu)


def flight_motion(f: Flight, tau: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """The closed form of the module docstring at the times ``tau`` after the take-off.

    Returns
    -------
    omega, k, x_o, v_o : numpy.ndarray, shape (n, 3)
        Angular velocity, axis, position and velocity of the sphere's centre O.
    """
    tau = np.atleast_1d(np.asarray(tau, float))
    a_g = f.a_g
    norm_l = float(np.linalg.norm(f.l_g))
    if norm_l > 0.0:
        e = f.l_g / norm_l
        phi = (norm_l / a_g) * tau[:, None]
        c, s = np.cos(phi), np.sin(phi)
        k = f.k * c + np.cross(e, f.k) * s + e * (e @ f.k) * (1.0 - c)
    else:
        k = np.tile(f.k, (tau.size, 1))
    w = (f.l_g - (f.sigma - a_g) * f.spin * k) / a_g
    x_g = f.x_g + f.v_g * tau[:, None] - 0.5 * f.fr_inv * tau[:, None] ** 2 * _K
    v_g = f.v_g - f.fr_inv * tau[:, None] * _K
    x_o = x_g - f.q * k
    v_o = v_g - f.q * np.cross(w, k)
    return w, k, x_o, v_o


def landing_height(f: Flight, tau: np.ndarray) -> np.ndarray:
    """Height of the sphere's lowest point above the floor, ``z_O - 1``, at the times ``tau``."""
    _, _, x_o, _ = flight_motion(f, tau)
    return x_o[:, 2] - 1.0


def landing_time(f: Flight) -> float:
    """The duration of the flight: the first zero of :func:`landing_height` after the take-off
    (module docstring), to round-off in time; 0 if the sphere does not rise (a graze). Needs
    ``fr_inv > 0`` (else InputError: without gravity the flight has no end)."""
    if not f.fr_inv > 0.0:
        raise InputError(
            f"fr_inv = {f.fr_inv!r} is outside the allowed range of landing_time: fr_inv > 0 (without gravity "
            "the top never lands)"
        )
    c0, vz = f.x_g[2] + abs(f.q) - 1.0, f.v_g[2]
    t_max = (vz + np.sqrt(vz * vz + 2.0 * f.fr_inv * max(c0, 0.0))) / f.fr_inv  # T_max (module docstring)
    if not t_max > 0.0:  # h <= z_G + |q| - 1 <= 0 from the take-off on: no rise (a graze)
        return 0.0
    rate = float(np.linalg.norm(f.l_g)) / f.a_g  # Omega_p = |L_G| / A_G, the rate at which k turns about L_G
    dt = t_max / 256.0
    if rate > 0.0:
        dt = min(dt, 2.0 * np.pi / rate / 64.0)
    n = int(np.ceil(t_max / dt)) + 1
    grid = np.linspace(0.0, t_max * (1.0 + 1e-12), n + 1)
    # the sphere rises (h > 0) before it can land: near the take-off h ~ c tau^3 with c > 0 (N
    # falls through 0 and the friction, proportional to N, with it); a first sample not above
    # zero is resolved on a finer grid towards the take-off
    first = grid[1]
    for _ in range(40):
        if landing_height(f, np.array([first]))[0] > 0.0:
            break
        first *= 0.125
    else:
        return 0.0  # no rise to round-off: the top stays on the floor (a graze)
    pts = grid[grid > first]
    if first < grid[1]:
        pts = np.concatenate([np.geomspace(first, grid[1], 64)[:-1], pts])
    else:
        pts = np.concatenate([[first], pts])
    h = landing_height(f, pts)
    j = int(np.nonzero(h <= 0.0)[0][0])  # h(T_max) < 0: there is one, and h(pts[0]) > 0
    from scipy.optimize import brentq  # here: scipy.optimize costs ~0.5 s of imports a run on the floor does not need

    return float(brentq(lambda t: landing_height(f, np.array([t]))[0], pts[j - 1], pts[j], xtol=1e-300, rtol=_RTOL))


#: Brent's relative tolerance: scipy's smallest, 4 machine epsilons
_RTOL = 4.0 * np.finfo(float).eps


def impact(f: Flight, tau: float) -> tuple[np.ndarray, np.ndarray, np.ndarray, Landing]:
    """The plastic impact at the landing ``tau`` after the take-off (module docstring).

    Returns
    -------
    omega, k, v_o : numpy.ndarray, shape (3,)
        The state just after the impact (``k`` unchanged; ``v_o`` the centre's velocity, with
        ``v_o . K = 0`` to round-off).
    landing : Landing
        The impulse, the contact point's velocity before and after, the energy dissipated
        (``time`` is ``tau``; the caller shifts it to the run's time).
    """
    w, k, _, v_o = (a[0] for a in flight_motion(f, np.array([tau])))
    a_g = f.a_g
    i_g = _inertia(k, a_g, f.sigma)
    r = -_K - f.q * k
    v_g = v_o + f.q * np.cross(w, k)
    v_c = v_g + np.cross(w, r)
    rk = np.cross(r, _K)
    lam = -v_c[2] / (1.0 / f.mu + rk @ np.linalg.solve(i_g, rk))
    p_imp = lam * _K
    v_g_new = v_g + p_imp / f.mu
    w_new = w + np.linalg.solve(i_g, np.cross(r, p_imp))
    v_c_new = v_g_new + np.cross(w_new, r)

    def kinetic(vg: np.ndarray, om: np.ndarray) -> float:
        return 0.5 * f.mu * float(vg @ vg) + 0.5 * float(om @ i_g @ om)

    loss = kinetic(v_g, w) - kinetic(v_g_new, w_new)
    v_o_new = v_g_new - f.q * np.cross(w_new, k)
    return w_new, k, v_o_new, Landing(float(tau), p_imp, v_c, v_c_new, float(loss))


def model_state(model: str, omega: np.ndarray, k: np.ndarray, v_o: np.ndarray, x_o: np.ndarray) -> np.ndarray:
    """The model's state vectors on the floor (O at height 1), one per row of the arguments (or
    one of vectors): sliding ``omega, k, V_h, X_h``, rolling ``omega, k, X_h``."""
    horizontal = (v_o[..., :2], x_o[..., :2]) if model == "sliding" else (x_o[..., :2],)
    return np.concatenate([omega, k, *horizontal], axis=-1)


#: flights at most in one run (a top that bounces ever more often, a Zeno sequence, stops there)
MAX_FLIGHTS = 1000


@dataclass(frozen=True)
class HybridRun(Solution):
    """A run through contact phases, flights and landings (:func:`run_with_flights`): the fields
    of a :class:`~stability.nonlinear.integrators.Solution`, and the phases.

    ``y`` holds the model states on the floor; in flight the model's layout filled from the free
    motion (the horizontal part of O's velocity and position). ``status`` is 0, an integrator's
    failure code, or :data:`~stability.nonlinear.integrators.TOO_MANY_FLIGHTS` (more than
    :data:`MAX_FLIGHTS`) or :data:`~stability.nonlinear.integrators.GRAZE` (a take-off without
    rise), which stop the run there (its ``message``:
    :data:`~stability.nonlinear.integrators.STATUS_MESSAGES`). ``event`` is ``"stick_contact"``
    if the run ended at the stick, else ``"contact_lost"`` if it took off at least once, else
    ``"none"``; ``event_time`` the time of that event (the first take-off), NaN for none.

    Attributes
    ----------
    v_o, x_o : numpy.ndarray, shape (m, 3)
        Velocity and position of the sphere's centre O.
    contact : numpy.ndarray of int8, shape (m,)
        1 on the floor, 0 in flight.
    takeoffs : list of float
    landings : list of Landing
    """

    v_o: np.ndarray = field(default_factory=lambda: np.empty((0, 3)))
    x_o: np.ndarray = field(default_factory=lambda: np.empty((0, 3)))
    contact: np.ndarray = field(default_factory=lambda: np.empty(0, np.int8))
    takeoffs: list = field(default_factory=list)
    landings: list = field(default_factory=list)
    #: where and why a flight's status stopped the run (a graze's time, the flights' limit)
    detail: str = ""

    @property
    def message(self) -> str:
        """Text of the status code, with where the run stopped for a flight's status."""
        return self.detail or super().message


def floor_centre(model: str, y: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Velocity and position of O, shape (n, 3) each, from the model states ``y`` (n rows) on the
    floor (O at height 1): sliding ``V_h, X_h`` from the state; rolling ``V0 = (omega_2, -omega_1,
    0)`` (eq. 5, ``V_c = 0``)."""
    n = y.shape[0]
    if model == "sliding":
        return np.column_stack([y[:, 6], y[:, 7], np.zeros(n)]), np.column_stack([y[:, 8], y[:, 9], np.ones(n)])
    return np.column_stack([y[:, 1], -y[:, 0], np.zeros(n)]), np.column_stack([y[:, 6], y[:, 7], np.ones(n)])


def run_with_flights(
    integrate: Callable[..., Solution],
    model: str,
    y0: np.ndarray,
    t_eval: np.ndarray,
    p: np.ndarray,
    params: dict[str, float],
    **kw: Any,
) -> HybridRun:
    """Integrate on the floor until the contact is lost, fly (closed form) to the landing, apply
    the impact (module docstring) and go on with the same model, up to ``t_eval[-1]``.

    ``integrate`` is :func:`stability.nonlinear.integrators.integrate` (passed in, with its
    keywords ``kw``, ``watch_contact`` on); ``params`` holds ``q, fr_inv, sigma, mu`` (floats).
    Samples: the requested times, plus each take-off
    (the state where ``N = 0``) and each landing (the state just after the impact).
    """
    q, fr, sg, mu = params["q"], params["fr_inv"], params["sigma"], params["mu"]
    ts, ys, vs, xs, cs = [], [], [], [], []
    takeoffs: list = []
    landings: list = []
    nfev = naccept = nreject = 0
    event, event_time, detail = "none", float("nan"), ""
    y, seg = np.asarray(y0, float), np.asarray(t_eval, float)
    while True:
        sol = integrate(model, y, seg, p, watch_contact=True, **kw)
        nfev, naccept, nreject = nfev + sol.nfev, naccept + sol.naccept, nreject + sol.nreject
        v_o, x_o = floor_centre(model, sol.y)
        on = np.ones(sol.t.size, np.int8)
        if sol.event == "contact_lost" and sol.t.size == 1:
            on[0] = 0  # landed and left again at once (N < 0 just after the impact): no contact force
        ts.append(sol.t), ys.append(sol.y), vs.append(v_o), xs.append(x_o), cs.append(on)
        status = sol.status
        if sol.status != 0 or sol.event != "contact_lost":
            if sol.event == "stick_contact":
                event, event_time = sol.event, sol.event_time
            break
        if len(takeoffs) >= MAX_FLIGHTS:
            status = TOO_MANY_FLIGHTS
            detail = f"more than {MAX_FLIGHTS} flights: the top bounces ever more often (stopped there)"
            break
        t0 = sol.event_time
        takeoffs.append(t0)
        if event == "none":
            event, event_time = "contact_lost", t0
        f = body_state(model, sol.y[-1], q=q, fr_inv=fr, sigma=sg, mu=mu)
        tau = landing_time(f)
        if tau == 0.0:  # N = 0 but no rise: the floor model cannot go on (N <= 0) and no flight starts
            status = GRAZE  # at t0, the last take-off
            detail = (
                f"at t = {t0:.9g} the normal force reached zero but the sphere does not rise (a graze): "
                "neither the floor model nor the flight holds there (stopped)"
            )
            break
        t_land = t0 + tau
        inside = t_eval[(t_eval > t0) & ((t_eval < t_land) | (t_land >= t_eval[-1]))]
        if inside.size:
            w, k, x_o, v_o = flight_motion(f, inside - t0)
            ts.append(inside), vs.append(v_o), xs.append(x_o), cs.append(np.zeros(inside.size, np.int8))
            ys.append(model_state(model, w, k, v_o, x_o))
        if t_land >= t_eval[-1]:
            break  # still in the air at the end
        w, k, v_o, landing = impact(f, tau)
        x_o = flight_motion(f, np.array([tau]))[2][0]
        landings.append(replace(landing, time=t_land))
        y = model_state(model, w, k, v_o, x_o)
        seg = np.concatenate([[t_land], t_eval[t_eval > t_land]])
    t, y = np.concatenate(ts), np.vstack(ys)
    work = (nfev, naccept, nreject, status, sol.method, event_time, event)
    return HybridRun(t, y, *work, np.vstack(vs), np.vstack(xs), np.concatenate(cs), takeoffs, landings, detail)
