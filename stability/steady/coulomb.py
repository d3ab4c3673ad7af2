"""The end of a Coulomb top (``alpha_k > 0``): it sticks and rolls, keeping its energy.

With a Coulomb term the slip of the contact point vanishes in finite time and the contact can
stick (:mod:`stability.nonlinear.stickslip`). While it sticks the top is the rolling sphere:
the contact point is at rest, so neither the friction nor the normal force does work, and the
energy ``E`` and Jellett's integral ``J`` (eq. 10) are both constant (paper, Sec. 3(i): "a
rolling top also possesses two integrals of motion"). Nothing dissipates any more: the top does
*not* settle on a steady state, as the viscous top does (:mod:`stability.steady.final`), unless it
happens to stick exactly on one. Its end is a rolling motion on the level ``(J, E_s)`` of its
last stick, and since ``E >= U_J(k . K)`` for every state (``U_J`` the effective potential of the
level, :func:`stability.steady.family.effective_potential`), its tilt stays for ever in the
interval around the stick tilt where ``U_J(c) <= E_s``: the *rolling band* reported here. The
energy ``E_s - U_J`` above the level's steady state is kept as nutation.

This holds as long as the friction rolling needs stays within the static limit; a hybrid run
(:func:`stability.nonlinear.stickslip.stick_slip`) over ``t_max`` decides whether the last
phase is a stick (``kind = "rolling"``) or the top still slips (``"unsettled"``), or loses
contact.
"""

from __future__ import annotations

import math
import time
from typing import Any

import numpy as np

from ..errors import DomainError, RunError
from ..nonlinear.stickslip import stick_slip
from . import family

__all__ = ["coulomb_end", "rolling_band"]

#: points of the grid in cos(tilt) on which the rolling band is bracketed before refinement
ROLLING_BAND_POINTS = 2001
#: relative shortfall of E below U_J(cos tilt) accepted as round-off (a stick on a steady state,
#: E = U_J up to the run's energy error, ~rtol; rolling_band's default run has rtol 1e-10)
ROLLING_BAND_SLACK = 1e-8


def rolling_band(
    tilt: float, energy: float, jellett: float, *, q: float, sigma: float, fr_inv: float, mu: float
) -> tuple[float, float]:
    """The tilt interval (degrees) around ``tilt`` where ``U_J(cos tilt) <= energy``.

    A rolling top (energy and ``J`` constant) never leaves it: ``E >= U_J(c)`` for every state
    of axis height ``c`` on the level ``J`` (docs/steady_states.md, the energy principle). The ends
    are the zeros of ``U_J(c) - E`` next to ``c = cos tilt``, bracketed on a grid of
    :data:`ROLLING_BAND_POINTS` cosines and refined by bisection to round-off; an end at the
    vertical (0 or 180 degrees) when ``U_J <= E`` all the way there.

    Raises
    ------
    stability.errors.DomainError
        ``energy < U_J(cos tilt)`` by more than :data:`ROLLING_BAND_SLACK` (relative): no state
        of that energy has this tilt on the level ``J``, there is no band.
    """

    def excess(c: float) -> float:
        return float(family.effective_potential(c, jellett, q, sigma, fr_inv, mu)) - energy

    c0 = math.cos(math.radians(tilt))
    if excess(c0) > ROLLING_BAND_SLACK * max(1.0, abs(energy)):
        raise DomainError(
            f"energy = {energy!r} is below U_J(cos tilt) = {excess(c0) + energy!r} at tilt = {tilt!r} deg (J = "
            f"{jellett!r}): outside the allowed range energy >= U_J, no rolling band (the energy principle)"
        )
    grid = np.linspace(-1.0, 1.0, ROLLING_BAND_POINTS)
    ends = []
    for side in (1.0, -1.0):  # towards c = 1 (smaller tilt), then c = -1
        pts = grid[grid > c0] if side > 0 else grid[grid < c0][::-1]
        lo, end = c0, side
        for c in pts:
            if excess(c) > 0.0:
                hi = c
                for _ in range(200):
                    mid = 0.5 * (lo + hi)
                    if mid in (lo, hi):
                        break
                    lo, hi = (mid, hi) if excess(mid) <= 0.0 else (lo, mid)
                end = lo
                break
            lo = c
        ends.append(math.degrees(math.acos(max(-1.0, min(1.0, end)))))
    return ends[0], ends[1]


def coulomb_end(
    y: np.ndarray,
    params: dict[str, float],
    *,
    alpha_k: Any,
    alpha_s: Any = None,
    t_max: float = 1000.0,
    rtol: float = 1e-10,
) -> tuple[dict[str, Any], dict[str, Any], tuple[float, float] | None]:
    """The end of a Coulomb top from a checked state ``y`` (``initial_state("sliding", ...)``)
    and checked parameters ``q, fr_inv, sigma, mu, alpha_v``: a hybrid run to ``t_max``
    (:func:`~stability.nonlinear.stickslip.stick_slip`, which checks ``alpha_k``, ``alpha_s``)
    and the rolling band of its last stick (module docstring).

    Returns
    -------
    fields : dict
        The fields of :class:`stability.steady.final.FinalState` but ``candidates`` and
        ``run``: ``kind = "rolling"`` (the run ends sticking; ``tilt`` the tilt at the last stick,
        ``energy`` its conserved energy, the band and the switches in ``reason``),
        ``"unsettled"`` (still slipping at ``t_max``) or ``"contact_lost"``;
        ``method = "simulation"``; ``contact = "lost"`` if the run reached ``N = 0``, else
        ``"held"`` (the run watches ``N`` in every phase).
    run : dict
        The fields of :class:`stability.steady.final.SettleRun` (the hybrid run).
    level : tuple of float or None
        ``(J, E)`` of the rolling motion (its candidates are the steady states of that level),
        None if it does not end rolling.
    """
    t0 = time.perf_counter()
    start = dict(omega=y[0:3], k=y[3:6], velocity=y[6:8], alpha_k=alpha_k, alpha_s=alpha_s)
    ds = stick_slip(t_end=t_max, **start, **params, rtol=rtol, atol=1e-3 * rtol, dt=max(0.1, t_max / 20_000))
    j, a = ds.h_cg.values, ds.attrs
    last_stick = np.flatnonzero(ds.switch_kind.values == "stick")
    sticks = a["final_phase"] == "stick"
    run = dict(t_end=float(ds.time[-1]), settled=sticks and a["event"] == "none", tilt_change=math.nan)
    run.update(slip_speed=0.0 if sticks else float(ds.slip_speed[-1]), chunks=1, seconds=time.perf_counter() - t0)
    run.update(jellett_drift=abs(float(j[-1]) - float(j[0])) / max(abs(float(j[0])), 1e-300))
    run.update(axial_spin=float(ds.spin[-1]), event=a["event"], event_time=a["event_time"])
    switches = (
        f"static limit alpha_s = {float(a['alpha_s']):.6g}; {int(a['n_switches'])} stick/slip switches "
        f"(hybrid run to t = {run['t_end']:.6g})"
    )
    jel = float(j[-1])
    # (no steady state: precession_rate NaN and state None, FinalState's defaults)
    common = dict(method="simulation", jellett=float(j[0]), initial_energy=float(ds.energy[0]))
    common.update(axial_spin=run["axial_spin"], parameters=dict(params, alpha_k=float(a["alpha_k"])))
    common.update(initial_tilt=float(ds.polar_angle[0]), contact="lost" if run["event"] == "contact_lost" else "held")
    if run["event"] != "none" or not sticks:  # no rolling end: the run's last sample
        kind, end, event = "unsettled", f"still slipping at t_max = {t_max:g}", {}
        if run["event"] != "none":
            kind, event = run["event"], dict(event=run["event"], event_time=run["event_time"])
            end = f"{kind.replace('_', ' ')} at t = {run['event_time']:.6g}: the model does not hold beyond, no final state"
        reason = f"Coulomb top (alpha_k > 0): {switches}; {end}"
        last = dict(tilt=float(ds.polar_angle[-1]), kind=kind, energy=float(ds.energy[-1]), reason=reason)
        return dict(**last, **event, **common), run, None
    t_stick = float(ds.switch_time.values[last_stick[-1]]) if last_stick.size else 0.0
    i_stick = int(np.searchsorted(ds.time.values, t_stick, side="right"))  # the first rolling sample
    e_s = float(np.mean(ds.energy.values[i_stick:]))  # constant while rolling (to the run's tolerance)
    tilt_s = float(ds.switch_tilt.values[last_stick[-1]]) if last_stick.size else float(ds.polar_angle[0])
    lo, hi = rolling_band(tilt_s, e_s, jel, **{k: params[k] for k in ("q", "sigma", "fr_inv", "mu")})
    seen = ds.polar_angle.values[i_stick:]
    need = float(np.max(ds.friction_magnitude.values[i_stick:] / ds.friction_limit.values[i_stick:]))
    if not math.isfinite(need):  # N > 0 while sticking (the run's event), so the limit is positive
        raise RunError(
            f"Coulomb top: the friction rolling needs, over its static limit, is {need!r} after the last stick "
            f"(t = {t_stick:.6g}): the hybrid run's forces are not finite there"
        )
    reason = (
        f"Coulomb top (alpha_k > 0): {switches}; it sticks at t = {t_stick:.6g} (tilt {tilt_s:.6g} deg) and "
        f"rolls without slipping from then on: no work is done at the resting contact point, so the energy "
        f"E = {e_s:.9g} and Jellett's J = {jel:.9g} are kept and it settles on no steady state; its tilt stays in "
        f"the rolling band [{lo:.6g}, {hi:.6g}] deg where U_J <= E (seen: [{seen.min():.6g}, {seen.max():.6g}] deg "
        f"up to t_max = {t_max:g}); the friction rolling needs peaks at {need:.3g} of the static limit"
    )
    run["tilt_change"] = float(np.ptp(seen))
    return dict(tilt=tilt_s, kind="rolling", energy=e_s, reason=reason, **common), run, (jel, e_s)
