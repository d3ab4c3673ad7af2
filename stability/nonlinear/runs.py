"""Nonlinear runs of the Tippe top: :func:`simulate` returns an xarray Dataset.

Models (:mod:`stability.nonlinear`): ``"sliding"`` (eqs. 1, 2, 4 with the contact constraint
and the friction law 7 or 16), ``"rolling"`` (``V_c = 0``, eq. 5) and ``"fixed_pivot"``.
Units: length R, time ``1/Omega`` (one spin period is ``2 pi``), energy ``A0 Omega^2``;
components in the fixed frame ``F_a`` (``K`` up).

Integrator choice (``method="auto"``): the compiled Dormand-Prince 5(4) unless the sliding
model is stiff, when scipy's ``LSODA`` (switching to BDF when stiffness is detected) is used:
the fast slip mode decays at about ``alpha_v A_C / (mu A_G)``, above :data:`STIFF_RATE`; and
with Coulomb friction (``alpha_k > 0``) the regularised law acts at sticking as a viscous one of
coefficient ``alpha_k / slip_scale``; see
``benchmarks/work_precision.py`` and docs/nonlinear.md for where explicit methods fail.
"""

from __future__ import annotations

import warnings
from collections.abc import Callable, Iterator, Mapping
from typing import Any

import numpy as np
import xarray as xr

from .._version import package_version
from ..errors import InputError, ParameterTypeError
from ..execution import pick
from ..interrupts import deferred
from ..models.inertia import inertia_contact, inertia_g
from ..parameters import (
    COMPUTABLE_MAX,
    DEFAULT_MU,
    LONG_NAMES,
    as_parameter,
    check_choice,
    check_domain,
    check_integer,
    check_interval,
    check_positive,
)
from ..products import PRODUCT_ATTR
from ..resources import check_memory, memory_limit, simulate_bytes
from . import get_nonlinear_model
from .contact import ON_CONTACT_LOSS
from .flight import IMPACT_LAWS, HybridRun, floor_centre, run_with_flights
from .friction import DEFAULT_SLIP_SCALE, FRICTION_LAWS, NORMAL_FORCE
from .integrators import COMPILED_METHODS, SCIPY_METHODS, check_tolerances, integrate
from .parameters import pack
from .quantities import energy_parts, h_cg

__all__ = ["STIFF_RATE", "auto_method", "check_run_memory", "initial_state", "model_parameter_vector", "simulate"]

#: decay rate of the fast slip mode above which "auto" picks LSODA: where the measured costs of
#: the compiled dopri5 (held to steps ~3.3 / rate by stability) and of LSODA cross, below which
#: dopri5 is also the more accurate (docs/performance.md, the integrators' stiff panel;
#: ``python benchmarks/run.py --suite integrators``)
STIFF_RATE: float = 400.0

_ONE = "1"
#: the component types of a state vector that take the fast path of :func:`_vector`
_PLAIN_COMPONENT = (float, int, np.float64)


def _vector(name: str, value: Any, n: tuple[int, ...]) -> np.ndarray:
    # fast paths (a state vector is checked on every final_state / simulate call; the general
    # path costs ~15 us): a tuple or list of plain numbers, or a 1-D float64 array, that passes
    # every test below (NaN fails the range) and comes out as the same doubles
    if (
        type(value) in (tuple, list)
        and len(value) in n
        and all(type(x) in _PLAIN_COMPONENT and -COMPUTABLE_MAX <= x <= COMPUTABLE_MAX for x in value)
    ):
        return np.array(value, dtype=float)
    if type(value) is np.ndarray and value.dtype == np.float64 and value.ndim == 1 and value.size in n:
        arr = value.copy()
        if all(-COMPUTABLE_MAX <= x <= COMPUTABLE_MAX for x in arr.tolist()):
            return arr
    sizes = " or ".join(map(str, n))
    arr = as_parameter(name, value)  # type, emptiness and finiteness, with the standard messages
    if arr.ndim != 1 or arr.size not in n:
        raise InputError(
            f"{name} = {value!r:.60} has shape {arr.shape}; {name} must be a vector of "
            f"{sizes} components (fixed frame I, J, K)"
        )
    if np.max(np.abs(arr)) > COMPUTABLE_MAX:
        raise InputError(
            f"{name} = {value!r:.60} is outside the computable range: every |component| <= {COMPUTABLE_MAX:g}"
        )
    return arr


def model_parameter_vector(
    model: str,
    top: Mapping[str, Any],
    *,
    friction: str = "isotropic",
    normal: str = "equilibrium",
    slip_scale: float = DEFAULT_SLIP_SCALE,
) -> tuple[dict[str, float], np.ndarray]:
    """Check the physical parameters of a nonlinear model and pack them for the kernels.

    Parameters
    ----------
    model : str
    top : mapping
        ``q``, ``fr_inv``, ``sigma`` and optionally ``mu`` (default :data:`DEFAULT_MU`),
        ``alpha_v`` (required for ``"sliding"``, refused otherwise) and ``alpha_k`` (default 0;
        nonzero refused but for ``"sliding"``), as :func:`simulate` takes them.
    friction, normal, slip_scale
        As :func:`simulate` takes them.

    Returns
    -------
    params : dict of float
        The checked parameters the model takes.
    p : numpy.ndarray
        Parameter vector (:func:`stability.nonlinear.parameters.pack`).

    Raises
    ------
    TypeError
        A missing or non-real parameter, or one the model does not take.
    ValueError
        A value outside the physical domain or an unknown option.
    """
    m = get_nonlinear_model(model)
    given = {"mu": DEFAULT_MU, "alpha_k": 0.0, **top}
    alpha_v, alpha_k = given.pop("alpha_v", None), given.pop("alpha_k")
    if m.name == "sliding":
        if alpha_v is None:
            raise ParameterTypeError("alpha_v is required for model 'sliding' (alpha_v >= 0)")
        given.update(alpha_v=alpha_v, alpha_k=alpha_k)
    else:
        if alpha_v is not None:
            raise ParameterTypeError(f"model {m.name!r} takes no parameter alpha_v (no friction law)")
        if alpha_k is not None and np.any(as_parameter("alpha_k", alpha_k) != 0):
            raise ParameterTypeError(f"model {m.name!r} takes no parameter alpha_k (no friction law)")
    p, _ = check_domain(scalar=True, **given)
    params = {name: float(v) for name, v in p.items()}
    check_choice("friction", friction, FRICTION_LAWS)
    check_choice("normal", normal, NORMAL_FORCE)
    if normal == "actual" and params["fr_inv"] == 0.0:
        raise InputError(
            "normal = 'actual' needs fr_inv > 0 (friction proportional to N(t) / (mu fr_inv)); got fr_inv = 0"
        )
    slip_scale = check_positive("slip_scale", slip_scale)
    return params, pack(**params, epsilon=float(slip_scale), law=FRICTION_LAWS[friction], normal=NORMAL_FORCE[normal])


def initial_state(model: str, omega: Any, k: Any, velocity: Any = None, position: Any = None) -> np.ndarray:
    """Initial state vector of a model from ``omega``, ``k`` and (sliding) the centre velocity.

    ``k`` is normalised (the paper's printed initial conditions have ``|k|`` off 1 in the
    fifth digit); a ``k`` further than 1 % from unit length is refused. The centre velocity of
    the sliding model defaults to zero; it must be horizontal (the centre stays at height R).
    The rolling and fixed-pivot models determine the velocity and refuse one.
    """
    m = get_nonlinear_model(model)
    w = _vector("omega", omega, (3,))
    kv = _vector("k", k, (3,))
    nk = float(np.linalg.norm(kv))
    if abs(nk - 1.0) > 1e-2:
        raise InputError(f"k = {k!r} has length {nk:.6g}; k is the unit symmetry axis (|k| must be within 1 % of 1)")
    kv = kv / nk
    parts = [w, kv]
    if m.name == "sliding":
        v = np.zeros(2) if velocity is None else _vector("velocity", velocity, (2, 3))
        if v.size == 3:
            if abs(v[2]) > 1e-12:
                raise InputError(
                    f"velocity = {velocity!r}: the vertical component must be 0 (the centre stays at height R)"
                )
            v = v[:2]
        parts.append(v)
    elif velocity is not None:
        raise InputError(
            f"velocity = {velocity!r}: model {m.name!r} determines the centre's velocity from the rotation; give none"
        )
    if m.has_translation:
        parts.append(np.zeros(2) if position is None else _vector("position", position, (2,)))
    return np.concatenate(parts)


def auto_method(model: str, params: dict[str, float]) -> str:
    """``"LSODA"`` when the sliding top's slip mode decays faster than :data:`STIFF_RATE`
    (rate ``alpha_v A_C / (mu A_G)``, ``A_C = 1 + mu (1 + 2 q)``, ``A_G = 1 - mu q^2``), or
    with Coulomb friction (stiff at sticking); otherwise the compiled ``"dopri5"``."""
    if model != "sliding":
        return "dopri5"
    mu, q = params["mu"], params["q"]
    a_g = inertia_g(q, mu)
    rate = params["alpha_v"] * inertia_contact(q, mu, a_g) / (mu * a_g)
    return "LSODA" if (rate > STIFF_RATE or params["alpha_k"] > 0) else "dopri5"


def check_run_memory(model: str, n_times: int, *, t_end: float, dt: float | None) -> None:
    """Refuse a run whose ``n_times`` output times cannot fit in memory
    (:func:`stability.resources.check_memory`), suggesting a ``dt`` that fits."""
    need = simulate_bytes(model, n_times)
    limit, _ = memory_limit()
    if need <= limit:
        return
    per = need / n_times
    fit = max(1, int(limit // per) - 1)
    if dt is not None:
        what = f"simulate: {n_times} output times (t_end / dt = {t_end:.6g} / {dt:.6g})"
        parameter = "t_end / dt"
        suggestion = float(f"{t_end / fit:.2g}")
        while t_end / suggestion + 1 > fit:
            suggestion *= 1.25
        way_out = (
            f"give a larger dt (dt = {suggestion:.2g} gives {int(np.ceil(t_end / suggestion)) + 1} output "
            "times), or a shorter t_end and continue from the run's last state"
        )
    else:
        what = f"simulate: {n_times} output times (t_eval)"
        parameter = "the length of t_eval"
        way_out = f"give fewer t_eval points (at most about {fit}), or a shorter t_end"
    check_memory(need, what=what, parameter=parameter, way_out=way_out)


def _progress(
    how: bool | Callable[[float], None], t_end: float
) -> tuple[Callable[[float], None] | None, Callable[[], None]]:
    """``(report(t), close())``: a tqdm bar over the time (True), the caller's function, or nothing."""
    if callable(how):
        return how, lambda: None
    if not how:
        return None, lambda: None
    from tqdm import tqdm

    form = "{desc}: {percentage:3.0f}%|{bar}| t = {n:.4g} of {total:.4g} [{elapsed}<{remaining}]"
    bar = tqdm(total=t_end, unit="t", desc="simulate", leave=False, delay=1.0, bar_format=form)

    def report(t: float) -> None:
        bar.update(max(0.0, min(t_end, float(t)) - bar.n))

    return report, bar.close


def _attrs(long_name: str, units: str = _ONE, **extra: str) -> dict[str, str]:
    return {"long_name": long_name, "units": units, **extra}


def simulate(
    model: str,
    *,
    t_end: float,
    omega: Any,
    k: Any,
    velocity: Any = None,
    q: Any,
    fr_inv: Any,
    sigma: Any,
    alpha_v: Any = None,
    alpha_k: Any = 0.0,
    mu: Any = DEFAULT_MU,
    friction: str = "isotropic",
    normal: str = "equilibrium",
    slip_scale: float = DEFAULT_SLIP_SCALE,
    method: str = "auto",
    rtol: float = 1e-9,
    atol: float = 1e-12,
    dt: float = 0.1,
    t_eval: Any = None,
    step: float | None = None,
    max_steps: int = 50_000_000,
    progress: bool | Callable[[float], None] = False,
    on_contact_loss: str = "stop",
    stick_tilt: float | None = None,
) -> xr.Dataset:
    """Integrate a nonlinear model of the top from a given state.

    Parameters
    ----------
    model : {"sliding", "rolling", "fixed_pivot"}
        Sliding sphere (eqs. 1, 2, 4, 5, 7), rolling sphere (``V_c = 0``) or heavy top on a
        fixed pivot at the sphere's bottom point.
    t_end : float
        Final time, in units of ``1/Omega`` (one spin period is ``2 pi``).
    omega, k : array_like, shape (3,)
        Initial angular velocity and symmetry axis (fixed frame; ``k`` is normalised).
    velocity : array_like, shape (2,) or (3,), optional
        Initial velocity of the sphere's centre O (sliding only; default zero).
    q, fr_inv, sigma, alpha_v, alpha_k, mu : float
        Parameters (docs/conventions.md); ``alpha_v`` (required) and ``alpha_k`` for
        ``"sliding"`` only.
    friction : {"isotropic", "componentwise"}
        Coulomb term along the slip (eq. 7, default) or per component (eq. 16).
    normal : {"equilibrium", "actual"}
        Friction proportional to the equilibrium normal force (the paper's law, default) or to
        ``N(t)``.
    slip_scale : float, default 1e-4
        Regularisation scale of the Coulomb term (:mod:`stability.nonlinear.friction`).
    method : str, default "auto"
        ``"dopri5"`` (compiled Dormand-Prince 5(4)), ``"rk4"`` (fixed step ``step``), or a
        scipy method (``"RK45"``, ``"DOP853"``, ``"Radau"``, ``"BDF"``, ``"LSODA"``);
        ``"auto"`` picks ``dopri5`` or, when stiff (large ``alpha_v``, or ``alpha_k > 0``),
        ``LSODA``.
    rtol, atol : float
        Integrator tolerances.
    dt : float, default 0.1
        Output interval (ignored if ``t_eval`` is given).
    t_eval : array_like, optional
        Output times, increasing, from 0 to ``t_end``.
    step : float, optional
        Step of ``"rk4"``; first step of the adaptive methods.
    max_steps : int
        Step limit of every method (the compiled ``"dopri5"`` and scipy's, which are stepped
        one by one for this): a run that hits it stops with a warning and ``status = -1``
        instead of running for hours (stiff friction with an explicit method).
    progress : bool or callable, default False
        A progress bar on stderr (True; shown once the run has taken a second), or
        ``progress(t)`` with the time reached, every few milliseconds of integration; silent by
        default.
    on_contact_loss : {"stop", "continue"}, default "stop"
        ``"stop"``: the sliding and rolling runs end at the first zero of the normal force
        (:mod:`stability.nonlinear.contact`): the last sample is the event, ``attrs["event"]``
        is ``"contact_lost"`` and ``attrs["event_time"]`` its time (``"none"`` and NaN when the
        contact holds to ``t_end``). ``"continue"`` (sliding model with ``normal="actual"``
        only): the top flies (closed form), lands with a plastic frictionless impact and goes
        on on the floor (:mod:`stability.nonlinear.flight`); ``event_time`` is the first
        take-off, the variables ``contact`` and ``height`` and the attributes
        ``takeoff_times``, ``landing_times`` and ``impact_*`` record the phases.
        Not watched at ``fr_inv = 0`` (no gravity: ``N`` is 0 at equilibrium and its sign says
        nothing) nor for the fixed pivot: ``attrs["contact_watched"] = 0``.
    stick_tilt : float, optional
        The tilt (degrees, in (0, 180)) at which the top's stick touches the floor
        (:meth:`stability.Top.stick_contact`): the run stops where the tilt first reaches it,
        ``attrs["event"] = "stick_contact"`` (sliding and rolling).

    Returns
    -------
    xarray.Dataset
        Along ``time``: ``omega``, ``k`` (and ``velocity``, ``position``, ``momentum`` of the
        centre for sliding and rolling) on an ``axis`` dimension, ``polar_angle`` (degrees),
        ``spin`` (``omega . k``), ``transverse_rate`` (``|omega_1 + i omega_2|``), the energy
        and its parts, ``h_cg`` (eq. 10; sliding and rolling), ``slip_speed``, ``friction``,
        ``friction_magnitude`` and ``normal_force``; CF attributes. A failed integration
        leaves NaN after the failure, ``attrs["status"] < 0`` and a ``RuntimeWarning``.

    Raises
    ------
    TypeError, ValueError
        For bad input; the message names the parameter, its value and the allowed range.
    stability.errors.ResourceError
        The output times would need more memory than is available (about
        :data:`stability.resources.SIMULATE_BYTES_PER_TIME` bytes each); the message suggests a
        ``dt``.

    Notes
    -----
    The run is interruptible: Ctrl-C (SIGINT) is acted on between slices of the compiled
    integration (milliseconds apart) and raises ``KeyboardInterrupt`` there
    (:mod:`stability.interrupts`).

    Examples
    --------
    >>> import stability
    >>> ds = stability.simulate("sliding", t_end=10.0, omega=[0.02, 0.0, 1.0], k=[0.05, 0.0, 1.0],
    ...                         q=-0.1, fr_inv=0.3, sigma=1.0, alpha_v=0.5)
    >>> float(ds.polar_angle[0]) > 0
    True
    """
    m = get_nonlinear_model(model)
    top = dict(q=q, fr_inv=fr_inv, sigma=sigma, alpha_v=alpha_v, alpha_k=alpha_k, mu=mu)
    params, p = model_parameter_vector(m.name, top, friction=friction, normal=normal, slip_scale=slip_scale)
    t_end = check_positive("t_end", t_end)
    rtol, atol = check_tolerances(rtol=rtol, atol=atol)
    max_steps = check_integer("max_steps", max_steps, minimum=1)
    if step is not None:
        step = check_positive("step", step)
    if t_eval is None:
        dt = check_positive("dt", dt)
        n = int(np.ceil(t_end / dt - 1e-9))
        if n > 10**8:
            raise InputError(
                f"dt = {dt:.6g} gives {n} output times up to t_end = {t_end:.6g}; "
                "the allowed range is t_end / dt <= 1e8"
            )
        check_run_memory(m.name, n + 1, t_end=t_end, dt=dt)
        t_eval = np.linspace(0.0, float(t_end), n + 1)
    else:
        t_eval = as_parameter("t_eval", t_eval)
        not_1d = t_eval.ndim != 1 or t_eval.size < 2 or t_eval[0] != 0.0
        if not_1d or np.any(np.diff(t_eval) <= 0) or not np.isclose(t_eval[-1], t_end):
            raise InputError(f"t_eval = {t_eval!r:.60} must increase strictly from 0 to t_end = {t_end:.6g}")
        check_run_memory(m.name, t_eval.size, t_end=t_end, dt=None)
    method = check_choice("method", method, ("auto",) + tuple(COMPILED_METHODS) + tuple(SCIPY_METHODS))
    if method == "auto":
        method = auto_method(m.name, params)
    check_choice("on_contact_loss", on_contact_loss, ON_CONTACT_LOSS)
    if on_contact_loss == "continue" and stick_tilt is not None:
        raise InputError(
            f"stick_tilt = {stick_tilt!r} with on_contact_loss = 'continue': the stick is not watched in "
            "flight (not built); give one of them"
        )
    if on_contact_loss == "continue" and (m.name != "sliding" or normal != "actual"):
        why = {
            "fixed_pivot": "model 'fixed_pivot': it has no floor to leave",
            "rolling": "model 'rolling': its contact force does not vanish with N (the rolling constraint needs a "
            "traction as N reaches 0), so the top cannot leave the floor smoothly",
        }.get(
            m.name,
            "normal = 'equilibrium': the paper's friction law keeps its full force as N reaches 0, so a "
            "free top would turn into the floor at once",
        )
        raise InputError(
            f"on_contact_loss = 'continue' is not available for {why}; use model = 'sliding' with "
            "normal = 'actual' (friction proportional to N, zero at the take-off), or on_contact_loss = 'stop'"
        )
    if stick_tilt is not None:
        stick_tilt = check_interval("stick_tilt", stick_tilt, 0.0, 180.0)
        if not m.has_translation:
            raise InputError(f"stick_tilt = {stick_tilt:g}: model {m.name!r} has no floor for a stick to touch")
    y0 = initial_state(m.name, omega, k, velocity)
    report, close = _progress(progress, float(t_end))
    # fr_inv = 0 (no gravity, the paper's high-spin limit) has N = 0 at equilibrium: the sign of N
    # says nothing there, the contact is the model's assumption; not watched (attrs say so)
    watched = m.has_translation and params["fr_inv"] > 0.0
    try:
        with deferred():
            options = dict(method=method, rtol=rtol, atol=atol, step=step, max_steps=max_steps)
            options.update(progress=report, stick_tilt=stick_tilt)
            if on_contact_loss == "continue" and watched:  # a HybridRun: the fields of a Solution, and more
                sol = run_with_flights(integrate, m.name, y0, t_eval, p, params, **options)
            else:
                sol = integrate(m.name, y0, t_eval, p, watch_contact=watched, **options)
    finally:
        close()
    if sol.status < 0:
        warnings.warn(f"simulate({m.name!r}): integration stopped: {sol.message}", RuntimeWarning, stacklevel=2)
    ds = trajectory_dataset(m.name, sol, params, p)
    ds.attrs.update(event=sol.event, event_time=sol.event_time, on_contact_loss=on_contact_loss)
    ds.attrs.update(contact_watched=int(watched), stick_tilt=float("nan") if stick_tilt is None else stick_tilt)
    ds.attrs.update(method=method, rtol=rtol, atol=atol, nfev=sol.nfev, naccept=sol.naccept, nreject=sol.nreject)
    ds.attrs.update(status=sol.status, message=sol.message)
    friction_law = friction if m.name == "sliding" else "none (constraint force)"
    ds.attrs.update(friction_law=friction_law, normal_force_scaling=normal, slip_scale=float(slip_scale))
    return ds


def trajectory_dataset(model: str, run: Any, params: dict[str, float], p: np.ndarray, forces: Any = None) -> xr.Dataset:
    """Build the output Dataset of :func:`simulate` from a run (its times ``run.t`` and states
    ``run.y``), the contact forces computed from the states unless given (``forces``, shape (n, 3)).

    A run with flights (``on_contact_loss="continue"``, a
    :class:`~stability.nonlinear.flight.HybridRun` of
    :func:`~stability.nonlinear.flight.run_with_flights`) gives O's velocity and position and
    ``contact`` (1 on the floor, 0 in flight): in flight the contact forces are 0 and O's height
    and vertical velocity are the free motion's. Its Dataset also has the variables ``contact``
    and ``height`` (of the sphere's lowest point), and the phases in the attributes
    (``takeoff_times``, ``landing_times``, and per landing the vertical impulse, the contact
    point's velocity before and after, the energy dissipated).
    """
    t, y = run.t, run.y
    flights = run if isinstance(run, HybridRun) else None
    contact = None if flights is None else flights.contact
    m = get_nonlinear_model(model)
    q, sigma, mu = params["q"], params["sigma"], params["mu"]
    omega = y[:, 0:3]
    k = y[:, 3:6]
    n = t.size
    if forces is None:
        good = np.isfinite(y).all(axis=1) & (True if contact is None else contact == 1)
        forces = np.full((n, 3), np.nan)
        if good.any():
            forces[good] = pick(m.contact_forces, int(good.sum()))(np.ascontiguousarray(y[good]), p)  # by size
        if contact is not None:
            forces[contact == 0] = 0.0  # in flight: no contact force
    comp = {"long_name": "component", "comment": "component along I, J, K of the fixed frame F_a (K up)"}
    # no CF standard_name "time": CF requires it to carry units of time ("s since ..."), and
    # this time is dimensionless (units of 1/Omega); axis = "T" still marks it as the time axis
    time = _attrs("time", "1/Omega", axis="T", comment="in units of 1/Omega; one spin period is 2 pi")
    coords = {"time": ("time", t, time), "axis": ("axis", np.array([1, 2, 3]), comp)}
    data: dict[str, tuple] = {}

    def put(name: str, values: np.ndarray, long_name: str, units: str, comment: str) -> None:
        dims = ("time", "axis") if values.ndim == 2 else "time"
        data[name] = (dims, values, _attrs(long_name, units, comment=comment))

    put("omega", omega, "angular velocity", "Omega", "in units of the spin rate Omega")
    put("k", k, "symmetry axis k", _ONE, "unit vector along the symmetry axis")
    wk = np.einsum("ij,ij->i", omega, k)
    kn = np.linalg.norm(k, axis=1)
    with np.errstate(invalid="ignore"):
        polar = np.degrees(np.arccos(np.clip(k[:, 2] / kn, -1.0, 1.0)))
    put("polar_angle", polar, "polar angle of k", "degree", "angle of k from the upward vertical K")
    put("spin", wk, "spin", "Omega", "omega . k, in units of the spin rate Omega")
    transverse = np.hypot(omega[:, 0], omega[:, 1])
    what = "transverse angular rate |omega_1 + i omega_2| (fixed frame)"
    put("transverse_rate", transverse, "transverse rate", "Omega", what)
    if m.has_translation:
        v0, x0 = floor_centre(m.name, y) if flights is None else (flights.v_o, flights.x_o)
        v_g = v0 + q * np.cross(omega, k)
        z_g = x0[:, 2] + q * k[:, 2]
        put("velocity", v0, "velocity of O", "Omega R", "velocity of the sphere's centre O")
        put("position", x0, "position of O", "R", "position of the sphere's centre O; the plane is at height 0")
        put("momentum", mu * v_g, "momentum mu V_G", _ONE, "linear momentum mu V_G")
        h = h_cg(omega, k, q=q, sigma=sigma, mu=mu)
        put("h_cg", h, "h_cg, eq. (10)", "A0 Omega", "angular momentum about G along r_cg = q k + K, eq. (10)")
        # (in flight: the horizontal velocity of the sphere's lowest point)
        slip = np.column_stack([v0[:, 0] - omega[:, 1], v0[:, 1] + omega[:, 0], np.zeros(n)])
        what = "speed of the contact point |V_c|, eq. (5)"
        put("slip_speed", np.linalg.norm(slip, axis=1), "slip speed", "Omega R", what)
        f = np.column_stack([forces[:, 0], forces[:, 1], np.zeros(n)])
        why = " (friction law)" if m.name == "sliding" else " needed to keep rolling"
        put("friction", f, "friction force", _ONE, "tangential contact force" + why)
        magnitude = np.hypot(f[:, 0], f[:, 1])
        put("friction_magnitude", magnitude, "friction magnitude", _ONE, "magnitude of the tangential contact force")
        put("normal_force", forces[:, 2], "normal force N", _ONE, "normal contact force; equilibrium value mu fr_inv")
    else:
        v_g = (1.0 + q) * np.cross(omega, k)
        z_g = (1.0 + q) * k[:, 2]
        put("reaction", forces, "pivot force", _ONE, "force of the pivot on the top")
        a_c = 1.0 + mu * (1.0 + 2.0 * q)
        l_p = a_c * omega + (sigma - a_c) * wk[:, None] * k
        what = "vertical angular momentum about the pivot"
        put("angular_momentum_vertical", l_p[:, 2], "L_z about the pivot", "A0 Omega", what)
    names = {
        "kinetic_translational": ("translational KE", "kinetic energy of translation of G"),
        "kinetic_spin": ("spin KE", "rotational kinetic energy of the spin about G"),
        "kinetic_transverse": ("transverse KE", "rotational kinetic energy of the transverse rotation about G"),
        "potential": ("potential energy", "potential energy mu fr_inv z_G"),
        "energy": ("energy", "total energy"),
    }
    for name, val in energy_parts(omega, k, v_g, z_g, params).items():
        short, what = names[name]
        put(name, val, short, "A0 Omega^2", f"{what}, in units of A0 Omega^2")
    ds = xr.Dataset(data, coords=coords)
    source = f"stability.simulate (tippe-stability {package_version()})"
    ds.attrs.update(Conventions="CF-1.10", title=f"Tippe top, nonlinear {m.name} model", source=source)
    ds.attrs.update(model=m.name, equations=m.equations)
    ds.attrs[PRODUCT_ATTR] = "nonlinear_run"
    for name, val in params.items():
        ds.attrs[name] = val
        ds.attrs[f"{name}_long_name"] = LONG_NAMES[name]
    if flights is None:
        return ds
    contact = _attrs("in contact", _ONE, comment="1 on the floor, 0 in flight (stability.nonlinear.flight)")
    ds["contact"] = ("time", flights.contact, contact)
    height = _attrs("height of the lowest point", "R", comment="height of the sphere's lowest point above the floor")
    ds["height"] = ("time", flights.x_o[:, 2] - 1.0, height)
    lands = flights.landings
    ds.attrs.update(
        impact_law=IMPACT_LAWS[m.name],
        flights=len(flights.takeoffs),
        takeoff_times=np.array(flights.takeoffs, float),
        landing_times=np.array([x.time for x in lands], float),
        impact_impulse_vertical=np.array([x.impulse[2] for x in lands], float),
        impact_impulse_horizontal=np.array([np.hypot(x.impulse[0], x.impulse[1]) for x in lands], float),
        impact_contact_velocity_before=np.array([x.contact_velocity_before[2] for x in lands], float),
        impact_contact_velocity_after=np.array([x.contact_velocity_after[2] for x in lands], float),
        impact_energy_loss=np.array([x.energy_loss for x in lands], float),
    )
    return ds


def run_in_chunks(
    state: dict, params: dict, *, chunk: float, t_max: float, samples: Any, rtol: Any, stick_tilt: float | None = None
) -> Iterator[tuple[float, float, xr.Dataset]]:
    """A sliding run in chunks until its caller stops it (settled, failed, an event) or ``t_max``:
    the one loop of :func:`stability.steady.final.settle` and :func:`stability.launches.flip.run_launch`.

    Yields ``(t, length, ds)`` per chunk: its start ``t``, its ``length = min(chunk, t_max - t)``
    and :func:`simulate` from ``state`` (``omega``, ``k``, ``velocity``) over it with ``params``,
    ``samples`` output intervals (an int, or ``samples(length)``), tolerance ``rtol`` (a float, or
    ``rtol()`` read at each chunk's start) and ``atol = 1e-3 rtol``, stopped at ``stick_tilt``.
    The next chunk starts from the last output, ``k`` renormalised to unit length."""
    t = 0.0
    while t < t_max:
        length = min(chunk, t_max - t)
        n, r = samples(length) if callable(samples) else samples, rtol() if callable(rtol) else rtol
        run = dict(state, t_end=length, t_eval=np.linspace(0.0, length, n + 1), rtol=r, atol=1e-3 * r)
        ds = simulate("sliding", **run, stick_tilt=stick_tilt, **params)
        yield t, length, ds
        t, k = t + length, ds.k.values[-1]
        state = {"omega": ds.omega.values[-1], "k": k / np.linalg.norm(k), "velocity": ds.velocity.values[-1][:2]}
