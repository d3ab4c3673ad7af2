"""Figures of the tumbling runs of Sec. 3(ii): Figs. 5-9, drawn from simulate() datasets.

Time axes are in spin periods (``t / 2 pi``, one period being ``2 pi / Omega``), as in the paper.
Every function takes datasets and an optional ``ax`` / ``axes`` and returns ``(Figure, Axes)``
(``(Figure, list of Axes)`` for several panels); none computes a run. :func:`plot_run` draws any
one run (what ``ds.tippe.plot()`` draws for a :func:`stability.simulate` dataset).
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import xarray as xr
from matplotlib.axes import Axes
from matplotlib.figure import Figure

from ..errors import InputError
from ._layout import PERIODS_LABEL, axes_or_new, panels_or_new, periods

__all__ = ["fig5", "fig6", "fig7", "fig8", "fig9", "plot_run"]


def fig5(runs: dict[str, xr.Dataset], *, axes: Sequence[Axes] | None = None) -> tuple[Figure, list[Axes]]:
    """Fig. 5: (a) spin, (b) transverse angular rate, (c) polar angle against time.

    Parameters
    ----------
    runs : dict
        Label -> run (one line per run, e.g. ``Fr^-1 = 0.3`` and ``0.1``).
    axes : sequence of 3 Axes, optional
        Where to draw; a new figure by default.

    Returns
    -------
    (Figure, list of 3 Axes)
    """
    fig, axes = panels_or_new(axes, 3, (6.4, 7.6), sharex=True)
    for label, ds in runs.items():
        t = periods(ds)
        axes[0].plot(t, ds.spin.values, label=label)
        axes[1].plot(t, ds.transverse_rate.values, label=label)
        axes[2].plot(t, ds.polar_angle.values, label=label)
    axes[0].set_ylabel(r"spin $\omega\cdot k$ / $\Omega$")
    axes[1].set_ylabel(r"transverse rate $|\omega_\perp|$ / $\Omega$")
    axes[2].set_ylabel(r"polar angle of $k$ (deg)")
    axes[2].axhline(90.0, color="0.3", linewidth=0.8, zorder=0)
    axes[2].set_xlabel(PERIODS_LABEL)
    axes[0].legend()
    for ax, tag in zip(axes, "abc"):
        ax.set_title(f"({tag})", loc="left", fontsize=9)
    return fig, axes


def plot_run(run: xr.Dataset, *, axes: Sequence[Axes] | None = None) -> tuple[Figure, list[Axes]]:
    """One nonlinear run (:func:`stability.simulate`): spin, transverse angular rate and polar
    angle against time, the panels of Fig. 5 (:func:`fig5`).

    Parameters
    ----------
    run : xarray.Dataset
        A run; its legend label is its ``label`` attribute (set by the scene recipes), else
        the model and ``fr_inv``.
    axes : sequence of 3 Axes, optional

    Returns
    -------
    (Figure, list of 3 Axes)
    """
    label = run.attrs.get("label") or f"{run.attrs.get('model', '')} model, Fr$^{{-1}}$ = {run.attrs['fr_inv']:g}"
    return fig5({label: run}, axes=axes)


def fig6(run: xr.Dataset, *, ax: Axes | None = None) -> tuple[Figure, Axes]:
    """Fig. 6: the energy components against time (energy in units of ``A0 Omega^2``).

    Returns
    -------
    (Figure, Axes)
    """
    fig, ax = axes_or_new(ax, figsize=(6.4, 4.2), layout="constrained")
    t = periods(run)
    parts = [
        ("energy", "total"),
        ("kinetic_spin", "spin (about G)"),
        ("kinetic_transverse", "transverse rotation"),
        ("kinetic_translational", "translation of G"),
        ("potential", "potential"),
    ]
    for name, label in parts:
        ax.plot(t, run[name].values, label=label)
    ax.set(xlabel=PERIODS_LABEL, ylabel=r"energy / $A_0 \Omega^2$")
    ax.legend(ncols=2)
    return fig, ax


def fig7(
    run: xr.Dataset, *, arrow_every: float = 5.0, zoom_periods: float = 10.0, axes: Sequence[Axes] | None = None
) -> tuple[Figure, list[Axes]]:
    """Fig. 7: the locus of the sphere's centre, (a) whole and (b) magnified start.

    Arrows show the centre's velocity every ``arrow_every`` time units (the paper's
    ``5 / (2 pi)`` spin periods) in (a) and every time unit in (b).

    Returns
    -------
    (Figure, list of 2 Axes)
    """
    fig, (ax1, ax2) = panels_or_new(axes, 2, (9.6, 4.4), row=True)
    x, y = run.position.sel(axis=1).values, run.position.sel(axis=2).values
    vx, vy = run.velocity.sel(axis=1).values, run.velocity.sel(axis=2).values
    t = run.time.values
    dt = float(t[1] - t[0])
    for ax, every, tmax in ((ax1, arrow_every, t[-1]), (ax2, 1.0, zoom_periods * (2.0 * np.pi))):
        sel = t <= tmax
        ax.plot(x[sel], y[sel], color="C0", linewidth=1.0)
        step = max(1, int(round(every / dt)))
        idx = np.arange(0, int(sel.sum()), step)
        ax.quiver(x[idx], y[idx], vx[idx], vy[idx], color="C1", angles="xy", width=0.003)
        ax.set_aspect("equal", adjustable="datalim")
        ax.set(xlabel=r"$X_0 / R$", ylabel=r"$Y_0 / R$")
    ax1.set_title("(a) whole run", loc="left", fontsize=9)
    ax2.set_title(f"(b) first {zoom_periods:g} spin periods", loc="left", fontsize=9)
    return fig, [ax1, ax2]


def fig8(run: xr.Dataset, *, until_angle: float = 150.0, ax: Axes | None = None) -> tuple[Figure, Axes]:
    """Fig. 8: the axis ``k`` on the unit sphere, coloured by time.

    Drawn from the start until the polar angle first reaches ``until_angle`` degrees (the
    flip; afterwards the axis circles the lower pole for the rest of the run); the subtitle
    says so and gives the run's last polar angle (where it ends: the circle of the steady
    tilted state of its Jellett level, 166.018 deg for the paper's Fr^-1 = 0.3 run). The path winds
    round the vertical once per precession period (~165 times at Fr^-1 = 0.3), so a single
    colour would fill the sphere; the colour (time in spin periods, colour bar) shows the
    drift from the north pole to the south. Seen from slightly above the equator, back half
    included (the wireframe is light).

    Parameters
    ----------
    run : xarray.Dataset
        A :func:`stability.simulate` run with ``k`` and ``polar_angle``.
    until_angle : float
        Polar angle (degrees) at which the path stops.
    ax : mpl_toolkits.mplot3d.Axes3D, optional
        A 3-D Axes to draw into; a new figure is made if omitted.

    Returns
    -------
    (Figure, Axes3D)
    """
    from mpl_toolkits.mplot3d.art3d import Line3DCollection

    if ax is not None and getattr(ax, "name", "") != "3d":
        raise InputError("ax must be a 3-D Axes (projection='3d') for Fig. 8")
    fig, ax = axes_or_new(ax, figsize=(5.6, 5.2), layout="constrained", projection="3d")
    u, v = np.mgrid[0 : 2 * np.pi : 40j, 0 : np.pi : 20j]
    ax.plot_wireframe(np.cos(u) * np.sin(v), np.sin(u) * np.sin(v), np.cos(v), color="0.85", linewidth=0.25)
    pol = run.polar_angle.values
    past = np.nonzero(pol >= until_angle)[0]
    end = int(past[0]) + 1 if past.size else pol.size
    k = run.k.values[:end]
    times = periods(run)[:end]
    pts = k.reshape(-1, 1, 3)
    lines = Line3DCollection(np.concatenate([pts[:-1], pts[1:]], axis=1), cmap="viridis", linewidths=0.45)
    lines.set_array(0.5 * (times[:-1] + times[1:]))
    ax.add_collection3d(lines)
    fig.colorbar(lines, ax=ax, shrink=0.6, pad=0.08, label=PERIODS_LABEL)
    for lim in (ax.set_xlim, ax.set_ylim, ax.set_zlim):
        lim(-1.0, 1.0)
    for ticks in (ax.set_xticks, ax.set_yticks, ax.set_zticks):
        ticks([-1.0, 0.0, 1.0])
    ax.set(xlabel="$K_1$", ylabel="$K_2$", zlabel="$K_3$")
    ax.view_init(elev=12, azim=-60)
    ax.set_box_aspect((1, 1, 1))
    ax.set_title(
        f"drawn from the start until the polar angle reaches {until_angle:g} deg; "
        f"the run ends at {float(pol[-1]):.3f} deg",
        fontsize=9,
    )
    return fig, ax


def fig9(
    sliding: xr.Dataset,
    rolling: xr.Dataset,
    cases: dict[str, xr.Dataset],
    paper_scheme: dict[str, xr.Dataset],
    slip_case: str,
    *,
    axes: Sequence[Axes] | None = None,
) -> tuple[Figure, list[Axes]]:
    """Fig. 9: (a) friction, sliding vs rolling; (b) polar angle for the friction cases;
    (c) sliding speed of one case.

    Parameters
    ----------
    sliding, rolling : xarray.Dataset
        Runs of the sliding and rolling spheres from the same initial conditions.
    cases : dict
        Label -> run of each friction case, integrated to tolerance (solid lines).
    paper_scheme : dict
        Label -> the same cases with the paper's fixed-step RK4 and sign law (16) (dotted).
    slip_case : str
        Label of the case whose sliding speed is drawn in (c) (from ``paper_scheme`` and
        ``cases``).
    axes : sequence of 3 Axes, optional
        Where to draw; a new figure by default.

    Returns
    -------
    (Figure, list of 3 Axes)
    """
    fig, (ax1, ax2, ax3) = panels_or_new(axes, 3, (6.4, 9.0))
    ax1.plot(periods(sliding), sliding.friction_magnitude.values, label="sliding model")
    ax1.plot(periods(rolling), rolling.friction_magnitude.values, linestyle=":", label="rolling model")
    ax1.set_ylabel(r"$|f|$ / $A_0\Omega^2 R^{-1}$")
    # the start from rest in the contact (a slip impulse) peaks far above the rest of the run:
    # the axis is scaled to the run after the first two periods and the peak is named
    later = periods(sliding) > 2.0
    peak = float(np.nanmax(sliding.friction_magnitude.values))
    top = 1.25 * float(
        np.nanmax(np.concatenate([sliding.friction_magnitude.values[later], rolling.friction_magnitude.values]))
    )
    if peak > top:
        ax1.set_ylim(0.0, top)
        where = dict(xy=(0.0, top), xytext=(0.06, 0.93), textcoords="axes fraction", fontsize=7, va="top")
        ax1.annotate(f"initial slip transient, peak {peak:.3g} (off scale)", **where)
    ax1.legend(loc="upper right")
    markers = ("o", "s", "^", "D", "v", "P")
    # the cases that stick coincide (polar angle ~9 deg): a marker per case keeps each visible
    for runs, line, width, name in ((cases, "-", 0.8, "{}"), (paper_scheme, ":", 1.0, "{}, paper's scheme")):
        for j, (label, ds) in enumerate(runs.items()):
            marks = {"marker": markers[j % len(markers)], "markevery": (0.03 * (j + 1), 0.12), "markersize": 4}
            style = dict(color=f"C{j}", linestyle=line, linewidth=width, **(marks if line == "-" else {}))
            ax2.plot(periods(ds), ds.polar_angle.values, **style, label=name.format(label))
    ax2.set_ylabel("polar angle of $k$ (deg)")
    ax2.legend(fontsize=7, ncols=2, loc="upper center", bbox_to_anchor=(0.5, -0.25), frameon=False)
    for ds, style, label in (
        (cases[slip_case], "-", "integrated to tolerance"),
        (paper_scheme[slip_case], ":", "paper's scheme (RK4, sign law)"),
    ):
        ax3.semilogy(periods(ds), np.maximum(ds.slip_speed.values, 1e-12), linestyle=style, label=label)
    ax3.set_ylabel(r"sliding speed $|V_c|$ / $\Omega R$")
    ax3.legend(fontsize=8)
    for ax, tag in zip((ax1, ax2, ax3), ("(a)", "(b)", f"(c) case {slip_case}")):
        ax.set_title(tag, loc="left", fontsize=9)
        ax.set_xlabel(PERIODS_LABEL)
    return fig, [ax1, ax2, ax3]
