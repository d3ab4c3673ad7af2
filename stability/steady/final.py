"""The final state of a sliding top, predicted from Jellett's integral and the energy.

Principle (docs/steady_states.md, sec. 5). Along every motion of the sliding sphere with
viscous friction ``alpha_v > 0``:

* Jellett's integral ``J = (K + q k) . I_G omega`` is constant (every contact force acts at the
  contact point C, and ``C - G = -(K + q k)``);
* the energy decreases, ``dE/dt = -alpha_v |V_c|^2``;
* ``E >= U_J(k . K)`` (the kinetic energy at fixed ``J`` and axis is smallest at the no-slip
  state with ``omega`` parallel to ``K + q k``), with equality exactly at the steady states.

By LaSalle's principle the motion tends to the set where the contact point does not slip, and
(``fr_inv > 0``, ``q != 0``) that set on the level ``J0`` is made of the steady states of
:func:`stability.steady.states.steady_states`: the motion ends on one of them with
``U_J <= E0``, generically a stable one. So: ``method = "jellett"`` when exactly one steady
state of the level lies below the initial energy without being unstable, and it is strictly
stable; it costs a few root findings (microseconds, no integration). Otherwise
(``method = "simulation"``) a run decides: two stable candidates (bistable levels), a marginal
one (a level at a fold or a branch point; ``fr_inv = 0`` or ``q = 0``, where the normal force
has no moment about G and continua of rolling motions sit next to the vertical states and, for
``q = 0``, to the ``c = 0`` state, so that ``J`` and ``E`` do not fix the end). The run
integrates :func:`stability.simulate` in chunks until the tilt stops moving and the contact
point stops slipping, or a time limit, and says which (:class:`SettleRun`).

Without friction (``alpha_v = 0``) the energy is conserved and there is no final state: refused.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from typing import Any, NamedTuple

import numpy as np
import xarray as xr

from ..errors import DomainError, InputError
from ..execution import announce, pick
from ..nonlinear import get_nonlinear_model
from ..nonlinear.integrators import check_tolerances
from ..nonlinear.parameters import pack
from ..nonlinear.runs import auto_method, initial_state, run_in_chunks
from ..parameters import DEFAULT_MU, as_parameter, check_flag, check_interval, check_positive
from ..products import FLAG_NAMES, STABLE, UNSTABLE
from . import family
from .products import DEGREE, check_scales, flag_attrs, potential_curve, product_attrs, sliding_parameters, var_attrs
from .states import level_spins, point_integrals, state_values
from .verdicts import flag_of

__all__ = ["Candidate", "FinalState", "SettleRun", "candidates", "chunk_length", "final_state", "predict", "settle"]

#: a run's end tilt within this of a steady state (degrees) is that state
MATCH_DEG = 0.05
#: relative tolerance of the comparison U_J <= E0
ENERGY_REL_TOL = 1e-12
#: wall time of a stiff deciding run (LSODA) per unit of simulated time: 11.2 s for 2e4 units
#: at q = 0, sigma = 0.8, fr_inv = 0.3, alpha_v = 1e8 (the 2-core machine, docs/hard_cases.md)
STIFF_SECONDS_PER_UNIT = 5.6e-4


class Candidate(NamedTuple):
    """One steady state of the Jellett level of a motion: a row of the candidate table (an
    immutable named tuple, cheap to make).

    Attributes
    ----------
    kind : str
        ``"upright"``, ``"inverted"`` or ``"tilted"``.
    tilt : float
        Polar angle of the axis, degrees.
    energy : float
        ``U_J`` of the state (its energy).
    precession_rate : float
        NaN for the vertical states.
    axial_spin : float
        ``omega . k``.
    stability : int
        0 stable, 1 marginal, 2 unstable (:mod:`stability.steady.verdicts`).
    energy_test : float
        The energy criterion (positive at a minimum of ``U_J``).
    reachable : bool
        ``U_J <= E0``: the motion can end there.
    """

    kind: str
    tilt: float
    energy: float
    precession_rate: float
    axial_spin: float
    stability: int
    energy_test: float
    reachable: bool


@dataclass(frozen=True)
class SettleRun:
    """How a deciding run went (``method = "simulation"``).

    Attributes
    ----------
    t_end : float
        Time integrated (units of ``1/Omega``).
    settled : bool
        The tilt moved by less than ``settle_tolerance`` degrees over the last chunk and the
        slip speed fell below ``1e-6``; False: the time limit ``t_max`` came first.
    tilt_change : float
        Movement of the tilt over the last chunk, degrees.
    slip_speed : float
        ``|V_c|`` at the end.
    chunks : int
        Number of chunks (``simulate`` calls).
    seconds : float
        Wall time of the run.
    jellett_drift : float
        ``|J(t_end) - J(0)| / |J(0)|``: the integrator's error on the conserved ``J``.
    axial_spin : float
        ``omega . k`` at the end.
    """

    t_end: float
    settled: bool
    tilt_change: float
    slip_speed: float
    chunks: int
    seconds: float
    jellett_drift: float
    axial_spin: float
    event: str = "none"
    event_time: float = math.nan


@dataclass(frozen=True, kw_only=True)
class FinalState:
    """The predicted end of a motion (:func:`final_state`).

    Attributes
    ----------
    tilt : float
        Final polar angle of the axis, degrees.
    kind : str
        ``"upright"``, ``"inverted"``, ``"tilted"`` (a steady state of the level), or after a run
        ``"rolling"`` (settled off every steady state: one of the no-slip continua of
        ``fr_inv = 0`` or ``q = 0``) or ``"unsettled"`` (the time limit came first), or ``"contact_lost"`` (the deciding run
        reached a zero of the normal force: no final state of the model; ``event``, ``event_time``), or
        ``"stick_contact"`` (given ``stick_tilt``, the motion reaches the toy's stick: ``tilt`` is the
        stick's, ``event_time`` when).
    method : str
        ``"jellett"`` (decided by ``J`` and ``E``) or ``"simulation"`` (a run decided).
    jellett : float
        Jellett's integral of the motion (simulate's units, ``A0 Omega``).
    initial_energy : float
        ``E0``.
    energy : float
        Energy of the final state (``U_J`` of the steady state; after a run that ends on no
        steady state, the run's last energy).
    precession_rate, axial_spin : float
        Of the final state (precession NaN for a vertical state or a state off the steady ones).
    state : Candidate or None
        The steady state it ends on.
    candidates : tuple of Candidate
        Every steady state of the level, by tilt.
    reason : str
        Why this method.
    run : SettleRun or None
        The deciding run (``method = "simulation"``).
    parameters : dict
        ``q, sigma, fr_inv, alpha_v, mu``.
    initial_tilt : float
        Degrees.
    contact : str
        Whether the sphere stays on the floor on the way: ``"held"`` (the deciding run watched
        the normal force to its end), ``"lost"`` (a run, or the start itself, reached ``N = 0``:
        no end state is reported), or ``"not checked"`` (decided by ``J`` and ``E`` without a
        run: ``N > 0`` at the start and ``N = mu Fr^-1 > 0`` at every steady state, the
        transient not integrated; ``simulate`` is the check).
    """

    tilt: float
    kind: str
    method: str
    jellett: float
    initial_energy: float
    energy: float
    precession_rate: float = math.nan
    axial_spin: float = math.nan
    state: Candidate | None = None
    candidates: tuple[Candidate, ...]
    reason: str
    run: SettleRun | None = None
    parameters: dict[str, float] = field(default_factory=dict)
    initial_tilt: float = math.nan
    event: str = "none"
    event_time: float = math.nan
    contact: str = "not checked"

    def to_dataset(self) -> xr.Dataset:
        """The prediction as a CF Dataset (product ``final_state``): 0-d variables ``tilt``,
        ``initial_tilt``, ``jellett``, ``initial_energy``, ``energy``, ``precession_rate``,
        ``axial_spin``; the candidate table over ``candidate``; the effective potential ``U_J``
        of the level over ``tilt_grid`` (what the figure draws, ``ds.tippe.plot()``:
        :func:`stability.plotting.plot_final_state`); ``kind``, ``method``, ``reason`` and the
        run's numbers as attributes."""
        cands = self.candidates

        def column(values: list, attrs: dict[str, Any], dtype: Any = None) -> tuple:
            return ("candidate", np.array(values, dtype=dtype), attrs)

        def yes_no(long_name: str, meanings: str, **extra: str) -> dict[str, Any]:
            flags = {"flag_values": np.array([0, 1], np.int8), "flag_meanings": meanings}
            return {"long_name": long_name, **extra, **flags}

        scalars = {  # name: long_name, units, short name
            "tilt": ("final polar angle of the axis from the upward vertical", DEGREE, "final tilt"),
            "initial_tilt": ("initial polar angle of the axis", DEGREE, "initial tilt"),
            "jellett": ("Jellett's integral J = (K + q k) . I_G omega of the motion", "A0 Omega", "Jellett's J"),
            "initial_energy": ("initial energy", "A0 Omega^2", None),
            "energy": ("energy of the final state", "A0 Omega^2", "final energy"),
            "precession_rate": ("precession rate of the final state", "Omega", "precession rate"),
            "axial_spin": ("spin about the axis of the final state, omega . k", "Omega", "axial spin"),
        }
        data = {k: ((), getattr(self, k), var_attrs(long, u, short=short)) for k, (long, u, short) in scalars.items()}
        columns = {  # candidate_<field>: a float's long name, units (default 1), short name; or attributes, dtype
            "kind": ({"long_name": "kind of state", "comment": "kind of the steady state of the level"}, str),
            "tilt": ("tilt of the steady state", DEGREE, "tilt"),
            "energy": ("energy U_J of the steady state", "A0 Omega^2", "energy U_J"),
            "precession_rate": ("precession rate of the steady state (NaN: vertical)", "Omega", "precession rate"),
            "axial_spin": ("spin about the axis of the steady state, omega . k", "Omega", "axial spin"),
            "stability": (flag_attrs("stability of the steady state"), np.int8),
            "energy_test": ("energy criterion (> 0 at a minimum of U_J)", "energy criterion"),  # units: 1
            "reachable": (yes_no("U_J <= initial energy", "unreachable reachable"), np.int8),
        }
        for name, spec in columns.items():
            attrs, dtype = (var_attrs(spec[0], *spec[1:-1], short=spec[-1]), None) if isinstance(spec[0], str) else spec
            data[f"candidate_{name}"] = column([getattr(c, name) for c in cands], attrs, dtype)
        final = yes_no("final state", "no yes", comment="the motion ends on this state")
        data["candidate_is_final"] = column([c is self.state for c in cands], final, np.int8)
        curve, curve_coords = potential_curve(self.jellett, self.parameters)
        attrs = product_attrs(
            "final_state", "Final state of a sliding Tippe top", "stability.final_state", self.parameters
        )
        attrs.update({k: getattr(self, k) for k in ("kind", "method", "reason", "event", "event_time", "contact")})
        attrs["model"] = "sliding"
        if self.run is not None:
            attrs.update({f"run_{k}": int(v) if isinstance(v, bool) else v for k, v in self.run.__dict__.items()})
        index = column(np.arange(len(cands)), {"long_name": "candidate", "comment": "index of the steady state"})
        return xr.Dataset(data | curve, coords={"candidate": index} | curve_coords, attrs=attrs)


def candidates(
    jellett: float, initial_energy: float, *, q: float, sigma: float, fr_inv: float, alpha_v: float, mu: float
) -> tuple[Candidate, ...]:
    """Every steady state of the level ``J`` with its energy, flag and reachability (``U_J <= E0``).

    The closed forms in one call (:func:`stability.steady.family.level_states`, interpreted): no
    integration, no eigenvalues (the flag is the energy criterion,
    :mod:`stability.steady.verdicts`; ``alpha_v > 0``)."""
    J, E0 = float(jellett), float(initial_energy)
    tol = ENERGY_REL_TOL * (abs(E0) + J * J + mu * fr_inv)
    rows = pick(family.level_states, 1)(J, float(q), float(sigma), float(fr_inv), float(mu)).tolist()
    out = []
    for i, (c, u, test, scale, lam, axial) in enumerate(rows):
        kind = "upright" if i == 0 else "inverted" if i == len(rows) - 1 else "tilted"
        tilt = 0.0 if i == 0 else 180.0 if kind == "inverted" else math.degrees(math.acos(c))
        flag = flag_of(kind, test, scale, q=q, fr_inv=fr_inv, alpha_v=alpha_v)
        out.append(Candidate(kind, tilt, u, lam, axial, flag, test, u <= E0 + tol))
    return tuple(out)


def predict(
    jellett: float, initial_energy: float, *, q: float, sigma: float, fr_inv: float, alpha_v: float, mu: float
) -> tuple[Candidate | None, str, tuple[Candidate, ...]]:
    """The decision of the Jellett method from the integrals ``(J0, E0)``, in floats: the steady
    state the motion ends on (None if ``J`` and ``E`` do not decide), the reason, and the
    candidate table (:func:`candidates`). No input checks: :func:`final_state` does them."""
    cands = candidates(jellett, initial_energy, q=q, sigma=sigma, fr_inv=fr_inv, alpha_v=alpha_v, mu=mu)
    reach = [c for c in cands if c.reachable and c.stability != UNSTABLE]
    if len(reach) == 1 and reach[0].stability == STABLE:
        why = "one steady state of the Jellett level lies below the initial energy without being unstable"
        return reach[0], why + ", and it is strictly stable", cands
    n_st = sum(c.stability == STABLE for c in reach)
    n_mg = len(reach) - n_st
    reason = f"{n_st} stable and {n_mg} marginal steady states of the Jellett level lie below the initial energy"
    if n_st >= 2:
        reason += " (bistable: the energy cannot tell which one the motion reaches)"
    if n_mg and (fr_inv == 0.0 or q == 0.0):
        reason += (
            " (fr_inv = 0 or q = 0: the normal force has no moment about G at a no-slip state, and "
            "continua of rolling motions next to the marginal states are steady too, so J and E do not "
            "fix the end)"
        )
    elif n_mg:
        reason += " (a marginal state: the level is at a fold or a branch point)"
    return None, reason, cands


def final_state(
    model: str = "sliding",
    *,
    omega: Any,
    k: Any,
    velocity: Any = None,
    q: Any,
    sigma: Any,
    fr_inv: Any,
    alpha_v: Any,
    mu: Any = DEFAULT_MU,
    simulation: bool = True,
    t_max: Any = 2e5,
    settle_tolerance: Any = 1e-4,
    rtol: Any = 1e-10,
    alpha_k: Any = 0.0,
    alpha_s: Any = None,
    stick_tilt: Any = None,
) -> FinalState:
    """The predicted end of the motion of a sliding top (simulate's state arguments).

    Parameters
    ----------
    model : {"sliding"}
    omega, k : array_like, shape (3,)
        Initial angular velocity and axis (fixed frame, ``K`` up); ``k`` within 1 % of unit
        length (normalised), as :func:`stability.simulate` takes them.
    velocity : array_like, shape (2,) or (3,), optional
        Initial horizontal velocity of the sphere's centre (default zero).
    q, sigma, fr_inv, alpha_v, mu : float
        Parameters (docs/conventions.md); ``alpha_v > 0`` (without friction there is no end).
    simulation : bool, default True
        Run the deciding simulation when ``J`` and ``E`` do not decide; False returns
        ``tilt = NaN``, ``kind = "undecided"`` instead.
    t_max : float, default 2e5
        Time limit of the deciding run (units of ``1/Omega``).
    settle_tolerance : float, default 1e-4
        The run stops when the tilt moves by less than this (degrees) over a chunk and the
        contact point no longer slips (``|V_c| < 1e-6``).
    rtol : float, default 1e-10
        Tolerance of the run (``atol = 1e-3 rtol``); ``J`` drifts by about ``0.25 rtol`` per
        1000 time units, and near a branch point the end tilt is sensitive to ``J``.
    alpha_k, alpha_s : float, optional
        Coulomb friction (eq. 7; ``alpha_s`` the static limit, default ``alpha_k``): with
        ``alpha_k > 0`` the top sticks and rolls, and the answer is that rolling motion
        (:func:`stability.steady.coulomb.coulomb_end`; a hybrid run to ``t_max``,
        ``alpha_v = 0`` allowed; its run lasts ``min(t_max, 1000)``). With ``alpha_k > 0``,
        ``stick_tilt`` and ``simulation=False`` are refused (InputError) and ``settle_tolerance``
        is not used (the run's last phase, stick or slip, decides).
    stick_tilt : float, optional
        The tilt (degrees) at which the top's stick touches the floor
        (:meth:`stability.Top.stick_contact`). When the end that ``J`` and ``E`` decide (or the
        undecided end) lies at or beyond it, a run (stopped at the stick, :func:`stability.simulate`)
        says when the motion reaches its stick: ``kind = "stick_contact"``, ``event_time``, the
        tilt the stick's; an end below it is kept (the transient is not checked, as for contact
        loss).

    Returns
    -------
    FinalState
        ``tilt``, ``kind``, ``method`` ("jellett" or "simulation"), ``jellett``, the energies,
        the steady state it ends on (``state``: precession rate, axial spin), the candidate
        table, the reason and the run (:class:`SettleRun`) if one decided;
        ``.to_dataset()`` gives the Dataset (product ``final_state``).

    Raises
    ------
    ValueError
        ``alpha_v = 0`` (no final state), parameters outside the physical domain, an ``omega``,
        ``k`` or ``velocity`` of the wrong shape or not finite, a ``k`` off unit length by more
        than 1 %, a vertical velocity, an unknown model.
    TypeError
        A non-real or array parameter.

    Examples
    --------
    >>> import stability
    >>> from stability.nonlinear.scene import INITIAL_CONDITIONS
    >>> end = stability.final_state(q=-0.1, sigma=1.0, fr_inv=0.3, alpha_v=0.5, **INITIAL_CONDITIONS[0.3])
    >>> end.method, end.kind, round(end.tilt, 3)
    ('jellett', 'tilted', 166.018)
    """
    params, _ = sliding_parameters(model, q=q, sigma=sigma, fr_inv=fr_inv, alpha_v=alpha_v, mu=mu, kernel=False)
    q, sigma, fr_inv, alpha_v, mu = (params[k_] for k_ in ("q", "sigma", "fr_inv", "alpha_v", "mu"))
    simulation = check_flag("simulation", simulation)
    y = initial_state("sliding", omega, k, velocity)  # shapes, finiteness, |k| within 1 %, horizontal velocity
    if np.any(as_parameter("alpha_k", alpha_k) != 0):  # a Coulomb top sticks and rolls (steady/coulomb.py)
        from .coulomb import coulomb_end

        for name, value, allowed in (("stick_tilt", stick_tilt, None), ("simulation", simulation, True)):
            if value is not allowed:  # the hybrid run has no stick event and no run-less answer
                raise InputError(
                    f"{name} = {value!r} is not allowed with alpha_k = {alpha_k!r} > 0: the Coulomb "
                    f"top's end is always a hybrid run (stability.stick_slip), which does not watch the "
                    f"stick; allowed: {name} = {allowed!r}"
                )
        check_positive("settle_tolerance", settle_tolerance)  # checked, not used: the hybrid run's last phase decides
        fields, run, level = coulomb_end(
            y, params, alpha_k=alpha_k, alpha_s=alpha_s, t_max=min(float(t_max), 1e3), rtol=rtol
        )
        # the level's steady states, flagged for the viscous sliding top (none without alpha_v)
        cands = () if level is None or alpha_v == 0.0 else candidates(*level, **params)
        return FinalState(**fields, candidates=cands, run=SettleRun(**run))
    if alpha_v == 0.0:
        raise DomainError(
            "alpha_v = 0 is outside the allowed range of final_state: alpha_v > 0 (without "
            "friction the energy is conserved and the motion has no final state)"
        )
    if stick_tilt is not None:
        stick_tilt = check_interval("stick_tilt", stick_tilt, 0.0, 180.0)
    # one query: interpreted unless compiled code is in memory (stability.execution.pick)
    J0, E0 = pick(point_integrals, 1)(np.asarray(y, dtype=np.float64), q, sigma, fr_inv, mu)
    check_scales(params, J0)
    tilt0 = math.degrees(math.acos(min(1.0, max(-1.0, float(y[5])))))
    end, reason, cands = predict(J0, E0, **params)
    # E >= U_J(c) on the level, with equality exactly at the steady state of that c (S5-S7): a start
    # whose energy is its candidate's at its own tilt is that steady state, where the top stays
    tol = ENERGY_REL_TOL * (abs(E0) + J0 * J0 + mu * fr_inv)
    for c in cands:
        if abs(c.tilt - tilt0) <= 1e-6 and abs(c.energy - E0) <= tol:
            reason += f"; the start is itself a steady state (the {c.kind} one, {FLAG_NAMES[c.stability]})"
            stays = ", where the top stays forever: the end given is where any perturbation of it leads"
            reason += stays if c.stability == UNSTABLE else ": the top stays there"
            break
    common = dict(jellett=J0, initial_energy=E0, candidates=cands, parameters=params, initial_tilt=tilt0)
    # fr_inv = 0 (no gravity): N = 0 at equilibrium, its sign says nothing (simulate does not watch it)
    # (the sliding model's vertical equation, one 6 x 6 solve: interpreted unless in memory)
    n0, start = math.nan, np.zeros((1, 10))
    if fr_inv > 0.0:
        start[0, :8] = np.asarray(y, dtype=np.float64)[:8]
        n0 = float(pick(get_nonlinear_model("sliding").contact_forces, 1)(start, pack(**params))[0, 2])
    if n0 <= 0.0:  # the sphere leaves the floor at once: no end state of the model
        why = f"but the normal force is N = {n0:.6g} <= 0 at the start: the sphere leaves the floor at once"
        lost = dict(kind="contact_lost", event="contact_lost", event_time=0.0, contact="lost", method="jellett")
        reason = f"{reason}; {why}, the model does not hold, no final state"
        return FinalState(tilt=tilt0, energy=E0, reason=reason, **lost, **common)
    if end is not None and fr_inv > 0.0:
        reason += (
            f"; contact not checked on the way (no run): N = {n0:.6g} at the start and mu Fr^-1 = "
            f"{mu * fr_inv:.6g} at the end state, the transient between not integrated (simulate checks it)"
        )
    if stick_tilt is not None and end is not None and end.tilt < stick_tilt:
        stick_tilt = None  # the decided end is below the stick: the stick plays no part
    if end is not None and stick_tilt is None:
        decided = dict(tilt=end.tilt, kind=end.kind, energy=end.energy, state=end, method="jellett", reason=reason)
        return FinalState(**decided, precession_rate=end.precession_rate, axial_spin=end.axial_spin, **common)
    if not simulation:
        undecided = dict(tilt=math.nan, kind="undecided", method="simulation", energy=math.nan)
        return FinalState(**undecided, reason=reason + "; no run (simulation=False)", **common)
    # the run's own checks, only where a run is needed (the answers without one stay fast)
    t_max, settle_tolerance = check_positive("t_max", t_max), check_positive("settle_tolerance", settle_tolerance)
    (rtol,) = check_tolerances(rtol=rtol)
    if auto_method("sliding", dict(params, alpha_k=0.0)) == "LSODA":
        announce(
            f"final_state's deciding run is stiff (alpha_v = {alpha_v:.3g}: scipy's LSODA, about "
            f"{STIFF_SECONDS_PER_UNIT * 1e4:.0f} s per 10^4 time units): up to ~"
            f"{STIFF_SECONDS_PER_UNIT * t_max:.2g} s for t_max = {t_max:g} (a smaller t_max bounds it; "
            "simulation=False skips it)"
        )
    settling = dict(t_max=t_max, settle_tolerance=settle_tolerance, rtol=rtol, stick_tilt=stick_tilt)
    tilt, energy, run = settle(y, params, chunk=chunk_length(cands, params, J0), **settling)
    outcome = dict(tilt=tilt, method="simulation", run=run, energy=energy, axial_spin=run.axial_spin)
    if run.event != "none":
        outcome.update(kind=run.event, event=run.event, event_time=run.event_time)
    if run.event == "stick_contact":
        end_text = f" ({end.kind} at {end.tilt:.4g} degrees)" if end is not None else ""
        what = (
            f"the motion reaches its stick at {tilt:.4g} degrees after t = {run.event_time:.6g} (units of "
            f"1/Omega): the sphere model's end{end_text} is a tilt the toy cannot have"
        )  # contact stays "not checked": the stick ended the run first
    elif run.event != "none":
        what = (
            f"{run.event.replace('_', ' ')} at t = {run.event_time:.6g} (tilt {tilt:.6g} deg): the model "
            "does not hold beyond, no final state"
        )
        outcome["contact"] = "lost" if run.event == "contact_lost" else "held"
    else:
        near = [c for c in cands if abs(c.tilt - tilt) <= MATCH_DEG and c.stability != UNSTABLE]
        state = min(near, key=lambda c: abs(c.tilt - tilt)) if near else None
        outcome.update(kind="rolling" if run.settled else "unsettled", contact="held")
        if state is not None and run.settled:
            outcome.update(kind=state.kind, energy=state.energy, axial_spin=state.axial_spin, state=state)
            outcome.update(precession_rate=state.precession_rate)
        moving = f"not settled at t_max = {t_max:g} (tilt still moving {run.tilt_change:.2g} deg per chunk)"
        how = "settled" if run.settled else moving
        what = f"{how} after t = {run.t_end:g} ({run.chunks} chunks, {run.seconds:.2g} s)"
    return FinalState(**outcome, reason=f"{reason}; a run decided: {what}", **common)


def chunk_length(cands: tuple[Candidate, ...], params: dict[str, float], jel: float) -> float:
    """About ``8 / |g|``, ``g`` the slowest decay rate of the reachable candidates that are not
    unstable (0.01 degree after the transit), within ``[500, 5e4]``; 2000 if none decays."""
    sel = [c for c in cands if c.reachable and c.stability != UNSTABLE]
    if not sel:
        return 2000.0
    kinds, theta, lam = [c.kind for c in sel], [math.radians(c.tilt) for c in sel], [c.precession_rate for c in sel]
    _, _, values = state_values(kinds, theta, lam, level_spins(kinds, jel, params), pack(**params), params)
    g = float(np.max(values["growth_rate"]))
    return float(np.clip(8.0 / abs(g), 500.0, 5e4)) if g < 0 else 2000.0


def settle(
    y0: np.ndarray,
    params: dict[str, float],
    *,
    chunk: float,
    t_max: float,
    settle_tolerance: float,
    rtol: float,
    stick_tilt: float | None = None,
) -> tuple[float, float, SettleRun]:
    """Integrate :func:`stability.simulate` in chunks of ``chunk`` time units from ``y0`` until the
    tilt moves by less than ``settle_tolerance`` degrees over a chunk and ``|V_c| < 1e-6``, or
    ``t_max`` (or a failed integration: then unsettled, tilt NaN; 20 samples a chunk), or an event (contact lost, the
    stick at ``stick_tilt`` degrees reached). Returns the end tilt (degrees), the end energy and
    the :class:`SettleRun`."""
    n, t0, j0, event, settled = 0, time.perf_counter(), None, "none", False
    state = dict(omega=y0[0:3], k=y0[3:6], velocity=y0[6:8])
    chunks = run_in_chunks(state, params, chunk=chunk, t_max=t_max, samples=20, rtol=rtol, stick_tilt=stick_tilt)
    for t, length, ds in chunks:
        n, t = n + 1, t + length
        j0 = float(ds.h_cg[0]) if j0 is None else j0
        pol = ds.polar_angle.values
        change, slip = float(np.max(pol) - np.min(pol)), float(ds.slip_speed[-1])  # change: NaN if the run failed
        if ds.attrs.get("event", "none") != "none":  # the model stops holding: the run ends there
            event, t = ds.attrs["event"], t - length + float(ds.attrs["event_time"])
            break
        if not np.all(np.isfinite(pol)):  # the integration failed (simulate warned): stop, unsettled
            slip = math.nan
            break
        if settled := change < settle_tolerance and slip < 1e-6:
            break
    drift = abs(float(ds.h_cg[-1]) - j0) / max(abs(j0), 1e-300)
    when = t if event != "none" else math.nan
    run = SettleRun(t, settled, change, slip, n, time.perf_counter() - t0, drift, float(ds.spin[-1]), event, when)
    return (float(pol[-1]) if np.isfinite(pol).all() else math.nan), float(ds.energy[-1]), run
