"""Composite figures made of the atlas plots."""

from __future__ import annotations

import xarray as xr
from matplotlib.figure import Figure

from .atlas_plots import plot_growth_rate

__all__ = ["atlas_figure"]


def atlas_figure(ds: xr.Dataset, x: str = "q") -> Figure:
    """Two panels: leading growth rate and its frequency against ``x`` (as in Fig. 3a-b).

    Parameters
    ----------
    ds : xarray.Dataset
        An atlas with ``x`` and at most one more grid dimension.
    x : str
        The abscissa.

    Returns
    -------
    matplotlib.figure.Figure
    """
    fig = Figure(figsize=(6.4, 6.4), layout="constrained")
    ax1, ax2 = fig.subplots(2, 1, sharex=True)
    plot_growth_rate(ds, x, quantity="growth_rate", ax=ax1)
    plot_growth_rate(ds, x, quantity="frequency", ax=ax2)
    ax1.set_xlabel("")
    ax2.set_title("")
    ax2.get_legend().remove()
    return fig
