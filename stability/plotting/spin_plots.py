"""The critical spin rate of a real top against one of its nondimensional parameters."""

from __future__ import annotations

import xarray as xr
from matplotlib.axes import Axes
from matplotlib.figure import Figure

from ..parameters import SYMBOLS
from ._layout import axes_or_new

__all__ = ["plot_critical_spin"]


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
