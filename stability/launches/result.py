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

from .._version import package_version
from ..products import PRODUCT_ATTR
from ..top import Top, from_rad_per_s, spin_text
from .flip import launch_parameters, run_launch

__all__ = ["PRODUCT", "Launch", "inverts_above", "launch", "stick_answer"]


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

    def _spin(self, w: float | None, name: str) -> str:
        if w is None:
            return f"none ({self.reasons.get(name, '')})"
        return spin_text(w, self.unit)

    def _time(self, t: float | None, name: str) -> str:
        if t is None:
            return f"never ({self.reasons.get(name, '')})"
        return f"{t:.4g} s ({t * self.spin / (2 * math.pi):.4g} spin periods)"

    def __str__(self) -> str:
        p = self.parameters
        lines = [
            f"launch at {self._spin(self.spin, 'spin')}, axis tilted {self.tilt:g} deg from the vertical, centre at rest",
            f"  the upright top becomes unstable above:        {self._spin(self.unstable_above, 'unstable_above')}",
            f"  launched upright, it inverts completely above: {self._spin(self.inverts_above, 'inverts_above')}",
            f"  high-spin class: {self.top_class}",
            (
                f"  ends: {self.reasons['end']} (the sphere model alone would end {self.end_kind} at "
                f"{self.end_tilt:.4g} degrees, by {self.method})"
                if self.event != "none"
                else f"  ends: {self.end_kind} at {self.end_tilt:.4g} degrees (decided by {self.method})"
            ),
            f"  time to 90 degrees: {self._time(self.flip_time, 'flip_time')}",
            f"  settles (within 1 degree of its end) after: {self._time(self.settle_time, 'settle_time')}",
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
        nan = math.nan

        def var(name: str, long_name: str, units: str) -> tuple:
            v = getattr(self, name)
            attrs = {"long_name": long_name, "units": units}
            if v is None:
                attrs["comment"] = self.reasons.get(name, "")
            return ((), nan if v is None else float(v), attrs)

        force = "smallest normal force along the run"
        data = {  # variable: var(field, long name, units)
            "spin": var("spin", "launch spin", "rad s-1"),
            "initial_tilt": var("tilt", "initial tilt of the axis", "degree"),
            "unstable_above": var("unstable_above", "spin above which the upright top is unstable", "rad s-1"),
            "inverts_above": var("inverts_above", "launch spin above which the top inverts completely", "rad s-1"),
            "end_tilt": var("end_tilt", "tilt where the launch ends", "degree"),
            "flip_time": var("flip_time", "time until the axis first crosses 90 degrees", "s"),
            "settle_time": var("settle_time", "time until the tilt stays within 1 degree of its end", "s"),
            "min_normal_force": var("min_normal_force", force, "N"),
            "min_normal_force_nd": var("min_normal_force_nd", force, "A0 Omega2 R-1"),
        }
        attrs = {
            "Conventions": "CF-1.10",
            PRODUCT_ATTR: PRODUCT,
            "title": "launch of a real top",
            "source": f"tippe-stability {package_version()}",
            "unit": self.unit,
            "top_class": self.top_class,
            "end_kind": self.end_kind,
            "method": self.method,
            "alpha_v_source": self.alpha_v_source,
            "event": self.event,
            **{k: float(v) for k, v in self.parameters.items()},
        }
        if self.event_time is not None:
            attrs.update(event_time=float(self.event_time), event_tilt=float(self.event_tilt))
        if self.on_stick is not None:
            attrs.update(
                on_stick=self.on_stick,
                stick_spin=float(self.stick_spin),  # type: ignore[arg-type]
                stick_critical_spin=float(self.stick_critical_spin),  # type: ignore[arg-type]
            )
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


def stick_answer(top: Top, spin: float, alpha_v: float) -> tuple[str, float, float]:
    """What a top that reaches its stick spinning at ``spin`` rad/s about its symmetry axis
    does: ``("spins", spin, critical)`` if ``spin`` is above the critical spin of the top on its
    stick (:func:`stability.critical_spin` of :meth:`stability.Top.on_stick`, upright: the
    spin above which the upright spin on the tip is stable, the tip's sphere with its own
    ``q' = (tip_center - com_offset) / tip_radius``), ``("falls_back", spin, critical)`` below.

    The spin about the axis is a body quantity: on the stick's sphere (axis ``k' = -k``) it is
    the same number reversed, and the upright state's stability does not depend on the sense.
    ``alpha_v`` is used only when the top has no ``mu_v`` (the sliding threshold does not
    depend on ``alpha_v > 0``: :func:`stability.critical_spin`)."""
    from ..linear.critical import critical_spin

    on = top.on_stick()
    crit = critical_spin(on, "sliding", "upright", alpha_v=alpha_v).spin
    return ("spins" if spin > crit else "falls_back"), float(spin), float(crit)


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
    from .flip import launch_state

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
    start = launch_state(tilt)
    fs = final_state(omega=start["omega"], k=start["k"], velocity=start["velocity"], **nd)
    stick = top.stick_contact()[0] if top.stick is not None else None
    run = run_launch(params, tilt=tilt, end_tilt=fs.tilt if math.isfinite(fs.tilt) else None, stick_tilt=stick)
    if run.crossing_time is None:
        reasons["flip_time"] = run.reason.split("; ")[0]
    settle = run.settle_time
    if fs.kind == "unsettled":
        settle = None
        reasons["settle_time"] = f"the end is not decided: {fs.reason}"
    elif settle is None:
        reasons["settle_time"] = run.reason
    force_unit = top.inertia_centre * w * w / top.radius
    ev = str(run.attrs.get("event", "none"))
    on_stick = stick_spin = stick_critical = None
    if ev == "stick_contact":
        on_stick, stick_spin, stick_critical = stick_answer(top, abs(run.attrs["event_spin"]) * w, nd["alpha_v"])
    if ev != "none":  # the run stopped where the model stops holding: its end is not the prediction's
        reasons["end"] = (
            f"the motion reaches its stick at {run.attrs['event_tilt']:.4g} degrees after "
            f"{run.attrs['event_time'] / w:.3g} s, then "
            + (
                f"spins on its stick (spin {stick_spin:.4g} rad/s about its axis, above the stick's "
                f"critical spin {stick_critical:.4g} rad/s)"
                if on_stick == "spins"
                else f"falls back (spin {stick_spin:.4g} rad/s about its axis, below the stick's critical "
                f"spin {stick_critical:.4g} rad/s)"
            )
            if ev == "stick_contact"
            else f"the sphere leaves the floor (normal force zero) at {run.attrs['event_tilt']:.4g} "
            f"degrees after {run.attrs['event_time'] / w:.3g} s: the sliding model no longer holds"
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
        min_normal_force=run.min_normal_force * force_unit,
        min_normal_force_nd=run.min_normal_force,
        parameters={k: params[k] for k in ("q", "mu", "sigma", "fr_inv", "alpha_v", "alpha_k") if k in params},
        alpha_v_source=source,
        event=str(ev),
        event_time=float(run.attrs["event_time"]) / w if ev != "none" else None,
        event_tilt=float(run.attrs["event_tilt"]) if ev != "none" else None,
        on_stick=on_stick,
        stick_spin=stick_spin,
        stick_critical_spin=stick_critical,
        reasons=reasons,
    )
