"""Figures of a real top: its critical spin rates, the flip times of its launches, and the error of
the cheap flip-time estimates."""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import xarray as xr
from matplotlib.axes import Axes
from matplotlib.figure import Figure

from ..parameters import SYMBOLS
from ._layout import axes_or_new

__all__ = ["plot_critical_spin", "plot_flip_estimates", "plot_flip_time"]


def plot_flip_time(
    ds: xr.Dataset, *, ax: Axes | None = None, marks: Sequence[tuple[float, float, str]] = (), estimate: bool = True
) -> tuple[Figure, Axes]:
    """Time to 90 degrees (s) against launch spin, one line per initial tilt.

    Parameters
    ----------
    ds : xarray.Dataset
        Product ``flip_time_map`` (:func:`stability.launches.estimate.flip_time_map`).
    ax : matplotlib.axes.Axes, optional
    marks : sequence of (spin, seconds, label)
        Points to mark (e.g. the paper's runs), spin in the dataset's unit.
    estimate : bool, default True
        Draw the e-folding estimate dotted beside each line, when the dataset has it.

    Returns
    -------
    (Figure, Axes)
    """
    fig, ax = axes_or_new(ax)
    spin = ds.spin.values
    for i, th in enumerate(ds.tilt.values):
        (line,) = ax.plot(
            spin, ds.flip_time.values[i], marker="o", markersize=2.5, label=f"tilt {th:g} deg: simulation"
        )
        if estimate and "flip_time_efold" in ds:
            label = f"tilt {th:g} deg: {ds.flip_time_efold.attrs.get('long_name', 'estimate').split(' of ')[0]}"
            ax.plot(spin, ds.flip_time_efold.values[i], ls=":", color=line.get_color(), label=label)
    for s, t, label in marks:
        ax.plot([s], [t], marker="*", markersize=11, color="k", ls="none")
        ax.annotate(label, (s, t), textcoords="offset points", xytext=(6, 4), fontsize=8)
    ax.set_yscale("log")
    ax.set_xlabel(f"launch spin ({ds.attrs.get('spin_unit', ds.spin.attrs.get('units', ''))})")
    ax.set_ylabel("time until the axis crosses 90 degrees (s)")
    ax.set_title(
        f"launched with the axis tilted, centre at rest: q = {ds.attrs['q']:.3g}, mu = {ds.attrs['mu']:.3g}, "
        f"sigma = {ds.attrs['sigma']:.3g}, R = {1e3 * ds.attrs['radius_m']:.2f} mm",
        fontsize=8,
    )
    ax.legend(fontsize=7)
    return fig, ax


def plot_flip_estimates(records: Sequence[dict[str, Any]], *, ax: Axes | None = None) -> tuple[Figure, Axes]:
    """Error against cost of the flip-time estimates (records of ``benchmarks/flip_estimates.py``:
    ``method``, ``seconds`` per launch, ``rel_error`` against the simulation)."""
    fig, ax = axes_or_new(ax)
    for method in dict.fromkeys(r["method"] for r in records):
        rs = [r for r in records if r["method"] == method]
        ax.scatter([r["seconds"] for r in rs], [max(r["rel_error"], 1e-16) for r in rs], s=12, label=method)
    ax.set(xscale="log", yscale="log", xlabel="seconds per launch", ylabel="relative error of the flip time")
    ax.legend(fontsize=8)
    return fig, ax


def plot_critical_spin(ds: xr.Dataset, *, ax: Axes | None = None) -> tuple[Figure, Axes]:
    """Upright and inverted critical spin rates (rpm) against the dataset's one dimension.

    Parameters
    ----------
    ds : xarray.Dataset
        From :func:`stability.recipes.critical_spin_dataset`.
    ax : matplotlib.axes.Axes, optional

    Returns
    -------
    (Figure, Axes)
    """
    fig, ax = axes_or_new(ax)
    (x,) = ds["critical_spin_upright"].dims
    for o, marker, label in (
        ("upright", "o", "upright: unstable above"),
        ("inverted", "s", "inverted (q -> -q): stable above"),
    ):
        ax.plot(ds[x].values, ds[f"critical_spin_{o}"].values, marker=marker, markersize=3, label=label)
    ax.set_xlabel(SYMBOLS.get(x, x) + ("  (upright offset; inverted: -q)" if x == "q" else ""))
    ax.set_ylabel("critical spin rate (rpm)")
    fixed = ", ".join(f"{SYMBOLS.get(k, k)} = {ds.attrs[k]:.3g}" for k in ("q", "sigma", "mu") if k != x)
    ax.set_title(
        f"{ds.attrs.get('preset', '')} top, R = {1e3 * ds.attrs['radius_m']:.2f} mm, {fixed}, "
        f"{ds.attrs.get('model', '')} model",
        fontsize=9,
    )
    ax.legend()
    return fig, ax
