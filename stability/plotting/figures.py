"""Composite figures made of the atlas plots, and the figure of an atlas by its grid."""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import xarray as xr
from matplotlib.axes import Axes
from matplotlib.figure import Figure

from ..errors import InputError
from ..grids.netcdf import require_atlas
from ._layout import panels_or_new
from .atlas_plots import plot_growth_rate
from .maps import plot_stability_map

__all__ = ["atlas_figure", "plot_atlas"]


def atlas_figure(ds: xr.Dataset, x: str = "q", *, axes: Sequence[Axes] | None = None) -> tuple[Figure, list[Axes]]:
    """Two panels: leading growth rate and its frequency against ``x`` (as in Fig. 3a-b).

    Parameters
    ----------
    ds : xarray.Dataset
        An atlas with ``x`` and at most one more grid dimension.
    x : str
        The abscissa.
    axes : sequence of 2 Axes, optional
        Where to draw; a new figure (the panels sharing x) by default.

    Returns
    -------
    (Figure, list of 2 Axes)
    """
    fig, axes = panels_or_new(axes, 2, (6.4, 6.4), sharex=True)
    _quantity_panels(ds, x, ("growth_rate", "frequency"), axes)
    return fig, axes


def _quantity_panels(ds: xr.Dataset, x: str, quantities: Sequence[str], axes: Sequence[Axes]) -> None:
    """:func:`~stability.plotting.atlas_plots.plot_growth_rate` of each quantity in a column of
    panels sharing ``x``: the title and legend on the first panel only, the abscissa's label on
    the last."""
    for k, (ax, quantity) in enumerate(zip(axes, quantities)):
        plot_growth_rate(ds, x, quantity=quantity, ax=ax)
        if k:
            ax.set_title("")
            ax.get_legend().remove()
        if k < len(quantities) - 1:
            ax.set_xlabel("")


def plot_atlas(
    ds: xr.Dataset, x: str | None = None, y: str | None = None, *, ax: Axes | None = None, **kw: Any
) -> tuple[Figure, Axes]:
    """The figure of an atlas chosen by its grid (what ``ds.tippe.plot()`` draws for an atlas).

    One grid dimension: the growth rate against it (:func:`~stability.plotting.atlas_plots.plot_growth_rate`);
    two: the stability map over them (:func:`~stability.plotting.maps.plot_stability_map`). For
    lines of one family over a two-dimensional grid, call ``plot_growth_rate`` (or
    :func:`atlas_figure`) with the abscissa.

    Parameters
    ----------
    ds : xarray.Dataset
        An atlas with one or two grid dimensions (select the others first, ``ds.sel(...)``).
    x, y : str, optional
        Abscissa and (maps) ordinate; default the grid dimensions in their order (``q``,
        ``fr_inv``, ``sigma``, ``alpha_v``, ``mu``).
    ax : matplotlib.axes.Axes, optional
    **kw
        Passed on to the function drawn (``quantity``, ``mode``; ``colorbar``, ``norm``, ``curve``).

    Returns
    -------
    (Figure, Axes)
    """
    require_atlas(ds)
    grid = list(ds["stability"].dims)
    if len(grid) == 1:
        if y is not None:
            raise InputError(f"y = {y!r}: the atlas has one grid dimension ({grid[0]}); a line plot has no y")
        return plot_growth_rate(ds, grid[0] if x is None else x, ax=ax, **kw)
    if len(grid) == 2:
        x = grid[0] if x is None else x
        y = next((d for d in grid if d != x), grid[1]) if y is None else y
        return plot_stability_map(ds, x, y, ax=ax, **kw)
    raise InputError(
        f"the atlas has {len(grid)} grid dimensions ({', '.join(grid) or 'none'}); its figure "
        "needs one (a line plot) or two (a stability map): select the others first (ds.sel(...))"
    )
