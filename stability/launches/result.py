"""The answer to "what happens if I spin this top at this rate?": :func:`launch`.

Derivations (docs/launch.md):

* ``unstable_above`` is the upright top's critical spin (:func:`stability.critical_spin`,
  eq. 11's neutral curve in ``fr_inv``).
* ``inverts_above`` is the launch spin of an upright top whose Jellett integral equals the
  one at the inverted branch point of the tilted family (:func:`stability.steady.branch.branch_points`,
  located on the nonlinear right-hand side), ``n = J_inv / (sigma (1 + q))`` in units of the
  launch spin (:func:`stability.steady.family.upright_jellett`). Closed form (checked in
  tests/test_launch.py): with G below O by ``alpha R`` (``q = -alpha``), Jellett's integral
  ``J = -L . a`` (``a`` from G to the contact point) of the spinning vertical top is
  ``C n R (1 - alpha)`` upright and ``C n R (1 + alpha)`` inverted, so a top launched upright
  at ``n_launch`` reaches the inverted state's branch point (its critical spin ``n_inv``) when
  ``n_launch = n_inv (1 + alpha) / (1 - alpha)``.
* ``end_tilt``, ``end_kind``, ``method``: :func:`stability.final_state` of the launch state.
* ``flip_time``, ``settle_time``, ``min_normal_force``: one run of the launch state
  (:func:`stability.launches.flip.run_launch`), in seconds (``t / Omega``) and newtons
  (``A0 Omega^2 / R`` per unit; equilibrium ``mu fr_inv`` is ``M g``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import xarray as xr

from ..top import Top, from_rad_per_s, spin_text
from .flip import launch_parameters, launch_state, product_header, run_launch

__all__ = ["PRODUCT", "Launch", "inverts_above", "launch"]


@dataclass(frozen=True)
class Launch:
    """What a launched top does (:func:`launch`). Spins in rad/s, times in s, forces in N.

    Attributes
    ----------
    spin : float
        Launch spin, rad/s; ``unit`` the caller's unit (used by ``str()``).
    tilt : float
        Initial tilt, degrees.
    unstable_above, inverts_above : float or None
        The spin above which the upright top is unstable (its critical spin), and the launch
        spin above which it inverts completely (module docstring), rad/s; None with the reason
        in ``reasons``.
    top_class : str
        High-spin class (:func:`stability.top_class`).
    end_tilt : float
        Where the launch ends, degrees; ``end_kind`` and ``method`` as :func:`stability.final_state`.
    flip_time, settle_time : float or None
        Seconds until the axis first crosses 90 degrees, and until it stays within 1 degree of
        its end; None with the reason in ``reasons``.
    min_normal_force : float
        Smallest normal force along the run, N; ``min_normal_force_nd`` in units of
        ``A0 Omega^2 / R`` (equilibrium ``mu fr_inv``).
    parameters : dict
        The nondimensional ``q, mu, sigma, fr_inv, alpha_v`` used (``Omega`` = the launch spin).
    alpha_v_source : str
        Where ``alpha_v`` came from.
    event, event_time, event_tilt :
        The run's contact event (``"none"`` until the nonlinear run reports one).
    on_stick, stick_spin, stick_critical_spin :
        For a run that reaches the stick (``event = "stick_contact"``): ``"spins"`` (then spins
        on its stick) or ``"falls_back"``, the spin about the symmetry axis at the event
        (``|omega . k|``, rad/s) and the critical spin of the top on its stick
        (:func:`stability.critical_spin` of :meth:`stability.Top.on_stick`, upright: stable
        above, rad/s); None otherwise.
    reasons : dict
        Field -> why it is None.
    """

    spin: float
    unit: str
    tilt: float
    unstable_above: float | None
    inverts_above: float | None
    top_class: str
    end_tilt: float
    end_kind: str
    method: str
    flip_time: float | None
    settle_time: float | None
    min_normal_force: float
    min_normal_force_nd: float
    parameters: dict[str, float]
    alpha_v_source: str
    event: str = "none"
    event_time: float | None = None
    event_tilt: float | None = None
    on_stick: str | None = None
    stick_spin: float | None = None
    stick_critical_spin: float | None = None
    reasons: dict[str, str] = field(default_factory=dict)

    def __str__(self) -> str:
        def spin(name: str) -> str:
            w = getattr(self, name)
            return f"none ({self.reasons.get(name, '')})" if w is None else spin_text(w, self.unit)

        def when(name: str) -> str:
            t = getattr(self, name)
            if t is None:
                return f"never ({self.reasons.get(name, '')})"
            return f"{t:.4g} s ({t * self.spin / (2 * math.pi):.4g} spin periods)"

        p = self.parameters
        ends = f"{self.end_kind} at {self.end_tilt:.4g} degrees"
        lines = [
            f"launch at {spin('spin')}, axis tilted {self.tilt:g} deg from the vertical, centre at rest",
            f"  the upright top becomes unstable above:        {spin('unstable_above')}",
            f"  launched upright, it inverts completely above: {spin('inverts_above')}",
            f"  high-spin class: {self.top_class}",
            f"  ends: {self.reasons['end']} (the sphere model alone would end {ends}, by {self.method})"
            if self.event != "none"
            else f"  ends: {ends} (decided by {self.method})",
            f"  time to 90 degrees: {when('flip_time')}",
            f"  settles (within 1 degree of its end) after: {when('settle_time')}",
            f"  smallest normal force: {self.min_normal_force:.4g} N ({self.min_normal_force_nd:.4g} A0 Omega^2/R; "
            f"equilibrium {p['mu'] * p['fr_inv']:.4g})",
            "  parameters: " + ", ".join(f"{k} = {v:.6g}" for k, v in p.items()),
            f"  alpha_v: {self.alpha_v_source}",
        ]
        if self.event != "none":
            lines.append(
                f"  WHERE THE MODEL STOPS: {self.reasons.get('end', self.event)}; the run stops there "
                f"({self.event} at {self.event_time:.4g} s, tilt {self.event_tilt:.4g} degrees)"
            )
        return "\n".join(lines)

    def __repr__(self) -> str:
        def s(v: float | None) -> str:
            return "None" if v is None else f"{from_rad_per_s(v, self.unit):.6g} {self.unit}"

        return (
            f"Launch(spin={s(self.spin)}, tilt={self.tilt:g} deg, unstable_above={s(self.unstable_above)}, "
            f"inverts_above={s(self.inverts_above)}, top_class={self.top_class!r}, end={self.end_kind} "
            f"{self.end_tilt:.4g} deg, flip_time={self.flip_time!r} s, settle_time={self.settle_time!r} s)"
        )

    def to_dataset(self) -> xr.Dataset:
        """The answer as a CF Dataset of 0-d variables (product ``launch``, docs/datasets.md);
        a field that is None is NaN with its reason in the variable's ``comment``."""
        force = "smallest normal force along the run"
        variables = {  # variable: field, long name, units
            "spin": ("spin", "launch spin", "rad s-1"),
            "initial_tilt": ("tilt", "initial tilt of the axis", "degree"),
            "unstable_above": ("unstable_above", "spin above which the upright top is unstable", "rad s-1"),
            "inverts_above": ("inverts_above", "launch spin above which the top inverts completely", "rad s-1"),
            "end_tilt": ("end_tilt", "tilt where the launch ends", "degree"),
            "flip_time": ("flip_time", "time until the axis first crosses 90 degrees", "s"),
            "settle_time": ("settle_time", "time until the tilt stays within 1 degree of its end", "s"),
            "min_normal_force": ("min_normal_force", force, "N"),
            "min_normal_force_nd": ("min_normal_force_nd", force, "A0 Omega2 R-1"),
        }
        data = {}
        for name, (f, long_name, units) in variables.items():
            v = getattr(self, f)
            why = {} if v is not None else {"comment": self.reasons.get(f, "")}
            data[name] = ((), math.nan if v is None else float(v), {"long_name": long_name, "units": units} | why)
        fields = ("unit", "top_class", "end_kind", "method", "alpha_v_source", "event")
        attrs = product_header(PRODUCT, "launch of a real top") | {k: getattr(self, k) for k in fields}
        attrs.update({k: float(v) for k, v in self.parameters.items()})
        optional = ("event_time", "event_tilt", "on_stick", "stick_spin", "stick_critical_spin")  # None: left out
        attrs.update({k: v if k == "on_stick" else float(v) for k in optional if (v := getattr(self, k)) is not None})
        return xr.Dataset(data, attrs=attrs)


NEVER_INVERTS = {
    "hangs": "the tilted family does not reach the inverted state (class 'hangs'): launched upright, this top "
    "never inverts completely",
    "never_inverts": "the upright state is stable at high spin (class 'never_inverts'): launched upright, this top "
    "does not invert",
}


#: the product attribute of :meth:`Launch.to_dataset` (docs/datasets.md)
PRODUCT = "launch"


def inverts_above(top: Top, reference: float, alpha_v: float) -> float | None:
    """The launch spin (rad/s) above which the top launched upright inverts completely: the
    upright-equivalent spin ``J_inv / (sigma (1 + q))`` of the inverted branch point
    (:func:`stability.steady.branch.branch_points`, nondimensional with ``Omega = reference``
    rad/s; the answer does not depend on the reference). None unless the top's high-spin class
    (:func:`stability.top_class`) is ``"inverts"`` (the reason: :data:`NEVER_INVERTS`): a
    ``"never_inverts"`` top has an inverted branch point too, but its upright launch stays up."""
    from ..steady.branch import branch_points
    from ..steady.classes import top_class
    from ..steady.family import upright_jellett

    if top_class(q=top.q, sigma=top.sigma, mu=top.mu) != "inverts":
        return None
    nd = top.nondimensional(reference, alpha_v=None if top.mu_v is not None else alpha_v, model="sliding")
    nd = {k: float(nd[k]) for k in ("q", "sigma", "fr_inv", "alpha_v", "mu")}
    j_inv = branch_points(**nd)["inverted"]
    if not math.isfinite(j_inv):
        return None
    return j_inv / float(upright_jellett(q=nd["q"], sigma=nd["sigma"])) * reference


def launch(
    top: Top, spin: Any, *, unit: str = "rad/s", tilt: float = 1.0, alpha_v: Any = None, model: str = "sliding"
) -> Launch:
    """What a top does when it is spun at ``spin`` (in ``unit``) with its axis tilted by ``tilt``.

    Parameters
    ----------
    top : stability.Top
        The top in SI units (``mu_v`` gives ``alpha_v`` by eq. 7).
    spin : float
        Launch spin, in ``unit`` (0.1 to 1e4 rev/s).
    unit : {"rad/s", "rev/s", "rpm", "Hz"}
    tilt : float, default 1.0
        Initial tilt, degrees: ``omega = spin k``, ``k`` tilted in the x-z plane, centre at rest.
    alpha_v : float, optional
        Viscous parameter (eq. 7, with the launch spin as reference) when the top has no
        ``mu_v`` (giving both is an error); default 0.5, the paper's.
    model : {"sliding"}

    Returns
    -------
    Launch
        ``str()`` prints it in the caller's unit; ``.to_dataset()`` gives the Dataset.
    """
    from ..linear.critical import critical_spin
    from ..steady.classes import top_class
    from ..steady.final import final_state

    w, params, source = launch_parameters(top, spin, unit, alpha_v, model)
    tilt = float(tilt)
    reasons: dict[str, str] = {}
    nd = {k: params[k] for k in ("q", "sigma", "fr_inv", "alpha_v", "mu")}
    try:
        up = critical_spin(top, "sliding", "upright", alpha_v=nd["alpha_v"]).spin
    except ValueError as e:
        up = None
        reasons["unstable_above"] = str(e)
    cls = str(top_class(q=nd["q"], sigma=nd["sigma"], mu=nd["mu"]))
    inv = inverts_above(top, w, nd["alpha_v"])
    if inv is None:
        reasons["inverts_above"] = NEVER_INVERTS.get(cls, "the tilted family does not reach the inverted state")
    fs = final_state(**launch_state(tilt), **nd)
    stick = top.stick_contact()[0] if top.stick is not None else None
    run = run_launch(params, tilt=tilt, end_tilt=fs.tilt if math.isfinite(fs.tilt) else None, stick_tilt=stick)
    if run.crossing_time is None:
        reasons["flip_time"] = run.reason.split("; ")[0]
    settle = None if fs.kind == "unsettled" else run.settle_time
    if settle is None:
        reasons["settle_time"] = f"the end is not decided: {fs.reason}" if fs.kind == "unsettled" else run.reason
    ev, a = str(run.attrs.get("event", "none")), run.attrs
    event: dict[str, Any] = {}  # the event's fields of Launch (none: their defaults)
    after = f"{a.get('event_tilt', math.nan):.4g} degrees after {a.get('event_time', math.nan) / w:.3g} s"
    if ev != "none":
        event = dict(event=ev, event_time=float(a["event_time"]) / w, event_tilt=float(a["event_tilt"]))
    if ev == "stick_contact":
        # a top that reaches its stick spinning faster than the critical spin of the top on its stick
        # (stability.critical_spin of Top.on_stick, upright) spins on, else falls back; the spin about
        # the axis is a body quantity (on the stick's sphere, axis -k, the same number reversed)
        stick_spin = abs(a["event_spin"]) * w
        stick_critical = float(critical_spin(top.on_stick(), "sliding", "upright", alpha_v=nd["alpha_v"]).spin)
        on_stick = "spins" if stick_spin > stick_critical else "falls_back"
        event.update(on_stick=on_stick, stick_spin=stick_spin, stick_critical_spin=stick_critical)
        how = "spins on its stick" if on_stick == "spins" else "falls back"
        side = "above" if on_stick == "spins" else "below"
        reasons["end"] = (
            f"the motion reaches its stick at {after}, then {how} (spin {stick_spin:.4g} rad/s about its axis, "
            f"{side} the stick's critical spin {stick_critical:.4g} rad/s)"
        )
    elif ev != "none":  # the run stopped where the model stops holding: its end is not the prediction's
        reasons["end"] = (
            f"the sphere leaves the floor (normal force zero) at {after}: the sliding model no longer holds"
        )
    return Launch(
        spin=w,
        unit=unit,
        tilt=tilt,
        end_tilt=float(fs.tilt),
        unstable_above=up,
        inverts_above=inv,
        top_class=cls,
        end_kind=fs.kind,
        method=fs.method,
        flip_time=None if run.crossing_time is None else run.crossing_time / w,
        settle_time=None if settle is None else settle / w,
        min_normal_force=run.min_normal_force * (top.inertia_centre * w * w / top.radius),
        min_normal_force_nd=run.min_normal_force,
        parameters={k: params[k] for k in ("q", "mu", "sigma", "fr_inv", "alpha_v", "alpha_k") if k in params},
        alpha_v_source=source,
        reasons=reasons,
        **event,
    )
