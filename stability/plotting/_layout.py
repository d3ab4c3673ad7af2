"""Where a plotting function draws: the caller's Axes, or a new figure's (the one place of that rule)."""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

import numpy as np
from matplotlib.axes import Axes
from matplotlib.figure import Figure

from ..errors import InputError

if TYPE_CHECKING:
    import xarray as xr

__all__ = ["PERIODS_LABEL", "axes_or_new", "panels_or_new", "periods", "run_panels"]

#: the label of a time axis in spin periods (one period is ``2 pi / Omega``), as the paper draws them
PERIODS_LABEL = r"time (spin periods $2\pi/\Omega$)"


def periods(run: xr.Dataset) -> np.ndarray:
    """A run's times ``run.time`` in spin periods, ``t / 2 pi``."""
    return run.time.values / (2.0 * np.pi)


def axes_or_new(
    ax: Axes | None, *, figsize: tuple[float, float] | None = None, layout: str | None = None, **subplot_kw: Any
) -> tuple[Figure, Axes]:
    """``ax`` and its figure, or a new figure (``figsize``, ``layout``) with one Axes
    (``Figure.add_subplot(**subplot_kw)``, e.g. ``projection="3d"``)."""
    if ax is None:
        fig = Figure(figsize=figsize, layout=layout)
        return fig, fig.add_subplot(**subplot_kw)
    return ax.figure, ax


def panels_or_new(
    axes: Sequence[Axes] | None, n: int, figsize: tuple[float, float], *, row: bool = False, **subplots_kw: Any
) -> tuple[Figure, list[Axes]]:
    """The caller's ``n`` Axes and their figure, or a new figure (constrained layout) of ``n``
    panels in a column (a row if ``row``; ``Figure.subplots(**subplots_kw)``, e.g.
    ``sharex=True``).

    Raises
    ------
    ValueError
        If ``axes`` does not hold exactly ``n`` Axes.
    """
    if axes is not None:
        axes = list(axes)
        if len(axes) != n:
            raise InputError(f"axes has {len(axes)} Axes; this figure draws {n} panels")
        return axes[0].figure, axes
    fig = Figure(figsize=figsize, layout="constrained")
    grid = fig.subplots(1 if row else n, n if row else 1, squeeze=False, **subplots_kw)
    return fig, list(grid.ravel())


def run_panels(run: xr.Dataset, axes: Sequence[Axes] | None) -> tuple[Figure, list[Axes], np.ndarray]:
    """The two panels of a run's figure over its time (:func:`panels_or_new`: a column of 2, the
    time axis shared) and the run's times ``run.time``."""
    fig, axes = panels_or_new(axes, 2, (6.4, 5.6), sharex=True)
    return fig, axes, run.time.values
