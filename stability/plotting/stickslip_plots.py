"""Figure of a stick-slip run (computation in :mod:`stability.nonlinear.stickslip`)."""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
import xarray as xr

from ._layout import run_panels

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

__all__ = ["plot_stick_slip"]


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
