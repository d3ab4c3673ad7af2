"""The bifurcation diagram of a real top: every steady state against the equivalent upright
spin, in the user's spin unit (docs/your_top.md, docs/steady_states.md).

The abscissa is the *equivalent upright spin*: the spin of an upright launch
(``omega = Omega K``) with the same Jellett integral. The tilted family is traced once, at the
``fr_inv`` of a reference spin ``Omega_ref`` (:data:`REFERENCE_RPM`), with ``J`` in units of
``A0 Omega_ref``. Why one trace serves every spin: in units of ``A0 Omega_ref`` the steady
states of a level ``J`` at ``fr_inv(Omega_ref)`` are those of the level ``J Omega_ref / Omega``
at ``fr_inv(Omega)`` rescaled in time, because ``fr_inv ~ Omega^-2`` is exactly the
rescaling of time (Sec. 2, eq. 3); an upright launch at ``Omega`` has
``J = sigma (1 + q) Omega / Omega_ref`` (:func:`stability.steady.family.upright_jellett`), so the
equivalent upright spin of a state of level ``J`` is ``J / (sigma (1 + q)) Omega_ref``. The
viscous parameter ``alpha_v ~ Omega^-1`` (eq. 7) does not rescale with time in the same way;
the positions of the steady states do not depend on it (no slip, no dissipation), and the
stability of the vertical states does not either for ``alpha_v > 0`` (the threshold of the
sliding model is independent of ``alpha_v``); the verdicts of the tilted states are those at
the ``alpha_v`` of the reference spin, recorded in the attributes.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

import numpy as np
import xarray as xr

from ..errors import InputError
from ..top import SPIN_UNITS, Top
from .products import FLAGS

__all__ = ["REFERENCE_RPM", "bifurcation_diagram"]

#: the diagram's reference spin: J in units of A0 Omega_ref (any value gives the same figure)
REFERENCE_RPM = 400.0


def bifurcation_diagram(
    top: Top,
    *,
    unit: str = "rpm",
    alpha_v: Any = None,
    runs: Sequence[float] = (),
    tilt: float = 1.0,
    paper_run: bool = False,
    spin_range: Sequence[float] | None = None,
    points: int = 221,
) -> dict[str, xr.Dataset]:
    """The bifurcation diagram of a top: its steady states against the equivalent upright spin.

    Parameters
    ----------
    top : Top
        The top (SI units).
    unit : {"rad/s", "rpm", "rev/s", ...}
        Spin unit of the abscissa, of ``runs`` and of ``spin_range``
        (:data:`stability.top.SPIN_UNITS`).
    alpha_v : float, optional
        The viscous parameter when the top has no ``mu_v``; with ``mu_v``, the ``alpha_v`` of the
        reference spin (eq. 7). Default 0.5 when neither is given (the paper's value; the
        diagram's states and the vertical verdicts do not depend on it, module docstring).
    runs : sequence of float
        Launch spins (in ``unit``) of nonlinear runs launched upright, axis tilted by ``tilt``
        degrees, integrated until they settle (:func:`stability.steady.final.settle`): their
        end tilts are drawn on the diagram.
    tilt : float
        Initial tilt of those runs, degrees.
    paper_run : bool
        Also the paper's Fr^-1 = 0.3 run of Sec. 3(ii) from its printed state (the Table 1 top).
    spin_range : (lo, hi), optional
        The abscissa's range in ``unit`` (default: 0.75 x the lowest and 1.1 x the highest of
        the branch points and ``runs``).
    points : int
        Levels at which the vertical states' stability is evaluated (branch points added).

    Returns
    -------
    dict of xarray.Dataset
        ``"branch"`` (:func:`stability.steady.branch.steady_branch` with the abscissa ``spin``),
        ``"vertical"`` (``stability_upright``, ``stability_inverted`` on a grid of ``spin``,
        :func:`stability.steady_states`), ``"runs"`` (``launch_spin``, ``spin``, ``predicted_tilt``,
        ``end_tilt``, ``t_end``, ``settled``, ``paper_run`` over ``run``). ``spin`` has
        ``units = unit``; every dataset has the attributes ``spin_unit``, ``reference_spin``
        (in ``unit``), the top's ``q``, ``sigma``, ``mu``, ``alpha_v``, ``radius_m``, ``mass_kg``.
        A top with a stick (:meth:`stability.Top.stick_contact`): every dataset has ``stick_tilt``
        (degrees) and ``stick_part``; the branch ``beyond_stick`` (1 where the state's tilt is at
        or beyond the stick's: a state the toy cannot have); the runs stop at the stick and have
        ``reaches_stick`` (1 for those that reach it) and ``stick_time`` (time units of the
        launch spin when they do, NaN else), their ``end_tilt`` the stick's.

    Raises
    ------
    InputError
        An unknown unit, a run spin or range that is not > 0.
    """
    from ..nonlinear.runs import initial_state
    from .branch import branch_points, steady_branch
    from .family import upright_jellett
    from .final import chunk_length, final_state, settle
    from .states import steady_states

    if unit not in SPIN_UNITS:
        raise InputError(f"unit = {unit!r} is not one of {', '.join(SPIN_UNITS)}")
    per_unit = SPIN_UNITS[unit]
    runs = tuple(float(r) for r in runs)
    if any(not (math.isfinite(r) and r > 0) for r in runs):
        raise InputError(f"runs = {runs!r}: every launch spin must be a number > 0 ({unit})")
    ref = REFERENCE_RPM * SPIN_UNITS["rpm"] / per_unit  # the reference spin in `unit`
    if top.mu_v is not None:
        if alpha_v is not None:
            raise InputError(
                f"alpha_v = {alpha_v!r} conflicts with this Top's mu_v = {top.mu_v:g} s/m; give one of them"
            )
        alpha_v = float(top.alpha_v(ref, unit))
    alpha_v = 0.5 if alpha_v is None else float(alpha_v)
    if not alpha_v > 0:
        raise InputError(f"alpha_v = {alpha_v!r} is outside the allowed range: alpha_v > 0")
    q, sigma, mu = top.q, top.sigma, top.mu
    stick_tilt, stick_part = top.stick_contact() if top.stick is not None else (None, "")
    fr_ref = float(top.fr_inv(ref, unit))
    j_per_unit = upright_jellett(q=q, sigma=sigma) / ref
    bp = branch_points(q=q, sigma=sigma, fr_inv=fr_ref, alpha_v=alpha_v, mu=mu)
    bp_spin = [v / j_per_unit for v in bp.values() if math.isfinite(v)]
    if spin_range is not None:
        lo, hi = (float(v) for v in spin_range)
        if not (math.isfinite(lo) and math.isfinite(hi) and 0 < lo < hi):
            raise InputError(f"spin_range = {tuple(spin_range)!r} must be (lo, hi) with 0 < lo < hi ({unit})")
    else:
        marks = list(runs) + bp_spin or [ref]
        lo, hi = 0.75 * min(marks), 1.1 * max(marks)
    branch = steady_branch(
        q=q, sigma=sigma, fr_inv=fr_ref, alpha_v=alpha_v, mu=mu, jellett_max=hi * j_per_unit, max_step=0.01
    )
    spin_attrs = {"long_name": "equivalent upright spin (launch spin of an upright top with this J)", "units": unit}
    branch["spin"] = (branch.jellett / j_per_unit).assign_attrs(spin_attrs)
    extra = branch.spin.values[branch.kind.values == "branch_point"]
    spins = np.unique(np.concatenate([np.linspace(lo, hi, points), extra]))
    flags: dict[str, list[int]] = {"upright": [], "inverted": []}
    for s in spins:
        ds = steady_states(q=q, sigma=sigma, fr_inv=fr_ref, alpha_v=alpha_v, mu=mu, jellett=s * j_per_unit)
        for kind in flags:
            flags[kind].append(int(ds.stability.values[ds.kind.values == kind][0]))
    flag = {k: {"long_name": f"stability of the {k} spin", **FLAGS} for k in flags}
    data = {f"stability_{k}": ("level", np.array(v, dtype=np.int8), flag[k]) for k, v in flags.items()}
    vertical = xr.Dataset(data, coords={"spin": ("level", spins, spin_attrs)})
    rows = []
    th = math.radians(tilt)
    launches = []  # (launch spin, parameters, start, the paper's run)
    for r in runs:
        params = top.nondimensional(r, unit, alpha_v=None if top.mu_v is not None else alpha_v, model="sliding")
        start = dict(omega=[0.0, 0.0, 1.0], k=[math.sin(th), 0.0, math.cos(th)])
        launches.append((r, {k: float(v) for k, v in params.items()}, start, False))
    if paper_run:  # the paper's Fr^-1 = 0.3 run of Sec. 3(ii), from its printed state
        from ..nonlinear.scene import INITIAL_CONDITIONS

        params = dict(q=q, sigma=sigma, fr_inv=0.3, alpha_v=alpha_v, mu=mu)
        launches.append((float(top.spin_rate(0.3, unit)), params, INITIAL_CONDITIONS[0.3], True))
    settling = dict(t_max=2e5, settle_tolerance=1e-3, rtol=1e-10, stick_tilt=stick_tilt)
    for r, params, start, paper in launches:
        # the launches' prediction without a run (the run below decides); the paper's with one
        pred = final_state(**params, **start, simulation=paper)
        chunk = chunk_length(pred.candidates, params, pred.jellett) if paper or pred.method == "jellett" else 5000.0
        end, _, run = settle(initial_state("sliding", **start), params, chunk=chunk, **settling)
        jel = abs(pred.jellett) if paper else pred.jellett
        stick_time = run.event_time if run.event == "stick_contact" else math.nan
        spin = jel / upright_jellett(q=q, sigma=sigma) * r
        rows.append((r, spin, pred.tilt, end, run.t_end, int(run.settled), paper, stick_time))
    arr = np.array(rows, dtype=float).reshape(-1, 8)
    columns = {  # name: long_name, units (None: none), dtype
        "launch_spin": ("launch spin", unit, None),
        "spin": ("equivalent upright spin of the launch's J", unit, None),
        "predicted_tilt": ("final tilt predicted by Jellett's integral", "degree", None),
        "end_tilt": ("tilt at the end of the nonlinear run", "degree", None),
        "t_end": ("length of the run", "1", None),
        "settled": ("the run settled (tilt moved < 1e-3 deg per chunk)", None, np.int8),
        "paper_run": ("the paper's Fr^-1 = 0.3 run of Sec. 3(ii) (printed initial state, clockwise)", None, np.int8),
    }
    data = {
        name: ("run", arr[:, i].astype(dt or float), {"long_name": long} | ({"units": u} if u else {}))
        for i, (name, (long, u, dt)) in enumerate(columns.items())
    }
    runs_ds = xr.Dataset(data, coords={"run": ("run", np.arange(len(rows)))})
    place = dict(spin_unit=unit, reference_spin=ref, radius_m=top.radius, mass_kg=top.mass)
    attrs = {"Conventions": "CF-1.10", **place, "q": q, "sigma": sigma, "mu": mu, "alpha_v": alpha_v}
    attrs["initial_tilt_deg"] = float(tilt)
    if stick_tilt is not None:
        attrs.update(stick_tilt=stick_tilt, stick_part=stick_part)
        branch.attrs.update(stick_tilt=stick_tilt, stick_part=stick_part)
        beyond = "the state's tilt is at or beyond the stick's: a state the toy cannot have"
        branch["beyond_stick"] = ("point", (branch.tilt.values >= stick_tilt).astype(np.int8), {"long_name": beyond})
        reaches = {"long_name": "the run reaches the stick"}
        runs_ds["reaches_stick"] = ("run", np.isfinite(arr[:, 7]).astype(np.int8), reaches)
        when = {"long_name": "time at which the run reaches the stick", "units": "1/Omega of the launch spin"}
        runs_ds["stick_time"] = ("run", arr[:, 7], when)
    for ds in (vertical, runs_ds):
        ds.attrs.update(attrs)
    branch.attrs.update(place)
    for name in ("kind", "detail"):
        branch[name] = branch[name].astype(str)
    return {"branch": branch, "vertical": vertical, "runs": runs_ds}
