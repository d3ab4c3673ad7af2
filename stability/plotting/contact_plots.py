"""Figures of where the model holds: a run's normal force and its event, a run's tilt up to the
stick, a run that flies and lands, a run that sticks and slips (computation in
:mod:`stability.nonlinear.contact`, :mod:`stability.nonlinear.flight`,
:mod:`stability.nonlinear.stickslip` and :func:`stability.simulate`)."""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np
import xarray as xr
from matplotlib.colors import TwoSlopeNorm

from ._layout import axes_or_new, run_panels

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

__all__ = ["plot_contact_loss_map", "plot_contact_run", "plot_flight_run", "plot_stick_slip"]


def _normal_force_panel(ax: Axes, t: np.ndarray, run: xr.Dataset) -> None:
    """The run's normal force ``N(t)`` with its equilibrium value ``mu fr_inv`` and zero."""
    ax.plot(t, run.normal_force.values, color="C0", label="N(t)")
    ax.axhline(run.attrs["mu"] * run.attrs["fr_inv"], color="0.5", ls=":", label=r"$\mu\,$Fr$^{-1}$ (equilibrium)")
    ax.axhline(0.0, color="k", lw=0.8)
    ax.set_ylabel("normal force N")


def plot_contact_run(run: xr.Dataset, *, axes: list[Axes] | None = None) -> tuple[Figure, list[Axes]]:
    """A run (:func:`stability.simulate`) with its event: the normal force ``N(t)`` (with its
    equilibrium value ``mu fr_inv`` and zero) and the tilt, the event marked (contact lost, or
    the stick reached, with the stick's tilt as a line).

    Parameters
    ----------
    run : xarray.Dataset
        A sliding or rolling run (its attributes ``event``, ``event_time``, ``stick_tilt``).
    axes : sequence of 2 Axes, optional

    Returns
    -------
    (Figure, list of 2 Axes)
    """
    fig, axes, t = run_panels(run, axes)
    event = run.attrs.get("event", "none")
    t_ev = float(run.attrs.get("event_time", math.nan))
    ax, ax2 = axes
    _normal_force_panel(ax, t, run)
    ax2.plot(t, run.polar_angle.values, color="C1", label="tilt")
    stick = float(run.attrs.get("stick_tilt", math.nan))
    if np.isfinite(stick):
        ax2.axhline(stick, color="C3", ls="--", label=f"stick touches ({stick:.4g}$^\\circ$)")
    ax2.set(ylabel="tilt of k (degree)", xlabel=r"time (units of $1/\Omega$)")
    if event != "none":
        what = "contact lost" if event == "contact_lost" else "stick reached"
        for a in axes:
            a.axvline(t_ev, color="C3", lw=0.8)
        ax.plot([t_ev], [float(run.normal_force[-1])], "o", color="C3", label=f"{what}, t = {t_ev:.6g}")
        ax2.plot([t_ev], [float(run.polar_angle[-1])], "o", color="C3")
    ax.legend(fontsize="small")
    ax2.legend(fontsize="small")
    ax.set_title(f"{run.attrs.get('model', '')} run: event {event}", fontsize="medium")
    return fig, axes


def plot_flight_run(run: xr.Dataset, *, axes: list[Axes] | None = None) -> tuple[Figure, list[Axes]]:
    """A run with flights (``simulate(..., on_contact_loss="continue")``): the normal force
    ``N(t)`` (0 in flight) and the height of the sphere's lowest point, the take-offs and landings
    marked.

    Parameters
    ----------
    run : xarray.Dataset
        A run with the variables ``contact``, ``height`` and the attributes ``takeoff_times``,
        ``landing_times``.
    axes : sequence of 2 Axes, optional

    Returns
    -------
    (Figure, list of 2 Axes)
    """
    fig, axes, t = run_panels(run, axes)
    ax, ax2 = axes
    _normal_force_panel(ax, t, run)
    ax2.plot(t, run.height.values, color="C1", label="height of the lowest point")
    ax2.axhline(0.0, color="k", lw=0.8)
    ax2.set(ylabel="height (units of R)", xlabel=r"time (units of $1/\Omega$)")
    ups = np.atleast_1d(run.attrs.get("takeoff_times", []))
    downs = np.atleast_1d(run.attrs.get("landing_times", []))
    for times, colour, line, label in ((ups, "C3", "-", "take-off"), (downs, "C2", "--", "landing (plastic impact)")):
        for i, tt in enumerate(times):
            for a in axes:
                a.axvline(tt, color=colour, lw=0.8, ls=line, label=label if (i == 0 and a is ax) else None)
    ax.legend(fontsize="small")
    ax2.legend(fontsize="small")
    ax.set_title(f"{run.attrs.get('model', '')} run: {len(ups)} flight(s), {len(downs)} landing(s)", fontsize="medium")
    return fig, axes


def plot_contact_loss_map(ds: xr.Dataset, *, ax: Axes | None = None) -> tuple[Figure, Axes]:
    """The contact-loss map (:func:`stability.contact_loss_boundary`): the smallest normal force
    of the launch's run over the grid as colour (units of ``M g``, diverging about 0), the
    boundary ``N_min = 0`` traced by continuation as a line.

    Parameters
    ----------
    ds : xarray.Dataset
        Product ``contact_loss_map``.
    ax : Axes, optional

    Returns
    -------
    (Figure, Axes)
    """
    fig, ax = axes_or_new(ax)
    z = ds.min_normal_force.values
    lo, hi = float(np.nanmin(z)), float(np.nanmax(z))
    norm = TwoSlopeNorm(0.0, vmin=min(lo, -1e-3), vmax=max(hi, 1e-3))
    mesh = ax.pcolormesh(ds.x.values, ds.y.values, z, cmap="RdBu", norm=norm, shading="nearest")
    fig.colorbar(mesh, ax=ax, label=r"smallest normal force $N_{min}$ / $Mg$")
    if ds.sizes.get("point", 0):
        piece = ds.boundary_piece.values
        for n in np.unique(piece):  # each smooth piece (they meet at kinks of N_min)
            sel, label = piece == n, "$N_{min} = 0$ (traced)" if n == piece[0] else None
            ax.plot(ds.boundary_x.values[sel], ds.boundary_y.values[sel], color="k", ls="-", lw=1.6, label=label)
        ax.legend(fontsize="small", loc="best")
    xl, yl = (ds[c].attrs for c in ("x", "y"))
    ax.set(xlabel=f"{xl['long_name']} ({xl['units']})", ylabel=f"{yl['long_name']} ({yl['units']})")
    held = ", ".join(
        f"{k.removeprefix('launch_').replace('_', ' ')} {v:g}" for k, v in ds.attrs.items() if k.startswith("launch_")
    )
    ax.set_title(f"where the launch loses its contact ({held}; {ds.attrs['duration']:g} s)", fontsize="medium")
    return fig, ax


def plot_stick_slip(run: xr.Dataset, *, axes: list[Axes] | None = None) -> tuple[Figure, list[Axes]]:
    """A hybrid run (:func:`stability.stick_slip`): the slip speed ``|V_c|`` against time with
    the switches marked (stick: down triangles, slip: up triangles) and the stick phases shaded;
    below, the friction force against its static limit ``alpha_s n`` and its kinetic value.

    Parameters
    ----------
    run : xarray.Dataset
        The run (variables ``phase``, ``slip_speed``, ``friction_magnitude``, ``friction_limit``
        and the ``switch_*`` variables).
    axes : sequence of 2 Axes, optional

    Returns
    -------
    (Figure, list of 2 Axes)
    """
    fig, axes, t = run_panels(run, axes)
    stuck = run.phase.values == 1
    ax, ax2 = axes
    ax.plot(t, run.slip_speed.values, color="C0", lw=1.0, label=r"slip speed $|V_c|$")
    # stick phases: shaded from the stick switch (the last sample of the slip phase before) to
    # the phase's last sample (the slip switch, or the end of the run)
    for a in np.flatnonzero(stuck & ~np.r_[False, stuck[:-1]]):
        rest = np.flatnonzero(~stuck[a:])
        b = a + rest[0] - 1 if rest.size else t.size - 1
        for x in axes:
            x.axvspan(t[max(a - 1, 0)], t[b], color="0.9", lw=0)
    kinds = run.switch_kind.values
    times = run.switch_time.values
    for kind, marker, color in (("stick", "v", "C2"), ("slip", "^", "C3"), ("transit", "x", "C4")):
        sel = kinds == kind
        if sel.any():
            ax.plot(times[sel], np.zeros(sel.sum()), marker, color=color, ls="none", label=f"{kind} ({sel.sum()})")
    ax.set_ylabel(r"slip speed $|V_c|$ ($\Omega R$)")
    ax.legend(fontsize="small")
    ax2.plot(t, run.friction_magnitude.values, color="C1", lw=1.0, label="friction |f|")
    ax2.plot(t, run.friction_limit.values, color="C3", ls="--", lw=0.8, label=r"static limit $\alpha_s n$")
    ax2.axhline(run.attrs["alpha_k"], color="0.4", ls=":", lw=0.8, label=r"kinetic $\alpha_K$")
    ax2.set(ylabel="friction force", xlabel=r"time (units of $1/\Omega$; stick phases shaded)")
    ax2.legend(fontsize="small")
    ax.set_title(
        f"stick and slip: alpha_k = {run.attrs['alpha_k']:.3g}, alpha_s = {run.attrs['alpha_s']:.3g}, "
        f"{run.attrs['n_switches']} switches",
        fontsize="medium",
    )
    return fig, axes
